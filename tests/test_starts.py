"""Shots from many start points in one batch (``mcrun.run.starts``): a start point's shots are
those of a scenario group struck from there; the batch's shots are its starts' own, in
start-major order; starts that are not in play are refused in one line. (The same on Dask, bit
for bit: ``tests/test_distributed.py``.)"""

import re
import textwrap

import numpy as np
import pytest

from mcrun.engine.backend import simulate_batch
from mcrun.quantities import InputError
from mcrun.run import local, sampling, starts
from mcrun.run import scenario as sc

N = 40
HOLE = """
[hole]
length_m = 300.0
width_m = 80.0
surface = "fairway"
"""
LAUNCH = """
[launch]
ball_speed = { dist = "normal", mean = "100 mph", sd = "2 mph" }
launch_angle = { dist = "normal", mean = "24 deg", sd = "1.5 deg" }
spin = { dist = "normal", mean = "8000 rpm", sd = "400 rpm" }
azimuth = { dist = "normal", mean = "0 deg", sd = "2 deg" }
"""
STARTS = np.array([[0.0, 0.0], [120.0, 0.0], [150.0, 20.0], [200.0, -30.0], [60.0, 5.5]])


def write(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture(scope="module")
def fairway(tmp_path_factory):
    return sc.load(write(tmp_path_factory.mktemp("starts"), HOLE + LAUNCH))


def test_a_start_point_is_a_group_struck_from_there(fairway, tmp_path):
    """The expected strokes of a start point are those of a run whose [hole] starts there (the
    same sampled shots: the scenario's one point), to rounding (the start line is the sampled
    azimuth plus the bearing to the pin, added in another order)."""
    result = starts.play_from(fairway, STARTS, n=N)
    for k, (x, y) in enumerate(STARTS):
        text = HOLE + f"start = [{x}, {y}]\n" + LAUNCH
        shots, summary = local.run_dataframes(write(tmp_path, text), n=N)
        row = summary.iloc[0]
        assert result.expected_strokes_start[k] == pytest.approx(
            row["expected_strokes_start"], abs=1e-12
        )
        assert result.expected_strokes_after_mean[k] == pytest.approx(
            shots["expected_strokes_after"].mean(), abs=1e-9
        )
        assert result.strokes_gained_se[k] == pytest.approx(row["strokes_gained_se"], rel=1e-6)
        assert result.shares["green"][k] == pytest.approx(
            (shots["finish_zone"] == "green").mean(), abs=1e-12
        )


def test_the_batch_holds_each_starts_own_shots(fairway):
    """With ``keep_shots`` the outcomes are start-major, and the rows of start k are, bit for
    bit, the kernel's on start k's shots alone: starts do not mix in a batch, whatever the
    chunking."""
    result = starts.play_from(fairway, STARTS, n=N, keep_shots=True, chunk_starts=2)
    assert result.outcomes.shape[0] == len(STARTS) * N
    point = fairway.points[0]
    inputs, _ = sampling.sample(fairway, point, 0, N)
    terrain = fairway.hole.terrain()
    for k in range(len(STARTS)):
        alone = simulate_batch(
            starts.tile(inputs, point.play, STARTS[k : k + 1], fairway.hole.pin_xy),
            terrain=terrain,
        )
        assert np.array_equal(result.outcomes[k * N : (k + 1) * N], alone, equal_nan=True)
    again = starts.play_from(fairway, STARTS, n=N, chunk_starts=3)
    assert np.array_equal(again.expected_strokes_after_mean, result.expected_strokes_after_mean)


def test_a_grid_of_starts_is_in_play_and_within_reach():
    hole = sc.load(sc.library_folder() / "par3-over-water.toml").hole
    grid = starts.starts_grid(hole, 3.0, within_m=(40.0, 120.0))
    assert len(grid) > 100 and hole.in_play_at(grid[:, 0], grid[:, 1]).all()
    d = np.hypot(grid[:, 0] - hole.pin_xy[0], grid[:, 1] - hole.pin_xy[1])
    assert d.min() >= 40.0 and d.max() <= 120.0


@pytest.mark.parametrize(
    "points, message",
    [
        ([[0.0, 0.0], [900.0, 0.0]], "starts_xy_m[1]: [900.0, 0.0] is off the hole's map"),
        ([[0.0, np.nan]], "starts_xy_m[0]: [0.0, nan] is not a finite point"),
        ([1.0, 2.0], "starts_xy_m: must be (m, 2) points"),
        # (played from (1, 0), and text read as numbers)
        ([[True, False]], "starts_xy_m: cannot read [[True, False]] as points"),
        ([["30", "-5"]], "starts_xy_m: cannot read [['30', '-5']] as points"),
    ],
)
def test_bad_starts_are_refused_in_one_line(fairway, points, message):
    with pytest.raises(InputError) as err:
        starts.play_from(fairway, points, n=N)
    assert message in str(err.value) and "\n" not in str(err.value)


def test_play_from_and_starts_grid_read_their_arguments_as_given(fairway):
    """Text taken apart letter by letter: aim_xy_m="12" aimed at (1, 2) and within_m="05"
    kept places within 5 m; keep_shots="no" kept them; a library name, progress="yes" or
    baseline="tour" were an AttributeError or a TypeError (after the first chunk)."""
    hole = fairway.hole
    for call, says in (
        (lambda: starts.play_from(fairway, [[50.0, 0.0]], n=N, aim_xy_m="12"), "aim_xy_m '12'"),
        (lambda: starts.starts_grid(hole, 10.0, within_m="05"), "within_m '05'"),
        (lambda: starts.starts_grid(hole, "10"), "spacing_m '10'"),
        (lambda: starts.starts_grid(hole, 10.0, within_m=(np.False_, np.True_)), "within_m"),
        (lambda: starts.play_from(fairway, [[50.0, 0.0]], n=N, keep_shots="no"),
         "keep_shots 'no': allowed: True or False"),
        (lambda: starts.play_from("pga-driver", [[50.0, 0.0]], n=N),
         "scenario 'pga-driver': allowed: a Scenario"),
        (lambda: starts.play_from(fairway, [[50.0, 0.0]], n=N, progress="yes"),
         "progress 'yes': allowed: a function"),
        (lambda: starts.play_from(fairway, [[50.0, 0.0]], n=N, baseline="tour"),
         "baseline 'tour': allowed: a Baseline"),
    ):  # fmt: skip
        with pytest.raises(InputError, match=re.escape(says)):
            call()
