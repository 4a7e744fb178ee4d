"""The aim search (``mcrun aim``, ``mcrun.run.aim``) from first principles: a symmetric hole is
aimed on its axis, water left of the pin moves the aim right and more so for a wider pattern, a
penalty-free fairway is aimed where the shots finish nearest the pin, the common random
numbers make the differences between aims far more precise than the values, and a green's map
of uphill putts cheaper than downhill ones moves a wedge's aim towards below the pin."""

import json
import math
import re
import textwrap

import numpy as np
import pandas as pd
import pytest

from mcrun.cli import main
from mcrun.run import aim, local
from mcrun.run import scenario as sc

# A 7-iron of a tour player (TrackMan 2019 averages), with its spin axis and start line given
# by each test.
SEVEN_IRON = """
ball_speed = {{ dist = "normal", mean = "120 mph", sd = "1.0 mph" }}
launch_angle = {{ dist = "normal", mean = "16.3 deg", sd = "1.0 deg" }}
spin = {{ dist = "normal", mean = "7097 rpm", sd = "400 rpm" }}
spin_axis = {{ dist = "normal", mean = "{axis} deg", sd = "{axis_sd} deg" }}
azimuth = {{ dist = "normal", mean = "0 deg", sd = "{azimuth_sd} deg" }}
"""

LAT0, LON0 = 45.0, 15.0
M_PER_DEG_LAT = 111_132.0
M_PER_DEG_LON = 111_320.0 * math.cos(math.radians(LAT0))


def lonlat(x_m, y_m):
    """A point x_m north (the hole runs north from the tee) and y_m east (to the right)."""
    return [LON0 + y_m / M_PER_DEG_LON, LAT0 + x_m / M_PER_DEG_LAT]


def ring(x0, x1, y0, y1):
    return [[lonlat(x0, y0), lonlat(x0, y1), lonlat(x1, y1), lonlat(x1, y0), lonlat(x0, y0)]]


def course(path, water=True):
    """A 150 m par 3 running north: fairway to a 30 m round green (a square here) with its pin
    at 150 m, water from 2 to 40 m left of the pin's line over the green's length."""
    features = [
        ({"leisure": "golf_course"}, "Polygon", ring(-20, 260, -120, 120)),
        ({"golf": "hole", "ref": "1", "par": "3"}, "LineString", [lonlat(0, 0), lonlat(150, 0)]),
        ({"golf": "fairway"}, "Polygon", ring(20, 200, -40, 40)),
        ({"golf": "green"}, "Polygon", ring(135, 165, -15, 15)),
        ({"golf": "pin"}, "Point", lonlat(150, 0)),
    ]
    if water:
        features.append(({"golf": "water_hazard"}, "Polygon", ring(120, 180, -40, -2)))
    path.write_text(
        json.dumps(
            {
                "type": "FeatureCollection",
                "features": [
                    {"type": "Feature", "properties": p, "geometry": {"type": t, "coordinates": c}}
                    for p, t, c in features
                ],
            }
        )
    )
    return path


def scenario(tmp_path, hole, groups):
    """A scenario on ``hole`` with one group per (name, axis, axis_sd, azimuth_sd)."""
    text = "[scenario]\nseed = 7\n\n" + textwrap.dedent(hole) + "\n"
    for name, axis, axis_sd, azimuth_sd in groups:
        launch = SEVEN_IRON.format(axis=axis, axis_sd=axis_sd, azimuth_sd=azimuth_sd)
        text += f'[[group]]\nname = "{name}"\n' + "".join(
            f"launch.{line}\n" for line in launch.strip().splitlines()
        )
    path = tmp_path / "aim.toml"
    path.write_text(text)
    return sc.load(path)


FLAT = """
[hole]
length_m = 150.0
width_m = 120.0
surface = "fairway"
"""


def test_a_symmetric_hole_is_aimed_on_its_axis(tmp_path):
    """One turf everywhere, a pattern without bias: the best aim is the line to the pin (within
    the search's 1 m resolution), and the aims either side cost the same to 3 SE."""
    s = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)])
    result = aim.search(s, n=4000, half_width_m=12.0, coarse_m=4.0)
    club = result.clubs[0]
    assert abs(club.offsets_m[club.best]) <= 1.0
    e = dict(zip(club.offsets_m, club.expected, strict=True))
    se = dict(zip(club.offsets_m, club.difference_se, strict=True))
    # (The same swing mirrored is not the same shot, so the two sides agree statistically.)
    assert abs(e[8.0] - e[-8.0]) < 3 * math.hypot(se[8.0], se[-8.0])


def test_a_draw_is_aimed_right_where_it_finishes_on_the_line(tmp_path):
    """A penalty-free fairway and a draw (spin axis -4 deg curves the ball left): the best aim
    is right of the pin by about the pattern's mean drift, where the shots finish nearest the
    pin (within 1.5 m)."""
    s = scenario(tmp_path, FLAT, [("7-iron", -4.0, 2.0, 1.0)])
    shots, _ = local.run_dataframes(s, n=4000)
    drift = shots["final_y_m"].mean()
    assert drift < -3.0  # a draw
    result = aim.search(s, n=4000, half_width_m=15.0, coarse_m=5.0, centre_m=0.0)
    club = result.clubs[0]
    assert club.offsets_m[club.best] == pytest.approx(-drift, abs=1.5)


def test_water_left_moves_the_aim_right_and_more_for_a_wider_pattern(tmp_path):
    """Water from 2 m left of the pin: the best aim is right of the pin, and further right for
    a pattern three times as wide; aiming there saves strokes against the pin, by more than
    3 SE of the paired difference."""
    hole = f"""
    [hole]
    map = "{course(tmp_path / "course.geojson").name}"
    hole = "1"
    cell_m = 0.5
    margin_m = 60.0
    """
    s = scenario(tmp_path, hole, [("narrow", 0.0, 1.0, 0.5), ("wide", 0.0, 3.0, 1.5)])
    result = aim.search(s, n=3000, half_width_m=15.0, coarse_m=3.0, centre_m=0.0)
    narrow, wide = result.clubs
    best_narrow = narrow.offsets_m[narrow.best]
    best_wide = wide.offsets_m[wide.best]
    assert 0.0 < best_narrow < best_wide
    k = wide.best
    assert wide.difference[k] < -3 * wide.difference_se[k]


def test_common_random_numbers_make_differences_precise(tmp_path):
    """Neighbouring aims 1 m apart: the paired difference's standard error is under a quarter
    of what independent samples of each aim would give (sqrt(2) times a value's)."""
    s = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)])
    result = aim.search(s, n=3000, offsets_m=[0.0, 1.0])
    club = result.clubs[0]
    k = club.offsets_m.index(1.0)
    assert club.difference_se[k] < 0.25 * math.sqrt(2.0) * club.expected_se[k]


def test_the_command_line_writes_every_aim(tmp_path, capsys):
    s_path = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)]).path
    out = tmp_path / "aims.parquet"
    code = main(["aim", str(s_path), "-n", "1000", "--offsets", "-2,0,2", "-o", str(out)])
    stdout = capsys.readouterr().out
    assert code == 0
    assert "best: 7-iron aimed" in stdout and f"wrote {out}" in stdout
    table = pd.read_parquet(out)
    assert sorted(table["aim_offset_m"]) == [-2.0, 0.0, 2.0]
    at_pin = table[table["aim_offset_m"] == 0.0].iloc[0]
    assert at_pin["difference_strokes"] == 0.0
    np.testing.assert_allclose(
        table["strokes_gained"],
        table["expected_strokes_after"].rsub(at_pin["expected_strokes_after"])
        + at_pin["strokes_gained"],
        rtol=0,
        atol=1e-12,
    )


@pytest.mark.parametrize(
    "argv, message",
    [
        (["pga-driver"], "an aim search needs a hole"),
        (["par3-over-water", "--offsets", "a,b"], "--offsets: cannot read 'a' as a length"),
        (["par3-over-water", "-n", "0"], "-n must be an integer >= 2"),
        (["par3-over-water", "-o", "x.csv"], "must be a .parquet file"),
    ],
)
def test_bad_aim_commands_give_one_line(capsys, argv, message):
    assert main(["aim", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and message in err


# --- refused before anything is flown -------------------------------------------------------------


@pytest.mark.parametrize(
    "argv, message",
    [
        # one shot has no standard error ("All-NaN slice" once)
        (["-n", "1"], "-n must be an integer >= 2"),
        (["--centre", "nan"], "--centre nan: must be a finite number of metres"),
        (["--centre", "inf"], "--centre inf: must be a finite number of metres"),
        (["--half-width", "-5"], "--half-width -5: must be a finite number of metres > 0"),
        (["--step", "0"], "--step 0: must be a finite number of metres > 0"),
        # a 196 TiB allocation once: the plan's memory against what there is
        (["-n", "1e12"], "-n 1,000,000,000,000: an aim search keeps every aim's score"),
        # 4 x 10^8 aims, which hung building them
        (["--half-width", "1e9"], "--half-width 1e+09 with --step 5: 400,000,001 aims per club"),
        # (said "801 aims per club; at most 801": counted unrounded, printed rounded)
        (["--half-width", "2001"], "--half-width 2001 with --step 5: 803 aims per club; at most"),
        (["--resolution", "1e-9"], "--resolution 1e-09: the finest spacing must be"),
        (["--resolution", "10"], "--resolution 10: the finest spacing must be at most"),
        # the NaN was dropped silently
        (["--offsets", "nan,1"], "--offsets nan,1: every aim must be a finite number"),
        (["--offsets", "1,,2"], "--offsets 1,,2: every aim must be a finite number"),
        # the step was ignored beside the aims given
        (["--offsets", "0", "--step", "2"], "--step: is for the search; --offsets gives the"),
    ],
)
def test_bad_aim_options_name_the_option_and_write_nothing(
    tmp_path, capsys, monkeypatch, argv, message
):
    """Each bad value is one line naming the option and what is allowed, exit code 2, before
    any shot is flown (the search is never called) and with nothing written."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(aim, "search", lambda *a, **k: pytest.fail("the search ran"))
    out = tmp_path / "a.parquet"
    code = main(["aim", "par3-over-water", *argv, "-o", str(out)])
    captured = capsys.readouterr()
    assert code == 2, captured
    assert captured.out == ""
    assert captured.err.count("\n") == 1 and captured.err.startswith("mcrun: error: "), captured
    assert message in captured.err
    assert list(tmp_path.iterdir()) == []


def test_memory_is_checked_against_what_there_is(tmp_path):
    """The plan's memory is every aim's score of every shot and one club's shots: a search that
    fits is planned, one that does not is refused naming N."""
    s = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)])
    planned = aim.check(s, n=1000, offsets_m=[0.0, 1.0], memory=10**9)
    assert planned.aims == 3 and planned.bytes == aim.memory_bytes(1, 1000, 3)
    assert "1 club x up to 3 aims x 1,000 shots" in planned.line()
    with pytest.raises(aim.AimError, match=r"^n 1,000: .* lower n$"):
        aim.check(s, n=1000, offsets_m=[0.0, 1.0], memory=planned.bytes)


def test_the_api_s_offsets_are_a_list_of_numbers(tmp_path):
    """offsets_m="12" flew aims at 1 and 2 m (its characters), [True] at 1 m, a generator was
    used up by its message ("give at least one aim"), a numpy scalar was a TypeError."""
    s = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)])
    for given in ("12", {1: 2}, np.float64(3.0), (o for o in [1.0, 2.0])):
        with pytest.raises(aim.AimError, match=r"^offsets_m .*: allowed: a list of aims, m right"):
            aim.check(s, n=10, offsets_m=given)
    with pytest.raises(aim.AimError, match=r"^offsets_m True: every aim must be a finite number"):
        aim.check(s, n=10, offsets_m=[True])
    assert aim.check(s, n=10, offsets_m=np.array([1.0, -2.0])).offsets_m == [1.0, -2.0]
    assert aim.check(s, n=10, offsets_m=["3", "4.5"]).offsets_m == [3.0, 4.5]  # (as --offsets)


@pytest.mark.parametrize("option", ["-o", "--plot"])
def test_outputs_are_checked_before_the_search(tmp_path, capsys, monkeypatch, option):
    """An output in a folder that cannot be made, or one that exists without --force, is one
    line before any shot is flown (it failed after the whole search once)."""
    pytest.importorskip("matplotlib")
    monkeypatch.setattr(aim, "search", lambda *a, **k: pytest.fail("the search ran"))
    suffix = ".parquet" if option == "-o" else ".png"
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    code = main(["aim", "par3-over-water", option, str(blocker / f"a{suffix}")])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and f"{option} {blocker}" in err, err
    assert "is not a folder" in err
    there = tmp_path / f"there{suffix}"
    there.write_bytes(b"")
    code = main(["aim", "par3-over-water", option, str(there)])
    err = capsys.readouterr().err
    assert code == 2 and "already exists: use --force" in err, err


def test_outputs_in_a_missing_folder_are_written_there(tmp_path, capsys):
    """A missing folder of -o and --plot is made, as a run's is."""
    pytest.importorskip("matplotlib")
    s_path = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)]).path
    table = tmp_path / "missing" / "a.parquet"
    picture = tmp_path / "other" / "a.png"
    argv = ["aim", str(s_path), "-n", "200", "--offsets", "0,2", "-o", str(table)]
    assert main([*argv, "--plot", str(picture)]) == 0, capsys.readouterr().err
    assert len(pd.read_parquet(table)) == 2
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_aims_all_off_the_map_are_refused(tmp_path, capsys, monkeypatch):
    """--centre 1e6 once reported a best aim of +999980 m, and --offsets 1e9 a table beside
    the reference aim: every shot of those aims left the map, so there is no best aim to say.
    Refused before a shot is flown: one line, exit code 2, nothing written."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(aim, "search", lambda *a, **k: pytest.fail("the search ran"))
    out = tmp_path / "a.parquet"
    for option, value in (("--centre", "1e6"), ("--offsets", "1e9,-2e9")):
        code = main(["aim", "par3-over-water", "-n", "50", option, value, "-o", str(out)])
        captured = capsys.readouterr()
        assert code == 2 and captured.out == ""
        shown = {"1e6": "1e+06", "1e9,-2e9": "1e+09,-2e+09"}[value]
        assert captured.err.splitlines()[-1].startswith(
            f"mcrun: error: {option} {shown}: every aim is off the hole's map, which spans "
        )
        assert "m right of the line from the tee to the pin: aim where the map is" in captured.err
    assert list(tmp_path.iterdir()) == []


def test_a_best_aim_with_shots_off_the_map_is_warned(tmp_path, capsys):
    """A best aim some of whose shots left the map (scored as out of bounds, where the ground
    is not known) is said on stderr, with the share; none when every shot stayed on it."""
    s = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)])  # a map 120 m wide
    code = main(["aim", str(s.path), "-n", "300", "--centre", "60", "--offsets", "60"])
    err = capsys.readouterr().err
    assert code == 0
    warning = [line for line in err.splitlines() if "warning" in line]
    assert len(warning) == 1 and "7-iron aimed +60.0 m:" in warning[0], err
    assert "% of its shots left the hole's map" in warning[0]
    result = aim.search(s, n=300, centre_m=60.0, offsets_m=[60.0])
    club = result.clubs[0]
    share = club.off_map_share(club.best)
    assert 0.0 < share < 1.0 and f"{100 * share:.1f} %" in warning[0]
    code = main(["aim", str(s.path), "-n", "300", "--offsets", "0"])
    assert code == 0 and "warning" not in capsys.readouterr().err


def test_a_best_aim_at_the_edge_of_the_aims_flown_is_searched_past_it(capsys):
    """par3-over-water from --centre 30 m (aims 10-50 m): its best was +2.0 m, the region's
    edge refined towards the pin until the step met the resolution, its expected strokes still
    falling there (1.897, where +0.0 m leaves 1.864). The search goes on past an edge at its
    step, and says where it stopped at one."""
    par3 = sc.load(sc.library_folder() / "par3-over-water.toml")
    club = aim.search(par3, n=500, centre_m=30.0).clubs[0]
    order = np.argsort(club.offsets_m)
    k = int(np.flatnonzero(order == club.best)[0])
    expected = np.asarray(club.expected)[order]
    assert 0 < k < len(order) - 1 and not club.at_edge  # (flown on both sides of it)
    assert expected[k - 1] > expected[k] < expected[k + 1]
    assert abs(club.offsets_m[club.best]) <= 1.0
    # A region too narrow and far for WALK_ROUNDS to reach the best: said.
    argv = ["aim", "par3-over-water", "-n", "300", "--centre", "35", "--half-width", "3",
            "--step", "1", "--resolution", "1"]  # fmt: skip
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "mcrun: warning: shot: its best aim, +20.0 m, is the last flown on its side" in err


def test_the_coarse_aims_are_centred_and_counted_as_flown():
    """From the region's left edge, a half width that is no whole number of steps left its
    right unflown (7 m at 5 m steps: -7, -2, 3)."""
    assert aim.coarse_offsets(7.0, 5.0) == [-7.0, -5.0, 0.0, 5.0, 7.0]
    assert aim.coarse_offsets(20.0, 5.0) == [-20.0, -15.0, -10.0, -5.0, 0.0, 5.0, 10.0, 15.0, 20.0]
    assert aim.coarse_count(7.0, 5.0) == 5 and aim.coarse_count(2000.0, 5.0) == aim.MAX_AIMS


def test_each_club_is_searched_about_its_own_aim_and_from_its_start(tmp_path, capsys):
    """A second group aimed 40 m left was searched about the first's aim, and compared with
    it; aims on the map about the line from a start off the tee were refused as off it (their
    offsets read about the tee's line); a --centre was called "the scenario's aim"."""
    library = sc.library_folder()
    launch = textwrap.dedent("""
        [launch]
        ball_speed = { dist = "normal", mean = "127 mph", sd = "1.1 mph" }
        launch_angle = { dist = "normal", mean = "14.1 deg", sd = "1.2 deg" }
        spin = { dist = "normal", mean = "6231 rpm", sd = "440 rpm" }
        azimuth = { dist = "normal", mean = "0 deg", sd = "1.2 deg" }
    """)  # fmt: skip
    (tmp_path / "two.toml").write_text(
        f'[scenario]\nseed = 1\n[hole]\nfile = "{library}/holes/riverside-2.toml"\n{launch}'
        '[[group]]\nname = "pin"\n[[group]]\nname = "left"\nhole.aim = [168.0, -40.0]\n'
    )  # fmt: skip
    result = aim.search(sc.load(tmp_path / "two.toml"), n=50)
    left = result.clubs[1]
    assert left.reference_m == pytest.approx(-40.0, abs=0.5)  # (168.4 m away: its own aim)
    assert min(left.offsets_m) < -55.0 and result.clubs[0].reference_m == 0.0
    assert main(["aim", str(tmp_path / "two.toml"), "-n", "50"]) == 0
    assert "differences are to each club's own aim (the scenario's)" in capsys.readouterr().out
    assert main(["aim", "par3-over-water", "-n", "50", "--offsets", "0,5", "--centre", "3"]) == 0
    in_metres = capsys.readouterr().out
    assert "differences are to --centre (+3.0 m)" in in_metres
    # the same lengths with their units (refused: "must be a finite number of metres")
    assert main(["aim", "par3-over-water", "-n", "50", "--offsets", "0 yd, 500cm", "--centre",
                 "300 cm"]) == 0  # fmt: skip
    assert capsys.readouterr().out == in_metres
    # a refusal, in metres, says what each length named was given as
    assert main(["aim", "par3-over-water", "-n", "50", "--centre", "2000yd"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcrun: error: --centre 1828.8: every aim is off the hole's map"), err
    assert err.endswith("(--centre 2000yd is 1828.8 m)\n"), err
    assert main(["aim", "par3-over-water", "--step", "2yd", "--resolution", "3yd"]) == 2
    assert capsys.readouterr().err.endswith(
        "(--step 2yd is 1.8288 m; --resolution 3yd is 2.7432 m)\n"
    )
    wedge = launch.replace("127 mph", "60 mph").replace("14.1 deg", "30 deg")
    (tmp_path / "start.toml").write_text(
        f'[scenario]\nseed = 1\n[hole]\nfile = "{library}/holes/riverside-9.toml"\n'
        f"start = [350.0, 40.0]\n{wedge.replace('6231 rpm', '7000 rpm')}"
    )  # fmt: skip
    start = sc.load(tmp_path / "start.toml")
    flown = aim.search(start, n=20, offsets_m=[-95.0, 70.0]).clubs[0]
    assert flown.off_map[-95.0] < 20 and flown.off_map[70.0] < 20  # (on the map, both)
    with pytest.raises(aim.AimError, match="every aim is off the hole's map, about the line "
                       "from the start to the pin"):  # fmt: skip
        aim.search(start, n=20, offsets_m=[-400.0, 400.0])


# --- pictures and tables, all or nothing ----------------------------------------------------------


def test_ctrl_c_while_drawing_leaves_no_picture_and_no_table(tmp_path, capsys, monkeypatch):
    """Ctrl-C while the picture is saved once left a 0-byte aim.png under its final name,
    which then blocked a rerun: now nothing is left, and the rerun writes both."""
    pytest.importorskip("matplotlib")
    from mcrun.report import style

    s_path = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)]).path
    folder = tmp_path / "out"
    folder.mkdir()
    table, picture = folder / "a.parquet", folder / "aim.png"
    argv = ["aim", str(s_path), "-n", "200", "--offsets", "0,2", "-o", str(table)]

    def interrupted(fig, dpi):
        raise KeyboardInterrupt

    monkeypatch.setattr(style, "png_bytes", interrupted)
    assert main([*argv, "--plot", str(picture)]) == 130
    assert capsys.readouterr().err.endswith("mcrun: interrupted: nothing was written\n")
    assert list(folder.iterdir()) == []
    monkeypatch.undo()
    assert main([*argv, "--plot", str(picture)]) == 0, capsys.readouterr().err
    assert sorted(p.name for p in folder.iterdir()) == ["a.parquet", "aim.png"]
    assert picture.stat().st_size > 0


def test_ctrl_c_while_the_outputs_are_put_in_place_waits_for_both(
    tmp_path, capsys, monkeypatch, ctrl_c_raises
):
    """Ctrl-C while the table is written waits until the picture is in place too, then stops
    the command, saying that everything was written."""
    pytest.importorskip("matplotlib")
    import signal

    s_path = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)]).path
    table, picture = tmp_path / "a.parquet", tmp_path / "aim.png"
    write_table = aim.write_table

    def interrupted(*args, **kwargs):
        signal.raise_signal(signal.SIGINT)
        return write_table(*args, **kwargs)

    monkeypatch.setattr(aim, "write_table", interrupted)
    argv = ["aim", str(s_path), "-n", "200", "--offsets", "0,2", "-o", str(table)]
    assert main([*argv, "--plot", str(picture)]) == 130
    assert capsys.readouterr().err.endswith("mcrun: interrupted: after writing everything\n")
    assert len(pd.read_parquet(table)) == 2 and picture.stat().st_size > 0


# --- the compile of the terrain's kernel ----------------------------------------------------------


def test_the_terrain_kernels_compile_is_said_apart_from_the_search(tmp_path, capsys, monkeypatch):
    """When the terrain's kernel is not compiled yet, ``mcrun aim`` compiles it before the
    search, saying so on stderr with the time it took, and the search's time is its own (the
    first search was silent for 80 s once and counted the compile in its own time)."""
    from mcrun import cli
    from mcrun.engine import warmup

    events = []

    def not_cached(ground, kernels=("batch",)):
        return events.append(ground) or False

    monkeypatch.setattr(cli, "_kernel_cached", not_cached)

    def warm_up(grounds, kernels=("batch",)):
        events.append(("compile", grounds))
        return (warmup.WarmUp("terrain", 61.6, False),)

    monkeypatch.setattr(warmup, "warm_up", warm_up)
    search = aim.search
    monkeypatch.setattr(aim, "search", lambda *a, **k: events.append("search") or search(*a, **k))
    s_path = scenario(tmp_path, FLAT, [("7-iron", 0.0, 3.0, 1.5)]).path
    code = main(["aim", str(s_path), "-n", "200", "--offsets", "0,2"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert events == ["terrain", ("compile", ("terrain",)), "search"]
    lines = captured.err.splitlines()
    assert lines[0].startswith("mcrun: compiling the kernel for a hole's ground (first run on")
    assert lines[1] == "mcrun: compiled the kernel for a hole's ground in 62 s"
    seconds = re.search(r"shots in (\d+\.\d) s\)", captured.out)
    assert seconds is not None and float(seconds[1]) < 30.0, captured.out


def test_the_best_aim_between_those_flown_is_the_parabola_s_vertex():
    """Expected strokes 1.4 + 0.05 (o + 0.37)^2 at five aims, flown in any order: the best
    between them is -0.37 (to rounding); a best flown aim at an end of them, or beside an aim
    without a value, is itself; no value at all: NaN."""
    offsets = [0.0, -1.0, -0.5, 0.5, -0.25]
    club = aim.ClubAims("wedge", offsets_m=offsets,
                        expected=[1.4 + 0.05 * (o + 0.37) ** 2 for o in offsets])  # fmt: skip
    assert club.best_between_m() == pytest.approx(-0.37, abs=1e-9)
    club.expected = [1.4 + 0.05 * (o - 0.9) ** 2 for o in offsets]
    assert club.best_between_m() == 0.5
    club.expected = [1.4 + 0.05 * (o + 0.37) ** 2 for o in offsets]
    club.expected[0] = math.nan  # the aim at 0, beside the best (-0.25)
    assert club.best_between_m() == -0.25
    club.expected = [math.nan] * len(offsets)
    assert math.isnan(club.best_between_m())


def test_on_a_side_slope_the_green_s_map_moves_a_wedge_s_best_aim_towards_below_the_pin(
    tmp_path, monkeypatch
):
    """Riverside 18's wedge from 110 m into its green tilted 2 % falling right (Stimp 11 ft;
    ``benchmarks.putting.side_slope_wedge``), five aims 0.25 m apart from 1 m left of the pin
    to the pin, 20,000 shots each. The pattern rolls down the slope after it lands, so the best
    aim lies above the pin (left of it) whatever values the finishes. Valued by the green's
    map with the putter's own read (uphill putts cheaper than downhill ones; 2,000 putts a
    read at 1.5 m, half the cost of the benchmark's 1 m), the best aim (``best_between_m``)
    lies at least 2.5 cm right of, below, the one the distance-only table gives. Over 8 seeds
    of the shots and the map (``python -m benchmarks.putting``) the margin was 5.8 to 13.5 cm
    (mean 9.9, SD 2.4): 2.5 cm is about the mean less 3 SD; here (seed 0) it is 9.4 cm."""
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    if str(root) not in sys.path:  # benchmarks/ is beside the package, not installed with it
        sys.path.insert(0, str(root))
    from benchmarks.putting import AIM_OFFSETS_M, own_read_map, side_slope_wedge

    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    best = {}
    for name, putting in (("map", own_read_map(2000, 0, resolution_m=1.5)), ("table", None)):
        scenario = aim.load_scenario(side_slope_wedge(tmp_path, putting, seed=0))
        result = aim.search(scenario, n=20_000, offsets_m=AIM_OFFSETS_M)
        best[name] = result.clubs[0].best_between_m()
    assert -1.0 < best["table"] < 0.0 and -1.0 < best["map"] < 0.0
    assert best["map"] - best["table"] >= 0.025
