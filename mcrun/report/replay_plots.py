"""The pictures of a replayed session (``mcrun replay --plot``, ``mcrun plot REPLAY.parquet``):
per club, from the frame of ``mcrun.run.replay.replay`` and the tables of ``mcrun.run.clubs``.

- ``STEM-clubs.png``: (a) the carry and total of every shot that ended ok, per club: a box
  (quartiles, whiskers to the farthest shot within 1.5 interquartile ranges, the median) with
  every shot drawn over it as a dot, spread sideways by a fixed pattern (no random jitter);
  (b) the gapping chart: the mean carry per club with its standard deviation (bar) and its 10th
  to 90th percentiles (line), and the gap to the next club written between them. Clubs are in
  the order of ``clubs.club_summary``, longest mean carry first.
- ``STEM-device.png`` (when the file holds the device's results): per quantity the device
  gives, the model minus the device per club and for all shots: the bias (mean difference) as
  a bar and the RMSE as a marker, in the quantity's unit.

matplotlib is optional (``mcrun[plot]``), imported only when drawing, as in
``mcrun.report.plots``.
"""

import math
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun import status as status_codes
from mcrun.report.run_view import PlotError
from mcrun.report.style import (
    FLIGHT_COLOUR,
    RUN_COLOUR,
    YARD_M,
    Pictures,
    fmt,
    require_matplotlib,
)
from mcrun.results import output, reader
from mcrun.run import clubs

CLUBS_PLOT = "clubs"
DEVICE_PLOT = "device"
FIGURE_WIDTH_IN = 12.0
# Height of the clubs figure, and of each row of quantities of the device figure (inches).
CLUBS_HEIGHT_IN = 9.0
DEVICE_ROW_HEIGHT_IN = 3.4
DEVICE_COLUMNS = 2
STRIP_WIDTH = 0.28  # the sideways spread of a box's dots, in club spacings


def plot_paths(destination, device=True):
    """{kind: path} of the PNGs written beside the replay output ``destination``:
    ``STEM-clubs.png`` and, with ``device``, ``STEM-device.png``."""
    destination = Path(destination)
    kinds = (CLUBS_PLOT, DEVICE_PLOT) if device else (CLUBS_PLOT,)
    return {k: destination.with_name(f"{destination.stem}-{k}.png") for k in kinds}


def has_device(frame):
    """Whether a replay frame holds the device's results (``model_minus_device_*``)."""
    return any(str(c).startswith("model_minus_device_") for c in frame.columns)


def _strip_offsets(n):
    """Sideways offsets of n dots: a fixed low-discrepancy pattern in [-1, 1] (golden ratio)."""
    return 2.0 * ((np.arange(n) * 0.6180339887498949) % 1.0) - 1.0


def _yards_axis(ax):
    right = ax.secondary_yaxis("right", functions=(lambda m: m / YARD_M, lambda yd: yd * YARD_M))
    right.set_ylabel("yd", fontsize=8)
    right.tick_params(labelsize=8)


def _figure(height, title):
    figure_class, canvas_class = require_matplotlib("replay --plot")
    fig = figure_class(figsize=(FIGURE_WIDTH_IN, height), layout="constrained")
    canvas_class(fig)
    fig.suptitle(title, fontsize=10.5)
    return fig


def clubs_figure(frame, name):
    """Carry and total per club (boxes and every shot) and the gapping chart."""
    summary = clubs.club_summary(frame)
    names = list(summary["club"])
    fig = _figure(CLUBS_HEIGHT_IN, f"{name}: carry and total per club (shots that ended ok)")
    spread, gapping = fig.subplots(2, 1)
    group = clubs.club_labels(frame)
    ok = frame["status"].to_numpy() == status_codes.OK
    x = np.arange(len(names), dtype=float)
    for column, colour, shift, label in (
        ("carry_m", FLIGHT_COLOUR, -0.2, "carry"),
        ("total_m", RUN_COLOUR, 0.2, "total (at rest)"),
    ):
        values = frame[column].to_numpy(dtype=float)
        data = [values[(group == club) & ok] for club in names]
        drawn = [(k, d) for k, d in enumerate(data) if d.size]
        if drawn:
            spread.boxplot(
                [d for _, d in drawn],
                positions=[x[k] + shift for k, _ in drawn],
                widths=0.34,
                showfliers=False,
                manage_ticks=False,
                patch_artist=True,
                boxprops={"facecolor": colour, "alpha": 0.3, "edgecolor": colour},
                medianprops={"color": colour, "lw": 1.5},
                whiskerprops={"color": colour},
                capprops={"color": colour},
            )
        for k, d in drawn:
            spread.plot(
                x[k] + shift + 0.5 * STRIP_WIDTH * _strip_offsets(d.size),
                d,
                "o",
                ms=3.0,
                color=colour,
                alpha=0.8,
                label=label if k == drawn[0][0] else None,
            )
    spread.set_xticks(x, names)
    spread.set_xlim(-0.6, len(names) - 0.4)
    spread.set_ylabel("distance (m)")
    spread.set_title("(a) carry and total of every shot: box of the quartiles, a dot per shot")
    spread.grid(axis="y", alpha=0.25)
    if spread.get_legend_handles_labels()[0]:
        spread.legend(fontsize=8, loc="upper right", framealpha=0.85)
    else:  # (every shot failed: matplotlib's warning of an empty legend, on stderr)
        spread.text(0.5, 0.5, "no shot ended ok", transform=spread.transAxes, ha="center")
    _yards_axis(spread)

    mean = summary["carry_m_mean"].to_numpy(dtype=float)
    sd = summary["carry_m_sd"].to_numpy(dtype=float)
    p10 = summary["carry_m_p10"].to_numpy(dtype=float)
    p90 = summary["carry_m_p90"].to_numpy(dtype=float)
    gapping.bar(x, np.nan_to_num(mean), width=0.55, color=FLIGHT_COLOUR, alpha=0.35)
    gapping.errorbar(
        x, mean, yerr=np.nan_to_num(sd), fmt="o", color=FLIGHT_COLOUR, capsize=6, lw=2.0,
        label="mean carry ± sd",
    )  # fmt: skip
    gapping.vlines(x + 0.12, p10, p90, color="black", lw=1.0, label="10th to 90th percentile")
    for k, row in enumerate(summary.itertuples()):
        gapping.annotate(
            f"{fmt(row.carry_m_mean)} m\n{row.shots_ok}/{row.shots} ok",
            (x[k], 0.0),
            xytext=(0, 4),
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize=8,
        )
        if k + 1 < len(names) and math.isfinite(row.gap_m):
            top = np.nanmax([p90[k], p90[k + 1], mean[k] + np.nan_to_num(sd[k])])
            gapping.annotate(
                f"gap {fmt(row.gap_m)} m",
                (x[k] + 0.5, top),
                xytext=(0, 6),
                textcoords="offset points",
                ha="center",
                fontsize=8.5,
            )
    gapping.set_xticks(x, names)
    gapping.set_xlim(-0.6, len(names) - 0.4)
    finite = np.concatenate([p90[np.isfinite(p90)], (mean + np.nan_to_num(sd))[np.isfinite(mean)]])
    gapping.set_ylim(0.0, 1.15 * float(finite.max()) if finite.size else 1.0)
    gapping.set_ylabel("carry (m)")
    gapping.set_title("(b) gapping: mean carry per club, its spread, and the gap to the next club")
    gapping.grid(axis="y", alpha=0.25)
    gapping.legend(fontsize=8, loc="upper right", framealpha=0.85)
    _yards_axis(gapping)
    return fig


def _unit(quantity):
    """The unit of a compared quantity from its name: ``carry_m`` -> m."""
    return "deg" if quantity.endswith("_deg") else "m"


def device_figure(frame, name):
    """The model minus the device per quantity: bias per club (bars) and RMSE (markers)."""
    table = clubs.device_comparison(frame)
    quantities = list(dict.fromkeys(table["quantity"]))
    rows = -(-len(quantities) // DEVICE_COLUMNS)
    fig = _figure(
        max(rows * DEVICE_ROW_HEIGHT_IN, 4.0),
        f"{name}: the model minus the device, per club (bias: bar; RMSE: diamond; "
        "shots that ended ok and that the device measured)",
    )
    axes = np.atleast_1d(fig.subplots(rows, DEVICE_COLUMNS, squeeze=False)).ravel()
    for ax, quantity in zip(axes, quantities, strict=False):
        mine = table[table["quantity"] == quantity].reset_index(drop=True)
        x = np.arange(len(mine), dtype=float)
        colours = ["0.45" if c == clubs.ALL else FLIGHT_COLOUR for c in mine["club"]]
        bias = mine["bias"].to_numpy(dtype=float)
        ax.bar(x, np.nan_to_num(bias), width=0.6, color=colours, alpha=0.75)
        ax.plot(x, mine["rmse"], "D", color="black", ms=5, label="RMSE")
        ax.plot(x, -mine["rmse"], "D", color="black", ms=5, mfc="none", label="- RMSE")
        ax.axhline(0.0, color="black", lw=0.8)
        reach = np.nanmax(np.abs(np.r_[bias, mine["rmse"].to_numpy(dtype=float), 1e-9]))
        ax.set_ylim(-1.25 * reach, 1.6 * reach)  # room above for the legend
        for k, row in mine.iterrows():
            ax.annotate(
                f"{fmt(row['bias'], '+.2f')}\n(n {row['shots']})",
                (x[k], 0.0),
                xytext=(0, -4 if row["bias"] >= 0 else 4),
                textcoords="offset points",
                ha="center",
                va="top" if row["bias"] >= 0 else "bottom",
                fontsize=7.5,
            )
        ax.set_xticks(x, mine["club"])
        ax.set_ylabel(f"model - device ({_unit(quantity)})")
        ax.set_title(quantity.removesuffix("_m").removesuffix("_deg").replace("_", " "))
        ax.grid(axis="y", alpha=0.25)
        ax.legend(fontsize=7.5, loc="upper right", framealpha=0.85)
    for ax in axes[len(quantities) :]:
        ax.set_visible(False)
    return fig


def figures(frame, name):
    """[(kind, Figure)] of a replay frame: the clubs, and the device when the file has it."""
    found = [(CLUBS_PLOT, clubs_figure(frame, name))]
    if has_device(frame):
        found.append((DEVICE_PLOT, device_figure(frame, name)))
    return found


def write_replay_plots(frame, destination, name=None, dpi=150):
    """Write the PNGs of a replay frame beside ``destination`` (``plot_paths``); return the
    paths written."""
    name = name or Path(destination).stem
    paths = plot_paths(destination)
    try:
        with Pictures() as pictures:  # all or nothing, as a run's files
            for kind, fig in figures(frame, name):
                pictures.add(paths[kind], fig, dpi)
            pictures.commit()
    except OSError as err:
        where = err.filename or Path(destination).parent
        raise PlotError(f"cannot write {where}: {reader.reason_of(err)}") from None
    return pictures.paths


def is_replay(path):
    """Whether ``path`` is a file written by ``mcrun replay`` (its provenance says so)."""
    path = Path(path)
    if not path.is_file():
        return False
    try:
        return output.read_provenance(path).get("file") == "replay"
    except Exception:  # not a Parquet, or no provenance: not a replay
        return False


def _check_replay(path, frame):
    """PlotError unless ``frame`` (read from ``path``) has shots and the columns the pictures
    draw, numbers where they are numbers, as ``mcrun replay`` writes them."""
    if frame.empty:
        raise PlotError(f"{path}: no shots to draw")
    for name in ("status", *(column for _, column in clubs.SPREAD)):
        if name not in frame:
            raise PlotError(f"{path} was not written by mcrun replay: no column {name}")
        if not pd.api.types.is_numeric_dtype(frame[name]):
            raise PlotError(f"{path}: column {name} is {frame[name].dtype}: allowed are "
                            "numbers, as mcrun replay writes them")  # fmt: skip


def not_a_replay(path):
    """Why the file ``path`` is not one that ``mcrun replay`` wrote (for ``mcrun plot FILE``),
    one line."""
    try:
        provenance = output.read_provenance(path)
    except Exception as err:  # not a Parquet, or provenance not as mcrun writes it
        why = f"its provenance cannot be read: {reader.reason_of(err)}"
    else:
        why = f"its provenance says file = {provenance.get('file')!r}, not 'replay'"
    return (
        f"{path} is a file but not one that mcrun replay wrote ({why}): give a run folder "
        "or a replay's file"
    )


def plot_replay_file(path, out_dir=None, dpi=150):
    """The PNGs of a replay output ``path`` (``mcrun plot REPLAY.parquet``), written into
    ``out_dir`` (default: beside it); return the paths written."""
    require_matplotlib("plot")
    path = Path(path)
    try:
        frame = pd.read_parquet(path)
    except Exception as err:  # a damaged file: one line
        raise PlotError(f"{path}: cannot read the replay: {err}") from None
    _check_replay(path, frame)
    destination = path if out_dir is None else Path(out_dir) / path.name
    if out_dir is not None:
        try:
            Path(out_dir).mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise PlotError(f"-o: cannot write to {out_dir}: {reader.reason_of(err)}") from None
    return write_replay_plots(frame, destination, path.stem, dpi)
