"""Out of bounds is decided where the ball comes to rest (Rule 18.2): a ball is out of bounds
only when it lies outside the boundary at rest, so one that bounces or rolls over the boundary
and back in is in bounds. Out-of-bounds ground is played on like any other while the ball moves
(its zone's turf); a penalty area still ends the shot where the ball touches it (Rule 17)."""

import numpy as np
import pytest
from test_terrain import CLUBS, grid, landed

from mcrun import api, ground
from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.schema import (
    CARRY,
    CARRY_LATERAL,
    FINAL_X,
    FINAL_Y,
    PENALTY_X,
    PENALTY_Y,
    STATUS,
)
from mcrun.status import IN_PENALTY_AREA, OK, OUT_OF_BOUNDS_STATUS
from mcrun.trajectory import FLIGHT

LEVEL = lambda X, Y: 0.0 * X  # noqa: E731
FAIRWAY_OB = dict(turfs=("fairway", "fairway"), penalty=(ground.IN_PLAY, ground.OUT_OF_BOUNDS))


def _carry(club):
    """(x, y) where a shot of ``club`` lands on level ground, hole frame (y to the right)."""
    inputs, _ = api.shot_inputs(**CLUBS[club], turf="fairway")
    _, path = simulate_traced(inputs, 0)
    last = path[path[:, 4] == FLIGHT][-1]
    return inputs, last[1], last[2]


def test_a_shot_landing_on_a_thin_out_of_bounds_strip_and_running_on_is_in_bounds():
    """A drive whose first impact is on a 2 m strip of out of bounds across the hole, which
    bounces and rolls on beyond it: ok (it touched out-of-bounds ground, and rests in bounds),
    where it rests on the same ground without the strip, to a micrometre: the strip is played
    as the fairway it is made of."""
    inputs, x_land, _ = _carry("driver")
    a, b = x_land - 1.0, x_land + 1.0
    strip = grid(0.0, 320.0, -40.0, 40.0, 0.5, LEVEL, zone=lambda X, Y: (X > a) & (X < b),
                 **FAIRWAY_OB)  # fmt: skip
    plain = grid(0.0, 320.0, -40.0, 40.0, 0.5, LEVEL, zone=lambda X, Y: 0 * X, **FAIRWAY_OB)
    got = simulate_batch(inputs, terrain=strip)[0]
    assert a + 0.25 < got[CARRY] < b - 0.25  # it touched the ground out of bounds
    assert got[STATUS] == OK
    assert got[FINAL_X] > b + 5.0  # it ran on beyond the strip
    assert np.isnan(got[PENALTY_X]) and np.isnan(got[PENALTY_Y])
    same = simulate_batch(inputs, terrain=plain)[0]
    assert same[STATUS] == OK
    assert got[FINAL_X] == pytest.approx(same[FINAL_X], abs=1e-6)
    assert got[FINAL_Y] == pytest.approx(same[FINAL_Y], abs=1e-6)


def test_a_ball_rolling_over_out_of_bounds_and_back_in_is_in_bounds():
    """A ball rolling across a 3 m strip of out of bounds (y from 10 to 13 m) comes to rest
    beyond it, on the hole: ok. A ball rolling into the out of bounds beyond y = 10 m that
    stops there: out_of_bounds, with its reference point where it rests."""
    band = grid(0.0, 60.0, -20.0, 40.0, 0.5, LEVEL, zone=lambda X, Y: (Y > 10.0) & (Y < 13.0),
                **FAIRWAY_OB)  # fmt: skip
    got = landed(band, 20.0, 4.0, 0.0, 8.0, -0.3, turf="fairway")
    assert got[STATUS] == OK
    assert got[FINAL_Y] > 13.5  # it rests beyond the strip, in bounds
    beyond = grid(0.0, 60.0, -20.0, 40.0, 0.5, LEVEL, zone=lambda X, Y: Y > 10.0, **FAIRWAY_OB)
    got = landed(beyond, 20.0, 4.0, 0.0, 8.0, -0.3, turf="fairway")
    assert got[STATUS] == OUT_OF_BOUNDS_STATUS
    assert got[FINAL_Y] > 13.5  # it rolled on into the out of bounds, as it did over the strip
    assert (got[PENALTY_X], got[PENALTY_Y]) == (got[FINAL_X], got[FINAL_Y])


def test_a_shot_coming_to_rest_out_of_bounds_is_out_where_it_rests():
    """A 7-iron landing well inside an out-of-bounds field beyond x = 100 m: it bounces and
    rolls on there (it used to end where it touched it) and is out_of_bounds where it rests."""
    inputs, x_land, _ = _carry("iron")
    assert x_land > 120.0
    field = grid(0.0, 300.0, -40.0, 40.0, 0.5, LEVEL, zone=lambda X, Y: X >= 100.0, **FAIRWAY_OB)
    got = simulate_batch(inputs, terrain=field)[0]
    assert got[STATUS] == OUT_OF_BOUNDS_STATUS
    assert got[FINAL_X] > got[CARRY] + 1.0  # it ran on after the landing
    assert (got[PENALTY_X], got[PENALTY_Y]) == (got[FINAL_X], got[FINAL_Y])
    assert got[CARRY_LATERAL] == pytest.approx(got[FINAL_Y], abs=2.0)


def test_water_still_ends_the_shot_where_the_ball_touches_it():
    """A 7-iron carrying over an out-of-bounds strip into water beyond x = 100 m: penalty_area,
    ending where it lands, its reference point on the water's edge (half a cell before its
    first nodes), not on the strip's. A ball rolling over the strip into the water: the same
    edge."""
    inputs, x_land, _ = _carry("iron")
    water_x = 100.0
    zone = lambda X, Y: np.where(X >= water_x, 2, (X > 95.0) & (X < 98.0))  # noqa: E731
    terrain = grid(0.0, 300.0, -40.0, 40.0, 0.5, LEVEL, zone=zone,
                   turfs=("fairway", "fairway", "fairway"),
                   penalty=(ground.IN_PLAY, ground.OUT_OF_BOUNDS, ground.PENALTY_AREA))  # fmt: skip
    got = simulate_batch(inputs, terrain=terrain)[0]
    assert got[STATUS] == IN_PENALTY_AREA
    assert got[FINAL_X] == got[CARRY]
    assert abs(got[PENALTY_X] - (water_x - 0.25)) < 0.01
    got = landed(terrain, 92.0, 0.0, 9.0, 0.0, -0.3, turf="fairway")
    assert got[STATUS] == IN_PENALTY_AREA
    assert abs(got[PENALTY_X] - (water_x - 0.25)) < 0.01
