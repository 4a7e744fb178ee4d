"""The whole hole played as a player (``mcrun.play``): first principles (a symmetric hole and
player give a symmetric solution; a penalty area raises the values only where shots can reach
it; the same solution on any number of threads), the Tour bag's calibrated spread against the
Tour's proximity and fairways, and ``mcrun play``."""

import dataclasses
import json
import math
import textwrap

import numpy as np
import pytest

from mcrun.cli import main
from mcrun.engine.schema import COLUMN
from mcrun.executor import Executor
from mcrun.hole.hole import load_hole
from mcrun.play import load_player, play_hole
from mcrun.play.calibration import (
    AMATEUR_TARGETS,
    FAIRWAY_SHARE,
    WOOD_YD,
    calibrate_ground,
    calibrate_rough,
    pattern,
    proximity_target_ft,
    rough_ratio,
)
from mcrun.play.lattice import TABLE_STEP_M, TEE_LIE, lattice, stacked, value_at
from mcrun.play.player import PART_POWERS, TOUR_GROUND, TOUR_ROUGH, TOUR_SPREAD, WOMEN, on_hole
from mcrun.play.solve import solve
from mcrun.play.transitions import WATER, fly, options_of, plan_actions
from mcrun.run import scenario as sc
from mcrun.strokes import tour_baseline

# Two clubs without spread: every shot of a club is the same shot, mirrored by a mirrored aim.
BAG = """
[scenario]
name = "two-clubs"
shots = 2
seed = 1

[weather]
temperature = "20 C"

[[group]]
name = "7-iron"
launch.ball_speed = "120 mph"
launch.launch_angle = "16 deg"
launch.spin = "7000 rpm"

[[group]]
name = "wedge"
launch.ball_speed = "100 mph"
launch.launch_angle = "24 deg"
launch.spin = "9000 rpm"
"""
LAT0, LON0 = 45.0, 15.0
M_LAT = 1.0 / 111_320.0
M_LON = M_LAT / np.cos(np.radians(LAT0))


def _lonlat(x_m, y_m):
    """A point x m north and y m east of (LON0, LAT0): the frame of a hole played north."""
    return [LON0 + y_m * M_LON, LAT0 + x_m * M_LAT]


def _ring(points):
    return [[_lonlat(x, y) for x, y in [*points, points[0]]]]


def symmetric_map():
    """A made-up course (not real data), mirror-symmetric about its hole's line: a 150 m hole
    played north, a fairway 28.4 m wide from 30 to 138 m, a round green of radius 11.3 m about
    the pin, the course boundary 60 m either side."""
    angles = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    green = [(150.0 + 11.3 * np.cos(a), 11.3 * np.sin(a)) for a in angles]
    features = [
        (
            "leisure",
            "golf_course",
            "Polygon",
            _ring([(-30, -60), (-30, 60), (200, 60), (200, -60)]),
        ),
        ("golf", "hole", "LineString", [_lonlat(0, 0), _lonlat(150, 0)]),
        ("golf", "fairway", "Polygon", _ring([(30, -14.2), (30, 14.2), (138, 14.2), (138, -14.2)])),
        ("golf", "green", "Polygon", _ring(green)),
    ]
    return {
        "type": "FeatureCollection",
        "features": [
            {"type": "Feature", "properties": {key: value, **({"ref": "1", "par": "3"}
                                                              if value == "hole" else {})},
             "geometry": {"type": kind, "coordinates": coordinates}}
            for key, value, kind, coordinates in features
        ],
    }  # fmt: skip


HOLE = """
map = "course.geojson"
hole = "1"
margin_m = 25.0
"""


@pytest.fixture(scope="module")
def symmetric(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("play")
    (tmp / "bag.toml").write_text(textwrap.dedent(BAG))
    (tmp / "hole.toml").write_text(textwrap.dedent(HOLE))
    (tmp / "course.geojson").write_text(json.dumps(symmetric_map()))
    player, hole = load_player(tmp / "bag.toml", straight=True), load_hole(tmp / "hole.toml")
    return player, hole, play_hole(player, hole, n=2, coarse_m=10.0, fine_m=5.0, plays=200)


def test_a_symmetric_hole_and_player_give_a_symmetric_solution(symmetric):
    """A course symmetric about its hole's line, straight shots: the value at (x, y) is the
    value at (x, -y) (to rounding), and the tee's best aim is the pin or ties with its
    mirror image."""
    _, _, result = symmetric
    xy, v = result.lattice.xy, result.solution.values
    key = {(round(x, 6), round(y, 6)): k for k, (x, y) in enumerate(xy)}
    pairs = [
        (k, key[(round(x, 6), round(-y, 6))])
        for k, (x, y) in enumerate(xy)
        if k > 0 and (round(x, 6), round(-y, 6)) in key
    ]  # fmt: skip (0: the tee)
    assert len(pairs) > 50
    a, b = np.array(pairs).T
    np.testing.assert_allclose(v[a], v[b], atol=1e-9)
    rows = result.tee_rows()
    best = rows[0]
    if "deg" in best[1]:
        mirror = best[1].replace("left", "RIGHT").replace("right", "left").replace("RIGHT", "right")
        assert any(name == mirror and abs(q - best[2]) < 1e-9 for _, name, q, _ in rows)


def _value_plainly(x, y, lie, values, lat):
    """A point's value as ``lattice.value_at`` defines it, plainly: the grid from hypot, the
    cell's nodes of the point's lie weighed one by one, then the nearest such node within two
    cells, then the table. (NumPy's hypot is the C library's, as Numba's is; Python's own
    may differ in the last bit.)"""
    d = float(np.hypot(x - lat.pin_xy[0], y - lat.pin_xy[1]))
    k = 0
    while k < len(lat.reach_m) - 1 and d > lat.reach_m[k]:
        k += 1
    x0, y0, cell, index = lat.grids[k]
    fx, fy = (x - x0) / cell, (y - y0) / cell
    ix, iy = math.floor(fx), math.floor(fy)
    tx, ty = fx - ix, fy - iy
    ny, nx = index.shape
    total = acc = 0.0
    for dy in range(2):
        for dx in range(2):
            jx, jy = ix + dx, iy + dy
            if 0 <= jx < nx and 0 <= jy < ny and index[jy, jx] >= 0:
                if lat.lie[index[jy, jx]] == lie:
                    w = (tx if dx else 1.0 - tx) * (ty if dy else 1.0 - ty)
                    total += w
                    acc += w * values[index[jy, jx]]
    if total > 1e-12:
        return acc / total
    best, found = 1e300, -1
    for jy in range(iy - 1, iy + 3):
        for jx in range(ix - 1, ix + 3):
            if 0 <= jx < nx and 0 <= jy < ny and index[jy, jx] >= 0:
                r = (jx - fx) ** 2 + (jy - fy) ** 2
                if lat.lie[index[jy, jx]] == lie and r < best:
                    best, found = r, index[jy, jx]
    if found >= 0:
        return values[found]
    f = min(d / TABLE_STEP_M, lat.table.shape[1] - 1.000001)
    j = int(f)
    return lat.table[lie, j] + (f - j) * (lat.table[lie, j + 1] - lat.table[lie, j])


def test_a_point_s_value_is_the_plain_weighing_of_its_nodes_bit_for_bit(symmetric):
    """``value_at`` (the grid picked on the squared distance, a cell's nodes weighed without
    branches, for the sweeps' speed) against the plain definition, at 4,000 points over the
    whole map and beyond it, in every lie a ball can rest in, and on the fine grid's reach:
    the same float, bit for bit."""
    _, _, result = symmetric
    lat, values = result.lattice, result.solution.values
    grids = stacked(lat)
    rng = np.random.default_rng(5)
    x = rng.uniform(lat.xy[:, 0].min() - 20.0, lat.xy[:, 0].max() + 20.0, 3000)
    y = rng.uniform(lat.xy[:, 1].min() - 20.0, lat.xy[:, 1].max() + 20.0, 3000)
    angle = rng.uniform(0.0, 2.0 * math.pi, 1000)  # on the fine grid's reach, to the ulp
    x = np.r_[x, lat.pin_xy[0] + lat.reach_m[0] * np.cos(angle)]
    y = np.r_[y, lat.pin_xy[1] + lat.reach_m[0] * np.sin(angle)]
    lies = np.unique(lat.lie)
    assert len(lies) >= 3
    for k, (px, py) in enumerate(zip(x, y, strict=True)):
        lie = lies[k % len(lies)]
        got = value_at(px, py, lie, values, *grids, lat.pin_xy[0], lat.pin_xy[1], lat.table)
        assert got == _value_plainly(px, py, lie, values, lat), (px, py, lie)


@pytest.mark.determinism
def test_the_solution_is_the_same_on_one_thread_and_on_two(symmetric):
    player, hole, result = symmetric
    one = solve(result.lattice, result.transitions, threads=1)
    np.testing.assert_array_equal(one.values, result.solution.values)
    np.testing.assert_array_equal(one.best_row, result.solution.best_row)


@pytest.mark.determinism
def test_the_transitions_are_the_same_on_one_thread_and_on_two(symmetric):
    """The jobs flown on one thread and as tasks on two (each job's shots put in their rows'
    places as it finishes, in whatever order): the solve's transitions, bit for bit."""
    player, hole, result = symmetric
    scenario = on_hole(player, hole)
    fields = ("row_state", "row_action", "row_start", "kind", "lie", "x", "y", "const")
    for threads in (1, 2):
        again = fly(scenario, result.lattice, result.n, player, chunk_rows=7,
                    baseline=tour_baseline(), executor=Executor(threads=threads))  # fmt: skip
        for name in fields:
            np.testing.assert_array_equal(getattr(again, name), getattr(result.transitions, name))


def test_the_tee_value_is_what_its_plays_average(symmetric):
    """Straight shots: the policy played 200 times averages the tee's value within 0.25
    strokes (the putts are drawn to the table's mean)."""
    _, _, result = symmetric
    assert abs(result.scores.mean() - result.tee_value) < 0.25


def _dry(hole):
    """``hole`` with every penalty area made rough."""
    zones = [("rough" if kind.startswith("water") else kind, p) for kind, p in hole.zones]
    return dataclasses.replace(hole, zones=zones, _terrain=None)


def test_a_penalty_area_raises_the_values_only_where_shots_can_reach_it():
    """Riverside 2, a par 3 over water, for the Tour bag (20 shots an action) with its water
    and with the water made rough: the same shots (common random numbers) from each state.
    Near the green (within 25 m of the pin, beyond the water) no shot reaches the water, and
    the values are the same bit for bit; where shots can end in the water, it costs strokes
    (by more than 0.1 somewhere). (From the tee the Tour player carries it: no cost there.)"""
    scenario = sc.load("par3-over-water")
    player = load_player("pga-tour-bag")
    wet = scenario.hole
    values = {}
    for name, hole in (("wet", wet), ("dry", _dry(wet))):
        base = tour_baseline()
        lat = lattice(hole, base, coarse_m=12.0, fine_m=4.0, fine_within_m=24.0)
        tr = fly(on_hole(player, hole), lat, 20, player, baseline=base)
        values[name] = (lat, solve(lat, tr).values, tr)
    lat, wet_v, tr = values["wet"]
    dry_lat, dry_v, _ = values["dry"]
    dry_at = {(x, y): k for k, (x, y) in enumerate(dry_lat.xy)}
    both = np.array([k for k, (x, y) in enumerate(lat.xy) if k and (x, y) in dry_at])
    other = np.array([dry_at[tuple(lat.xy[k])] for k in both])
    d = np.hypot(lat.xy[both, 0] - wet.pin_xy[0], lat.xy[both, 1] - wet.pin_xy[1])
    near = d < 25.0
    assert near.sum() > 10
    np.testing.assert_array_equal(wet_v[both[near]], dry_v[other[near]])
    # The states some of whose shots ended in the water: the water costs there.
    splashed = np.unique(tr.row_state[np.repeat(np.arange(len(tr.row_state)), tr.n)
                                      [tr.kind == WATER]])  # fmt: skip
    reached = np.isin(both, splashed)
    assert reached.sum() > 5
    assert (wet_v[both[reached]] - dry_v[other[reached]]).max() > 0.1


def test_the_tour_bag_s_spread_meets_the_tour_s_proximity_and_fairways():
    """Each club of the Tour bag at its ``TOUR_SPREAD`` on the calibration's 4,000 shots:
    approach clubs within 1.5 ft of the Tour's proximity at their distance (20 ft at 112.5 yd,
    27.5 ft at 162.5 yd, 50.25 ft at 225 yd, linear between), driver and woods within 3 points
    of the Tour's 60 % of fairways 30 m wide."""
    player = load_player("pga-tour-bag")
    assert player.spread == TOUR_SPREAD
    assert proximity_target_ft(225.0) == 50.25 and proximity_target_ft(137.5) == 23.75
    for club, factor in enumerate(TOUR_SPREAD):
        total, proximity, share, _ = pattern(player.scenario, club, 4000, factor)
        if total < WOOD_YD:
            assert abs(proximity - proximity_target_ft(total)) < 1.5, player.clubs[club]
        else:
            assert abs(share - FAIRWAY_SHARE) < 0.03, player.clubs[club]


@pytest.mark.parametrize("name", ["scratch", "bogey", "scratch-woman", "bogey-woman"])
def test_the_model_amateurs_spread_meets_their_proximity_and_fairways(name):
    """The scratch and bogey presets at their spreads and ball speeds, 4,000 shots a club:
    approach clubs within 4 % of their proximity target (the Tour's line times
    ``AMATEUR_TARGETS``' ratio), woods within 3 points of their fairways. A woman's approach
    clubs meet her man's targets at her distances (``WOMEN``), her woods take his spreads."""
    player = load_player(name)
    man = WOMEN.get(name, name)
    ratio, share = AMATEUR_TARGETS[man]
    for club, factor in enumerate(player.spread):
        wood = pattern(player.scenario, club, 4000, 1.0)[0] >= WOOD_YD
        total, proximity, got, _ = pattern(player.scenario, club, 4000, factor,
                                           player.speed_of(club))  # fmt: skip
        if wood and name in WOMEN:
            assert factor == load_player(man).spread[club], player.clubs[club]
        elif wood:
            assert abs(got - share) < 0.03, player.clubs[club]
        else:
            target = ratio * proximity_target_ft(total)
            assert abs(proximity / target - 1.0) < 0.04, player.clubs[club]


def test_the_tour_bag_off_the_ground_and_from_the_rough_meets_its_targets():
    """The Tour bag's ``TOUR_GROUND`` and ``TOUR_ROUGH``/``PITCH_ROUGH`` on the calibration's
    4,000 shots: the woods off the ground as far (within 0.01 strokes) from Table 9 on the plane
    as the approach clubs are on average; from the rough, the full shots' proximity within
    1.5 ft of the fairway's times the Tour's ratio (GolfTEC's 1.51 from 100-125 yd and 1.45
    from over 200), the pitches' cost over the fairway within 0.01 strokes of Table 9's."""
    player = load_player("tour")
    assert player.ground == TOUR_GROUND and player.rough == TOUR_ROUGH
    assert abs(rough_ratio(112.5) - 30.25 / 20.0) < 1e-12
    assert abs(rough_ratio(300.0) - 72.75 / 50.25) < 1e-12
    ground, rows = calibrate_ground(player, fit=False)
    fitted = [(club, got, target) for club, _, got, target, _ in rows if target is not None]
    assert [club for club, _, _ in fitted] == ["3-wood", "5-wood"]
    for club, got, target in fitted:
        assert abs(got - target) < 0.01, club
    _, _, rows = calibrate_rough(player, fit=False)
    assert len(rows) == len(player.clubs) + len(PART_POWERS)
    checked = 0
    for club, power, _, what, target, got, _ in rows:
        if target is None:
            assert club == "Driver"  # struck from the tee only
            continue
        checked += 1
        tolerance = 1.5 if what == "rough proximity ft" else 0.01
        assert abs(got - target) < tolerance, (club, power)
    assert checked == len(rows) - 1


def test_the_driver_is_struck_from_the_tee_and_a_wood_off_the_ground_at_its_own_spread():
    """The Tour bag on Riverside 9: the driver fits the tee only; the 3-wood is two options,
    one from the tee at its spread and one from every other state at its spread times its
    ``TOUR_GROUND``, its shots wider."""
    player = load_player("tour")
    hole = sc.load("par4-tee-shot").hole
    lat = lattice(hole, tour_baseline(), 16.0, 8.0, 16.0)
    options = options_of(on_hole(player, hole), 64, player)
    driver = [o for o in options if o.club == 0]
    wood = {o.where: o for o in options if o.club == 1}
    assert [o.where for o in driver] == ["tee"] and set(wood) == {"tee", "ground"}
    speed = COLUMN["ball_speed_mps"]  # the ground's deviations TOUR_GROUND[1] times the tee's
    tee_sd, ground_sd = (wood[w].inputs[:, speed].std() for w in ("tee", "ground"))
    assert abs(ground_sd / tee_sd - TOUR_GROUND[1]) < 1e-9
    actions, jobs = plan_actions(hole, lat, options)
    for rows, a, club, *_ in jobs:
        where = next(o.where for o in options if o.club == club
                     and o.total_m == actions[a].total_m)  # fmt: skip
        tee = lat.lie[rows] == TEE_LIE
        if where == "tee":
            assert tee.all()
        elif where == "ground":
            assert not tee.any()
    assert any(club == 0 for _, _, club, *_ in jobs)


def test_mcrun_play_prints_the_solution(symmetric, tmp_path, capsys):
    folder = tmp_path
    # (a player needs a dispersion: mcrun play refuses the straight bag)
    spread = 'launch.azimuth = { dist = "normal", mean = "0 deg", sd = "1 deg" }\nlaunch.spin ='
    (folder / "bag.toml").write_text(textwrap.dedent(BAG).replace("launch.spin =", spread))
    (folder / "hole.toml").write_text(textwrap.dedent(HOLE))
    (folder / "course.geojson").write_text(json.dumps(symmetric_map()))
    out = folder / "play.parquet"
    code = main(["play", str(folder / "bag.toml"), str(folder / "hole.toml"), "-n", "2",
                 "--coarse", "10m", "--fine", "5m", "--plays", "100", "-o", str(out),
                 "--vs", str(folder / "bag.toml"), "--plot", str(folder / "play.png")])  # fmt: skip
    printed = capsys.readouterr().out
    assert code == 0
    assert "expected score from the tee:" in printed and "plays:" in printed
    # the same player again: the same solution, +0.000
    assert "+0.000 against two-clubs" in printed
    assert (folder / "play.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    import pandas as pd

    frame = pd.read_parquet(out)
    assert {"state", "club", "aim", "expected_strokes", "best"} <= set(frame.columns)
    assert frame.groupby("state")["best"].sum().max() == 1
    from mcrun.results import output

    meta = output.read_provenance(out)  # (what its rows depend on, to solve it again)
    assert (meta["n"], meta["coarse_m"], meta["fine_m"], meta["plays"]) == (2, 10.0, 5.0, 100)
    assert meta["versions"]["mcrun"]


def test_the_picture_scores_against_par_or_counts_strokes_where_par_is_not_known(symmetric):
    """The picture's bars: the shares of the plays against par where the hole's par is known,
    and by their strokes where it is not (rather than against the tee value rounded)."""
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from mcrun.play import SCORE_NAMES
    from mcrun.report.play_plot import play_figure

    _, hole, result = symmetric
    for par in (4, None):
        shown = dataclasses.replace(result, hole=dataclasses.replace(hole, par=par))
        fig = play_figure(shown)
        bars = fig.axes[1]
        labels = [t.get_text().replace("\n", " ") for t in bars.get_xticklabels()]
        heights = [p.get_height() for p in bars.patches]
        plt.close(fig)
        assert sum(heights) == pytest.approx(100.0)
        if par:
            assert labels == list(SCORE_NAMES)
        else:
            shares = shown.stroke_shares()
            assert labels == [f"{k} strokes" for k in shares]
            assert heights == pytest.approx([100 * v for v in shares.values()])


@pytest.mark.parametrize(
    "argv, says",
    [
        (["play", "par3-over-water", "scenarios/holes/riverside-2.toml"], "a player is a bag"),
        (["play", "pga-tour-bag", "pga-driver"], "a scenario without a [hole]"),
        (["play", "pga-tour-bag", "par3-over-water", "-n", "1"], "-n '1': allowed"),
    ],
)
def test_mcrun_play_refuses_bad_input_in_one_line(argv, says, capsys, monkeypatch):
    from pathlib import Path

    monkeypatch.chdir(Path(__file__).resolve().parents[1])
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert says in err and len(err.splitlines()) == 1


def oob_map(length_m=360.0):
    """``symmetric_map`` stretched to a par 4 of ``length_m`` with the course's boundary 20 m
    right of the hole's line (out of bounds beyond) and 60 m left of it."""
    course = symmetric_map()
    angles = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    green = [(length_m + 11.3 * np.cos(a), 11.3 * np.sin(a)) for a in angles]
    shapes = {
        "golf_course": _ring([(-30, -60), (-30, 20), (length_m + 50, 20), (length_m + 50, -60)]),
        "hole": [_lonlat(0, 0), _lonlat(length_m, 0)],
        "fairway": _ring(
            [(30, -14.2), (30, 14.2), (length_m - 12, 14.2), (length_m - 12, -14.2)]
        ),  # fmt: skip
        "green": _ring(green),
    }
    for feature in course["features"]:
        value = feature["properties"].get("leisure") or feature["properties"]["golf"]
        feature["geometry"]["coordinates"] = shapes[value]
        if value == "hole":
            feature["properties"]["par"] = "4"
    return course


def test_out_of_bounds_on_the_right_moves_the_tee_shot_left(tmp_path):
    """Broadie's example (Every Shot Counts, 2014; the strokes-gained reference): out of bounds
    along the right of a par 4, the driver's best aim from the tee is left of the line down the
    middle, and the solution saves strokes against the driver aimed down the middle; more for
    a wider pattern (the Tour bag's spread doubled, whose best tee shot is a shorter club)."""
    (tmp_path / "course.geojson").write_text(json.dumps(oob_map()))
    # A map wide enough for the left rough: the boundary 60 m left is out of bounds.
    (tmp_path / "hole.toml").write_text(textwrap.dedent(HOLE).replace("25.0", "70.0"))
    hole = load_hole(tmp_path / "hole.toml")
    saved = {}
    for factor in (1.0, 2.0):
        player = load_player("pga-tour-bag")
        player = dataclasses.replace(player, spread=tuple(factor * v for v in player.spread))
        result = play_hole(player, hole, n=30, coarse_m=12.0, fine_m=6.0, plays=10)
        driver = [name for _, name, _, _ in result.tee_rows() if name.startswith("Driver")]
        assert "left" in driver[0], (factor, driver[0])
        saved[factor] = result.savings()["Driver at the pin"][1]
    assert saved[1.0] > 0.0
    assert saved[2.0] > saved[1.0]


@pytest.mark.parametrize("name, drive_yd, reach_yd", [("scratch", 250.0, 470.0),
                                                      ("bogey", 200.0, 370.0),
                                                      ("scratch-woman", 210.0, 400.0),
                                                      ("bogey-woman", 150.0, 280.0)])  # fmt: skip
def test_the_scratch_and_bogey_presets_follow_the_usga_definitions(name, drive_yd, reach_yd):
    """USGA Course Rating: a scratch man drives 250 yd and reaches 470 yd in two, a bogey man
    200 and 370, a scratch woman 210 and 400, a bogey woman 150 and 280. The presets' drive on
    the level, at their spreads, within 3 yd of it, and drive plus 3-wood at least the reach."""
    player = load_player(name)
    drive = pattern(player.scenario, 0, 4000, player.spread[0], player.speed_of(0))
    wood = pattern(player.scenario, 1, 4000, player.spread[1], player.speed_of(1))
    assert abs(drive[0] - drive_yd) < 3.0
    assert drive[0] + wood[0] >= reach_yd


def test_ten_more_yards_of_driving():
    """``longer``: the Tour player's driver 10 yd longer on the level (within 0.5 yd), every
    other club unchanged."""
    from mcrun.play.calibration import longer

    player = load_player("tour")
    before = pattern(player.scenario, 0, 2000, player.spread[0], player.speed_of(0))[0]
    more = longer(player, 0, 10.0)
    after = pattern(more.scenario, 0, 2000, more.spread[0], more.speed_of(0))[0]
    assert abs(after - before - 10.0) < 0.5
    assert more.speed[1:] == (1.0,) * (len(more.clubs) - 1)


def test_the_player_putts_with_its_own_putter(symmetric, monkeypatch):
    """A preset putts with its own putter (scratch: the scratch putter; bogey: the 15-handicap's,
    the nearest), unless told; on a hole valued by the table (the Tour's putts) any other putter
    values the green by its map; the solve asks for the map of the player's putter."""
    import mcrun.play as play
    from mcrun.putting.on_hole import putting_of

    assert load_player("tour").putter == "tour"
    assert load_player("scratch").putter == "scratch"
    assert load_player("bogey").putter == "15-handicap"
    assert load_player("bogey", putter="tour").putter == "tour"
    player, hole, _ = symmetric
    assert putting_of(hole, "tour") == hole.putting and hole.putting["model"] == "table"
    spec = putting_of(hole, "scratch")
    assert spec["model"] == "physics" and spec["putter"] == "scratch"
    asked = []

    def map_of_hole(hole, progress=None, putter=None):
        asked.append(putter)

    monkeypatch.setattr(play, "map_of_hole", map_of_hole)
    scratch = dataclasses.replace(player, putter="scratch")
    play_hole(scratch, hole, n=2, coarse_m=10.0, fine_m=5.0, plays=20)
    assert asked == ["scratch"]
