"""The batch kernel: many shots in parallel, structure-of-arrays in, structure-of-arrays out.

``simulate_batch`` runs ``shot.simulate_shot`` in ``prange`` over the rows of ``inputs``, an
(n, N_INPUT) float64 array in Fortran order (each column contiguous, named by ``INPUT_FIELDS``,
SI, user frame) and writes ``out``, an (n, N_OUTCOME) float64 array in Fortran order whose
columns are ``shot.OUTCOME_FIELDS``. Every shot is independent of the others and of the thread
that runs it, so the results are the same bit for bit whatever the thread count.
"""

import numpy as np
from numba import njit, prange

from mcrun.aero import QUADRATIC_COEFFICIENTS
from mcrun.flight import make_flight_params
from mcrun.shot import N_OUTCOME, simulate_shot
from mcrun.turf import Turf

INPUT_FIELDS = (
    "ball_speed_mps",
    "launch_angle_rad",
    "azimuth_rad",
    "spin_radps",
    "spin_axis_rad",
    "air_density_kgpm3",
    "kinematic_viscosity_m2ps",
    "aero_model",
    "cd_scale",
    "cl_scale",
    "wind_x_mps",
    "wind_right_mps",
    "wind_profile",
    "wind_reference_height_m",
    "wind_profile_parameter",
    "mu",
    "softness",
    "e0",
    "e1",
    "e2",
    "e_break_speed_mps",
    "e_high",
    "rho_g",
    "critical_height_m",
    "slope_rad",
    "fall_line_rad",
    "dt_s",
)
N_INPUT = len(INPUT_FIELDS)
COLUMN = {name: k for k, name in enumerate(INPUT_FIELDS)}


@njit(cache=True)
def _shot(inputs, i, table, out, j, traj):
    """Shot i of ``inputs`` into row j of ``out``."""
    c = inputs[i]
    p = make_flight_params(
        c[5], c[6], int(c[7]), c[8], c[9], c[10], c[11], int(c[12]), c[13], c[14]
    )
    turf = Turf(c[15], c[16], c[17], c[18], c[19], c[20], c[21], c[22], c[23])
    return simulate_shot(
        c[0], c[1], c[2], c[3], c[4], p, turf, c[24], c[25], c[26], table, out, j, traj
    )


@njit(parallel=True, cache=True)
def _simulate_batch(inputs, table, out):
    no_trajectory = np.empty((0, 5))
    for i in prange(inputs.shape[0]):
        _shot(inputs, i, table, out, i, no_trajectory)


def simulate_batch(inputs, out=None, table=QUADRATIC_COEFFICIENTS):
    """Simulate every row of ``inputs`` (n, N_INPUT); return ``out`` (n, N_OUTCOME), F-order."""
    if inputs.ndim != 2 or inputs.shape[1] != N_INPUT:
        raise ValueError(f"inputs must have shape (n, {N_INPUT}), got {inputs.shape}")
    if out is None:
        out = np.empty((inputs.shape[0], N_OUTCOME), order="F")
    _simulate_batch(inputs, table, out)
    return out


@njit(cache=True)
def trajectory_of(inputs, i, table, traj):
    """Trajectory of shot i of ``inputs`` into ``traj`` (m, 5); returns its number of points."""
    out = np.empty((1, N_OUTCOME))
    return _shot(inputs, i, table, out, 0, traj)
