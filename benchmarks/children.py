"""``mcrun`` as a child process: its command line, and a run of it measured for wall time and
peak memory (the end-to-end and start-up figures)."""

import json
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from benchmarks.common import ROOT


def mcrun_command():
    """argv prefix that runs ``mcrun``: the console script beside this Python, else on PATH."""
    script = Path(sys.executable).with_name("mcrun")
    if script.exists():
        return [str(script)]
    found = shutil.which("mcrun")
    if found:
        return [found]
    return [sys.executable, "-c", "import sys; from mcrun.cli import main; sys.exit(main())"]


def mcrun_run_command():
    """argv prefix of ``mcrun run``."""
    return [*mcrun_command(), "run"]


@dataclass
class Child:
    argv: list
    wall_s: float
    returncode: int
    peak_rss_mb: float
    stdout: str
    stderr: str


# Runs a command and reports its wall time and peak memory. Linux charges a child the peak
# resident memory of the process it was spawned from (the maximum is kept across exec), so the
# suite's own gigabyte would show in every child's ru_maxrss: this small launcher is spawned
# instead, and forks the command from itself.
_LAUNCHER = """
import json, os, sys, time
report, argv = sys.argv[1], sys.argv[2:]
start = time.perf_counter()
pid = os.fork()
if pid == 0:
    try:
        os.execvp(argv[0], argv)
    except OSError as err:
        print(err, file=sys.stderr)
    os._exit(127)
_, status, usage = os.wait4(pid, 0)
wall = time.perf_counter() - start
code = os.waitstatus_to_exitcode(status)
with open(report, "w") as f:
    json.dump({"wall_s": wall, "maxrss_kib": usage.ru_maxrss, "returncode": code}, f)
sys.exit(code if code >= 0 else 1)
"""


def run_child(argv, env=None):
    """Run ``argv`` to completion: its wall time, exit code, output and peak resident memory
    (its own ``ru_maxrss``; see ``_LAUNCHER``)."""
    with (
        tempfile.TemporaryFile() as out,
        tempfile.TemporaryFile() as err,
        tempfile.TemporaryDirectory() as folder,
    ):
        report = Path(folder) / "report.json"
        launcher = [sys.executable, "-c", _LAUNCHER, str(report), *map(str, argv)]
        subprocess.run(launcher, stdout=out, stderr=err, env=env, cwd=ROOT, check=False)
        measured = json.loads(report.read_text())
        out.seek(0)
        err.seek(0)
        return Child(
            argv=[str(a) for a in argv],
            wall_s=measured["wall_s"],
            returncode=measured["returncode"],
            peak_rss_mb=measured["maxrss_kib"] / 1024.0,  # ru_maxrss is in KiB on Linux
            stdout=out.read().decode(errors="replace"),
            stderr=err.read().decode(errors="replace"),
        )


def failed(child):
    """The end of a failed child's output, in one line."""
    tail = (child.stderr.strip() or child.stdout.strip()).splitlines()[-3:]
    return f"exit {child.returncode}: {' | '.join(tail)}"


def folder_mb(path):
    """The size of the files under ``path``, MB."""
    return sum(p.stat().st_size for p in Path(path).rglob("*") if p.is_file()) / 2**20
