"""The golden file: results written before a restructuring, which it must leave unchanged.

The cases go through the command line (``mcrun run``, ``mcrun shot --json``, ``mcrun bounce
--json``), whose interface a restructuring keeps, so that the same cases run on any layout of
the package: every library scenario at N shots with a fixed seed (its shots and its summary),
and one-shot cases over every aerodynamic model, wind profile, turf preset, slope and club
delivery, some with their trajectory.

``python tests/golden_cases.py [SCENARIO ... | --shots]`` writes the file anew
(``tests/data/golden/``; with names, only those library scenarios' files; with ``--shots``, only
the one-shot cases); do that only
when a change moves numbers on purpose, and say which and why. ``tests/test_golden.py``
compares the current tree with it: at the tolerance of ``tests/tolerance.py`` on any CPU, bit
for bit with ``pytest --bit-for-bit`` on the machine that wrote it.
"""

import contextlib
import io
import json
import sys
import tempfile
from pathlib import Path

import pandas as pd

GOLDEN = Path(__file__).parent / "data" / "golden"
N = 200
SEED = 11

DRIVE = ["--ball-speed", "74.6", "--launch", "10.9", "--spin", "281"]
SEVEN = ["--ball-speed", "53.6", "--launch", "16.3", "--spin", "739"]
WEDGE = ["--ball-speed", "45", "--launch", "24.2", "--spin", "990"]
LAUNCHES = {"drive": DRIVE, "seven": SEVEN, "wedge": WEDGE}
MODELS = ("ferguson2022", "smits_smith1994", "lyu2018", "penner2002", "trackman2019")
TURFS = ("green", "firm_green", "fairway", "rough")


def shot_cases():
    """{name: (argv after ``mcrun``, whether the trajectory is kept)}."""
    cases = {}
    for model in MODELS:
        for name, launch in LAUNCHES.items():
            cases[f"model-{model}-{name}"] = (["shot", *launch, "--aero", model], name == "seven")
    for profile in ("uniform", "log", "power"):
        for wind in ("5,-3", "-6,2"):
            for name in ("drive", "seven"):
                argv = ["shot", *LAUNCHES[name], "--wind", wind, "--wind-profile", profile]
                cases[f"wind-{profile}-{wind}-{name}"] = (argv, wind == "5,-3" and name == "drive")
    cases["wind-log-z0"] = (["shot", *DRIVE, "--wind", "8,0", "--wind-profile", "log",
                             "--wind-param", "0.1", "--wind-height", "2"], False)  # fmt: skip
    for turf in TURFS:
        for name, launch in LAUNCHES.items():
            cases[f"turf-{turf}-{name}"] = (["shot", *launch, "--turf", turf], False)
    for slope, fall_line in ((2, 0), (3, 180), (5, 90), (5, -45), (10, 30), (25, 0), (40, 135)):
        for name in ("seven", "wedge"):
            argv = ["shot", *LAUNCHES[name], "--slope", str(slope), "--fall-line", str(fall_line)]
            cases[f"slope-{slope}-{fall_line}-{name}"] = (argv, slope in (5, 25))
    cases["club-driver"] = (["shot", "--club-speed", "49", "--loft", "11"], True)
    cases["club-iron-mass"] = (["shot", "--club-speed", "38", "--loft", "32",
                                "--club-mass", "0.27"], False)  # fmt: skip
    cases["curve"] = (["shot", *DRIVE, "--azimuth", "-2", "--spin-axis", "12"], True)
    cases["topspin-free"] = (["shot", "--ball-speed", "30", "--launch", "5", "--spin", "0"], False)
    cases["slow"] = (["shot", "--ball-speed", "0.5", "--launch", "1", "--spin", "0"], True)
    cases["air"] = (["shot", *DRIVE, "--altitude", "1600", "--temperature", "30",
                     "--humidity", "0.8"], False)  # fmt: skip
    cases["density"] = (["shot", *SEVEN, "--air-density", "1.0", "--cd-scale", "1.1",
                         "--cl-scale", "0.9"], False)  # fmt: skip
    cases["overrides"] = (["shot", *WEDGE, "--mu", "0.3", "--softness", "1.4", "--stimp", "11ft",
                           "--critical-height", "8mm"], False)  # fmt: skip
    cases["dt"] = (["shot", *SEVEN, "--dt", "0.05"], False)
    cases["steep-down"] = (["shot", *WEDGE, "--slope", "45", "--fall-line", "0"], False)
    for speed, angle, spin in ((7.7, 45, 0), (12, 40, 150), (24, 60, 500), (5, 30, -120)):
        argv = ["bounce", "--speed", str(speed), "--angle", str(angle), "--spin", str(spin)]
        cases[f"bounce-{speed}-{angle}-{spin}"] = (argv, False)
    return cases


def library_scenarios():
    """The names of the library scenarios, from the package's own scenario folder: those on a
    plane (written before there were holes) and those on a hole (written before the kernel's
    tables were named and its files split)."""
    folder = Path(__file__).parents[1] / "scenarios"
    return sorted(p.stem for p in folder.glob("*.toml"))


def _main(argv):
    from mcrun.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(argv))
    return code, out.getvalue(), err.getvalue()


def run_shot(argv, trajectory):
    """(outcome dict, trajectory DataFrame or None) of one case."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "t.csv"
        extra = ["--trajectory", str(path)] if trajectory else []
        code, out, err = _main([*argv, "--json", *extra])
        if code != 0:
            raise RuntimeError(f"mcrun {' '.join(argv)}: exit {code}: {err}")
        return json.loads(out), (pd.read_csv(path) if trajectory else None)


def run_scenario(name, out_dir):
    """(shots, summary) DataFrames of a library scenario at N shots, seed SEED."""
    code, _, err = _main(["run", name, "-n", str(N), "--seed", str(SEED), "-o", str(out_dir),
                          "--quiet", "--threads", "2"])  # fmt: skip
    if code != 0:
        raise RuntimeError(f"mcrun run {name}: exit {code}: {err}")
    return (
        pd.read_parquet(Path(out_dir) / "shots.parquet"),
        pd.read_parquet(Path(out_dir) / "summary.parquet"),
    )


def write(names=None):
    """Write the golden file anew; with ``names``, only those library scenarios' files, or
    with ``--shots`` only the one-shot cases (shots.json, trajectories.parquet)."""
    GOLDEN.mkdir(parents=True, exist_ok=True)
    if names and names != ["--shots"]:
        _write_scenarios(names)
        return
    outcomes, trajectories = {}, []
    for name, (argv, keep) in shot_cases().items():
        outcome, trajectory = run_shot(argv, keep)
        outcomes[name] = outcome
        if trajectory is not None:
            trajectories.append(trajectory.assign(case=name))
    (GOLDEN / "shots.json").write_text(json.dumps(outcomes, indent=1, sort_keys=True) + "\n")
    pd.concat(trajectories, ignore_index=True).to_parquet(GOLDEN / "trajectories.parquet")
    if names != ["--shots"]:
        _write_scenarios(library_scenarios())


def _write_scenarios(names):
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            shots, summary = run_scenario(name, Path(tmp) / name)
            shots.to_parquet(GOLDEN / f"{name}.shots.parquet")
            summary.to_parquet(GOLDEN / f"{name}.summary.parquet")
            print(name, len(shots), "shots", file=sys.stderr)


if __name__ == "__main__":
    write(sys.argv[1:])
