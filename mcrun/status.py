"""Status codes of a shot: the kernels return one instead of raising."""

OK = 0
INVALID_INPUT = 1  # a non-finite or out-of-range input reached the kernel
NOT_LANDED = 2  # still in the air after the flight time bound
TOO_MANY_BOUNCES = 3  # still bouncing after the bounce bound
NOT_STOPPED = (
    4  # still rolling after the roll time or distance bound (e.g. a slope steeper than atan(rho_g))
)

# On a hole (``mcrun.ground.Terrain``). A ball that touches a penalty area or leaves the grid
# ends there at once, with (penalty_x_m, penalty_y_m) where its ground track crossed into it;
# out of bounds is decided where the ball comes to rest (Rule 18.2: a ball that hops or rolls
# over the boundary and back in is in bounds), and (penalty_x_m, penalty_y_m) is that rest
# position, the final one (scoring plays it again from its start: stroke and distance).
IN_PENALTY_AREA = 5  # it landed or rolled into a penalty area (water)
OUT_OF_BOUNDS_STATUS = 6  # it came to rest out of bounds
OFF_MAP = 7  # it left the hole's grid, where the ground is not known

HOLE_STATUSES = (IN_PENALTY_AREA, OUT_OF_BOUNDS_STATUS, OFF_MAP)

# A putt's roll (``putting.roll``) ends OK (at rest on the green), NOT_STOPPED (still rolling at
# its time cap: on a slope steeper than its stopping slope, or not), or one of these. They are
# not a shot's (``NAMES``): no putt's status is written to a run's Parquet.
HOLED = 8  # it dropped in the cup
OFF_GREEN = 9  # it left the green (or its grid): a chip from where it left

NAMES = {
    OK: "ok",
    INVALID_INPUT: "invalid_input",
    NOT_LANDED: "not_landed",
    TOO_MANY_BOUNCES: "too_many_bounces",
    NOT_STOPPED: "not_stopped",
    IN_PENALTY_AREA: "penalty_area",
    OUT_OF_BOUNDS_STATUS: "out_of_bounds",
    OFF_MAP: "off_map",
}

# Bounds that make every shot end.
MAX_FLIGHT_TIME_S = 60.0
# The bouncing ends by the rules of ``bounce.impact`` (critical height, hop decay) within
# about 110 impacts for any landing and slope (20,000 random landings on 0-10 deg); this bound
# is only a guard against an endless loop.
MAX_BOUNCES = 1000
MAX_ROLL_TIME_S = 120.0
MAX_ROLL_DISTANCE_M = 1000.0
