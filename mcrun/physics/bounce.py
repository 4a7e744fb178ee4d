"""The bounce of a golf ball on compliant turf: Penner (2002), section 2, in 3D.

The turf deforms under the ball, so the ball bounces as off a rigid surface tilted by theta_c
towards it (eq. 8); on that equivalent surface Daish's rigid-surface bounce applies: the ball
either slides through the impact (eqs. 2a-2c) or leaves it rolling (3a-3c), whichever the
friction mu against the critical mu_c (4) allows, with the restitution e(v) of eq. (5).

3D vector form (reduces exactly to the paper's equations in the plane of incidence): with the
ground normal n, the horizontal direction t of the incoming velocity and the equivalent normal
n' = n cos(theta_c) - t sin(theta_c), the contact point slips at u = v_t' + w x (-r n'); the
tangential impulse is J = -(2/7) m u (rolling exit, mu >= mu_c = (2/7)|u| / ((1+e)|v.n'|)) or
J = -mu (1+e) m |v.n'| u/|u| (sliding), and v += -(1+e)(v.n') n' + J/m, w += 5/(2 m r) (-n' x J).
"""

import math

from numba import njit

from mcrun.physics.constants import BALL_RADIUS_M, DEG, G_MPS2
from mcrun.physics.trig import atan2_first_quadrant, sincos_first_quadrant
from mcrun.status import MAX_BOUNCES

# Haake's impact (18.6 m/s at 44.4 deg) fitted with theta_c = 15.4 deg: Penner (2002) eq. (8).
THETA_C_REF_RAD = 15.4 * DEG
SPEED_REF_MPS = 18.6
PHI_REF_RAD = 44.4 * DEG


@njit(cache=True, error_model="numpy", inline="always")
def restitution(normal_speed, turf):
    """Ball-turf coefficient of restitution at normal impact speed |v_iy'|, eqs. (5a, 5b)."""
    if normal_speed <= turf.e_break_speed_mps:
        e = turf.e0 + turf.e1 * normal_speed + turf.e2 * normal_speed * normal_speed
    else:
        e = turf.e_high
    return min(max(e, 0.0), 1.0)


@njit(cache=True, error_model="numpy", inline="always")
def no_return_tilt(phi, vt, speed, e):
    """A tilt (rad) of the equivalent surface from which a ball without spin, met at phi from
    the ground's normal (tangential speed vt of ``speed``) and rebounding with restitution e,
    still leaves forwards.

    The slowest forward exit is the rolling one (eq. 3; a sliding exit keeps more of the
    tangential speed): (5/7) v sin(phi - theta) along the equivalent surface and
    e v cos(phi - theta) off it. Its component along the ground, (v/2) [(5/7 - e) sin(phi)
    + (5/7 + e) sin(phi - 2 theta)], is >= 0 for theta <= (phi + asin(y)) / 2 with
    y = k sin(phi), k = (5 - 7e) / (5 + 7e). We take (phi + a) / 2 with a <= asin(y) in one
    division and no arcsine: a = y + y^3 / 6 for y >= 0 (the arcsine's series has no negative
    term), a = 1.0047 y for y < 0 (e <= 1 keeps y >= -1/6, where the arcsine, concave, lies
    above this chord). That is within about 0.01 rad of the largest tilt for eq. (5)'s e; it is at
    least phi / 2 for e <= 5/7 and never exceeds phi.
    """
    # k sin(phi) = (5 - 7e) vt / ((5 + 7e) speed), in one division.
    y = (5.0 - 7.0 * e) * vt / ((5.0 + 7.0 * e) * speed) if speed > 0.0 else 0.0
    return 0.5 * (phi + (y + y * y * y * (1.0 / 6.0) if y >= 0.0 else 1.0047 * y))


@njit(cache=True, error_model="numpy", inline="always")
def equivalent_surface_tilt(speed, phi, vt, normal_speed, turf):
    """theta_c (rad): eq. (8) scaled by the turf's softness, bounded by ``no_return_tilt``.

    Eq. (8) is Penner's fit to one impact (18.6 m/s at 44.4 deg) and grows without bound; far
    from it (fast, shallow impacts) it would tilt the equivalent surface until it faced the
    ball and threw it back. The bound keeps every ball without spin going forwards, with e
    evaluated at ``normal_speed`` = |v.n| of the real ground: the equivalent surface's normal
    speed is larger and e(v) does not grow with speed (``turf.check_turf``), so that e is the
    largest the impact can have and the bound holds for the e it gets. Inside the range where
    the paper uses eq. (8) (18-28 m/s, 34-68 deg) the bound is not reached.
    """
    theta_c = turf.softness * THETA_C_REF_RAD * (speed / SPEED_REF_MPS) * (phi / PHI_REF_RAD)
    return min(theta_c, no_return_tilt(phi, vt, speed, restitution(normal_speed, turf)))


@njit(cache=True, error_model="numpy", inline="always")
def incidence(vx, vy, vz, nx, ny, nz, turf):
    """The first half of ``bounce``: the equivalent surface the ball at velocity v meets on turf
    of normal n. Returns its unit normal (ex, ey, ez), the normal velocity v.e and theta_c."""
    vn = vx * nx + vy * ny + vz * nz
    tx = vx - vn * nx
    ty = vy - vn * ny
    tz = vz - vn * nz
    vt = math.sqrt(tx * tx + ty * ty + tz * tz)
    inverse_vt = 1.0 / vt if vt > 0.0 else 0.0
    tx *= inverse_vt
    ty *= inverse_vt
    tz *= inverse_vt
    speed = math.sqrt(vx * vx + vy * vy + vz * vz)
    phi = atan2_first_quadrant(vt, abs(vn))
    theta_c = equivalent_surface_tilt(speed, phi, vt, abs(vn), turf)
    s, c = sincos_first_quadrant(theta_c)
    # Equivalent surface normal, tilted towards the incoming ball (eqs. 6, 7).
    ex = c * nx - s * tx
    ey = c * ny - s * ty
    ez = c * nz - s * tz
    return ex, ey, ez, vx * ex + vy * ey + vz * ez, theta_c


@njit(cache=True, error_model="numpy", inline="always")
def rebound(vx, vy, vz, wx, wy, wz, ex, ey, ez, vne, turf):
    """The second half of ``bounce``: the impact on the equivalent surface of normal e, met at
    normal velocity vne (``incidence``). Returns (vx, vy, vz, wx, wy, wz, e, mu_c, rolling)."""
    e = restitution(abs(vne), turf)
    # Slip of the contact point at -r n' along the equivalent surface.
    rx = -BALL_RADIUS_M * ex
    ry = -BALL_RADIUS_M * ey
    rz = -BALL_RADIUS_M * ez
    ux = vx - vne * ex + (wy * rz - wz * ry)
    uy = vy - vne * ey + (wz * rx - wx * rz)
    uz = vz - vne * ez + (wx * ry - wy * rx)
    u = math.sqrt(ux * ux + uy * uy + uz * uz)
    # Eq. (4), mu_c = (2/7) |u| / ((1 + e) |v.n'|); the test mu >= mu_c without its division.
    normal_impulse = (1.0 + e) * abs(vne)
    mu_c = (2.0 / 7.0) * u / normal_impulse
    rolling = turf.mu * normal_impulse >= (2.0 / 7.0) * u
    # Eq. (3): a rolling exit brings the slip to zero; eq. (2): sliding, friction throughout.
    f = 2.0 / 7.0 if rolling else turf.mu * normal_impulse / u
    jx = -f * ux
    jy = -f * uy
    jz = -f * uz
    dn = -(1.0 + e) * vne
    # Angular impulse of the contact force at -r n': I dw = (-r n') x J, I = (2/5) m r^2.
    k = 2.5 / (BALL_RADIUS_M * BALL_RADIUS_M)
    return (
        vx + dn * ex + jx,
        vy + dn * ey + jy,
        vz + dn * ez + jz,
        wx + k * (ry * jz - rz * jy),
        wy + k * (rz * jx - rx * jz),
        wz + k * (rx * jy - ry * jx),
        e,
        mu_c,
        rolling,
    )


@njit(cache=True, error_model="numpy", inline="always")
def bounce(vx, vy, vz, wx, wy, wz, nx, ny, nz, turf):
    """One impact on turf of normal n (unit, pointing out of the ground).

    Returns (vx, vy, vz, wx, wy, wz, theta_c_rad, e, mu_c, rolling) after the impact, where
    rolling is True when the ball leaves the equivalent surface rolling (eq. 3), False when it
    slides through the impact (eq. 2). In two halves, ``incidence`` and ``rebound``, that a
    loop over many shots runs one after the other (``batch``).
    """
    ex, ey, ez, vne, theta_c = incidence(vx, vy, vz, nx, ny, nz, turf)
    vx, vy, vz, wx, wy, wz, e, mu_c, rolling = rebound(
        vx, vy, vz, wx, wy, wz, ex, ey, ez, vne, turf
    )
    return vx, vy, vz, wx, wy, wz, theta_c, e, mu_c, rolling


@njit(cache=True, error_model="numpy", inline="always")
def hop_height(vx, vy, vz, nx, ny, nz):
    """Height above the ground plane of a ballistic hop leaving it at velocity v (no air)."""
    vn = vx * nx + vy * ny + vz * nz
    # 1 / (g n_z) is the one division of the hop: its duration is 2 (v.n) / (g n_z).
    return 0.5 * vn * vn * (1.0 / (G_MPS2 * nz)) if vn > 0.0 else 0.0


# The end of the bouncing.
# A hop higher than this fraction of the one before ends the bouncing (``impact``). On level
# turf the hops shrink by 5 % or more each time; on a downhill, gravity along the slope during
# each hop feeds eq. (8)'s growth of theta_c with speed and the hops settle at a height of
# their own (5 mm at 3 deg, 33 mm at 5 deg) instead of dying out.
HOP_DECAY_LIMIT = 0.99

# What follows an impact (``impact``).
HOPS = 0
ROLLS = 1
TOO_MANY = 2


@njit(cache=True, error_model="numpy", inline="always")
def impact(vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, bounces, previous_height):
    """One impact (``bounce``) and what follows it: the velocity and spin after it, the height
    and duration of the hop it starts, and whether the ball HOPS, ROLLS (the hop would be lower
    than the critical height, Penner 2002, or higher than HOP_DECAY_LIMIT times the one
    before) or has bounced TOO_MANY times. Branch-free, for loops over many shots."""
    ex, ey, ez, vne, _ = incidence(vx, vy, vz, nx, ny, nz, turf)
    return impact_rebound(
        vx, vy, vz, wx, wy, wz, nx, ny, nz, ex, ey, ez, vne, turf, bounces, previous_height
    )


@njit(cache=True, error_model="numpy", inline="always")
def impact_rebound(
    vx, vy, vz, wx, wy, wz, nx, ny, nz, ex, ey, ez, vne, turf, bounces, previous_height
):
    """The rest of ``impact`` once ``bounce.incidence`` has found the equivalent surface."""
    vx, vy, vz, wx, wy, wz, _, _, _ = rebound(vx, vy, vz, wx, wy, wz, ex, ey, ez, vne, turf)
    height = hop_height(vx, vy, vz, nx, ny, nz)
    rolls = (height < turf.critical_height_m) | (
        (bounces > 0) & (height > HOP_DECAY_LIMIT * previous_height)
    )
    then = ROLLS if rolls else (TOO_MANY if bounces == MAX_BOUNCES else HOPS)
    # Exact ballistic hop back to the plane: n.(v T - g z T^2 / 2) = 0.
    hop_time = 2.0 * (vx * nx + vy * ny + vz * nz) * (1.0 / (G_MPS2 * nz))
    return vx, vy, vz, wx, wy, wz, height, hop_time, then


@njit(cache=True, error_model="numpy", inline="always")
def hop(x, y, z, vx, vy, vz, hop_time):
    """Position (x, y, z) and vertical velocity at the end of a hop of ``hop_time`` in vacuum."""
    return (
        x + vx * hop_time,
        y + vy * hop_time,
        z + vz * hop_time - 0.5 * G_MPS2 * hop_time * hop_time,
        vz - G_MPS2 * hop_time,
    )


def bounce_in_plane(speed_mps, angle_from_vertical_rad, backspin_radps, turf):
    """One impact on level turf as the paper states it, in the plane of incidence.

    Angles from the vertical, backspin positive. Returns a dict of theta_c_deg, e, mu_c, mode
    ("sliding" or "rolling"), rebound_speed_mps, rebound_angle_deg (from the vertical,
    negative when the ball goes back), rebound_spin_radps (backspin positive) and hop_height_m.
    """
    # In the core's frame (y to the left), backspin about the axis v x z = -y.
    vx = speed_mps * math.sin(angle_from_vertical_rad)
    vz = -speed_mps * math.cos(angle_from_vertical_rad)
    rvx, rvy, rvz, rwx, rwy, rwz, theta_c, e, mu_c, rolling = bounce(
        vx, 0.0, vz, 0.0, -backspin_radps, 0.0, 0.0, 0.0, 1.0, turf
    )
    return {
        "theta_c_deg": math.degrees(theta_c),
        "e": e,
        "mu_c": mu_c,
        "mode": "rolling" if rolling else "sliding",
        "rebound_speed_mps": math.hypot(rvx, rvz),
        "rebound_angle_deg": math.degrees(math.atan2(rvx, rvz)),
        "rebound_spin_radps": -rwy,
        "hop_height_m": hop_height(rvx, rvy, rvz, 0.0, 0.0, 1.0),
    }


def critical_backspin_radps(speed_mps, angle_from_vertical_rad, turf):
    """Backspin above which a rolling exit goes backwards along the equivalent surface, eq. (10).

    omega_c = 5 v_ix' / (2 r), with theta_c from eq. (8) (``equivalent_surface_tilt``).
    """
    theta_c = equivalent_surface_tilt(
        speed_mps,
        angle_from_vertical_rad,
        speed_mps * math.sin(angle_from_vertical_rad),
        speed_mps * math.cos(angle_from_vertical_rad),
        turf,
    )
    v_x_tilted = speed_mps * math.sin(angle_from_vertical_rad - theta_c)  # eq. (6a)
    return 2.5 * v_x_tilted / BALL_RADIUS_M
