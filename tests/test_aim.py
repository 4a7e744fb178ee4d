"""The aim search (``mcrun aim``, ``mcrun.run.aim``) from first principles: a symmetric hole is
aimed on its axis, water left of the pin moves the aim right and more so for a wider pattern, a
penalty-free fairway is aimed where the shots finish nearest the pin, and the common random
numbers make the differences between aims far more precise than the values."""

import json
import math
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
        (["par3-over-water", "--offsets", "a,b"], "--offsets a,b"),
        (["par3-over-water", "-n", "0"], "n must be an integer >= 1"),
        (["par3-over-water", "-o", "x.csv"], "must be a .parquet file"),
    ],
)
def test_bad_aim_commands_give_one_line(capsys, argv, message):
    assert main(["aim", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and message in err
