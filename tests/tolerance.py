"""How results computed on one CPU are compared with results written on another.

Everything that is exact on any CPU is compared exactly: statuses, zones, labels, counts, shot
and point numbers, and where a float is NaN. A float is compared at a tolerance made of the
two ways a float error can reach it:

- ``ULPS`` units in the last place of the value itself. A value recomputed from the same inputs by
  another routine differs by that: NumPy computes float64 sin, cos and arctan2 with its own SIMD
  routines on CPUs with AVX-512 and with the C library elsewhere, and the two differ by up to a
  few ulp (4 ulp is the bound vectorised math libraries document); 16 is four of those. A
  latitude or longitude converted from a shot's metres differs by this alone.
- ``GROWTH`` times the column's scale. An input a few ulp off is carried through the shot's
  thousands of integration steps, bounce searches and roll, which multiply it. How much is
  measured, not guessed: the golden cases run with NumPy's AVX-512 routines turned off and Numba
  compiling for a generic x86-64 CPU, against the file written with both on, differ at most by
  3.5e-9 of the column's scale (a summary's regression share on real survey ground, from heights
  one ulp apart; 1.0e-9 for a shot's column, ``total_time_s``). That is up to 1.6e7 ulp of
  amplification (2^24) from 1 ulp of input; allowing 4 ulp of input and a margin of 4 gives
  2^-52 * 2^24 * 4 * 4 = 2^-24 (6.0e-8) of the scale.

A column's scale is its largest magnitude, except for positions in degrees of longitude and
latitude, whose float error comes from the shot's metres: their scale is the column's spread
(largest less smallest), the run's extent on the ground, so that a tolerance of metres is not
read as one of degrees of the whole Earth.

A change that only moves numbers within these bounds passes on every CPU; ``pytest
--bit-for-bit`` compares everything bit for bit instead, for a refactoring on the machine that
wrote the file.
"""

import math

import numpy as np
import pandas as pd

ULPS = 16
GROWTH = 2.0**-24
GEO_COLUMNS = ("_lon_deg", "_lat_deg")


def column_tolerance(name, expected):
    """The absolute tolerance of each value of a float column (an array like ``expected``)."""
    finite = expected[np.isfinite(expected)]
    if finite.size == 0:
        return np.zeros_like(expected)
    if name.endswith(GEO_COLUMNS):
        scale = float(finite.max() - finite.min())
    else:
        scale = float(np.abs(finite).max())
    return ULPS * np.spacing(np.abs(expected)) + GROWTH * scale


def assert_floats_close(name, actual, expected, what=""):
    """``actual`` matches ``expected`` (float arrays) within the column's tolerance; NaN and
    infinities where the expected has them."""
    actual, expected = np.asarray(actual, float), np.asarray(expected, float)
    assert actual.shape == expected.shape, f"{what}{name}: {actual.shape} != {expected.shape}"
    same_special = (np.isnan(actual) == np.isnan(expected)) & (
        np.isinf(expected) <= (actual == expected)
    )
    bad = ~same_special
    finite = np.isfinite(expected) & np.isfinite(actual)
    tolerance = column_tolerance(name, expected)
    with np.errstate(invalid="ignore"):
        bad |= finite & ~(np.abs(actual - expected) <= tolerance)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise AssertionError(
            f"{what}{name}: {int(bad.sum())} of {bad.size} values differ beyond the tolerance; "
            f"first at row {k}: {actual[k]!r} against {expected[k]!r} "
            f"(tolerance {tolerance[k]:.3g})"
        )


def assert_frames_close(actual, expected, what=""):
    """Two frames hold the same columns and rows: floats within tolerance, the rest exactly."""
    assert list(actual.columns) == list(expected.columns), f"{what}columns differ"
    assert len(actual) == len(expected), f"{what}{len(actual)} rows != {len(expected)}"
    for name in expected.columns:
        a, e = actual[name], expected[name]
        if e.dtype.kind == "f":
            assert a.dtype == e.dtype, f"{what}{name}: dtype {a.dtype} != {e.dtype}"
            assert_floats_close(name, a.to_numpy(), e.to_numpy(), what)
        else:
            pd.testing.assert_series_equal(a.reset_index(drop=True), e.reset_index(drop=True),
                                           check_exact=True, obj=f"{what}{name}")  # fmt: skip


def assert_outcomes_close(actual, expected, what=""):
    """Two outcome dicts (``mcrun shot --json``) hold the same keys and values: each float
    within its tolerance (its own magnitude the scale), the rest exactly."""
    assert set(actual) == set(expected), f"{what}keys differ"
    for key, e in expected.items():
        a = actual[key]
        if isinstance(e, float) and not isinstance(a, bool) and isinstance(a, float | int):
            if math.isnan(e):
                assert math.isnan(a), f"{what}{key}: {a!r} against NaN"
                continue
            assert_floats_close(key, [a], [e], what)
        else:
            assert a == e, f"{what}{key}: {a!r} against {e!r}"
