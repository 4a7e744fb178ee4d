"""The look the pictures share: matplotlib loaded on demand (``require_matplotlib``), the
figure sizes and colours, a figure titled with its run (``new_figure``), the ellipses, notes
and legend entries of a top view, an honest top view (``fit_equal``), the numbers as shown
(``fmt``), a figure's PNG (``png_bytes``) and pictures written as a run's files are
(``Pictures``).

matplotlib is optional (``mcrun[plot]``): imported only when drawing, used through Figure
objects and the Agg canvas (no pyplot, no display, no global state).
"""

import contextlib
import io
import math
import re
import textwrap
import warnings

from mcrun import exits
from mcrun.report.run_view import PlotError
from mcrun.results import output

MISSING_MATPLOTLIB = "mcrun {} needs matplotlib: pip install 'mcrun[plot]'"

# Size of each figure (inches); the PNG is this times the dpi, in pixels (constrained layout
# keeps the figure size).
FIGURE_SIZES_IN = {
    "positions": (11.0, 7.0),
    "distances": (12.0, 4.8),
    "trajectories": (11.0, 7.5),
    "summary": (12.0, 8.5),
    "finish": (9.0, 8.5),
    "hole": (12.0, 9.0),
}

FLIGHT_COLOUR = "#1f77b4"
RUN_COLOUR = "#ff7f0e"
TARGET_COLOUR = "#d62728"
YARD_M = 0.9144


def require_matplotlib(command="plot"):
    """Figure and the Agg canvas; PlotError with the one-line message when matplotlib is
    missing."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise PlotError(MISSING_MATPLOTLIB.format(command)) from None
    return Figure, FigureCanvasAgg


def fmt(value, spec=".1f", unit=""):
    """``value`` formatted, "-" when missing; never "-0.0"."""
    if value is None or not math.isfinite(float(value)):
        return "-"
    text = format(float(value), spec)
    if text.startswith("-") and float(text) == 0.0:
        text = text[1:]
    return text + unit


def short_label(run, row):
    """A point's label without the key paths: "Driver", "5 m/s, 45 deg"."""
    parts = [row["group"]] if row.get("group") else []
    parts += [str(row[k]) for k in run.sweep_keys]
    return ", ".join(parts) or row.get("label") or f"point {row['point']}"


# The lines of a figure's title that its question may take.
QUESTION_LINES = 3


def new_figure(kind, run, what, row=None):
    """A Figure of ``FIGURE_SIZES_IN[kind]`` titled with the run: scenario, what the plot
    shows, the question, N and seed (and the point)."""
    figure_class, canvas_class = require_matplotlib()
    width, height = FIGURE_SIZES_IN[kind]
    fig = figure_class(figsize=(width, height), layout="constrained")
    canvas_class(fig)
    chars = int(width * 72.0 / (10.0 * 0.55))
    wrap = {"width": chars, "max_lines": QUESTION_LINES, "placeholder": " ...",
            "break_on_hyphens": False}  # fmt: skip
    lines = textwrap.wrap(f"{run.name}: {what}", **wrap)
    if run.question:  # (at most QUESTION_LINES: a question of 300 kB took minutes to draw)
        lines += textwrap.wrap(run.question, **wrap)
    facts = []
    if run.n is not None:
        facts.append(f"N = {int(run.n):,} shots per point")
    if run.seed is not None:
        facts.append(f"seed {run.seed}")
    if row is not None and run.points > 1:
        facts.append(f"point {int(row['point'])}: {row['label']}")
    lines += textwrap.wrap(", ".join(facts), **wrap)
    fig.suptitle("\n".join(lines), fontsize=10.5)
    return fig


def note(ax, text, loc="upper left"):
    x, ha = (0.02, "left") if "left" in loc else (0.98, "right")
    y, va = (0.98, "top") if "upper" in loc else (0.02, "bottom")
    ax.text(
        x,
        y,
        text,
        transform=ax.transAxes,
        ha=ha,
        va=va,
        fontsize=8.5,
        bbox={"facecolor": "white", "edgecolor": "0.7", "alpha": 0.85, "boxstyle": "round"},
        zorder=10,
    )


def draw_ellipse(ax, centre_x, centre_y, a, b, angle_deg, level, colour="black"):
    """An ellipse on a top view whose horizontal axis is lateral (right positive) and whose
    vertical axis is downrange; ``angle_deg`` from the target line towards the right."""
    from matplotlib.patches import Ellipse

    if not all(math.isfinite(v) for v in (centre_x, centre_y, a, b, angle_deg)):
        return None
    patch = Ellipse(
        (centre_y, centre_x),
        width=2.0 * a,
        height=2.0 * b,
        angle=90.0 - angle_deg,
        fill=False,
        edgecolor=colour,
        lw=1.6 if level == 95 else 1.2,
        ls="-" if level == 95 else "--",
        zorder=6,
        label=f"{level} % ellipse",
    )
    ax.add_patch(patch)
    return patch


def fit_equal(fig, axes):
    """Widen the limits of ``axes`` so that a metre is as long across as along (an honest top
    view), each axes keeping the box the layout gives it.

    The layout is computed once and then frozen: constrained layout and a fixed aspect do not
    agree (each draw would move the axes), so the aspect is made by the limits instead.
    """
    fig.get_layout_engine().execute(fig)
    fig.set_layout_engine("none")
    width, height = fig.get_size_inches()
    for ax in axes:
        box = ax.get_position()
        w_in, h_in = box.width * width, box.height * height
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        scale = max(abs(x1 - x0) / w_in, abs(y1 - y0) / h_in)  # m per inch
        cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        ax.set_xlim(cx - 0.5 * scale * w_in, cx + 0.5 * scale * w_in)
        ax.set_ylim(cy - 0.5 * scale * h_in, cy + 0.5 * scale * h_in)


def colour_of(k, n):
    """The colour of the k-th of n points or series: matplotlib's ten, or twenty above ten."""
    if n <= 10:
        return f"C{k % 10}"
    from matplotlib import colormaps

    return colormaps["tab20"](k % 20)


def legend_line(**kwargs):
    from matplotlib.lines import Line2D

    return Line2D([], [], **kwargs)


# matplotlib's warning for each character its font lacks (a club named in Japanese, an emoji).
# ("... missing from font(s) DejaVu Sans." in recent matplotlib, "... from current font." in
# older ones.)
_MISSING_GLYPH = re.compile(r"Glyph (\d+) .*missing from (?:current font|font\(s\) (.+?))\.?$")


def png_bytes(fig, dpi):
    """The PNG of a Figure at ``dpi``: its size in inches times the dpi, in pixels. Characters
    the font lacks are drawn as boxes, said in one warning (matplotlib's were one a character,
    each with its source line)."""
    buffer = io.BytesIO()
    with warnings.catch_warnings(record=True) as caught:  # (the others as the filters say)
        warnings.filterwarnings("always", message=r"Glyph \d+")
        fig.savefig(buffer, format="png", dpi=dpi)
    missing, fonts = {}, {}
    for warning in caught:
        match = _MISSING_GLYPH.match(str(warning.message))
        if match:
            missing[chr(int(match[1]))] = None
            fonts[match[2] or "the current font"] = None
        else:
            warnings.warn_explicit(warning.message, warning.category, warning.filename,
                                   warning.lineno)  # fmt: skip
    if missing:
        warnings.warn(
            f"{len(missing)} character(s) not in the font ({', '.join(fonts)}), drawn "
            f"as boxes: {' '.join(missing)}",
            stacklevel=2,
        )
    return buffer.getvalue()


class WrittenThenInterrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM that came while pictures were renamed into place, and waited until
    they all were: ``paths`` are written."""

    def __init__(self, paths):
        super().__init__(f"{len(paths)} picture(s) written")
        self.paths = list(paths)


class Pictures:
    """A set of PNGs written all or nothing, as a run's files are (``output.AtomicFile``): each
    under a hidden temporary name beside its destination (``.NAME.partial-HOST-PID-TOKEN``) as
    it is drawn, all renamed into place by ``commit``, Ctrl-C and SIGTERM waiting until the
    last rename (``exits.interrupts_deferred``). On an error or an interrupt before ``commit``
    the temporary files are removed: no picture is left under its final name, and those of an
    earlier run of the command are left as they were. ``force``: replace existing pictures
    (otherwise an existing one is refused, OutputError, before it is drawn).

        with Pictures() as pictures:
            for path, fig in ...:
                pictures.add(path, fig, dpi)
            pictures.commit()
    """

    def __init__(self, force=True):
        self.force = force
        self.paths = []
        self._files = []
        self._stack = contextlib.ExitStack()

    def __enter__(self):
        self._stack.__enter__()
        return self

    def add(self, path, fig, dpi):
        """Draw ``fig`` at ``dpi`` into a temporary file beside ``path``."""
        target = self._stack.enter_context(output.AtomicFile(path, force=self.force))
        target.tmp.write_bytes(png_bytes(fig, dpi))
        self._files.append(target)
        self.paths.append(target.path)

    def commit(self):
        """Rename every picture into place, interrupts deferred until the last; one that came
        meanwhile is raised then, as ``WrittenThenInterrupted``."""
        done = False
        try:
            with exits.interrupts_deferred():
                for target in self._files:
                    target.commit()
                done = True
        except KeyboardInterrupt:
            if not done:
                raise
            raise WrittenThenInterrupted(self.paths) from None

    def __exit__(self, exc_type, exc, tb):
        return self._stack.__exit__(exc_type, exc, tb)
