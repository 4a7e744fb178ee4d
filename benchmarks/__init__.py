"""The benchmark suite of mcrun: speed, accuracy and memory, measured side by side.

Run it with ``python -m benchmarks`` (full, a few minutes) or ``python -m benchmarks --quick``
(under a minute, a check before each commit). It writes ``benchmarks/results/latest.json``
(every number, and the machine it ran on) and ``latest.md`` (the tables of docs/performance.md); the
quick mode writes ``quick.json`` and ``quick.md`` instead, so that it never replaces the full
results.

- ``reference.py``: the reference integration (scipy DOP853 at rtol = atol = 1e-12), written
  out again from the equations, independent of ``mcrun.physics.flight``.
- ``baselines.py``: the flight alone as others would write it (solve_ivp per shot, NumPy
  vectorised RK4, Numba one shot per ``prange`` iteration), for comparison.
- ``figures/``: one module per figure, its measurement beside the Markdown it writes:
  ``kernel.py`` (complete shots/s vs threads, on holes, accuracy against DOP853),
  ``baselines.py`` (the flight alone as others write it, beside mcrun), ``steps.py`` (accuracy
  and speed vs the RK4 step), ``end_to_end.py`` (``mcrun run`` to Parquet: rate and peak memory
  vs N), ``startup.py`` (``mcrun shot`` and a small run, cold and warm).
- ``common.py``: the sizes of a run (full, quick), the interleaved timing, the shared inputs and
  number formats; ``children.py``: ``mcrun`` as a measured child process; ``machine.py``: what
  the numbers were measured on.
- ``suite.py``: the driver: runs the figures, writes the JSON and the Markdown.
- ``holes.py``: the kernel on each library hole, an aim search and a course's grid
  (``python -m benchmarks.holes``, ``results/holes.md``).
- ``profile.py``: where the kernel's time goes, function by function, sampled by Linux
  ``perf`` (``python -m benchmarks.profile [SCENARIO]``; needs ``perf``).
- ``ground_parts.py``: what each part of a shot on curved ground costs alone, for one ball and
  over lanes of balls (``python -m benchmarks.ground_parts``, ``results/ground-parts.md``).
- ``monitors.py``: reading and replaying a 100,000-row launch-monitor export
  (``python -m benchmarks.monitors``, ``results/monitors.md``). Measured once: 0.61 s to read,
  0.90 s to read, replay and summarise per club, of which 0.08 s in the kernel, so 0.82 s
  besides the simulation (target: under 2 s); 2 shared cores, load 1.3.
"""
