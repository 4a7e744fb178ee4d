"""Runs on a hole: a scenario's ``[hole]``, the shots' zones, positions and distances, the
summary's zone shares, the aim, and the mistakes a user can make in the table."""

import math
import re
import shutil
import textwrap
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun.cli import main
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import OUTCOME_FIELDS
from mcrun.results import on_hole
from mcrun.run import local, sampling
from mcrun.run import scenario as sc
from mcrun.run.scenario import ScenarioError

LIBRARY = sc.library_folder()
MAPS = Path(__file__).resolve().parent / "data" / "maps"

LAUNCH = """
[launch]
ball_speed = { dist = "normal", mean = "127 mph", sd = "1.1 mph" }
launch_angle = { dist = "normal", mean = "14.1 deg", sd = "1.2 deg" }
spin = { dist = "normal", mean = "6231 rpm", sd = "440 rpm" }
spin_axis = { dist = "normal", mean = "0 deg", sd = "2.5 deg" }
azimuth = { dist = "normal", mean = "0 deg", sd = "1.2 deg" }
"""


def scenario_file(tmp_path, hole, extra=""):
    path = tmp_path / "s.toml"
    path.write_text(textwrap.dedent(hole) + LAUNCH + textwrap.dedent(extra))
    return path


@pytest.fixture(scope="module")
def par3(tmp_path_factory):
    """The library's par 3 over water, 3,000 shots."""
    out = tmp_path_factory.mktemp("par3") / "run"
    result = local.run_scenario("par3-over-water", n=3000, out_dir=out, progress=False)
    return result.shots(), result.summary(), sc.load(LIBRARY / "par3-over-water.toml").hole


def test_wilson_interval():
    """Wilson's score interval at 95 %: 50 of 100 gives 0.5 -/+ 0.0962 (z = 1.96: centre
    0.5, half-width z sqrt(p(1-p)/n + z^2/4n^2) / (1 + z^2/n)); 0 of 100 gives
    [0, z^2 / (n + z^2)] = [0, 3.699 %]."""
    lo, hi = on_hole.wilson(50, 100)
    assert lo == pytest.approx(0.40383, abs=1e-5) and hi == pytest.approx(0.59617, abs=1e-5)
    lo, hi = on_hole.wilson(0, 100)
    assert lo == pytest.approx(0.0, abs=1e-15) and hi == pytest.approx(0.036993, abs=1e-6)


def test_zone_shares_are_the_shots_counts(par3):
    """The summary's share of each zone is the count of shots.parquet's zone column over the
    shots that landed, and its interval is Wilson's of that count."""
    shots, summary, _ = par3
    row = summary.iloc[0]
    landed = shots["landing_zone"].notna().sum()
    assert row["n_landed"] == landed == len(shots)
    for which in ("landing", "finish"):
        counts = shots[f"{which}_zone"].value_counts()
        for zone in on_hole.ZONE_NAMES:
            k = int(counts.get(zone, 0))
            assert row[f"p_{which}_{zone}"] == k / landed, (which, zone)
            lo, hi = on_hole.wilson(k, landed)
            assert row[f"p_{which}_{zone}_lo95"] == lo and row[f"p_{which}_{zone}_hi95"] == hi
    assert 0.5 < row["p_finish_green"] < 0.95  # a tour 6-iron at a 168 m green


def test_the_summary_s_expected_strokes_are_the_shots_as_the_strokes_module_sums_them(par3):
    """The summary's expected strokes, streamed chunk by chunk as the shots are made
    (``on_hole.HoleTally``), against ``strokes.point_strokes`` of the shots read back: each
    outcome's count exactly, the means and parts within 1e-12 (the tally's sums are exact,
    numpy's pairwise ones to rounding)."""
    from mcrun.strokes import OUTCOMES, point_strokes

    shots, summary, _ = par3
    row = summary.iloc[0]
    after = shots["expected_strokes_after"].to_numpy(float)
    outcome = np.where(shots["finish_zone"].isna(), "failed",
                       shots["finish_zone"].astype(object)).astype(object)  # fmt: skip
    outcome[~np.isfinite(after)] = "failed"
    full = point_strokes(
        pd.DataFrame({
            "outcome": outcome,
            "expected_strokes_after": after,
            "strokes_gained": shots["strokes_gained"].to_numpy(float),
            "lie_cost_strokes": np.zeros(len(shots)),
            "expected_strokes_start": shots["strokes_gained"] + 1.0 + after,
        })
    )  # fmt: skip
    assert row["n_scored"] == full["n_scored"]
    for name in ("expected_strokes_after_mean", "expected_strokes_after_se",
                 "strokes_gained_mean", "strokes_gained_se", "expected_strokes_start"):  # fmt: skip
        assert row[name] == pytest.approx(full[name], rel=1e-12, abs=1e-15), name
    for name in OUTCOMES:
        assert row[f"p_outcome_{name}"] == full[f"p_{name}"], name
        part = full[f"expected_strokes_after_part_{name}"]
        assert row[f"expected_strokes_after_part_{name}"] == pytest.approx(part, rel=1e-12), name


def test_the_expected_strokes_from_the_start_do_not_hang_on_the_first_shot(tmp_path):
    """A point whose first shot failed (its values NaN) had an expected_strokes_start of NaN
    in its summary; every scored shot gives the start's value, the first of them now, in
    chunks as in one."""
    text = (LIBRARY / "par3-over-water.toml").read_text()
    text = text.replace('"holes/', f'"{LIBRARY}/holes/').replace(
        'mean = "6231 rpm", sd = "440 rpm"', 'mean = "0 rpm", sd = "3000 rpm"')  # fmt: skip
    (tmp_path / "wet.toml").write_text(text)
    starts = []
    for chunk in (20, 3):
        run = local.run_scenario(tmp_path / "wet.toml", n=20, seed=7, chunk_size=chunk,
                                 out_dir=tmp_path / f"run{chunk}", progress=False)  # fmt: skip
        shots = run.shots()
        assert shots["status_name"].iloc[0] == "invalid_input"  # (a backspin below 0)
        each = (shots["strokes_gained"] + 1.0 + shots["expected_strokes_after"]).dropna()
        assert each.max() - each.min() < 1e-12  # (one start)
        starts.append(run.summary().loc[0, "expected_strokes_start"])
        assert starts[-1] == each.iloc[0]
    assert starts[0] == starts[1]


def test_the_summary_streamed_in_chunks_is_the_summary_of_one(par3, tmp_path):
    """The same run cut into chunks of 700 shots: every count and share of the summary the same,
    the exact means the same to the bit, the standard errors within 1e-12."""
    _, summary, _ = par3
    again = local.run_scenario("par3-over-water", n=3000, out_dir=tmp_path / "run",
                               progress=False, chunk_size=700).summary()  # fmt: skip
    for name in summary.columns:
        if name.endswith("_se"):
            assert again.loc[0, name] == pytest.approx(summary.loc[0, name], rel=1e-12), name
        elif (name.startswith(("p_", "n_", "expected_strokes", "strokes_gained"))
              and not name.startswith(("p50", "p90"))):  # fmt: skip
            assert again.loc[0, name] == summary.loc[0, name], name


def test_shot_columns_on_a_hole(par3):
    """Each shot's zones are the terrain's at its landing and finish; its distance to the pin
    and its lon/lat follow from its finish in the hole's frame; the summary's target is the
    pin, its distance percentiles are the pin distances'."""
    shots, summary, hole = par3
    x, y = shots["final_x_m"].to_numpy(), shots["final_y_m"].to_numpy()
    zones = np.array(on_hole.ZONE_NAMES)[np.where((z := hole.zone_at(x, y)) < 0, 8, z)]
    assert (shots["finish_zone"].astype(str).to_numpy() == zones).all()
    landing = hole.zone_at(shots["carry_m"].to_numpy(), shots["carry_lateral_m"].to_numpy())
    assert (
        shots["landing_zone"].astype(str).to_numpy() == np.array(on_hole.ZONE_NAMES)[landing]
    ).all()
    px, py = hole.pin_xy
    np.testing.assert_array_equal(shots["pin_distance_m"], np.hypot(x - px, y - py))
    lon, lat = hole.frame.to_lonlat(x, y)
    np.testing.assert_array_equal(shots["final_lon_deg"], lon)
    np.testing.assert_array_equal(shots["final_lat_deg"], lat)
    # Back to the frame within a micrometre (the projection's round trip).
    bx, by = hole.frame.to_xy(lon, lat)
    assert np.max(np.hypot(bx - x, by - y)) < 1e-6
    row = summary.iloc[0]
    assert (row["target_x_m"], row["target_y_m"]) == pytest.approx((px, py), abs=1e-9)
    ok = shots["status_name"] == "ok"
    assert row["distance_r50_m"] == pytest.approx(
        np.quantile(shots.loc[ok, "pin_distance_m"], 0.5), abs=0.01
    )
    # Flat ground: every ball ends at the tee's height.
    assert np.abs(shots.loc[ok, "final_z_m"]).max() == 0.0


def test_a_flat_hole_of_one_turf_is_the_plane(tmp_path):
    """A hole without a map, flat and all fairway, gives the plane model's shots with the
    fairway preset: the same carry, bounces and finish within a millimetre."""
    hole = """
    [hole]
    length_m = 170.0
    width_m = 120.0
    surface = "fairway"
    """
    s_hole = sc.load(scenario_file(tmp_path, hole))
    s_plane = sc.loads(LAUNCH + '\n[turf]\npreset = "fairway"\n', tmp_path / "p.toml")
    inputs, _ = sampling.sample(s_hole, s_hole.points[0], 0, 400)
    plane_inputs, _ = sampling.sample(s_plane, s_plane.points[0], 0, 400)
    # The same shots (the turf columns differ: on a hole the zones' turf is used).
    np.testing.assert_array_equal(inputs[:, :5], plane_inputs[:, :5])
    on_hole_out = simulate_batch(inputs, terrain=s_hole.hole.terrain())
    on_plane = simulate_batch(plane_inputs)
    k = {name: i for i, name in enumerate(OUTCOME_FIELDS)}
    for name in ("carry_m", "carry_lateral_m", "final_x_m", "final_y_m", "total_m"):
        assert np.max(np.abs(on_hole_out[:, k[name]] - on_plane[:, k[name]])) < 1e-3, name
    assert (on_hole_out[:, k["bounces"]] == on_plane[:, k["bounces"]]).all()


def test_the_aim_turns_every_shot(tmp_path):
    """``aim`` = [x, y] turns the shots' start line towards it: the mean finish lies on the
    line from the tee through the aim point (within 1 % of the lateral offset), where without
    an aim it is on the line to the pin."""
    hole = """
    [hole]
    length_m = 170.0
    width_m = 120.0
    surface = "fairway"
    aim = [160.0, -12.0]
    """
    shots, _ = local.run_dataframes(scenario_file(tmp_path, hole), n=2000)
    x, y = shots["final_x_m"].mean(), shots["final_y_m"].mean()
    assert y / x == pytest.approx(-12.0 / 160.0, rel=0.05)


RECTANGLE = "[hole]\nlength_m = 150.0\nwidth_m = 60.0\n"
# A course of one hole, 150 m north from (15 E, 45 N), its green round the pin.
ONE_HOLE = """{"type": "FeatureCollection", "features": [
 {"type": "Feature", "properties": {"golf": "hole"}, "geometry": {"type": "LineString",
  "coordinates": [[15.0, 45.0], [15.0, 45.00135]]}},
 {"type": "Feature", "properties": {"golf": "green"}, "geometry": {"type": "Polygon",
  "coordinates": [[[14.9998, 45.0012], [15.0002, 45.0012], [15.0002, 45.0015],
                   [14.9998, 45.0015], [14.9998, 45.0012]]]}}]}"""


@pytest.mark.parametrize(
    "hole, extra, message",
    [
        (
            "[hole]\nlength_m = 150.0\nwidth_m = 60.0\n",
            '[turf]\npreset = "green"\n',
            "turf: on a hole each zone",
        ),
        (
            "[hole]\nlength_m = 150.0\nwidth_m = 60.0\naim = [-5.0, 0.0]\n",
            "",
            "hole.aim: must be [x_m, y_m]",
        ),
        (
            '[hole]\nlength_m = 150.0\nwidth_m = 60.0\naim = "pin"\n',
            "",
            "hole.aim: must be [x_m, y_m]",
        ),
        ('[hole]\nfile = "nowhere.toml"\n', "", "hole.file: cannot read"),
        (RECTANGLE + "bogus = 1\n", "", "unknown key 'bogus'"),
        ('[hole]\nmap = "missing.geojson"\nhole = 1\n', "", "missing.geojson"),
        ('[hole]\nmap = "not-a-map.geojson"\nhole = 1\n', "", "not-a-map.geojson"),
        ('[hole]\nmap = "one-hole.geojson"\nhole = 5\n', "", "hole"),
        ('[hole]\nfile = "course.kml"\n', "", "course.kml: is a KML file (Google Earth), not a"),
        ('[hole]\nmap = "course.kml"\nhole = 1\n', "", "is a KML file (Google Earth), not a"),
        ('[hole]\nmap = "no-green.geojson"\nhole = 1\n', "", "hole 1 has no green"),
    ],
)
def test_bad_hole_tables_give_one_line(tmp_path, capsys, hole, extra, message):
    """Each mistake in ``[hole]`` is one line naming the file and the key, exit 2, and the
    run writes nothing."""
    (tmp_path / "not-a-map.geojson").write_text('{"type": "Feature"}')
    (tmp_path / "one-hole.geojson").write_text(ONE_HOLE)
    (tmp_path / "course.kml").write_text('<?xml version="1.0"?>\n<kml><Document/></kml>\n')
    shutil.copy(MAPS / "no-green.geojson", tmp_path)  # a hole line, tee and fairway, no green
    path = scenario_file(tmp_path, hole, extra)
    with pytest.raises(ScenarioError, match=re.escape(message)):
        sc.load(path)
    out = tmp_path / "run"
    assert main(["run", str(path), "-n", "10", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("mcrun: error:") and message in err
    assert str(path) in err
    assert not out.exists()


def test_every_library_hole_scenario_loads():
    """The library's hole scenarios load, with their holes' pins on a green."""
    for name in ("par3-over-water", "par4-tee-shot", "wedge-two-tier-firm", "wedge-two-tier-soft"):
        s = sc.load(LIBRARY / f"{name}.toml")
        hole = s.hole
        x, y = hole.pin_xy
        assert on_hole.ZONE_NAMES[hole.zone_at(x, y)] == "green", name
        assert math.isfinite(s.aim_rad)


def test_hole_shots_read_in_pandas_as_categories(par3):
    shots, _, _ = par3
    assert isinstance(shots["finish_zone"].dtype, pd.CategoricalDtype)


@pytest.mark.determinism
def test_a_hole_run_on_dask_is_the_local_run(tmp_path):
    """The same run on a local Dask cluster: every shot and the zone shares, bit for bit."""
    pytest.importorskip("distributed")
    from mcrun.results.reader import read_shots
    from mcrun.run import distributed

    local.run_scenario("par3-over-water", n=600, out_dir=tmp_path / "local", progress=False,
                       chunk_size=256)  # fmt: skip
    distributed.run_scenario("par3-over-water", n=600, out_dir=tmp_path / "dask",
                             progress=False, chunk_size=256, workers=2)  # fmt: skip
    a, b = read_shots(tmp_path / "local"), read_shots(tmp_path / "dask")
    key = ["point", "shot"]
    a = a.sort_values(key).reset_index(drop=True).drop(columns="group")
    b = b.sort_values(key).reset_index(drop=True).drop(columns="group")
    for frame in (a, b):
        for name in frame.columns:
            if isinstance(frame[name].dtype, pd.CategoricalDtype):
                frame[name] = frame[name].astype(str)
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    sa = pd.read_parquet(tmp_path / "local" / "summary.parquet")
    sb = pd.read_parquet(tmp_path / "dask" / "summary.parquet")
    zones = [c for c in sa.columns if c.startswith(("p_finish_", "p_landing_", "expected_"))]
    pd.testing.assert_frame_equal(sa[zones], sb[zones], check_exact=True)


def test_a_shot_finishes_in_the_zone_its_status_names(tmp_path):
    """One source of truth for where a shot ended: on real ground (drive-real-ground, whose
    drives run off the survey's grid), every shot that left the map finishes ``off_map``, even
    where the nearest node of where it stopped is the fairway it crossed from (23 of 53 at
    this seed did), and the finish shares are the statuses' shares."""
    result = local.run_scenario(
        LIBRARY / "drive-real-ground.toml", n=3000, seed=1, out_dir=tmp_path / "run",
        progress=False,
    )  # fmt: skip
    shots, summary = result.shots(), result.summary()
    status = shots["status_name"].astype(str)
    finish = shots["finish_zone"].astype(str)
    named = {"off_map": ["off_map"], "out_of_bounds": ["out_of_bounds"],
             "penalty_area": ["water", "water_yellow"]}  # fmt: skip
    assert (status == "off_map").sum() > 20  # the case this checks is there
    for name, zones in named.items():
        assert finish[status == name].isin(zones).all(), name
    # A ball at rest is on the map, so the share that finished off it is the status's.
    assert summary["p_finish_off_map"].iloc[0] == (status == "off_map").sum() / len(shots)


def test_a_yellow_penalty_area_finishes_there_and_has_no_lateral_drop(tmp_path):
    """Par 3 over water aimed at the pond right of the green (a golf=water_hazard: a yellow
    penalty area), and the same with ``penalty_areas = "red"`` in [hole]. The same shots end in
    the pond (the kernel sees two penalty areas alike); they finish in ``water_yellow``, or
    ``water`` (red), with one penalty stroke. Yellow's relief (stroke and distance, or back on
    the line from the pin, behind the crossing) is red's without the lateral drop, so no ball
    scores better in yellow, and most worse."""
    text = (LIBRARY / "par3-over-water.toml").read_text(encoding="utf-8")
    hole_file = (LIBRARY / "holes" / "riverside-2.toml").as_posix()
    aimed = text.replace(
        'file = "holes/riverside-2.toml"', f'file = "{hole_file}"\naim = [155.0, 22.0]'
    )
    red = aimed.replace("aim = [", 'penalty_areas = "red"\naim = [')
    got = {}
    for colour, body in (("yellow", aimed), ("red", red)):
        (tmp_path / f"{colour}.toml").write_text(body, encoding="utf-8")
        result = local.run_scenario(
            tmp_path / f"{colour}.toml", n=1000, seed=3, out_dir=tmp_path / colour, progress=False
        )
        got[colour] = result.shots()
    yellow, red = got["yellow"], got["red"]
    in_area = yellow["status_name"].astype(str) == "penalty_area"
    assert in_area.sum() > 30
    assert (in_area == (red["status_name"].astype(str) == "penalty_area")).all()
    assert (yellow.loc[in_area, "finish_zone"].astype(str) == "water_yellow").all()
    assert (red.loc[in_area, "finish_zone"].astype(str) == "water").all()
    assert (yellow.loc[in_area, "penalty_strokes"] == 1.0).all()
    after_y = yellow.loc[in_area, "expected_strokes_after"].to_numpy()
    after_r = red.loc[in_area, "expected_strokes_after"].to_numpy()
    assert (after_y >= after_r - 1e-12).all()
    # Most cross in from the rough (the lateral drop there is a metre nearer than the line's
    # first point); those from mown grass lose its lie, a third of a stroke or more.
    assert (after_y > after_r).mean() > 0.5
    assert (after_y > after_r + 0.3).sum() >= 5
    # Elsewhere nothing moves.
    np.testing.assert_array_equal(
        yellow.loc[~in_area, "expected_strokes_after"], red.loc[~in_area, "expected_strokes_after"]
    )
