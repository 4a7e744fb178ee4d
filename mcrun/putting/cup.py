"""The cup: when a rolling ball whose centre crosses the cup's rim drops.

The hole is 4.25 in (108 mm) across (Rules of Golf, Definitions, "Hole"). A ball crossing the cup
at offset ``b`` from its centre (the distance of the centre's path from the cup's centre) has the
chord ``2 sqrt(R^2 - b^2)`` of the rim to cross while it falls; it drops when it is slower than

    v_max(b) = V_CAPTURE_CENTRE_MPS * sqrt(1 - (b / R)^2),

the dead-centre limit scaled with the chord (A. J. Holmes, "Putting: how a golf ball and hole
interact", Am. J. Phys. 59, 129 (1991); A. R. Penner, "The physics of putting", Can. J. Phys. 80,
83-96 (2002), whose dead-centre limit is about 1.63 m/s). A ball that is not captured goes on
with its speed and direction unchanged: the rim's deflection and the lip-outs of a ball that
drops in and climbs out (Hogan and Antali, Royal Society Open Science, 2025) are left out.
"""

import math

from numba import njit

from mcrun.strokes.baseline import HOLE_RADIUS_M

__all__ = ["HOLE_RADIUS_M", "V_CAPTURE_CENTRE_MPS", "capture_speed_mps", "captured"]

# Penner (2002): the largest speed at which a ball crossing the cup dead centre drops.
V_CAPTURE_CENTRE_MPS = 1.63


@njit(cache=True)
def capture_speed_mps(offset_m):
    """The largest speed (m/s) at which a ball crossing the cup at ``offset_m`` drops (0 at and
    beyond the rim)."""
    u = offset_m / HOLE_RADIUS_M
    if u >= 1.0:
        return 0.0
    return V_CAPTURE_CENTRE_MPS * math.sqrt(1.0 - u * u)


@njit(cache=True)
def captured(speed_mps, offset_m):
    """Whether a ball crossing the cup's rim at ``speed_mps`` and ``offset_m`` drops."""
    return speed_mps < capture_speed_mps(offset_m)
