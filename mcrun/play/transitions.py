"""The transitions of a hole's decision process: every action (a club, at a power, and an aim)
flown from every state it fits, the same ``n`` sampled shots of the club from every state and
aim (common random numbers), and where each shot left the ball, in a compact form.

Aims (``AIMS``): the pin, and 2 and 4 deg either side of the line to it; where the club stops
short of the pin (its mean total on the level under ``reach``), the point of the hole's line
(its centre line, tee to green) that far along it, and 3 deg either side: the fairway and
lay-up targets. A club fits a state when its mean total is under the distance to the pin plus
``OVERSHOOT_M`` or a tenth of it (hitting well over the green is never the best), and the
shortest shot of the bag (the wedge at its least power) fits every state.

A shot's kind (``KINDS``): ``PLAY`` at rest in play off the green (its point and lie);
``GREEN`` at rest on the green (its expected putts: the hole's putting map, or the baseline's
putts by distance); ``WATER`` in a penalty area (the drop: for a red area the reference point,
from the fairway where it lies on mown grass and from the rough otherwise, as the scores do;
for a yellow one the first point in play on the line from the pin through the reference point,
behind it); ``RESTART`` out of bounds or off the map (stroke and distance); ``FAILED`` (left
out of the means).
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from mcrun import status
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import OUTCOME_FIELDS
from mcrun.executor import Executor
from mcrun.hole.zones import MOWN_ZONES, ZONE_KINDS
from mcrun.play.lattice import GREEN_LIE, LIE_CODE_OF_ZONE, TEE_LIE
from mcrun.play.player import LIE_LAUNCH, PART_POWERS, club_shots, lie_launch, tee_only
from mcrun.run import starts
from mcrun.strokes.baseline import HOLE_RADIUS_M, LIES

__all__ = ["AIMS", "KINDS", "Action", "Option", "Transitions", "fly", "options_of", "plan_actions"]

PLAY, GREEN, WATER, RESTART, FAILED = range(5)
KINDS = ("play", "green", "water", "restart", "failed")
# (target, angle deg + right of the line to it)
AIMS = (("pin", 0.0), ("pin", -2.0), ("pin", 2.0), ("pin", -4.0), ("pin", 4.0),
        ("line", 0.0), ("line", -3.0), ("line", 3.0))  # fmt: skip
OVERSHOOT_M = 20.0
DROP_BLOCK = 8  # the metres behind a yellow area's reference point tried at once
_OUT = {name: k for k, name in enumerate(OUTCOME_FIELDS)}


@dataclass(frozen=True)
class Action:
    club: int  # the point of the player's scenario
    power: float  # ball speed and spin times this (1: a full shot)
    aim: int  # index of AIMS
    total_m: float  # the shot's mean total on the level, full power

    def name(self, clubs):
        """In words, with the bag's club names ``clubs``: "PW 40% at the line 3 deg right"."""
        power = "" if self.power == 1.0 else f" {100 * self.power:.0f}%"
        target, angle = AIMS[self.aim]
        side = "" if angle == 0 else f" {abs(angle):g} deg {'right' if angle > 0 else 'left'}"
        return f"{clubs[self.club]}{power} at the {target}{side}"


@dataclass
class Transitions:
    """Every row (a state and an action): ``row_state``, ``row_action`` (index of
    ``actions``), and its shots ``row_start[r]`` .. ``row_start[r + 1]`` in the arrays ``kind``,
    ``lie`` (codes of LIES), ``x``, ``y`` (where it rests or drops), ``const`` (a shot on the
    green: its expected putts)."""

    actions: list
    row_state: np.ndarray
    row_action: np.ndarray
    row_start: np.ndarray
    kind: np.ndarray
    lie: np.ndarray
    x: np.ndarray
    y: np.ndarray
    const: np.ndarray
    n: int
    shots_flown: int


FROM = ("any", "tee", "ground")


@dataclass(frozen=True)
class Option:
    """A club at a power, its ``n`` shots' kernel inputs, and what they do on the level (the
    plane's ground, the club's own turf and weather): the mean total, the mean carry and the
    longest total of its shots (m); its pattern factor from the rough (``Player.rough_of``) and
    where it is struck from (``FROM``: "any" lie, the "tee" only, or the "ground", every lie but
    the tee's)."""

    club: int
    power: float
    inputs: np.ndarray
    total_m: float
    carry_m: float
    longest_m: float
    rough: float = LIE_LAUNCH["rough"][2]
    where: str = "any"


def _on_the_level(inputs):
    """(mean total, mean carry, longest total) m of ``inputs`` flown on the plane."""
    out = simulate_batch(np.asfortranarray(inputs.copy()))
    total, carry = out[:, _OUT["total_m"]], out[:, _OUT["carry_m"]]
    if not np.isfinite(total).any():
        return math.nan, math.nan, math.nan
    return float(np.nanmean(total)), float(np.nanmean(carry)), float(np.nanmax(total))


def options_of(scenario, n, player):
    """The ``Option`` of every full club of ``player`` (a ``Player``) on its ``scenario`` (the
    player's own, or one of its holes: ``player.on_hole``), each at its spread, ball speed
    factor and rough's factor, and of the wedge's part powers. A club struck from the tee only
    (``player.tee_only``) is an option from the tee; a club with a spread of its own off the
    ground (``Player.ground``) is two, one from the tee and one from every other lie."""
    options = []
    last = len(scenario.points) - 1
    for club in range(len(scenario.points)):
        spread, speed = player.spread[club], player.speed_of(club)
        ground = player.ground_of(club)
        if tee_only(player.clubs[club]) and club != last:  # (a bag of one club plays it)
            struck = (("tee", spread),)
        elif ground != 1.0:
            struck = (("tee", spread), ("ground", spread * ground))
        else:
            struck = (("any", spread),)
        for power in (1.0, *(PART_POWERS if club == last else ())):
            for where, factor in struck:
                inputs = club_shots(scenario, club, n, power, factor, speed)
                options.append(Option(club, power, inputs, *_on_the_level(inputs),
                                      rough=player.rough_of(club, power), where=where))  # fmt: skip
    return options


def _line_point(line, x0, y0, ahead_m):
    """The point of the polyline ``line`` ``ahead_m`` along it beyond the projection of
    (x0, y0) on it (arrays of starts), the line's end at most."""
    seg = np.diff(line, axis=0)
    length = np.hypot(seg[:, 0], seg[:, 1])
    arc = np.r_[0.0, np.cumsum(length)]
    best_arc = np.zeros(len(x0))
    best_d = np.full(len(x0), np.inf)
    for k in range(len(seg)):
        if length[k] == 0:
            continue
        t = ((x0 - line[k, 0]) * seg[k, 0] + (y0 - line[k, 1]) * seg[k, 1]) / length[k] ** 2
        t = np.clip(t, 0.0, 1.0)
        d = np.hypot(line[k, 0] + t * seg[k, 0] - x0, line[k, 1] + t * seg[k, 1] - y0)
        closer = d < best_d
        best_d = np.where(closer, d, best_d)
        best_arc = np.where(closer, arc[k] + t * length[k], best_arc)
    target = np.minimum(best_arc + ahead_m, arc[-1])
    k = np.clip(np.searchsorted(arc, target, side="right") - 1, 0, len(seg) - 1)
    t = (target - arc[k]) / np.where(length[k] > 0, length[k], 1.0)
    return line[k, 0] + t * seg[k, 0], line[k, 1] + t * seg[k, 1]


def _aims(hole, xy, aim, total_m):
    """The aim points (m, 2) of ``AIMS[aim]`` from the starts ``xy``; None where the aim is not
    offered (a line aim of a club that reaches the pin, or of a hole without a line)."""
    target, angle = AIMS[aim]
    px, py = hole.pin_xy
    dist = np.hypot(px - xy[:, 0], py - xy[:, 1])
    if target == "pin":
        tx, ty = np.full(len(xy), px), np.full(len(xy), py)
        offered = np.ones(len(xy), dtype=bool)
    else:
        if hole.line_xy is None or len(hole.line_xy) < 2:
            return None, np.zeros(len(xy), dtype=bool)
        line = np.vstack([hole.line_xy[hole.line_xy[:, 0] > 0.0], [hole.pin_xy]])
        line = np.vstack([[(0.0, 0.0)], line])
        tx, ty = _line_point(line, xy[:, 0], xy[:, 1], total_m)
        offered = total_m < dist - OVERSHOOT_M
    bearing = np.arctan2(ty - xy[:, 1], tx - xy[:, 0]) + math.radians(angle)
    reach = np.maximum(np.hypot(tx - xy[:, 0], ty - xy[:, 1]), 1.0)
    return np.column_stack([xy[:, 0] + reach * np.cos(bearing),
                            xy[:, 1] + reach * np.sin(bearing)]), offered  # fmt: skip


def _drops(hole, rx, ry, area):
    """(x, y, lie code) of the drop of balls in a penalty area of kind ``area`` (zone codes)
    that crossed into it at (rx, ry)."""
    px, py = hole.pin_xy
    mown = np.isin(hole.zone_at(rx, ry), [ZONE_KINDS.index(z) for z in MOWN_ZONES])
    lie = np.where(mown, LIES.index("fairway"), LIES.index("rough")).astype(np.int8)
    x, y = rx.copy(), ry.copy()
    yellow = area == ZONE_KINDS.index("water_yellow")
    if yellow.any():
        dx, dy = rx[yellow] - px, ry[yellow] - py
        d0 = np.maximum(np.hypot(dx, dy), 1e-9)
        ux, uy = dx / d0, dy / d0
        # Every metre behind, up to 100 m (none in play: the first), a block of them at a time.
        behind = np.arange(1.0, 101.0)
        first = np.zeros(len(d0), dtype=np.int64)
        left = np.arange(len(d0))
        for a in range(0, len(behind), DROP_BLOCK):
            steps = behind[a : a + DROP_BLOCK]
            bx = px + ux[left, None] * (d0[left, None] + steps)
            by = py + uy[left, None] * (d0[left, None] + steps)
            playable = hole.in_play_at(bx, by)
            found = playable.any(axis=1)
            first[left[found]] = a + np.argmax(playable[found], axis=1)
            left = left[~found]
            if left.size == 0:
                break
        x[yellow] = px + ux * (d0 + behind[first])
        y[yellow] = py + uy * (d0 + behind[first])
        zone = hole.zone_at(x[yellow], y[yellow])
        code = LIE_CODE_OF_ZONE[np.maximum(zone, 0)]
        lie[yellow] = np.where(code >= 0, code, LIES.index("rough"))
    return x, y, lie


def _classify(hole, out, putting, baseline):
    """(kind, lie, x, y, const) of every shot of ``out`` (the kernel's outcomes)."""
    state = out[:, _OUT["status"]].astype(np.int64)
    fx, fy = out[:, _OUT["final_x_m"]], out[:, _OUT["final_y_m"]]
    m = len(state)
    kind = np.full(m, FAILED, dtype=np.int8)
    lie = np.full(m, -1, dtype=np.int8)
    const = np.zeros(m)
    x, y = fx.copy(), fy.copy()
    ok = state == status.OK
    zone = np.where(ok, hole.zone_at(np.where(ok, fx, 0.0), np.where(ok, fy, 0.0)), -1)
    code = np.where(zone >= 0, LIE_CODE_OF_ZONE[np.maximum(zone, 0)], -1)
    green = ok & (code == GREEN_LIE)
    kind[green] = GREEN
    if green.any():
        d = np.hypot(fx[green] - hole.pin_xy[0], fy[green] - hole.pin_xy[1])
        if putting is None:
            const[green] = baseline.expected("green", d)
        else:
            const[green] = putting.value_at(fx[green], fy[green])[0]
        const[green] = np.where(d <= HOLE_RADIUS_M, 0.0, const[green])
    play = ok & (code >= 0) & (code != GREEN_LIE)
    kind[play] = PLAY
    lie[play] = code[play]
    restart = (state == status.OUT_OF_BOUNDS_STATUS) | (state == status.OFF_MAP) | (ok & (code < 0))
    kind[restart] = RESTART
    water = state == status.IN_PENALTY_AREA
    if water.any():
        rx, ry = out[water, _OUT["penalty_x_m"]], out[water, _OUT["penalty_y_m"]]
        area = hole.penalty_area_at(fx[water], fy[water])
        x[water], y[water], lie[water] = _drops(hole, rx, ry, area)
        kind[water] = WATER
    return kind, lie, x, y, const


def _batch(scenario, putting, baseline, n, job):
    """A job of ``fly`` (a task of the executor): the classified shots (kind, lie, x, y, const)
    of its club's n shots ``inputs`` struck from its states ``xy`` (their ``lies``) at its aim
    ``points``."""
    club, inputs, xy, points, lies, rough = job
    out = starts.flown_from(scenario, club, inputs, xy, (points[:, 0], points[:, 1]),
                            launch=lambda batch: lie_launch(batch, lies, n, rough))  # fmt: skip
    return _classify(scenario.hole, out, putting, baseline)


@njit(cache=True, nogil=True)
def _put_rows(column, where, values):
    """column[where[j]] = the j-th n values of ``values`` (n, column's width), for every j: a
    job's shots put in their rows' places, without the GIL, in half the time NumPy's fancy
    indexing takes in a solve (most of what is left is the first touch of the rows' pages)."""
    n = column.shape[1]
    for j in range(where.shape[0]):
        for i in range(n):
            column[where[j], i] = values[j * n + i]


def plan_actions(hole, lat, options, chunk_rows=256):
    """(actions, jobs) of the ``options`` (``options_of``) over the states of ``lat`` on
    ``hole``: every action (an option and an aim) with the states it fits, and the jobs that
    fly them, (rows, action, club, inputs, aim points, rough's factor) of up to ``chunk_rows``
    states each. An option struck from the tee (``Option.where``) fits the tee's states only,
    one struck from the ground every other."""
    px, py = hole.pin_xy
    dist = np.hypot(px - lat.xy[:, 0], py - lat.xy[:, 1])
    shortest = min(range(len(options)), key=lambda k: options[k].total_m)
    actions, jobs = [], []
    for k, option in enumerate(options):
        total = option.total_m
        fits = total <= dist + np.maximum(OVERSHOOT_M, 0.1 * dist)
        if k == shortest:
            fits[:] = True
        if option.where != "any":
            fits &= (lat.lie == TEE_LIE) == (option.where == "tee")
        for aim in range(len(AIMS)):
            points, offered = _aims(hole, lat.xy, aim, total)
            chosen = np.flatnonzero(fits & offered)
            if chosen.size == 0:
                continue
            a = len(actions)
            actions.append(Action(option.club, option.power, aim, total))
            for c in range(0, chosen.size, chunk_rows):
                rows = chosen[c : c + chunk_rows]
                jobs.append((rows, a, option.club, option.inputs, points[rows], option.rough))
    return actions, jobs


def fly(scenario, lat, n, player, putting=None, baseline=None, chunk_rows=256, progress=None,
        client=None, planned=None, executor=None):  # fmt: skip
    """The Transitions of the player's ``scenario`` on its hole over the states of ``lat``,
    the options of ``player`` (``options_of``).
    The jobs (``plan_actions``) are the tasks of ``executor`` (a ``mcrun.executor.Executor``;
    default one on this process's threads, or on the workers of ``client``, a
    ``dask.distributed.Client``): each job's shots go to their rows' places as it finishes,
    so that the transitions are the same, bit for bit, whatever ran them. ``planned``: the
    (actions, jobs) of ``plan_actions`` (of ``options_of(scenario, n, player)``), when
    the caller has them. ``progress(k)``: called with the actions flown so far (the share of
    the jobs done), of ``len(actions)``."""
    if planned is None:
        options = options_of(scenario, n, player)
        planned = plan_actions(scenario.hole, lat, options, chunk_rows)
    actions, jobs = planned
    executor = executor or Executor(client=client)
    if executor.on_dask:
        from mcrun.run.distributed import warm_workers
        from mcrun.run.plan import kernels_of

        warm_workers(executor.client, *kernels_of(scenario))
    # The rows in their order (by state, then action), and where each job's rows go in it.
    sizes = [len(job[0]) for job in jobs]
    rows_state = np.concatenate([job[0] for job in jobs]).astype(np.int64)
    rows_action = np.repeat(np.array([job[1] for job in jobs], dtype=np.int64), sizes)
    order = np.lexsort((rows_action, rows_state))
    place = np.empty_like(order)
    place[order] = np.arange(len(order))
    offsets = np.r_[0, np.cumsum(sizes)].astype(np.int64)
    # (kind, lie, x, y, const) of every row's n shots
    shots = (np.empty((len(order), n), dtype=np.int8), np.empty((len(order), n), dtype=np.int8),
             *(np.empty((len(order), n)) for _ in range(3)))  # fmt: skip

    def done(k, part):
        where = place[offsets[k] : offsets[k + 1]]
        for column, values in zip(shots, part, strict=True):
            _put_rows(column, where, values)

    def said(finished):
        progress(len(actions) * finished // len(jobs))

    items = [(club, inputs, lat.xy[rows], points, lat.lie[rows], rough)
             for rows, _, club, inputs, points, rough in jobs]  # fmt: skip
    executor.map(_batch, items, shared=(scenario, putting, baseline, n), done=done,
                 progress=None if progress is None else said, name="job")  # fmt: skip
    return Transitions(
        actions=actions,
        row_state=rows_state[order],
        row_action=rows_action[order],
        row_start=np.arange(len(order) + 1, dtype=np.int64) * n,
        kind=shots[0].reshape(-1),
        lie=shots[1].reshape(-1),
        x=shots[2].reshape(-1),
        y=shots[3].reshape(-1),
        const=shots[4].reshape(-1),
        n=int(n),
        shots_flown=int(sum(sizes)) * n,
    )
