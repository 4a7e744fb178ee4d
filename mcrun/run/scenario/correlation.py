"""A correlation between the normal quantities of a section, checked, and the factor that
draws it (a Cholesky factor of a semi-definite matrix, in plain Python so that it is the same
on every machine)."""

import math

import numpy as np

from mcrun.run.scenario.specs import PARAMETERS, Correlation
from mcrun.run.scenario.values import as_table, short
from mcrun.units import is_number


def read_correlation(ctx, leaf, section, dists, leaves, context=""):
    """A Correlation from ``{names = [...], matrix = [[...]]}``, checked against the point."""
    where = leaf.where
    table = as_table(ctx, where, leaf.value)
    for key in table:
        if key not in ("names", "matrix"):
            raise ctx.error(f"{where}.{key}", "unknown key; allowed: names, matrix")
    names = table.get("names")
    if not isinstance(names, list) or len(names) < 2 or not all(isinstance(n, str) for n in names):
        raise ctx.error(
            f"{where}.names", f"must be a list of at least two quantity names, got {short(names)}"
        )
    if len(set(names)) != len(names):
        raise ctx.error(f"{where}.names", f"must not repeat a name, got {names}")
    quantities = tuple(PARAMETERS[section])
    for name in names:
        if name not in quantities:
            raise ctx.error(
                f"{where}.names", f"unknown quantity {name!r}; allowed: {', '.join(quantities)}"
            )
        dist = dists.get(name)
        if dist is None or dist.dist != "normal":
            if name not in leaves:
                got = "not given"
            elif leaves[name].where == f"{section}.{name}":
                got = f"a {dist.dist}"
            else:
                got = f"a {dist.dist}, at {leaves[name].where}"
            raise ctx.error(
                f"{where}.names",
                f"{name} must be a normal distribution to be correlated ({section}.{name} is "
                f"{got}){context}",
            )
    k = len(names)
    rows = table.get("matrix")
    if (
        not isinstance(rows, list)
        or len(rows) != k
        or not all(isinstance(r, list) and len(r) == k for r in rows)
        or not all(is_number(x) and math.isfinite(x) for r in rows for x in r)
    ):
        raise ctx.error(
            f"{where}.matrix", f"must be a {k} x {k} list of lists of numbers, got {short(rows)}"
        )
    matrix = np.array(rows, dtype=float)
    if not np.all(np.diag(matrix) == 1.0):
        raise ctx.error(
            f"{where}.matrix", f"must have 1 on the diagonal, got {np.diag(matrix).tolist()}"
        )
    if np.max(np.abs(matrix - matrix.T)) > 1e-12:
        raise ctx.error(f"{where}.matrix", "must be symmetric")
    if np.max(np.abs(matrix)) > 1.0:
        raise ctx.error(f"{where}.matrix", "entries must be within [-1, 1]")
    smallest = np.linalg.eigvalsh(matrix)[0]
    if smallest < -PSD_TOLERANCE * k:
        raise ctx.error(
            f"{where}.matrix",
            f"must be positive semi-definite, its smallest eigenvalue is {smallest:.3g}",
        )
    factor = semidefinite_cholesky(matrix)
    matrix.setflags(write=False)
    factor = np.ascontiguousarray(factor)
    factor.setflags(write=False)
    return Correlation(tuple(names), matrix, factor)


# Pivots of the Cholesky factor below this, relative to the matrix's scale (its largest
# eigenvalue is at most k for a k x k correlation matrix), are zero: a rank-deficient matrix
# whose rounding leaves a pivot of 1e-17 instead of 0 must not give its factor a column of
# 3e-9. Eigenvalues down to -PSD_TOLERANCE * k are rounding too.
PSD_TOLERANCE = 1e-10


def semidefinite_cholesky(matrix):
    """Lower-triangular F with F F^T = ``matrix``, for a positive semi-definite matrix.

    The Cholesky algorithm in plain Python (k is a handful of launch quantities), where a pivot
    below PSD_TOLERANCE * k is zero and so is the rest of its column: for a semi-definite matrix
    that column is zero in exact arithmetic. No LAPACK, so the factor, and the samples drawn
    with it, do not depend on which BLAS kernel the machine runs.
    """
    k = matrix.shape[0]
    factor = np.zeros((k, k))
    for j in range(k):
        pivot = matrix[j, j] - sum(factor[j, m] * factor[j, m] for m in range(j))
        if pivot <= PSD_TOLERANCE * k:
            continue
        factor[j, j] = math.sqrt(pivot)
        # Times the reciprocal, as LAPACK's dpotrf scales a column: the same factor, to the
        # bit, for the library's matrices.
        scale = 1.0 / factor[j, j]
        for i in range(j + 1, k):
            dot = sum(factor[i, m] * factor[j, m] for m in range(j))
            factor[i, j] = (matrix[i, j] - dot) * scale
    return factor
