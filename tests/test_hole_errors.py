"""Every bad input of a hole is one line naming the file, the key or feature, and what is
allowed (mcrun.hole.errors.HoleError)."""

import json
import shutil
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from mcrun.hole.errors import HoleError
from mcrun.hole.hole import hole_from_table, load_hole

HOLES = Path(__file__).resolve().parent.parent / "scenarios" / "holes"
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
        ({"map": MAP, "hole": 2, "turf": {"green": {"spin": 1}}}, "'turf.green.spin': unknown"),
        ({"map": MAP, "hole": 2, "par": 9}, "'par' = 9 must be a whole number 2-7"),
        ({"map": "missing.geojson", "hole": 2}, "missing.geojson: cannot read the map"),
        ({"length_m": 9, "width_m": 9, "elevation": "d.tif"}, "an 'elevation' needs the hole"),
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
