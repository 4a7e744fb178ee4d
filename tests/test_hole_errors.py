"""Every bad input of a hole is one line naming the file, the key or feature, and what is
allowed (mcrun.hole.errors.HoleError)."""

import json
import re
import shutil
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from mcrun.hole.errors import HoleError
from mcrun.hole.hole import hole_from_table, load_hole
from mcrun.hole.osm import read_course

HOLES = Path(__file__).resolve().parent.parent / "scenarios" / "holes"
MAPS = Path(__file__).resolve().parent / "data" / "maps"
MAP = "riverside-zagreb.osm.geojson"


@pytest.fixture
def folder(tmp_path):
    shutil.copy(HOLES / MAP, tmp_path / MAP)
    return tmp_path


def _error(table, folder):
    with pytest.raises(HoleError) as info:
        hole_from_table(table, folder, f"{folder / 'h.toml'} [hole]").terrain()
    message = str(info.value)
    assert "\n" not in message and "h.toml" in message
    return message


def _fake_elevation(monkeypatch, height_m):
    fake = types.ModuleType("mcrun.hole.elevation")

    class Fake:
        source = "fake"

        def height_m(self, lon, lat):
            return height_m(np.asarray(lon, float), np.asarray(lat, float))

    fake.load_elevation = lambda path, crs=None: Fake()
    monkeypatch.setitem(sys.modules, "mcrun.hole.elevation", fake)


def test_a_file_that_is_not_geojson(folder):
    (folder / "bad.geojson").write_text("{not json")
    assert "bad.geojson: is not a GeoJSON file (line 1" in _error({"map": "bad.geojson"}, folder)
    (folder / "point.geojson").write_text(json.dumps({"type": "Point", "coordinates": [0, 0]}))
    message = _error({"map": "point.geojson", "hole": 1}, folder)
    assert "point.geojson: is a GeoJSON Point, not a FeatureCollection" in message
    (folder / "empty.geojson").write_text(json.dumps({"type": "FeatureCollection", "features": []}))
    assert "has no golf=hole LineString" in _error({"map": "empty.geojson", "hole": 1}, folder)


def test_a_hole_that_does_not_exist_says_how_many_there_are(folder):
    message = _error({"map": MAP, "hole": 19}, folder)
    assert "hole 19 does not exist: the map has 18 golf=hole lines; give a position 1-18" in message
    assert "hole 'seven' does not exist" in _error({"map": MAP, "hole": "seven"}, folder)


def test_a_pin_outside_the_green(folder):
    message = _error({"map": MAP, "hole": 2, "pin": [15.8920, 45.7752]}, folder)
    assert "the pin [15.892000, 45.775200] of hole 2 is outside every green" in message
    assert "give a 'pin' on a green" in message


def test_an_elevation_that_does_not_cover_the_hole(folder, monkeypatch):
    # Heights only west of 15.8925 E: the tee of hole 2 (15.89313 E) is not covered, then a
    # grid that runs off the covered side.
    _fake_elevation(monkeypatch, lambda lon, lat: np.where(lon < 15.8925, 120.0, np.nan))
    message = _error({"map": MAP, "hole": 2, "elevation": "dem.tif"}, folder)
    assert "dem.tif does not cover the tee" in message
    _fake_elevation(monkeypatch, lambda lon, lat: np.where(lon < 15.8935, 120.0, np.nan))
    message = _error({"map": MAP, "hole": 2, "elevation": "dem.tif"}, folder)
    assert "dem.tif does not cover the hole's grid" in message and "'margin_m'" in message


def test_nan_holes_inside_the_hole(folder, monkeypatch):
    def holed(lon, lat):  # a 2 m gap half-way to the pin
        gap = (abs(lon - 15.89206) < 2e-5) & (abs(lat - 45.775135) < 2e-5)
        return np.where(gap, np.nan, 120.0)

    _fake_elevation(monkeypatch, holed)
    message = _error({"map": MAP, "hole": 2, "elevation": "dem.tif"}, folder)
    assert "dem.tif has holes (NaN) inside the hole's area" in message


def test_an_elevation_file_the_loader_refuses(folder, monkeypatch):
    fake = types.ModuleType("mcrun.hole.elevation")

    def refuse(path, crs=None):
        raise ValueError(f"{path}: no coordinate system; give elevation_crs")

    fake.load_elevation = refuse
    monkeypatch.setitem(sys.modules, "mcrun.hole.elevation", fake)
    message = _error({"map": MAP, "hole": 2, "elevation": "dem.tif"}, folder)
    assert "'elevation':" in message and "give elevation_crs" in message


@pytest.mark.parametrize(
    ("table", "expected"),
    [
        ({"map": MAP, "hole": 2, "colour": 1}, "unknown key 'colour'; allowed: map, hole"),
        ({"map": MAP}, "'hole' is missing: give the hole's ref or its position 1-18"),
        ({"map": MAP, "hole": 2, "cell_m": 0}, "'cell_m' = 0 must be a number in [0.05, 10]"),
        ({"map": MAP, "hole": 2, "tee": [15.9]}, "'tee' = [15.9] must be [lon, lat]"),
        ({"map": MAP, "hole": 2, "width_m": 20}, "'width_m' is for a hole without a 'map'"),
        ({"length_m": 100}, "a hole without a 'map' needs 'width_m'"),
        ({"width_m": 10}, "needs 'length_m' (or 'tee' and 'pin') and 'width_m'"),
        ({"length_m": 9, "width_m": 9, "surface": "water"}, "'surface' = 'water': choose rough"),
        ({"map": MAP, "hole": 2, "turf": {"green": {"rho_g": 9}}}, "'turf.green': turf rho_g"),
        ({"map": MAP, "hole": 2, "turf": {"sand": {}}}, "'turf.sand': unknown zone kind"),
        # (accepted, and never used: a ball ends where it touches a penalty area)
        (
            {"map": MAP, "hole": 2, "turf": {"water": {"mu": 0.3}}},
            "'turf.water': a ball ends where it touches a penalty area",
        ),
        ({"map": MAP, "hole": 2, "turf": {"water_yellow": {}}}, "'turf.water_yellow': a ball"),
        ({"map": MAP, "hole": 2, "turf": {"green": {"spin": 1}}}, "'turf.green.spin': unknown"),
        # (a list: a TypeError, unhashable)
        (
            {"map": MAP, "hole": 2, "turf": {"green": {"preset": ["green"]}}},
            "'turf.green.preset' = ['green']: choose green, ",
        ),  # fmt: skip
        ({"map": MAP, "hole": 2, "par": 9}, "'par' = 9 must be a whole number 2-7"),
        ({"map": "missing.geojson", "hole": 2}, "missing.geojson: cannot read the map"),
        ({"length_m": 9, "width_m": 9, "elevation": "d.tif"}, "an 'elevation' needs the hole"),
        (
            {"tee": [15.9, 45.78], "pin": [16.5, 45.78], "width_m": 60},
            "the pin is 46,661.3 m from the tee: allowed: up to 2,000 m",  # (refused after 40 s)
        ),
        (
            {"tee": [15.9, 45.78], "pin": [15.925721, 45.78], "width_m": 60},  # 2,000.3 m
            "the pin is 2,000.3 m from the tee",  # (said "2,000 m", as allowed, before)
        ),
    ],
)
def test_bad_keys(folder, table, expected):
    assert expected in _error(table, folder)


def test_a_hole_file_that_is_not_toml(tmp_path):
    path = tmp_path / "h.toml"
    path.write_text("map = \n")
    with pytest.raises(HoleError, match=r"h.toml: is not valid TOML") as info:
        load_hole(path)
    assert "\n" not in str(info.value)


def test_a_hole_file_that_is_no_file(tmp_path):
    """A device (/dev/zero was read until memory ran out), a folder, a NUL in the path (a
    ValueError traceback) or a file far larger than a hole's keys: one line each."""
    big = tmp_path / "big.toml"
    big.write_text("# padding\n" * 200_000)
    cases = [
        ("/dev/zero", "/dev/zero: is not a regular file (a device or a pipe)"),
        (tmp_path, "is a folder, not a hole file"),
        (tmp_path / "a\0b.toml", "a path cannot hold a NUL character"),
        (big, "2,000,000 bytes: a hole TOML file is at most 1,000,000"),
    ]
    for path, says in cases:
        with pytest.raises(HoleError, match=re.escape(says)):
            load_hole(path)


def test_a_hole_without_a_green_is_refused(tmp_path):
    # tests/data/maps/no-green.geojson: a hole line, its tee and fairway, no green mapped.
    shutil.copy(MAPS / "no-green.geojson", tmp_path)
    message = _error({"map": "no-green.geojson", "hole": 1}, tmp_path)
    assert "hole 1 has no green:" in message and "has no golf=green polygon" in message
    assert "a hole is played to a pin on its green" in message
    # A pin given by hand does not make a green.
    message = _error({"map": "no-green.geojson", "hole": 1, "pin": [15.9, 45.7825]}, tmp_path)
    assert "hole 1 has no green:" in message


def test_a_green_only_far_away_is_not_the_holes(tmp_path):
    # The half-mapped course with one green, 2 km north of the hole's end (0.018 deg).
    data = json.loads((MAPS / "no-green.geojson").read_text())
    lon, lat = data["features"][1]["geometry"]["coordinates"][-1]
    ring = [[lon + dx, lat + 0.018 + dy] for dx, dy in ((0, 0), (2e-4, 0), (2e-4, 2e-4), (0, 0))]
    green = {"type": "Polygon", "coordinates": [ring]}
    data["features"].append({"type": "Feature", "properties": {"golf": "green"}, "geometry": green})
    (tmp_path / "far.geojson").write_text(json.dumps(data))
    message = _error({"map": "far.geojson", "hole": 1}, tmp_path)
    assert "hole 1 has no green:" in message and "within 1000 m of the hole's end" in message


@pytest.mark.parametrize(
    ("coordinates", "shown"),
    [([15.9, 145.78], "[15.9, 145.78]"), ([215.9, 45.78], "[215.9, 45.78]")],
)
def test_points_off_the_earth_are_refused(tmp_path, coordinates, shown):
    data = json.loads((MAPS / "no-green.geojson").read_text())
    data["features"][1]["geometry"]["coordinates"][1] = coordinates  # the hole line's middle
    (tmp_path / "off.geojson").write_text(json.dumps(data))
    message = _error({"map": "off.geojson", "hole": 1}, tmp_path)
    feature = data["features"][1]["id"]
    assert f"off.geojson: feature {feature}: point {shown} is off the Earth" in message
    assert "longitude in [-180, 180], latitude in [-90, 90]" in message


def test_web_mercator_metres_in_a_map_are_refused(tmp_path):
    # tests/data/maps/web-mercator.geojson: EPSG:3857 metres where lon/lat belong.
    shutil.copy(MAPS / "web-mercator.geojson", tmp_path)
    message = _error({"map": "web-mercator.geojson", "hole": 1}, tmp_path)
    assert "web-mercator.geojson: feature way/" in message and "is off the Earth" in message


def test_a_kml_map_says_it_is_kml(tmp_path):
    (tmp_path / "course.kml").write_text('<?xml version="1.0"?>\n<kml><Document/></kml>\n')
    message = _error({"map": "course.kml", "hole": 1}, tmp_path)
    assert "course.kml: is a KML file (Google Earth), not a course map" in message
    assert "allowed is a GeoJSON FeatureCollection (.geojson, .json)" in message
    (tmp_path / "h.toml").write_text('<?xml version="1.0"?>\n<gpx version="1.1"></gpx>\n')
    with pytest.raises(HoleError, match=r"h.toml: is a GPX file \(GPS tracks\), not a hole"):
        load_hole(tmp_path / "h.toml")
    (tmp_path / "h.toml").write_text('{"type": "FeatureCollection", "features": []}\n')
    with pytest.raises(HoleError, match=r"h.toml: is not a hole TOML file but looks like JSON"):
        load_hole(tmp_path / "h.toml")


def test_conflicting_copies_of_an_elevation_point_are_refused(tmp_path):
    # tests/data/maps/points-conflicting-copies.csv: one point three times, once 500 m high.
    shutil.copy(MAPS / "points-conflicting-copies.csv", tmp_path)
    table = {"tee": [15.9001, 45.7801], "pin": [15.9005, 45.7803], "width_m": 10}
    table |= {"margin_m": 0, "elevation": "points-conflicting-copies.csv"}
    message = _error(table, tmp_path)
    assert "'elevation': points-conflicting-copies.csv: the point lon 15.9002, lat 45.78015" in (
        message
    )
    assert "is given 3 times with different heights (100.25, 500, 100.25 m, rows 7, 8, 14)" in (
        message
    )


def test_a_ref_shared_by_two_courses_is_ambiguous_and_a_position_chooses(tmp_path):
    # tests/data/maps/two-courses.geojson with South Park Golf's first hole tagged ref 1 too.
    data = json.loads((MAPS / "two-courses.geojson").read_text())
    lines = [f for f in data["features"] if f["properties"].get("golf") == "hole"]
    lines[2]["properties"]["ref"] = "1"
    (tmp_path / "country.geojson").write_text(json.dumps(data))
    message = _error({"map": "country.geojson", "hole": 1}, tmp_path)
    assert "hole 1: 2 holes have ref 1 (#1 on North Links, #3 on South Park Golf)" in message
    assert "give the one you mean by its position in the file, as '#N'" in message
    hole = hole_from_table({"map": "country.geojson", "hole": "#3"}, tmp_path, "h.toml")
    assert hole.name == "South Park Golf, hole 1" and hole.index == 3
    assert hole_from_table({"map": "country.geojson", "hole": 2}, tmp_path, "t").index == 2
    message = _error({"map": "country.geojson", "hole": "#9"}, tmp_path)
    assert "hole '#9' does not exist: the map has 5 golf=hole lines; give a position 1-5 or a " in (
        message
    )
    assert "a ref (1, 2, 3)" in message


def test_a_grid_too_large_is_refused_before_it_is_built(folder):
    """A fine cell over a wide margin (each within its range) would be 1.76 billion nodes: the
    count is refused up front, with the least cell that fits, in place of running out of
    memory after a minute; a plain hole of 2 km by 2 km at 0.3 m is 44.5 million, within."""
    message = _error({"map": MAP, "hole": 2, "cell_m": 0.05, "margin_m": 1000}, folder)
    assert "'cell_m' = 0.05 over 2168 x 2026 m (the hole and its margin_m) is a grid of " in message
    assert "allowed are at most 50,000,000 (a cell_m of at least 0.3 m" in message
    table = {"length_m": 2000, "width_m": 2000, "cell_m": 0.3, "margin_m": 0}
    hole_from_table(table, folder, "plain")  # (its grid is built on demand: not here)
    table["cell_m"] = 0.25
    with pytest.raises(HoleError, match="is a grid of 8,001 x 8,001 nodes"):
        hole_from_table(table, folder, "plain")


@pytest.mark.parametrize(
    ("coordinates", "says"),
    [
        ([[15.9, 45.78]], "1 point: allowed is a line or a ring of at least 2 [lon, lat] points"),
        ([], "0 points: allowed is a line or a ring of at least 2"),
        ([[15.9, 45.78], [float("nan"), 45.79]], "point 2 is [nan, 45.79]: allowed are finite"),
        ([[15.9, 45.78], [15.9, float("inf")]], "point 2 is [15.9, inf]: allowed are finite"),
        ([15.9, 45.78], "its coordinates are not lists of [lon, lat] points"),
    ],
)
def test_a_hole_line_s_geometry_is_named_as_it_is_wrong(tmp_path, coordinates, says):
    data = json.loads((MAPS / "no-green.geojson").read_text())
    data["features"][1]["geometry"]["coordinates"] = coordinates  # the hole line
    (tmp_path / "line.geojson").write_text(json.dumps(data))  # (NaN as JSON's NaN)
    message = _error({"map": "line.geojson", "hole": 1}, tmp_path)
    assert f"line.geojson: feature {data['features'][1]['id']}: {says}" in message


def test_a_hole_line_of_no_length_and_a_par_out_of_range_are_listed_as_unplayable(folder, capsys):
    """A golf=hole line that ends where it starts has no tee-to-green direction (its pin would
    be any green nearby); a par of 99 is none: each is refused for its hole, and marked in the
    map's listing, which lists the others."""
    from mcrun.cli import main

    data = json.loads((folder / MAP).read_text())
    holes = [f for f in data["features"] if f["properties"].get("golf") == "hole"]
    holes[1]["geometry"]["coordinates"] = [holes[1]["geometry"]["coordinates"][0]] * 2
    holes[2]["properties"]["par"] = "99"
    holes[0]["properties"]["par"] = 4.0  # a real field, as QGIS writes one: par 4
    holes[6]["properties"]["par"] = "4_0"  # (int() read it as 40)
    line = holes[7]["geometry"]["coordinates"]  # a point 2.8 km off the hole (half a minute,
    line.insert(1, [line[0][0], line[0][1] - 0.025])  # 400 MB, a grid of 6 million nodes)
    holes[3]["properties"]["par"] = "4;5"  # men's and women's: not taken for no par
    holes[4]["properties"]["ref"] = [9, "18"]  # a nine played twice, as a converter's list
    holes[5]["properties"]["name"] = "Amen\nCorner "  # (printed raw, over two lines, before)
    holes[8]["properties"]["name"] = "\u202eRed\x1b[31m"  # (reached the terminal raw)
    (folder / "odd.geojson").write_text(json.dumps(data))
    message = _error({"map": "odd.geojson", "hole": 2}, folder)
    assert "hole 2: its golf=hole line ends 0.0 m from where it starts: allowed is" in message
    assert "the map's par of hole 4 is '4;5': allowed is a whole number 2-7 (mend" in _error(
        {"map": "odd.geojson", "hole": 4}, folder
    )
    hole = hole_from_table({"map": "odd.geojson", "hole": 4, "par": 4.0}, folder, "h.toml")
    assert hole.par == 4 and type(hole.par) is int  # (printed "par: 4.0" before)
    assert main(["hole", str(folder / "odd.geojson")]) == 0
    out = capsys.readouterr().out
    assert "  ! hole 2: its golf=hole line ends 0.0 m" in out
    assert "  ! par 99: allowed is a whole number 2-7" in out
    assert "  ! par '4;5': allowed is a whole number 2-7" in out
    assert "   5  9;18    -     411.3" in out
    course = read_course(folder / "odd.geojson")  # hole 9 is its ref's, not position 9
    assert course.hole("9").index == course.hole("18").index == 5
    assert "hole 6: Amen Corner\n" in out and "hole 9: Red[31m\n" in out
    plain = hole_from_table({"length_m": 90, "width_m": 30, "name": "Short\n\tone"}, folder, "h")
    assert plain.name == "Short one"
    assert "   1     -    4     356.0" in out and "  ! par '4_0': allowed" in out
    assert "  ! hole 8: its golf=hole line reaches 2,7" in out
    assert "5 of 18 holes cannot be played as mapped" in out


def test_a_feature_that_cannot_be_read_stops_only_what_needs_it(folder, capsys):
    """A map cut at its edge leaves broken pieces: a hole line of one point is kept, unplayable
    (choosing it says why; the other holes keep their numbers and play), and a bunker with a
    NaN point is left out, said by the listing and a hole's description, where either stopped
    the whole map before."""
    from mcrun.cli import main

    data = json.loads((folder / MAP).read_text())
    holes = [f for f in data["features"] if f["properties"].get("golf") == "hole"]
    holes[1]["geometry"]["coordinates"] = holes[1]["geometry"]["coordinates"][:1]
    bunker = next(f for f in data["features"] if f["properties"].get("golf") == "bunker")
    bunker["geometry"]["coordinates"][0][1] = [float("nan"), 45.77]
    (folder / "cut.geojson").write_text(json.dumps(data))
    message = _error({"map": "cut.geojson", "hole": 2}, folder)
    assert f"feature {holes[1]['id']}: 1 point: allowed is a line or a ring" in message
    hole = hole_from_table({"map": "cut.geojson", "hole": 3}, folder, "h3")
    whole = hole_from_table({"map": MAP, "hole": 3}, folder, "h3")
    assert hole.length_m == whole.length_m and hole.index == 3
    assert len(hole.map_skipped) == 1 and whole.map_skipped == ()
    assert main(["hole", str(folder / "cut.geojson"), "--hole", "3"]) == 0
    assert "map: 1 feature(s) of the map left out, their geometry unreadable (the first: " in (
        capsys.readouterr().out
    )
    assert main(["hole", str(folder / "cut.geojson")]) == 0
    out = capsys.readouterr().out
    assert f"  ! feature {holes[1]['id']}: 1 point" in out
    assert "1 of 18 holes cannot be played as mapped" in out
    assert (f"1 feature(s) of the map left out, their geometry unreadable (the first: feature "
            f"{bunker['id']}: point 2 is [nan, 45.77]: allowed are finite") in out  # fmt: skip
    from mcrun.cli.rate import play_order
    from mcrun.hole.osm import read_course

    order, note = play_order(read_course(folder / "cut.geojson"))
    assert order == {k: k for k in range(1, 19)}  # (the broken line keeps its place)
    assert note == play_order(read_course(folder / MAP))[1]  # its walks left out: the same


def test_greens_without_a_ring_or_of_two_points_are_left_out_and_named(folder):
    """A green whose polygon has no ring (``"coordinates": []``, an IndexError before) or a ring
    of 2 points (the pin "outside every green" before) is left out as unreadable, and a hole
    that has no green left says why; a map saved with a byte-order mark reads."""
    data = json.loads((folder / MAP).read_text())
    greens = [f for f in data["features"] if f["properties"].get("golf") == "green"]
    for k, green in enumerate(greens):
        ring = green["geometry"]["coordinates"][0]
        green["geometry"]["coordinates"] = [] if k % 2 else [ring[:2]]
    (folder / "bad-greens.geojson").write_text(json.dumps(data))
    message = _error({"map": "bad-greens.geojson", "hole": 2}, folder)
    assert f"has no golf=green polygon it reads ({len(greens)} feature(s) left out" in message
    course = read_course(folder / "bad-greens.geojson")
    assert sorted(line.split(": ", 1)[1].split(":")[0] for line in course.skipped[:2]) == [
        "a polygon without a ring", "a ring of 2 points enclosing nothing"]  # fmt: skip
    (folder / "bom.geojson").write_text("\ufeff" + (folder / MAP).read_text(), encoding="utf-8")
    assert len(read_course(folder / "bom.geojson").greens) == len(greens)


def test_the_commands_that_play_a_hole_say_what_of_its_map_was_left_out(folder, capsys):
    """A hole played on a map with an unreadable feature is played as the rest of the map draws
    it: ``mcrun run`` and ``validate`` (and ``aim``, ``play``, ``putt --hole``, by the same
    ``say_skipped``) say so on stderr, and ``mcrun rate`` among its notes; a whole map, nothing."""
    from mcrun.cli import main
    from mcrun.cli.rate import course_holes

    data = json.loads((folder / MAP).read_text())
    bunker = next(f for f in data["features"] if f["properties"].get("golf") == "bunker")
    bunker["geometry"]["coordinates"][0][1] = [float("nan"), 45.77]
    (folder / "cut.geojson").write_text(json.dumps(data))
    scenario = (HOLES.parent / "par4-tee-shot.toml").read_text()
    for name in ("cut.geojson", MAP):
        (folder / "h.toml").write_text(
            (HOLES / "riverside-9.toml").read_text().replace(f'"{MAP}"', f'"{name}"')
        )
        (folder / "s.toml").write_text(scenario.replace("holes/riverside-9.toml", "h.toml"))
        assert main(["validate", str(folder / "s.toml")]) == 0
        err = capsys.readouterr().err
        if name == MAP:
            assert "left out" not in err
        else:
            assert (f"mcrun: note: {folder / 'cut.geojson'}: 1 feature(s) of the map left out, "
                    f"their geometry unreadable (the first: feature {bunker['id']}: point 2 is "
                    "[nan, 45.77]") in err  # fmt: skip
    notes = course_holes(folder / "cut.geojson", "9")[3]
    assert any(n.startswith("1 feature(s) of the map left out") for n in notes)
    assert not any("left out" in n for n in course_holes(folder / MAP, "9")[3])


def test_a_bad_hole_elevation_ground_shape_or_baseline_is_an_input_error(tmp_path):
    """One class catches every bad input of the Python API: a hole, an elevation file, a
    ground shape and a strokes baseline raise mcrun.InputError (each a ValueError of its own
    before, which ``except mcrun.InputError`` let through)."""
    from mcrun import InputError
    from mcrun.hole.elevation import load_elevation
    from mcrun.hole.shapes import check_shape
    from mcrun.strokes.baseline import load_baseline

    (tmp_path / "h.toml").write_text("[hole]\nsurface = 'lava'\n")
    (tmp_path / "b.csv").write_text("lie,distance_m\n")
    for call in (
        lambda: load_hole(tmp_path / "h.toml"),
        lambda: load_elevation(tmp_path / "none.csv"),
        lambda: check_shape("volcano"),
        lambda: load_baseline(tmp_path / "b.csv"),
    ):
        with pytest.raises(InputError):
            call()


def test_a_hole_line_drawn_backwards_is_refused(folder):
    """A golf=hole line drawn from the green to the tee starts on its green; its end found the
    nearest other green, and the hole was played (and rated) to another hole's pin."""
    data = json.loads((folder / MAP).read_text())
    hole = [f for f in data["features"] if f["properties"].get("golf") == "hole"][1]
    before = hole_from_table({"map": MAP, "hole": 2}, folder, "h.toml")
    hole["geometry"]["coordinates"].reverse()
    (folder / "reversed.geojson").write_text(json.dumps(data))
    message = _error({"map": "reversed.geojson", "hole": 2}, folder)
    assert message.endswith("hole 2: its golf=hole line starts on a green and ends off one: "
                            "drawn backwards? allowed is a line from the tee to the green (or a "
                            "'tee' and a 'pin' in a hole file)")  # fmt: skip
    # Its tee and pin given, the line's direction does not matter.
    table = {"map": "reversed.geojson", "hole": 2, "tee": list(before.tee_lonlat),
             "pin": list(before.pin_lonlat)}  # fmt: skip
    assert hole_from_table(table, folder, "h.toml").length_m == pytest.approx(before.length_m)


def test_a_hole_file_s_name_is_text(folder):
    """name = 5 was named "5"; name = "" fell back to the file's name."""
    for name in (5, "", "  "):
        message = _error({"map": MAP, "hole": 2, "name": name}, folder)
        assert f"'name' = {name!r}: allowed: a name (text), or no 'name' for the map's" in message
    named = hole_from_table({"map": MAP, "hole": 2, "name": "Two"}, folder, "h.toml")
    assert named.name == "Two"
