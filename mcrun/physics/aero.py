"""Aerodynamic coefficients of a spinning golf ball: C_D and C_L from the spin ratio and Re.

Each model is named after the work it comes from, and chosen by that name
(``aero="ferguson2022"``). Inside the kernels a model is an integer id. The spin ratio is
S = r |w| / |v_rel| and the Reynolds number Re = |v_rel| 2r / nu.

Three models share one closed form, C_D = a0 + a1 S + a2 S^2 and C_L = b0 + b1 S + b2 S^2
with S clipped at s_max; their coefficients live in ``QUADRATIC_COEFFICIENTS``.
"""

import math

import numpy as np
from numba import njit

FERGUSON2022 = 0
SMITS_SMITH1994 = 1
LYU2018 = 2
PENNER2002 = 3
TRACKMAN2019 = 4

MODELS = {
    "ferguson2022": FERGUSON2022,
    "smits_smith1994": SMITS_SMITH1994,
    "lyu2018": LYU2018,
    "penner2002": PENNER2002,
    "trackman2019": TRACKMAN2019,
}

# The model that best predicts measured shots (benchmarks/calibration.md, README).
DEFAULT_MODEL = "trackman2019"

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
}

# (a0, a1, a2, b0, b1, b2, s_max) of C_D = a0 + a1 S + a2 S^2, C_L = b0 + b1 S + b2 S^2.
QUADRATIC_COEFFICIENTS = np.array(
    [
        # ferguson2022, as published.
        [0.1304, 0.9287, -0.8259, 0.0504, 1.2031, -1.1490, 0.75],
        # smits_smith1994 and lyu2018 have their own forms: rows unused.
        [np.nan] * 7,
        [np.nan] * 7,
        # penner2002: smooth quadratics through Bearman and Harvey's summary points (C_D 0.276
        # at S 0.05 rising to 0.29 at S 0.15 and 0.35 at 0.3; C_L 0.13 at S 0.05, 0.22 at 0.15,
        # 0.31 at 0.3), least-squares tuned to the four landings Penner (2002) section 3
        # quotes. The lift had to rise about 25 % above the summary points' C_L to get them.
        [0.2803, -0.1389, 1.2498, 0.0765, 1.1877, -1.3468, 0.40],
        # trackman2019: `mcrun calibrate --fit` (from ferguson2022, s_max fitted) on the TrackMan
        # 2019 PGA and LPGA averages; carry/apex/land-angle RMSE 3.29 m / 2.22 m / 3.24 deg
        # against ferguson2022's 3.95 / 1.42 / 5.58 (benchmarks/calibration.md).
        [0.1678, 0.8328, -0.7391, 0.04213, 1.514, -1.631, 0.4972],
    ]
)

LYU_RE_SWITCH = 1.0530e5


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
    return quadratic(s, c[0], c[1], c[2], c[3], c[4], c[5], c[6])


# The models of the quadratic form, whose rows of QUADRATIC_COEFFICIENTS are used and whose shots
# may fly in the batch kernel's quadratic lanes. A list of those that are, so that a model added
# with a form of its own is not taken for one.
QUADRATIC_MODELS = (FERGUSON2022, PENNER2002, TRACKMAN2019)


@njit(cache=True, error_model="numpy")
def is_quadratic(model):
    """Whether the model with this id has the quadratic form (its row of the table is used)."""
    return model in QUADRATIC_MODELS


def model_id(name):
    """Integer id of an aerodynamic model given by name; ValueError naming the choices."""
    try:
        return MODELS[name]
    except KeyError:
        raise ValueError(
            f"unknown aerodynamic model '{name}': choose one of {', '.join(MODELS)}"
        ) from None
