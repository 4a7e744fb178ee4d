"""``python -m benchmarks.profile [SCENARIO] [--shots N] [--seconds S]``: where the kernel's time
goes, function by function, sampled by Linux ``perf`` at a fixed rate of CPU time (``-e
cpu-clock``, which needs no hardware counters, so it works in containers and virtual machines).

perf cannot name Numba's compiled functions: it reads the names of code made at run time from
``/tmp/perf-PID.map`` (a line per function: start, size, name, in hex). This compiles the
scenario's kernel afresh, into a temporary cache (a kernel loaded from Numba's cache does not
list its functions), writes that map with the address of each of them, runs the kernel (on
every thread it has) for about ``--seconds`` under ``perf record``, and prints each function's
share of the samples that fell in the kernel (its compilation's samples fall in Python and
LLVM, and are not counted). Numba's reference counts (``NRT_incref``, ``NRT_decref``) are
counted with the kernel. Needs ``perf`` on the PATH (exit 2 without it); asserts nothing, and
leaves nothing behind.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

SAMPLES_PER_S = 2000
REFERENCE_COUNTS = ("NRT_incref", "NRT_decref")


def readable(symbol):
    """A Numba function's symbol as its Python name: ``_ZN5mcrun6engine4roll...B...`` is
    ``mcrun.engine.roll``; a closure's ``<locals>`` kept; any other symbol as it is."""
    if not symbol.startswith("_ZN"):
        return symbol
    parts, i = [], 3
    while i < len(symbol) and symbol[i].isdigit():
        j = i
        while symbol[j].isdigit():
            j += 1
        n = int(symbol[i:j])
        parts.append(symbol[j : j + n])
        i = j + n
    return ".".join(parts).replace("_3clocals_3e", "<locals>") if parts else symbol


def write_perf_map(libraries, path):
    """Write perf's map of the functions compiled into ``libraries`` (Numba code libraries, as
    compiled, not loaded from its cache) to ``path``: each function from its address to the next
    one's. Returns the functions' names, in the map's order."""
    starts = {}
    for library in libraries:
        for function in library._final_module.functions:
            if function.is_declaration:
                continue
            address = library.get_pointer_to_function(function.name)
            if address:
                starts[address] = readable(function.name)
    ordered = sorted(starts)
    with open(path, "w") as out:
        for k, address in enumerate(ordered):
            size = ordered[k + 1] - address if k + 1 < len(ordered) else 1 << 16
            out.write(f"{address:x} {min(size, 1 << 20):x} {starts[address]}\n")
    return [starts[address] for address in ordered]


def shares(report, names):
    """{function: share of the kernel's samples} from ``perf report --stdio --sort sym``'s
    text, counting the functions of ``names`` and Numba's reference counts."""
    counted = {}
    for line in report.splitlines():
        m = re.match(r"\s*([\d.]+)%\s+\[\.\]\s+(\S.*?)\s*$", line)
        if m and (m.group(2) in names or m.group(2) in REFERENCE_COUNTS):
            counted[m.group(2)] = counted.get(m.group(2), 0.0) + float(m.group(1))
    total = sum(counted.values())
    ordered = sorted(counted.items(), key=lambda kv: -kv[1])
    return {k: v / total for k, v in ordered} if total else {}


def _child(scenario, shots, seconds, names):
    """Compile the kernel of ``scenario``, write the map (and, to ``names``, its path and the
    functions' names), run it for ``seconds``."""
    from mcrun.engine import batch
    from mcrun.engine.backend import simulate_batch
    from mcrun.run import sampling
    from mcrun.run import scenario as sc

    s = sc.load(sc.find(scenario))
    terrain = s.hole.terrain() if s.hole is not None else None
    inputs, _ = sampling.sample(s, s.points[0], 0, shots)
    simulate_batch(inputs[:64], terrain=terrain)
    libraries = [
        task.overloads[sig].library
        for task in (batch._batch_task, batch._batch_task_general)
        for sig in task.signatures
        if ("Terrain" in str(sig)) == (terrain is not None)
    ]
    path = f"/tmp/perf-{os.getpid()}.map"
    mapped = write_perf_map(libraries, path)
    with open(names, "w") as out:
        out.write("\n".join([path, *mapped]) + "\n")
    started = time.perf_counter()
    rounds = 0
    while time.perf_counter() - started < seconds:
        simulate_batch(inputs, terrain=terrain)
        rounds += 1
    rate = rounds * shots / (time.perf_counter() - started)
    n = len(mapped)
    print(f"{n} functions mapped; {rounds * shots:,} shots at {rate:,.0f} shots/s", flush=True)


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m benchmarks.profile", description=__doc__)
    p.add_argument("scenario", nargs="?", default="drive-real-ground")
    p.add_argument("--shots", type=int, default=100_000)
    p.add_argument("--seconds", type=float, default=10.0)
    p.add_argument("--child", metavar="NAMES", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        _child(args.scenario, args.shots, args.seconds, args.child)
        return 0
    perf = shutil.which("perf")
    if perf is None:
        print("benchmarks.profile: perf is not on the PATH (Linux: linux-tools or perf)",
              file=sys.stderr)  # fmt: skip
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "perf.data")
        listed = os.path.join(tmp, "names")
        env = {**os.environ, "NUMBA_CACHE_DIR": os.path.join(tmp, "numba")}
        child = [sys.executable, "-m", "benchmarks.profile", args.scenario, "--child", listed,
                 "--shots", str(args.shots), "--seconds", str(args.seconds)]  # fmt: skip
        print(f"compiling {args.scenario}'s kernel afresh (a minute or two), then "
              f"{args.seconds:g} s under perf", flush=True)  # fmt: skip
        record = [perf, "record", "-q", "-e", "cpu-clock", "-F", str(SAMPLES_PER_S), "-o", data]
        done = subprocess.run(record + ["--", *child], env=env)
        if done.returncode != 0:
            print(f"benchmarks.profile: perf record exited {done.returncode}", file=sys.stderr)
            return 2
        report = subprocess.run(
            [perf, "report", "-i", data, "--stdio", "--sort", "sym"],
            capture_output=True, text=True, env=env,
        ).stdout  # fmt: skip
        path, *names = open(listed).read().splitlines()
        os.remove(path)
    table = shares(report, set(names))
    print("\n| function | share of the kernel's samples |\n|---|---|")
    for name, share in table.items():
        if share >= 0.005:
            print(f"| {name} | {100 * share:.1f} % |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
