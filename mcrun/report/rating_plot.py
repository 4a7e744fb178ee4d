"""The picture of a rated course (``mcrun.play.rating``): each hole's expected strokes over
par for the scratch and the bogey player, and what its obstacles cost each where they were
asked for."""

import math

import numpy as np

from mcrun.report.style import require_matplotlib

FIGURE_SIZE_IN = (12.0, 7.0)
DPI = 120
COLOURS = ("#2f6fb8", "#c0392b")


def rating_figure(rating, title):
    """The Figure of ``rating`` (a ``CourseRating``), titled ``title``."""
    figure_class, canvas_class = require_matplotlib("rate --plot")
    fig = figure_class(figsize=FIGURE_SIZE_IN, layout="constrained")
    canvas_class(fig)
    players = rating.players[:2]
    costs = any(math.isfinite(s.obstacles_strokes) for p in players for s in rating.scores[p])
    axes = fig.subplots(2 if costs else 1, 1, squeeze=False)[:, 0]
    numbers = [s.hole for s in rating.scores[players[0]]]
    x = np.arange(len(numbers))
    width = 0.4
    for k, player in enumerate(players):
        over = [s.expected_strokes - h.par for s, h in zip(rating.scores[player], rating.holes,
                                                           strict=True)]  # fmt: skip
        axes[0].bar(x + (k - 0.5) * width, over, width, color=COLOURS[k], label=player)
        if costs:
            cost = [s.obstacles_strokes for s in rating.scores[player]]
            axes[1].bar(x + (k - 0.5) * width, cost, width, color=COLOURS[k], label=player)
    axes[0].set_ylabel("expected strokes over par")
    axes[0].axhline(0.0, color="0.3", lw=0.8)
    axes[0].set_title(title, fontsize=10)
    if costs:
        axes[1].set_ylabel("strokes the obstacles cost\n(bunkers, penalty areas, out of bounds)")
        axes[1].axhline(0.0, color="0.3", lw=0.8)
    for ax in axes:
        ax.set_xticks(x, [str(n) for n in numbers])
        ax.set_xlabel("hole")
        ax.legend(fontsize=8)
    attribution = rating.holes[0].attribution
    if attribution:
        fig.text(0.99, 0.005, f"Map data {attribution}", ha="right", va="bottom", fontsize=7,
                 color="0.4")  # fmt: skip
    return fig
