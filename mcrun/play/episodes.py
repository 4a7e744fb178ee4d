"""The score distribution of a solved hole: the policy played N times from the tee, each shot
one of the n flown for its state and action, drawn at random (seeded).

A ball at rest off the green moves to the state of its lie nearest to it; on the green it takes
a number of putts drawn to match its expected putts E (1 or 2 putts where E <= 2: two with
probability E - 1; else 2 or 3, three with probability E - 2): the distribution's mean is the
map's or the table's, its spread the least any such distribution has, an approximation. A water
ball takes its penalty stroke and is dropped (or replayed, where the solution's values say so);
out of bounds, one penalty stroke and the shot again. A play stops at ``MAX_STROKES``.
"""

import numpy as np

from mcrun.play.lattice import stacked, value_at
from mcrun.play.transitions import FAILED, GREEN, PLAY, RESTART, WATER

__all__ = ["MAX_STROKES", "play_policy"]

MAX_STROKES = 15


def _nearest_states(lat, x, y, lie):
    """The state nearest (x, y) with its lie (else of any lie) among the grids' nodes around."""
    best = np.full(len(x), -1, dtype=np.int64)
    best_d = np.full(len(x), np.inf)
    for x0, y0, cell, index in lat.grids:
        ny, nx = index.shape
        fx, fy = (x - x0) / cell, (y - y0) / cell
        for dy in range(-1, 3):
            for dx in range(-1, 3):
                ix = np.floor(fx).astype(np.int64) + dx
                iy = np.floor(fy).astype(np.int64) + dy
                ok = (ix >= 0) & (iy >= 0) & (ix < nx) & (iy < ny)
                s = np.full(len(x), -1, dtype=np.int64)
                s[ok] = index[iy[ok], ix[ok]]
                d = np.hypot(ix - fx, iy - fy) * cell
                d = np.where(s >= 0, d, np.inf)
                d = np.where((s >= 0) & (lat.lie[np.maximum(s, 0)] != lie), d + 1e6, d)
                closer = d < best_d
                best, best_d = np.where(closer, s, best), np.where(closer, d, best_d)
    far = best < 0
    if far.any():
        d = np.hypot(lat.xy[None, :, 0] - x[far, None], lat.xy[None, :, 1] - y[far, None])
        best[far] = np.argmin(d, axis=1)
    return best


def play_policy(lat, tr, solution, plays, seed=0, second_rows=None):
    """The strokes (int array of ``plays``) of the solution's policy played from the tee;
    ``second_rows``: an int array of ``plays`` that receives the transition row each play's
    second stroke played (-1 where the play was over after one)."""
    rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence([seed, 25])))
    state = np.zeros(plays, dtype=np.int64)
    strokes = np.zeros(plays, dtype=np.int64)
    done = np.zeros(plays, dtype=bool)
    grids = stacked(lat)
    if second_rows is not None:
        second_rows[:] = -1
    stroke = 0
    while not done.all():
        live = np.flatnonzero(~done)
        rows = solution.best_row[state[live]]
        stroke += 1
        if second_rows is not None and stroke == 2:
            second_rows[live] = rows
        first, n = tr.row_start[rows], tr.n
        shot = first + rng.integers(0, n, len(live))
        for _ in range(8):  # a failed shot is drawn again
            failed = tr.kind[shot] == FAILED
            if not failed.any():
                break
            shot[failed] = first[failed] + rng.integers(0, n, int(failed.sum()))
        kind = tr.kind[shot]
        strokes[live] += 1
        green = kind == GREEN
        e = tr.const[shot[green]]
        u = rng.random(len(e))
        putts = np.where(e <= 0.0, 0, np.where(e <= 2.0, 1 + (u < e - 1.0), 2 + (u < e - 2.0)))
        strokes[live[green]] += putts
        done[live[green]] = True
        penalty = (kind == WATER) | (kind == RESTART)
        strokes[live[penalty]] += 1
        moves = (kind == PLAY) | (
            (kind == WATER) & _drop_better(solution, tr, state[live], shot, lat, grids)
        )
        if moves.any():
            state[live[moves]] = _nearest_states(lat, tr.x[shot[moves]], tr.y[shot[moves]],
                                                 tr.lie[shot[moves]])  # fmt: skip
        capped = strokes >= MAX_STROKES
        strokes[capped] = MAX_STROKES
        done |= capped
    return strokes


def _drop_better(solution, tr, states, shot, lat, grids):
    """Whether a water ball's drop is worth less than playing again from its state."""
    out = np.zeros(len(shot), dtype=bool)
    for k in np.flatnonzero(tr.kind[shot] == WATER):
        i = shot[k]
        drop = value_at(tr.x[i], tr.y[i], tr.lie[i], solution.values, *grids, lat.pin_xy[0],
                        lat.pin_xy[1], lat.table)  # fmt: skip
        out[k] = drop < solution.values[states[k]]
    return out
