"""The one door to the kernel: ``simulate_batch`` runs a batch of shots on a backend.

The runners (local and Dask), the replay, the Python API and the benchmarks call this and
nothing else of the engine's functions. ``backend="cpu"`` (the only one today) runs the
lockstep lanes of ``mcrun.engine.batch`` in Numba threads; the physics it calls holds nothing
CPU-specific, so that another backend (numba.cuda, say) can compile the same formulae.
"""

from mcrun.engine import batch
from mcrun.physics.aero import QUADRATIC_COEFFICIENTS

BACKENDS = ("cpu",)


def _check(backend):
    if backend not in BACKENDS:
        raise ValueError(f"unknown backend '{backend}': choose one of {', '.join(BACKENDS)}")


def simulate_batch(inputs, out=None, backend="cpu", table=QUADRATIC_COEFFICIENTS, terrain=None):
    """Simulate every row of ``inputs`` ((n, N_INPUT), columns ``schema.INPUT_FIELDS``); return
    the outcomes, (n, N_OUTCOME) in Fortran order, columns ``schema.OUTCOME_FIELDS``.
    ``table`` holds the quadratic aerodynamic models' coefficients (a calibration tries
    others)."""
    _check(backend)
    return batch.simulate_batch(inputs, out, table, terrain)


def simulate_traced(inputs, shot=0, backend="cpu", table=QUADRATIC_COEFFICIENTS, terrain=None):
    """``simulate_batch`` on this thread, with the path of row ``shot``: returns (outcomes,
    trajectory), the trajectory's rows (t_s, x_m, y_m, z_m, phase code), y to the right."""
    _check(backend)
    return batch.simulate_traced(inputs, shot, table, terrain=terrain)


def simulate_landed(
    inputs, landings, traced=-1, dt_record_s=batch.TRAJECTORY_DT_S, backend="cpu", terrain=None
):
    """The run alone of balls that have landed (``batch.simulate_landed``)."""
    _check(backend)
    return batch.simulate_landed(inputs, landings, traced, dt_record_s, terrain=terrain)
