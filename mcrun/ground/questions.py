"""The questions the shot loop asks of the ground, each answered on both kinds of ground.

Each question is one function of (terrain, ...): with ``terrain`` None the shot's own Plane
(``ground.plane``) answers and the flight comes down to z = 0, exactly as the slope model
always has; with a Terrain its grid answers (``ground.grid``, ``ground.hop_search``). Numba compiles
the loop once for each (``question``: an ``overload`` picks the answer by the type of
``terrain``), so the plane's loop is the same code, and the same numbers, as before there were
terrains; run as Python (``NUMBA_DISABLE_JIT=1``), the same answer is picked by the value.
"""

import functools
import math

from numba import njit, types
from numba.core import errors
from numba.extending import overload

from mcrun.ground.grid import (
    _grid_calm_reach,
    _grid_contact,
    _grid_crossing,
    _grid_flight_check,
    _grid_gradient,
    _grid_height,
    _grid_normal,
    _grid_rest_state,
    _grid_state,
    _grid_surface,
    _grid_turf,
)
from mcrun.ground.hop_search import _grid_hop
from mcrun.ground.plane import plane_surface
from mcrun.ground.terrain import borrowed, is_view
from mcrun.physics.bounce import hop
from mcrun.status import OK


def _flat(terrain):
    """Whether ``terrain`` (a value, or its Numba type) is none: the shot's own Plane."""
    return terrain is None or isinstance(terrain, types.NoneType)


def _unviewed(terrain):
    """Whether ``terrain`` (a value, or its Numba type) is a Terrain that the grid's answers
    read through its view (``borrowed``), not the view itself or a Plane's None."""
    return not (_flat(terrain) or is_view(terrain))


def question(answers):
    """A question to the ground: ``answers(terrain, ...)`` returns the function that answers it
    on this kind of ground (``_flat``), called with the same arguments; the grid's answers take
    the Terrain's view (``terrain.TerrainView``). Compiled, it is an ``overload``, inlined, that
    picks the answer by the type of ``terrain`` once, and a kernel asks of the view it borrowed
    (``borrowed``, where it is given a Terrain); called from Python, or as Python
    (``NUMBA_DISABLE_JIT=1``), a question asked of a Terrain is asked of its view and the answer
    is picked at each call."""

    def ask(terrain, *args):
        if _unviewed(terrain):
            terrain = borrowed(terrain)
        return answers(terrain, *args)(terrain, *args)

    @functools.wraps(answers)
    def typed(terrain, *args):
        if _unviewed(terrain):
            raise errors.TypingError(
                f"{answers.__name__}: compiled code asks the ground of a Terrain's view: pass "
                f"ground.borrowed(terrain), not {terrain}"
            )
        return answers(terrain, *args)

    ask.__name__ = ask.__qualname__ = answers.__name__
    ask.__doc__ = answers.__doc__
    overload(ask, inline="always")(typed)
    return ask


def by_ground(on_plane, on_grid):
    """A call ``f(terrain, a, b, c)`` of ``on_plane(terrain, a, b, c)`` on a Plane and of
    ``on_grid(terrain, a, b, c)`` on a grid, picked by the type of ``terrain`` as a question's
    answer is: the kernel of each kind of ground compiles its own alone (a loop written for
    one kind costs the other's compile nothing)."""

    def answers(terrain, a, b, c):
        if _flat(terrain):
            return lambda terrain, a, b, c: on_plane(terrain, a, b, c)
        return lambda terrain, a, b, c: on_grid(terrain, a, b, c)

    answers.__name__ = on_plane.__name__
    return question(answers)


@question
def height_at(terrain, x, y):
    """Height (m) of the ground's surface at (x, y): where the flight ends. On a Plane the flight
    comes down to z = 0 and the plane through the landing point is the landing area."""
    if _flat(terrain):
        return lambda terrain, x, y: 0.0
    return lambda terrain, x, y: _grid_height(terrain, x, y)


@question
def clearance(terrain, x, y, z):
    """Height (m) of a ball at (x, y, z) above the ground, and its rate of change at velocity
    (vx, vy, vz): z - h and vz - grad(h).v. On a Plane, z and vz themselves."""
    if _flat(terrain):
        return lambda terrain, x, y, z: z
    return lambda terrain, x, y, z: z - _grid_height(terrain, x, y)


@question
def clearance_rate(terrain, x, y, vx, vy, vz):
    """d/dt of ``clearance`` for a ball at (x, y) moving at (vx, vy, vz)."""
    if _flat(terrain):
        return lambda terrain, x, y, vx, vy, vz: vz

    def rate(terrain, x, y, vx, vy, vz):
        hx, hy = _grid_gradient(terrain, x, y)
        return vz - (hx * vx + hy * vy)

    return rate


@question
def flight_check(terrain, x, y, z):
    """What a flight step asks of the ground where it ends, (x, y, z), in one look-up: the
    ball's height above it (``clearance``) and the state of the ground under it
    (``state_at``)."""
    if _flat(terrain):
        return lambda terrain, x, y, z: (z, OK)
    return lambda terrain, x, y, z: _grid_flight_check(terrain, x, y, z)


@question
def normal_at(terrain, plane, x, y):
    """Unit normal (nx, ny, nz) of the ground at (x, y), core frame: the Plane's, or the grid's
    (-dh/dx, -dh/dy, 1) normalised."""
    if _flat(terrain):
        return lambda terrain, plane, x, y: (plane.nx, plane.ny, plane.nz)
    return lambda terrain, plane, x, y: _grid_normal(terrain, x, y)


@question
def normal_or(terrain, nx, ny, nz, x, y):
    """``normal_at`` where the Plane's normal is (nx, ny, nz)."""
    if _flat(terrain):
        return lambda terrain, nx, ny, nz, x, y: (nx, ny, nz)
    return lambda terrain, nx, ny, nz, x, y: _grid_normal(terrain, x, y)


@question
def turf_at(terrain, plane, x, y):
    """The turf of the ground at (x, y): the Plane's, or that of the zone there."""
    if _flat(terrain):
        return lambda terrain, plane, x, y: plane.turf
    return lambda terrain, plane, x, y: _grid_turf(terrain, x, y)


# Where the ball touches the ground, for the Rules (``state_at``): in play, or a place where the
# shot ends there (its status, ``mcrun.status``); and where it rests (``rest_state``).
@question
def state_at(terrain, x, y):
    """OK where a moving ball plays on at (x, y); IN_PENALTY_AREA or OFF_MAP (``mcrun.status``)
    where its shot ends there (Rule 17: a ball that touches a penalty area is in it). Out of
    bounds is OK here: the ball is played on over it like any ground (its zone's turf), and only
    where it comes to rest does ``rest_state`` say it is out (Rule 18.2). Always OK on a
    Plane."""
    if _flat(terrain):
        return lambda terrain, x, y: OK
    return lambda terrain, x, y: _grid_state(terrain, x, y)


@question
def rest_state(terrain, x, y):
    """The status of a ball that comes to rest at (x, y), in play: OUT_OF_BOUNDS_STATUS where
    the zone there is out of bounds (Rule 18.2: a ball is out of bounds only when it lies
    outside the boundary at rest; the zone is that of the node nearest the ball's centre), OK
    elsewhere. Always OK on a Plane."""
    if _flat(terrain):
        return lambda terrain, x, y: OK
    return lambda terrain, x, y: _grid_rest_state(terrain, x, y)


@question
def contact(terrain, plane, x, y):
    """What an impact asks of the ground at (x, y), in one look-up: the state there
    (``state_at``), its unit normal (``normal_at``) and turf (``turf_at``), and its
    ``calm_reach``."""
    if _flat(terrain):
        return lambda terrain, plane, x, y: (
            OK, plane.nx, plane.ny, plane.nz, plane.turf, math.inf
        )  # fmt: skip
    return lambda terrain, plane, x, y: _grid_contact(terrain, x, y)


@question
def calm_reach(terrain, x, y):
    """How far (m) a ball at (x, y) may go in any direction on one plane of one zone: the
    ``calm_cells`` of the cell under it, in metres (0 where the ground bends or the zone
    changes there; no limit on a Plane)."""
    if _flat(terrain):
        return lambda terrain, x, y: math.inf
    return lambda terrain, x, y: _grid_calm_reach(terrain, x, y)


@question
def _surface(terrain, plane, x, y, z):
    """The Surface at (x, y): ``surface``."""
    if _flat(terrain):
        return lambda terrain, plane, x, y, z: plane_surface(plane, z)
    return lambda terrain, plane, x, y, z: _grid_surface(terrain, x, y)


@njit(cache=True, error_model="numpy")
def surface(terrain, plane, x, y, z):
    """What the roll asks at each step (``engine.rolling``; a call, not inlined at the roll's
    five calls, which would cost compile time and nothing else): the Surface at
    (x, y), ball height z: on a Plane, z itself (the ball stays on the plane), its normal and
    turf, always in play, no limit to a step and no patch; on a grid, the height of the ground
    there, its normal and turf, the state there (``state_at``), a quarter of a cell, or the
    cell's calm reach, as the longest step, and the smooth patch of ground around it, where the
    roll may step further."""
    return _surface(terrain, plane, x, y, z)


@question
def varies(terrain):
    """Whether the ground changes from place to place (a grid), so that the shot loop must ask
    it anew where the ball goes; a Plane does not."""
    if _flat(terrain):
        return lambda terrain: False
    return lambda terrain: True


@question
def step_length(terrain):
    """The longest step (m) of a ball along the ground anywhere: a quarter of a cell of the
    grid, within which its slope changes little (``surface`` gives longer ones on calm
    ground); no limit on a Plane."""
    if _flat(terrain):
        return lambda terrain: math.inf
    return lambda terrain: 0.25 * terrain.cell_m


@question
def hop_landing(terrain, x, y, z, vx, vy, vz, hop_time):
    """Where a hop from (x, y, z) at velocity (vx, vy, vz) meets the ground again: (x, y, z,
    vz, t) at its end. On a Plane, after ``hop_time`` (the exact return to the plane, from
    ``bounce.impact``); on a grid, the first time its parabola goes below the surface."""
    if _flat(terrain):

        def on_plane(terrain, x, y, z, vx, vy, vz, hop_time):
            x1, y1, z1, vz1 = hop(x, y, z, vx, vy, vz, hop_time)
            return x1, y1, z1, vz1, hop_time

        return on_plane
    return lambda terrain, x, y, z, vx, vy, vz, hop_time: _grid_hop(
        terrain, x, y, z, vx, vy, vz, hop_time
    )


@question
def crossing(terrain, xa, ya, xb, yb):
    """Where the ground track from (xa, ya), in play, to (xb, yb), not, crosses into what ends
    the shot there (``state_at``: a penalty area, or off the map; out of bounds counts as in
    play): the Rules' reference point, to a millimetre. On a Plane (always in play), (xb,
    yb)."""
    if _flat(terrain):
        return lambda terrain, xa, ya, xb, yb: (xb, yb)
    return lambda terrain, xa, ya, xb, yb: _grid_crossing(terrain, xa, ya, xb, yb)
