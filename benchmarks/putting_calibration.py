"""``python -m benchmarks.putting_calibration [--refit] [--n N]``: the putters against the Tour.

The Tour putter's make rates and average putts on Tour-like greens against the PGA Tour's, and
its putts on slopes against Broadie's ShotLink figures (``mcrun.putting.calibration``), N
holings-out each (20,000) on the calibration's seeded errors and greens; the scratch and
15-handicap presets on the same greens. With ``--refit``, first the refit itself
(``calibration.refit`` from the preset, on ``calibration.FIT_N`` holings-out: the same start,
the same fit), its steps and the parameters it ends at.

Prints Markdown tables and writes ``benchmarks/results/putting-calibration.md``; asserts
nothing.
"""

import argparse
from pathlib import Path

from benchmarks.common import publish
from mcrun.putting.calibration import (
    DISTANCES_FT,
    FIT_N,
    SLOPE_TARGETS,
    calibration_table,
    refit,
    slope_checks,
    tour_holeouts,
)
from mcrun.putting.putter import PUTTERS

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "putting-calibration.md"


def _putter_line(p):
    return (f"start line {p.line_sd_deg:g} deg, speed {p.speed_sd_pct:g} %, read "
            f"{p.read_sd_pct:g} % of slope, pace {p.pace_m:g} m with {p.pace_slope_share:g} of "
            "the slope beyond the hole")  # fmt: skip


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=20000)
    parser.add_argument("--refit", action="store_true")
    args = parser.parse_args(argv)
    lines = ["# The putters against the Tour", ""]
    if args.refit:
        steps = []
        fitted, loss, _ = refit(PUTTERS["tour"], report=steps.append)
        lines += [f"Refit from the preset ({FIT_N:,} holings-out a target):", ""]
        lines += [f"- {step}" for step in steps]
        lines += ["", f"Ends at: {_putter_line(fitted)} (loss {loss:.3f}).", ""]
    tour = PUTTERS["tour"]
    lines += [
        f"The Tour putter: {_putter_line(tour)}; {args.n:,} holings-out a distance on Tour-like "
        "greens (standard errors in brackets).",
        "",
        "| ft | make, simulated | make, Tour | average putts, simulated | average putts, Tour |",
        "|---|---|---|---|---|",
    ]
    holeouts = tour_holeouts(tour, args.n)
    for ft, make, make_se, tour_make, putts, putts_se, tour_putts in calibration_table(
        tour, args.n, holeouts=holeouts
    ):
        lines.append(
            f"| {ft} | {make:.1f} % ({make_se:.1f}) | "
            + (f"{tour_make:g} %" if tour_make is not None else "")
            + f" | {putts:.3f} ({putts_se:.3f}) | "
            + (f"{tour_putts:g}" if tour_putts is not None else "")
            + " |"
        )
    checks = slope_checks(tour, args.n, ten_ft=holeouts[10])
    lines += ["", "| on slopes | simulated | Tour | held to |", "|---|---|---|---|"]
    for key, (what, value, lo, hi) in SLOPE_TARGETS.items():
        shown = "2.5-5 (about 5 % relative)" if value is None else f"{value:g}"
        extra = ""
        if key.startswith("uphill"):
            extra = (f" ({checks['make_uphill_pct_8ft']:.1f} % against "
                     f"{checks['make_downhill_pct_8ft']:.1f} %; +- "
                     f"{checks['uphill_minus_downhill_make_pct_8ft_se']:.1f})")  # fmt: skip
        lines.append(f"| {what} | {checks[key]:.2f}{extra} | {shown} | {lo:g} to {hi:g} |")
    lines += ["", f"The presets on the same greens ({args.n // 5:,} holings-out):", ""]
    lines += ["| ft | " + " | ".join(str(d) for d in DISTANCES_FT) + " |",
              "|---|" + "---|" * len(DISTANCES_FT)]  # fmt: skip
    for name in ("scratch", "15-handicap"):
        rows = calibration_table(PUTTERS[name], args.n // 5)
        lines.append(f"| {name}: make | " + " | ".join(f"{r[1]:.1f} %" for r in rows) + " |")
        lines.append(f"| {name}: putts | " + " | ".join(f"{r[4]:.3f}" for r in rows) + " |")
    lines.append("")
    publish(RESULTS, lines)


if __name__ == "__main__":
    main()
