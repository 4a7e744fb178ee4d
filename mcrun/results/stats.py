"""Dispersion statistics of a run, one summary row per point (group and sweep combination).

Everything is computed over the shots whose status is ok; the others are only counted, by
status. Two passes, both with memory independent of the number of shots:

1. While the run streams (``PointStats.update`` per chunk): the count by status, and the mean
   and co-moment matrix of the outcome quantities and of the sampled inputs, merged chunk by
   chunk with the pairwise update of Chan, Golub and LeVeque (1979),
   C = C_a + C_b + (m_b - m_a)(m_b - m_a)^T n_a n_b / n. These centred sums are the mergeable
   form of the sums of x, x x^T and x y, without their cancellation. They give the means, the
   standard deviations (ddof = 1, as pandas), the covariance of the final position and its
   dispersion ellipses, and the standardised regression coefficients (below).
2. After the run (``summarise``, ``exact_quantiles``): the percentiles, which no bounded
   streaming summary gives exactly, are computed from ``shots.parquet`` itself, reading one
   column of one point at a time, row group by row group. When a point's column fits in
   ``budget_bytes`` (default 64 MiB, 8 million shots) it is read whole and its order
   statistics taken from a sort; above that, a histogram-then-select pass finds the bins that
   hold the wanted order statistics and a second pass collects only those bins (refined again
   if a bin is still too large), so that 100 million shots need no more memory than one
   million. Both paths return the same exact order statistics, interpolated as pandas'
   default (``numpy.percentile``'s "linear": the value at position h = (n - 1) q of the
   sorted sample, linearly between its neighbours).
   The distance to the target needs this pass too: its default target is the mean final
   position, known only once every shot has been seen.
   A local run reads these values not from its Parquet but from a ``Spill``: a temporary file
   the writer appends each chunk's ok values of ``SPILLED`` to, raw float64 (72 bytes a shot),
   read back chunk by chunk. The values and their chunks are those the Parquet holds, so the
   summary is the same bit for bit, at a fraction of decoding the Parquet twice.

Why exact rather than a sketch (t-digest, P^2): a summary a user compares with pandas on
``shots.parquet`` should agree with it to rounding, and the second pass costs a fraction of the
simulation itself.

Drivers of the variance: for y = total_m and y = final_y_m, the linear model
y = b0 + sum_j b_j x_j over the sampled inputs x_j that vary within the point, fitted by least
squares from the co-moments; SRC_j = b_j sd(x_j) / sd(y), and for independent inputs SRC_j^2
is the share of var(y) that x_j explains (the shares add up to R^2; with correlated inputs,
e.g. ball speed and spin, they are only indicative). The candidates are the inputs a
distribution varies (``mcrun.run.plan.driver_inputs``), not the columns derived from them (the air
density from the temperature, the ball launch from the club delivery); as a safeguard, an
input that the candidates before it explain to more than ``DERIVED_R2`` of its variance is left
out, since a regression cannot tell its effect from theirs.

The run (run_m) against the landing state (``LANDING_DRIVERS``: angle, speed and spin at
impact): these are outcomes, strongly correlated with each other, so a joint regression would
split their effects arbitrarily; the summary gives each one's correlation with the run and its
square, the share of the run's variance it explains alone. That is where a user reads off the
finding of Penner (2002) that the impact angle governs the run.
"""

import math
import operator
import os
import tempfile

import numba
import numpy as np
import pyarrow.compute as pc
import pyarrow.parquet as pq

from mcrun import status as status_codes
from mcrun.engine.schema import OUTCOME_FIELDS

QUANTITIES = (
    "carry_m",
    "total_m",
    "run_m",
    "carry_lateral_m",
    "final_y_m",
    "apex_m",
    "landing_angle_deg",
    "first_bounce_height_m",
)
PERCENTILES = (1, 5, 25, 50, 75, 95, 99)
ELLIPSE_LEVELS = (68, 95)
DISTANCE_PERCENTILES = (50, 95)
DRIVEN = ("total_m", "final_y_m")
# The run regressed on the landing state: Penner (2002) finds the impact angle governs it.
LANDING_DRIVERS = ("landing_angle_deg", "landing_speed_mps", "landing_spin_radps")
DDOF = 1
DERIVED_R2 = 0.999
# A spread of values within this share of their magnitude is rounding, not variation (copies of
# one shot fitted by a normal vary by an ulp or so): such a value drives nothing and is not
# driven.
SPREAD_ROUNDING = 1e-9

DEFAULT_BUDGET_BYTES = 64 * 2**20
_HISTOGRAM_BINS = 4096

_OUTCOME_COLUMN = {name: k for k, name in enumerate(OUTCOME_FIELDS)}
_STATUS = _OUTCOME_COLUMN["status"]
_STATUS_NAMES = tuple(status_codes.NAMES[k] for k in sorted(status_codes.NAMES))


def ellipse_scale(level_percent):
    """sqrt of the chi-square(2 dof) quantile: sqrt(-2 ln(1 - p)), the semi-axis per sd."""
    return math.sqrt(-2.0 * math.log(1.0 - level_percent / 100.0))


def ellipse(cov_xx, cov_xy, cov_yy, level_percent):
    """(semi-major m, semi-minor m, angle deg, area m^2) of the ``level_percent`` % ellipse.

    The semi-axes are sqrt(eigenvalue) * sqrt(chi2_2(p)) of the 2x2 covariance; the angle is
    that of the major axis from the target line, turning to the right, in [0, 180): 0 along
    the line (a dispersion in distance), 90 across it (a dispersion in direction, the usual
    case of a full shot, which this range keeps away from the wrap-around).
    """
    half_sum = 0.5 * (cov_xx + cov_yy)
    radius = math.hypot(0.5 * (cov_xx - cov_yy), cov_xy)
    major = max(half_sum + radius, 0.0)
    minor = max(half_sum - radius, 0.0)
    angle = 0.5 * math.degrees(math.atan2(2.0 * cov_xy, cov_xx - cov_yy))
    if angle < 0.0:
        angle += 180.0
    k = ellipse_scale(level_percent)
    a = k * math.sqrt(major)
    b = k * math.sqrt(minor)
    return a, b, angle + 0.0, math.pi * a * b


class Comoments:
    """Count, mean vector and co-moment matrix sum (x - mean)(x - mean)^T of k columns,
    updated with blocks of rows and mergeable (Chan, Golub and LeVeque 1979)."""

    def __init__(self, k):
        self.n = 0
        self.mean = np.zeros(k)
        self.comoment = np.zeros((k, k))
        self.min = np.full(k, np.inf)
        self.max = np.full(k, -np.inf)

    def update(self, block):
        """Add the rows of ``block`` (m, k)."""
        m = block.shape[0]
        if m == 0:
            return
        other = Comoments(block.shape[1])
        other.n = m
        other.mean = block.mean(axis=0)
        centred = block - other.mean
        other.comoment = centred.T @ centred
        other.min = block.min(axis=0)
        other.max = block.max(axis=0)
        self.merge(other)

    def merge(self, other):
        """Add the rows summarised by ``other``."""
        if other.n == 0:
            return
        if self.n == 0:
            self.n, self.mean, self.comoment = other.n, other.mean.copy(), other.comoment.copy()
            self.min, self.max = other.min.copy(), other.max.copy()
            return
        n = self.n + other.n
        delta = other.mean - self.mean
        self.comoment = (
            self.comoment + other.comoment + np.outer(delta, delta) * (self.n * other.n / n)
        )
        self.mean = self.mean + delta * (other.n / n)
        self.n = n
        self.min = np.minimum(self.min, other.min)
        self.max = np.maximum(self.max, other.max)

    def covariance(self, ddof=DDOF):
        if self.n - ddof <= 0:
            return np.full_like(self.comoment, np.nan)
        return self.comoment / (self.n - ddof)


class ExactSum:
    """The sum of many float64 values, exact: each value is its significand (53 bits, split in
    two halves of 26 and 27 bits) times a power of two, and the halves are added as integers
    per power; the total is rounded once, to nearest (as ``math.fsum``). So the sum does not
    depend on the order of the values, on the chunks they come in, or on the order the chunks'
    sums are merged in: a local run and a Dask run give the same bits. Values must be finite."""

    _OFFSET = 1100  # frexp's exponents are -1073 .. 1024
    _BLOCK = 1 << 20  # values per bincount: each half's sum stays under 2^53, exact in float64

    def __init__(self):
        self.parts = {}  # exponent e -> the sum of the significands (integers) times 2^(e-53)

    def add(self, values):
        values = np.asarray(values, dtype=float).ravel()
        for a in range(0, values.size, self._BLOCK):
            m, e = np.frexp(values[a : a + self._BLOCK])
            significand = np.ldexp(m, 53).astype(np.int64)  # exact: |m| < 1
            high = significand >> 26
            low = significand - (high << 26)
            index = e + self._OFFSET
            for half, shift in ((high, 26), (low, 0)):
                sums = np.bincount(index, weights=half, minlength=2 * self._OFFSET)
                for k in np.flatnonzero(sums):
                    key = int(k) - self._OFFSET
                    self.parts[key] = self.parts.get(key, 0) + (int(sums[k]) << shift)

    def merge(self, other):
        for key, value in other.parts.items():
            self.parts[key] = self.parts.get(key, 0) + value

    def value(self):
        """The sum, rounded to the nearest float64 (0.0 for none)."""
        if not self.parts:
            return 0.0
        low = min(self.parts)
        total = sum(value << (key - low) for key, value in self.parts.items())
        scale = low - 53
        # Python's division of integers is rounded correctly: so is the sum.
        return total / (1 << -scale) if scale < 0 else float(total << scale)


class RunningMoments:
    """Count, exact sum (``ExactSum``) and sum of squared deviations of a stream of values,
    merged chunk by chunk (Chan's update): the mean exact, the sample standard deviation to
    rounding."""

    def __init__(self):
        self.n = 0
        self.total = ExactSum()
        self.mean = 0.0
        self.m2 = 0.0

    def add(self, values):
        values = np.asarray(values, dtype=float)
        other = RunningMoments()
        other.n = int(values.size)
        if other.n:
            other.total.add(values)
            other.mean = float(values.mean())
            other.m2 = float(((values - other.mean) ** 2).sum())
        self.merge(other)

    def merge(self, other):
        if other.n == 0:
            return
        n = self.n + other.n
        delta = other.mean - self.mean
        self.mean += delta * other.n / n
        self.m2 += other.m2 + delta * delta * self.n * other.n / n
        self.n = n
        self.total.merge(other.total)

    def mean_se(self):
        """(the exact mean, the standard error of the mean) as ``strokes.expected._mean_se``
        gives them (NaN for no value, and an SE for fewer than two)."""
        mean = self.total.value() / self.n if self.n else math.nan
        se = math.sqrt(self.m2 / (self.n - 1)) / math.sqrt(self.n) if self.n > 1 else math.nan
        return mean, se


class PointStats:
    """Streaming statistics of one point: counts by status and co-moments of the ok shots.

    ``inputs`` are the names of the sampled input columns (the candidates for the variance
    drivers); the outcome columns are ``QUANTITIES``, final_x_m and the landing state.
    """

    def __init__(self, inputs, on_hole=None):
        self.inputs = tuple(inputs)
        self.outcomes = (*QUANTITIES, "final_x_m", "landing_speed_mps", "landing_spin_radps")
        self.columns = (*self.outcomes, *self.inputs)
        self.index = {name: k for k, name in enumerate(self.columns)}
        self.n_shots = 0
        self.status_counts = np.zeros(len(_STATUS_NAMES), dtype=np.int64)
        self.moments = Comoments(len(self.columns))
        self.on_hole = on_hole  # a run on a hole: its ``on_hole.HoleTally``

    def update(self, outcomes, sampled, hole_columns=None):
        """Add a chunk: ``outcomes`` (m, N_OUTCOME) as ``batch.simulate_batch`` writes it and
        ``sampled`` a mapping of input name -> (m,) array (at least ``self.inputs``); on a
        hole, its shots' ``hole_columns`` (``on_hole.shot_columns``) too."""
        codes = outcomes[:, _STATUS].astype(np.int64)
        if self.on_hole is not None:
            self.on_hole.update(hole_columns, codes)
        self.n_shots += len(codes)
        self.status_counts += np.bincount(codes, minlength=len(_STATUS_NAMES))[: len(_STATUS_NAMES)]
        ok = codes == status_codes.OK
        n_ok = int(ok.sum())
        rows = slice(None) if n_ok == len(codes) else ok  # a slice copies faster than a mask
        block = np.empty((n_ok, len(self.columns)), order="F")
        for k, name in enumerate(self.outcomes):
            block[:, k] = outcomes[rows, _OUTCOME_COLUMN[name]]
        for k, name in enumerate(self.inputs, start=len(self.outcomes)):
            block[:, k] = np.broadcast_to(np.asarray(sampled[name], dtype=float), ok.shape)[rows]
        self.moments.update(block)

    def merge(self, other):
        if other.columns != self.columns:
            raise ValueError("cannot merge statistics of different columns")
        self.n_shots += other.n_shots
        self.status_counts += other.status_counts
        self.moments.merge(other.moments)
        if self.on_hole is not None:
            self.on_hole.merge(other.on_hole)

    @property
    def n_ok(self):
        return int(self.status_counts[status_codes.OK])

    def mean(self, name):
        return float(self.moments.mean[self.index[name]]) if self.n_ok else math.nan

    def covariance(self, a, b):
        return float(self.moments.covariance()[self.index[a], self.index[b]])

    def correlation(self, a, b):
        """Pearson correlation of two columns over the ok shots (NaN if either is constant, to
        rounding: ``varies``)."""
        cov = self.moments.covariance()
        i, j = self.index[a], self.index[b]
        if self.n_ok < 2 or not (cov[i, i] > 0.0 and cov[j, j] > 0.0):
            return math.nan
        if not (self.varies(a) and self.varies(b)):
            return math.nan
        return float(cov[i, j] / math.sqrt(cov[i, i] * cov[j, j]))

    def bounds(self, name):
        """(min, max) of a column over the ok shots."""
        k = self.index[name]
        return float(self.moments.min[k]), float(self.moments.max[k])

    def distance_bounds(self, target_x, target_y):
        """(lo, hi) that hold the distance of every ok shot's final position to the target,
        from the box of the final positions (widened by a few roundings)."""
        x0, x1 = self.bounds("final_x_m")
        y0, y1 = self.bounds("final_y_m")
        near = math.hypot(
            max(x0 - target_x, 0.0, target_x - x1), max(y0 - target_y, 0.0, target_y - y1)
        )
        far = math.hypot(
            max(abs(x0 - target_x), abs(x1 - target_x)), max(abs(y0 - target_y), abs(y1 - target_y))
        )
        return near * (1.0 - 1e-12), far * (1.0 + 1e-12)

    def varies(self, name):
        """Whether ``name``'s ok values spread beyond rounding (``SPREAD_ROUNDING``)."""
        k = self.index[name]
        lo, hi = self.moments.min[k], self.moments.max[k]
        return bool(hi - lo > SPREAD_ROUNDING * max(abs(lo), abs(hi)))

    def drivers(self, y, candidates=None, derived_r2=DERIVED_R2):
        """Standardised regression coefficients of ``y`` on the inputs that vary.

        ``candidates``: input names in order of preference (default ``self.inputs``); an input
        that the inputs kept before it explain to more than ``derived_r2`` of its variance is
        skipped. Returns (dict input -> SRC, R^2).
        """
        candidates = self.inputs if candidates is None else tuple(candidates)
        cov = self.moments.covariance()
        iy = self.index[y]
        var_y = cov[iy, iy]
        if self.n_ok < 3 or not var_y > 0.0 or not self.varies(y):
            return {}, math.nan
        kept = []
        for name in candidates:
            if not self.varies(name):
                continue
            j = self.index[name]
            var_j = cov[j, j]
            if not var_j > 0.0:
                continue
            if kept:
                ckk = cov[np.ix_(kept, kept)]
                ckj = cov[kept, j]
                residual = var_j - ckj @ np.linalg.solve(ckk, ckj)
                if residual <= (1.0 - derived_r2) * var_j:
                    continue
            kept.append(j)
        if not kept:
            return {}, math.nan
        cxx = cov[np.ix_(kept, kept)]
        cxy = cov[kept, iy]
        beta = np.linalg.solve(cxx, cxy)
        src = beta * np.sqrt(np.diag(cxx) / var_y)
        r2 = float(beta @ cxy / var_y)
        return {self.columns[j]: float(s) for j, s in zip(kept, src, strict=True)}, r2


# --- exact percentiles from shots.parquet ------------------------------------------------------


def _order_statistics_positions(n, quantiles):
    """numpy's "linear" method: virtual index, the ranks below and above it, and the weight."""
    q = np.asarray(quantiles, dtype=float)
    # numpy's own for "linear", (n - 1) q: its general form, n q + (1 - q) - 1 (alpha = beta =
    # 1), is the same number but rounded otherwise, a few ulps off pandas' quantile
    virtual = (n - 1) * q
    below = np.floor(virtual)
    gamma = virtual - below
    lo = np.clip(below, 0, n - 1).astype(np.int64)
    hi = np.clip(below + 1, 0, n - 1).astype(np.int64)
    return lo, hi, gamma


def _lerp(a, b, t):
    """numpy's _lerp: a + (b - a) t, computed from b for t >= 0.5."""
    diff = b - a
    return np.where(t >= 0.5, b - diff * (1.0 - t), a + diff * t)


def exact_quantiles(source, n, quantiles, budget_bytes=DEFAULT_BUDGET_BYTES):
    """Exact quantiles (pandas' linear interpolation) of the values ``source()`` yields.

    ``source`` is called once per pass and returns an iterable of 1-D float arrays whose
    concatenation is the sample (n values). Memory: at most ``budget_bytes`` of values at once
    (plus one array from the source): the sample is taken whole when it fits, otherwise its
    order statistics are found by histogram-then-select. ``exact_quantiles_of`` for several
    samples at once.
    """
    variables = {"values": (np.asarray, quantiles)}
    return exact_quantiles_of(source, variables, n, budget_bytes)[0]["values"]


def exact_quantiles_of(chunks, variables, n, budget_bytes=DEFAULT_BUDGET_BYTES, bounds=None):
    """Exact quantiles of several samples of n values each, read in the same passes.

    ``chunks`` is called once per pass and returns an iterable of chunks; ``variables`` maps a
    name to (values_of, quantiles), values_of(chunk) giving a 1-D float array of the chunk's
    values of that sample. ``bounds`` may map a name to (lo, hi) that hold all its values (it
    saves the pass that finds them). Memory: at most ``budget_bytes`` of values at once, for all
    the samples together (plus one chunk). Returns ({name: quantiles}, {name: sum of the
    values}), the sums added chunk by chunk.
    """
    sums = dict.fromkeys(variables, 0.0)
    if n == 0:
        return {name: np.full(len(q), np.nan) for name, (_, q) in variables.items()}, sums
    positions = {name: _order_statistics_positions(n, q) for name, (_, q) in variables.items()}
    cap = max(budget_bytes // 8, 1)
    bounds = dict(bounds or {})
    if n * len(variables) <= cap:  # read whole
        bounds = dict.fromkeys(variables, (-math.inf, math.inf))
    missing = [name for name in variables if name not in bounds]
    if missing:
        low = dict.fromkeys(missing, math.inf)
        high = dict.fromkeys(missing, -math.inf)
        for chunk in chunks():
            for name, (values_of, _) in variables.items():
                v = np.asarray(values_of(chunk), dtype=float)
                sums[name] += float(np.sum(v))
                if name in low and len(v):
                    low[name] = min(low[name], float(np.min(v)))
                    high[name] = max(high[name], float(np.max(v)))
        bounds.update({name: (low[name], high[name]) for name in missing})
    requests = {}
    for name, (values_of, _) in variables.items():
        lo, hi, _ = positions[name]
        ranks = np.unique(np.concatenate([lo, hi])).tolist()
        requests[name] = (values_of, ranks, *bounds[name], 0, n)
    found = _select(requests, chunks, cap, sums=None if missing else sums)
    quantiles = {}
    for name, (lo, hi, gamma) in positions.items():
        a = np.array([found[name][r] for r in lo.tolist()])
        b = np.array([found[name][r] for r in hi.tolist()])
        quantiles[name] = _lerp(a, b, gamma)
    return quantiles, sums


def _in_range(v, lo, hi):
    v = np.asarray(v, dtype=float)
    return v[(v >= lo) & (v <= hi)]


def _bin_scale(lo, hi):
    """Bins per unit of the histogram of [lo, hi] (lo < hi, finite)."""
    scale = _HISTOGRAM_BINS / (hi - lo)
    if not math.isfinite(scale):
        scale = _HISTOGRAM_BINS / (hi / 2.0 - lo / 2.0) / 2.0
    return scale


def _bin_of(v, lo, scale):
    return np.minimum(((v - lo) * scale).astype(np.int64), _HISTOGRAM_BINS - 1)


class _Filling:
    """A preallocated array filled chunk by chunk (no list of parts to concatenate, which
    would hold the values twice)."""

    def __init__(self, size, dtype=float):
        self.values = np.empty(size, dtype=dtype)
        self.size = 0

    def add(self, v):
        if self.size + len(v) > len(self.values):
            raise ValueError(f"the source gave more than the {len(self.values)} values expected")
        self.values[self.size : self.size + len(v)] = v
        self.size += len(v)


def _select(requests, chunks, cap, sums=None):
    """Order statistics of several samples, read in the same passes.

    ``requests`` maps a name to (values_of, ranks, lo, hi, below, count): the order statistics
    ``ranks`` (0-based, of the whole sample) that lie among the ``count`` values within
    [lo, hi], ``below`` values being < lo; values_of(chunk) gives a chunk's values of the
    sample. A request whose values fit its share of ``cap`` (values of 8 bytes) is read whole;
    the others are histogrammed, and a second pass collects the bins that hold the wanted
    ranks, or the exact min and max of a bin still too large, refined in turn. ``sums``, if
    given, receives the sum of every sample's values in the first pass. Returns
    {name: {rank: value}}.
    """
    found = {}
    share = max(cap // len(requests), 1)
    whole = {}
    histograms = {}
    for name, (_, ranks, lo, hi, _, count) in requests.items():
        if lo == hi:
            found[name] = dict.fromkeys(ranks, lo)
        elif count <= share:
            whole[name] = _Filling(count)
        else:
            histograms[name] = (_bin_scale(lo, hi), np.zeros(_HISTOGRAM_BINS, dtype=np.int64))
    for chunk in chunks() if whole or histograms or sums is not None else ():
        for name, (values_of, _, lo, hi, _, _) in requests.items():
            v = np.asarray(values_of(chunk), dtype=float)
            if sums is not None:
                sums[name] += float(np.sum(v))
            if name in whole:
                whole[name].add(_in_range(v, lo, hi))
            elif name in histograms:
                scale, counts = histograms[name]
                counts += np.bincount(
                    _bin_of(_in_range(v, lo, hi), lo, scale), minlength=_HISTOGRAM_BINS
                )
    for name, filled in whole.items():
        ranks, below, count = requests[name][1], requests[name][4], requests[name][5]
        if filled.size != count:
            raise ValueError(f"the source gave {filled.size} values, expected {count}")
        kth = [r - below for r in ranks]
        found[name] = dict(zip(ranks, np.partition(filled.values, kth)[kth].tolist(), strict=True))
    del whole
    if not histograms:
        return found
    # The bins that hold the wanted ranks (empty bins share the start of the next non-empty).
    wanted = {}
    for name, (_, counts) in histograms.items():
        _, ranks, _, _, below, _ = requests[name]
        starts = below + np.concatenate([[0], np.cumsum(counts)[:-1]])
        bins = {}
        for r in ranks:
            b = int(np.searchsorted(starts, r, side="right") - 1)
            while counts[b] == 0:
                b += 1
            bins.setdefault(b, []).append(r)
        wanted[name] = (bins, starts)
    # Second pass: each wanted bin's values when they fit (the collected bins together, with
    # their bin numbers of 2 bytes, stay within the cap), else its exact min and max.
    bin_share = max(cap * 4 // 5 // sum(len(bins) for bins, _ in wanted.values()), 1)
    collect = {}
    big = {}
    for name, (bins, _) in wanted.items():
        counts = histograms[name][1]
        small = [b for b in bins if counts[b] <= bin_share]
        keep = np.zeros(_HISTOGRAM_BINS, dtype=bool)
        keep[small] = True
        size = int(counts[small].sum())
        collect[name] = (keep, _Filling(size), _Filling(size, np.int16))
        big[name] = {b: [math.inf, -math.inf] for b in bins if counts[b] > bin_share}
    for chunk in chunks():
        for name, (keep, values, index) in collect.items():
            values_of, _, lo, hi, _, _ = requests[name]
            v = _in_range(values_of(chunk), lo, hi)
            i = _bin_of(v, lo, histograms[name][0])
            kept = keep[i]
            values.add(v[kept])
            index.add(i[kept])
            for b, mm in big[name].items():
                x = v[i == b]
                if len(x):
                    mm[0], mm[1] = min(mm[0], float(x.min())), max(mm[1], float(x.max()))
    refine = {}
    for name, (bins, starts) in wanted.items():
        _, values, index = collect.pop(name)
        counts = histograms[name][1]
        found.setdefault(name, {})
        for b, rs in bins.items():
            if b in big[name]:
                # _bin_of is monotone: the bin's values are exactly those within its min..max.
                mn, mx = big[name][b]
                refine[name, b] = (requests[name][0], rs, mn, mx, int(starts[b]), int(counts[b]))
            else:
                in_bin = np.sort(values.values[index.values == b])
                found[name].update({r: float(in_bin[r - int(starts[b])]) for r in rs})
    if refine:
        for (name, _), more in _select(refine, chunks, cap).items():
            found[name].update(more)
    return found


# The columns a summary reads back (``summarise``): the quantities and the final x (the distance).
SPILLED = (*QUANTITIES, "final_x_m")


class Spill:
    """The ok shots' values of ``SPILLED``, chunk by chunk as a run writes them, in a
    temporary file in ``folder`` (removed when closed): ``block(table)`` in a chunk's task,
    ``append(point, block)`` in the writer's order, then ``columns(point)``, which reads them
    back as ``ShotsColumns`` reads the Parquet (a dict of each chunk's ok values)."""

    def __init__(self, folder=None):
        self.file = tempfile.TemporaryFile(prefix="mcrun-spill-", dir=folder)
        self.blocks = {}  # point -> [(offset in bytes, ok shots)]

    @staticmethod
    def block(table):
        """A chunk's block: its ok shots' values of ``SPILLED`` (rows) from its Arrow
        ``table``, C-ordered float64."""
        ok = table.column("status").to_numpy() == status_codes.OK
        block = np.empty((len(SPILLED), int(ok.sum())))
        for k, name in enumerate(SPILLED):
            block[k] = table.column(name).to_numpy()[ok]
        return block

    def append(self, point, block):
        """``block`` (``block``) of a chunk of ``point``, after those before it."""
        offset = self.file.seek(0, 2)
        if block.size:  # a chunk without an ok shot has nothing to write (and no view to cast)
            self.file.write(memoryview(np.ascontiguousarray(block)).cast("B"))
        self.blocks.setdefault(point, []).append((offset, block.shape[1]))

    def columns(self, point):
        """The point's values, as a ``ShotsColumns`` gives them."""
        self.file.flush()
        return _SpilledColumns(self, point)

    def close(self):
        self.file.close()


class _SpilledColumns:
    """A point's spilled values, chunk by chunk (``ShotsColumns.chunks``), each column read
    alone (``os.pread``: several threads may read at once)."""

    concurrent = True  # ``summarise`` may read it from several threads

    def __init__(self, spill, point):
        self.spill, self.point = spill, point

    def chunks(self, columns):
        rows = [SPILLED.index(c) for c in columns]
        fd = self.spill.file.fileno()
        for offset, count in self.spill.blocks.get(self.point, []):
            yield {c: np.frombuffer(os.pread(fd, 8 * count, offset + 8 * k * count), np.float64)
                   for c, k in zip(columns, rows, strict=True)}  # fmt: skip


class ShotsColumns:
    """Ok-status values of one point's columns in a shots.parquet, row group by row group.

    ``source``: the file's path, or a ``pyarrow.parquet.ParquetFile`` already open. A run's
    summary passes every point the same open file: opening it reads the footer, which lists
    every row group of the run, so opening it per point would make the summary quadratic in
    the number of points. ``row_groups``: those that hold the point's shots; a row group may
    hold several points (in order), and ``point`` picks its rows. ``cache``: a dict shared by
    the points of one file, which keeps the row group read last, so that the points sharing it
    read it once. ``chunk_rows``: the run's chunk size; the values come a chunk at a time, as
    the run simulated them, so that sums over them (the mean distance) do not depend on how
    the chunks were grouped in the file.
    """

    def __init__(self, source, row_groups, point=None, cache=None, chunk_rows=None):
        self.source = source
        self.row_groups = list(row_groups)
        self.point = point
        self.cache = {} if cache is None else cache
        self.chunk_rows = chunk_rows

    def chunks(self, columns):
        """Iterator of dicts column -> ok values, one per chunk of the point (``chunk_rows``),
        or per row group."""
        if isinstance(self.source, pq.ParquetFile):
            yield from self._chunks(self.source, columns)
            return
        with pq.ParquetFile(self.source) as f:
            yield from self._chunks(f, columns)

    def tables(self, columns):
        """Iterator of Arrow tables of ``columns`` over all the point's shots, whatever their
        status, a row group at a time."""
        f = self.source if isinstance(self.source, pq.ParquetFile) else pq.ParquetFile(self.source)
        try:
            for g in self.row_groups:
                table = f.read_row_group(g, columns=[*columns, "point"])
                if self.point is not None:
                    table = table.filter(pc.equal(table["point"], self.point))
                yield table.select(list(columns))
        finally:
            if f is not self.source:
                f.close()

    def _read(self, f, g, columns):
        key = (g, tuple(columns))
        if key not in self.cache:
            self.cache.clear()
            table = f.read_row_group(g, columns=[*columns, "status", "point"])
            self.cache[key] = {c: table.column(c).to_numpy() for c in table.column_names}
        return self.cache[key]

    def _chunks(self, f, columns):
        for g in self.row_groups:
            values = self._read(f, g, columns)
            start, stop = 0, len(values["status"])
            if self.point is not None:
                start, stop = np.searchsorted(values["point"], [self.point, self.point + 1])
            step = self.chunk_rows or max(stop - start, 1)
            for lo in range(start, stop, step):
                rows = slice(lo, min(lo + step, stop))
                ok = values["status"][rows] == status_codes.OK
                yield {c: values[c][rows][ok] for c in columns}


def _quantiles_on_threads(columns, variables, n, budget_bytes, bounds):
    """``exact_quantiles_of`` the ``variables`` of ``summarise`` over ``columns``: where they
    may be read from several threads at once (a ``Spill``'s), in a group of the variables a
    thread (the budget shared), each group reading only its columns; the same values."""
    from mcrun.executor import on_threads

    names = list(variables)
    groups = 1
    if getattr(columns, "concurrent", False):
        groups = max(min(numba.get_num_threads(), len(names)), 1)
    parts = [names[k::groups] for k in range(groups)]
    results = [None] * groups

    def needs(part):
        wanted = [name for name in part if name in QUANTITIES]
        if "distance" in part:
            wanted += [c for c in ("final_x_m", "final_y_m") if c not in wanted]
        return wanted

    def work(k):
        part = parts[k]
        results[k] = exact_quantiles_of(
            lambda: columns.chunks(needs(part)), {n: variables[n] for n in part}, n,
            budget_bytes // groups, {n: bounds[n] for n in part},
        )  # fmt: skip

    on_threads(work, groups)
    quantiles, sums = {}, {}
    for q, s in results:
        quantiles.update(q)
        sums.update(s)
    return quantiles, sums


def _percentile_name(p):
    return f"p{p:02d}"


def summarise(
    stats,
    columns,
    target_m=None,
    budget_bytes=DEFAULT_BUDGET_BYTES,
    drivers=None,
    derived_r2=DERIVED_R2,
    on_hole=False,
):
    """The summary row (dict) of one point.

    ``stats``: its PointStats; ``columns``: a ShotsColumns over its rows of shots.parquet;
    ``target_m``: (x, y) of the target, default the mean final position; ``drivers``: input
    names in order of preference for the regression (default ``stats.inputs``), see
    ``PointStats.drivers``; ``on_hole``: count the statuses only a hole gives too.
    """
    n_ok = stats.n_ok
    row = {"n_shots": stats.n_shots, "n_ok": n_ok, "n_failed": stats.n_shots - n_ok}
    for code, name in enumerate(_STATUS_NAMES):
        if code != status_codes.OK and (on_hole or code not in status_codes.HOLE_STATUSES):
            row[f"n_{name}"] = int(stats.status_counts[code])
    if target_m is None:
        target_m = (stats.mean("final_x_m"), stats.mean("final_y_m"))
    tx, ty = (float(t) for t in target_m)
    # The percentiles of every quantity and of the distance to the target, in the same passes
    # over shots.parquet; the streaming minima and maxima bound the histograms.
    q = np.array(PERCENTILES) / 100.0
    variables = {name: (operator.itemgetter(name), q) for name in QUANTITIES}
    variables["distance"] = (
        lambda c: np.hypot(c["final_x_m"] - tx, c["final_y_m"] - ty),
        np.array(DISTANCE_PERCENTILES) / 100.0,
    )
    bounds = {name: stats.bounds(name) for name in QUANTITIES}
    bounds["distance"] = stats.distance_bounds(tx, ty)
    quantiles, sums = _quantiles_on_threads(columns, variables, n_ok, budget_bytes, bounds)
    for name in QUANTITIES:
        row[f"{name}_mean"] = stats.mean(name)
        row[f"{name}_std"] = math.sqrt(stats.covariance(name, name)) if n_ok > 1 else math.nan
        for p, v in zip(PERCENTILES, quantiles[name], strict=True):
            row[f"{name}_{_percentile_name(p)}"] = float(v)
    row["final_x_m_mean"] = stats.mean("final_x_m")
    cxx = stats.covariance("final_x_m", "final_x_m")
    cxy = stats.covariance("final_x_m", "final_y_m")
    cyy = stats.covariance("final_y_m", "final_y_m")
    row["cov_xx_m2"], row["cov_xy_m2"], row["cov_yy_m2"] = cxx, cxy, cyy
    for level in ELLIPSE_LEVELS:
        a, b, angle, area = ellipse(cxx, cxy, cyy, level) if n_ok > 1 else (math.nan,) * 4
        row[f"ellipse{level}_semi_major_m"] = a
        row[f"ellipse{level}_semi_minor_m"] = b
        row[f"ellipse{level}_angle_deg"] = angle
        row[f"ellipse{level}_area_m2"] = area
    row["target_x_m"], row["target_y_m"] = tx, ty
    row["distance_mean_m"] = sums["distance"] / n_ok if n_ok else math.nan
    for p, v in zip(DISTANCE_PERCENTILES, quantiles["distance"], strict=True):
        row[f"distance_r{p}_m"] = float(v)
    for y in DRIVEN:
        src, r2 = stats.drivers(y, drivers, derived_r2)
        row[f"{y}_r2"] = r2
        for name in stats.inputs:
            s = src.get(name, math.nan)
            row[f"{y}_src_{name}"] = s
            row[f"{y}_share_{name}"] = s * s
    for name in LANDING_DRIVERS:
        r = stats.correlation("run_m", name)
        row[f"run_m_corr_{name}"] = r
        row[f"run_m_share_{name}"] = r * r
    return row
