"""Shots struck away from the tee (``start_x_m``, ``start_y_m`` of the kernel's inputs): on
ground that is the same everywhere relative to the ball, a shot from elsewhere is the shot from
the tee moved there, so its distances are the same and its positions move with it.

- On the slope model's plane: carry, lateral carry, total, apex and run within 1 um of the shot
  from the tee, the finish moved by the start (translation changes only the rounding).
- On a hole's terrain that is a tilted plane (bilinear interpolation is exact on it): the same,
  and the ball finishes at the height of the tee's finish plus the start's height.
- The recorded path starts at the start, on the ground.
"""

import math

import numpy as np
import pytest

from mcrun import api, ground
from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.schema import (
    APEX,
    BOUNCES,
    CARRY,
    CARRY_LATERAL,
    COLUMN,
    FINAL_X,
    FINAL_Y,
    FINAL_Z,
    RUN,
    STATUS,
    TOTAL,
)
from mcrun.physics.turf import PRESETS
from mcrun.status import OK

DRIVE = dict(
    ball_speed_mps=74.7,
    launch_angle_deg=10.9,
    spin_radps=2686.0 * math.pi / 30.0,
    spin_axis_deg=4.0,
)
WEDGE = dict(
    ball_speed_mps=46.0, launch_angle_deg=24.0, spin_radps=8500.0 * math.pi / 30.0, azimuth_deg=-2.0
)
STARTS = [(0.0, 0.0), (153.25, -12.5), (-40.0, 31.0)]
SAME = (CARRY, CARRY_LATERAL, TOTAL, APEX, RUN)


def _from(inputs, starts):
    """``inputs`` (one row) repeated for each start."""
    rows = np.repeat(inputs, len(starts), axis=0)
    rows[:, COLUMN["start_x_m"]] = [s[0] for s in starts]
    rows[:, COLUMN["start_y_m"]] = [s[1] for s in starts]
    return np.asfortranarray(rows)


def _tilted(slope_x, slope_y):
    """A terrain that is the plane z = slope_x x + slope_y y, 1 m nodes, fairway, big enough
    for a drive from every start."""
    xs = np.arange(-60.0, 501.0)
    ys = np.arange(-80.0, 81.0)
    X, Y = np.meshgrid(xs, ys)
    return ground.make_terrain(
        -60.0, -80.0, 1.0, slope_x * X + slope_y * Y, np.zeros(X.shape, np.int8),
        np.array([PRESETS["fairway"]], np.float64), np.array([ground.IN_PLAY], np.int8),
    )  # fmt: skip


@pytest.mark.parametrize("shot", [DRIVE, WEDGE])
def test_a_shot_from_elsewhere_on_the_plane_is_the_tee_shot_moved(shot):
    inputs, _ = api.shot_inputs(**shot, turf="fairway")
    out = simulate_batch(_from(inputs, STARTS))
    assert (out[:, STATUS] == OK).all()
    for k, (x0, y0) in enumerate(STARTS):
        assert out[k, BOUNCES] == out[0, BOUNCES]
        for col in SAME:
            assert out[k, col] == pytest.approx(out[0, col], abs=1e-6), col
        assert out[k, FINAL_X] == pytest.approx(out[0, FINAL_X] + x0, abs=1e-6)
        assert out[k, FINAL_Y] == pytest.approx(out[0, FINAL_Y] + y0, abs=1e-6)


@pytest.mark.parametrize("slope_x,slope_y", [(0.02, 0.0), (-0.015, 0.01)])
def test_a_shot_from_elsewhere_on_a_tilted_hole_is_the_tee_shot_moved(slope_x, slope_y):
    terrain = _tilted(slope_x, slope_y)
    inputs, _ = api.shot_inputs(**WEDGE)
    out = simulate_batch(_from(inputs, STARTS), terrain=terrain)
    assert (out[:, STATUS] == OK).all()
    for k, (x0, y0) in enumerate(STARTS):
        rise = slope_x * x0 + slope_y * y0
        assert out[k, BOUNCES] == out[0, BOUNCES]
        for col in SAME:
            assert out[k, col] == pytest.approx(out[0, col], abs=1e-6), col
        assert out[k, FINAL_X] == pytest.approx(out[0, FINAL_X] + x0, abs=1e-6)
        assert out[k, FINAL_Y] == pytest.approx(out[0, FINAL_Y] + y0, abs=1e-6)
        assert out[k, FINAL_Z] == pytest.approx(out[0, FINAL_Z] + rise, abs=1e-6)


def test_the_path_starts_at_the_start_on_the_ground():
    terrain = _tilted(0.02, -0.01)
    inputs, _ = api.shot_inputs(**WEDGE)
    rows = _from(inputs, [(120.0, 7.5)])
    out, path = simulate_traced(rows, 0, terrain=terrain)
    assert out[0, STATUS] == OK
    t, x, y, z = path[0, :4]
    assert (t, x, y) == (0.0, 120.0, 7.5)
    assert z == pytest.approx(0.02 * 120.0 - 0.01 * 7.5, abs=1e-12)
    # The apex is above the start: the highest point of the path less the start's height.
    assert out[0, APEX] == pytest.approx(path[:, 3].max() - z, abs=0.05)
    assert math.isfinite(out[0, FINAL_Z])
