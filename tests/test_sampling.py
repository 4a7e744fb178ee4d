"""The sampler (mcrun.run.sampling): determinism, distributions, correlation, resampling and the
conversions into the kernel's inputs.

Statistical tolerances, at N = 20,000 samples: a mean within 4 standard errors; a standard
deviation within 4 % (its standard error is about 0.5 %); a proportion within 4 standard
errors; a sample correlation within 0.03 of its target (standard error below 0.007). Every
draw is deterministic, so none of these can fail at random: a failure means a wrong sampler.
"""

import math
import textwrap
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from mcrun import api
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN, INPUT_FIELDS, N_INPUT, OUTCOME_FIELDS, PLANE_FIELDS
from mcrun.engine.shot import default_dt_s
from mcrun.physics import aero, atmosphere
from mcrun.physics.constants import DEG
from mcrun.physics.launch import launch_from_club
from mcrun.physics.turf import PRESETS, rho_g_from_stimp
from mcrun.quantities import by_path
from mcrun.run import scenario as sc
from mcrun.run.sampling import (
    block_generator,
    draw_block,
    sample,
    sampled_columns,
    truncnormal_standard,
)

N = 20_000
LIBRARY = Path(__file__).resolve().parent.parent / "scenarios"
SESSION_CSV = Path(__file__).resolve().parent / "data" / "launch_monitor_session.csv"
RPM = 2.0 * math.pi / 60.0


def load(tmp_path, text, name="s.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return sc.load(path)


RANDOM = """
[scenario]
seed = 7
block_size = 1000
[launch]
ball_speed = { dist = "normal", mean = "167 mph", sd = "1.5 mph" }
launch_angle = { dist = "triangular", low = 8, mode = 10, high = 15 }
spin = { dist = "lognormal", median = "2686 rpm", sigma = 0.1 }
spin_axis = { dist = "truncnormal", mean = 0, sd = 4, low = -3, high = 6 }
azimuth = { dist = "uniform", low = -2, high = 3 }
[turf]
preset = "fairway"
mu = { dist = "truncnormal", mean = 0.4, sd = 0.05, low = 0.3, high = 0.5 }
stimp = { dist = "uniform", low = "8 ft", high = "12 ft" }
restitution = { dist = "normal", mean = 1.0, sd = 0.02 }
[weather]
wind_speed = { dist = "truncnormal", mean = "4 m/s", sd = "2 m/s", low = 0, high = "10 m/s" }
wind_direction = { dist = "uniform", low = 0, high = 360 }
temperature = { dist = "normal", mean = "20 C", sd = "3 C" }
altitude = { dist = "uniform", low = "0 m", high = "1600 m" }
humidity = { dist = "uniform", low = 0.2, high = 0.8 }
[[group]]
name = "a"
[[group]]
name = "b"
"""


@pytest.fixture(scope="module")
def random_scenario(tmp_path_factory):
    return load(tmp_path_factory.mktemp("random"), RANDOM)


def same(a, b):
    """Bit-for-bit equality of two (inputs, sampled) pairs."""
    assert a[0].tobytes() == b[0].tobytes()
    assert list(a[1]) == list(b[1])
    for name in a[1]:
        assert a[1][name].tobytes() == b[1][name].tobytes(), name


# --- determinism -------------------------------------------------------------------------------


def test_chunking_does_not_change_a_sample(random_scenario):
    s = random_scenario
    point = s.points[1]
    whole = sample(s, point, 0, 10_000)
    first, second = sample(s, point, 0, 3_000), sample(s, point, 3_000, 10_000)
    joined = (
        np.asfortranarray(np.concatenate([first[0], second[0]])),
        {k: np.concatenate([first[1][k], second[1][k]]) for k in first[1]},
    )
    same(whole, joined)
    # Odd chunks that cut blocks anywhere, one sample at a time included.
    edges = [0, 1, 999, 1000, 1001, 4321, 4322, 10_000]
    parts = [sample(s, point, a, b) for a, b in zip(edges[:-1], edges[1:], strict=True)]
    joined = (
        np.asfortranarray(np.concatenate([p[0] for p in parts])),
        {k: np.concatenate([p[1][k] for p in parts]) for k in whole[1]},
    )
    same(whole, joined)


def test_prefix_property(random_scenario):
    """The first 10,000 samples of a run of 20,000 are a run of 10,000."""
    s = random_scenario
    longer = sample(s, s.points[0], 0, 20_000)
    shorter = sample(s, s.points[0], 0, 10_000)
    same(shorter, (longer[0][:10_000], {k: v[:10_000] for k, v in longer[1].items()}))


def test_reloading_gives_the_same_numbers_and_points_differ(random_scenario, tmp_path):
    again = load(tmp_path, RANDOM)
    same(
        sample(random_scenario, random_scenario.points[0], 0, 2000),
        sample(again, again.points[0], 0, 2000),
    )
    a = sample(again, again.points[0], 0, 2000)[0]
    b = sample(again, again.points[1], 0, 2000)[0]
    assert not np.array_equal(a, b)  # points have their own streams (spawn key)
    other_seed = load(tmp_path, RANDOM.replace("seed = 7", "seed = 8"), "t.toml")
    assert not np.array_equal(a, sample(other_seed, other_seed.points[0], 0, 2000)[0])


def test_block_generator_is_the_contracts_seed_sequence(tmp_path):
    """Block b of point p: Generator(PCG64(SeedSequence(seed, spawn_key=(p, b)))); a single
    normal quantity is its first block_size standard normals, scaled."""
    s = load(
        tmp_path,
        """
        [scenario]
        seed = 2019
        block_size = 64
        [launch]
        ball_speed = { dist = "normal", mean = 70, sd = 2 }
        launch_angle = 11
        spin = 280
        [[group]]
        name = "a"
        [[group]]
        name = "b"
        """,
    )
    point = s.points[1]
    _, sampled = sample(s, point, 64 * 3, 64 * 5)
    expected = []
    for block in (3, 4):
        rng = np.random.Generator(
            np.random.PCG64(np.random.SeedSequence(2019, spawn_key=(1, block)))
        )
        expected.append(70.0 + 2.0 * rng.standard_normal(64))
        assert (
            block_generator(2019, 1, block).random()
            == np.random.Generator(
                np.random.PCG64(np.random.SeedSequence(2019, spawn_key=(1, block)))
            ).random()
        )
    assert sampled["ball_speed_mps"].tobytes() == np.concatenate(expected).tobytes()


def test_global_numpy_random_state_is_untouched(random_scenario):
    np.random.seed(12345)
    expected = np.random.random(3)
    np.random.seed(12345)
    sample(random_scenario, random_scenario.points[0], 0, 3000)
    assert np.array_equal(np.random.random(3), expected)


def test_shapes_order_and_columns(random_scenario):
    s = random_scenario
    inputs, sampled = sample(s, s.points[0], 5, 2005)
    assert inputs.shape == (2000, N_INPUT) and inputs.flags.f_contiguous
    assert list(sampled) == sampled_columns(s)
    assert all(len(v) == 2000 for v in sampled.values())
    assert {"altitude_m", "stimp_m"} <= set(sampled)
    assert not {"club_speed_mps", "source_row"} & set(sampled)
    empty_inputs, empty = sample(s, s.points[0], 7, 7)
    assert empty_inputs.shape == (0, N_INPUT) and all(len(v) == 0 for v in empty.values())


# --- distributions -------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def drawn(random_scenario):
    return sample(random_scenario, random_scenario.points[0], 0, N)


def within_4_se(x, mean, sd):
    assert abs(np.mean(x) - mean) < 4.0 * sd / math.sqrt(len(x)), (np.mean(x), mean)


def test_normal_moments(drawn):
    x = drawn[1]["ball_speed_mps"]
    mean, sd = 167 * 0.44704, 1.5 * 0.44704
    within_4_se(x, mean, sd)
    assert np.std(x) == pytest.approx(sd, rel=0.04)
    temperature = drawn[1]["temperature_c"]  # an sd of "3 C" is 3 K
    within_4_se(temperature, 20.0, 3.0)
    assert np.std(temperature) == pytest.approx(3.0, rel=0.04)


def test_truncnormal_moments_and_bounds(drawn):
    x = drawn[1]["spin_axis_deg"]
    assert x.min() >= -3.0 and x.max() <= 6.0
    reference = stats.truncnorm(-3.0 / 4.0, 6.0 / 4.0, loc=0.0, scale=4.0)
    within_4_se(x, reference.mean(), reference.std())
    assert np.std(x) == pytest.approx(reference.std(), rel=0.04)
    mu = drawn[1]["mu"]
    assert mu.min() >= 0.3 and mu.max() <= 0.5
    within_4_se(mu, 0.4, stats.truncnorm(-2, 2, loc=0.4, scale=0.05).std())


@pytest.mark.parametrize(("a", "b"), [(-1.0, 2.0), (3.0, 5.0), (-8.0, -6.0), (12.0, 40.0)])
def test_truncnormal_inverse_cdf_in_the_tails(a, b):
    """Intervals inside, above and far out in either tail of the standard normal."""
    u = np.random.Generator(np.random.PCG64(1)).random(N)
    x = truncnormal_standard(a, b, u)
    assert x.min() >= a and x.max() <= b
    reference = stats.truncnorm(a, b)
    within_4_se(x, reference.mean(), reference.std())
    assert np.std(x) == pytest.approx(reference.std(), rel=0.04)
    # The inverse CDF is exact: the draws' CDF values are the uniforms.
    assert np.allclose(reference.cdf(x), u, atol=1e-9)


def test_uniform_moments_and_bounds(drawn):
    x = drawn[1]["azimuth_deg"]
    assert x.min() >= -2.0 and x.max() <= 3.0
    within_4_se(x, 0.5, 5.0 / math.sqrt(12.0))
    assert np.std(x) == pytest.approx(5.0 / math.sqrt(12.0), rel=0.04)


def test_triangular_mean_and_mode(drawn):
    x = drawn[1]["launch_angle_deg"]
    low, mode, high = 8.0, 10.0, 15.0
    assert x.min() >= low and x.max() <= high
    sd = math.sqrt((low**2 + mode**2 + high**2 - low * mode - low * high - mode * high) / 18.0)
    within_4_se(x, (low + mode + high) / 3.0, sd)
    # The mode: P(X < mode) = (mode - low) / (high - low).
    p = (mode - low) / (high - low)
    assert abs(np.mean(x < mode) - p) < 4.0 * math.sqrt(p * (1 - p) / N)


def test_lognormal_median_and_sigma(drawn):
    x = drawn[1]["spin_radps"]
    log = np.log(x / (2686 * RPM))
    within_4_se(log, 0.0, 0.1)  # the median is exp(mean of the log)
    assert np.std(log) == pytest.approx(0.1, rel=0.04)
    assert abs(np.mean(x < 2686 * RPM) - 0.5) < 4.0 * math.sqrt(0.25 / N)


def test_constants_are_constant(tmp_path):
    s = load(tmp_path, '[launch]\nball_speed = "167 mph"\nlaunch_angle = 10.9\nspin = 280\n')
    inputs, sampled = sample(s, s.points[0], 0, 3000)
    assert (sampled["ball_speed_mps"] == 167 * 0.44704).all()
    assert (inputs[:, COLUMN["launch_angle_rad"]] == 10.9 * DEG).all()
    assert (np.diff(inputs, axis=0) == 0).all()


# --- correlation ---------------------------------------------------------------------------------

CORRELATED = """
[scenario]
seed = 3
[launch]
ball_speed = { dist = "normal", mean = "167 mph", sd = "1.5 mph" }
launch_angle = { dist = "normal", mean = "10.9 deg", sd = "1.0 deg" }
spin = { dist = "normal", mean = "2686 rpm", sd = "270 rpm" }
correlation = { names = ["ball_speed", "launch_angle", "spin"], matrix = [
    [1.0, 0.1, -0.3],
    [0.1, 1.0, -0.4],
    [-0.3, -0.4, 1.0],
] }
"""


def test_correlation_matrix_reproduced(tmp_path):
    s = load(tmp_path, CORRELATED)
    _, x = sample(s, s.points[0], 0, N)
    names = ("ball_speed_mps", "launch_angle_deg", "spin_radps")
    got = np.corrcoef([x[n] for n in names])
    assert np.abs(got - s.points[0].params["launch.correlation"].matrix).max() < 0.03
    # The marginals keep their means and sds.
    for name, mean, sd in zip(
        names, (167 * 0.44704, 10.9, 2686 * RPM), (1.5 * 0.44704, 1.0, 270 * RPM), strict=True
    ):
        within_4_se(x[name], mean, sd)
        assert np.std(x[name]) == pytest.approx(sd, rel=0.04)


def test_semi_definite_correlation(tmp_path):
    """A singular (positive semi-definite) matrix works: perfectly correlated quantities."""
    text = CORRELATED.replace(
        "[1.0, 0.1, -0.3],\n    [0.1, 1.0, -0.4],\n    [-0.3, -0.4, 1.0],",
        "[1.0, 1.0, -1.0],\n    [1.0, 1.0, -1.0],\n    [-1.0, -1.0, 1.0],",
    )
    s = load(tmp_path, text)
    assert s.points[0].params["launch.correlation"].matrix[0, 1] == 1.0
    _, x = sample(s, s.points[0], 0, N)
    z_speed = (x["ball_speed_mps"] - 167 * 0.44704) / (1.5 * 0.44704)
    z_spin = (x["spin_radps"] - 2686 * RPM) / (270 * RPM)
    assert np.allclose(z_speed, -z_spin, atol=1e-9)
    assert np.std(z_speed) == pytest.approx(1.0, rel=0.04)


def test_semidefinite_factor_is_exact_and_blas_free():
    """A rank-one correlation matrix, perturbed by rounding as an eigen-solver would leave it,
    gets a factor with exactly zero columns: no sample of one quantity leaks into another's
    noise (an eigenvalue of 9e-18 once gave a column of 3e-9 on some BLAS kernels)."""
    one = np.array([[1.0, 1.0, -1.0], [1.0, 1.0, -1.0], [-1.0, -1.0, 1.0]])
    for noise in (0.0, 1e-17, -1e-17):
        matrix = one + noise * np.array([[0, 0, 0], [0, 1, 0], [0, 0, 1]])
        factor = sc.semidefinite_cholesky(matrix)
        assert np.array_equal(factor[:, 1:], np.zeros((3, 2)))
        assert np.array_equal(factor[:, 0], [1.0, 1.0, -1.0])
    # Full rank: the Cholesky factor itself (the library's matrix, to the bit).
    matrix = np.array([[1.0, 0.1, -0.3], [0.1, 1.0, -0.4], [-0.3, -0.4, 1.0]])
    assert np.array_equal(sc.semidefinite_cholesky(matrix), np.linalg.cholesky(matrix))


# --- resampling measured shots -------------------------------------------------------------------


def session_si():
    frame = pd.read_csv(SESSION_CSV, comment="#")
    return np.column_stack(
        [
            frame["ball_speed_mph"] * 0.44704,
            frame["launch_deg"],
            frame["spin_rpm"] * RPM,
            frame["spin_axis_deg"],
        ]
    )


def test_resampling_draws_only_rows_of_the_file(tmp_path):
    s = load(tmp_path, f'[scenario]\nseed = 5\n[launch]\nfile = "{SESSION_CSV}"\n')
    _, x = sample(s, s.points[0], 0, 5000)
    rows = session_si()
    drawn = np.column_stack(
        [x["ball_speed_mps"], x["launch_angle_deg"], x["spin_radps"], x["spin_axis_deg"]]
    )
    assert np.allclose(drawn, rows[x["source_row"]], rtol=1e-12, atol=1e-12)
    assert set(np.unique(x["source_row"])) == set(range(20))  # every row comes up
    assert (x["azimuth_deg"] == 0.0).all()  # no azimuth column: 0


def test_parquet_copy_resamples_the_same(tmp_path):
    frame = pd.read_csv(SESSION_CSV, comment="#")
    frame.to_parquet(tmp_path / "session.parquet")
    csv = load(tmp_path, f'[scenario]\nseed = 5\n[launch]\nfile = "{SESSION_CSV}"\n', "c.toml")
    parquet = load(tmp_path, '[scenario]\nseed = 5\n[launch]\nfile = "session.parquet"\n')
    same(sample(csv, csv.points[0], 0, 3000), sample(parquet, parquet.points[0], 0, 3000))


def test_jitter_has_the_stated_sd(tmp_path):
    text = f"""
    [launch]
    file = "{SESSION_CSV}"
    jitter = {{ ball_speed = "0.5 mph", spin_rpm = 50, azimuth = "1 deg" }}
    """
    s = load(tmp_path, text)
    _, x = sample(s, s.points[0], 0, N)
    rows = session_si()[x["source_row"]]
    for k, name, sd in (
        (0, "ball_speed_mps", 0.5 * 0.44704),
        (2, "spin_radps", 50 * RPM),
    ):
        residual = x[name] - rows[:, k]
        within_4_se(residual, 0.0, sd)
        assert np.std(residual) == pytest.approx(sd, rel=0.04)
    assert np.allclose(x["launch_angle_deg"], rows[:, 1], rtol=1e-13, atol=0)  # not jittered
    within_4_se(x["azimuth_deg"], 0.0, 1.0)  # absent from the file: 0, jittered
    assert np.std(x["azimuth_deg"]) == pytest.approx(1.0, rel=0.04)


# --- conversions into the kernel's inputs --------------------------------------------------------


def test_club_conversion_matches_launch_from_club(tmp_path):
    text = """
    [club]
    speed = { dist = "normal", mean = "45 m/s", sd = "2 m/s" }
    mass = { dist = "uniform", low = "190 g", high = "210 g" }
    loft = { dist = "normal", mean = 13.3, sd = 1.5 }
    spin_axis = { dist = "normal", mean = 15, sd = 6 }
    """
    s = load(tmp_path, text)
    inputs, x = sample(s, s.points[0], 0, 2000)
    assert {"club_speed_mps", "club_mass_kg", "loft_deg"} <= set(x)
    raw = draw_block(s, s.points[0], 0)  # the SI draws of samples 0..4095
    for i in range(2000):
        speed, angle, spin = launch_from_club(
            raw["club.speed"][i], raw["club.mass"][i], raw["club.loft"][i]
        )
        assert inputs[i, COLUMN["ball_speed_mps"]] == speed
        assert inputs[i, COLUMN["launch_angle_rad"]] == (angle / DEG) * DEG  # as mcrun.api
        assert inputs[i, COLUMN["spin_radps"]] == spin
    assert np.array_equal(inputs[:, COLUMN["spin_axis_rad"]], raw["club.spin_axis"][:2000])
    assert np.allclose(x["loft_deg"], raw["club.loft"][:2000] / DEG)
    assert x["ball_speed_mps"].tobytes() == inputs[:, COLUMN["ball_speed_mps"]].tobytes()


def test_club_conversion_is_bit_exact_for_a_constant_delivery(tmp_path):
    s = load(tmp_path, "[club]\nspeed = 40\nmass = 0.25\nloft = 46\n")
    inputs, _ = sample(s, s.points[0], 0, 10)
    speed, angle_deg, spin = api.launch_conditions(
        club_speed_mps=40.0, club_mass_kg=0.25, loft_deg=46.0
    )
    assert (inputs[:, COLUMN["ball_speed_mps"]] == speed).all()
    assert (inputs[:, COLUMN["launch_angle_rad"]] == angle_deg * DEG).all()
    assert (inputs[:, COLUMN["spin_radps"]] == spin).all()


def test_weather_turf_and_model_conversions(random_scenario, drawn):
    inputs, x = drawn
    col = {name: inputs[:, k] for k, name in enumerate(INPUT_FIELDS)}
    # Wind: speed and the direction it blows towards -> (along the target line, to the right).
    direction = x["wind_direction_deg"] * DEG
    assert np.allclose(col["wind_x_mps"], x["wind_speed_mps"] * np.cos(direction), atol=1e-12)
    assert np.allclose(col["wind_right_mps"], x["wind_speed_mps"] * np.sin(direction), atol=1e-12)
    # Air from temperature, altitude and humidity, as the single-shot API computes it.
    for i in range(0, N, 997):
        rho, nu = api.air_properties(
            temperature_c=x["temperature_c"][i],
            altitude_m=x["altitude_m"][i],
            relative_humidity=x["relative_humidity"][i],
        )
        assert col["air_density_kgpm3"][i] == pytest.approx(rho, rel=1e-12)
        assert col["kinematic_viscosity_m2ps"][i] == pytest.approx(nu, rel=1e-12)
    assert np.allclose(x["pressure_pa"], atmosphere.pressure_at_altitude_pa(x["altitude_m"]))
    # Stimp -> rho_g; restitution scales e0, e1, e2 and e_high of the preset.
    stimp = x["stimp_m"]
    assert stimp.min() >= 8 * 0.3048 and stimp.max() <= 12 * 0.3048
    assert np.allclose(col["rho_g"], [rho_g_from_stimp(v) for v in stimp], rtol=1e-14)
    fairway = PRESETS["fairway"]
    for name in ("e0", "e1", "e2", "e_high"):
        assert np.allclose(col[name], getattr(fairway, name) * x["restitution"], rtol=1e-14)
    assert (col["e_break_speed_mps"] == fairway.e_break_speed_mps).all()
    assert (col["aero_model"] == aero.MODELS[aero.DEFAULT_MODEL]).all()  # the default
    assert (col["dt_s"] == default_dt_s("uniform")).all()
    assert (col["mu"] == x["mu"]).all()


@pytest.mark.parametrize(
    "turf",
    [
        "mu = { dist = 'normal', mean = 0.1, sd = 0.2 }",
        "stimp = { dist = 'normal', mean = '1 m', sd = '2 m' }",
    ],
)
def test_out_of_range_draws_become_invalid_kernel_inputs(tmp_path, turf):
    """A normal friction of 0.1 +- 0.2, or a Stimp reading of 1 +- 2 m, draws some negative
    values: those shots get a NaN ball speed, so the kernel reports invalid_input (a Stimp of 0
    or less gives no rho_g, and no error); the sampled value is kept."""
    text = f"""
    [launch]
    ball_speed = 70
    launch_angle = 11
    spin = 280
    [turf]
    {turf}
    """
    s = load(tmp_path, text)
    inputs, x = sample(s, s.points[0], 0, 4000)
    name, path = ("mu", "turf.mu") if turf.startswith("mu") else ("stimp_m", "turf.stimp")
    assert 0.2 < (x[name] < 0.0).mean() < 0.4
    lo, hi = by_path(path).limits
    refused = ~((x[name] >= lo) & (x[name] <= hi))
    assert np.isnan(inputs[refused, COLUMN["ball_speed_mps"]]).all()
    assert (inputs[~refused, COLUMN["ball_speed_mps"]] == 70.0).all()
    assert (x["ball_speed_mps"] == 70.0).all()


def test_draws_out_of_range_convert_without_a_warning(tmp_path):
    """A temperature of 20 +- 94 C draws values whose air overflows (exp of a huge number):
    their shots are refused as invalid_input, silently, not with NumPy's warnings on stderr."""
    text = """
    [launch]
    ball_speed = 70
    launch_angle = 11
    spin = 280
    [weather]
    temperature = { dist = "normal", mean = "20 C", sd = "94 C" }
    """
    s = load(tmp_path, text)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        inputs, x = sample(s, s.points[0], 0, 4000)
    lo, hi = by_path("weather.temperature").range  # (C; its limits are in K)
    refused = ~((x["temperature_c"] >= lo) & (x["temperature_c"] <= hi))
    assert 0.5 < refused.mean() < 1.0
    assert np.isnan(inputs[refused, COLUMN["ball_speed_mps"]]).all()
    assert not np.isnan(inputs[~refused, COLUMN["ball_speed_mps"]]).any()


def test_mixed_launch_modes_share_one_set_of_columns(tmp_path):
    text = f"""
    [[group]]
    name = "ball"
    launch.ball_speed = 70
    launch.launch_angle = 11
    launch.spin = 280
    [[group]]
    name = "club"
    club.speed = 45
    club.loft = 13.3
    [[group]]
    name = "file"
    launch.file = "{SESSION_CSV}"
    """
    s = load(tmp_path, text)
    assert [p.mode for p in s.points] == ["ball", "club", "file"]
    columns = sampled_columns(s)
    assert {"club_speed_mps", "source_row"} <= set(columns)
    ball, club, measured = (sample(s, p, 0, 100)[1] for p in s.points)
    assert np.isnan(ball["club_speed_mps"]).all() and (ball["source_row"] == -1).all()
    assert (club["club_speed_mps"] == 45.0).all()
    assert (measured["source_row"] >= 0).all()
    assert all(list(x) == columns for x in (ball, club, measured))


# --- the paper's Fig. 4 as a scenario --------------------------------------------------------


def test_fig4_inputs_equal_the_single_shot_api():
    """penner-fig4-drives.toml: every point's kernel inputs are, bit for bit, what
    mcrun.api.simulate uses for the same club delivery, air and turf."""
    s = sc.load(LIBRARY / "penner-fig4-drives.toml")
    assert [p.label for p in s.points] == [
        "club.speed=35 m/s",
        "club.speed=45 m/s",
        "club.speed=55 m/s",
    ]
    for point, club_speed in zip(s.points, (35.0, 45.0, 55.0), strict=True):
        inputs, x = sample(s, point, 0, 3)
        row, _ = api.shot_inputs(
            club_speed_mps=club_speed,
            club_mass_kg=0.200,
            loft_deg=13.3,
            aero_model="penner2002",
            temperature_c=20.0,
            altitude_m=0.0,
            relative_humidity=0.0,
        )
        assert inputs.tobytes() == np.repeat(row, 3, axis=0).tobytes()
        assert x["air_density_kgpm3"][0] == pytest.approx(1.204, abs=5e-4)  # Penner's air


def test_fig4_batch_equals_single_shot_api():
    """The same, through the kernels: the batch kernel on the scenario's inputs gives every
    outcome field of mcrun.api.simulate exactly (Penner 2002 Fig. 4, first bounce 2.82 m at
    35 m/s)."""
    s = sc.load(LIBRARY / "penner-fig4-drives.toml")
    for point, club_speed in zip(s.points, (35.0, 45.0, 55.0), strict=True):
        inputs, _ = sample(s, point, 0, 2)
        out = simulate_batch(inputs)
        single = api.simulate(
            club_speed_mps=club_speed,
            club_mass_kg=0.200,
            loft_deg=13.3,
            turf="green",
            aero_model="penner2002",
            temperature_c=20.0,
            altitude_m=0.0,
            relative_humidity=0.0,
        ).outcome
        for k, name in enumerate(OUTCOME_FIELDS):
            if name not in PLANE_FIELDS:
                continue
            assert out[0, k] == single[name], name
            assert out[1, k] == single[name], name
        if club_speed == 35.0:
            assert single["first_bounce_height_m"] == pytest.approx(2.82, rel=0.01)


def test_fig7_launch_spins_land_with_the_papers_spins():
    """penner-fig7-9iron-backspin.toml: its launch spins land, with penner2002, at the landing
    spins of Penner (2002) Fig. 7, 809 / 1000 / 1200 rad/s (within 0.5 %), at the paper's
    23.8 m/s (within 1 %) and 34.0 deg from the vertical (within 1 deg)."""
    s = sc.load(LIBRARY / "penner-fig7-9iron-backspin.toml")
    field = {name: k for k, name in enumerate(OUTCOME_FIELDS)}
    for point, landing_spin in zip(s.points, (809.0, 1000.0, 1200.0), strict=True):
        out = simulate_batch(sample(s, point, 0, 1)[0])[0]
        assert out[field["landing_spin_radps"]] == pytest.approx(landing_spin, rel=0.005)
        assert out[field["landing_speed_mps"]] == pytest.approx(23.8, rel=0.01)
        assert out[field["landing_angle_deg"]] == pytest.approx(34.0, abs=1.0)
