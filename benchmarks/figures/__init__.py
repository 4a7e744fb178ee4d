"""The figures of the suite, one module each, in the order of the report. Each holds its
measurement next to the Markdown it writes:

- ``measure(config, inputs)``: the figure's numbers, a JSON-friendly dict (what ``latest.json``
  holds under the figure's name);
- ``markdown(result)``: its section of ``latest.md``, a list of lines;
- ``targets(result)``: the issues' targets it measures, as rows (target, measured, met,
  shown) of the table at the top of the report; none for a figure without one.

``kernel``: complete shots per second vs threads, on holes, and the accuracy against DOP853;
``baselines``: the flight alone as others write it, beside mcrun; ``steps``: accuracy and speed
vs the RK4 step; ``end_to_end``: ``mcrun run`` as a child process, rate and peak memory vs N;
``run_phases``: a run's phases per shot and the run against the kernel, on 1 and 2 threads;
``startup``: ``mcrun shot`` and a small ``mcrun run``, cold and warm.
"""

from benchmarks.figures import baselines, end_to_end, kernel, run_phases, startup, steps

# name -> module, in the order of the report (and of ``--only``'s choices).
FIGURES = {
    "kernel": kernel,
    "baselines": baselines,
    "steps": steps,
    "end_to_end": end_to_end,
    "run_phases": run_phases,
    "startup": startup,
}
