"""The ground under the ball: what the shot loop asks of it, and the two kinds there are.

The shot loop (``engine.batch``) holds no slope or turf of its own: it asks the ground, where
the ball is, for the ball's height above it (``clearance``, ``clearance_rate``: the flight ends
where it goes below; ``flight_check`` with the state under it, at each flight step), its normal
and turf (``normal_at``, ``turf_at``; ``contact`` with the state and the ``calm_reach``, where a
ball comes down for its next impact), where a hop comes down on it (``hop_landing``), what the
roll needs at each step (``surface``: height, normal, turf, state, the longest step), the state
there under the Rules for a moving ball (``state_at``: in play, or a penalty area or off the map,
where the shot ends at once), where the ball crossed into such a place (``crossing``), and the
status of a ball at rest (``rest_state``: out of bounds or not). Out of bounds is ground like
any other while the ball moves, with its zone's turf: a ball is out only where it comes to rest
on it (Rule 18.2), so one that hops over the boundary and back in is in bounds. The questions
a loop asks at every step are answered in one look-up of the grid each. Two kinds of ground answer:

- a shot's own ``Plane`` (``terrain`` None): the slope model. The flight comes down to z = 0 and
  the landing area is the plane of the shot's slope through the landing point, of one turf,
  built from the shot's input row;
- a hole's ``Terrain`` (``make_terrain``): heights on a grid, bilinear between nodes, and a zone
  per node with its turf and what it is for the Rules (in play, penalty area, out of bounds).

Each question is a Numba ``overload`` on the type of ``terrain`` (``questions.question``), so
the loop is compiled once for each kind, and the Plane's loop is the same code, with the same
numbers, as before there were terrains. Compiled code asks the grid's questions of a Terrain's
view (``borrowed``: ten numbers, its arrays as pointers), which a kernel borrows once.

Where things are: ``questions`` (the questions, each answered on both kinds), ``plane`` (a
shot's own Plane), ``terrain`` (a hole's Terrain, its build, and the view of it a kernel's task
borrows), ``grid`` (the look-ups of its grid), ``hop_search`` (where a hop comes down on it).
The types the roll reads, ``Surface`` and its ``Patch``, are the physics' (``physics.roll``).
"""

from mcrun.ground.plane import Plane, plane
from mcrun.ground.questions import (
    by_ground,
    calm_reach,
    clearance,
    clearance_rate,
    contact,
    crossing,
    flight_check,
    height_at,
    hop_landing,
    normal_at,
    normal_or,
    rest_state,
    state_at,
    step_length,
    surface,
    turf_at,
    varies,
)
from mcrun.ground.terrain import (
    IN_PLAY,
    MAX_CALM_CELLS,
    OUT_OF_BOUNDS,
    PENALTY_AREA,
    Terrain,
    TerrainView,
    borrowed,
    calm_cells,
    make_terrain,
    read_turf,
)
from mcrun.physics.roll import LEVEL_PATCH, NO_PATCH, Patch, Surface

__all__ = [
    "IN_PLAY",
    "LEVEL_PATCH",
    "MAX_CALM_CELLS",
    "NO_PATCH",
    "OUT_OF_BOUNDS",
    "PENALTY_AREA",
    "Patch",
    "Plane",
    "Surface",
    "Terrain",
    "TerrainView",
    "borrowed",
    "by_ground",
    "calm_cells",
    "calm_reach",
    "clearance",
    "clearance_rate",
    "contact",
    "crossing",
    "flight_check",
    "height_at",
    "hop_landing",
    "make_terrain",
    "normal_at",
    "normal_or",
    "plane",
    "read_turf",
    "rest_state",
    "state_at",
    "step_length",
    "surface",
    "turf_at",
    "varies",
]
