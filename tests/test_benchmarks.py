"""The benchmark suite (``benchmarks/``), its quick pieces at tiny N.

What is checked is what the suite's numbers rest on, not its timings (no test asserts a time):
the results have the keys docs/performance.md's tables are made from, the reference integration
(DOP853, rtol 1e-12, ``benchmarks/reference.py``) and mcrun's kernel give the same carry and
total within 1 cm (the issue's accuracy target), and the baselines (``benchmarks/baselines.py``)
fly the same equations: the same shot carries as far as with mcrun, within 1 cm.
"""

import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # benchmarks/ is beside the package, not installed with it
    sys.path.insert(0, str(ROOT))

from benchmarks import baselines, suite  # noqa: E402
from benchmarks.common import QUICK, Inputs  # noqa: E402
from mcrun.engine.backend import simulate_batch  # noqa: E402
from mcrun.engine.schema import CARRY  # noqa: E402

TINY = replace(
    QUICK,
    mode="tiny",
    kernel_n=2000,
    accuracy_shots=3,
    solve_ivp_n=3,
    numpy_n=200,
    numba_n=2000,
    mcrun_n=2000,
    step_dts=(0.01, 0.2),
    step_rate_n=1000,
    e2e_sizes=(),
    repeats=1,
    budget_s=1.0,
)
FIGURES = ("kernel", "baselines", "steps")


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    measured = suite.run_suite(TINY, figures=FIGURES, log=lambda line: None)
    json_path, md_path = suite.write(measured, tmp_path_factory.mktemp("bench"), "tiny")
    return json.loads(json_path.read_text()), md_path.read_text()


def test_results_have_the_keys_of_the_tables(results):
    data, text = results
    assert {"suite", "machine", "targets", *FIGURES} <= data.keys()
    for name in FIGURES:
        assert "error" not in data[name], data[name].get("error")
    assert {"cpu", "logical_cores", "numba", "numpy", "python"} <= data["machine"].keys()
    kernel = data["kernel"]
    assert [r["threads"] for r in kernel["rows"]] == [1, 2]
    assert kernel["status_counts"] == {"ok": TINY.kernel_n}
    keys = [r["key"] for r in data["baselines"]["rows"]]
    assert keys == ["solve_ivp", "numpy", "numba", "mcrun", "mcrun_10ms"]
    assert [r["dt_s"] for r in data["steps"]["rows"]] == list(TINY.step_dts)
    # The Markdown carries every table.
    for heading in ("Kernel throughput", "The flight alone", "Accuracy vs step"):
        assert heading in text


def test_rates_and_scaling_are_what_the_times_give(results):
    """Each rate is the shots over the best of the rounds timed (one round per variant here),
    and the scaling is the 2-thread rate over the 1-thread rate, the very numbers the tables
    and the targets row show. (No bound on the times: this machine's load moves them.)"""
    data, text = results
    kernel = data["kernel"]
    for row in kernel["rows"]:
        assert row["n"] == TINY.kernel_n
        assert len(row["times_s"]) == TINY.repeats
        assert row["best_s"] == min(row["times_s"]) > 0.0
        assert row["shots_per_s"] == pytest.approx(row["n"] / row["best_s"], rel=1e-12)
    one, two = kernel["rows"]
    assert kernel["scaling"] == pytest.approx(two["shots_per_s"] / one["shots_per_s"], rel=1e-12)
    assert f"Scaling from 1 to 2 threads: {kernel['scaling']:.2f}x." in text
    scaling = [t for t in data["targets"] if t["target"].startswith("scaling")]
    assert len(scaling) == 1
    assert scaling[0]["measured"] == kernel["scaling"]
    assert scaling[0]["met"] == (kernel["scaling"] >= 1.8)
    for row in kernel["terrain"]["rows"]:
        assert row["shots_per_s"] == pytest.approx(row["n"] / row["best_s"], rel=1e-12)
    for row in data["baselines"]["rows"]:
        assert row["shots_per_s"] == pytest.approx(row["n"] / row["best_s"], rel=1e-12)


def test_kernel_within_1cm_of_the_dop853_reference(results):
    """The issue's target: carry and total within 1 cm of DOP853 at rtol 1e-12."""
    accuracy = results[0]["kernel"]["accuracy"]
    assert accuracy["shots"] == TINY.accuracy_shots
    assert accuracy["max_carry_error_cm"] < 1.0
    assert accuracy["max_total_error_cm"] < 1.0
    assert accuracy["within_1cm"]


def test_rk4_baselines_carry_as_mcrun_within_1cm(results):
    """Same equations, same step: the NumPy and Numba flights land where mcrun's does."""
    rows = {r["key"]: r for r in results[0]["baselines"]["rows"]}
    assert rows["numpy"]["max_carry_difference_cm"] < 1.0
    assert rows["numba"]["max_carry_difference_cm"] < 1.0


def test_solve_ivp_baseline_carries_as_mcrun_within_1cm():
    """At a tolerance that resolves a cm, the solve_ivp flight lands where mcrun's does (at
    scipy's default rtol 1e-3, the table reports its difference: about a cm)."""
    inputs = Inputs(TINY.seed).first(3)
    mcrun_carry = simulate_batch(inputs)[:, CARRY]
    shots = baselines.FlightSet.from_inputs(inputs)
    carry = baselines.solve_ivp_carry(shots, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(carry, mcrun_carry, rtol=0.0, atol=0.01)


def test_step_study_error_grows_with_the_step(results):
    """RK4's error grows with the step (200 ms errs more than 10 ms by far), and 200 ms, the
    default in uniform wind, still puts carry and total within 1 cm for every club."""
    steps = results[0]["steps"]
    fine, coarse = steps["rows"]
    for label in fine["carry_error_cm"]:
        for row in (fine, coarse):
            assert row["carry_error_cm"][label] < 1.0
            assert row["total_error_cm"][label] < 1.0
        assert coarse["carry_error_cm"][label] > 10.0 * fine["carry_error_cm"][label]


def test_profile_names_numba_functions_and_maps_their_code(tmp_path):
    """``benchmarks.profile``: a Numba symbol read as its Python name, perf's map of a compiled
    function covering the address it starts at, and the kernel's shares renormalised over its
    own functions (the rest of a perf report left out)."""
    from numba import njit

    from benchmarks import profile

    assert (
        profile.readable("_ZN5mcrun6engine7rolling4rollB4v442B54c8tJTIeFIjxE")
        == "mcrun.engine.rolling.roll"
    )
    assert profile.readable("_ZN5mcrun2fl12_make_flight12_3clocals_3e3flyB2v1E") == (
        "mcrun.fl._make_flight.<locals>.fly"
    )
    assert profile.readable("NRT_incref") == "NRT_incref"

    @njit
    def twice(x):
        return 2.0 * x

    twice(1.0)
    library = twice.overloads[twice.signatures[0]].library
    path = tmp_path / "perf.map"
    mapped = profile.write_perf_map([library], path)
    assert len(mapped) >= 1
    rows = [line.split(" ", 2) for line in path.read_text().splitlines()]
    assert [r[2] for r in rows] == mapped
    name = "test_benchmarks.test_profile_names_numba_functions_and_maps_their_code.<locals>.twice"
    named = [r for r in rows if r[2] == name]  # (and its Python wrapper: cpython.test_...)
    assert len(named) == 1
    start = int(named[0][0], 16)
    entry = next(
        f.name for f in library._final_module.functions if profile.readable(f.name) == name
    )
    assert start == library.get_pointer_to_function(entry)
    assert int(named[0][1], 16) > 0

    report = (
        "    40.00%  [.] _PyEval_EvalFrameDefault\n"
        "    30.00%  [.] mcrun.engine.rolling.roll\n"
        "    20.00%  [.] NRT_decref\n"
        "    10.00%  [.] mcrun.ground.questions.surface\n"
    )
    shares = profile.shares(report, {"mcrun.engine.rolling.roll", "mcrun.ground.questions.surface"})
    assert list(shares) == [
        "mcrun.engine.rolling.roll",
        "NRT_decref",
        "mcrun.ground.questions.surface",
    ]
    assert shares["mcrun.engine.rolling.roll"] == pytest.approx(0.5, abs=1e-12)
    assert sum(shares.values()) == pytest.approx(1.0, abs=1e-12)


def test_ground_parts_times_each_part_where_drives_roll_out():
    """``benchmarks.ground_parts`` (a few hundred calls a part): a row for every part and way of
    running it, each a time; its roll steps all on the grid, in play (balls that left it would
    time the edge's cells); the hops' tracks longer with their speed, and their line the least
    squares through their rows."""
    from benchmarks import ground_parts

    rows, fixed, per_cell, in_play = ground_parts.measure(calls=512)
    runs = 1 + len(ground_parts.LANE_COUNTS)
    assert [part for part, *_ in rows] == (
        ["roll step on a curved cell"] * runs
        + ["its Runge-Kutta step"] * runs
        + ["the roll's look-up (ground.surface)"] * 2
        + ["a hop's search"] * len(ground_parts.HOP_TRACK_SCALES)
    )
    assert all(np.isfinite(ns) and ns > 0.0 for *_, ns in rows)
    assert in_play == 1.0
    hops = rows[-len(ground_parts.HOP_TRACK_SCALES) :]
    cells = [float(how.split()[2]) for _, how, _ in hops]
    assert cells == sorted(cells) and cells[0] < 0.1 < 1.0 < cells[-1]
    want = np.polyfit(cells, [ns for *_, ns in hops], 1)
    assert per_cell == pytest.approx(want[0], rel=1e-2, abs=0.05)
    assert fixed == pytest.approx(want[1], rel=1e-2, abs=0.05)
