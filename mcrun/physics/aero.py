"""Aerodynamic coefficients of a spinning golf ball: C_D and C_L from the spin ratio and Re.

Each model is named after the work it comes from, and chosen by that name
(``aero="ferguson2022"``). Inside the kernels a model is an integer id. The spin ratio is
S = r |w| / |v_rel| and the Reynolds number Re = |v_rel| 2r / nu.

Three models share one closed form, C_D = a0 + a1 S + a2 S^2 and C_L = b0 + b1 S + b2 S^2
with S clipped at s_max; their coefficients live in ``QUADRATIC_COEFFICIENTS``.

The Reynolds models (``REYNOLDS_MODELS``) add to that quadratic a rise of the drag as the ball
slows below Re = 1e5 (the dimpled ball's drag crisis run backwards), and carry their own spin
decay:

    C_D = a0 + a1 S + a2 S^2 + c_lyu D_lyu(Re) + c_ramp D_ramp(Re)
    C_L = b0 + b1 S + b2 S^2                                         (S clipped at s_max)
    dw/dt = -(k |v_rel| / r + lambda) w

with D_lyu(Re) = L(min(Re, LYU_RE_MIN)) - L(LYU_RE_MIN), L(Re) = 1.29e-10 Re^2 - 2.59e-5 Re + 1.50
the low-Re drag Lyu et al. (2018) measured in still air (zero above its minimum at Re 1.004e5,
0.16 at 6.5e4, 0.33 at 5e4), and D_ramp(Re) = clip((1e5 - Re) / 5e4, 0, 1) the linear rise
between Re 1e5 and 5e4 of libgolf (after Alan Nathan's trajectory calculator), whose C_D goes
from 0.2 to 0.5 there. k |v_rel| / r is the spin decay of Smits and Smith (1994), lambda a
constant rate (exp(-lambda t) when k = 0; TrackMan: "typically 4 % for each second"). Their
parameters are columns 7-10 of the same table; min and max keep the form free of branches.
"""

import math

import numpy as np
from numba import njit

from mcrun.physics.constants import BALL_RADIUS_M, SPIN_DECAY_K

FERGUSON2022 = 0
SMITS_SMITH1994 = 1
LYU2018 = 2
PENNER2002 = 3
TRACKMAN2019 = 4
TRACKMAN2019_LYU = 5
TRACKMAN2019_RAMP = 6
TRACKMAN2019_EXP = 7
TRACKMAN2019_LYU_EXP = 8

MODELS = {
    "ferguson2022": FERGUSON2022,
    "smits_smith1994": SMITS_SMITH1994,
    "lyu2018": LYU2018,
    "penner2002": PENNER2002,
    "trackman2019": TRACKMAN2019,
    "trackman2019_lyu": TRACKMAN2019_LYU,
    "trackman2019_ramp": TRACKMAN2019_RAMP,
    "trackman2019_exp": TRACKMAN2019_EXP,
    "trackman2019_lyu_exp": TRACKMAN2019_LYU_EXP,
}

# The model that best predicts measured shots it was not fitted to (cross-validated on the
# TrackMan 2019 tour averages: benchmarks/calibration.md, docs/calibration.md). Before:
# trackman2019.
DEFAULT_MODEL = "trackman2019_lyu"

SOURCES = {
    "ferguson2022": "Ferguson, McNally and McPhee (2022), ISEA proceedings, "
    "doi 10.5703/1288284317493: quadratic fits to 1,040 measured shots, S clipped at 0.75.",
    "smits_smith1994": "Smits and Smith (1994), Science and Golf II, 340-347: "
    "C_D = 0.24 + 0.18 S + 0.06 sin(pi (Re - 9e4) / 2e5), C_L = 0.54 S^0.4; "
    "Re held inside its range of validity 7e4-2.1e5.",
    "lyu2018": "Lyu et al. (2018), Proceedings 2(6):238: C_L = 1.99 S - 3.25 S^2 "
    "(S clipped at 0.32), C_D quadratic in Re, switching between the low- and high-Re fits "
    "where they cross (Re 1.053e5).",
    "penner2002": "Stand-in for the Bearman and Harvey (1976) tables Penner (2002) flew his "
    "balls with: quadratics near their summary points, tuned to the paper's four landings.",
    "trackman2019": "Quadratic form of ferguson2022 refitted with `mcrun calibrate` to the "
    "TrackMan 2019 PGA and LPGA Tour averages (carry, apex and land angle of 23 clubs).",
    "trackman2019_lyu": "The quadratic form plus the low-Re drag rise Lyu, Kensrud and Smith "
    "(2018) measured in still air (Proceedings 2(6):238, doi 10.3390/proceedings2060238), scaled; "
    "Smits and Smith's spin decay; refitted to the TrackMan 2019 averages.",
    "trackman2019_ramp": "The quadratic form plus libgolf's linear drag rise between Re 1e5 and "
    "5e4 (after A. Nathan's trajectory calculator), scaled; Smits and Smith's spin decay; "
    "refitted to the TrackMan 2019 averages.",
    "trackman2019_exp": "The quadratic form with the spin decaying 4 % per second (TrackMan "
    "newsletter, October 2010); refitted to the TrackMan 2019 averages.",
    "trackman2019_lyu_exp": "trackman2019_lyu with the spin decaying 4 % per second (TrackMan); "
    "refitted to the TrackMan 2019 averages.",
}

# Columns of the table: (a0, a1, a2, b0, b1, b2, s_max) of C_D = a0 + a1 S + a2 S^2,
# C_L = b0 + b1 S + b2 S^2 (S clipped at s_max), then, used by the Reynolds models only, the
# scales c_lyu and c_ramp of the low-Re drag rises and the spin decay's k and lambda (1/s).
# The quadratic models' lanes decay the spin with constants.SPIN_DECAY_K, which their rows repeat.
N_COLUMNS = 11
C_LYU, C_RAMP, SPIN_K, SPIN_RATE = 7, 8, 9, 10
_NO_ROW = [np.nan] * N_COLUMNS
_SMITS_DECAY = [0.0, 0.0, SPIN_DECAY_K, 0.0]
QUADRATIC_COEFFICIENTS = np.array(
    [
        # ferguson2022, as published.
        [0.1304, 0.9287, -0.8259, 0.0504, 1.2031, -1.1490, 0.75, *_SMITS_DECAY],
        # smits_smith1994 and lyu2018 have their own forms: rows unused.
        _NO_ROW,
        _NO_ROW,
        # penner2002: smooth quadratics near Bearman and Harvey's summary points (C_D about
        # 0.28 at S 0.15, 0.27-0.32 once S > 0.1; C_L about 0.18 at S 0.15, 0.08-0.25 over S
        # 0.02-0.3), least-squares tuned to the four landings Penner (2002) section 3 quotes:
        # C_D 0.276 at S 0.05, 0.29 at 0.15, 0.35 at 0.3; C_L 0.13, 0.22 and 0.31 there. The
        # lift had to rise about 25 % above the summary points' C_L to get the landings.
        [0.2803, -0.1389, 1.2498, 0.0765, 1.1877, -1.3468, 0.40, *_SMITS_DECAY],
        # trackman2019: `mcrun calibrate --fit` (from ferguson2022, s_max fitted) on the TrackMan
        # 2019 PGA and LPGA averages; carry/apex/land-angle RMSE 3.29 m / 2.22 m / 3.24 deg
        # against ferguson2022's 3.95 / 1.42 / 5.58 (benchmarks/calibration.md).
        [0.1678, 0.8328, -0.7391, 0.04213, 1.514, -1.631, 0.4972, *_SMITS_DECAY],
        # The Reynolds models, each `mcrun calibrate --fit --form NAME` (from ferguson2022, the
        # rise from its published size) on the TrackMan 2019 PGA and LPGA averages; the spin
        # decay is held at its published value. Cross-validated in benchmarks/calibration.md.
        # trackman2019_lyu: Lyu et al.'s low-Re drag rise, scaled; Smits and Smith's decay.
        [0.1756, 0.6576, -0.825, 0.06089, 1.246, -1.463, 0.7737, 1.18, 0.0, SPIN_DECAY_K, 0.0],
        # trackman2019_ramp: libgolf's linear rise between Re 1e5 and 5e4, scaled.
        [0.1253, 1.13, -2.045, 0.01892, 1.615, -2.26, 0.3, 0.0, 0.3086, SPIN_DECAY_K, 0.0],
        # trackman2019_exp: no Re term; the spin decays 4 % per second (TrackMan).
        [0.1634, 0.8573, -0.77, 0.04041, 1.503, -1.581, 0.5068, 0.0, 0.0, 0.0, 0.04],
        # trackman2019_lyu_exp: Lyu et al.'s rise and the spin decaying 4 % per second.
        [0.1735, 0.6681, -0.8349, 0.05668, 1.27, -1.501, 0.7307, 1.172, 0.0, 0.0, 0.04],
    ]
)

LYU_RE_SWITCH = 1.0530e5
# The minimum of Lyu et al.'s low-Re fit L(Re) = 1.29e-10 Re^2 - 2.59e-5 Re + 1.50, where the
# rise D_lyu starts (Re = 2.59e-5 / (2 1.29e-10)), and L there.
LYU_RE_MIN = 2.59e-5 / (2.0 * 1.29e-10)
LYU_CD_MIN = 1.50 - 2.59e-5 * 2.59e-5 / (4.0 * 1.29e-10)
# The linear rise of libgolf (after A. Nathan): from 0 at Re 1e5 to 1 at 5e4 and below.
RAMP_RE_HIGH = 1.0e5
RAMP_RE_LOW = 5.0e4


@njit(cache=True, error_model="numpy")
def quadratic(spin_ratio, a0, a1, a2, b0, b1, b2, s_max):
    """(C_D, C_L) of the quadratic form, with S clipped at s_max."""
    s = min(spin_ratio, s_max)
    return a0 + s * (a1 + s * a2), b0 + s * (b1 + s * b2)


@njit(cache=True, error_model="numpy")
def coefficients(model, spin_ratio, reynolds, table):
    """Drag and lift coefficients (C_D, C_L) of ``model`` at spin ratio S and Reynolds number Re.

    ``table`` is ``QUADRATIC_COEFFICIENTS`` (passed in so that a calibration can try other rows).
    """
    s = spin_ratio
    if model == SMITS_SMITH1994:
        re = min(max(reynolds, 7.0e4), 2.1e5)
        cd = 0.24 + 0.18 * s + 0.06 * math.sin(math.pi * (re - 9.0e4) / 2.0e5)
        cl = 0.54 * s**0.4
        return cd, cl
    if model == LYU2018:
        re = reynolds
        if re < LYU_RE_SWITCH:
            cd = 1.29e-10 * re * re - 2.59e-5 * re + 1.50
        else:
            cd = 1.91e-11 * re * re - 5.40e-6 * re + 0.56
        s = min(s, 0.32)
        cl = 1.99 * s - 3.25 * s * s
        return cd, cl
    c = table[model]
    cd, cl = quadratic(s, c[0], c[1], c[2], c[3], c[4], c[5], c[6])
    if is_reynolds(model):
        cd += c[C_LYU] * lyu_rise(reynolds) + c[C_RAMP] * ramp_rise(reynolds)
    return cd, cl


@njit(cache=True, error_model="numpy", inline="always")
def lyu_rise(reynolds):
    """D_lyu(Re): Lyu et al.'s (2018) low-Re drag above its minimum, 0 above Re 1.004e5."""
    re = min(reynolds, LYU_RE_MIN)
    return 1.29e-10 * re * re - 2.59e-5 * re + 1.50 - LYU_CD_MIN


@njit(cache=True, error_model="numpy", inline="always")
def ramp_rise(reynolds):
    """D_ramp(Re): 0 above Re 1e5, rising linearly to 1 at 5e4 and staying there below."""
    return min(max((RAMP_RE_HIGH - reynolds) / (RAMP_RE_HIGH - RAMP_RE_LOW), 0.0), 1.0)


@njit(cache=True, error_model="numpy")
def spin_decay_rate(model, speed, table):
    """The rate (1/s) at which the spin of ``model`` decays at air speed |v_rel|:
    dw/dt = -rate w. Smits and Smith's k |v_rel| / r for all but the Reynolds models, which
    take k and lambda from their row: k |v_rel| / r + lambda."""
    if is_reynolds(model):
        c = table[model]
        return c[SPIN_K] * speed / BALL_RADIUS_M + c[SPIN_RATE]
    return SPIN_DECAY_K * speed / BALL_RADIUS_M


# The models of the quadratic form, whose rows of QUADRATIC_COEFFICIENTS are used and whose shots
# may fly in the batch kernel's quadratic lanes. A list of those that are, so that a model added
# with a form of its own is not taken for one.
QUADRATIC_MODELS = (FERGUSON2022, PENNER2002, TRACKMAN2019)


@njit(cache=True, error_model="numpy")
def is_quadratic(model):
    """Whether the model with this id has the quadratic form (its row of the table is used)."""
    return model in QUADRATIC_MODELS


# The Reynolds models: the quadratic in S plus the low-Re drag rises and their own spin decay,
# flown in the general lanes (they are not quadratic in S alone).
REYNOLDS_MODELS = (TRACKMAN2019_LYU, TRACKMAN2019_RAMP, TRACKMAN2019_EXP, TRACKMAN2019_LYU_EXP)


@njit(cache=True, error_model="numpy")
def is_reynolds(model):
    """Whether the model with this id is one of the Reynolds models (columns 7-10 used)."""
    return model in REYNOLDS_MODELS


# The models whose shots in uniform wind fly in the batch kernel's vectorised lanes
# (``flight.derivatives_quadratic``): the quadratic models and the Reynolds models, whose
# rises and spin decay are free of branches.
LANE_MODELS = QUADRATIC_MODELS + REYNOLDS_MODELS


@njit(cache=True, error_model="numpy")
def flies_in_lanes(model):
    """Whether shots of the model with this id fly in the vectorised lanes in uniform wind."""
    return model in LANE_MODELS


def model_id(name):
    """Integer id of an aerodynamic model given by name; ValueError naming the choices."""
    try:
        return MODELS[name]
    except KeyError:
        raise ValueError(
            f"unknown aerodynamic model '{name}': choose one of {', '.join(MODELS)}"
        ) from None
