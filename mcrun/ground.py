"""The ground under the ball: what the shot loop asks of it, and the one kind there is today.

The shot loop (``engine.batch``) does not hold a slope or a turf of its own: at the landing,
at every impact and when the ball settles into its roll it asks the ground under the ball for

- ``height_at(ground, x, y)``: the height of its surface (m), where the flight ends;
- ``normal_at(ground, x, y)``: its unit normal, in the core's frame (y to the LEFT);
- ``turf_at(ground, x, y)``: the turf there (``physics.turf.Turf``).

Today's one kind is ``Plane``: the flight ends at z = 0, and the landing area is the plane of
the shot's slope through the landing point, of one turf, built from the shot's own input row
(``plane_of``). A terrain and turf zones (a real hole) are other kinds behind the same three
functions, which is all the loop needs to change to play them.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from mcrun.physics.turf import Turf


# What a zone of a Terrain is for the Rules (``Terrain.penalty``).
IN_PLAY = 0
PENALTY_AREA = 1  # water: the ball is not played from there
OUT_OF_BOUNDS = 2


class Terrain(NamedTuple):
    """A hole's ground on a regular grid, in the hole's frame: x (m) from the tee towards the
    pin, y (m) to the RIGHT of that line, heights (m) relative to the ground at the tee.

    Node [iy, ix] lies at (x0_m + ix cell_m, y0_m + iy cell_m); the height between nodes is
    bilinear, the zone is that of the nearest node. Its arrays are shared by every thread.
    """

    x0_m: float
    y0_m: float
    cell_m: float
    height_m: np.ndarray  # (ny, nx) float64
    zone: np.ndarray  # (ny, nx) int8: a row of ``turf`` and ``penalty``
    turf: np.ndarray  # (n_zones, len(Turf._fields)) float64: each zone's Turf, in its order
    penalty: np.ndarray  # (n_zones,) int8: IN_PLAY, PENALTY_AREA or OUT_OF_BOUNDS


class Plane(NamedTuple):
    """A plane of one turf: the landing area of one shot."""

    nx: float  # unit normal, core frame
    ny: float
    nz: float
    turf: Turf


@njit(cache=True, error_model="numpy")
def plane(slope, fall_line, turf):
    """The Plane of the given slope (rad) falling towards ``fall_line`` (rad from the target
    line, positive to the RIGHT): its normal tilts towards the fall line, which is
    (cos a, -sin a, 0) in the core's frame."""
    if slope == 0.0:
        return Plane(0.0, 0.0, 1.0, turf)
    sb = math.sin(slope)
    return Plane(sb * math.cos(fall_line), -sb * math.sin(fall_line), math.cos(slope), turf)


@njit(cache=True, error_model="numpy", inline="always")
def height_at(ground, x, y):
    """Height (m) of the ground's surface at (x, y): where the flight ends. The plane through
    the landing point is the landing area; the flight comes down to z = 0."""
    return 0.0


@njit(cache=True, error_model="numpy", inline="always")
def normal_at(ground, x, y):
    """Unit normal (nx, ny, nz) of the ground at (x, y), core frame."""
    return ground.nx, ground.ny, ground.nz


@njit(cache=True, error_model="numpy", inline="always")
def turf_at(ground, x, y):
    """The turf of the ground at (x, y)."""
    return ground.turf
