"""Status codes of a shot: the kernels return one instead of raising."""

OK = 0
INVALID_INPUT = 1  # a non-finite or out-of-range input reached the kernel
NOT_LANDED = 2  # still in the air after the flight time bound
TOO_MANY_BOUNCES = 3  # still bouncing after the bounce bound
NOT_STOPPED = (
    4  # still rolling after the roll time or distance bound (e.g. a slope steeper than atan(rho_g))
)

NAMES = {
    OK: "ok",
    INVALID_INPUT: "invalid_input",
    NOT_LANDED: "not_landed",
    TOO_MANY_BOUNCES: "too_many_bounces",
    NOT_STOPPED: "not_stopped",
}

# Bounds that make every shot end.
MAX_FLIGHT_TIME_S = 60.0
# The bouncing ends by the rules of ``bounce.impact`` (critical height, hop decay) within
# about 110 impacts for any landing and slope (20,000 random landings on 0-10 deg); this bound
# is only a guard against an endless loop.
MAX_BOUNCES = 1000
MAX_ROLL_TIME_S = 120.0
MAX_ROLL_DISTANCE_M = 1000.0
