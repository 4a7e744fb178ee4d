"""The real course (Riverside, Zagreb; map data (c) OpenStreetMap contributors, ODbL) read as
holes (mcrun.hole.osm, mcrun.hole.hole): holes, tee and pin, lengths, the Terrain and its size."""

import sys
import types
from pathlib import Path

import numpy as np
import pytest
from pyproj import Geod

from mcrun.ground import IN_PLAY, OUT_OF_BOUNDS, PENALTY_AREA
from mcrun.hole.hole import hole_from_table, load_hole
from mcrun.hole.osm import read_course
from mcrun.hole.zones import GREEN, TEE, WATER, WATER_YELLOW, ZONE_KINDS
from mcrun.physics.turf import PRESETS, Turf

HOLES = Path(__file__).resolve().parent.parent / "scenarios" / "holes"
MAP = HOLES / "riverside-zagreb.osm.geojson"
GEOD = Geod(ellps="WGS84")


def test_the_course_has_18_holes_each_ending_in_a_green_with_its_pin():
    course = read_course(MAP)
    assert len(course.holes) == 18 and len(course.pins) == 18
    assert [h.index for h in course.holes] == list(range(1, 19))
    assert all(h.ref is None for h in course.holes)  # the extract has no ref tags
    assert len(course.boundary) == 1


def test_hole_2_length_is_the_geodesic_from_its_tee_to_its_pin():
    # Independently: the hole line's first point and the golf=pin node inside hole 2's green
    # (15.89099, 45.77502, read off the file), and the WGS84 geodesic between them. The plane
    # of the frame is short of the geodesic by s^3 / (6 R^2) = 2e-8 m at 168 m.
    hole = hole_from_table({"map": MAP.name, "hole": 2}, HOLES, "t")
    _, _, geodesic_m = GEOD.inv(15.89313, 45.77525, 15.89099, 45.77502)
    assert hole.length_m == pytest.approx(geodesic_m, abs=1e-6)
    assert hole.length_m == pytest.approx(168.4, abs=0.05)
    assert hole.pin_lonlat == pytest.approx((15.89099, 45.77502), abs=1e-9)
    assert hole.zone_at(0.0, 0.0) == TEE and hole.zone_at(*hole.pin_xy) == GREEN
    lon, lat = hole.to_lonlat(*hole.pin_xy)
    assert (float(lon), float(lat)) == pytest.approx((15.89099, 45.77502), abs=1e-9)


def test_the_library_holes_are_what_their_names_say():
    par3 = load_hole(HOLES / "riverside-2.toml")
    x = np.linspace(0.0, par3.length_m, 2000)
    crossed = x[par3.zone_at(x, 0 * x) == WATER_YELLOW]  # golf=water_hazard: yellow
    assert par3.par == 3 and crossed.min() == pytest.approx(93, abs=2)
    assert crossed.max() == pytest.approx(128, abs=2)
    wedge = load_hole(HOLES / "riverside-18-wedge.toml")
    assert wedge.length_m == pytest.approx(110.0, abs=0.1)
    assert ZONE_KINDS[wedge.zone_at(0.0, 0.0)] == "fairway"
    par4 = load_hole(HOLES / "riverside-9.toml")
    t = par4.terrain()
    xx = t.x0_m + np.arange(t.zone.shape[1]) * t.cell_m
    yy = t.y0_m + np.arange(t.zone.shape[0]) * t.cell_m
    band = (xx[None, :] > 180) & (xx[None, :] < 290) & (abs(yy[:, None]) < 35)
    assert ((t.zone == ZONE_KINDS.index("bunker")) & band).sum() * t.cell_m**2 > 300


def test_terrain_tables_follow_the_zones_and_the_overrides():
    table = {"map": MAP.name, "hole": 2, "turf": {"green": {"preset": "firm_green", "rho_g": 0.1}}}
    t = hole_from_table(table, HOLES, "t").terrain()
    assert t.turf.shape == (len(ZONE_KINDS), len(Turf._fields))
    green = Turf(*t.turf[GREEN])
    assert green == PRESETS["firm_green"]._replace(rho_g=0.1)
    assert Turf(*t.turf[ZONE_KINDS.index("bunker")]) == PRESETS["bunker"]
    assert (
        t.penalty[WATER] == t.penalty[WATER_YELLOW] == PENALTY_AREA
        and t.penalty[-1] == OUT_OF_BOUNDS
    )
    assert t.penalty[GREEN] == IN_PLAY
    assert t.zone.dtype == np.int8 and t.height_m.shape == t.zone.shape
    assert np.all(t.height_m == 0.0)


def test_a_whole_course_at_half_a_metre_fits_in_200_mb():
    hole = hole_from_table({"map": MAP.name, "hole": 2}, HOLES, "t")
    t = hole.terrain_over(hole.course_extent_m())
    nbytes = t.height_m.nbytes + t.zone.nbytes + t.turf.nbytes + t.penalty.nbytes
    # 2271 x 1702 nodes (850 m x 1135 m) at 9 bytes a node: 34.8 MB measured.
    assert t.zone.size > 3.5e6 and nbytes < 200e6
    assert nbytes == pytest.approx(9 * t.zone.size, rel=1e-3)


def test_heights_come_from_the_elevation_relative_to_the_tee(monkeypatch):
    # A fake elevation rising 1 m per 1e-4 deg of latitude (11.1 m north): a slope of 1/11.1.
    fake = types.ModuleType("mcrun.hole.elevation")

    class Ramp:
        source = "ramp"

        def height_m(self, lon, lat):
            return 100.0 + (np.asarray(lat) - 45.0) * 1e4 + 0.0 * np.asarray(lon)

    fake.load_elevation = lambda path, crs=None: Ramp()
    monkeypatch.setitem(sys.modules, "mcrun.hole.elevation", fake)
    hole = hole_from_table({"map": MAP.name, "hole": 2, "elevation": "x.tif"}, HOLES, "t")
    t = hole.terrain()
    lat_tee, lat_pin = 45.77525, 45.77502
    iy, ix = round(-t.y0_m / t.cell_m), round((hole.pin_xy[0] - t.x0_m) / t.cell_m)
    assert t.height_m[iy, ix] == pytest.approx((lat_pin - lat_tee) * 1e4, abs=0.05)
    assert t.height_m[round(-t.y0_m / t.cell_m), round(-t.x0_m / t.cell_m)] == pytest.approx(
        0, abs=1e-9
    )


def test_a_shape_without_a_map_is_a_rectangle_of_one_surface(monkeypatch):
    fake = types.ModuleType("mcrun.hole.shapes")
    fake.shape_height = lambda kind, params, x, y: 3.0 + params["slope"] * np.asarray(x)
    monkeypatch.setitem(sys.modules, "mcrun.hole.shapes", fake)
    table = {
        "shape": {"kind": "tilted_plane", "slope": 0.02},
        "surface": "green",
        "length_m": 30.0,
        "width_m": 20.0,
        "margin_m": 5.0,
        "cell_m": 0.25,
    }
    hole = hole_from_table(table, ".", "t")
    t = hole.terrain()
    assert np.all(t.zone == GREEN) and t.zone.shape == (81, 161)
    assert t.height_m[0, -1] == pytest.approx(0.02 * 35.0)
    assert hole.frame is None and np.isnan(hole.to_lonlat(1.0, 2.0)[0])
    assert hole.zone_at(100.0, 0.0) == -1
