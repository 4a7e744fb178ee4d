"""Bad input to ``mcrun play`` (``mcrun.play``) and to the starts API (``mcrun.run.starts``):
each is refused before a shot is flown on the hole, in one line naming the file, the option or
the argument and what is allowed; on the command line with exit code 2 and nothing written.
No test here solves a hole: ``no_solve`` fails any that would start flying."""

import json
import math
import re
import sys
import textwrap
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from mcrun.cli import main
from mcrun.errors import InputError
from mcrun.hole.hole import load_hole
from mcrun.play import PlayerError, PlayResult, load_player, plan_play
from mcrun.run import scenario as sc
from mcrun.run import starts

REPO = Path(__file__).resolve().parents[1]
PAR3 = "scenarios/holes/riverside-2.toml"  # 168 m over water
PAR4 = "scenarios/holes/riverside-9.toml"  # 388 m
GB = 1_000_000_000


@pytest.fixture(autouse=True)
def at_the_repository(monkeypatch):
    monkeypatch.chdir(REPO)


@pytest.fixture(autouse=True)
def no_solve(monkeypatch):
    """Any shot flown on a hole fails the test: every refusal comes before the solve."""

    def fly(*args, **kwargs):
        raise AssertionError("the solve started")

    monkeypatch.setattr("mcrun.play.fly", fly)


@pytest.fixture
def eight_gb(monkeypatch):
    """This machine has 8 GB of memory available, whatever it has."""
    monkeypatch.setattr("mcrun.run.aim.available_memory", lambda: 8 * GB)


def refused(argv, tmp_path, capsys):
    """``mcrun ARGV -o OUT``: exit code 2, one line on stderr and nothing in OUT's folder; the
    line."""
    out = tmp_path / "out"
    out.mkdir()
    code = main([*argv, "-o", str(out / ("play.parquet" if argv[0] == "play" else "run"))])
    captured = capsys.readouterr()
    assert code == 2, captured
    assert captured.err.startswith("mcrun: error: ") and captured.err.count("\n") == 1, captured
    assert "Traceback" not in captured.err
    assert list(out.iterdir()) == []
    return captured.err


def write(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(text))
    return path


# --- 1. size and memory, before the solve --------------------------------------------------------


@pytest.mark.parametrize(
    "options, says",
    [
        (["--plays", "1e12"], "--plays 1,000,000,000,000: the plays of the policy take about "
         "128 TB of memory, and 8.0 GB is available: allowed here: --plays up to about "),
        (["-n", "1e9"], "-n 1,000,000,000: a solve keeps every shot of every action from every "
         "state in memory, an estimated "),
        (["-n", "100001"], "-n 100,001: a solve keeps every shot"),
    ],
)  # fmt: skip
def test_a_solve_that_would_not_fit_in_memory_is_refused_before_it_starts(
    options, says, eight_gb, tmp_path, capsys
):
    err = refused(["play", "tour", PAR3, *options], tmp_path, capsys)
    assert says in err
    if options[0] == "-n":
        most = int(err.split("-n up to about ")[1].replace(",", ""))
        assert 100 < most < 100_001  # the default fits; what was asked does not


def test_a_plan_says_its_shots_time_and_memory():
    """``plan_play``: the rows (states x the actions that fit them), the shots, an estimate of
    the time and memory, and one line saying them; refused in one line naming the argument
    where the memory given would not hold it."""
    from mcrun.play import plan_play

    player, hole = load_player("tour"), load_hole(PAR3)
    plan = plan_play(player, hole, n=4, coarse_m=20.0, fine_m=10.0, plays=100, memory=8 * GB)
    assert plan.rows > plan.states and plan.shots == 4 * plan.rows
    assert 0.0 < plan.seconds < 10.0 and 0 < plan.bytes < GB
    line = plan.line()
    assert f"{plan.shots:,} shots" in line and "of memory" in line and "\n" not in line
    with pytest.raises(PlayerError, match=r"^n 4: a solve keeps .* is available: allowed here: "):
        plan_play(player, hole, n=4, coarse_m=20.0, fine_m=10.0, plays=1, memory=plan.bytes // 2)
    with pytest.raises(PlayerError, match=r"^plays 0: allowed: a whole number of at least 1"):
        plan_play(player, hole, n=4, plays=0)


@pytest.mark.parametrize(
    "options, says",
    [
        (["--workers", "0"], "--workers 0: is for --dask local"),
        (["--workers", "2"], "--workers 2: is for --dask local"),
        (["--dask", "local", "--workers", "0"], "--workers '0': allowed: a whole number of "
         "worker processes from 1 to "),
        (["--dask", "local", "--workers", "1e9"], "--workers '1e9': allowed: a whole number of "
         "worker processes from 1 to "),
        (["--dask", "local", "--workers", "2.5"], "--workers '2.5': allowed"),
        (["--longer", "10"], "--longer 10: give its unit, e.g. 10yd"),  # (10 m, not 10 yd)
    ],
)  # fmt: skip
def test_workers_are_for_dask_local_and_bounded(options, says, eight_gb, tmp_path, capsys):
    err = refused(["play", "tour", PAR3, *options], tmp_path, capsys)
    assert says in err
    if "allowed" in says:  # the bound and why: 4 a core, 300 MB each of the 8 GB
        assert "4 a core" in err and "300 MB" in err and "8.0 GB is available" in err


def test_without_dask_play_on_dask_says_how_to_install_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # import fails as if missing
    err = refused(["play", "tour", PAR3, "--dask", "local"], tmp_path, capsys)
    assert "the Dask backend needs dask.distributed: pip install 'mcrun[dask]'" in err


def test_mcrun_run_bounds_its_workers_too(eight_gb, tmp_path, capsys):
    err = refused(["run", "pga-driver", "-n", "100", "--dask", "local", "--workers", "1e9"],
                  tmp_path, capsys)  # fmt: skip
    assert "--workers '1e9': allowed: a whole number of worker processes from 1 to " in err


# --- 2. the starts API ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def par3():
    return sc.load("par3-over-water")


@pytest.mark.parametrize(
    "call, says",
    [
        (lambda s: starts.starts_grid(s.hole, 0.0), r"^spacing_m 0.0: allowed: a positive"),
        (lambda s: starts.starts_grid(s.hole, -3.0), r"^spacing_m -3.0: allowed: a positive"),
        (lambda s: starts.starts_grid(s.hole, math.nan), r"^spacing_m nan: allowed"),
        (lambda s: starts.starts_grid(s.hole, 1e-4), r"^spacing_m 0.0001: .* at most "
         r"10,000,000: allowed here: a spacing of at least about"),
        (lambda s: starts.starts_grid(s.hole, 3.0, within_m=(200.0, 100.0)),
         r"^within_m \(200.0, 100.0\): allowed: \(min, max\) metres from the pin, 0 <= min <= max"),
        (lambda s: starts.starts_grid(s.hole, 3.0, within_m=50.0), r"^within_m 50.0: allowed"),
        (lambda s: starts.starts_grid(s.hole, 3.0, zones=["grenn"]),
         r"^zones: 'grenn' is not a zone kind; allowed: rough, fairway"),
        (lambda s: starts.play_from(s, "abc"), r"^starts_xy_m: cannot read 'abc' as points"),
        (lambda s: starts.play_from(s, np.zeros((0, 2))), r"^starts_xy_m: no starts"),
        (lambda s: starts.play_from(s, [[50.0, 0.0]], n="x"), r"^n must be an integer >= 2"),
        (lambda s: starts.play_from(s, [[50.0, 0.0]], point="a"), r"^point must be an index"),
        (lambda s: starts.play_from(s, [[50.0, 0.0]], aim_xy_m="ab"),
         r"^aim_xy_m 'ab': allowed: a point"),
        (lambda s: starts.play_from(s, [[50.0, 0.0]], chunk_starts=0),
         r"^chunk_starts must be an integer >= 1"),
    ],
)  # fmt: skip
def test_the_starts_api_refuses_bad_arguments_with_a_value_error(par3, call, says):
    with pytest.raises(ValueError, match=says) as err:
        call(par3)
    assert "\n" not in str(err.value)


# --- 3. a player without dispersion ------------------------------------------------------------

STRAIGHT = """
[scenario]
name = "straight"
shots = 2
seed = 1

[[group]]
name = "7-iron"
launch.ball_speed = "120 mph"
launch.launch_angle = "16 deg"
launch.spin = "7000 rpm"
"""


def test_a_player_without_dispersion_is_refused_at_load(tmp_path, capsys):
    bag = write(tmp_path / "in" / "straight.toml", STRAIGHT)
    err = refused(["play", str(bag), PAR3], tmp_path, capsys)
    assert f"{bag}: club '7-iron': every shot is the same (launch.ball_speed, " in err
    assert "a player needs a dispersion: allowed is a launch with at least one of them" in err
    with pytest.raises(PlayerError, match="a player needs a dispersion"):
        load_player(bag)
    assert load_player(bag, straight=True).clubs == ("7-iron",)  # tests from first principles
    for wrong in (None, 3):  # (a TypeError of the path before)
        with pytest.raises(PlayerError, match=rf"^player {wrong}: allowed: a preset \(tour, "):
            load_player(wrong)


def test_a_player_with_a_sweep_is_refused(tmp_path):
    """A player file with a [sweep] made each swept value a club of its own (the solver chose
    the wind as it chose a club, exit 0): refused, naming the sweep's keys."""
    bag = (Path(__file__).parents[1] / "scenarios" / "pga-tour-bag.toml").read_text()
    path = write(tmp_path / "swept.toml", bag + '\n[sweep]\n"weather.wind_speed" = [0, 5]\n')
    with pytest.raises(PlayerError, match=r"swept\.toml: a \[sweep\] \(weather\.wind_speed\): "
                       r"a player is a bag of clubs"):  # fmt: skip
        load_player(path)


@pytest.mark.parametrize(
    ("names", "says"),
    [
        (
            ["7-iron\u001b[31m", "8-iron"],
            "group[0].name: '7-iron\\x1b[31m': allowed: text without control characters",
        ),  # (where any scenario's file is read)
        (["Iron ", "Iron"], "clubs 'Iron ' and 'Iron' print the same"),
        (["6-Driv\u00e9", "6-Drive\u0301"], "print the same"),  # composed and decomposed
    ],
)
def test_a_player_s_club_names_print_as_themselves(tmp_path, names, says):
    """mcrun play prints the clubs: an escape sequence (or a line break) in a name reached the
    terminal raw, and two names that print the same were two clubs it could not tell apart."""
    head, group = STRAIGHT.split("[[group]]")
    groups = "".join("[[group]]" + group.replace('"7-iron"', json.dumps(n)) for n in names)
    path = write(tmp_path / "names.toml", head + groups)
    with pytest.raises(InputError, match=re.escape(says)):
        load_player(path, straight=True)


def test_a_player_whose_club_cannot_fly_its_shots_is_refused(tmp_path):
    """A club whose spread is far too wide for its mean (spin sd 19,000 rpm: nearly half its
    backspins below 0) left most shots unflown, and ``mcrun play`` printed its value as inf,
    exit 0: the player is refused, naming the club and how many of its first shots cannot be
    flown."""
    bag = (Path(__file__).parents[1] / "scenarios" / "pga-tour-bag.toml").read_text()
    wide = bag.replace('mean = "2686 rpm", sd = "270 rpm"', 'mean = "2686 rpm", sd = "19000 rpm"')
    assert wide != bag
    path = write(tmp_path / "wide.toml", wide)
    says = (
        r"wide\.toml: club 'Driver': \d+ of its first 64 shots at a spread of 1\.654 "
        r"cannot be flown \(a ball speed"
    )
    with pytest.raises(PlayerError, match=says):
        load_player(path)


def test_a_player_s_spread_that_is_not_numbers_is_named_as_given():
    """``load_player(spread=)``: text, a bool or an object is refused, named as given (``"1"``
    was read as its characters, True as a factor of 1); a number or one per club is taken."""
    for wrong, says in (("1", "'1'"), (True, "True"), ([1.0, "x"], "[1.0, 'x']")):
        with pytest.raises(PlayerError, match=rf"spread {re.escape(says)}: allowed: one factor"):
            load_player("tour", spread=wrong)
    assert load_player("tour", spread=1.2).spread == (1.2,) * 12
    assert load_player("tour", spread=np.full(12, 0.9)).spread == (0.9,) * 12


# --- 4. a hole without a green, or its pin off it ----------------------------------------------

LAT0, LON0 = 45.0, 15.0


def _lonlat(x_m, y_m):
    """A point x m north and y m east of (LON0, LAT0)."""
    return [LON0 + y_m / (111_320.0 * math.cos(math.radians(LAT0))), LAT0 + x_m / 111_320.0]


def _ring(points):
    return [[_lonlat(x, y) for x, y in [*points, points[0]]]]


def course(green=True, extra=()):
    """A made-up course (not real data): a 150 m hole played north, a fairway and (or not) a
    green 20 m square about the pin; ``extra``: more (key, value, rectangle (x0, y0, x1, y1) m)
    polygons."""
    boundary = _ring([(-30, -60), (-30, 60), (200, 60), (200, -60)])
    shapes = [
        ("leisure", "golf_course", "Polygon", boundary),
        ("golf", "hole", "LineString", [_lonlat(0, 0), _lonlat(150, 0)]),
        ("golf", "fairway", "Polygon", _ring([(30, -14), (30, 14), (138, 14), (138, -14)])),
    ]
    if green:
        shapes.append(("golf", "green", "Polygon", _ring([(140, -10), (140, 10), (160, 10),
                                                          (160, -10)])))  # fmt: skip
    for key, value, (x0, y0, x1, y1) in extra:
        shapes.append((key, value, "Polygon", _ring([(x0, y0), (x0, y1), (x1, y1), (x1, y0)])))
    return {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {key: value, **({"ref": "1"} if value == "hole" else {})},
         "geometry": {"type": kind, "coordinates": coordinates}}
        for key, value, kind, coordinates in shapes]}  # fmt: skip


@pytest.mark.parametrize(
    "green, pin, says",
    [
        (False, None, "hole 1 has no green: "),
        (True, "pin = [15.0, 45.0005]\n", "of hole 1 is outside every green of "),
    ],
)
def test_a_hole_without_a_green_or_its_pin_off_it_says_so(green, pin, says, tmp_path, capsys):
    """Not "map: unknown key" (the hole file read as a scenario): the hole reader's own line,
    as ``mcrun putt --hole`` says it."""
    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "course.geojson").write_text(json.dumps(course(green)))
    text = 'map = "course.geojson"\nhole = "1"\n' + (pin or "")
    hole = write(tmp_path / "in" / "hole.toml", text)
    err = refused(["play", "tour", str(hole)], tmp_path, capsys)
    assert says in err and "unknown key" not in err
    assert err.startswith(f"mcrun: error: {hole}: ")


WEDGE = """
[scenario]
name = "wedge"

[launch]
ball_speed = "100 mph"
launch_angle = "24 deg"
spin = "8000 rpm"

[hole]
file = "hole.toml"
"""


@pytest.mark.parametrize(
    "extra, says",
    [
        # A bunker mapped over the pin: its putting map held a three-putt everywhere.
        ([("golf", "bunker", (147, -3, 153, 3))], "hole: the pin (149.7, 0.0) m is on bunker on "
         "the hole's grid of 1 m, not on a green (a bunker mapped over it there"),
        # A pond over the tee: every shot scored from a tee in play, 100 % in water, exit 0.
        ([("natural", "water", (-20, -20, 20, 20))], "hole.start: [0.0, 0.0] is in a penalty "
         "area (water) (the default start: give one in play): a shot starts in play"),
    ],
)  # fmt: skip
def test_a_hole_whose_pin_or_tee_is_not_in_play_is_not_run(extra, says, tmp_path, capsys):
    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "course.geojson").write_text(json.dumps(course(extra=extra)))
    write(tmp_path / "in" / "hole.toml", 'map = "course.geojson"\nhole = "1"\ncell_m = 1.0\n')
    scenario = write(tmp_path / "in" / "wedge.toml", WEDGE)
    assert says in refused(["run", str(scenario), "-n", "10"], tmp_path, capsys)


@pytest.mark.parametrize(
    "extra, green, says",
    [
        ([("golf", "bunker", (147, -3, 153, 3))], True, "the pin (149.7, 0.0) m is on bunker on "
         "the hole's grid of 0.25 m, not on a green"),
        # A green of 1 cm, on one node of its grid: a map of no point (NaN, exit 0); of none,
        # it was said to be steeper than its stopping slope everywhere.
        ([("golf", "green", (149.995, -0.005, 150.005, 0.005))], False, "no point of the map's "
         "grid of 3 m is on the green (0.06 m^2): a finer resolution, or a green mapped larger"),
        ([("golf", "green", (149.9995, -0.0005, 150.0005, 0.0005))], False, "the green around "
         "the pin covers no node of its grid of 0.25 m: a green mapped smaller than its cell"),
    ],
)  # fmt: skip
def test_putts_on_a_green_without_its_pin_are_refused(extra, green, says, tmp_path, capsys):
    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "course.geojson").write_text(json.dumps(course(green, extra)))
    hole = write(tmp_path / "in" / "hole.toml", 'map = "course.geojson"\nhole = "1"\n')
    out = tmp_path / "map.parquet"
    code = main(["putt", "--hole", str(hole), "-n", "2", "--resolution", "3m", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and says in err and err.count("\n") == 1 and not out.exists()


def test_a_hole_whose_pin_is_not_on_a_green_is_not_played(tmp_path, capsys):
    hole = write(tmp_path / "in" / "hole.toml", "length_m = 300.0\nwidth_m = 60.0\n")
    err = refused(["play", "tour", str(hole)], tmp_path, capsys)
    assert f"{hole}: the pin (300.0, 0.0) m is on fairway, not on a green: a hole is played" in err


# --- 5. a bag that cannot play the hole --------------------------------------------------------

PUTTER = """
[scenario]
name = "putter-only"

[[group]]
name = "Putter"
launch.ball_speed = { dist = "normal", mean = "4 m/s", sd = "0.1 m/s" }
launch.launch_angle = { dist = "normal", mean = "2 deg", sd = "0.5 deg" }
launch.spin = { dist = "normal", mean = "100 rpm", sd = "10 rpm" }
"""
# A chip of 11 m on the level, 13.6 m the longest of its 64 shots.
CHIPPER = """
[scenario]
name = "chipper-only"

[[group]]
name = "chipper"
launch.ball_speed = { dist = "normal", mean = "8 m/s", sd = "0.3 m/s" }
launch.launch_angle = { dist = "normal", mean = "30 deg", sd = "1 deg" }
launch.spin = { dist = "normal", mean = "2000 rpm", sd = "100 rpm" }
"""


def test_a_bag_of_putters_is_refused_before_the_solve(tmp_path, capsys):
    bag = write(tmp_path / "in" / "putter.toml", PUTTER)
    err = refused(["play", str(bag), PAR3], tmp_path, capsys)
    assert f"{bag}: no club of putter-only flies: every club's mean carry on the level is " in err


def test_a_bag_that_cannot_reach_the_green_in_a_play_s_strokes_is_refused(tmp_path, capsys):
    """Riverside 9's green is 372 m from the tee; 15 strokes (the most a play counts) of 1.5
    times the chipper's longest shot (13.6 m) reach 306 m. Its par 3, 151 m, it can play."""
    bag = write(tmp_path / "in" / "chipper.toml", CHIPPER)
    err = refused(["play", str(bag), PAR4], tmp_path, capsys)
    assert f"{bag}: chipper-only cannot reach the green of {PAR4}: it is 372 m from the tee" in err
    assert "15 strokes (the most a play counts) of 1.5 times that reach" in err
    from mcrun.play import plan_play

    plan = plan_play(load_player(bag), load_hole(PAR3), n=2, coarse_m=30.0, fine_m=15.0)
    assert plan.rows > 0


# --- 6. a hole whose par is not known ----------------------------------------------------------


def test_without_a_par_the_plays_are_counted_in_strokes():
    from mcrun.cli.play import _score_line

    scores = np.array([3, 3, 4, 5])

    def result(par):
        return PlayResult(None, SimpleNamespace(par=par), None, None, None, None, scores, 2, 0,
                          0.0)  # fmt: skip

    line = _score_line(result(None))
    assert line == ("4 plays: 3 strokes 50.0 %, 4 strokes 25.0 %, 5 strokes 25.0 %; mean 3.750 "
                    "(the hole's par is not known)")  # fmt: skip
    assert "par 50.0 %" in _score_line(result(3)) and "bogey 25.0 %" in _score_line(result(3))


def test_a_gap_between_the_plays_and_the_solve_beyond_chance_is_noted():
    """``mcrun play bogey riverside-8 --coarse 40m``: an expected score of 6.868 +- 0.114 from
    the tee where its plays scored 9.050, without a word. A gap is noted beyond 4 standard
    errors of the two together and 0.1 strokes."""
    scores = np.array([4.0, 5.0] * 200)  # mean 4.5, se 0.5 / sqrt(400) x 1.0013 = 0.025

    def result(tee_value, tee_se):
        solution = SimpleNamespace(values=[tee_value], q_se=[tee_se], best_row=[0])
        return PlayResult(None, None, None, None, solution, None, scores, 2, 0, 0.0)

    gap, se = result(4.0, 0.1).plays_gap()
    assert gap == 0.5 and se == pytest.approx(math.hypot(0.1, 0.5 / math.sqrt(399)), rel=1e-12)
    note = result(4.0, 0.1).gap_note()
    assert note.startswith("the plays' mean is +0.500 strokes from the expected score from the "
                           "tee (+- 0.103)")  # fmt: skip
    assert result(4.1, 0.1).gap_note() is None  # 0.4 < 4 x 0.103
    assert result(4.45, 0.001).gap_note() is None  # 0.05 < 4 x 0.025
    assert result(4.41, 0.001).gap_note() is None  # 0.09 < 0.1 stroke
    assert result(4.38, 0.001).gap_note() is not None  # 0.12


def test_a_spread_is_held_to_a_player_s_and_checked_as_played():
    """A spread of 1e-9 was a player without dispersion in all but name (75 % birdies); one of
    10 left 9 of the driver's first 64 shots unflown, which the solve dropped without a word:
    the dispersion's checks ran on the file's own spread."""
    with pytest.raises(PlayerError, match=r"spread 1e-09: allowed: one factor in \[0.1, 10\]"):
        load_player("pga-tour-bag", spread=1e-9)
    with pytest.raises(PlayerError, match=r"club 'Driver': 9 of its first 64 shots at a spread "
                       r"of 10 cannot be flown"):  # fmt: skip
        load_player("pga-tour-bag", spread=10)
    with pytest.raises(PlayerError, match=r"^putter \['tour'\]: allowed: tour, "):
        load_player("pga-tour-bag", putter=["tour"])  # (a TypeError: unhashable)


@pytest.mark.parametrize(
    ("change", "says"),
    [
        ({"ground": (math.nan,) * 12}, r"ground \(nan, nan, .*\): allowed: 12 factors in "
                                       r"\[0.1, 10\], one per club \(or none\)$"),
        ({"spread": (1.0,) * 3}, r"spread \(1.0, 1.0, 1.0\): allowed: 12 factors in \[0.1, 10\], "
                                 r"one per club$"),
        ({"speed": (1.0,) * 11}, r"speed \(1.0, .*\): allowed: 12 factors"),
        ({"clubs": ()}, r"clubs \(\): allowed: a tuple of names$"),
        ({"putter": "scratchy"}, r"putter 'scratchy': allowed: tour, scratch, 15-handicap$"),
    ],
)  # fmt: skip
def test_a_bag_built_by_hand_is_checked_where_it_is_made(change, says):
    """A Player replaced with a NaN ground factor, or a tuple of another length, was an
    IndexError (or NaN strokes) deep in the solve."""
    import dataclasses

    tour = load_player("tour")
    with pytest.raises(PlayerError, match=r"^player 'tour' \(.*pga-tour-bag.toml\): " + says):
        dataclasses.replace(tour, **change)


def test_a_solve_s_seed_and_lattice_are_checked(tmp_path, capsys):
    """plan_play's seed was int()-ed (1.7 ran as 1, True as 1, 2**70 solved, text a ValueError);
    --fine coarser than --coarse made "near the pin" the coarser part, without a word."""
    player, hole = load_player("tour"), load_hole(PAR3)
    for seed, says in ((1.7, "seed must be an integer >= 0, got 1.7"), (True, "got True"),
                       (2**70, "seed must be an integer up to 2**63 - 1")):  # fmt: skip
        with pytest.raises(InputError, match=re.escape(says)):
            plan_play(player, hole, n=4, seed=seed, plays=10, coarse_m=40.0, fine_m=20.0)
    # A spacing as text was read ("20" as 20 m), a memory of True as 1 byte, straight="no" true.
    for given, says in (
        ({"coarse_m": "20"}, "coarse_m '20': allowed: a number of metres"),
        ({"memory": True}, "memory True: allowed: the bytes available"),
    ):
        with pytest.raises(InputError, match=re.escape(says)):
            plan_play(player, hole, n=4, plays=10, **{"coarse_m": 40.0, "fine_m": 20.0, **given})
    with pytest.raises(InputError, match=re.escape("straight 'no': allowed: True or False")):
        load_player("tour", straight="no")
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    err = refused(["play", "tour", str(PAR3), "--coarse", "8m", "--fine", "40m"],
                  tmp_path / "a", capsys)  # fmt: skip
    assert "--fine 40 m: allowed: at most --coarse (8 m)" in err
    err = refused(["play", "tour", str(PAR3), "--vs", "nobody"], tmp_path / "b", capsys)
    assert err.startswith("mcrun: error: --vs: nobody: no such file")
    # a mistyped preset was told of files and scenarios alone
    (tmp_path / "c").mkdir()
    err = refused(["play", "bogy", str(PAR3)], tmp_path / "c", capsys)
    assert err == (
        "mcrun: error: bogy: no such file, nor a scenario of the library (mcrun "
        "scenarios lists it); a player is a preset (tour, scratch, bogey, "
        "scratch-woman, bogey-woman), a player file or a library scenario's name\n"
    )


def test_play_s_help_names_every_preset(capsys):
    """The presets are named in ``play --help`` (written out there: the CLI does not import the
    players' module to build its parser) and in a mistyped player's message: all of them."""
    from mcrun.play.player import PLAYERS

    assert main(["play", "--help"]) == 0
    said = " ".join(capsys.readouterr().out.split()).replace("- ", "-")  # (argparse wraps at -)
    assert said.count(f"({', '.join(PLAYERS)})") == 1  # PLAYER's help
    assert f"a preset: {', '.join(PLAYERS)};" in said  # the description
