"""The map of a hole, drawn as golfers read it: the zones in their colours, the elevation
contours when the hole has a ground shape, the tee and the pin, in the hole's frame (metres:
lateral across the page, + right; downrange up the page, as the position plots).

``draw_hole(hole_map, ax)`` draws a ``mcrun.results.geometry.HoleMap`` (what a run recorded of
its hole: ``RunFolder.hole_map``; of a hole in memory: ``geometry.hole_map_of``) onto an axes
so that shot clouds can be drawn over it; ``write_hole_map`` writes a figure of one hole.
matplotlib is optional (``mcrun[plot]``).
"""

from pathlib import Path

import numpy as np

from mcrun import exits
from mcrun.hole.zones import ZONE_COLOURS
from mcrun.report.style import require_matplotlib
from mcrun.results import output
from mcrun.results.geometry import HoleMap, hole_map_of

HOLE_FIGURE_SIZE_IN = (6.0, 9.0)


def draw_hole(hole_map, ax=None):
    """Draw ``hole_map`` (a ``mcrun.results.geometry.HoleMap``, or a ``mcrun.hole.hole.Hole``
    drawn as a run on it records it) onto ``ax`` (a new figure's when None); return the axes.
    Horizontal: y (m, + right of the tee-pin line); vertical: x (m, from the tee towards the
    pin). The map's attribution is written on the axes when it has one."""
    if ax is None:
        figure_class, canvas_class = require_matplotlib("hole")
        fig = figure_class(figsize=HOLE_FIGURE_SIZE_IN, layout="constrained")
        canvas_class(fig)
        ax = fig.add_subplot()
    from matplotlib.colors import to_rgb
    from matplotlib.patches import Patch

    t = hole_map if isinstance(hole_map, HoleMap) else hole_map_of(hole_map)
    hole = t.facts
    kinds = t.zone_kinds
    ny, nx = t.zone.shape
    c = t.cell_m
    colours = np.array([to_rgb(ZONE_COLOURS[k]) for k in kinds])
    y_max, x_max = t.y0_m + (ny - 1) * c, t.x0_m + (nx - 1) * c
    ax.imshow(
        colours[t.zone.T],  # rows: x (downrange), columns: y (lateral)
        origin="lower",
        extent=(t.y0_m - c / 2, y_max + c / 2, t.x0_m - c / 2, x_max + c / 2),
        interpolation="nearest",
    )
    if hole.ground != "flat" and np.ptp(t.height_m) > 0.05:
        step = _contour_step_m(float(np.ptp(t.height_m)))
        levels = np.arange(np.floor(t.height_m.min() / step), np.ceil(t.height_m.max() / step) + 1)
        y = t.y0_m + np.arange(ny) * c
        x = t.x0_m + np.arange(nx) * c
        contours = ax.contour(
            y, x, t.height_m.T, levels=levels * step, colors="0.2", linewidths=0.5
        )
        ax.clabel(contours, fontsize=6, fmt="%g m")
    if hole.line_xy is not None:
        line = np.asarray(hole.line_xy, float)
        ax.plot(line[:, 1], line[:, 0], color="white", lw=0.8, ls="--")
    ax.plot(0.0, 0.0, marker="s", color="white", mec="black", ms=7, ls="none", label="tee")
    ax.plot(
        t.pin_xy[1],
        t.pin_xy[0],
        marker="^",
        color="red",
        mec="black",
        ms=9,
        ls="none",
        label="pin",
    )
    present = np.unique(t.zone)
    handles = [
        Patch(color=ZONE_COLOURS[kinds[k]], label=kinds[k].replace("_", " ")) for k in present
    ]
    ax.legend(
        handles=handles + ax.get_legend_handles_labels()[0],
        fontsize=7,
        loc="upper left",
        framealpha=0.8,
    )
    ax.set_aspect("equal")
    ax.set_xlabel("lateral (m), + right of the tee-pin line")
    ax.set_ylabel("downrange (m), from the tee towards the pin")
    title = hole.name or hole.source
    if hole.par is not None:
        title += f", par {hole.par}"
    ax.set_title(
        f"{title}\n{hole.length_m:.0f} m ({hole.length_m / 0.9144:.0f} yd) tee to pin", fontsize=9
    )
    if hole.attribution:
        ax.text(
            0.99,
            0.01,
            hole.attribution,
            transform=ax.transAxes,
            ha="right",
            va="bottom",
            fontsize=6,
            bbox=dict(facecolor="white", alpha=0.7, lw=0),
        )
    return ax


def _contour_step_m(span_m):
    """A round contour interval giving about 5-20 lines over ``span_m``."""
    for step in (0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0):
        if span_m / step <= 20:
            return step
    return 20.0


def write_hole_map(hole_map, path, dpi=150, force=True):
    """Draw ``hole_map`` and write the figure to ``path`` (PNG, or what its suffix names), as a
    run's files are written: under a temporary name, renamed into place with interrupts
    deferred, so that an interrupted command leaves no picture under its final name.
    ``force``: replace a file there (else OutputError)."""
    ax = draw_hole(hole_map)
    with output.AtomicFile(path, force=force) as target:
        ax.figure.savefig(target.tmp, dpi=dpi, format=Path(path).suffix[1:] or "png")
        with exits.interrupts_deferred():
            target.commit()
    return path
