"""The one door to the kernel: ``simulate_batch`` runs a batch of shots on a backend.

The runners (local and Dask), the replay, the Python API and the benchmarks call this and
nothing else of the engine's functions. ``backend="cpu"`` (the only one today) runs the
lockstep lanes of ``mcrun.engine.batch`` in Numba threads; the physics it calls holds nothing
CPU-specific, so that another backend (numba.cuda, say) can compile the same formulae.
"""

from mcrun.engine import batch

BACKENDS = ("cpu",)


def simulate_batch(inputs, out=None, backend="cpu"):
    """Simulate every row of ``inputs`` ((n, N_INPUT), columns ``schema.INPUT_FIELDS``); return
    the outcomes, (n, N_OUTCOME) in Fortran order, columns ``schema.OUTCOME_FIELDS``."""
    if backend not in BACKENDS:
        raise ValueError(f"unknown backend '{backend}': choose one of {', '.join(BACKENDS)}")
    return batch.simulate_batch(inputs, out)
