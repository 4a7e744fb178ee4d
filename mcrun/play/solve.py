"""The hole solved for a player: value iteration over the transitions, the best action from
every state, the expected score from the tee with its standard error, and the strokes each
decision saves.

V(s) = min over the actions a that fit s of Q(s, a), Q(s, a) = the mean over its shots of

- ``PLAY``: 1 + V(where it rests, its lie) (``lattice.value_at``);
- ``GREEN``: 1 + its expected putts;
- ``WATER``: 1 + 1 (the penalty) + the better of V(s) (stroke and distance) and V(the drop);
- ``RESTART``: 1 + 1 + V(s) (stroke and distance);

its ``FAILED`` shots left out. Starting from the baseline's strokes at every state, the sweeps
(every row from the last sweep's values, rows on the kernels' threads, ``executor.on_threads``:
the same values whatever their number) go on until no value moves by more than
``TOLERANCE`` (``SolveResult.sweeps``, ``change``). A standard error of Q is that of the mean
of its shots' costs at the solution (the values themselves are taken as known).
"""

import math
import time
from dataclasses import dataclass

import numba
import numpy as np
from numba import njit

from mcrun.executor import on_threads
from mcrun.play.lattice import TABLE_STEP_M, stacked, value_at
from mcrun.play.transitions import GREEN, PLAY, RESTART, WATER

__all__ = ["MAX_SWEEPS", "TOLERANCE", "SolveResult", "solve"]

TOLERANCE = 1e-6
MAX_SWEEPS = 500


@njit(cache=True, nogil=True, error_model="numpy", _nrt=False)
def _q_rows(rows, first, last, values, row_state, row_start, kind, lie, x, y, const, g_x0, g_y0,
            g_cell, g_index, g_lie, reach, px, py, table, q, q_se):  # fmt: skip
    """Q (and its standard error) of the rows ``rows[first:last]`` from ``values``.

    Compiled without Numba's reference counts (``_nrt=False``: it allocates nothing and only
    reads and writes the arrays it is given). With them, the arrays handed to the inlined
    ``value_at`` are counted in and out at every shot, in branches that Numba's pruning of the
    counts does not reach: a sweep took 1.6-2 times as long."""
    for j in range(first, last):
        r = rows[j]
        s = row_state[r]
        total, total2, count = 0.0, 0.0, 0
        for i in range(row_start[r], row_start[r + 1]):
            k = kind[i]
            if k == PLAY:
                c = 1.0 + value_at(x[i], y[i], lie[i], values, g_x0, g_y0, g_cell, g_index,
                                   g_lie, reach, px, py, table)  # fmt: skip
            elif k == GREEN:
                c = 1.0 + const[i]
            elif k == WATER:
                drop = value_at(x[i], y[i], lie[i], values, g_x0, g_y0, g_cell, g_index, g_lie,
                                reach, px, py, table)  # fmt: skip
                c = 2.0 + min(values[s], drop)
            elif k == RESTART:
                c = 2.0 + values[s]
            else:
                continue
            total += c
            total2 += c * c
            count += 1
        if count == 0:
            q[r] = np.inf
            q_se[r] = np.nan
            continue
        mean = total / count
        q[r] = mean
        var = max(total2 / count - mean * mean, 0.0) * count / max(count - 1, 1)
        q_se[r] = math.sqrt(var / count)


@njit(cache=True)
def _best(q, row_state, allowed, n_states, out_v, out_row):
    for s in range(n_states):
        out_v[s] = np.inf
        out_row[s] = -1
    for r in range(q.shape[0]):
        if not allowed[r]:
            continue
        s = row_state[r]
        if q[r] < out_v[s]:
            out_v[s] = q[r]
            out_row[s] = r


@dataclass
class SolveResult:
    """The solution: per state its value and best row; per row Q and its standard error."""

    values: np.ndarray
    best_row: np.ndarray
    q: np.ndarray
    q_se: np.ndarray
    sweeps: int
    change: float
    seconds: float


def solve(lat, tr, allowed=None, start_values=None, threads=None):
    """Value iteration of the transitions ``tr`` over the lattice ``lat``; ``allowed``: a mask
    of the rows a policy may choose (default all: the best policy). The sweeps compute the Q of
    those rows alone; the others' Q, for the result, once at the end from the values the last
    sweep read (as a sweep of every row would have)."""
    started = time.perf_counter()
    threads = numba.get_num_threads() if threads is None else int(threads)
    n_states = lat.size
    allowed = np.ones(len(tr.row_state), dtype=np.bool_) if allowed is None else allowed
    if start_values is None:
        d = np.hypot(lat.xy[:, 0] - lat.pin_xy[0], lat.xy[:, 1] - lat.pin_xy[1])
        column = np.minimum((d / TABLE_STEP_M).astype(int), lat.table.shape[1] - 1)
        values = lat.table[lat.lie, column].copy()
    else:
        values = start_values.copy()
    grids = stacked(lat)
    q = np.empty(len(tr.row_state))
    q_se = np.empty(len(tr.row_state))
    best_v = np.empty(n_states)
    best_row = np.empty(n_states, dtype=np.int64)
    args = (tr.row_state, tr.row_start, tr.kind, tr.lie, tr.x, tr.y, tr.const, *grids,
            lat.pin_xy[0], lat.pin_xy[1], lat.table)  # fmt: skip

    def rows_q(rows, v):
        """Q of ``rows`` from the values ``v``, in slices on the threads."""
        bounds = np.linspace(0, len(rows), min(threads * 8, max(len(rows), 1)) + 1)
        bounds = bounds.astype(np.int64)
        on_threads(lambda k: _q_rows(rows, bounds[k], bounds[k + 1], v, *args, q, q_se),
                   len(bounds) - 1, threads)  # fmt: skip

    # The sweeps ask the rows the policy may choose; the others' Q, once, from the values the
    # last sweep read.
    chosen = np.flatnonzero(allowed)
    sweeps, change = 0, math.inf
    while sweeps < MAX_SWEEPS:
        rows_q(chosen, values)
        _best(q, tr.row_state, allowed, n_states, best_v, best_row)
        # A state no allowed row fits keeps its value (the tee's lattice always has one).
        new = np.where(best_row >= 0, best_v, values)
        change = float(np.max(np.abs(new - values)))
        read, values = values, new
        sweeps += 1
        if change <= TOLERANCE:
            break
    if len(chosen) < len(q):
        rows_q(np.flatnonzero(~allowed), read)
    return SolveResult(values, best_row.copy(), q, q_se, sweeps, change,
                       time.perf_counter() - started)  # fmt: skip
