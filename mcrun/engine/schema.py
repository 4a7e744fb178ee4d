"""The kernel's schemas: the columns of its inputs and of its outcomes.

Inputs: an (n, N_INPUT) float64 array, one row a shot, its columns ``INPUT_FIELDS`` (SI, the
user's frame: y and every angle positive to the right). Outcomes: an (n, N_OUTCOME) float64
array whose columns are ``OUTCOME_FIELDS``, NaN where a shot did not get that far, with the
status code (``mcrun.status``) in the last.
"""

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
    STATUS,
) = range(len(OUTCOME_FIELDS))
N_OUTCOME = len(OUTCOME_FIELDS)
