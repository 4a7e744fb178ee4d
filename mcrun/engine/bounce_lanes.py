"""Bounce and roll lanes: once a task's shots have landed, their bounces run LANES at a time too.

One impact and hop of every lane per pass of vectorised loops (``bounce.impact`` and
``bounce.hop``, ``_impact_lanes``); a lane whose ball stops bouncing hands it to the roll table,
where LANES shots roll out together (``roll.roll_out_short``, or ``rolling.roll_out`` on their own
where that is not enough, ``_file_rolls``), and takes the next landed shot. The tables' rows are
``engine.tables``'s BOUNCE, INCIDENCE and REBOUND; a shot comes in as its LANDING.
"""

import math

import numpy as np
from numba import njit

from mcrun import ground
from mcrun.engine.rolling import roll_out
from mcrun.engine.shot import write_run
from mcrun.engine.tables import (
    BOUNCE,
    INCIDENCE,
    LANDING,
    LANES,
    NO_SHOTS,
    REBOUND,
    TRACER,
    any_lane_busy,
    input_turf,
)
from mcrun.ground import read_turf
from mcrun.physics.bounce import HOPS, TOO_MANY, hop, impact, impact_rebound, incidence
from mcrun.physics.constants import G_MPS2
from mcrun.physics.roll import roll_out_short
from mcrun.status import NOT_STOPPED, OK, TOO_MANY_BOUNCES
from mcrun.trajectory import BOUNCE as BOUNCE_PHASE
from mcrun.trajectory import record

# What comes after an impact (``bounce.impact``'s HOPS, ROLLS, TOO_MANY), or: its hop came down
# where the shot ends (STATE).
ENDS = -1.0


@njit(cache=True, error_model="numpy", inline="always")
def _lane_ground(b, k):
    """The ground under bounce lane k."""
    return ground.Plane(
        b[BOUNCE.NX * LANES + k], b[BOUNCE.NY * LANES + k], b[BOUNCE.NZ * LANES + k],
        read_turf(b, BOUNCE.TURF * LANES + k, LANES),
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def _set_lane_ground(b, k, nx, ny, nz, turf):
    """Rows NX.. and TURF.. of bounce lane k: the normal and turf of the ground under it."""
    b[BOUNCE.NX * LANES + k] = nx
    b[BOUNCE.NY * LANES + k] = ny
    b[BOUNCE.NZ * LANES + k] = nz
    for j, value in enumerate(turf):
        b[(BOUNCE.TURF + j) * LANES + k] = value


@njit(cache=True, error_model="numpy", inline="always")
def _incidences(b, e):
    """The equivalent surface of every bounce lane's impact (``bounce.incidence``) into e."""
    for k in range(LANES):
        under = _lane_ground(b, k)
        ex, ey, ez, vne, _ = incidence(
            b[BOUNCE.VX * LANES + k],
            b[BOUNCE.VY * LANES + k],
            b[BOUNCE.VZ * LANES + k],
            under.nx,
            under.ny,
            under.nz,
            under.turf,
        )
        e[INCIDENCE.EX * LANES + k] = ex
        e[INCIDENCE.EY * LANES + k] = ey
        e[INCIDENCE.EZ * LANES + k] = ez
        e[INCIDENCE.VNE * LANES + k] = vne


@njit(cache=True, error_model="numpy")
def _impact_lanes_on_plane(terrain, b, e, rb):
    """One impact, and the hop it starts, for every bounce lane on its Plane: ``bounce.impact``
    in two vectorised loops (as ``step_lanes``, so that the lanes' long chains overlap).
    Returns the number of lanes (empty ones included) whose ball no longer hops."""
    _incidences(b, e)
    ended = 0
    for k in range(LANES):
        under = _lane_ground(b, k)
        x = b[BOUNCE.X * LANES + k]
        y = b[BOUNCE.Y * LANES + k]
        nx, ny, nz = under.nx, under.ny, under.nz
        bounces = b[BOUNCE.BOUNCES * LANES + k]
        vx, vy, vz, wx, wy, wz, height, hop_time, then = impact_rebound(
            b[BOUNCE.VX * LANES + k],
            b[BOUNCE.VY * LANES + k],
            b[BOUNCE.VZ * LANES + k],
            b[BOUNCE.WX * LANES + k],
            b[BOUNCE.WY * LANES + k],
            b[BOUNCE.WZ * LANES + k],
            nx,
            ny,
            nz,
            e[INCIDENCE.EX * LANES + k],
            e[INCIDENCE.EY * LANES + k],
            e[INCIDENCE.EZ * LANES + k],
            e[INCIDENCE.VNE * LANES + k],
            under.turf,
            bounces,
            b[BOUNCE.PREVIOUS * LANES + k],
        )
        # (On a plane, always in play: the hop's end is the exact return to it.)
        x1, y1, z1, vz1, hop_time = ground.hop_landing(
            terrain, x, y, b[BOUNCE.Z * LANES + k], vx, vy, vz, hop_time
        )
        hops = then == HOPS
        first = hops & (bounces == 0)
        b[BOUNCE.FIRST_HEIGHT * LANES + k] = height if first else b[BOUNCE.FIRST_HEIGHT * LANES + k]
        b[BOUNCE.FIRST_LENGTH * LANES + k] = x1 - x if first else b[BOUNCE.FIRST_LENGTH * LANES + k]
        b[BOUNCE.X * LANES + k] = x1 if hops else x
        b[BOUNCE.Y * LANES + k] = y1 if hops else y
        b[BOUNCE.Z * LANES + k] = z1 if hops else b[BOUNCE.Z * LANES + k]
        b[BOUNCE.VX * LANES + k] = vx
        b[BOUNCE.VY * LANES + k] = vy
        b[BOUNCE.VZ * LANES + k] = vz1 if hops else vz
        b[BOUNCE.WX * LANES + k] = wx
        b[BOUNCE.WY * LANES + k] = wy
        b[BOUNCE.WZ * LANES + k] = wz
        b[BOUNCE.T * LANES + k] = (
            b[BOUNCE.T * LANES + k] + hop_time if hops else b[BOUNCE.T * LANES + k]
        )
        b[BOUNCE.PREVIOUS * LANES + k] = height if hops else b[BOUNCE.PREVIOUS * LANES + k]
        b[BOUNCE.BOUNCES * LANES + k] = bounces + 1.0 if hops else bounces
        b[BOUNCE.THEN * LANES + k] = then
        ended += 0 if then == HOPS else 1
    return ended


@njit(cache=True, error_model="numpy")
def _impact_lanes_on_grid(terrain, b, e, rb):
    """``_impact_lanes`` on a terrain: the impacts' rebounds, and their hops where the ground
    is calm (one plane and zone as far as the hop goes: there the plane's exact hop, as on a
    Plane), in vectorised loops (into the rebound table ``rb``), then each other lane's hop on
    the grid (``ground.hop_landing``) and the ground where it comes down (``ground.contact``).
    """
    _incidences(b, e)
    for k in range(LANES):
        under = _lane_ground(b, k)
        vx, vy, vz, wx, wy, wz, height, hop_time, then = impact_rebound(
            b[BOUNCE.VX * LANES + k],
            b[BOUNCE.VY * LANES + k],
            b[BOUNCE.VZ * LANES + k],
            b[BOUNCE.WX * LANES + k],
            b[BOUNCE.WY * LANES + k],
            b[BOUNCE.WZ * LANES + k],
            under.nx,
            under.ny,
            under.nz,
            e[INCIDENCE.EX * LANES + k],
            e[INCIDENCE.EY * LANES + k],
            e[INCIDENCE.EZ * LANES + k],
            e[INCIDENCE.VNE * LANES + k],
            under.turf,
            b[BOUNCE.BOUNCES * LANES + k],
            b[BOUNCE.PREVIOUS * LANES + k],
        )
        x1, y1, z1, vz1 = hop(
            b[BOUNCE.X * LANES + k],
            b[BOUNCE.Y * LANES + k],
            b[BOUNCE.Z * LANES + k],
            vx,
            vy,
            vz,
            hop_time,
        )
        calm = (hop_time > 0.0) & (
            math.sqrt(vx * vx + vy * vy) * hop_time <= b[BOUNCE.REACH * LANES + k]
        )
        rb[REBOUND.VX * LANES + k] = vx
        rb[REBOUND.VY * LANES + k] = vy
        rb[REBOUND.VZ * LANES + k] = vz
        rb[REBOUND.WX * LANES + k] = wx
        rb[REBOUND.WY * LANES + k] = wy
        rb[REBOUND.WZ * LANES + k] = wz
        rb[REBOUND.HEIGHT * LANES + k] = height
        rb[REBOUND.HOP_T * LANES + k] = hop_time
        rb[REBOUND.THEN * LANES + k] = then
        rb[REBOUND.X1 * LANES + k] = x1
        rb[REBOUND.Y1 * LANES + k] = y1
        rb[REBOUND.Z1 * LANES + k] = z1
        rb[REBOUND.VZ1 * LANES + k] = vz1
        rb[REBOUND.CALM * LANES + k] = 1.0 if calm else 0.0
    ended = 0
    for k in range(LANES):
        x = b[BOUNCE.X * LANES + k]
        y = b[BOUNCE.Y * LANES + k]
        vx = rb[REBOUND.VX * LANES + k]
        vy = rb[REBOUND.VY * LANES + k]
        vz = rb[REBOUND.VZ * LANES + k]
        height = rb[REBOUND.HEIGHT * LANES + k]
        then = rb[REBOUND.THEN * LANES + k]
        bounces = b[BOUNCE.BOUNCES * LANES + k]
        hops = then == HOPS
        vz1 = vz
        if hops:
            if rb[REBOUND.CALM * LANES + k] != 0.0:
                # On the plane and zone under the ball: its normal and turf stay.
                x1 = rb[REBOUND.X1 * LANES + k]
                y1 = rb[REBOUND.Y1 * LANES + k]
                z1 = rb[REBOUND.Z1 * LANES + k]
                vz1 = rb[REBOUND.VZ1 * LANES + k]
                hop_time = rb[REBOUND.HOP_T * LANES + k]
                state = OK
                b[BOUNCE.REACH * LANES + k] = ground.calm_reach(terrain, x1, y1)
            else:
                x1, y1, z1, vz1, hop_time = ground.hop_landing(
                    terrain,
                    x,
                    y,
                    b[BOUNCE.Z * LANES + k],
                    vx,
                    vy,
                    vz,
                    rb[REBOUND.HOP_T * LANES + k],
                )
                # The ground where it comes down: what the next impact asks of it.
                state, nx, ny, nz, turf, reach = ground.contact(terrain, _lane_ground(b, k), x1, y1)
                _set_lane_ground(b, k, nx, ny, nz, turf)
                b[BOUNCE.REACH * LANES + k] = reach
            b[BOUNCE.QX * LANES + k] = x
            b[BOUNCE.QY * LANES + k] = y
            b[BOUNCE.STATE * LANES + k] = state
            if state != OK:
                then = ENDS
            if bounces == 0:
                b[BOUNCE.FIRST_HEIGHT * LANES + k] = height
                b[BOUNCE.FIRST_LENGTH * LANES + k] = x1 - x
            b[BOUNCE.X * LANES + k] = x1
            b[BOUNCE.Y * LANES + k] = y1
            b[BOUNCE.Z * LANES + k] = z1
            b[BOUNCE.T * LANES + k] += hop_time
            b[BOUNCE.PREVIOUS * LANES + k] = height
            b[BOUNCE.BOUNCES * LANES + k] = bounces + 1.0
        b[BOUNCE.VX * LANES + k] = vx
        b[BOUNCE.VY * LANES + k] = vy
        b[BOUNCE.VZ * LANES + k] = vz1
        b[BOUNCE.WX * LANES + k] = rb[REBOUND.WX * LANES + k]
        b[BOUNCE.WY * LANES + k] = rb[REBOUND.WY * LANES + k]
        b[BOUNCE.WZ * LANES + k] = rb[REBOUND.WZ * LANES + k]
        b[BOUNCE.THEN * LANES + k] = then
        ended += 0 if then == HOPS else 1
    return ended


@njit(cache=True, error_model="numpy")
def _record_hop(b, k, before, traj, tracer, terrain):
    """The trajectory points of the hop bounce lane k has just made from the state ``before``
    (its rows before the impact): the impact taken again (``bounce.impact``, the same
    numbers), then the ballistic arc every DT_RECORD up to the hop's end."""
    s = before
    under = _lane_ground(b, k)  # (the ground where it hit: the impact does not change it)
    vx, vy, vz, _, _, _, _, _, _ = impact(
        s[BOUNCE.VX],
        s[BOUNCE.VY],
        s[BOUNCE.VZ],
        s[BOUNCE.WX],
        s[BOUNCE.WY],
        s[BOUNCE.WZ],
        under.nx,
        under.ny,
        under.nz,
        under.turf,
        s[BOUNCE.BOUNCES],
        s[BOUNCE.PREVIOUS],
    )
    n = int(tracer[TRACER.ROW])
    t = s[BOUNCE.T]
    while tracer[TRACER.T_NEXT] < b[BOUNCE.T * LANES + k]:
        h = tracer[TRACER.T_NEXT] - t
        n = record(
            traj, n, tracer[TRACER.T_NEXT], s[BOUNCE.X] + vx * h, s[BOUNCE.Y] + vy * h,
            s[BOUNCE.Z] + vz * h - 0.5 * G_MPS2 * h * h, BOUNCE_PHASE,
        )  # fmt: skip
        tracer[TRACER.T_NEXT] += tracer[TRACER.DT_RECORD]
    tracer[TRACER.ROW] = n


# One impact of every lane, on the kind of ground the kernel is compiled for (the other's loop
# is not compiled into it).
_impact_lanes = ground.by_ground(_impact_lanes_on_plane, _impact_lanes_on_grid)


@njit(cache=True, error_model="numpy")
def _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k, terrain):
    """Put the next landed shot of ``pending`` into bounce lane k (shot[k] = -1 if none)."""
    if next_j == pending.shape[0]:
        shot[k] = -1
        return next_j
    i = pending[next_j]
    g = landings[i - start]
    for row, value in (
        (BOUNCE.X, g[LANDING.X]),
        (BOUNCE.Y, g[LANDING.Y]),
        (BOUNCE.Z, ground.height_at(terrain, g[LANDING.X], g[LANDING.Y])),
        (BOUNCE.VX, g[LANDING.VX]),
        (BOUNCE.VY, g[LANDING.VY]),
        (BOUNCE.VZ, g[LANDING.VZ]),
        (BOUNCE.WX, g[LANDING.WX]),
        (BOUNCE.WY, g[LANDING.WY]),
        (BOUNCE.WZ, g[LANDING.WZ]),
        (BOUNCE.T, g[LANDING.T]),
        (BOUNCE.BOUNCES, 0.0),
        (BOUNCE.PREVIOUS, 0.0),
        (BOUNCE.FIRST_HEIGHT, 0.0),
        (BOUNCE.FIRST_LENGTH, 0.0),
        (BOUNCE.QX, g[LANDING.X]),
        (BOUNCE.QY, g[LANDING.Y]),
        (BOUNCE.STATE, float(OK)),
    ):
        b[row * LANES + k] = value
    # The ground where it landed: the Plane of the landing (its normal, the shot's turf), or
    # the terrain's there.
    _, nx, ny, nz, turf, reach = ground.contact(
        terrain,
        ground.Plane(g[LANDING.NX], g[LANDING.NY], g[LANDING.NZ], input_turf(inputs, i)),
        g[LANDING.X],
        g[LANDING.Y],
    )
    _set_lane_ground(b, k, nx, ny, nz, turf)
    b[BOUNCE.REACH * LANES + k] = reach
    shot[k] = i
    return next_j + 1


@njit(cache=True, error_model="numpy")
def _roll_lanes(r, terrain):
    """``roll.roll_out_short`` of every lane of the roll table ``r`` (the vectorised loop), on
    a Plane; on a terrain every ball rolls out on its own (``rolling.roll_out``), and nothing
    is asked here."""
    if ground.varies(terrain):
        for k in range(LANES):
            r[BOUNCE.SHORT * LANES + k] = 0.0
        return
    for k in range(LANES):
        under = _lane_ground(r, k)
        x = r[BOUNCE.X * LANES + k]
        y = r[BOUNCE.Y * LANES + k]
        nx, ny, nz = ground.normal_at(terrain, under, x, y)
        turf = ground.turf_at(terrain, under, x, y)
        x, y, t, short = roll_out_short(
            x,
            y,
            r[BOUNCE.Z * LANES + k],
            r[BOUNCE.VX * LANES + k],
            r[BOUNCE.VY * LANES + k],
            r[BOUNCE.VZ * LANES + k],
            r[BOUNCE.WX * LANES + k],
            r[BOUNCE.WY * LANES + k],
            r[BOUNCE.WZ * LANES + k],
            nx,
            ny,
            nz,
            turf.mu,
            turf.rho_g,
            r[BOUNCE.T * LANES + k],
        )
        r[BOUNCE.REST_X * LANES + k] = x
        r[BOUNCE.REST_Y * LANES + k] = y
        r[BOUNCE.REST_T * LANES + k] = t
        r[BOUNCE.SHORT * LANES + k] = 1.0 if short else 0.0


@njit(cache=True, error_model="numpy")
def _file_rolls(start, landings, r, count, out, traj, tracer, terrain):
    """Roll out the first ``count`` shots of the roll table ``r`` and write their run: LANES
    at a time by ``_roll_lanes``, and on their own (``rolling.roll_out``) where that is not
    enough, the ground is a terrain or the shot is traced."""
    _roll_lanes(r, terrain)
    for j in range(count):
        s = r[j::LANES]  # s[row] is row ``row`` of column j
        i = int(s[BOUNCE.SHOT])
        x, y, t, status = s[BOUNCE.REST_X], s[BOUNCE.REST_Y], s[BOUNCE.REST_T], OK
        # (On the Plane, the rest's height on it.)
        z = (
            s[BOUNCE.Z]
            - (s[BOUNCE.NX] * (x - s[BOUNCE.X]) + s[BOUNCE.NY] * (y - s[BOUNCE.Y])) / s[BOUNCE.NZ]
        )
        ref_x = np.nan
        ref_y = np.nan
        # The path's buffer, its next row and time, and its interval: the traced shot's, an
        # empty buffer for the others; none in a batch (its recording pruned from the kernel).
        if tracer is None:
            traced = False
            path, row, t_next, dt_record = traj, 0, s[BOUNCE.T], 0.0
        else:
            traced = i == tracer[TRACER.TRACED]
            path = traj if traced else traj[:0]
            row = int(tracer[TRACER.ROW]) if traced else 0
            t_next = tracer[TRACER.T_NEXT] if traced else s[BOUNCE.T]
            dt_record = tracer[TRACER.DT_RECORD]
        if s[BOUNCE.SHORT] == 0.0 or traced:
            x, y, z, t, status, n, qx, qy = roll_out(
                s[BOUNCE.X],
                s[BOUNCE.Y],
                s[BOUNCE.Z],
                s[BOUNCE.VX],
                s[BOUNCE.VY],
                s[BOUNCE.VZ],
                s[BOUNCE.WX],
                s[BOUNCE.WY],
                s[BOUNCE.WZ],
                terrain,
                _lane_ground(r, j),
                s[BOUNCE.T],
                path,
                row,
                t_next,
                dt_record,
            )
            if traced:
                tracer[TRACER.ROW] = n
            if status > NOT_STOPPED:
                ref_x, ref_y = ground.crossing(terrain, qx, qy, x, y)
            elif status == OK:
                # Out of bounds where it rests (Rule 18.2), not where it went over the line;
                # its reference point is its rest.
                status = ground.rest_state(terrain, x, y)
                if status != OK:
                    ref_x, ref_y = x, y
        landing_x = landings[i - start, LANDING.X]
        write_run(out, i, landing_x, x, y, z, t, status, s[BOUNCE.BOUNCES], s[BOUNCE.FIRST_HEIGHT],
                  s[BOUNCE.FIRST_LENGTH], ref_x, ref_y)  # fmt: skip


@njit(cache=True, error_model="numpy")
def bounce_all(inputs, start, landings, pending, out, traj, tracer, terrain):
    """The bounces and the roll of the landed shots ``pending``, LANES at a time; a shot that
    stops hopping waits in the roll table until LANES shots roll out together."""
    # (Of ones: see ``tables.LANES``.)
    b = np.ones(BOUNCE.N * LANES)
    r = np.ones(BOUNCE.N * LANES)  # the roll table
    e = np.ones(INCIDENCE.N * LANES)  # the equivalent surfaces of the impacts
    rb = np.ones(REBOUND.N * LANES)  # their rebounds, on a terrain
    before = np.zeros(BOUNCE.N)  # the traced lane before its impact
    waiting = NO_SHOTS  # shots in it
    shot = np.full(LANES, -1)
    next_j = NO_SHOTS
    for k in range(LANES):
        next_j = _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k, terrain)
    while any_lane_busy(shot):
        traced = -1
        if tracer is not None:  # (a batch has none: pruned from its kernel)
            for k in range(LANES):
                if shot[k] == tracer[TRACER.TRACED]:
                    traced = k
                    for row in range(BOUNCE.N):  # (a slice copy compiles a shape check)
                        before[row] = b[row * LANES + k]
        ended = _impact_lanes(terrain, b, e, rb)
        if tracer is not None:
            if traced >= 0 and (b[BOUNCE.THEN * LANES + traced] == HOPS) | (
                b[BOUNCE.THEN * LANES + traced] == ENDS
            ):
                _record_hop(b, traced, before, traj, tracer, terrain)
        if ended == 0:
            continue
        for k in range(LANES):
            i = shot[k]
            if i < 0:
                continue
            if b[BOUNCE.THEN * LANES + k] == HOPS:
                continue
            if b[BOUNCE.THEN * LANES + k] == TOO_MANY:
                s = b[k::LANES]  # s[row] is row ``row`` of lane k
                landing_x = landings[i - start, LANDING.X]
                write_run(
                    out,
                    i,
                    landing_x,
                    s[BOUNCE.X],
                    s[BOUNCE.Y],
                    s[BOUNCE.Z],
                    s[BOUNCE.T],
                    TOO_MANY_BOUNCES,
                    s[BOUNCE.BOUNCES],
                    s[BOUNCE.FIRST_HEIGHT],
                    s[BOUNCE.FIRST_LENGTH],
                    np.nan,
                    np.nan,
                )
            elif b[BOUNCE.THEN * LANES + k] == ENDS:
                s = b[k::LANES]
                ref_x, ref_y = ground.crossing(
                    terrain, s[BOUNCE.QX], s[BOUNCE.QY], s[BOUNCE.X], s[BOUNCE.Y]
                )
                write_run(
                    out,
                    i,
                    landings[i - start, LANDING.X],
                    s[BOUNCE.X],
                    s[BOUNCE.Y],
                    s[BOUNCE.Z],
                    s[BOUNCE.T],
                    int(s[BOUNCE.STATE]),
                    s[BOUNCE.BOUNCES],
                    s[BOUNCE.FIRST_HEIGHT],
                    s[BOUNCE.FIRST_LENGTH],
                    ref_x,
                    ref_y,
                )
            else:
                for row in range(BOUNCE.N):
                    r[row * LANES + waiting] = b[row * LANES + k]
                r[BOUNCE.SHOT * LANES + waiting] = i
                waiting += 1
                if waiting == LANES:
                    _file_rolls(start, landings, r, waiting, out, traj, tracer, terrain)
                    waiting = NO_SHOTS
            next_j = _load_bounce_lane(
                inputs, landings, start, pending, next_j, b, shot, k, terrain
            )
    if waiting > 0:
        _file_rolls(start, landings, r, waiting, out, traj, tracer, terrain)
