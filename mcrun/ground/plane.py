"""A shot's own ground (``terrain`` None in the shot loop): the ``Plane`` of its slope, of one
turf, through the landing point (the slope model)."""

import math
from typing import NamedTuple

from numba import njit

from mcrun.physics.roll import NO_PATCH, Surface
from mcrun.physics.turf import Turf
from mcrun.status import OK


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


@njit(cache=True, error_model="numpy")
def plane_surface(plane, z):
    """``surface`` on a Plane: the ball stays on it (its height is z itself), of one normal and
    turf, always in play, with no limit to a step and no patch."""
    return Surface(z, plane.nx, plane.ny, plane.nz, plane.turf, OK, math.inf, NO_PATCH)
