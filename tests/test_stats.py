"""Dispersion statistics (mcrun.results.stats) against direct computations on synthetic samples.

The streaming sums must give what pandas gives on the whole sample (means, std with ddof = 1,
covariances) to rounding, the percentiles must be pandas' default (linear interpolation)
whichever path computes them (a sort in memory, or histogram-then-select when the sample is
larger than the memory budget), the ellipses must follow from the covariance's eigenvalues,
and the standardised regression coefficients must equal a least-squares fit on standardised
data.
"""

import math

import numpy as np
import pandas as pd
import pytest

from mcrun.engine.schema import N_OUTCOME, OUTCOME_FIELDS
from mcrun.results import stats
from mcrun.status import INVALID_INPUT, NOT_STOPPED, OK

Q = np.array(stats.PERCENTILES) / 100.0
REL = 1e-9


def chunked(values, sizes):
    """A source for exact_quantiles: the values in chunks of the given sizes, repeatable."""
    edges = np.cumsum(sizes)[:-1]
    parts = np.split(values, edges)
    return lambda: iter(parts)


SAMPLES = {
    "normal": np.random.default_rng(1).normal(250.0, 8.0, 20_001),
    "ties": np.repeat([1.0, 2.0, 2.0, 3.0], 5_000),
    "constant": np.full(3_000, 17.25),
    "heavy tail": np.concatenate(
        [np.zeros(9_000), np.random.default_rng(2).lognormal(0.0, 3.0, 1_234)]
    ),
    "adjacent floats": np.repeat([1.0, np.nextafter(1.0, 2.0)], [4_000, 6_000]),
    "one value": np.array([3.5]),
    # sizes where numpy's general position, n q + (1 - q) - 1, rounds otherwise than (n - 1) q
    "41 values": np.random.default_rng(4).normal(0.0, 8.0, 41),
    "101 values": np.random.default_rng(5).normal(0.0, 8.0, 101),
}


@pytest.mark.parametrize("name", list(SAMPLES))
@pytest.mark.parametrize("budget_values", [10, 1_000, 10**7])
def test_exact_quantiles_equal_pandas(name, budget_values):
    """Sort path (budget above n) and histogram-select path (budget of 10 or 1000 values): bit
    for bit (a few ulps off at 41 and 101 values, where the position was rounded otherwise)."""
    values = SAMPLES[name]
    rng = np.random.default_rng(3)
    shuffled = rng.permutation(values)
    sizes = rng.integers(1, 5_000, size=len(values) // 100 + 2)
    sizes = sizes[: np.searchsorted(np.cumsum(sizes), len(values)) + 1]
    sizes[-1] = len(values) - sizes[:-1].sum()
    got = stats.exact_quantiles(chunked(shuffled, sizes), len(values), Q, 8 * budget_values)
    want = pd.Series(values).quantile(Q).to_numpy()
    np.testing.assert_array_equal(got, want)


def test_exact_quantiles_empty():
    assert np.isnan(stats.exact_quantiles(lambda: iter([]), 0, Q)).all()


def test_comoments_merge_equals_numpy():
    """Chan's pairwise merge of chunks of uneven size equals the two-pass covariance."""
    rng = np.random.default_rng(4)
    data = rng.normal(size=(10_000, 4)) @ rng.normal(size=(4, 4)) + [300.0, -2.0, 0.0, 1e4]
    total = stats.Comoments(4)
    for part in np.array_split(data, [1, 2, 777, 5000, 5001]):
        total.update(part)
    np.testing.assert_allclose(total.mean, data.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(total.covariance(), np.cov(data.T, ddof=1), rtol=1e-10)
    np.testing.assert_array_equal(total.min, data.min(axis=0))
    np.testing.assert_array_equal(total.max, data.max(axis=0))
    # Merging two accumulators equals accumulating everything in one.
    a, b = stats.Comoments(4), stats.Comoments(4)
    a.update(data[:3000])
    b.update(data[3000:])
    a.merge(b)
    np.testing.assert_allclose(a.covariance(), total.covariance(), rtol=1e-12)


def test_ellipse_axes_angle_area():
    """A covariance with standard deviations 10 m and 4 m, major axis 30 deg right of the
    line: semi-axes 10 k and 4 k with k = sqrt(-2 ln(1 - p)) (k = 2.4477 at 95 %), angle 30."""
    a = math.radians(30.0)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    cov = rot @ np.diag([100.0, 16.0]) @ rot.T
    major, minor, angle, area = stats.ellipse(cov[0, 0], cov[0, 1], cov[1, 1], 95)
    k = math.sqrt(-2.0 * math.log(0.05))
    assert k == pytest.approx(2.4477, abs=1e-4)
    assert major == pytest.approx(10.0 * k, rel=1e-12)
    assert minor == pytest.approx(4.0 * k, rel=1e-12)
    assert angle == pytest.approx(30.0, abs=1e-9)
    assert area == pytest.approx(math.pi * 40.0 * k * k, rel=1e-12)
    # Left of the line: 150 deg in [0, 180); across the line: 90.
    assert stats.ellipse(cov[0, 0], -cov[0, 1], cov[1, 1], 68)[2] == pytest.approx(150.0)
    assert stats.ellipse(4.0, 0.0, 100.0, 68)[2] == 90.0
    assert stats.ellipse(100.0, 0.0, 4.0, 68)[2] == 0.0


def test_ellipse_holds_its_share_of_a_normal_sample():
    """The 68 % and 95 % ellipses of a bivariate normal hold 68 % and 95 % of its points
    (binomial sd of the fraction at n = 200000: 0.001)."""
    rng = np.random.default_rng(5)
    cov = np.array([[16.0, 6.0], [6.0, 100.0]])
    xy = rng.multivariate_normal([0.0, 0.0], cov, size=200_000)
    inv = np.linalg.inv(cov)
    d2 = np.einsum("ij,jk,ik->i", xy, inv, xy)
    for level in (68, 95):
        k = stats.ellipse_scale(level)
        assert np.mean(d2 <= k * k) == pytest.approx(level / 100.0, abs=0.005)


def _outcomes(values, status):
    """An outcomes array as simulate_batch writes it, with the given fields set."""
    out = np.full((len(status), N_OUTCOME), np.nan, order="F")
    for name, column in values.items():
        out[:, OUTCOME_FIELDS.index(name)] = column
    out[:, OUTCOME_FIELDS.index("status")] = status
    return out


def test_point_stats_drivers_equal_least_squares():
    """y = 3 x1 - x2 + 0.5 x3 + noise over independent inputs: the SRCs equal the coefficients
    of a least-squares fit on standardised data, R^2 that fit's, and a derived input (an exact
    linear function of x1 and x2) and a constant one are left out."""
    rng = np.random.default_rng(6)
    n = 5_000
    x = rng.normal(size=(n, 3)) * [2.0, 1.0, 4.0]
    y = 3.0 * x[:, 0] - x[:, 1] + 0.5 * x[:, 2] + rng.normal(size=n)
    derived = 2.0 * x[:, 0] + x[:, 1]
    sampled = {"x1": x[:, 0], "x2": x[:, 1], "derived": derived, "x3": x[:, 2], "c": np.ones(n)}
    status = np.where(np.arange(n) % 50 == 0, INVALID_INPUT, OK)
    values = {name: y for name in stats.QUANTITIES}
    values["final_x_m"] = y
    point = stats.PointStats(list(sampled))
    for part in np.array_split(np.arange(n), 7):
        point.update(_outcomes({k: v[part] for k, v in values.items()}, status[part]),
                     {k: v[part] for k, v in sampled.items()})  # fmt: skip
    ok = status == OK
    src, r2 = point.drivers("total_m")
    assert list(src) == ["x1", "x2", "x3"]
    xs = (x[ok] - x[ok].mean(0)) / x[ok].std(0, ddof=1)
    ys = (y[ok] - y[ok].mean()) / y[ok].std(ddof=1)
    coef, *_ = np.linalg.lstsq(xs, ys, rcond=None)
    np.testing.assert_allclose([src[k] for k in ("x1", "x2", "x3")], coef, rtol=REL)
    residual = ys - xs @ coef
    assert r2 == pytest.approx(1.0 - residual @ residual / (ys @ ys), rel=REL)
    # Independent inputs: the shares SRC^2 add up to R^2 (to sampling noise).
    assert sum(s * s for s in src.values()) == pytest.approx(r2, abs=0.02)
    assert point.n_shots == n and point.n_ok == int(ok.sum())
    assert point.status_counts[INVALID_INPUT] == n - ok.sum()


def test_point_stats_counts_failures_and_ignores_them():
    """Failed shots are counted by status and take no part in the moments (their outcome
    fields, NaN or not, are not read)."""
    status = np.array([OK, NOT_STOPPED, OK, INVALID_INPUT, OK])
    carry = np.array([100.0, 5.0, 110.0, np.nan, 120.0])
    values = {name: carry for name in stats.QUANTITIES}
    values["final_x_m"] = carry
    point = stats.PointStats([])
    point.update(_outcomes(values, status), {})
    assert point.n_shots == 5 and point.n_ok == 3
    assert point.status_counts[NOT_STOPPED] == 1 and point.status_counts[INVALID_INPUT] == 1
    assert point.mean("carry_m") == pytest.approx(110.0, rel=1e-15)
    assert math.sqrt(point.covariance("carry_m", "carry_m")) == pytest.approx(10.0, rel=1e-15)


def test_an_exact_sum_is_math_fsum_whatever_the_chunks_and_their_order():
    """``ExactSum``: the correctly rounded sum (``math.fsum``) of values of every sign and
    magnitude, whatever the chunks they come in and the order the chunks are merged in."""
    rng = np.random.default_rng(3)
    values = rng.normal(0.0, 1.0, 20_000) * 10.0 ** rng.integers(-300, 300, 20_000)
    values = np.concatenate([values, [1e300, 1.0, -1e300, 5e-324, -0.0, 0.0], -values[:500]])
    whole = stats.ExactSum()
    whole.add(values)
    assert whole.value() == math.fsum(values)
    cuts = np.sort(rng.choice(len(values), 30, replace=False))
    parts = []
    for chunk in np.split(values, cuts):
        part = stats.ExactSum()
        part.add(chunk)
        parts.append(part)
    merged = stats.ExactSum()
    for k in rng.permutation(len(parts)):
        merged.merge(parts[k])
    assert merged.value() == math.fsum(values)
    assert stats.ExactSum().value() == 0.0


def test_running_moments_give_the_mean_and_its_standard_error_chunk_by_chunk():
    rng = np.random.default_rng(4)
    values = rng.normal(3.0, 0.5, 10_001)
    moments = stats.RunningMoments()
    for chunk in np.array_split(values, 7):
        moments.add(chunk)
    mean, se = moments.mean_se()
    assert mean == math.fsum(values) / len(values)
    assert se == pytest.approx(values.std(ddof=1) / math.sqrt(len(values)), rel=1e-12)


@pytest.mark.parametrize("name", ["par3-over-water", "penner-fig6-irons"])
def test_the_summary_reads_from_its_spill_what_the_parquet_holds(name, tmp_path, monkeypatch):
    """A local run's summary reads its values back from ``stats.Spill``: for every point, the
    same chunks of the same ok values, bit for bit, as ``ShotsColumns`` reads from the run's
    shots.parquet (chunks of 700 shots, not dividing the 2,500 of a point; a hole; several
    points)."""
    import pyarrow.parquet as pq

    from mcrun.run.local import run_scenario

    spilled = {}

    class Kept(stats.Spill):
        def close(self):
            for point in self.blocks:
                spilled[point] = list(self.columns(point).chunks(stats.SPILLED))
            super().close()

    monkeypatch.setattr(stats, "Spill", Kept)
    result = run_scenario(name, n=2500, seed=3, out_dir=tmp_path / "run", chunk_size=700,
                          progress=False)  # fmt: skip
    with pq.ParquetFile(result.shots_path) as f:
        groups = range(f.num_row_groups)
        for point, chunks in spilled.items():
            read = list(stats.ShotsColumns(f, groups, point, {}, 700).chunks(stats.SPILLED))
            assert len(read) == len(chunks) == 4
            for a, b in zip(read, chunks, strict=True):
                for column in stats.SPILLED:
                    np.testing.assert_array_equal(a[column].view(np.int64),
                                                  b[column].view(np.int64))  # fmt: skip
    assert len(spilled) == result.points


def test_a_point_whose_chunks_hold_no_ok_shot_is_summarised_as_none_ok(tmp_path):
    """A chunk without an ok shot spills nothing: a point on turf without rolling resistance
    (``turf.rho_g`` 0, where no ball stops: every shot not_stopped) is summarised with no ok
    shot and no values, beside a point whose shots are all ok."""
    from mcrun.run.local import run_scenario

    scenario = tmp_path / "rho.toml"
    scenario.write_text(
        '[scenario]\nname = "rho"\nshots = 300\nseed = 1\n'
        '[launch]\nball_speed = { dist = "normal", mean = "167 mph", sd = "1.5 mph" }\n'
        'launch_angle = "10.9 deg"\nspin = "2686 rpm"\n'
        '[turf]\npreset = "fairway"\n[sweep]\n"turf.rho_g" = [0, 0.1]\n',
        encoding="utf-8",
    )
    result = run_scenario(scenario, out_dir=tmp_path / "run", chunk_size=100, progress=False)
    summary = result.summary().set_index("point")
    assert summary.loc[0, "n_ok"] == 0 and summary.loc[0, "n_not_stopped"] == 300
    assert summary.loc[1, "n_ok"] == 300
    assert np.isnan(summary.loc[0, "total_m_mean"]) and summary.loc[1, "total_m_mean"] > 200.0
    statuses = pd.read_parquet(result.shots_path, columns=["point", "status"])
    assert set(statuses.loc[statuses.point == 0, "status"]) == {NOT_STOPPED}


@pytest.mark.parametrize("budget_values", [100_000, 500])
def test_the_summary_s_quantiles_on_threads_are_those_of_one_thread(tmp_path, budget_values):
    """``summarise``'s percentiles from a ``Spill`` (read whole, or histogrammed and refined
    under a small budget), a group of variables a thread: the same values and sums, bit for
    bit, as one thread reading every column, and numpy's percentiles."""
    import numba

    rng = np.random.default_rng(5)
    spill = stats.Spill(tmp_path)
    blocks = [rng.normal(50.0, 20.0, size=(len(stats.SPILLED), 3000)) for _ in range(5)]
    for block in blocks:
        spill.append(0, block)
    columns = spill.columns(0)

    class OneThread:  # the same values, read as ShotsColumns reads them: no ``concurrent``
        def chunks(self, names):
            return columns.chunks(names)

    q = np.array(stats.PERCENTILES) / 100.0
    variables = {name: (lambda c, name=name: c[name], q) for name in stats.QUANTITIES}
    variables["distance"] = (lambda c: np.hypot(c["final_x_m"] - 3.0, c["final_y_m"] + 1.0), q)
    values = {name: np.concatenate([b[stats.SPILLED.index(name)] for b in blocks])
              for name in stats.SPILLED}  # fmt: skip
    bounds = {name: (values[name].min(), values[name].max()) for name in stats.QUANTITIES}
    distance = np.hypot(values["final_x_m"] - 3.0, values["final_y_m"] + 1.0)
    bounds["distance"] = (distance.min(), distance.max())
    n, budget = 15_000, 8 * budget_values
    previous = numba.get_num_threads()
    numba.set_num_threads(2)
    try:
        both = stats._quantiles_on_threads(columns, variables, n, budget, bounds)
    finally:
        numba.set_num_threads(previous)
    one = stats._quantiles_on_threads(OneThread(), variables, n, budget, bounds)
    for name in variables:
        np.testing.assert_array_equal(both[0][name], one[0][name])
        assert both[1][name] == one[1][name]
        expected = distance if name == "distance" else values[name]
        np.testing.assert_array_equal(both[0][name], np.percentile(expected, 100 * q))
    spill.close()


def test_values_that_vary_only_by_rounding_drive_nothing(tmp_path):
    """Copies of one shot fitted by a normal (its standard deviations an ulp or so) fly shots
    that differ in their last bits only: no input explains their variance and no landing state
    their run (NaN), where their rounding gave shares of 8 % and correlations of +-1."""
    from mcrun.run.local import run_scenario

    (tmp_path / "same.csv").write_text("ball_speed_mph,launch_deg,spin_rpm\n" + "150,12,2500\n" * 3)
    scenario = tmp_path / "same.toml"
    scenario.write_text('[launch]\nfile = "same.csv"\nsample = "normal"\n', encoding="utf-8")
    result = run_scenario(scenario, n=200, seed=1, out_dir=tmp_path / "run", progress=False)
    row = result.summary().iloc[0]
    shots = pd.read_parquet(result.shots_path, columns=["ball_speed_mps", "total_m"])
    assert 0.0 < shots["ball_speed_mps"].std() < 1e-12 * shots["ball_speed_mps"].mean()
    assert np.isnan(row["total_m_r2"]) and np.isnan(row["final_y_m_r2"])
    shares = [v for k, v in row.items() if "_share_" in k or "_corr_" in k]
    assert shares and np.isnan(shares).all()
