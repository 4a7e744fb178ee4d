"""The flight alone as others write it (``benchmarks/baselines.py``: ``solve_ivp`` per shot,
NumPy vectorised RK4, Numba one shot per ``prange`` iteration) beside mcrun's kernel (complete
shots, at its default step and at the baselines' 10 ms), on the same pga-driver shots, with
each baseline's carry against mcrun's."""

import numba
import numpy as np

from benchmarks import baselines
from benchmarks.common import best_of, count, outputs, rate, threads_available, timing
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import CARRY, COLUMN
from mcrun.physics import aero


def measure(config, inputs):
    """The flight alone by solve_ivp, NumPy and Numba, beside mcrun's complete shots (at its
    default step, and at the baselines' 10 ms)."""
    n_max = max(config.solve_ivp_n, config.numpy_n, config.numba_n, config.mcrun_n)
    rows = inputs.first(n_max)
    if np.any(rows[:, COLUMN["aero_model"]] != aero.MODELS["trackman2019"]):
        raise ValueError("the baselines fly trackman2019; the scenario must too")
    shots = baselines.FlightSet.from_inputs(rows, model="trackman2019")
    threads = threads_available()
    default_dt = float(rows[0, COLUMN["dt_s"]])
    mcrun_rows = {"mcrun": inputs.first(config.mcrun_n)}
    mcrun_rows["mcrun_10ms"] = mcrun_rows["mcrun"].copy(order="F")
    mcrun_rows["mcrun_10ms"][:, COLUMN["dt_s"]] = baselines.DT_S
    mcrun_out = outputs(config.mcrun_n)

    subsets = {
        "solve_ivp": shots.take(slice(0, config.solve_ivp_n)),
        "numpy": shots.take(slice(0, config.numpy_n)),
        "numba": shots.take(slice(0, config.numba_n)),
    }
    carry = {}

    def flight(name, fn):
        def run():
            carry[name] = fn(subsets[name])

        return run

    def kernel(name):
        return lambda: simulate_batch(mcrun_rows[name], mcrun_out)

    variants = {
        "solve_ivp": flight("solve_ivp", baselines.solve_ivp_carry),
        "numpy": flight("numpy", baselines.numpy_carry),
        "numba": flight("numba", baselines.numba_carry),
        "mcrun": kernel("mcrun"),
        "mcrun_10ms": kernel("mcrun_10ms"),
    }
    # Warm-up: compile (or load) the Numba baselines and the kernel.
    baselines.numba_carry(shots.take(slice(0, 10)))
    simulate_batch(inputs.first(1000), outputs(1000))
    numba.set_num_threads(threads)
    times = best_of(variants, config.repeats, config.budget_s)
    out = simulate_batch(rows)  # mcrun's carry (default step) for every shot a baseline flew

    described = {
        "solve_ivp": ("scipy `solve_ivp` per shot, RK45, default tolerances", 1, "flight"),
        "numpy": ("NumPy, all shots vectorised, RK4 dt = 10 ms", 1, "flight"),
        "numba": ("Numba, one shot per `prange` iteration, RK4 dt = 10 ms", threads, "flight"),
        "mcrun": (
            f"mcrun kernel (`simulate_batch`), its default dt = {default_dt * 1000:g} ms",
            threads,
            "complete shot",
        ),
        "mcrun_10ms": ("mcrun kernel (`simulate_batch`), dt = 10 ms", threads, "complete shot"),
    }
    table = []
    for name, (label, n_threads, work) in described.items():
        n = len(subsets[name]) if name in subsets else config.mcrun_n
        row = {"key": name, "implementation": label, "threads": n_threads, "work": work}
        row.update(timing(n, times[name]))
        if name in carry:
            error = np.abs(carry[name] - out[:n, CARRY])
            row["max_carry_difference_cm"] = float(100.0 * error.max())
        table.append(row)
    by_key = {row["key"]: row["shots_per_s"] for row in table}
    for row in table:
        row["vs_solve_ivp"] = row["shots_per_s"] / by_key["solve_ivp"]
    best = max(by_key[k] for k in subsets)
    return {
        "model": "trackman2019",
        "dt_s": baselines.DT_S,
        "mcrun_default_dt_s": default_dt,
        "rows": table,
        "mcrun_vs_best_baseline": by_key["mcrun"] / best,
        "mcrun_10ms_vs_best_baseline": by_key["mcrun_10ms"] / best,
        "carry_difference_against": "mcrun's kernel at its default step, on the same shots",
    }


def targets(r):
    return []


def markdown(r):
    lines = [
        "### The flight alone, as it is usually written, beside mcrun's complete shots",
        "",
        f"pga-driver shots, {r['model']}; the baselines are in `benchmarks/baselines.py`. "
        f"Carry difference: against {r['carry_difference_against']}.",
        "",
        "| implementation | work | threads | shots timed | shots/s | x solve_ivp "
        "| max carry difference (cm) |",
        "|---|---|---|---|---|---|---|",
    ]
    for row in r["rows"]:
        diff = row.get("max_carry_difference_cm")
        lines.append(
            f"| {row['implementation']} | {row['work']} | {row['threads']} | {count(row['n'])} | "
            f"{rate(row['shots_per_s'])} | {row['vs_solve_ivp']:,.0f} | "
            + ("-" if diff is None else f"{diff:.2g}")
            + " |"
        )
    lines += [
        "",
        "mcrun's complete shots vs the fastest baseline's flight alone: "
        f"{r['mcrun_vs_best_baseline']:.1f}x at mcrun's default step, "
        f"{r['mcrun_10ms_vs_best_baseline']:.1f}x at the same 10 ms step.",
    ]
    return lines
