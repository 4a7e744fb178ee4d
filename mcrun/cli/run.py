"""``mcrun run``, ``mcrun validate`` and ``mcrun scenarios``: run a scenario, check one, list the
library.

``mcrun run`` runs on the local engine (``mcrun.run.local``), or on a Dask cluster
(``mcrun.run.distributed``) when given ``--dask local``, ``--scheduler`` or
``--scheduler-file``; both print the same summary table.
"""

import json
import math
import sys
from pathlib import Path

import numpy as np

from mcrun.cli import USER_ERRORS, Interrupted, compile_if_needed, kernels_of
from mcrun.cli.options import local_workers, named
from mcrun.quantities import InputError
from mcrun.results import stats
from mcrun.run import local, plan, sampling
from mcrun.run import scenario as scenario_module
from mcrun.units import control_free

# --- printing ----------------------------------------------------------------------------------


def _fmt(value, spec=".1f"):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return format(float(value) + 0.0, spec)


def _mean_sd(row, name, spec=".1f"):
    return f"{_fmt(row[f'{name}_mean'], spec)} ± {_fmt(row[f'{name}_std'], spec)}"


# The inputs' variance shares (squared standardised coefficients) add up to R^2 when the inputs
# are independent; where they miss it by more than this, they are correlated (the scenario's
# correlation, or the sample's at small n) and the shares overlap: said so.
SHARES_APART = 0.05
OVERLAP_NOTE = "; the inputs correlated, the shares overlap"

# The points a terminal shows of a run or a scenario; a larger sweep's are all in its files.
SHOWN_POINTS = 40


def _more_points(total, shown, where):
    """The line that says how many points were not shown, and where they are."""
    return f"... and {total - shown:,} more points ({where})"


def format_summary(summary, top=3):
    """The summary as an aligned text table, one line per point, then the variance drivers;
    the first SHOWN_POINTS points of a larger sweep."""
    total = len(summary)
    summary = summary.iloc[:SHOWN_POINTS]
    header = [
        "point",
        "label",
        "ok/shots",
        "carry_m",
        "total_m",
        "final_y_m",
        "ellipse95_m",
        "r50_m",
        "r95_m",
    ]
    lines = [header]
    for row in summary.to_dict("records"):
        lines.append(
            [
                str(row["point"]),
                row["label"] or "-",
                f"{row['n_ok']}/{row['n_shots']}",
                _mean_sd(row, "carry_m"),
                _mean_sd(row, "total_m"),
                _mean_sd(row, "final_y_m"),
                f"{_fmt(row['ellipse95_semi_major_m'])} x {_fmt(row['ellipse95_semi_minor_m'])}"
                f" @ {_fmt(row['ellipse95_angle_deg'], '.0f')} deg",
                _fmt(row["distance_r50_m"]),
                _fmt(row["distance_r95_m"]),
            ]
        )
    widths = [max(len(line[k]) for line in lines) for k in range(len(header))]
    text = [
        "  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip()
        for line in lines
    ]
    for row in summary.to_dict("records"):
        if "n_landed" in row:  # a run on a hole: where the shots finished
            shares = [
                (name[len("p_finish_") :], v)
                for name, v in row.items()
                if name.startswith("p_finish_") and not name.endswith("95") and v > 0
            ]
            parts = ", ".join(
                f"{zone} {100 * v:.1f}% [{100 * row[f'p_finish_{zone}_lo95']:.1f}, "
                f"{100 * row[f'p_finish_{zone}_hi95']:.1f}]"
                for zone, v in sorted(shares, key=lambda kv: -kv[1])
            )
            text.append(f"point {row['point']}: finished in {parts} (95% intervals)")
        for y in (*stats.DRIVEN, "run_m"):
            prefix = f"{y}_share_"
            shares = {
                k[len(prefix) :]: v
                for k, v in row.items()
                if k.startswith(prefix) and isinstance(v, float) and math.isfinite(v)
            }
            if not shares:
                continue
            best = sorted(shares.items(), key=lambda kv: -kv[1])[:top]
            parts = ", ".join(f"{k} {100 * v:.0f}%" for k, v in best)
            if y == "run_m":
                text.append(f"point {row['point']}: run_m explained alone by {parts}")
            else:
                r2 = row[f"{y}_r2"]
                overlap = math.isfinite(r2) and abs(sum(shares.values()) - r2) > SHARES_APART
                text.append(
                    f"point {row['point']}: variance of {y} from {parts} "
                    f"(R^2 {_fmt(r2, '.2f')}{OVERLAP_NOTE if overlap else ''})"
                )
    if total > len(summary):
        text.append(_more_points(total, len(summary), "every point is in summary.parquet"))
    return "\n".join(text)


def _json_safe(value):
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _say(line):
    print(line, file=sys.stderr, flush=True)


def _dask_backend(args):
    """Whether ``mcrun run`` was asked for the Dask backend (``mcrun.run.distributed``)."""
    names = ("dask", "scheduler", "scheduler_file", "workers")
    return any(getattr(args, name, None) is not None for name in names)


def _run_on_dask(args):
    """``mcrun run`` with ``--dask local``, ``--scheduler`` or ``--scheduler-file``."""
    from mcrun.run import distributed

    if args.threads is not None:
        raise InputError(
            "--threads is for the local engine; the Dask backend runs one Numba thread per "
            "Dask thread (use --workers N with --dask local)"
        )
    if args.scheduler == "local":  # (the API's name of a local cluster, not an address)
        raise InputError("--scheduler local: a local cluster is --dask local (--scheduler is an "
                         "existing cluster's address, e.g. tcp://HOST:8786)")  # fmt: skip
    if args.workers is not None and args.dask != "local":
        raise InputError("--workers is for --dask local (an existing cluster has its workers)")
    return distributed.run_scenario(
        args.scenario,
        scheduler=args.scheduler if args.scheduler else args.dask,
        scheduler_file=args.scheduler_file,
        workers=local_workers(args.workers),
        **_run_options(args),
    )


def fit_lines(scenario):
    """Lines saying the normal fitted to each launch file that a point draws from (means, sds
    and correlations: ``scenario.launch_fits``); none when no point fits one."""
    lines = []
    for fit in scenario_module.launch_fits(scenario.points):
        which = f"club {fit['club']!r} of " if fit["club"] else ""
        points = ", ".join(str(k) for k in fit["points"][:SHOWN_POINTS])
        if len(fit["points"]) > SHOWN_POINTS:
            points += ", ..."
        lines.append(
            f"point(s) {points}: launch.file fitted as a correlated normal to {fit['shots']} "
            f"shots of {which}{fit['file']}:"
        )
        lines += scenario_module.describe_fit(fit).splitlines()
    return lines


def _announcer(scenario):
    """What a run says before it starts: the plan line, then the normal fits drawn from."""
    fits = fit_lines(scenario)

    def announce(line):
        _say(line)
        for fit_line in fits:
            _say(fit_line)

    return announce


# The run's arguments as its options name them (an error said 'n must be ...' of -n).
RUN_OPTIONS = {"n": "-n", "seed": "--seed", "chunk_size": "--chunk-size",
               "trajectories_every": "--trajectories", "threads": "--threads",
               "out_dir": "-o"}  # fmt: skip


def _run_options(args):
    """The options of ``mcrun run`` that both executors take."""
    return dict(
        n=args.n,
        seed=args.seed,
        out_dir=args.output,
        chunk_size=args.chunk_size,
        trajectories_every=args.trajectories,
        progress=not args.quiet,
        force=args.force,
        ignore_disk_space=args.ignore_disk_space,
        announce=None if args.quiet else _announcer(args.scenario),
    )


def _cmd_run(args):
    try:
        args.scenario = _load(args.scenario)
        # The kernels of the scenario's ground alone (a hole's runs nothing on the plane), said
        # apart from the run's time.
        ground, _ = plan.kernels_of(args.scenario)
        compile_if_needed(ground, kernels_of(args, plan.general_flight(args.scenario)))
        if _dask_backend(args):
            result = named(lambda: _run_on_dask(args), RUN_OPTIONS)
        else:
            result = named(
                lambda: local.run_scenario(
                    args.scenario, threads=args.threads, **_run_options(args)
                ),
                RUN_OPTIONS,
            )
    except KeyboardInterrupt:
        raise Interrupted("the run was stopped and nothing was written") from None
    summary = result.summary()
    if args.json:
        records = [{k: _json_safe(v) for k, v in r.items()} for r in summary.to_dict("records")]
        print(
            json.dumps(
                {
                    "out_dir": str(result.out_dir),
                    "files": [str(p) for p in result.paths],
                    "n": result.n,
                    "seed": result.seed,
                    "threads": result.threads,
                    "elapsed_s": result.elapsed_s,
                    "summary": records,
                },
                allow_nan=False,
            )
        )
        return 0
    print(format_summary(summary))
    shots = result.n * result.points
    rate = shots / result.elapsed_s if result.elapsed_s > 0 else math.inf
    threads = f"{result.threads} thread" + ("s" if result.threads != 1 else "")
    where = getattr(result, "where", threads)
    print(f"{shots} shots in {result.elapsed_s:.1f} s ({rate:,.0f} shots/s on {where}); wrote:")
    for path in result.paths:
        print(f"  {path}")
    return 0


def describe(scenario):
    """A short description of a scenario's points (what ``mcrun validate`` prints)."""
    lines = [f"scenario {scenario.name} ({scenario.path})"]
    if scenario.question:
        lines.append(f"question: {scenario.question}")
    lines.append(
        f"{len(scenario.points)} point(s) x {scenario.shots} shots, seed {scenario.seed}, "
        f"block size {scenario.block_size}"
    )
    names = sampling.sampled_columns(scenario)
    for point in scenario.points[:SHOWN_POINTS]:
        varying = plan.driver_inputs(point, names)
        model = point.params["models.aero"]
        label = point.label or "(single point)"
        lines.append(
            f"  {point.index}: {label}: aero {model}; sampled: "
            + (", ".join(varying) if varying else "none (every input constant)")
        )
    if len(scenario.points) > SHOWN_POINTS:
        lines.append("  " + _more_points(len(scenario.points), SHOWN_POINTS, "in the sweep"))
    lines += fit_lines(scenario)
    return "\n".join(lines)


def _load(spec):
    """The scenario ``spec`` (a file or a library name), what of its hole's map was left out
    said."""
    scenario = scenario_module.load(spec)
    if scenario.hole is not None:
        from mcrun.cli.hole import say_skipped

        say_skipped(scenario.hole)
    return scenario


def _cmd_validate(args):
    scenario = _load(args.scenario)
    text = describe(scenario)
    print(text)
    return 0


def _cmd_scenarios(args):
    folder = Path(args.dir) if args.dir else scenario_module.library_folder()
    if not folder.is_dir():
        raise InputError(f"--dir {folder}: not a folder")
    entries = [(*entry, _load_error(entry[1])) for entry in scenario_module.list_library(folder)]
    if args.json:
        print(
            json.dumps(
                [
                    {"name": name, "question": q, "path": str(path), "error": error}
                    for name, path, q, error in entries
                ]
            )
        )
        return 0
    if not entries:
        print(f"no scenarios in {folder}")
        return 0
    width = max(len(name) for name, _, _, _ in entries)
    for name, _, question, error in entries:  # (a question's line breaks, as the JSON's \n)
        print(f"{name:<{width}}  {control_free(' '.join(question.split()))}".rstrip())
        if error is not None:
            print(f"{'':<{width}}  does not load: {error}")
    return 0


def _load_error(path):
    """Why the scenario file ``path`` does not load, in one line; None if it loads."""
    try:
        scenario_module.load(path)
    except USER_ERRORS as err:
        return " ".join(str(err).split())
    return None


def _add_dask_options(p):
    """The Dask backend's options of ``mcrun run`` (``mcrun.run.distributed``)."""
    group = p.add_argument_group(
        "Dask backend (pip install 'mcrun[dask]')",
        "Run the chunks as tasks on a Dask cluster: the same shots and summary as the local "
        "engine, bit for bit; shots are written as a dataset, shots/part-NNNNN.parquet, to a "
        "folder or fsspec URL (-o s3://...) that the client and every worker reach.",
    )
    where = group.add_mutually_exclusive_group()
    where.add_argument(
        "--dask",
        choices=["local"],
        help="a LocalCluster on this machine: --workers processes of one thread each",
    )
    where.add_argument(
        "--scheduler", metavar="ADDRESS", help="an existing cluster, e.g. tcp://HOST:8786"
    )
    where.add_argument(
        "--scheduler-file", metavar="PATH", help="an existing cluster's scheduler file"
    )
    group.add_argument(
        "--workers",
        metavar="N",
        help="worker processes of --dask local (default: the cores; at most 4 a core, as many "
        "as the memory holds)",
    )


def register(subparsers):
    """Add ``run``, ``validate``, ``scenarios`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "run",
        help="run a Monte Carlo scenario and write shots, summary (and trajectories) Parquet",
        description="Run every point of a scenario (a TOML file, see 'mcrun scenarios') with "
        "N shots each, and write a folder with shots.parquet (one row per shot), "
        "summary.parquet (one row per point: dispersion statistics and what drives it) and "
        "optionally trajectories.parquet. The same seed gives the same shots, bit for bit, "
        "whatever the thread count and chunk size. Ctrl-C stops cleanly and writes nothing.",
        allow_abbrev=False,
    )
    p.add_argument(
        "scenario", metavar="SCENARIO", help="scenario file (.toml), or a library scenario's name"
    )
    p.add_argument("-n", metavar="N", help="shots per point (default: the scenario's); 1e6 works")
    p.add_argument("--seed", metavar="S", help="random seed (default: the scenario's)")
    p.add_argument(
        "-o",
        "--output",
        metavar="DIR",
        help="output folder (default runs/<scenario name>-<seed>); refused if it holds a run, "
        "unless --force",
    )
    p.add_argument("--force", action="store_true", help="replace an existing run folder")
    p.add_argument("--threads", metavar="T", help="Numba threads (default: all cores)")
    p.add_argument(
        "--trajectories", metavar="K", help="also write the path of every K-th shot of each point"
    )
    p.add_argument(
        "--chunk-size",
        metavar="C",
        default=plan.DEFAULT_CHUNK_SIZE,
        help=f"shots per chunk and row group (default {plan.DEFAULT_CHUNK_SIZE}); the shots "
        "do not depend on it (the summary's means and covariances, merged chunk by chunk, and "
        "what is made of them, in their last bits only)",
    )
    p.add_argument(
        "--ignore-disk-space",
        action="store_true",
        help="run even when the estimated size of the output is not under the free space of "
        "its disk (by default such a run is refused before it starts)",
    )
    p.add_argument(
        "--quiet", action="store_true", help="no progress bar, and no line saying the run's size"
    )
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    _add_dask_options(p)
    p.set_defaults(func=_cmd_run)

    p = subparsers.add_parser(
        "validate",
        help="check a scenario file and describe its points",
        description="Load and check a scenario; print its points and what each samples. "
        "Exit 0 when valid, else one line naming the file, the key and what is allowed, exit 2.",
        allow_abbrev=False,
    )
    p.add_argument(
        "scenario", metavar="SCENARIO", help="scenario file (.toml), or a library scenario's name"
    )
    p.set_defaults(func=_cmd_validate)

    p = subparsers.add_parser(
        "scenarios",
        help="list the scenario library, with the question each one answers",
        allow_abbrev=False,
    )
    p.add_argument(
        "--dir",
        metavar="DIR",
        help=f"library folder (default: ${scenario_module.ENV_LIBRARY}, else the scenarios/ "
        "folder beside the package)",
    )
    p.add_argument("--json", action="store_true", help="print JSON instead")
    p.set_defaults(func=_cmd_scenarios)
