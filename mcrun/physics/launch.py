"""Launch: the ball's initial state, from a launch monitor's numbers or from the club delivery.

Club delivery follows Penner's club-ball collision (Penner 2001, Am. J. Phys. 69, 563): the ball
leaves the face rolling, with the normal speed set by the club-ball restitution.
"""

import math

from numba import njit

from mcrun.physics.constants import BALL_MASS_KG, BALL_RADIUS_M
from mcrun.physics.trig import sincos

# The club-head mass of a club delivery that does not give one: Penner's driver, 200 g (Penner
# 2002 section 3.1).
DEFAULT_CLUB_MASS_KG = 0.200


@njit(cache=True)
def club_restitution(normal_speed_mps):
    """Club-ball coefficient of restitution, e_c = 0.86 - 0.0029 V_n (Penner 2001)."""
    return 0.86 - 0.0029 * normal_speed_mps


@njit(cache=True)
def launch_from_club(club_speed_mps, club_mass_kg, loft_rad):
    """Ball speed (m/s), launch angle above horizontal (rad) and backspin (rad/s) of a club
    of mass M delivered at speed v_c with dynamic loft L (face to vertical). Penner (2001)."""
    m = BALL_MASS_KG
    big_m = club_mass_kg
    v_normal_club = club_speed_mps * math.cos(loft_rad)
    v_tangent_club = club_speed_mps * math.sin(loft_rad)
    e_c = club_restitution(v_normal_club)
    v_n = (1.0 + e_c) * big_m / (big_m + m) * v_normal_club
    # The ball rolls off the face: tangential speed and spin of a rolling sphere.
    v_t = (2.0 / 7.0) * big_m / (big_m + 2.0 * m / 7.0) * v_tangent_club
    spin = 2.5 * v_t / BALL_RADIUS_M
    return math.sqrt(v_n * v_n + v_t * v_t), loft_rad - math.atan(v_t / v_n), spin


@njit(cache=True)
def initial_state(speed, launch_angle, azimuth, spin, spin_axis):
    """Velocity and unit spin axis at launch, in the core's frame (x target, y LEFT, z up).

    ``azimuth`` and ``spin_axis`` are positive to the right, as launch monitors report them:
    a positive spin axis tilts the lift to the right and curves the ball right.
    Returns (vx, vy, vz, ax, ay, az, spin) with the axis (ax, ay, az) a unit vector.
    """
    sa, ca = sincos(launch_angle)
    sz, cz = sincos(azimuth)
    vx = speed * ca * cz
    vy = -speed * ca * sz
    vz = speed * sa
    # Pure backspin is about b = v_hat x z_hat (horizontal, to the right of the flight), so
    # that the lift, along w x v, points up_perp = b x v_hat. The spin axis is b tilted about v
    # by spin_axis, w_hat = cos(a) b - sin(a) up_perp, which turns the lift to the right for a > 0.
    hx = cz
    hy = -sz
    bx = hy
    by = -hx
    ux = -sa * hx
    uy = -sa * hy
    uz = ca
    s, c = sincos(spin_axis)
    return vx, vy, vz, c * bx - s * ux, c * by - s * uy, -s * uz, spin
