"""The picture of a solved hole (``mcrun.play``): on the hole's map, the player's expected
strokes from every state as colour and the best aim from some of them (arrows, the club
named at a few), beside the score distribution of the policy played from the tee."""

import math

import numpy as np

from mcrun.play import SCORE_NAMES
from mcrun.play.transitions import AIMS
from mcrun.report.hole_map import draw_hole
from mcrun.report.style import require_matplotlib

FIGURE_SIZE_IN = (13.0, 8.0)
DPI = 120
ARROWS = 60


def play_figure(result):
    """The Figure of ``result`` (a ``mcrun.play.PlayResult``)."""
    figure_class, canvas_class = require_matplotlib("play --plot")
    fig = figure_class(figsize=FIGURE_SIZE_IN, layout="constrained")
    canvas_class(fig)
    left, right = fig.subplots(1, 2, width_ratios=[1.4, 1.0])
    draw_hole(result.hole, left)
    lat, s, tr = result.lattice, result.solution, result.transitions
    dots = left.scatter(lat.xy[:, 1], lat.xy[:, 0], c=s.values, s=6, cmap="viridis_r",
                        zorder=3)  # fmt: skip
    fig.colorbar(dots, ax=left, label="expected strokes to hole out")
    px, py = result.hole.pin_xy
    picks = np.unique(np.linspace(0, lat.size - 1, ARROWS).astype(int))
    for k in np.r_[0, picks]:
        row = s.best_row[k]
        if row < 0:
            continue
        a = tr.actions[tr.row_action[row]]
        x, y = lat.xy[k]
        target, angle = AIMS[a.aim]
        bearing = math.atan2(py - y, px - x) + math.radians(angle)
        # (a part-power shot's distance falls faster than its power: drawn as power^1.5)
        length = min(a.total_m * a.power**1.5, math.hypot(px - x, py - y) + 10.0)
        left.annotate("", xy=(y + length * math.sin(bearing), x + length * math.cos(bearing)),
                      xytext=(y, x), arrowprops=dict(arrowstyle="->", color="crimson", lw=0.8),
                      zorder=4)  # fmt: skip
        if k == 0 or k in picks[::6]:
            power = "" if a.power == 1.0 else f" {100 * a.power:.0f}%"
            left.text(y, x, result.player.clubs[a.club] + power, fontsize=7, zorder=5)
    left.set_title(f"{result.player.name} on {result.hole.name or result.hole.source}\n"
                   "expected strokes to hole out, and the best aim", fontsize=9)  # fmt: skip
    if result.hole.par:
        shares = result.score_shares()
        labels = [k.replace(" or ", "\nor ") for k in SCORE_NAMES]
        heights = [100 * shares[k] for k in SCORE_NAMES]
    else:  # no par to score against: the plays by their strokes
        shares = result.stroke_shares()
        labels = [f"{k} strokes" for k in shares]
        heights = [100 * v for v in shares.values()]
    right.bar(range(len(labels)), heights, color="0.4")
    right.set_xticks(range(len(labels)), labels, fontsize=8)
    right.set_ylabel("share of plays (%)")
    title = (f"{len(result.scores):,} plays of the policy from the tee\nmean "
             f"{result.scores.mean():.3f}; expected {result.tee_value:.3f} +- "
             f"{result.tee_se:.3f}")  # fmt: skip
    right.set_title(title, fontsize=9)
    right.grid(alpha=0.3, axis="y")
    return fig
