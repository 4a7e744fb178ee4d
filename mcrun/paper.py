"""``mcrun paper -o DIR``: Penner (2002) redrawn from our model, and every number beside his.

Writes ``fig3.png`` ... ``fig8.png`` (the paper's Figs. 3-8) and ``targets.md``: each number the
paper states (bounce, launch, flight and the figures), the paper's value, ours and the difference.
Ours are computed here, live, from the physics core; the paper's are the table ``PAPER_VALUES``
below, each with the place the paper states it.

How each figure is made:
- Fig. 3: Haake's impact (18.6 m/s at 44.4 deg, 484 rad/s backspin) through ``bounce_once``
  with theta_c = 15.4 deg, beside his measured rebound.
- Figs. 4 and 6: full shots from the club (Penner 2001 club model, ``penner2002`` aerodynamics in
  air of 1.204 kg/m^3, the paper's green), ``api.simulate(..., trajectory=True)``.
- Fig. 5: a sweep of the driver's club-head speed, run against launch speed.
- Figs. 7 and 8: the paper's 9-iron LANDING state run through the shot loop from its landing on
  (``backend.simulate_landed``).

matplotlib is optional (``mcrun[plot]``): it is imported only when a figure is drawn, and figures
are rendered with the Agg canvas, so no display is needed.
"""

import math
import textwrap
from pathlib import Path

import numpy as np

from mcrun import __version__
from mcrun.api import bounce_once, simulate
from mcrun.engine.backend import simulate_landed
from mcrun.engine.schema import (
    BOUNCES,
    COLUMN,
    FIRST_BOUNCE_HEIGHT,
    FIRST_BOUNCE_LENGTH,
    N_INPUT,
    STATUS,
    TOTAL,
)
from mcrun.engine.shot import DEFAULT_DT_S
from mcrun.physics.bounce import critical_backspin_radps
from mcrun.physics.launch import launch_from_club
from mcrun.physics.turf import PRESETS
from mcrun.status import NAMES, OK
from mcrun.trajectory import BOUNCE, FLIGHT, ROLL

MISSING_MATPLOTLIB = "mcrun paper needs matplotlib: pip install 'mcrun[plot]'"

# --- the paper's shots -------------------------------------------------------------------------

# Section 3: Penner flew his balls with Bearman and Harvey's coefficients in air of 1.204 kg/m^3.
PENNER_AIR = {"aero_model": "penner2002", "air_density_kgpm3": 1.204}
# Section 3.1: drives, club-head 0.200 kg, dynamic loft 13.3 deg.
DRIVER = {"club_mass_kg": 0.200, "loft_deg": 13.3}
DRIVE_CLUB_SPEEDS_MPS = (35.0, 45.0, 55.0)
# Fig. 5: the sweep of club-head speed (launch speeds of about 42 to 81 m/s).
SWEEP_CLUB_SPEEDS_MPS = tuple(float(v) for v in range(30, 61))
# Section 3.2: irons, club-head 0.250 kg at 40 m/s; loft 17 deg (1-iron) to 46 deg (9-iron).
IRON_MASS_KG = 0.250
IRON_CLUB_SPEED_MPS = 40.0
FIG6_IRONS = (2, 4, 6)
# Section 3.2: the 9-iron lands at 23.8 m/s, 34.0 deg from the vertical; Figs. 7 and 8 give it
# these backspins.
NINE_IRON_LANDING = (23.8, 34.0)
NINE_IRON_SPINS_RADPS = (809.0, 1000.0, 1200.0)
# Section 2: Haake's (1990) impact and measured rebound.
HAAKE_IMPACT = (18.6, 44.4, 484.0)  # m/s, deg from the vertical, backspin rad/s
HAAKE_REBOUND = (5.1, 33.0, 145.0)  # m/s, deg from the vertical, topspin rad/s
PAPER_MODEL_REBOUND = (4.34, 34.1, 154.0)  # what the paper's Fig. 3b quotes

# Trajectory sampling of the figures (s): fine enough that a sampled hop meets the ground within
# a few mm (the hops of the run last 0.1-1.5 s and the ball moves at under 10 m/s).
PLOT_DT_S = 0.0005

# Size of each figure (inches); the PNG is this times the dpi, in pixels.
FIGURE_SIZES_IN = {
    "fig3": (10.0, 5.0),
    "fig4": (8.0, 7.5),
    "fig5": (8.0, 5.6),
    "fig6": (8.0, 7.5),
    "fig7": (8.0, 7.5),
    "fig8": (8.0, 7.5),
}
DEFAULT_DPI = 150


def iron_loft_deg(number):
    """Loft of an n-iron, interpolated from 17 deg (1-iron) to 46 deg (9-iron) in 3.625 deg
    steps. The paper gives only the ends of the range (section 3.2): an assumption of ours."""
    return 17.0 + 3.625 * (number - 1)


def drive(club_speed_mps, trajectory=False):
    """A drive of section 3.1 (and Figs. 4, 5) from the club, to rest on the paper's green."""
    dt = PLOT_DT_S if trajectory else DEFAULT_DT_S
    result = simulate(
        club_speed_mps=club_speed_mps,
        turf="green",
        trajectory=trajectory,
        dt_s=dt,
        **DRIVER,
        **PENNER_AIR,
    )
    return _checked(result, f"drive at {club_speed_mps:g} m/s")


def iron(number, trajectory=False):
    """An iron of section 3.2 (and Fig. 6) from the club, to rest on the paper's green."""
    dt = PLOT_DT_S if trajectory else DEFAULT_DT_S
    result = simulate(
        club_speed_mps=IRON_CLUB_SPEED_MPS,
        club_mass_kg=IRON_MASS_KG,
        loft_deg=iron_loft_deg(number),
        turf="green",
        trajectory=trajectory,
        dt_s=dt,
        **PENNER_AIR,
    )
    return _checked(result, f"{number}-iron")


def _checked(result, what):
    if result.outcome["status"] != OK:
        raise RuntimeError(f"the {what} ended with status {result.status_name}")
    return result


def run_from_landing(speed_mps, angle_deg, backspin_radps, turf, trajectory=False):
    """Bounces and roll (the shot loop from the landing on, ``backend.simulate_landed``) of a
    ball landing on level turf at the origin.

    The ball moves along +x at ``speed_mps``, ``angle_deg`` from the vertical, with
    ``backspin_radps`` of backspin. Returns (summary, path): summary has final_x_m, bounces,
    first_bounce_height_m and first_bounce_length_m (the first hop lands at
    x = first_bounce_length_m); path is None, or with ``trajectory`` an array of rows
    (t_s, x_m, y_m, z_m, phase) starting at the landing point, sampled every PLOT_DT_S.
    """
    a = math.radians(angle_deg)
    row = np.zeros((1, N_INPUT))
    for field, value in PRESETS[turf]._asdict().items():
        row[0, COLUMN[field]] = value
    # Core frame (y to the left): backspin is spin about v x z = -y.
    landing = [[0.0, 0.0, speed_mps * math.sin(a), 0.0, -speed_mps * math.cos(a), 0.0,
                -backspin_radps, 0.0, 0.0, 0.0, 0.0, 1.0]]  # fmt: skip
    out, path = simulate_landed(
        row, np.array(landing), traced=0 if trajectory else -1, dt_record_s=PLOT_DT_S
    )
    x, status, bounces = out[0, TOTAL], int(out[0, STATUS]), int(out[0, BOUNCES])
    height, length = out[0, FIRST_BOUNCE_HEIGHT], out[0, FIRST_BOUNCE_LENGTH]
    if status != OK:
        raise RuntimeError(f"the run from landing ended with status {NAMES[status]}")
    summary = {
        "final_x_m": x,
        "bounces": bounces,
        "first_bounce_height_m": height,
        "first_bounce_length_m": length,
    }
    if not trajectory:
        return summary, None
    return summary, np.vstack([[[0.0, 0.0, 0.0, 0.0, float(BOUNCE)]], path])


def nine_iron_run(backspin_radps, turf, trajectory=False):
    """Figs. 7 and 8: the 9-iron's landing (23.8 m/s at 34.0 deg) with the given backspin."""
    return run_from_landing(*NINE_IRON_LANDING, backspin_radps, turf, trajectory)


def backward_run_m(summary):
    """How far the ball runs back after the first bounce (Fig. 8): from the first hop's landing
    point to rest, positive towards the player."""
    return summary["first_bounce_length_m"] - summary["final_x_m"]


# --- the paper's numbers -----------------------------------------------------------------------

BOUNCE_TABLE = "Bounce model alone (eqs. 4-8, 10; the paper's landing states, level turf)"
LAUNCH_TABLE = "Launch (club model of Penner 2001)"
FLIGHT_TABLE = "Flight (aero model penner2002, air 1.204 kg/m^3)"
RUN_TABLE = "Whole run (the figures; full shots from the club, or the 9-iron's landing)"

D35 = "drive, 35 m/s club: lands 26.8 m/s at 68.0 deg, 224 rad/s, mu 0.40"
D55 = "drive, 55 m/s club: lands 26.2 m/s at 46.2 deg, 315 rad/s, mu 0.40"
NINE = "9-iron: lands 23.8 m/s at 34.0 deg"
FIRM = "9-iron, firm green (mu 0.25), 809 / 1000 / 1200 rad/s"
HAAKE = "Haake: 18.6 m/s at 44.4 deg, 484 rad/s, theta_c 15.4 deg"
HAAKE_MEASURED = "Haake, measured rebound (vs our model)"


def _nine_green(w):
    return f"9-iron, {w:g} rad/s, green (mu 0.40)"


def _fig4_case(v):
    return f"Fig. 4, drive, {v:g} m/s club"


def _fig6_case(number):
    return f"Fig. 6, {number}-iron (loft {iron_loft_deg(number):.3f} deg, assumed)"


def _fig7_case(w):
    return f"Fig. 7, 9-iron landing, {w:g} rad/s, green"


def _fig8_case(w):
    return f"Fig. 8, 9-iron landing, {w:g} rad/s, firm green"


MU_C = "mu_c, eq. (4)"
EXIT = "leaves the impact"
DIRECTION = "rebound direction"
REBOUND_SPIN = "spin after the impact"
SAME_HOP = "first hop for the three spins"
CRITICAL = "critical backspin, eq. (10) (rad/s)"
THETA_C = "theta_c, eq. (8) (deg)"
E = "e, eq. (5)"
FIRST_HEIGHT = "first bounce height (m)"
BALL_SPEED = "ball speed (m/s)"
LAUNCH_ANGLE = "launch angle above horizontal (deg)"
BACKSPIN = "backspin (rad/s)"
LANDING_SPEED = "landing speed (m/s)"
LANDING_ANGLE = "landing angle from vertical (deg)"
LANDING_SPIN = "landing backspin (rad/s)"
REBOUND_SPEED = "rebound speed (m/s)"
REBOUND_ANGLE = "rebound angle from vertical (deg)"
REBOUND_TOPSPIN = "rebound topspin (rad/s)"
RUN = "run, landing to rest (m)"
IMPACT_ANGLE = "impact angle from vertical (deg)"
REST = "rest, from the landing point (m)"
BACK_RUN = "run back after the first bounce (m)"
FIG4_TREND = ("Fig. 4, drives 35 / 45 / 55 m/s club", "run as club speed rises")
FIG5_TREND = ("Fig. 5, drives 30-60 m/s club", "run as launch speed falls")
FIG7_TREND = ("Fig. 7, 809 / 1000 / 1200 rad/s", "backward bounce and roll as backspin rises")

# Where the paper states each number.
SEC2 = "Penner 2002 section 2"
SEC31 = "Penner 2002 section 3.1"
SEC32 = "Penner 2002 section 3.2"
FIG3A = "Penner 2002 section 2 (Haake 1990), Fig. 3a"
FIG3B = "Penner 2002 section 2, Fig. 3b"
FIG4 = "Penner 2002 section 3.1, Fig. 4"
FIG5 = "Penner 2002 section 3.1, Fig. 5"
FIG6 = "Penner 2002 section 3.2, Fig. 6"
FIG7 = "Penner 2002 section 3.2, Fig. 7"
FIG8 = "Penner 2002 section 3.2, Fig. 8"

# The paper's flights (section 3): launch (m/s, deg above horizontal, rad/s) -> landing (m/s,
# deg from the vertical, rad/s), and where it says so.
FLIGHTS = {
    "driver 35 m/s": ((48.8, 10.7, 253.0), (26.8, 68.0, 224.0), SEC31),
    "driver 55 m/s": ((74.3, 10.7, 397.0), (26.2, 46.2, 315.0), SEC31),
    "1-iron": ((56.6, 13.8, 372.0), (24.7, 51.9, 313.0), SEC32),
    "9-iron": ((42.5, 35.4, 915.0), (23.8, 34.0, 809.0), SEC32),
}
# The paper's launches from the club (sections 3.1, 3.2): (club speed m/s, head mass kg,
# loft deg) -> (ball speed m/s, launch angle deg, backspin rad/s).
LAUNCHES = {
    "driver 35 m/s": ((35.0, 0.200, 13.3), (48.8, 10.7, 253.0), SEC31),
    "driver 55 m/s": ((55.0, 0.200, 13.3), (74.3, 10.7, 397.0), SEC31),
    "1-iron": ((40.0, 0.250, 17.0), (56.6, 13.8, 372.0), SEC32),
    "9-iron": ((40.0, 0.250, 46.0), (42.5, 35.4, 915.0), SEC32),
}


def _launch_case(name):
    (club_speed, mass, loft), _, _ = LAUNCHES[name]
    return f"{name.split()[0]}, {mass:.3f} kg, loft {loft:g} deg, {club_speed:g} m/s"


def _flight_case(name):
    launch = FLIGHTS[name][0]
    return f"{name}: launch {launch[0]:g} m/s, {launch[1]:g} deg, {launch[2]:g} rad/s"


# (table, case, quantity, paper's value, decimals the paper prints, where the paper states it).
# A str value is qualitative; None: the paper draws it but gives no number (ours is shown).
PAPER_VALUES = (
    (BOUNCE_TABLE, D35, MU_C, 0.23, 2, SEC31),
    (BOUNCE_TABLE, D35, EXIT, "rolling", 0, SEC31),
    (BOUNCE_TABLE, D35, FIRST_HEIGHT, 2.82, 2, SEC31),
    (BOUNCE_TABLE, D55, MU_C, 0.18, 2, SEC31),
    (BOUNCE_TABLE, D55, EXIT, "rolling", 0, SEC31),
    (BOUNCE_TABLE, D55, FIRST_HEIGHT, 1.17, 2, SEC31),
    (BOUNCE_TABLE, NINE, CRITICAL, 903.0, 0, SEC32),
    *(
        row
        for w, mu_c in zip(NINE_IRON_SPINS_RADPS, (0.28, 0.33, 0.38), strict=True)
        for row in (
            (BOUNCE_TABLE, _nine_green(w), MU_C, mu_c, 2, FIG7),
            (BOUNCE_TABLE, _nine_green(w), EXIT, "rolling", 0, FIG7),
            (BOUNCE_TABLE, _nine_green(w), DIRECTION, "backward", 0, FIG7),
        )
    ),
    (BOUNCE_TABLE, FIRM, EXIT, "sliding", 0, FIG8),
    (BOUNCE_TABLE, FIRM, DIRECTION, "forward", 0, FIG8),
    (BOUNCE_TABLE, FIRM, REBOUND_SPIN, "backspin", 0, FIG8),
    (BOUNCE_TABLE, FIRM, SAME_HOP, "identical", 0, FIG8),
    (BOUNCE_TABLE, HAAKE, THETA_C, 15.4, 1, SEC2),
    # The printed equations give 0.30 (targets.md); the paper prints 0.29.
    (BOUNCE_TABLE, HAAKE, MU_C, 0.29, 2, SEC2),
    (BOUNCE_TABLE, HAAKE, E, 0.14, 2, SEC2),
    (BOUNCE_TABLE, HAAKE, EXIT, "rolling", 0, SEC2),
    (BOUNCE_TABLE, HAAKE, REBOUND_SPIN, "topspin", 0, SEC2),
    # The paper's own model rebound (Fig. 3b); its printed equations give about 4.16 m/s,
    # 41.7 deg, 163 rad/s (physics.md): the equations are what we implement.
    (BOUNCE_TABLE, HAAKE, REBOUND_SPEED, PAPER_MODEL_REBOUND[0], 2, FIG3B),
    (BOUNCE_TABLE, HAAKE, REBOUND_ANGLE, PAPER_MODEL_REBOUND[1], 1, FIG3B),
    (BOUNCE_TABLE, HAAKE, REBOUND_TOPSPIN, PAPER_MODEL_REBOUND[2], 0, FIG3B),
    (BOUNCE_TABLE, HAAKE_MEASURED, REBOUND_SPEED, HAAKE_REBOUND[0], 1, FIG3A),
    (BOUNCE_TABLE, HAAKE_MEASURED, REBOUND_ANGLE, HAAKE_REBOUND[1], 1, FIG3A),
    (BOUNCE_TABLE, HAAKE_MEASURED, REBOUND_TOPSPIN, HAAKE_REBOUND[2], 0, FIG3A),
    *(
        row
        for name, (_, ball, source) in LAUNCHES.items()
        for row in (
            (LAUNCH_TABLE, _launch_case(name), BALL_SPEED, ball[0], 1, source),
            (LAUNCH_TABLE, _launch_case(name), LAUNCH_ANGLE, ball[1], 1, source),
            (LAUNCH_TABLE, _launch_case(name), BACKSPIN, ball[2], 0, source),
        )
    ),
    *(
        row
        for name, (_, landing, source) in FLIGHTS.items()
        for row in (
            (FLIGHT_TABLE, _flight_case(name), LANDING_SPEED, landing[0], 1, source),
            (FLIGHT_TABLE, _flight_case(name), LANDING_ANGLE, landing[1], 1, source),
            (FLIGHT_TABLE, _flight_case(name), LANDING_SPIN, landing[2], 0, source),
        )
    ),
    (RUN_TABLE, _fig4_case(35), FIRST_HEIGHT, 2.82, 2, FIG4),
    (RUN_TABLE, _fig4_case(35), RUN, None, 1, FIG4),
    (RUN_TABLE, _fig4_case(45), FIRST_HEIGHT, None, 2, FIG4),
    (RUN_TABLE, _fig4_case(45), RUN, None, 1, FIG4),
    (RUN_TABLE, _fig4_case(55), FIRST_HEIGHT, 1.17, 2, FIG4),
    (RUN_TABLE, _fig4_case(55), RUN, None, 1, FIG4),
    (RUN_TABLE, *FIG4_TREND, "decreases", 0, FIG4),
    (RUN_TABLE, *FIG5_TREND, "grows", 0, FIG5),
    (RUN_TABLE, _fig6_case(2), IMPACT_ANGLE, 42.8, 1, FIG6),
    (RUN_TABLE, _fig6_case(2), FIRST_HEIGHT, 0.97, 2, FIG6),
    (RUN_TABLE, _fig6_case(4), IMPACT_ANGLE, None, 1, FIG6),
    (RUN_TABLE, _fig6_case(4), FIRST_HEIGHT, None, 2, FIG6),
    (RUN_TABLE, _fig6_case(6), IMPACT_ANGLE, 36.3, 1, FIG6),
    (RUN_TABLE, _fig6_case(6), FIRST_HEIGHT, 0.54, 2, FIG6),
    *((RUN_TABLE, _fig7_case(w), REST, None, 2, FIG7) for w in NINE_IRON_SPINS_RADPS),
    (RUN_TABLE, *FIG7_TREND, "grows", 0, FIG7),
    (RUN_TABLE, _fig8_case(809), BACK_RUN, "negligible", 2, FIG8),
    (RUN_TABLE, _fig8_case(1000), BACK_RUN, 1.11, 2, FIG8),
    (RUN_TABLE, _fig8_case(1200), BACK_RUN, 4.74, 2, FIG8),
)

# Below this a backward run is "negligible" (a ball's radius is 21 mm).
NEGLIGIBLE_M = 0.05


def _direction(angle_from_vertical_deg):
    return "backward" if angle_from_vertical_deg < 0.0 else "forward"


def _spin_sense(backspin_radps):
    return "backspin" if backspin_radps > 0.0 else "topspin"


def _trend(values):
    """'grows', 'decreases' or 'not monotonic': how a sequence changes, in its order."""
    steps = np.diff(values)
    if np.all(steps > 0.0):
        return "grows"
    if np.all(steps < 0.0):
        return "decreases"
    return "not monotonic"


def our_values():
    """Our value of every row of ``PAPER_VALUES``, keyed (case, quantity), from the core."""
    ours = {}
    # Bounce model alone, from the paper's landing states.
    for case, impact in ((D35, (26.8, 68.0, 224.0)), (D55, (26.2, 46.2, 315.0))):
        b = bounce_once(*impact, turf="green")
        ours[case, MU_C] = b["mu_c"]
        ours[case, EXIT] = b["mode"]
        ours[case, FIRST_HEIGHT] = b["hop_height_m"]
    speed, angle = NINE_IRON_LANDING
    ours[NINE, CRITICAL] = critical_backspin_radps(speed, math.radians(angle), PRESETS["green"])
    for w in NINE_IRON_SPINS_RADPS:
        b = bounce_once(speed, angle, w, turf="green")
        ours[_nine_green(w), MU_C] = b["mu_c"]
        ours[_nine_green(w), EXIT] = b["mode"]
        ours[_nine_green(w), DIRECTION] = _direction(b["rebound_angle_deg"])
    firm = [bounce_once(speed, angle, w, turf="firm_green") for w in NINE_IRON_SPINS_RADPS]
    ours[FIRM, EXIT] = " / ".join(sorted({b["mode"] for b in firm}))
    ours[FIRM, DIRECTION] = " / ".join(sorted({_direction(b["rebound_angle_deg"]) for b in firm}))
    ours[FIRM, REBOUND_SPIN] = " / ".join(
        sorted({_spin_sense(b["rebound_spin_radps"]) for b in firm})
    )
    # Eqs. (2a, 2b) do not involve the spin: the same hop, to rounding.
    same = all(
        math.isclose(b[k], firm[0][k], rel_tol=1e-12)
        for b in firm
        for k in ("rebound_speed_mps", "rebound_angle_deg", "hop_height_m")
    )
    ours[FIRM, SAME_HOP] = "identical" if same else "different"
    b = bounce_once(*HAAKE_IMPACT, turf="green")
    ours[HAAKE, THETA_C] = b["theta_c_deg"]
    ours[HAAKE, MU_C] = b["mu_c"]
    ours[HAAKE, E] = b["e"]
    ours[HAAKE, EXIT] = b["mode"]
    ours[HAAKE, REBOUND_SPIN] = _spin_sense(b["rebound_spin_radps"])
    for case in (HAAKE, HAAKE_MEASURED):
        ours[case, REBOUND_SPEED] = b["rebound_speed_mps"]
        ours[case, REBOUND_ANGLE] = b["rebound_angle_deg"]
        ours[case, REBOUND_TOPSPIN] = -b["rebound_spin_radps"]
    # Launch from the club.
    for name, ((club_speed, mass, loft), _, _) in LAUNCHES.items():
        ball_speed, launch_angle, spin = launch_from_club(club_speed, mass, math.radians(loft))
        ours[_launch_case(name), BALL_SPEED] = ball_speed
        ours[_launch_case(name), LAUNCH_ANGLE] = math.degrees(launch_angle)
        ours[_launch_case(name), BACKSPIN] = spin
    # Flight, from the paper's launches.
    for name, (launch, _, _) in FLIGHTS.items():
        result = simulate(
            ball_speed_mps=launch[0],
            launch_angle_deg=launch[1],
            spin_radps=launch[2],
            turf="green",
            **PENNER_AIR,
        )
        out = _checked(result, name).outcome
        ours[_flight_case(name), LANDING_SPEED] = out["landing_speed_mps"]
        ours[_flight_case(name), LANDING_ANGLE] = out["landing_angle_deg"]
        ours[_flight_case(name), LANDING_SPIN] = out["landing_spin_radps"]
    # Whole run.
    drives = [drive(v).outcome for v in DRIVE_CLUB_SPEEDS_MPS]
    for v, out in zip(DRIVE_CLUB_SPEEDS_MPS, drives, strict=True):
        ours[_fig4_case(v), FIRST_HEIGHT] = out["first_bounce_height_m"]
        ours[_fig4_case(v), RUN] = out["run_m"]
    ours[FIG4_TREND] = _trend([out["run_m"] for out in drives])
    _, runs, _ = run_vs_launch_speed()
    ours[FIG5_TREND] = _trend(runs[::-1])  # in order of falling launch speed
    for number in FIG6_IRONS:
        out = iron(number).outcome
        ours[_fig6_case(number), IMPACT_ANGLE] = out["landing_angle_deg"]
        ours[_fig6_case(number), FIRST_HEIGHT] = out["first_bounce_height_m"]
    rests = [nine_iron_run(w, "green")[0]["final_x_m"] for w in NINE_IRON_SPINS_RADPS]
    for w, rest in zip(NINE_IRON_SPINS_RADPS, rests, strict=True):
        ours[_fig7_case(w), REST] = rest
    ours[FIG7_TREND] = _trend([-rest for rest in rests])  # how far back
    for w in NINE_IRON_SPINS_RADPS:
        ours[_fig8_case(w), BACK_RUN] = backward_run_m(nine_iron_run(w, "firm_green")[0])
    return ours


def run_vs_launch_speed():
    """Fig. 5: (launch speeds m/s, runs m, club speeds m/s) of drives over the sweep."""
    outs = [drive(v).outcome for v in SWEEP_CLUB_SPEEDS_MPS]
    return (
        np.array([o["launch_speed_mps"] for o in outs]),
        np.array([o["run_m"] for o in outs]),
        np.array(SWEEP_CLUB_SPEEDS_MPS),
    )


# --- targets.md --------------------------------------------------------------------------------

TARGETS_COLUMNS = ("case", "quantity", "paper", "mcrun", "mcrun - paper", "source")


def _fmt(value, decimals, sign=False):
    """``value`` to ``decimals`` places, never "-0.00"."""
    value = round(value, decimals) + 0.0
    return f"{value:+.{decimals}f}" if sign else f"{value:.{decimals}f}"


def _cells(paper, ours, decimals):
    """(paper, mcrun, difference) cells of one row."""
    if isinstance(ours, str):
        shown = "—" if paper is None else paper
        diff = "—" if paper is None else ("same" if ours == paper else "DIFFERS")
        return shown, ours, diff
    ours_cell = _fmt(ours, decimals + 1)
    if paper is None:
        return "—", ours_cell, "—"
    if isinstance(paper, str):
        if paper == "negligible":
            verdict = "negligible" if abs(ours) < NEGLIGIBLE_M else "NOT negligible"
            return paper, ours_cell, f"{verdict} (under {NEGLIGIBLE_M:g} m)"
        return paper, ours_cell, "—"
    diff = ours - paper
    cell = _fmt(diff, decimals + 1, sign=True)
    if paper != 0.0:
        cell += f" ({_fmt(100.0 * diff / abs(paper), 1, sign=True)} %)"
    return _fmt(paper, decimals), ours_cell, cell


_NOTES = """\
Notes:
- Haake's impact: the paper's own model rebound (4.34 m/s, 34.1 deg, 154 rad/s, Fig. 3b) does
  not follow from its printed equations (3), (6), (7); those give the values in the mcrun column,
  and the printed mu_c 0.29 comes out 0.30. We implement the equations, which reproduce the
  drive and 9-iron numbers to three digits.
- Flight: the paper flew its balls with Bearman and Harvey's (1976) tables, which are not public
  in numeric form; `penner2002` is our stand-in (see `mcrun models`).
- Fig. 6: the paper gives the irons' impact angles and first bounces but not their lofts; we
  assume lofts interpolated from 17 deg (1-iron) to 46 deg (9-iron) in 3.625 deg steps.
- Fig. 8: the run back is measured from the landing point of the first hop to where the ball
  rests. The paper does not say how it models the slide after the bounces; the order and the
  sign are what must match.
- Fig. 5: the paper's empirical curves (Cochran and Stobbs; Williams) are not available
  numerically: fig5.png shows our model only.
"""


def targets_markdown(ours=None):
    """targets.md: every number of the paper beside ours, as Markdown tables."""
    ours = our_values() if ours is None else ours
    lines = [
        "# Penner (2002) beside mcrun",
        "",
        f"Generated by `mcrun paper` (mcrun {__version__}) from the physics core. Angles of",
        "landing, impact and rebound are from the vertical, as in the paper; launch angles are",
        "above the horizontal. Shots fly with the `penner2002` aerodynamic model in air of",
        "1.204 kg/m^3 and run on the paper's green (mu 0.40, rho_g 0.131, h_c 5 mm) unless the",
        "case says otherwise. Difference = mcrun - paper; — where the paper draws the case but",
        "gives no number.",
        "",
    ]
    table = None
    for section, case, quantity, paper, decimals, source in PAPER_VALUES:
        if section != table:
            table = section
            lines += [
                "",
                f"## {section}",
                "",
                "| " + " | ".join(TARGETS_COLUMNS) + " |",
                "|" + "---|" * len(TARGETS_COLUMNS),
            ]
        cells = _cells(paper, ours[case, quantity], decimals)
        lines.append("| " + " | ".join((case, quantity, *cells, source)) + " |")
    lines += ["", _NOTES, "## Figures", ""]
    for name, (title, caption) in FIGURE_TEXT.items():
        lines.append(f"- `{name}.png`: {title}. {caption}")
    return "\n".join(lines).replace("\n\n\n", "\n\n") + "\n"


def parse_targets_markdown(text):
    """{(case, quantity): {column: cell}} from a targets.md (the inverse of the table rows)."""
    rows = {}
    for line in text.splitlines():
        if not line.startswith("| ") or line.startswith("| case |"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        row = dict(zip(TARGETS_COLUMNS, cells, strict=True))
        rows[row["case"], row["quantity"]] = row
    return rows


# --- figures -----------------------------------------------------------------------------------

FIGURE_TEXT = {
    "fig3": (
        "Fig. 3: the bounce of Haake's impact",
        "(a) Haake's (1990) measurement; (b) our bounce model (eqs. 3, 6-8) with theta_c = "
        "15.4 deg, with the rebound the paper quotes for its model in grey. Velocity vectors to "
        "scale; the incoming one ends at the impact point. Angles from the vertical.",
    ),
    "fig4": (
        "Fig. 4: the run of drives at 35, 45 and 55 m/s club-head speed",
        "Club-head 0.200 kg, dynamic loft 13.3 deg (Penner 2001 club model), penner2002 "
        "flight in air of 1.204 kg/m^3, the paper's green (mu 0.40). Height against distance "
        "from the landing point; the filled circle marks where the ball stops bouncing and "
        "begins to roll (next hop under 5 mm).",
    ),
    "fig5": (
        "Fig. 5: the run of a drive against its launch speed",
        "Our model only (dashed, as the paper draws its model): the paper's empirical curves "
        "(Cochran and Stobbs; Williams) are not available numerically. Drives of 30-60 m/s "
        "club-head speed, club as in Fig. 4, on the paper's green.",
    ),
    "fig6": (
        "Fig. 6: the run of 2-, 4- and 6-iron shots",
        "Club-head 0.250 kg at 40 m/s; lofts ASSUMED by interpolating 17 deg (1-iron) to "
        "46 deg (9-iron) in 3.625 deg steps (the paper gives only those two). penner2002 "
        "flight, the paper's green; the filled circle marks where bouncing turns to rolling.",
    ),
    "fig7": (
        "Fig. 7: the 9-iron with 809, 1000 and 1200 rad/s of backspin on the green",
        "From the paper's landing state, 23.8 m/s at 34.0 deg from the vertical, on its green "
        "(mu 0.40): bounces and roll only. The filled circle marks where bouncing turns to "
        "rolling.",
    ),
    "fig8": (
        "Fig. 8: the same 9-iron landings on a firm green (mu 0.25)",
        "23.8 m/s at 34.0 deg from the vertical with 809, 1000 and 1200 rad/s, mu 0.25 (all "
        "else as the green): the ball slides through the first impact, hops forward with "
        "backspin, then runs back. The filled circle marks where bouncing turns to rolling.",
    ),
}


def _matplotlib():
    """The matplotlib pieces the figures need; ImportError with the one-line message."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise ImportError(MISSING_MATPLOTLIB) from None
    return Figure, FigureCanvasAgg


# Margins of every figure (inches): room for the title and legend on top, the axis labels and
# the caption below. Laid out by hand so that the PNG is exactly the figure size times the dpi.
_MARGIN_TOP_IN = 1.1
_MARGIN_BOTTOM_IN = 1.3
_MARGIN_LEFT_IN = 0.85
_MARGIN_RIGHT_IN = 0.25


GROUND_COLOUR = "#a08660"


def _figure(name, hspace=0.35, wspace=0.1, top_in=_MARGIN_TOP_IN):
    """A Figure of ``FIGURE_SIZES_IN[name]`` with its title on top and its caption below."""
    figure_class, canvas_class = _matplotlib()
    width, height = FIGURE_SIZES_IN[name]
    fig = figure_class(figsize=(width, height))
    canvas_class(fig)
    fig.subplots_adjust(
        left=_MARGIN_LEFT_IN / width,
        right=1.0 - _MARGIN_RIGHT_IN / width,
        top=1.0 - top_in / height,
        bottom=_MARGIN_BOTTOM_IN / height,
        hspace=hspace,
        wspace=wspace,
    )
    title, caption = FIGURE_TEXT[name]
    fig.suptitle(title, fontsize=12, y=1.0 - 0.1 / height, va="top")
    caption += " Redrawn by mcrun from Penner (2002), Can. J. Phys. 80, 931."
    chars = int((width - 0.2) * 72.0 / (8.5 * 0.56))
    fig.text(0.1 / width, 0.1 / height, textwrap.fill(caption, chars), fontsize=8.5, va="bottom")
    return fig


def _legend(fig, handles):
    """One legend for the whole figure, under its title."""
    height = fig.get_figheight()
    fig.legend(
        handles=handles,
        loc="upper center",
        bbox_to_anchor=(0.5, 1.0 - 0.38 / height),
        ncols=math.ceil(len(handles) / 2),
        fontsize=8.5,
        frameon=False,
        handlelength=1.6,
        columnspacing=1.4,
    )


def _run_path(trajectory, landing_x_m):
    """(distance from landing m, height m, phase) of the run part of a trajectory: from its
    last flight point (the landing) on."""
    landing = int(np.flatnonzero(trajectory[:, 4] == FLIGHT)[-1])
    part = trajectory[landing:]
    return part[:, 1] - landing_x_m, part[:, 3], part[:, 4]


def _draw_runs(fig, cases, xlabel):
    """Stacked panels (as the paper's figures), one per case: height against distance from the
    landing point, the ground, the filled circle where bouncing turns to rolling and a tick
    where the ball rests.

    ``cases``: (label, colour, distance, height, phase, note) per panel.
    """
    axes = fig.subplots(len(cases), 1, sharex=True, sharey=True)
    handles = []
    for ax, (label, colour, dist, height, phase, note) in zip(axes, cases, strict=True):
        (line,) = ax.plot(dist, height, color=colour, lw=1.6, label=label)
        handles.append(line)
        roll_start = int(np.flatnonzero(phase == ROLL)[0])
        (dot,) = ax.plot(
            dist[roll_start],
            height[roll_start],
            "o",
            color="black",
            ms=7,
            zorder=5,
            label="stops bouncing, begins to roll",
        )
        (rest,) = ax.plot(
            dist[-1], height[-1], "|", color="black", ms=16, mew=2, zorder=5, label="at rest"
        )
        ax.axhline(0.0, color=GROUND_COLOUR, lw=2.0, zorder=0)
        ax.axvline(0.0, color="grey", lw=0.8, ls=":")
        ax.set_ylabel("height (m)")
        ax.set_title(label, fontsize=10, loc="left")
        ax.text(
            0.99,
            0.93,
            note,
            transform=ax.transAxes,
            ha="right",
            va="top",
            fontsize=8.5,
            bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8},
        )
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(xlabel)
    top = max(float(np.max(c[3])) for c in cases)
    axes[0].set_ylim(-0.04 * top, 1.35 * top)
    _legend(fig, [*handles, dot, rest])
    return axes


def _save(fig, out_dir, name, dpi):
    path = Path(out_dir) / f"{name}.png"
    fig.savefig(path, dpi=dpi)
    return path


def fig3(out_dir, dpi):
    """Fig. 3: Haake's impact, measured and modelled, as velocity vectors."""
    fig = _figure("fig3", wspace=0.08, top_in=0.55)
    speed, angle, backspin = HAAKE_IMPACT
    ours = bounce_once(speed, angle, backspin, turf="green")
    mcrun_rebound = (
        ours["rebound_speed_mps"],
        ours["rebound_angle_deg"],
        -ours["rebound_spin_radps"],
    )
    panels = (
        ("(a) Haake (1990), measured", [(*HAAKE_REBOUND, "measured rebound", "#c0392b")]),
        (
            f"(b) mcrun bounce model, theta_c = {ours['theta_c_deg']:.1f} deg",
            [
                (*mcrun_rebound, "mcrun rebound", "#1f77b4"),
                (*PAPER_MODEL_REBOUND, "paper's model (Fig. 3b)", "grey"),
            ],
        ),
    )
    axes = fig.subplots(1, 2, sharex=True, sharey=True)
    phi = math.radians(angle)
    for k, (ax, (title, rebounds)) in enumerate(zip(axes, panels, strict=True)):
        ax.axhspan(-4.0, 0.0, color=GROUND_COLOUR, alpha=0.3, lw=0)
        ax.axhline(0.0, color=GROUND_COLOUR, lw=2)
        ax.plot([0, 0], [0, 15], color="grey", lw=0.8, ls=":")
        ax.annotate(
            "",
            xy=(0, 0),
            xytext=(-speed * math.sin(phi), speed * math.cos(phi)),
            arrowprops={"arrowstyle": "-|>", "color": "black", "lw": 1.8},
        )
        ax.text(
            -15.0,
            1.0,
            f"incoming\n{speed:g} m/s at {angle:g} deg\n{backspin:g} rad/s backspin",
            ha="left",
            va="bottom",
            fontsize=9,
        )
        y_text = 14.3
        for v, a, topspin, label, colour in rebounds:
            ar = math.radians(a)
            ax.annotate(
                "",
                xy=(v * math.sin(ar), v * math.cos(ar)),
                xytext=(0, 0),
                arrowprops={
                    "arrowstyle": "-|>",
                    "color": colour,
                    "lw": 1.8,
                    "ls": "--" if colour == "grey" else "-",
                },
            )
            ax.text(
                1.0,
                y_text,
                f"{label}:\n{v:.2f} m/s at {a:.1f} deg\n{topspin:.0f} rad/s topspin",
                color=colour if colour != "grey" else "dimgrey",
                fontsize=8.5,
                va="top",
            )
            y_text -= 4.6
        if k == 1:
            tc = math.radians(ours["theta_c_deg"])
            ax.plot(
                [-6 * math.cos(tc), 5 * math.cos(tc)],
                [-6 * math.sin(tc), 5 * math.sin(tc)],
                color="saddlebrown",
                lw=1.4,
                ls="-.",
            )
            ax.text(
                -6.0,
                -3.7,
                f"equivalent rigid surface, tilted {ours['theta_c_deg']:.1f} deg\n"
                f"e = {ours['e']:.2f}, mu_c = {ours['mu_c']:.2f}: leaves {ours['mode']}",
                fontsize=8.5,
                color="saddlebrown",
                va="bottom",
            )
        ax.set_title(title, fontsize=10)
        ax.set_aspect("equal")
        ax.set_xlim(-15.5, 12.5)
        ax.set_ylim(-4.0, 15.0)
        ax.set_xlabel("horizontal velocity (m/s), + towards the target")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("vertical velocity (m/s)")
    return _save(fig, out_dir, "fig3", dpi)


def _shot_case(label, colour, result):
    out = result.outcome
    frame = result.trajectory
    path = np.column_stack(
        [frame[["t_s", "x_m", "y_m", "z_m"]].to_numpy(dtype=float), frame["phase"].cat.codes]
    )
    dist, height, phase = _run_path(path, out["carry_m"])
    note = (
        f"lands {out['landing_speed_mps']:.1f} m/s at {out['landing_angle_deg']:.1f} deg, "
        f"{out['landing_spin_radps']:.0f} rad/s; "
        f"first bounce {out['first_bounce_height_m']:.2f} m; "
        f"run {out['run_m']:.1f} m"
    )
    return label, colour, dist, height, phase, note


def fig4(out_dir, dpi):
    """Fig. 4: the runs of drives at 35, 45 and 55 m/s club-head speed."""
    fig = _figure("fig4")
    cases = [
        _shot_case(f"{v:g} m/s club-head speed", f"C{k}", drive(v, trajectory=True))
        for k, v in enumerate(DRIVE_CLUB_SPEEDS_MPS)
    ]
    _draw_runs(fig, cases, "distance from the landing point (m)")
    return _save(fig, out_dir, "fig4", dpi)


def fig5(out_dir, dpi):
    """Fig. 5: run against launch speed over a sweep of the driver's club-head speed."""
    fig = _figure("fig5", top_in=0.55)
    speeds, runs, clubs = run_vs_launch_speed()
    ax = fig.subplots()
    ax.plot(speeds, runs, "--", color="C0", lw=1.8, label="mcrun model (drives)")
    for v in DRIVE_CLUB_SPEEDS_MPS:
        k = int(np.flatnonzero(clubs == v)[0])
        ax.plot(speeds[k], runs[k], "o", color="C0", ms=6)
        ax.annotate(
            f"{v:g} m/s club\n(Fig. 4)",
            (speeds[k], runs[k]),
            xytext=(8, 6),
            textcoords="offset points",
            fontsize=8.5,
        )
    ax.set_xlabel("launch speed (m/s)")
    ax.set_ylabel("run, landing to rest (m)")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9)
    return _save(fig, out_dir, "fig5", dpi)


def fig6(out_dir, dpi):
    """Fig. 6: the runs of 2-, 4- and 6-irons."""
    fig = _figure("fig6")
    cases = [
        _shot_case(f"{n}-iron (loft {iron_loft_deg(n):.1f} deg, assumed)", f"C{k}", iron(n, True))
        for k, n in enumerate(FIG6_IRONS)
    ]
    _draw_runs(fig, cases, "distance from the landing point (m)")
    return _save(fig, out_dir, "fig6", dpi)


def _nine_iron_figure(name, turf, out_dir, dpi):
    fig = _figure(name)
    cases = []
    for k, w in enumerate(NINE_IRON_SPINS_RADPS):
        summary, path = nine_iron_run(w, turf, trajectory=True)
        note = (
            f"first hop {summary['first_bounce_height_m']:.2f} m high, "
            f"{summary['first_bounce_length_m']:+.2f} m long; "
            f"rests {_fmt(summary['final_x_m'], 2, sign=True)} m from landing"
        )
        if turf == "firm_green":
            note += f"; runs back {_fmt(backward_run_m(summary), 2)} m"
        cases.append((f"{w:g} rad/s backspin", f"C{k}", path[:, 1], path[:, 3], path[:, 4], note))
    _draw_runs(fig, cases, "distance from the landing point (m), + towards the target")
    return _save(fig, out_dir, name, dpi)


def fig7(out_dir, dpi):
    """Fig. 7: the 9-iron landing with 809, 1000 and 1200 rad/s on the green (mu 0.40)."""
    return _nine_iron_figure("fig7", "green", out_dir, dpi)


def fig8(out_dir, dpi):
    """Fig. 8: the same on the firm green (mu 0.25)."""
    return _nine_iron_figure("fig8", "firm_green", out_dir, dpi)


FIGURES = {"fig3": fig3, "fig4": fig4, "fig5": fig5, "fig6": fig6, "fig7": fig7, "fig8": fig8}


def write_paper(out_dir, dpi=DEFAULT_DPI):
    """Write fig3.png ... fig8.png and targets.md into ``out_dir``; return their paths."""
    _matplotlib()  # fail before any work when matplotlib is missing
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = [draw(out_dir, dpi) for draw in FIGURES.values()]
    targets = out_dir / "targets.md"
    targets.write_text(targets_markdown(), encoding="utf-8")
    return [*paths, targets]
