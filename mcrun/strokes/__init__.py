"""Expected strokes to hole out and strokes gained: the PGA Tour baseline (Broadie 2012) or a
user's, and the expected strokes left after each shot of a run on a hole (docs/strokes.md)."""

from mcrun.strokes.baseline import (
    LIES,
    Baseline,
    BaselineError,
    load_baseline,
    tour_baseline,
)
from mcrun.strokes.expected import (
    LIE_OF_ZONE,
    OUTCOMES,
    PUTTING_COLUMNS,
    SHOT_COLUMNS,
    check_lie_of_zone,
    point_strokes,
    score_shots,
    start_of,
)

__all__ = [
    "LIES",
    "LIE_OF_ZONE",
    "OUTCOMES",
    "PUTTING_COLUMNS",
    "SHOT_COLUMNS",
    "Baseline",
    "BaselineError",
    "check_lie_of_zone",
    "load_baseline",
    "point_strokes",
    "score_shots",
    "start_of",
    "tour_baseline",
]
