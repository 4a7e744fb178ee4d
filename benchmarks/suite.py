"""The benchmark suite's driver: runs the figures (``benchmarks/figures/``, one module each,
its measurement beside its Markdown), then writes every number as JSON and the tables as
Markdown, with the machine they were measured on and the issues' targets at the top.

``python -m benchmarks [--quick] [--huge] [--out DIR] [--only FIGURES]``.
"""

import argparse
import json
import math
import os
import sys
import time
from dataclasses import asdict
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from benchmarks.common import FULL, QUICK, RESULTS, Inputs
from benchmarks.figures import FIGURES as FIGURE_MODULES
from benchmarks.figures import end_to_end
from benchmarks.machine import machine_info

FIGURES = tuple(FIGURE_MODULES)
HUGE_N = end_to_end.HUGE_N


def run_suite(config, figures=FIGURES, huge=False, log=print):
    """Run ``figures`` with ``config``; return the results dict (what latest.json holds)."""
    started = datetime.now(UTC)
    inputs = Inputs(config.seed)
    results = {"suite": {"mode": config.mode, "config": asdict(config), "huge": huge}}
    # Other work on the machine shows here: a load near the core count halves a 2-thread rate.
    results["suite"]["load_average_at_start"] = os.getloadavg()
    for name in figures:
        log(f"benchmarks: {name} ...")
        start = time.perf_counter()
        try:
            if name == "end_to_end":
                results[name] = end_to_end.measure(config, inputs, huge=huge)
            else:
                results[name] = FIGURE_MODULES[name].measure(config, inputs)
        except Exception as err:  # report and go on: one broken figure must not hide the rest
            results[name] = {"error": f"{type(err).__name__}: {err}"}
        results[name]["elapsed_s"] = time.perf_counter() - start
        log(f"benchmarks: {name} done in {results[name]['elapsed_s']:.1f} s")
    results["suite"]["started"] = started.isoformat(timespec="seconds")
    results["suite"]["elapsed_s"] = (datetime.now(UTC) - started).total_seconds()
    results["suite"]["load_average_at_end"] = os.getloadavg()
    results["machine"] = machine_info()
    results["targets"] = targets(results)
    return results


def targets(results):
    """The issues' targets beside what was measured, figure by figure (those not measured are
    left out)."""
    return [
        row
        for name, module in FIGURE_MODULES.items()
        if name in results
        for row in module.targets(results[name])
    ]


# --- JSON and Markdown -------------------------------------------------------------------------


def _plain(value):
    """``value`` with NumPy scalars and tuples made JSON-friendly (NaN -> None)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def markdown(results):
    """The Markdown report: the tables of docs/performance.md."""
    m = results.get("machine", {})
    suite = results["suite"]
    load = suite.get("load_average_at_start", [math.nan])[0]
    lines = [
        "## Benchmarks",
        "",
        f"Measured {suite.get('started', '?')} with `python -m benchmarks"
        + (" --quick" if suite["mode"] == "quick" else "")
        + ("" if not suite.get("huge") else " --huge")
        + f"` on {m.get('cpu', '?')} ({m.get('usable_cores', '?')} cores"
        + (", AVX-512" if m.get("avx512") else "")
        + f", {m.get('memory_gb') or 0:.0f} GB), Python {m.get('python')}, NumPy {m.get('numpy')}, "
        f"Numba {m.get('numba')} ({m.get('numba_threading_layer')} threading layer), "
        f"commit {m.get('git_commit')}{' (with local changes)' if m.get('git_dirty') else ''}. "
        "Best of several rounds, compilation excluded; the variants of a table ran side by "
        "side in one process. Load average (1 min) before the run: "
        f"{load:.2f}"
        + (
            f" (other work shared the {m.get('usable_cores', '?')} cores: the rates, and most "
            "of all the 2-thread scaling, read low)."
            if load > 0.5
            else "."
        ),
        "",
    ]
    if results.get("targets"):
        lines += ["| target | measured | met |", "|---|---|---|"]
        for t in results["targets"]:
            lines.append(f"| {t['target']} | {t['shown']} | {'yes' if t['met'] else '**no**'} |")
        lines.append("")
    for name, module in FIGURE_MODULES.items():
        if name not in results:
            continue
        if "error" in results[name]:
            lines += [f"### {name}", "", f"Failed: `{results[name]['error']}`", ""]
        else:
            lines += module.markdown(results[name]) + [""]
    return "\n".join(lines)


def write(results, out_dir, stem):
    """Write ``<stem>.json`` and ``<stem>.md`` into ``out_dir``; return their paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    json_path = out_dir / f"{stem}.json"
    md_path = out_dir / f"{stem}.md"
    json_path.write_text(json.dumps(_plain(results), indent=1, allow_nan=False) + "\n")
    md_path.write_text(markdown(results))
    return json_path, md_path


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m benchmarks",
        description="Run mcrun's benchmark suite; write <out>/latest.json and latest.md "
        "(--quick: quick.json and quick.md).",
    )
    parser.add_argument(
        "--quick", action="store_true", help="small N, fewer rounds: under a minute"
    )
    parser.add_argument(
        "--huge", action="store_true", help="also run mcrun run of 1e8 shots (minutes; full mode)"
    )
    parser.add_argument("--out", default=str(RESULTS), help="output folder (default %(default)s)")
    parser.add_argument(
        "--only",
        metavar="FIGURES",
        help=f"comma-separated subset of {','.join(FIGURES)}",
    )
    args = parser.parse_args(argv)
    figures = FIGURES
    if args.only:
        figures = tuple(f.strip() for f in args.only.split(","))
        unknown = [f for f in figures if f not in FIGURES]
        if unknown:
            parser.error(
                f"--only: unknown figure(s) {', '.join(unknown)}; choose from {', '.join(FIGURES)}"
            )
    if args.huge and args.quick:
        parser.error("--huge runs in full mode only")
    config = QUICK if args.quick else FULL
    results = run_suite(config, figures=figures, huge=args.huge)
    stem = "quick" if args.quick else "latest"
    paths = write(results, args.out, stem)
    print(markdown(results))
    print("wrote " + ", ".join(str(p) for p in paths))
    failed = [name for name in figures if "error" in results[name]]
    if failed:
        print(f"benchmarks: failed: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0
