"""The deterministic sampler: a scenario point's distributions drawn into the kernel's inputs.

Determinism rule: sample i of a point belongs to block b = i // block_size. Each block has its
own generator, ``Generator(PCG64(SeedSequence(seed, spawn_key=(point.index, b))))``, which
draws every random quantity of the point for all block_size samples of the block, in a fixed
order (sorted key paths). ``sample`` computes the blocks it needs and slices them. So the inputs
of sample i depend only on (scenario, seed, i): the chunk size and the thread count cannot
change them, and the first N samples of a longer run are those of a shorter run. Conversions
(club -> ball launch, weather -> air, wind, Stimp, restitution) are also computed on whole
blocks, so that every value comes out of the same operation on arrays of the same shape,
whichever chunk asks for it. Nothing here touches NumPy's global random state.

Conversions at this edge (the kernel sees only SI floats, ``mcrun.engine.schema.INPUT_FIELDS``),
those of the single shot (``mcrun.quantities.kernel_columns``):

- club delivery -> ball launch with ``mcrun.physics.launch.launch_from_club`` (Penner 2001);
- temperature, pressure or altitude, humidity -> air density and kinematic viscosity
  (``mcrun.physics.atmosphere``), as ``mcrun.api.air_properties`` does;
- wind speed and the direction it blows TOWARDS (0 tailwind, 90 deg left to right) ->
  (wind_x_mps, wind_right_mps);
- Stimp reading -> rho_g (``mcrun.physics.turf.rho_g_from_stimp``); restitution scale -> e0, e1, e2
  and e_high of the preset scaled.

A constant stays a Python float through these conversions (computed once, as the single-shot
API computes it), so a scenario of constants gives exactly the kernel inputs of
``mcrun.api.simulate``. A drawn value outside its documented range (``mcrun.quantities``'
limits) makes its shot's ball speed NaN in ``inputs``, so the kernel returns ``invalid_input``
for that shot; ``sampled`` keeps the value drawn.
"""

import math

import numpy as np
from numba import njit

from mcrun.engine.schema import N_INPUT, pack
from mcrun.quantities import QUANTITIES, SAMPLED_ORDER, by_path, kernel_columns, kernel_part

__all__ = [
    "block_generator",
    "column_dtype",
    "draw_block",
    "sample",
    "sampled_columns",
    "truncnormal_standard",
]

# The columns of the alternatives (a club delivery, an altitude, a Stimp reading): in a run's
# table when a point gives them.
_OPTIONAL = {q.column: q.paths for q in QUANTITIES if q.optional}


def sampled_columns(scenario):
    """Names of the ``sampled`` columns of every point of ``scenario``, in order
    (``quantities.SAMPLED_ORDER``).

    The same for all points of a scenario (one Parquet schema): club columns appear when a
    point uses a club delivery (NaN for the others), ``source_row`` (the file's row of the
    measured shot, 0-based, -1 when not resampled) when a point resamples a file (not when it
    draws from a normal fitted to the file), ``altitude_m`` and
    ``stimp_m`` when a point gives them (NaN otherwise).
    """
    given = set().union(*(p.params for p in scenario.points))
    resamples = any(_resamples(p) for p in scenario.points)

    def kept(name):
        if name == "source_row":
            return resamples
        paths = _OPTIONAL.get(name)
        return paths is None or not given.isdisjoint(paths)

    return [name for name in SAMPLED_ORDER if kept(name)]


def _resamples(point):
    """Whether ``point`` resamples the shots of a launch file (rather than fitting a normal)."""
    spec = point.params.get("launch.file")
    return spec is not None and spec.fit is None


def block_generator(seed, point_index, block):
    """The generator of block ``block`` of point ``point_index`` of a run with ``seed``."""
    return np.random.Generator(
        np.random.PCG64(np.random.SeedSequence(seed, spawn_key=(point_index, block)))
    )


# --- truncated normal by inverse CDF -------------------------------------------------------

# Acklam's rational approximation of the normal quantile (relative error 1.15e-9), refined by
# one Halley step on erfc to full double precision.
_A = (-39.69683028665376, 220.9460984245205, -275.9285104469687, 138.3577518672690,
      -30.66479806614716, 2.506628277459239)  # fmt: skip
_B = (-54.47609879822406, 161.5858368580409, -155.6989798598866, 66.80131188771972,
      -13.28068155288572)  # fmt: skip
_C = (-0.007784894002430293, -0.3223964580411365, -2.400758277161838, -2.549732539343734,
      4.374664141464968, 2.938163982698783)  # fmt: skip
_D = (0.007784695709041462, 0.3224671290700398, 2.445134137142996, 3.754408661907416)
_P_LOW = 0.02425
_SQRT2 = math.sqrt(2.0)
_SQRT2PI = math.sqrt(2.0 * math.pi)


@njit(cache=True)
def _ndtr(x):
    """Standard normal CDF, accurate in the lower tail."""
    return 0.5 * math.erfc(-x / _SQRT2)


@njit(cache=True)
def _ndtri(p):
    """Standard normal quantile."""
    if p <= 0.0:
        return -math.inf
    if p >= 1.0:
        return math.inf
    if p < _P_LOW:
        q = math.sqrt(-2.0 * math.log(p))
        x = (((((_C[0] * q + _C[1]) * q + _C[2]) * q + _C[3]) * q + _C[4]) * q + _C[5]) / (
            (((_D[0] * q + _D[1]) * q + _D[2]) * q + _D[3]) * q + 1.0
        )
    elif p <= 1.0 - _P_LOW:
        q = p - 0.5
        r = q * q
        x = (
            (((((_A[0] * r + _A[1]) * r + _A[2]) * r + _A[3]) * r + _A[4]) * r + _A[5])
            * q
            / (((((_B[0] * r + _B[1]) * r + _B[2]) * r + _B[3]) * r + _B[4]) * r + 1.0)
        )
    else:
        q = math.sqrt(-2.0 * math.log1p(-p))
        x = -(((((_C[0] * q + _C[1]) * q + _C[2]) * q + _C[3]) * q + _C[4]) * q + _C[5]) / (
            (((_D[0] * q + _D[1]) * q + _D[2]) * q + _D[3]) * q + 1.0
        )
    e = _ndtr(x) - p
    u = e * _SQRT2PI * math.exp(0.5 * x * x)
    if math.isfinite(u):
        x = x - u / (1.0 + 0.5 * x * u)
    return x


@njit(cache=True)
def truncnormal_standard(a, b, u):
    """Standard normal truncated to [a, b], by inverse CDF: the ``u``-quantiles (u in [0, 1)).

    An interval above the mean is mirrored into the lower tail, where the CDF keeps its
    precision."""
    flip = a > 0.0
    if flip:
        a, b = -b, -a
    fa = _ndtr(a)
    fb = _ndtr(b)
    out = np.empty(u.shape[0])
    for k in range(u.shape[0]):
        # Mirrored, 1 - u keeps the map increasing: x is the u-quantile either way.
        p = 1.0 - u[k] if flip else u[k]
        x = _ndtri(fa + p * (fb - fa))
        x = min(max(x, a), b)
        out[k] = -x if flip else x
    return out


# --- drawing a block -------------------------------------------------------------------------


def _draw(rng, dist, n):
    """n draws of a non-constant Dist."""
    args = dist.args
    if dist.dist == "normal":
        return args[0] + args[1] * rng.standard_normal(n)
    if dist.dist == "truncnormal":
        mean, sd, low, high = args
        u = rng.random(n)
        return mean + sd * truncnormal_standard((low - mean) / sd, (high - mean) / sd, u)
    if dist.dist == "uniform":
        return rng.uniform(args[0], args[1], n)
    if dist.dist == "triangular":
        return rng.triangular(args[0], args[1], args[2], n)
    if dist.dist == "lognormal":
        return args[0] * np.exp(args[1] * rng.standard_normal(n))
    raise AssertionError(dist.dist)


def _random_items(point):
    """The point's random items, in draw order: (key path, what)."""
    correlated = set()
    for key in ("launch.correlation", "club.correlation"):
        if key in point.params:
            section = key.partition(".")[0]
            correlated.update(f"{section}.{n}" for n in point.params[key].names)
    items = []
    for key in sorted(point.params):
        spec = point.params[key]
        if key in correlated or isinstance(spec, str):
            continue
        if key.endswith(".correlation") or key == "launch.file":
            items.append(key)
        elif not spec.is_constant:
            items.append(key)
    return items


def draw_block(scenario, point, block):
    """The raw draws of one block: {key path: SI array of block_size, or float for a
    constant}; a resampled file adds ``launch.file.rows`` (int64, the file's rows of the shots
    drawn) and its (jittered) quantities as ``launch.<quantity>``; a normal fitted to a file
    adds its quantities as ``launch.<quantity>``, drawn as a correlation's are."""
    n = scenario.block_size
    rng = block_generator(scenario.seed, point.index, block)
    raw = {}
    for key, spec in point.params.items():
        if not isinstance(spec, str) and hasattr(spec, "is_constant") and spec.is_constant:
            raw[key] = float(spec.value)
    for key in _random_items(point):
        spec = point.params[key]
        if key.endswith(".correlation"):
            section = key.partition(".")[0]
            z = rng.standard_normal((n, len(spec.names)))
            for j, name in enumerate(spec.names):
                # x_j = sum_l F[j, l] z_l, elementwise in a fixed order (no BLAS).
                x = spec.factor[j, 0] * z[:, 0]
                for m in range(1, len(spec.names)):
                    x = x + spec.factor[j, m] * z[:, m]
                mean, sd = point.params[f"{section}.{name}"].args
                raw[f"{section}.{name}"] = mean + sd * x
        elif key == "launch.file" and spec.fit is not None:
            fit = spec.fit
            z = rng.standard_normal((n, len(fit.names)))
            for j, name in enumerate(fit.names):
                # x_j = sum_l F[j, l] z_l, elementwise in a fixed order (no BLAS).
                x = fit.factor[j, 0] * z[:, 0]
                for m in range(1, len(fit.names)):
                    x = x + fit.factor[j, m] * z[:, m]
                raw[f"launch.{name}"] = fit.mean[j] + fit.sd[j] * x
        elif key == "launch.file":
            rows = rng.integers(0, spec.n_rows, size=n)
            raw["launch.file.rows"] = spec.source_rows[rows]
            for name in sorted(set(spec.columns) | set(spec.jitter)):
                column = spec.columns.get(name)
                value = column[rows] if column is not None else np.zeros(n)
                sd = spec.jitter.get(name)
                if sd is not None:
                    value = value + sd * rng.standard_normal(n)
                raw[f"launch.{name}"] = value
        else:
            raw[key] = _draw(rng, spec, n)
    return raw


# --- conversions -------------------------------------------------------------------------------


def _convert(scenario, point, raw, columns, inputs=None):
    """(inputs, sampled) of one block from its raw draws; ``inputs`` may be given, a view of
    block_size rows to fill. A sampled column that is constant is a read-only broadcast view."""
    n = scenario.block_size
    names = {key: spec for key, spec in point.params.items() if isinstance(spec, str)}
    # (a drawn value out of its limits may overflow its conversion: its shot is refused below)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        everything = kernel_columns({**raw, **names})
    kernel = kernel_part(everything)
    if point.play is not None:
        # On a hole: struck from the point's start, about the line from there to its aim.
        kernel["azimuth_rad"] = everything["azimuth_rad"] + point.play.aim_rad
        kernel["start_x_m"], kernel["start_y_m"] = point.play.start_m

    # Drawn values outside their documented range: the kernel must refuse the shot.
    bad = np.zeros(n, dtype=bool)
    for key, value in raw.items():
        if isinstance(value, float) or key == "launch.file.rows":
            continue
        lo, hi = by_path(key).limits
        bad |= ~((value >= lo) & (value <= hi))
    inputs = pack(kernel, n, out=inputs, invalid=bad)

    sampled = {}
    for name in columns:
        if name == "source_row":
            rows = raw.get("launch.file.rows")
            sampled[name] = np.full(n, -1, dtype=np.int64) if rows is None else rows
        else:
            value = everything.get(name, math.nan)
            sampled[name] = np.broadcast_to(np.asarray(value, dtype=float), (n,))
    return inputs, sampled


def column_dtype(name):
    """The dtype of a sampled column: int64 for ``source_row``, float64 for the others."""
    return np.int64 if name == "source_row" else float


def sample(scenario, point, start, stop, columns=None):
    """The kernel inputs and the sampled columns of samples ``start`` .. ``stop - 1`` of a point.

    ``columns``: ``sampled_columns(scenario)``, when the caller has it: that function looks at
    every point, so a run computes it once rather than once per chunk.

    Returns
    -------
    inputs : ndarray, shape (stop - start, N_INPUT), Fortran order
        Columns ``mcrun.engine.schema.INPUT_FIELDS``, SI, user frame.
    sampled : dict of str -> ndarray
        ``sampled_columns(scenario)``, each of length stop - start, with units in the names;
        a column that is constant for the point is a read-only broadcast view.
    """
    start = int(start)
    stop = int(stop)
    if not 0 <= start <= stop:
        raise ValueError(f"need 0 <= start <= stop, got {start}, {stop}")
    size = scenario.block_size
    n = stop - start
    if columns is None:
        columns = sampled_columns(scenario)
    inputs = np.empty((n, N_INPUT), order="F")
    sampled = {}
    if n == 0:
        return inputs, {name: np.empty(0, dtype=column_dtype(name)) for name in columns}
    for block in range(start // size, (stop - 1) // size + 1):
        first = block * size
        lo = max(start, first) - first
        hi = min(stop, first + size) - first
        at = first + lo - start
        whole = lo == 0 and hi == size  # the block's rows go straight into ``inputs``
        block_inputs, block_sampled = _convert(
            scenario,
            point,
            draw_block(scenario, point, block),
            columns,
            inputs[at : at + size] if whole else None,
        )
        if not whole:
            inputs[at : at + hi - lo] = block_inputs[lo:hi]
        for name in columns:
            values = block_sampled[name]
            if values.strides == (0,):  # constant for the point, so in every block
                sampled[name] = np.broadcast_to(values[:1], (n,))
                continue
            if name not in sampled:
                sampled[name] = np.empty(n, dtype=column_dtype(name))
            sampled[name][at : at + hi - lo] = values[lo:hi]
    return inputs, sampled
