"""The shot loop: every shot, from launch to rest, in lockstep lanes.

``simulate_batch`` simulates the rows of ``inputs``, an (n, N_INPUT) float64 array in Fortran
order (each column contiguous, named by ``schema.INPUT_FIELDS``, SI, user frame), in tasks of
TASK_SHOTS shots on a pool of threads, and writes ``out``, an (n, N_OUTCOME) float64 array in
Fortran order whose columns are ``schema.OUTCOME_FIELDS``. A single shot, with its trajectory
or without, is the same loop on one row (``simulate_traced``): there is no other. The batch
kernels pass no path buffer and no tracer (None), so that every branch that records a path is
pruned from them as they compile (``tracer is not None``); ``simulate_traced`` compiles the same
loop with them. Each kernel comes in two kinds, compiled apart on first use: for shots of the
quadratic flight kind (the usual models in uniform wind) and for batches that also hold shots
of the general kind (``needs_general``).

A task's shots go through the phases of a shot in lanes, LANES shots at a time, each phase
written once: they fly (RK4 steps, ``physics.flight``) and land (the root inside the last step,
``engine.shot``) in the flight lanes (``engine.flight_lanes``), then bounce
(``physics.bounce.impact`` and ``hop``, until its rule ends the bouncing) and roll out
(``physics.roll``) in the bounce lanes (``engine.bounce_lanes``), asking the ground
(``mcrun.ground``) for its normal and turf. The lanes' tables are declared, row by row, in
``engine.tables``. Every shot is independent of the others, of its lane and of the thread that
runs it, so the results are the same bit for bit whatever the thread count or the order of the
rows.

Frames as in ``engine.shot``: user frame in and out, the core's (y to the LEFT) inside.
"""

import numpy as np
from numba import njit

from mcrun import ground
from mcrun.engine.bounce_lanes import bounce_all
from mcrun.engine.flight_lanes import GENERAL, QUADRATIC, flight_kind, fly_general, fly_quadratic
from mcrun.engine.schema import N_INPUT, N_OUTCOME
from mcrun.engine.shot import TRAJECTORY_DT_S, from_start
from mcrun.engine.tables import IN, LANDING, LANES, N_LANDING, NO_SHOTS, TRACER
from mcrun.executor import on_threads
from mcrun.physics import aero
from mcrun.physics.aero import LANE_MODELS, QUADRATIC_COEFFICIENTS
from mcrun.physics.flight import WIND_UNIFORM

__all__ = [
    "LANES",
    "N_LANDING",
    "TASK_SHOTS",
    "TRAJECTORY_DT_S",
    "simulate_batch",
    "simulate_landed",
    "simulate_traced",
]


@njit(cache=True, error_model="numpy")
def _kinds(inputs, start, stop, out):
    """Check shots start..stop-1 and write their launch fields: their flight kinds."""
    kinds = np.empty(stop - start, dtype=np.int8)
    for i in range(start, stop):
        kinds[i - start] = flight_kind(inputs, i, out)
    return kinds


@njit(cache=True, error_model="numpy")
def _run_out(inputs, start, stop, landings, pending, out, traj, tracer, terrain):
    """Bounce and roll out the landed shots ``pending`` LANES at a time, then measure the
    distances of shots start..stop-1 from where each was struck."""
    bounce_all(inputs, start, landings, pending, out, traj, tracer, terrain)
    for i in range(start, stop):
        x0 = inputs[i, IN.start_x_m]
        y0 = inputs[i, IN.start_y_m]
        from_start(out, i, x0, y0, ground.height_at(terrain, x0, -y0))


@njit(cache=True, error_model="numpy")
def _lockstep(inputs, start, stop, table, out, traj, tracer, terrain):
    """Simulate shots start..stop-1 of ``inputs`` into ``out``, every one of the quadratic
    flight kind (or invalid): check them, fly them LANES at a time and land them LANES at a
    time, then bounce and roll them out LANES at a time (``_run_out``)."""
    kinds = _kinds(inputs, start, stop, out)
    landings = np.empty((stop - start, N_LANDING))
    pending = np.empty(stop - start, dtype=np.int64)
    n_landed = fly_quadratic(
        inputs, kinds, QUADRATIC, start, stop, table, out, landings, pending, NO_SHOTS, traj,
        tracer, terrain,
    )  # fmt: skip
    _run_out(inputs, start, stop, landings, pending[:n_landed], out, traj, tracer, terrain)


@njit(cache=True, error_model="numpy")
def _lockstep_general(inputs, start, stop, table, out, traj, tracer, terrain):
    """``_lockstep`` for shots of both flight kinds: the quadratic ones, then the others."""
    kinds = _kinds(inputs, start, stop, out)
    landings = np.empty((stop - start, N_LANDING))
    pending = np.empty(stop - start, dtype=np.int64)
    n_landed = fly_quadratic(
        inputs, kinds, QUADRATIC, start, stop, table, out, landings, pending, NO_SHOTS, traj,
        tracer, terrain,
    )  # fmt: skip
    n_landed = fly_general(
        inputs, kinds, GENERAL, start, stop, table, out, landings, pending, n_landed, traj,
        tracer, terrain,
    )  # fmt: skip
    _run_out(inputs, start, stop, landings, pending[:n_landed], out, traj, tracer, terrain)


def needs_general(inputs):
    """Whether a shot of ``inputs`` may fly in the general lanes (``flight_lanes.flight_kind``:
    an aerodynamic model not of ``aero.LANE_MODELS``, or a wind profile), so that the batch
    needs the kernels that fly them. Each kind of kernel is compiled on its first use: a run
    of the usual models in uniform wind never compiles the general lanes."""
    lanes = np.isin(inputs[:, IN.aero_model], LANE_MODELS) & (
        inputs[:, IN.wind_profile] == WIND_UNIFORM
    )
    return not lanes.all()


def general_flight(aero_model, wind_profile):
    """``needs_general`` of shots of the aerodynamic model and the wind profile given by name
    (what a command or a scenario names, before any shot is drawn)."""
    return aero.model_id(aero_model) not in LANE_MODELS or wind_profile != "uniform"


# Shots per task: enough to keep the lanes full, few enough to balance two threads.
TASK_SHOTS = 2048


@njit(cache=True, error_model="numpy", nogil=True)
def _batch_task(inputs, task, table, out, terrain):
    """Task ``task`` of a batch: its TASK_SHOTS shots, of the quadratic flight kind. No path
    is recorded (traj and tracer None): the recording's branches are pruned from this kernel
    as it compiles, and it carries none of their code (``simulate_traced`` has its own)."""
    n = inputs.shape[0]
    start = task * TASK_SHOTS
    stop = min(n, start + TASK_SHOTS)
    _lockstep(inputs, start, stop, table, out, None, None, ground.borrowed(terrain))


@njit(cache=True, error_model="numpy", nogil=True)
def _batch_task_general(inputs, task, table, out, terrain):
    """``_batch_task`` for shots of both flight kinds."""
    n = inputs.shape[0]
    start = task * TASK_SHOTS
    stop = min(n, start + TASK_SHOTS)
    _lockstep_general(inputs, start, stop, table, out, None, None, ground.borrowed(terrain))


def _as_kernel_layout(inputs):
    """``inputs`` as the one layout the kernel is compiled for: float64, Fortran order, at
    least two rows. Numba types an array of fewer than two rows as C-contiguous (it is both),
    which would compile the kernel again for that layout: such a batch runs as two rows,
    padded with zeros (a shot of speed 0, answered with invalid_input at once)."""
    if inputs.ndim != 2 or inputs.shape[1] != N_INPUT:
        raise ValueError(f"inputs must have shape (n, {N_INPUT}), got {inputs.shape}")
    if inputs.shape[0] < 2:
        padded = np.zeros((2, N_INPUT), order="F")
        padded[: inputs.shape[0]] = inputs
        return padded
    # A slice of the rows (not contiguous) is copied, not compiled again.
    return np.asfortranarray(inputs, dtype=np.float64)


def simulate_batch(inputs, out=None, table=QUADRATIC_COEFFICIENTS, terrain=None):
    """Simulate every row of ``inputs`` (n, N_INPUT) on ``terrain`` (a ``ground.Terrain``; None:
    each shot's own Plane); return ``out`` (n, N_OUTCOME), F-order."""
    rows = _as_kernel_layout(inputs)
    n = inputs.shape[0]
    if out is None:
        out = np.empty((n, N_OUTCOME), order="F")
    result = out if rows.shape[0] == n else np.empty((rows.shape[0], N_OUTCOME), order="F")
    _run(rows, table, result, terrain)
    if result is not out:
        out[:] = result[:n]
    return out


def _run(inputs, table, out, terrain):
    """The batch's tasks on ``numba.get_num_threads()`` threads (``executor.on_threads``),
    each thread taking the next task until none is left; on this thread alone when the batch
    is one task or is itself a task of a batch of tasks (a job of a solve, an aim). The kernel
    releases the GIL, so the threads run at once; each task's shots are its own, so neither
    the thread count nor the order of the tasks changes a bit. (A ``prange`` loop would do the
    same, at the price of Numba's parallel pipeline at every compile: 8 s of the plane's cold
    start.)"""
    task = _batch_task_general if needs_general(inputs) else _batch_task
    tasks = (inputs.shape[0] + TASK_SHOTS - 1) // TASK_SHOTS
    on_threads(lambda k: task(inputs, k, table, out, terrain), tasks)


@njit(cache=True, error_model="numpy")
def _simulate_traced(inputs, shot, table, out, traj, terrain):
    tracer = np.array([float(shot), 0.0, 0.0, TRAJECTORY_DT_S])
    _lockstep(inputs, 0, inputs.shape[0], table, out, traj, tracer, ground.borrowed(terrain))
    return int(tracer[TRACER.ROW])


@njit(cache=True, error_model="numpy")
def _simulate_traced_general(inputs, shot, table, out, traj, terrain):
    tracer = np.array([float(shot), 0.0, 0.0, TRAJECTORY_DT_S])
    _lockstep_general(
        inputs, 0, inputs.shape[0], table, out, traj, tracer, ground.borrowed(terrain)
    )
    return int(tracer[TRACER.ROW])


def simulate_traced(inputs, shot, table=QUADRATIC_COEFFICIENTS, trajectory_rows=4096,
                    terrain=None):  # fmt: skip
    """Simulate the rows of ``inputs`` on this thread, recording the path of row ``shot``:
    returns (outcomes (n, N_OUTCOME), trajectory (m, 5): t, x, y, z, phase, user frame). The
    buffer grows until the whole path fits."""
    n = inputs.shape[0]
    rows = _as_kernel_layout(inputs)
    out = np.empty((rows.shape[0], N_OUTCOME), order="F")
    kernel = _simulate_traced_general if needs_general(rows) else _simulate_traced
    path = _recorded(lambda traj: kernel(rows, shot, table, out, traj, terrain), trajectory_rows)
    return out[:n], path


def _recorded(simulate, rows):
    """The path ``simulate(traj)`` records (it returns how many rows the path has), in a buffer
    of ``rows`` rows grown until the whole path fits."""
    while True:
        traj = np.empty((rows, 5))
        m = simulate(traj)
        if m <= rows:
            return traj[:m]
        rows = m


@njit(cache=True, error_model="numpy")
def _simulate_landed(inputs, landings, out, traj, tracer, terrain):
    bounce_all(
        inputs, 0, landings, np.arange(landings.shape[0]), out, traj, tracer,
        ground.borrowed(terrain),
    )  # fmt: skip
    return int(tracer[TRACER.ROW])


def simulate_landed(inputs, landings, traced=-1, dt_record_s=TRAJECTORY_DT_S, trajectory_rows=4096,
                    terrain=None):  # fmt: skip
    """The run alone (bounces, slide and roll) of balls that have landed: the loop from its
    landing on, for studies of the bounce (Penner's figures start from a landing).

    ``landings`` (n, N_LANDING): x, y, vx, vy, vz, wx, wy, wz, t, nx, ny, nz of each ball as it
    touches the ground, in the core's frame (y to the LEFT), with the ground's normal;
    ``inputs`` (n, N_INPUT) gives each its turf (on a ``terrain``, its zones do, and the
    ball starts on its surface). Returns (outcomes, trajectory): the run's
    fields of ``schema.OUTCOME_FIELDS`` (from ``bounces`` on; total_m and final_x_m are the x
    where the ball rests, run_m its distance from the landing), and the path of row
    ``traced`` (rows t, x, y, z, phase every ``dt_record_s``, user frame; empty if none).
    """
    n = landings.shape[0]
    rows = _as_kernel_layout(inputs)
    landings = np.ascontiguousarray(landings, dtype=np.float64)
    out = np.full((rows.shape[0], N_OUTCOME), np.nan, order="F")
    t_next = landings[traced, LANDING.T] + dt_record_s if traced >= 0 else 0.0

    def simulate(traj):
        tracer = np.array([float(traced), 0.0, t_next, dt_record_s])
        return _simulate_landed(rows, landings, out, traj, tracer, terrain)

    return out[:n], _recorded(simulate, trajectory_rows if traced >= 0 else 0)
