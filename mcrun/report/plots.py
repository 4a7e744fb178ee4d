"""``mcrun plot RUN_DIR -o DIR``: the pictures of a finished run, one PNG per plot.

``mcrun plot`` writes one PNG per plot of a finished run folder (``mcrun run``, local or Dask:
read through ``mcrun.results.reader``):

- ``pointNN-positions.png``: (a) where the balls land (carry_m, carry_lateral_m) and (b) where
  they finish (final_x_m, final_y_m), seen from above with the target line pointing up, the
  68 % and 95 % dispersion ellipses and the target. The ellipses of (b) are summary.parquet's;
  those of (a) are computed here the same way (``stats.ellipse`` of the co-moments).
- ``pointNN-distances.png``: histograms of carry, run and total, with the mean and the 5 % and
  95 % percentiles of summary.parquet.
- ``pointNN-trajectories.png`` (when the run wrote trajectories.parquet): a side view (height
  against downrange) and a top view (lateral against downrange) of sampled paths.
- ``pointNN-hole.png`` (a run on a hole): the hole map with the landing and finish positions,
  the 50 % and 95 % ellipses of the finish, the pin, the aim line and each zone's share
  (``mcrun.report.hole_plots``).
- for a run of several points (a sweep or groups): ``summary.png``, the summary statistics
  against the swept parameter or per group (means with 5-95 % bars), and ``finish.png``, the
  mean finish and 95 % ellipse of every point on one top view.

``mcrun report`` (``mcrun.report.html``) embeds the same plots in one self-contained HTML page.

Memory, whatever the number of shots: the shots are read one point at a time (the row groups
of shots.parquet, or the parts of a Dask run's dataset, that hold that point), only the
columns the plots need, in batches of ``BATCH_ROWS``. What is drawn from them:

- histograms (1-D of carry, run, total; 2-D of the landing and final positions) are BINNED,
  accumulated batch by batch over every ok shot of the point, on bins fixed beforehand from
  summary.parquet's 1 % and 99 % percentiles (widened by ``RANGE_PAD``, ``POSITION_PAD`` for
  the positions, on each side; shots beyond are counted and the count printed on the plot);
- a point with at most ``SCATTER_MAX_SHOTS`` ok shots is drawn as dots, every one of them;
  above that the positions are drawn as a density (the 2-D histogram), never as a sample;
- trajectories are a fixed, deterministic SAMPLE: the first ``TRAJECTORIES_PER_POINT`` shots of
  each point in trajectories.parquet (which holds the path of every k-th shot), read until
  that many are complete.

matplotlib is optional (``mcrun[plot]``): imported only when drawing, used through Figure
objects and the Agg canvas (no pyplot, no display, no global state).
"""

import sys
from pathlib import Path

from tqdm import tqdm

from mcrun import exits
from mcrun.report.figures import (
    distances_figure,
    finish_figure,
    positions_figure,
    summary_figure,
    sweep_layout,
    trajectories_figure,
)
from mcrun.report.run_view import (
    SCATTER_MAX_SHOTS,
    TRAJECTORIES_PER_POINT,
    PlotError,
    check_unchanged,
    open_run,
    read_point_shots,
    sample_trajectories,
)
from mcrun.report.style import Pictures, require_matplotlib
from mcrun.results import reader
from mcrun.results.output import PLOTS_FOLDER, writable_folder

DEFAULT_PLOT_DPI = 150


def point_name(run, point):
    width = max(2, len(str(run.points - 1)))
    return f"point{point:0{width}d}"


def figures(
    run,
    scatter_max=SCATTER_MAX_SHOTS,
    trajectories_per_point=TRAJECTORIES_PER_POINT,
    point_figures=None,
):
    """The plots of a run, one at a time: (file stem, caption, Figure). Reads one point at a
    time; the figures are not kept. ``point_figures(run, row, label, stem)``: more figures
    of each point, after its distances (``hole_plots.point_figures``, the hole's map)."""
    require_matplotlib()
    if run.points > 1:
        x_label, _, _, _ = sweep_layout(run)
        per = "per group" if x_label == "group" else f"against {x_label}"
        yield (
            "summary",
            f"Summary statistics {per}: means with bars from the 5 % to the 95 % percentile "
            "(summary.parquet).",
            summary_figure(run),
        )
        yield (
            "finish",
            "Mean finish and 95 % dispersion ellipse of every point, seen from above.",
            finish_figure(run),
        )
    for row in run.summary.to_dict("records"):
        point = int(row["point"])
        stem = point_name(run, point)
        label = f"point {point} ({row['label']}): " if run.points > 1 else ""
        shots = read_point_shots(run, point, scatter_max)
        how = (
            f"every one of the {shots.n_ok:,} ok shots as a dot"
            if shots.scatter
            else f"the density of all {shots.n_ok:,} ok shots, binned"
        )
        yield (
            f"{stem}-positions",
            f"{label}landing and final positions seen from above ({how}), with the 68 % and "
            "95 % dispersion ellipses and the target.",
            positions_figure(run, row, shots),
        )
        yield (
            f"{stem}-distances",
            f"{label}histograms of carry, run and total over all {shots.n_ok:,} ok shots, "
            "with the mean and the 5 % and 95 % percentiles.",
            distances_figure(run, row, shots),
        )
        if point_figures is not None:
            yield from point_figures(run, row, label, stem)
        if run.has_trajectories:
            paths = sample_trajectories(run, point, trajectories_per_point)
            if paths:
                yield (
                    f"{stem}-trajectories",
                    f"{label}side and top views of {len(paths)} sampled "
                    f"{'trajectory' if len(paths) == 1 else 'trajectories'} (the first in "
                    "trajectories.parquet).",
                    trajectories_figure(run, row, paths),
                )


def write_plots(
    run_dir,
    out_dir=None,
    dpi=DEFAULT_PLOT_DPI,
    scatter_max=SCATTER_MAX_SHOTS,
    point_figures=None,
    progress=False,
):
    """Write the PNGs of a run folder into ``out_dir`` (default RUN_DIR/plots); return
    [(path, caption)]. ``point_figures``: as ``figures``; ``progress``: a bar on stderr
    counting the pictures drawn (a sweep of 60 points draws for minutes).

    All or nothing (``style.Pictures``): each PNG is drawn under a temporary name and all are
    renamed into place at the end, so that an error or Ctrl-C leaves none of this call's
    pictures (and those of an earlier call as they were), never a part of the set, nor the
    folder where it made one."""
    run = open_run(run_dir)
    require_matplotlib()
    out_dir = Path(run.beside(PLOTS_FOLDER) if out_dir is None else out_dir)
    made = not (out_dir.exists() or out_dir.is_symlink())
    out_dir = writable_folder(out_dir)
    written = []
    try:
        with (
            Pictures(force=True) as pictures,
            tqdm(unit="picture", file=sys.stderr, disable=not progress, leave=False) as bar,
        ):
            for stem, caption, fig in figures(run, scatter_max, point_figures=point_figures):
                path = out_dir / f"{stem}.png"
                try:
                    pictures.add(path, fig, dpi)
                except OSError as err:
                    if exits.is_name_too_long(err):
                        raise
                    check_unchanged(run, run_dir, "the pictures were")  # (its folder gone)
                    raise PlotError(f"cannot write {path}: {reader.reason_of(err)}") from None
                written.append((path, caption))
                bar.update(1)
            check_unchanged(run, run_dir, "the pictures were")
            pictures.commit()
    except BaseException:
        if made and out_dir.is_dir() and not any(out_dir.iterdir()):
            out_dir.rmdir()  # (the folder it made for them, left empty)
        raise
    return written
