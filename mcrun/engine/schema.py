"""The kernel's schemas: the columns of its inputs and of its outcomes.

Inputs: an (n, N_INPUT) float64 array, one row a shot, its columns ``INPUT_FIELDS`` (SI, the
user's frame: y and every angle positive to the right), built by ``pack``. A shot is struck from
(start_x_m, start_y_m), on the ground there (on a hole: its height; on a Plane: z = 0), the tee
(0, 0) by default; its azimuth is from the frame's x axis. Outcomes: an
(n, N_OUTCOME) float64 array whose columns are ``OUTCOME_FIELDS``, NaN where a shot did not get
that far, with the status code (``mcrun.status``) in the last; ``encode_outcomes`` types them.
"""

import math

import numpy as np

from mcrun.physics.constants import STANDARD_WIND_HEIGHT_M
from mcrun.physics.flight import WIND_UNIFORM

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
    "start_x_m",
    "start_y_m",
)
N_INPUT = len(INPUT_FIELDS)
COLUMN = {name: k for k, name in enumerate(INPUT_FIELDS)}

# The inputs ``pack`` fills when they are not given: a straight shot without sidespin, in still
# air (the reference height of a wind profile then matters not), on level ground, with the
# aerodynamic model's coefficients unscaled.
INPUT_DEFAULTS = {
    "azimuth_rad": 0.0,
    "spin_axis_rad": 0.0,
    "cd_scale": 1.0,
    "cl_scale": 1.0,
    "wind_x_mps": 0.0,
    "wind_right_mps": 0.0,
    "wind_profile": float(WIND_UNIFORM),
    "wind_reference_height_m": STANDARD_WIND_HEIGHT_M,
    "wind_profile_parameter": 0.0,
    "slope_rad": 0.0,
    "fall_line_rad": 0.0,
    "start_x_m": 0.0,
    "start_y_m": 0.0,
}


def pack(columns, n, out=None, invalid=None):
    """The kernel's inputs, (n, N_INPUT) float64 in Fortran order, from named SI columns.

    Parameters
    ----------
    columns : dict of str -> array of n or float
        Values by name of ``INPUT_FIELDS`` (ids, such as ``aero_model``, as floats); a name
        left out takes its ``INPUT_DEFAULTS`` value. ValueError for an unknown name, or a
        missing one without a default.
    n : int
        The number of shots.
    out : ndarray, optional
        The (n, N_INPUT) array to fill (a view of the rows of a larger one, say).
    invalid : bool array of n, optional
        Shots the kernel must refuse: their ball speed is NaN, which it answers with status
        ``invalid_input``.
    """
    unknown = sorted(set(columns) - set(COLUMN))
    if unknown:
        raise ValueError(f"unknown kernel input(s): {', '.join(unknown)}")
    missing = [k for k in INPUT_FIELDS if k not in columns and k not in INPUT_DEFAULTS]
    if missing:
        raise ValueError(f"missing kernel input(s): {', '.join(missing)}")
    if out is None:
        out = np.empty((n, N_INPUT), order="F")
    elif out.shape != (n, N_INPUT):
        raise ValueError(f"out must have shape ({n}, {N_INPUT}), got {out.shape}")
    for k, name in enumerate(INPUT_FIELDS):
        out[:, k] = columns[name] if name in columns else INPUT_DEFAULTS[name]
    if invalid is not None:
        out[invalid, COLUMN["ball_speed_mps"]] = math.nan
    return out


# The outcomes. Distances along the frame's axes from where the shot was struck: carry_m,
# carry_lateral_m and total_m (x and y of the landing, x at rest, less the start's), apex_m (the
# height above the ground at the start); run_m from the landing. Positions in the frame:
# final_x_m, final_y_m, final_z_m and penalty_x_m, penalty_y_m.
OUTCOME_FIELDS = (
    "launch_speed_mps",
    "launch_angle_deg",
    "launch_spin_radps",
    "carry_m",
    "carry_lateral_m",
    "apex_m",
    "flight_time_s",
    "landing_speed_mps",
    "landing_angle_deg",
    "landing_spin_radps",
    "bounces",
    "first_bounce_height_m",
    "first_bounce_length_m",
    "run_m",
    "total_m",
    "final_x_m",
    "final_y_m",
    "total_time_s",
    "final_z_m",
    "penalty_x_m",
    "penalty_y_m",
    "status",
)
(
    LAUNCH_SPEED,
    LAUNCH_ANGLE,
    LAUNCH_SPIN,
    CARRY,
    CARRY_LATERAL,
    APEX,
    FLIGHT_TIME,
    LANDING_SPEED,
    LANDING_ANGLE,
    LANDING_SPIN,
    BOUNCES,
    FIRST_BOUNCE_HEIGHT,
    FIRST_BOUNCE_LENGTH,
    RUN,
    TOTAL,
    FINAL_X,
    FINAL_Y,
    TOTAL_TIME,
    FINAL_Z,
    PENALTY_X,
    PENALTY_Y,
    STATUS,
) = range(len(OUTCOME_FIELDS))
N_OUTCOME = len(OUTCOME_FIELDS)
# The outcomes that only a hole gives (``ground.Terrain``): the height where the ball ends,
# relative to the tee, and the Rules' reference point of a shot its status ended: where it
# crossed into a penalty area or off the map, or, out of bounds, where it rests
# (``mcrun.status``). A run on a Plane leaves them out of what it writes (``plane_fields``).
HOLE_FIELDS = ("final_z_m", "penalty_x_m", "penalty_y_m")
PLANE_FIELDS = tuple(name for name in OUTCOME_FIELDS if name not in HOLE_FIELDS)

# The outcomes that are counts or codes, and their types; the others are float64. A count is
# missing (NaN in the kernel's outcomes) where a shot did not get that far; the status never is.
OUTCOME_DTYPES = {"bounces": np.int32, "status": np.int8}


def encode_outcomes(outcomes, names=PLANE_FIELDS):
    """The columns ``names`` of ``outcomes`` (n, N_OUTCOME), typed: {name: (values, missing)}.

    ``values`` is contiguous, of ``OUTCOME_DTYPES[name]`` or float64 (NaN kept where a shot did
    not get that far); ``missing`` is a boolean mask for a count (bounces), the rows that have
    no value (their ``values`` 0), and None for the others. The one encoding of the outcomes:
    Parquet, the replay's DataFrame and the API's dict (None) are made from it.
    """
    encoded = {}
    for name in names:
        column = outcomes[:, OUTCOME_FIELDS.index(name)]
        dtype = OUTCOME_DTYPES.get(name)
        if dtype is None:
            encoded[name] = (np.ascontiguousarray(column), None)
        elif name == "status":
            encoded[name] = (column.astype(dtype), None)
        else:
            missing = ~np.isfinite(column)
            encoded[name] = (np.where(missing, 0, column).astype(dtype), missing)
    return encoded


def outcome_record(outcomes, i=0, names=PLANE_FIELDS):
    """Row ``i`` of ``outcomes`` as ``encode_outcomes`` types it, in Python values: a float
    (NaN where the shot did not get that far), an int, or None for a missing count."""
    return {
        name: None if missing is not None and missing[0] else values[0].item()
        for name, (values, missing) in encode_outcomes(outcomes[i : i + 1], names).items()
    }
