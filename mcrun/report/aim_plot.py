"""The picture of an aim search (``mcrun.run.aim``): expected strokes against the aim for each
club, and on the hole's map the finish pattern of the best aim beside that of the reference
aim (the pin, or the scenario's aim), as ``aim.patterns`` flew them again."""

import math

import numpy as np

from mcrun.report.hole_map import draw_hole
from mcrun.report.style import Pictures, require_matplotlib

FIGURE_SIZE_IN = (13.0, 7.0)
PATTERN_DOTS = 2000
DPI = 120


def aim_figure(result, patterns):
    """The Figure of ``result`` (an ``aim.AimSearch``) and its best club's finishes
    ``patterns`` (``aim.patterns``: {"best": (x, y), "reference": (x, y)}, m in the hole's
    frame)."""
    figure_class, canvas_class = require_matplotlib("aim --plot")
    fig = figure_class(figsize=FIGURE_SIZE_IN, layout="constrained")
    canvas_class(fig)
    left, right = fig.subplots(1, 2, width_ratios=[1.0, 1.1])
    for club in result.clubs:
        x = np.array(club.offsets_m)
        e = np.array(club.expected)
        se = np.array(club.expected_se)
        (line,) = left.plot(x, e, marker="o", ms=3, label=club.club)
        left.fill_between(x, e - 2 * se, e + 2 * se, color=line.get_color(), alpha=0.2, lw=0)
        k = club.best
        left.plot([x[k]], [e[k]], marker="*", ms=14, color=line.get_color())
    left.set_xlabel(f"aim: m right of the pin at {result.pin_distance_m:.0f} m")
    left.set_ylabel("expected strokes left after the shot (band: +/- 2 SE)")
    left.set_title("Expected strokes by aim (the same shots at every aim)")
    left.grid(alpha=0.3)
    left.legend(loc="upper center")

    hole = result.scenario.hole
    draw_hole(hole, right)
    club, k = result.best()
    best = club.offsets_m[k]
    x0, y0 = patterns["best"]
    xr, yr = patterns["reference"]
    dots = slice(0, PATTERN_DOTS)
    right.scatter(yr[dots], xr[dots], s=3, color="0.2", alpha=0.5,
                  label=f"aimed at the reference ({club.reference_m:+.1f} m)")  # fmt: skip
    right.scatter(y0[dots], x0[dots], s=3, color="crimson", alpha=0.6,
                  label=f"best aim ({best:+.1f} m)")  # fmt: skip
    d = result.pin_distance_m
    sx, sy = result.start_xy_m
    for offset, colour in ((club.reference_m, "0.2"), (best, "crimson")):
        b = result.bearing_rad(offset)
        right.plot([sy, sy + 1.15 * d * math.sin(b)], [sx, sx + 1.15 * d * math.cos(b)],
                   color=colour, lw=1.0, ls="--")  # fmt: skip
    px, py = hole.pin_xy
    finite = np.isfinite(x0) & np.isfinite(y0)
    xs = np.r_[x0[finite], xr[np.isfinite(xr)], px]
    ys = np.r_[y0[finite], yr[np.isfinite(yr)], py]
    pad = 15.0
    lo_x, hi_x = np.percentile(xs, [0.5, 99.5])
    lo_y, hi_y = np.percentile(ys, [0.5, 99.5])
    right.set_xlim(lo_y - pad, hi_y + pad)
    right.set_ylim(lo_x - pad, hi_x + pad)
    right.set_title(f"{club.club}: {club.expected[k]:.3f} strokes left at the best aim, "
                    f"{club.difference[k]:+.3f} +/- {club.difference_se[k]:.3f} vs the reference",
                    fontsize=9)  # fmt: skip
    right.legend(loc="lower left", fontsize=8)
    return fig


def write_aim_plot(result, patterns, path, dpi=DPI, force=True):
    """Write ``aim_figure`` to ``path`` (PNG) as a run's files are (``style.Pictures``): under a
    temporary name, renamed into place once drawn; an existing ``path`` is replaced only with
    ``force``. Returns the path."""
    with Pictures(force=force) as pictures:
        pictures.add(path, aim_figure(result, patterns), dpi)
        pictures.commit()
    return pictures.paths[0]
