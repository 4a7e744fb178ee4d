"""Turf: what the bounce and the roll need to know about the ground, and the presets.

The paper's green and firm green are Penner (2002); fairway and rough are ENGINEERING
ESTIMATES (no published bounce measurements exist for them), labelled so in ``PRESETS``; the
fairway's softness is calibrated to the Tour's driver roll-out.
"""

import numbers
from typing import NamedTuple

import numpy as np

from mcrun.physics.constants import G_MPS2

# Stimpmeter: the ball leaves the ramp at 1.83 m/s (USGA); a green of reading S_t (m)
# decelerates a rolling ball at a = v0^2 / (2 S_t).
STIMP_LAUNCH_SPEED_MPS = 1.83
# A green's drift: the sideways spread of a rolling ball, mm per metre rolled (the putting
# roll's random walk, ``putting.greens``): 4.9 on pure creeping bentgrass (Virginia Tech, Crop
# Science 2018); allowed from 0 (a perfect green) to twice the worst measured (17 mm/m).
GREEN_DRIFT_MM_PER_M = 4.9
GREEN_DRIFT_RANGE_MM_PER_M = (0.0, 34.0)


class Turf(NamedTuple):
    """A turf, in SI. ``e_*`` are the coefficients of Penner (2002) eq. (5)."""

    mu: float  # ball-turf kinetic friction
    softness: float  # scale on theta_c of eq. (8); 1 = the paper's green
    e0: float  # e = e0 + e1 |v| + e2 |v|^2 for |v| <= e_break_speed_mps (5a)
    e1: float
    e2: float
    e_break_speed_mps: float
    e_high: float  # e above the break speed (5b)
    rho_g: float  # rolling resistance of eq. (9)
    critical_height_m: float  # below this hop height the ball rolls


def rho_g_from_stimp(stimp_m):
    """Rolling resistance rho_g of a green with Stimpmeter reading ``stimp_m`` (metres).

    a = v0^2 / (2 S_t) and a = (5/7) rho_g g (Penner 2002 eq. 9), so rho_g = (7/5) a / g.
    The paper's rho_g = 0.131 is a Stimp of 1.82 m (6.0 ft), a slow green. Accepts arrays.
    """
    if not np.all(np.asarray(stimp_m) > 0):
        raise ValueError(f"a Stimpmeter reading must be positive, got {stimp_m} m")
    return 1.4 * STIMP_LAUNCH_SPEED_MPS**2 / (2.0 * stimp_m) / G_MPS2


def stimp_from_rho_g(rho_g):
    """Stimpmeter reading (m) of a green with rolling resistance rho_g: infinite for rho_g 0 (no
    rolling resistance: the ball never stops on the level). Accepts arrays."""
    rho_g = np.asarray(rho_g, dtype=float)
    with np.errstate(divide="ignore"):
        stimp_m = 1.4 * STIMP_LAUNCH_SPEED_MPS**2 / (2.0 * rho_g * G_MPS2)
    return float(stimp_m) if stimp_m.ndim == 0 else stimp_m


# Penner (2002) eq. (5): e(v) measured on relatively soft turf (Penner 2001).
_PAPER_E = dict(e0=0.510, e1=-0.0375, e2=0.000903, e_break_speed_mps=20.0, e_high=0.120)

PRESETS = {
    # Penner (2002): mu 0.40 (Daish), rho_g 0.131, h_c 5 mm, theta_c from eq. (8).
    "green": Turf(mu=0.40, softness=1.0, rho_g=0.131, critical_height_m=0.005, **_PAPER_E),
    # Penner (2002) Fig. 8: the firm tournament green, mu 0.25, all else as the green.
    "firm_green": Turf(mu=0.25, softness=1.0, rho_g=0.131, critical_height_m=0.005, **_PAPER_E),
    # CALIBRATED ESTIMATE: fairway. rho_g 0.20 (a Stimp of about 1.19 m, 3.9 ft: fairways are
    # mown longer than greens); the paper's e(v) and mu; softness 1.1, calibrated so that the
    # PGA Tour's average drive (TrackMan 2019: 167 mph, 10.9 deg, 2686 rpm; default aero model,
    # 20 C) rolls out 18.6 yd, inside the 15-22 yd of Tour drives on Tour fairways: the PGA
    # Tour's 100th-ranked driver of 2017 carried 277 yd for 292 yd measured, in 2007 266 yd for
    # 288.5 yd. The roll-out is nearly all bounces: softness 1.0 gives 25.3 yd, 1.2 gives 12.8,
    # while rho_g 0.20 -> 0.30 takes off 0.5 yd and mu changes nothing (the drive leaves its
    # bounces rolling). Irons and wedges then roll little: PGA 5-iron 6.6 yd, 7-iron 1.8 yd,
    # PW -0.2 yd (docs/model.md, "Turf").
    "fairway": Turf(mu=0.40, softness=1.1, rho_g=0.20, critical_height_m=0.005, **_PAPER_E),
    # ESTIMATE: rough. rho_g 0.50 (a Stimp of about 0.48 m, 1.6 ft), more friction, and a
    # softer surface (theta_c x 1.5: the ball sinks deeper into long grass).
    "rough": Turf(mu=0.60, softness=1.5, rho_g=0.50, critical_height_m=0.005, **_PAPER_E),
    # ESTIMATE: fringe (collar): mown between green and fairway height, so its rolling
    # resistance lies between theirs: rho_g 0.16 (a Stimp of about 1.49 m, 4.9 ft); bounce as
    # the paper's green.
    "fringe": Turf(mu=0.40, softness=1.0, rho_g=0.16, critical_height_m=0.005, **_PAPER_E),
    # ESTIMATE: tee: mown and kept as a fairway, so the fairway's mowing (rho_g) and the
    # paper's bounce (the fairway's softness is calibrated to drives landing on a fairway).
    "tee": Turf(mu=0.40, softness=1.0, rho_g=0.20, critical_height_m=0.005, **_PAPER_E),
    # ESTIMATE: bunker sand. No bounce fit of a golf ball on sand is published. A sphere
    # dropped onto loose sand penetrates and does not rebound (Uehara et al. 2003, "Low-speed
    # impact craters in loose granular media", Phys. Rev. Lett. 90, 194301); bunker sands are
    # judged by how the ball plugs and lies (Science and Golf IV, 2002, "playing quality of
    # bunker sands"). So: the paper's e(v) scaled by 0.4 (e = 0.20 at low speed, 0.05 at
    # 20 m/s and above), theta_c x 3 (the ball sinks into the sand), mu 0.70 and rho_g 1.0: a
    # ball landing at 2 m/s stops within about 0.3 m (v^2 / (2 (5/7) rho_g g)).
    "bunker": Turf(
        mu=0.70,
        softness=3.0,
        e0=0.204,
        e1=-0.015,
        e2=0.000361,
        e_break_speed_mps=20.0,
        e_high=0.048,
        rho_g=1.0,
        critical_height_m=0.005,
    ),
}

ESTIMATED_PRESETS = ("fairway", "rough", "fringe", "tee", "bunker")


def turf_preset(name):
    """The preset called ``name``; ValueError naming the choices."""
    try:
        return PRESETS[name]
    except KeyError:
        raise ValueError(f"unknown turf '{name}': choose one of {', '.join(PRESETS)}") from None


# The allowed range (inclusive, SI) of each Turf field that has one; the restitution
# coefficients e0, e1, e2 are bounded by the rule of check_turf instead.
LIMITS = {
    "mu": (0.0, 2.0),
    "softness": (0.0, 5.0),
    "e_break_speed_mps": (0.0, 200.0),
    "e_high": (0.0, 1.0),
    "rho_g": (0.0, 5.0),
    # A hop below it rolls: 0 would never roll, which the kernel refuses as an invalid input.
    "critical_height_m": (1e-4, 1.0),
}


def check_turf(turf):
    """ValueError with one line naming the first out-of-range field of ``turf``."""
    for field in turf._fields:
        value = getattr(turf, field)
        if not isinstance(value, numbers.Real) or isinstance(value, bool):
            raise ValueError(f"turf {field} must be a number, got {value!r}")
    for field, (lo, hi) in LIMITS.items():
        value = getattr(turf, field)
        if not lo <= value <= hi:
            raise ValueError(f"turf {field} = {value} is outside [{lo}, {hi}]")
    for field in ("e0", "e1", "e2"):
        if not abs(getattr(turf, field)) < 10.0:
            raise ValueError(f"turf {field} = {getattr(turf, field)} is not a finite coefficient")
    # e(v) must not grow with the impact speed, as no measured restitution does: the bound on
    # theta_c (bounce.equivalent_surface_tilt) relies on it. The slope of the quadratic (5a)
    # is linear in v, so its ends decide; (5b) must not jump above (5a) at the break.
    v = turf.e_break_speed_mps
    at_break = turf.e0 + turf.e1 * v + turf.e2 * v * v
    if turf.e1 > 0.0 or turf.e1 + 2.0 * turf.e2 * v > 0.0 or turf.e_high > max(at_break, 0.0):
        raise ValueError(
            f"turf restitution e0 + e1 v + e2 v^2 = {turf.e0:g} + {turf.e1:g} v + {turf.e2:g} "
            f"v^2 up to {v:g} m/s, then {turf.e_high:g}, grows with the impact speed: it must not"
        )
    return turf
