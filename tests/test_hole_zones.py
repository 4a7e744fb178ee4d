"""Zone kinds, overlap order and rasterisation (mcrun.hole.zones)."""

from pathlib import Path

import numpy as np
import pytest

from mcrun.hole.hole import hole_from_table
from mcrun.hole.zones import (
    BUNKER,
    FAIRWAY,
    GREEN,
    OUT,
    ROUGH,
    WATER,
    WATER_YELLOW,
    ZONE_KINDS,
    contains,
    polygon_mask,
    rasterize,
    shoelace_area_m2,
    zone_of_tags,
)
from mcrun.physics.turf import ESTIMATED_PRESETS, PRESETS, check_turf

HOLES = Path(__file__).resolve().parent.parent / "scenarios" / "holes"


def _square(x0, y0, side):
    return np.array([[x0, y0], [x0 + side, y0], [x0 + side, y0 + side], [x0, y0 + side]], float)


def _perimeter_m(polygon):
    return sum(np.hypot(*np.diff(np.vstack([r, r[:1]]), axis=0).T).sum() for r in polygon)


def test_a_square_with_a_hole_on_grid_lines_is_exact():
    polygon = [_square(0.0, 0.0, 10.0), _square(3.0, 3.0, 3.0)[::-1]]  # outer, then a hole
    cell = 0.1
    mask = polygon_mask(polygon, -1.05, -1.05, cell, 130, 130)
    assert mask.sum() * cell**2 == pytest.approx(shoelace_area_m2(polygon), abs=1e-9)
    assert shoelace_area_m2(polygon) == pytest.approx(91.0)
    xs = -1.05 + np.arange(130) * cell
    xx, yy = np.meshgrid(xs, xs)
    assert np.array_equal(mask, contains(polygon, xx, yy))
    assert not contains(polygon, 4.5, 4.5) and contains(polygon, 1.0, 1.0)


def test_every_mapped_polygon_rasterises_to_its_shoelace_area():
    # Each boundary node may fall either side: the error is bounded by the perimeter times the
    # cell; measured at most 0.18 x perimeter x cell over the 165 zones of Riverside at 0.5 m,
    # and 0.03 % over their total.
    hole = hole_from_table({"map": HOLES / "riverside-zagreb.osm.geojson", "hole": 9}, ".", "t")
    cell = 0.5
    total_raster = total_shoelace = 0.0
    for _, polygon in hole.zones:
        xy = np.concatenate(polygon)
        x0, y0 = xy.min(0) - 1.0
        nx, ny = ((xy.max(0) - xy.min(0)) / cell + 5).astype(int)
        raster = polygon_mask(polygon, x0, y0, cell, nx, ny).sum() * cell**2
        shoelace = shoelace_area_m2(polygon)
        assert abs(raster - shoelace) <= 0.25 * _perimeter_m(polygon) * cell
        total_raster += raster
        total_shoelace += shoelace
    assert len(hole.zones) == 165
    assert total_raster == pytest.approx(total_shoelace, rel=1e-3)


def test_overlaps_resolve_in_the_stated_order():
    # A fairway with a bunker in it, a pond over part of the bunker, a green inside a fringe-less
    # fairway, a course boundary that leaves the right strip out; listed in the wrong order.
    zones = [
        ("water", [_square(14.0, 4.0, 4.0)]),
        ("water_yellow", [_square(16.0, 6.0, 3.0)]),  # over the red pond's corner: wins
        ("bunker", [_square(12.0, 2.0, 4.0)]),
        ("fairway", [_square(0.0, 0.0, 20.0)]),
        ("green", [_square(2.0, 2.0, 4.0)]),
        ("rough", [_square(1.0, 1.0, 18.0)]),  # mapped rough over the fairway: loses to it
    ]
    boundary = [[_square(-5.0, -5.0, 29.0)]]  # x, y up to 24: the right of the grid is out
    grid = rasterize(zones, -4.0, -4.0, 1.0, 30, 30, boundary)

    def at(x, y):
        return grid[int(y + 4), int(x + 4)]

    assert at(-2, -2) == ROUGH  # inside the boundary, no polygon
    assert at(10, 10) == FAIRWAY  # rough < fairway
    assert at(3, 3) == GREEN
    assert at(13, 3) == BUNKER  # fairway < bunker
    assert at(15, 5) == WATER  # bunker < water
    assert at(17, 7) == WATER_YELLOW  # water < water_yellow
    assert at(25, 10) == OUT  # outside the boundary
    assert ZONE_KINDS.index("out_of_bounds") == OUT


def test_every_zone_preset_is_a_valid_turf_and_the_new_ones_are_estimates():
    for name in ("bunker", "fringe", "tee"):
        check_turf(PRESETS[name])
        assert name in ESTIMATED_PRESETS
    # Sand holds the ball: a 2 m/s roll stops within 0.3 m (v^2 / (2 (5/7) rho_g g)).
    assert 2.0**2 / (2 * 5 / 7 * PRESETS["bunker"].rho_g * 9.80665) < 0.3
    assert PRESETS["green"].rho_g < PRESETS["fringe"].rho_g < PRESETS["fairway"].rho_g


@pytest.mark.parametrize(
    "tags, kind",
    [
        ({"golf": "water_hazard"}, "water_yellow"),  # yellow stakes
        ({"golf": "lateral_water_hazard"}, "water"),  # red stakes
        ({"natural": "water"}, "water"),  # unmarked: red (Rule 17.1)
        ({"golf": "water_hazard", "natural": "water"}, "water_yellow"),  # golf=* first
        ({"golf": "lateral_water_hazard", "natural": "water"}, "water"),
    ],
)
def test_openstreetmap_tags_name_the_colour_of_a_penalty_area(tags, kind):
    assert zone_of_tags(tags) == kind


def _riverside_2(**keys):
    table = {"map": "riverside-zagreb.osm.geojson", "hole": 2, "cell_m": 1.0, "margin_m": 40.0}
    return hole_from_table({**table, **keys}, HOLES, "t")


def test_a_hole_file_sets_the_colour_of_every_penalty_area():
    """Riverside 2's pond is a golf=water_hazard: yellow as mapped; 'penalty_areas' turns it
    red (or yellow), the same nodes; any other value is refused, naming the key."""
    mapped = _riverside_2().zone_areas_m2()
    red = _riverside_2(penalty_areas="red").zone_areas_m2()
    yellow = _riverside_2(penalty_areas="yellow").zone_areas_m2()
    assert mapped["water_yellow"] > 2000 and mapped["water"] == 0
    assert red["water_yellow"] == 0 and red["water"] == mapped["water_yellow"]
    assert yellow == mapped
    from mcrun.hole.errors import HoleError

    with pytest.raises(HoleError, match="'penalty_areas' = 'blue': choose red, yellow"):
        _riverside_2(penalty_areas="blue")
