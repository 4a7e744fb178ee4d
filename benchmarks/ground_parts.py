"""``python -m benchmarks.ground_parts [--calls N]``: what each part of a shot on real, curved
ground costs, timed alone: a roll step, its Runge-Kutta step, the roll's look-up of the ground,
and a hop's search, on the grid of drive-real-ground (USGS 3DEP ground, every 0.5 m cell
curved).

Each part runs ``--calls`` times in a compiled loop, one thread, best of five rounds, after a
warm-up that is not timed; the figure is nanoseconds a call. A loop that carries one ball takes
its chain of waits (each call starts from the last one's result); a loop over lanes of balls
(2, 4 or 16, each call on the next ball) lets the processor overlap the balls' calls, and the
compiler vectorise the loop where its body has no branch. Which of the two a part gains from
is what says how it could be made faster: docs/performance.md (real survey ground) reads
these numbers. Prints a Markdown table and writes
``benchmarks/results/ground-parts.md``; asserts nothing.
"""

import argparse
import time
from pathlib import Path

import numpy as np
from numba import njit

from benchmarks.common import publish
from mcrun import ground
from mcrun.ground.grid import _grid_surface
from mcrun.physics.constants import G_MPS2
from mcrun.physics.roll import (
    PATCH_DT_MAX_S,
    exit_time,
    patch_acceleration,
    patch_step,
    plane_gravity,
)
from mcrun.physics.turf import PRESETS
from mcrun.run import scenario as sc
from mcrun.status import OK

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "ground-parts.md"
SCENARIO = "drive-real-ground"
LANE_COUNTS = (2, 4, 16)
# Where the drives of the scenario roll out, in the core's frame: x (m) from the tee, y (m) to
# the left.
X_RANGE_M = (230.0, 280.0)
Y_RANGE_M = (-8.0, 8.0)
# The longest roll step the loops take (s): short, so that a ball stays on the fairway.
STEP_S = 0.02
RHO_G = PRESETS["fairway"].rho_g
# Hops: their take-off speeds scaled so that their ground tracks cross from none to a few cells.
HOP_TRACK_SCALES = (0.01, 0.1, 0.3, 1.0)


# --- the parts, as the kernel runs them ---------------------------------------------------------


@njit(cache=True, error_model="numpy", inline="always")
def _roll_step(terrain, plane, px, py, vx, vy):
    """A roll step on a curved cell as ``rolling.roll`` takes it: the ground's Surface where
    the ball is (a call), gravity along it, the time to the patch's edge and the Runge-Kutta
    step; returns the ball's new (x, y, vx, vy), put back among the drives' finishes where it
    leaves them or nearly stops, and whether the step started in play on the grid."""
    here = ground.surface(terrain, plane, px, py, 0.0)
    patch = here.patch
    _, _, _, _, g_t, _, _ = plane_gravity(here.nx, here.ny, here.nz)
    ax, ay = patch_acceleration(px, py, vx, vy, patch, RHO_G)
    h_edge = min(
        exit_time(px - patch.xc, vx, ax, patch.u_lo, patch.u_hi),
        exit_time(patch.yc - py, -vy, -ay, patch.w_lo, patch.w_hi),
    )
    # (0 g_t: gravity is computed, as the roll needs it, and not dropped by the compiler.)
    h = min(STEP_S, PATCH_DT_MAX_S, h_edge + 1e-3 + 0.0 * g_t)
    x1, y1, vx1, vy1 = patch_step(px, py, vx, vy, ax, ay, h, patch, RHO_G)
    if (x1 > X_RANGE_M[1]) | (vx1 < 0.5):
        x1, vx1 = X_RANGE_M[0], 3.0
    return x1, y1, vx1, vy1, here.state == OK


@njit(cache=True, error_model="numpy")
def _roll_steps_chain(terrain, plane, xs, ys, calls):
    terrain = ground.borrowed(terrain)
    x, y, vx, vy = xs[0], ys[0], 3.0, 0.2
    in_play = 0
    for _ in range(calls):
        x, y, vx, vy, ok = _roll_step(terrain, plane, x, y, vx, vy)
        in_play += ok
    return in_play / calls


@njit(cache=True, error_model="numpy")
def _roll_steps_lanes(terrain, plane, xs, ys, calls, lanes):
    terrain = ground.borrowed(terrain)
    x = xs[:lanes].copy()
    y = ys[:lanes].copy()
    vx = np.full(lanes, 3.0)
    vy = np.full(lanes, 0.2)
    in_play = 0
    for _ in range(calls // lanes):
        for k in range(lanes):
            x[k], y[k], vx[k], vy[k], ok = _roll_step(terrain, plane, x[k], y[k], vx[k], vy[k])
            in_play += ok
    return in_play / (calls // lanes * lanes)


@njit(cache=True, error_model="numpy", inline="always")
def _rk4(patch, px, py, vx, vy):
    """The Runge-Kutta step of a roll on a patch (``physics.roll.patch_step``) from its start's
    acceleration, the ball kept on the patch."""
    ax, ay = patch_acceleration(px, py, vx, vy, patch, RHO_G)
    x1, y1, vx1, vy1 = patch_step(px, py, vx, vy, ax, ay, 1e-3, patch, RHO_G)
    return 0.999 * x1, 0.999 * y1, vx1, vy1


@njit(cache=True, error_model="numpy")
def _rk4_chain(patch, calls):
    x, y, vx, vy = 0.1, 0.1, 2.0, 0.3
    for _ in range(calls):
        x, y, vx, vy = _rk4(patch, x, y, vx, vy)
    return x + y + vx + vy


@njit(cache=True, error_model="numpy")
def _rk4_lanes(patch, calls, lanes):
    x = np.full(lanes, 0.1)
    y = np.full(lanes, 0.1)
    vx = np.linspace(1.9, 2.1, lanes)
    vy = np.full(lanes, 0.3)
    for _ in range(calls // lanes):
        for k in range(lanes):
            x[k], y[k], vx[k], vy[k] = _rk4(patch, x[k], y[k], vx[k], vy[k])
    return x.sum()


@njit(cache=True, error_model="numpy")
def _look_ups(terrain, plane, calls, inlined):
    """The roll's look-up of the ground (``ground.surface``, a call; or inlined), each at a
    point that waits on the last one's answer, as a roll's steps do."""
    terrain = ground.borrowed(terrain)
    total = 0.0
    x = X_RANGE_M[0]
    y = 0.0
    for _ in range(calls):
        if inlined:
            here = _grid_surface(terrain, x, y)
        else:
            here = ground.surface(terrain, plane, x, y, 0.0)
        total += here.patch.bx + here.nz + here.turf.mu + here.step_m
        x += 0.01 + 1e-9 * total
        y += 0.001
        x = X_RANGE_M[0] if x > X_RANGE_M[1] else x
        y = 0.0 if y > Y_RANGE_M[1] else y
    return total


@njit(cache=True, error_model="numpy")
def _hops(terrain, x, y, z, vx, vy, vz, calls):
    """Where hops from the ground at (x, y, z) come down on the grid (``ground.hop_landing``:
    the search cell by cell), one after another."""
    terrain = ground.borrowed(terrain)
    total = 0.0
    n = x.size
    for j in range(calls):
        i = j % n
        x1, _, _, _, t = ground.hop_landing(
            terrain, x[i], y[i], z[i] + 1e-7, vx[i], vy[i], vz[i], 2.0 * vz[i] / G_MPS2
        )
        total += x1 + t
    return total


@njit(cache=True, error_model="numpy")
def _heights(terrain, x, y):
    terrain = ground.borrowed(terrain)
    out = np.empty(x.size)
    for i in range(x.size):
        out[i] = ground.height_at(terrain, x[i], y[i])
    return out


# --- the measurement ----------------------------------------------------------------------------


def nanoseconds(run, calls, rounds=5):
    """Nanoseconds a call of ``run(calls)``, its best of ``rounds`` after a warm-up, and what
    its last round returned."""
    run(max(calls // 100, 16))
    best = np.inf
    for _ in range(rounds):
        start = time.perf_counter()
        result = run(calls)
        best = min(best, time.perf_counter() - start)
    return best / calls * 1e9, result


def measure(calls, seed=1):
    """Every part's nanoseconds a call, as (part, how it is run, ns) rows; the hops' fixed
    cost and cost per cell crossed (a least-squares line through their ns against cells); and
    the least share of roll steps, of a round, that started in play on the grid (1.0: the
    balls stayed where drives finish, on curved cells)."""
    scenario = sc.load(sc.find(SCENARIO))
    terrain = scenario.hole.terrain()
    plane = ground.Plane(0.0, 0.0, 1.0, PRESETS["fairway"])
    rng = np.random.default_rng(seed)
    xs = rng.uniform(*X_RANGE_M, 4096)
    ys = rng.uniform(*Y_RANGE_M, 4096)
    rows = []
    steps_in_play = []

    def row(part, how, run):
        ns, result = nanoseconds(run, calls)
        rows.append((part, how, ns))
        return result

    step = "roll step on a curved cell"
    steps_in_play.append(
        row(step, "one ball", lambda c: _roll_steps_chain(terrain, plane, xs, ys, c))
    )
    for k in LANE_COUNTS:
        steps_in_play.append(
            row(
                step,
                f"{k} balls in lanes",
                lambda c, k=k: _roll_steps_lanes(terrain, plane, xs, ys, c, k),
            )
        )
    # A patch of the grid's own kind (bilinear, twisted), as ``ground.surface`` builds it.
    here = _grid_surface(ground.borrowed(terrain), 250.0, 0.3)
    patch = here.patch._replace(u_hi=np.inf, w_hi=np.inf)
    rk4 = "its Runge-Kutta step"
    row(rk4, "one ball", lambda c: _rk4_chain(patch, c))
    for k in LANE_COUNTS:
        row(rk4, f"{k} balls in lanes", lambda c, k=k: _rk4_lanes(patch, c, k))
    look_up = "the roll's look-up (ground.surface)"
    row(look_up, "a call (the roll's)", lambda c: _look_ups(terrain, plane, c, False))
    row(look_up, "inlined", lambda c: _look_ups(terrain, plane, c, True))
    speed = rng.uniform(2.0, 12.0, 4096)
    vz = rng.uniform(0.2, 2.5, 4096)
    vy = 0.1 * speed * rng.normal(size=4096)
    z = _heights(terrain, xs, ys)
    cells = []
    for s in HOP_TRACK_SCALES:
        vx = 0.99 * s * speed
        cells.append(float(np.mean(np.hypot(vx, s * vy) * 2.0 * vz / G_MPS2)) / terrain.cell_m)
        row("a hop's search", f"tracks of {cells[-1]:.2f} cells on average",
            lambda c, vx=vx, s=s: _hops(terrain, xs, ys, z, vx, s * vy, vz, c))  # fmt: skip
    per_cell, fixed = np.polyfit(cells, [ns for *_, ns in rows[-len(cells) :]], 1)
    return rows, fixed, per_cell, min(steps_in_play)


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m benchmarks.ground_parts", description=__doc__)
    p.add_argument("--calls", type=int, default=1_000_000, help="calls of each part per round")
    args = p.parse_args(argv)
    rows, fixed, per_cell, in_play = measure(args.calls)
    lines = [
        "## The parts of a shot on real ground",
        "",
        f"Each part alone on {SCENARIO}'s grid, one thread, {args.calls:,} calls a round, best "
        "of five rounds (`python -m benchmarks.ground_parts`):",
        "",
        "| part | run as | ns a call |",
        "|---|---|---|",
        *(f"| {part} | {how} | {ns:.1f} |" for part, how, ns in rows),
        "",
        f"A hop's search: {fixed:.1f} ns, and {per_cell:.1f} ns more for each cell its ground "
        "track crosses (a line through the rows above). The roll steps started in play on the "
        f"grid: {in_play:.1%} of them at least.",
        "",
    ]
    publish(RESULTS, lines)


if __name__ == "__main__":
    main()
