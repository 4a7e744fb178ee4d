"""What the figures of the suite share: the sizes of a run (``Config``), the interleaved timing,
the pga-driver inputs sampled once, and the number formats of the Markdown.

Timing: each figure runs its variants in one process, interleaved round by round (A, B, A, B,
...), so that a ratio holds on a noisy machine; a figure reports the best of its rounds, after a
warm-up call (compilation) that is not timed. A variant stops repeating once it has used its
time budget. Nothing here asserts a time: the targets are reported as met or not.
"""

import math
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numba
import numpy as np

from mcrun.engine.schema import COLUMN, OUTCOME_FIELDS, STATUS
from mcrun.run import sampling
from mcrun.run import scenario as scenario_module
from mcrun.status import NAMES as STATUS_NAMES

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "scenarios" / "pga-driver.toml"
RESULTS = ROOT / "benchmarks" / "results"
MPH = 0.44704  # m/s
RPM = 2.0 * math.pi / 60.0  # rad/s


@dataclass(frozen=True)
class Config:
    """Sizes and repetitions of one run of the suite."""

    mode: str
    kernel_n: int  # pga-driver shots timed in the kernel figure
    threads: tuple  # thread counts of the kernel figure
    accuracy_shots: int  # of those, checked against DOP853
    solve_ivp_n: int  # the baselines figure
    numpy_n: int
    numba_n: int
    mcrun_n: int
    step_dts: tuple  # the steps figure
    step_rate_n: int
    e2e_sizes: tuple  # the end-to-end figure
    e2e_repeats: int
    phases_n: int  # the run_phases figure: shots of each scenario
    cold_start: bool  # the start-up figure
    warm_repeats: int
    repeats: int  # rounds of each timed variant (best of)
    budget_s: float  # a variant stops repeating after this much time
    seed: int = 2019


FULL = Config(
    mode="full",
    kernel_n=1_000_000,
    threads=(1, 2),
    accuracy_shots=20,
    solve_ivp_n=200,
    numpy_n=50_000,
    numba_n=100_000,
    mcrun_n=100_000,
    step_dts=(0.005, 0.01, 0.02, 0.05, 0.1, 0.2),
    step_rate_n=100_000,
    e2e_sizes=(100_000, 1_000_000, 10_000_000),
    e2e_repeats=2,
    phases_n=2_000_000,
    cold_start=True,
    warm_repeats=3,
    repeats=5,
    budget_s=20.0,
)
QUICK = replace(
    FULL,
    mode="quick",
    kernel_n=100_000,
    accuracy_shots=10,
    solve_ivp_n=20,
    numpy_n=5_000,
    numba_n=20_000,
    mcrun_n=20_000,
    step_rate_n=20_000,
    e2e_sizes=(100_000,),
    e2e_repeats=1,
    phases_n=200_000,
    cold_start=False,
    repeats=2,
    budget_s=3.0,
)


# --- timing ------------------------------------------------------------------------------------


def best_of(variants, repeats, budget_s):
    """Time each callable of ``variants`` (name -> fn) in interleaved rounds.

    Returns name -> list of wall times (s). Warm up before calling this: every call is timed.
    """
    times = {name: [] for name in variants}
    for round_ in range(repeats):
        for name, fn in variants.items():
            if round_ > 0 and sum(times[name]) > budget_s:
                continue
            start = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - start)
    return times


def timing(n, times):
    """The record of ``n`` shots timed ``times`` (s): best time, every time, shots/s."""
    best = min(times)
    return {"n": n, "best_s": best, "times_s": times, "shots_per_s": n / best}


def threads_available():
    return numba.config.NUMBA_NUM_THREADS


# --- inputs ------------------------------------------------------------------------------------


class Inputs:
    """The pga-driver kernel inputs, sampled once and shared by the figures."""

    def __init__(self, seed):
        self.scenario = scenario_module.load(SCENARIO)
        self.seed = seed
        self._rows = np.empty((0, len(COLUMN)), order="F")

    def first(self, n):
        """A copy of the first ``n`` samples (n, N_INPUT), F-contiguous.

        Contiguous, as a run passes them: a row slice of an F-order array is not, and the
        kernel would compile (and run) another specialisation for it.
        """
        if n > self._rows.shape[0]:
            scenario = self.scenario
            if scenario.seed != self.seed:
                scenario = replace(scenario, seed=self.seed)
            self._rows, _ = sampling.sample(scenario, scenario.points[0], 0, n)
        return np.asfortranarray(self._rows[:n].copy())


def outputs(n):
    """An outcome array for ``n`` shots, as the kernel fills it."""
    return np.empty((n, len(OUTCOME_FIELDS)), order="F")


def status_counts(out):
    """How many shots of ``out`` ended with each status, by its name."""
    codes, counts = np.unique(out[:, STATUS], return_counts=True)
    return {
        STATUS_NAMES.get(int(c), str(int(c))): int(k) for c, k in zip(codes, counts, strict=True)
    }


# --- the report --------------------------------------------------------------------------------


def publish(path, lines):
    """Print a script's report (its Markdown ``lines``) and write it to ``path``, making its
    folder where needed."""
    text = "\n".join(lines)
    print(text)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def target(name, measured, met, shown):
    """One row of the report's targets table: what the issue asks, the number measured, whether
    it is met, and the number as the table shows it."""
    return {"target": name, "measured": measured, "met": met, "shown": shown}


# --- number formats of the Markdown ------------------------------------------------------------


def rate(x):
    return f"{x:,.0f}"


def cm(x):
    return "n/a" if x is None else f"{x:.1e}"


def count(n):
    return f"{n:,}" if n < 1_000_000 else f"{n:.0e}".replace("e+0", "e")


def statuses(counts):
    """``status_counts`` as the tables show them: ``ok 99,990, not_stopped 10``."""
    return ", ".join(f"{k} {v:,}" for k, v in counts.items())
