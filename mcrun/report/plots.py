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

import io
import math
import re
import textwrap
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun import exits
from mcrun import status as status_codes
from mcrun.api import InputError
from mcrun.results import output, reader, stats
from mcrun.run.scenario import question_of

MISSING_MATPLOTLIB = "mcrun {} needs matplotlib: pip install 'mcrun[plot]'"

# How the plots read a run (see the module docstring).
SCATTER_MAX_SHOTS = 5000
TRAJECTORIES_PER_POINT = 100
BATCH_ROWS = 65536
HISTOGRAM_BINS = 61  # odd: a point whose shots are all alike falls in the middle bin
DENSITY_BINS = (50, 200)  # bins per axis of a density: sqrt(ok shots) / 2 within these
RANGE_PAD = 0.15  # share of the 1 %..99 % span added on each side of a histogram's axis
POSITION_PAD = 0.3  # the same for the top views of the positions
MIN_SPAN_M = 1.0  # the smallest span an axis shows (a point whose shots are all alike)

DEFAULT_PLOT_DPI = 150
PLOTS_FOLDER = "plots"

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

_SHOT_COLUMNS = (
    "point",
    "status",
    "carry_m",
    "carry_lateral_m",
    "run_m",
    "total_m",
    "final_x_m",
    "final_y_m",
)
_TRAJECTORY_COLUMNS = ("point", "shot", "x_m", "y_m", "z_m", "phase")
DISTANCES = (
    ("carry_m", "carry"),
    ("run_m", "run (landing to rest)"),
    ("total_m", "total (at rest)"),
)


class PlotError(InputError):
    """A run folder cannot be read or its pictures cannot be written; one line for the user."""


# --- the run folder ----------------------------------------------------------------------------


@dataclass
class Run:
    """A run folder opened for its pictures: the reader's ``RunFolder`` (either layout), its
    summary by point and the swept parameters (the summary's columns between label and
    n_shots)."""

    folder: reader.RunFolder
    summary: pd.DataFrame
    sweep_keys: list
    # A run on a hole: (hole, aim azimuth rad, reason it could not be rebuilt), once
    # ``hole_plots.hole_of`` has read it.
    hole_state: tuple | None = None

    @property
    def path(self):
        return self.folder.path

    @property
    def provenance(self):
        return self.folder.provenance

    @property
    def has_trajectories(self):
        return self.folder.has_trajectories

    @property
    def name(self):
        return self.provenance.get("scenario_name") or Path(str(self.path)).name

    @property
    def n(self):
        return self.provenance.get("n")

    @property
    def seed(self):
        return self.provenance.get("seed")

    @property
    def points(self):
        return len(self.summary)

    @property
    def question(self):
        return question_of(self.provenance.get("scenario_text") or "")

    @property
    def explicit_target(self):
        """Whether the scenario names a target (else it is each point's mean final position)."""
        try:
            data = tomllib.loads(self.provenance.get("scenario_text") or "")
        except tomllib.TOMLDecodeError:
            return False
        groups = data.get("group", [])
        return "target" in data.get("scenario", {}) or any(
            isinstance(g, dict) and "target" in g for g in groups
        )

    def beside(self, name):
        """``name`` in the run folder: where its pictures go unless told (-o)."""
        if self.folder.url is not None:
            raise PlotError(f"{self.path} is a URL: give -o, a local file or folder to write")
        return Path(self.path) / name


def open_run(run_dir):
    """Open a finished run folder of either layout (``reader.open_run``) and check that it
    holds what the plots draw."""
    folder = reader.open_run(run_dir)
    summary = folder.summary
    needed = (
        "point",
        "group",
        "label",
        "n_shots",
        "n_ok",
        "total_m_mean",
        "ellipse95_semi_major_m",
        "target_x_m",
    )
    missing = [c for c in needed if c not in summary.columns]
    if missing:
        raise PlotError(
            f"{folder.path}/{output.SUMMARY_FILE} was not written by mcrun run: no column "
            f"{missing[0]}"
        )
    missing = [c for c in _SHOT_COLUMNS if c not in folder.shot_columns]
    if missing:
        raise PlotError(
            f"the shots of {folder.path} were not written by mcrun run: no column {missing[0]}"
        )
    summary = summary.sort_values("point").reset_index(drop=True)
    columns = list(summary.columns)
    sweep_keys = columns[columns.index("label") + 1 : columns.index("n_shots")]
    return Run(folder, summary, sweep_keys)


# --- what is drawn of one point ----------------------------------------------------------------


def _finite(*values):
    return [float(v) for v in values if v is not None and math.isfinite(float(v))]


def _span(values, pad=RANGE_PAD, min_span=MIN_SPAN_M):
    """(lo, hi) around the finite ``values``: their extent widened by ``pad`` on each side."""
    values = _finite(*values)
    if not values:
        return -min_span, min_span
    lo, hi = min(values), max(values)
    if hi - lo < min_span:
        middle = 0.5 * (lo + hi)
        lo, hi = middle - 0.5 * min_span, middle + 0.5 * min_span
    width = hi - lo
    return lo - pad * width, hi + pad * width


def _ellipse_extent(a, b, angle_deg):
    """Half extents (along the target line, across it) of an ellipse of semi-axes a, b whose
    major axis is ``angle_deg`` from the target line."""
    if not all(math.isfinite(v) for v in (a, b, angle_deg)):
        return 0.0, 0.0
    t = math.radians(angle_deg)
    return (
        math.sqrt((a * math.cos(t)) ** 2 + (b * math.sin(t)) ** 2),
        math.sqrt((a * math.sin(t)) ** 2 + (b * math.cos(t)) ** 2),
    )


def position_limits(row):
    """((downrange lo, hi), (lateral lo, hi)) in m of a point's positions plot, from its
    summary row: the 1-99 % range of carry and total, of the landing and final lateral
    positions, the 95 % ellipse and the target."""
    dx, dy = _ellipse_extent(
        row["ellipse95_semi_major_m"], row["ellipse95_semi_minor_m"], row["ellipse95_angle_deg"]
    )
    mx, my = row["final_x_m_mean"], row["final_y_m_mean"]
    x = [row.get(f"{q}_{p}") for q in ("carry_m", "total_m") for p in ("p01", "p99")]
    y = [row.get(f"{q}_{p}") for q in ("carry_lateral_m", "final_y_m") for p in ("p01", "p99")]
    x += [mx - dx, mx + dx, row["target_x_m"]]
    y += [my - dy, my + dy, row["target_y_m"]]
    return _span(x, POSITION_PAD), _span(y, POSITION_PAD)


class PointShots:
    """What the plots need of one point's ok shots, accumulated batch by batch.

    ``hist[q]`` counts of carry_m, run_m and total_m on ``edges[q]`` (``outside[q]``: shots
    beyond); ``density`` 2-D counts of the landing and final positions on ``position_edges``
    (downrange, lateral); ``dots`` every position when the point has at most ``scatter_max``
    ok shots; ``moments`` co-moments of the landing and final positions.
    """

    def __init__(self, row, scatter_max=SCATTER_MAX_SHOTS):
        self.n_ok = 0
        self.n_failed = 0
        self.edges = {}
        for name, _ in DISTANCES:
            lo, hi = _span([row.get(f"{name}_p01"), row.get(f"{name}_p99")])
            self.edges[name] = np.linspace(lo, hi, HISTOGRAM_BINS + 1)
        self.hist = {name: np.zeros(HISTOGRAM_BINS, dtype=np.int64) for name, _ in DISTANCES}
        self.outside = dict.fromkeys(self.hist, 0)
        xlim, ylim = position_limits(row)
        bins = int(np.clip(round(math.sqrt(max(int(row["n_ok"]), 0)) / 2.0), *DENSITY_BINS))
        self.position_edges = (np.linspace(*xlim, bins + 1), np.linspace(*ylim, bins + 1))
        self.scatter = int(row["n_ok"]) <= scatter_max
        self.density = {k: np.zeros((bins, bins)) for k in ("landing", "final")}
        self.dots = {"landing": [], "final": []}
        self.beyond = {"landing": 0, "final": 0}  # ok shots outside the position bins
        self.moments = {"landing": stats.Comoments(2), "final": stats.Comoments(2)}

    def update(self, batch):
        ok = batch["status"] == status_codes.OK
        self.n_failed += int((~ok).sum())
        self.n_ok += int(ok.sum())
        for name in self.hist:
            values = batch[name][ok]
            counts, _ = np.histogram(values, bins=self.edges[name])
            self.hist[name] += counts
            self.outside[name] += len(values) - int(counts.sum())
        positions = {
            "landing": (batch["carry_m"][ok], batch["carry_lateral_m"][ok]),
            "final": (batch["final_x_m"][ok], batch["final_y_m"][ok]),
        }
        (x0, *_, x1), (y0, *_, y1) = self.position_edges
        for key, (x, y) in positions.items():
            self.beyond[key] += int(np.count_nonzero((x < x0) | (x > x1) | (y < y0) | (y > y1)))
            self.moments[key].update(np.column_stack([x, y]))
            if self.scatter:
                self.dots[key].append(np.column_stack([x, y]))
            else:
                counts, _, _ = np.histogram2d(x, y, bins=self.position_edges)
                self.density[key] += counts

    def positions(self, key):
        """(n, 2) downrange and lateral positions (dots only)."""
        parts = self.dots[key]
        return np.concatenate(parts) if parts else np.empty((0, 2))

    def ellipse(self, key, level):
        """(semi-major, semi-minor, angle deg) of the ``level`` % ellipse, ``stats.ellipse``."""
        m = self.moments[key]
        if m.n < 2:
            return math.nan, math.nan, math.nan
        c = m.covariance()
        return stats.ellipse(c[0, 0], c[0, 1], c[1, 1], level)[:3]


def read_point_shots(run, point, scatter_max=SCATTER_MAX_SHOTS):
    """PointShots of ``point`` (one pass over its row groups, the plotted columns only)."""
    row = run.summary.loc[run.summary["point"] == point].iloc[0].to_dict()
    shots = PointShots(row, scatter_max)
    for batch in run.folder.shot_batches(point, _SHOT_COLUMNS, BATCH_ROWS):
        shots.update(batch)
    return shots


def sample_trajectories(run, point, limit=TRAJECTORIES_PER_POINT):
    """The paths of the first ``limit`` shots of ``point`` in trajectories.parquet: a list of
    (shot, x, y, z, phase names) arrays, in the file's order (shot index)."""
    paths = {}
    done = False
    for batch in run.folder.trajectory_batches(point, _TRAJECTORY_COLUMNS, BATCH_ROWS):
        shot = batch["shot"]
        _, first = np.unique(shot, return_index=True)
        keep = np.zeros(len(shot), dtype=bool)
        for start in np.sort(first):
            s = int(shot[start])
            if s not in paths:
                if len(paths) == limit:
                    done = True
                    break
                paths[s] = []
            keep |= shot == s
        for s in np.unique(shot[keep]):
            rows = shot == s
            paths[int(s)].append(
                np.column_stack([batch["x_m"][rows], batch["y_m"][rows], batch["z_m"][rows]])
            )
            paths[int(s)].append(batch["phase"][rows])
        if done:
            break
    out = []
    for s, parts in paths.items():
        xyz = np.concatenate(parts[0::2])
        phase = np.concatenate(parts[1::2])
        out.append((s, xyz[:, 0], xyz[:, 1], xyz[:, 2], phase))
    return out


# --- drawing -----------------------------------------------------------------------------------


def require_matplotlib(command="plot"):
    """Figure and the Agg canvas; PlotError with the one-line message when matplotlib is
    missing."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError:
        raise PlotError(MISSING_MATPLOTLIB.format(command)) from None
    return Figure, FigureCanvasAgg


def _fmt(value, spec=".1f", unit=""):
    """``value`` formatted, "-" when missing; never "-0.0"."""
    if value is None or not math.isfinite(float(value)):
        return "-"
    text = format(float(value), spec)
    if text.startswith("-") and float(text) == 0.0:
        text = text[1:]
    return text + unit


def _short_label(run, row):
    """A point's label without the key paths: "Driver", "5 m/s, 45 deg"."""
    parts = [row["group"]] if row.get("group") else []
    parts += [str(row[k]) for k in run.sweep_keys]
    return ", ".join(parts) or row.get("label") or f"point {row['point']}"


def _figure(kind, run, what, row=None):
    """A Figure of ``FIGURE_SIZES_IN[kind]`` titled with the run: scenario, what the plot
    shows, the question, N and seed (and the point)."""
    figure_class, canvas_class = require_matplotlib()
    width, height = FIGURE_SIZES_IN[kind]
    fig = figure_class(figsize=(width, height), layout="constrained")
    canvas_class(fig)
    chars = int(width * 72.0 / (10.0 * 0.55))
    lines = [f"{run.name}: {what}"]
    if run.question:
        lines += textwrap.wrap(run.question, chars)
    facts = []
    if run.n is not None:
        facts.append(f"N = {int(run.n):,} shots per point")
    if run.seed is not None:
        facts.append(f"seed {run.seed}")
    if row is not None and run.points > 1:
        facts.append(f"point {int(row['point'])}: {row['label']}")
    lines.append(", ".join(facts))
    fig.suptitle("\n".join(lines), fontsize=10.5)
    return fig


def _note(ax, text, loc="upper left"):
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


def _draw_ellipse(ax, centre_x, centre_y, a, b, angle_deg, level, colour="black"):
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


def _fit_equal(fig, axes):
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


def _colour(k, n):
    """The colour of the k-th of n points or series: matplotlib's ten, or twenty above ten."""
    if n <= 10:
        return f"C{k % 10}"
    from matplotlib import colormaps

    return colormaps["tab20"](k % 20)


def _legend_line(**kwargs):
    from matplotlib.lines import Line2D

    return Line2D([], [], **kwargs)


def positions_figure(run, row, shots):
    """Landing and final positions, their 68/95 % ellipses and the target (one point)."""
    fig = _figure("positions", run, "where the balls land and finish, seen from above", row)
    axes = fig.subplots(1, 2, sharex=True, sharey=True)
    xedges, yedges = shots.position_edges
    mesh = None
    if not shots.scatter:
        vmax = max(float(shots.density[k].max()) for k in shots.density) or 1.0
    for ax, key in zip(axes, ("landing", "final"), strict=True):
        colour = FLIGHT_COLOUR if key == "landing" else RUN_COLOUR
        if shots.scatter:
            xy = shots.positions(key)
            many = len(xy) > 1000
            ax.scatter(
                xy[:, 1],
                xy[:, 0],
                s=4 if many else 9,
                color=colour,
                alpha=0.35 if many else 0.6,
                lw=0,
                rasterized=True,
            )
        else:
            counts = np.ma.masked_equal(shots.density[key], 0.0)
            mesh = ax.pcolormesh(
                yedges, xedges, counts, cmap="viridis", vmin=0.0, vmax=vmax, rasterized=True
            )
        if key == "final":
            ellipses = {
                level: (
                    row[f"ellipse{level}_semi_major_m"],
                    row[f"ellipse{level}_semi_minor_m"],
                    row[f"ellipse{level}_angle_deg"],
                )
                for level in stats.ELLIPSE_LEVELS
            }
            centre = (row["final_x_m_mean"], row["final_y_m_mean"])
            ax.plot(
                row["target_y_m"],
                row["target_x_m"],
                marker="*",
                ms=15,
                color=TARGET_COLOUR,
                mec="white",
                mew=0.8,
                ls="none",
                zorder=8,
            )
        else:
            ellipses = {level: shots.ellipse("landing", level) for level in stats.ELLIPSE_LEVELS}
            moments = shots.moments["landing"]
            centre = tuple(moments.mean) if moments.n else (math.nan, math.nan)
        for level, (a, b, angle) in ellipses.items():
            _draw_ellipse(ax, centre[0], centre[1], a, b, angle, level)
        ax.plot(centre[1], centre[0], "+", color="black", ms=11, mew=1.6, zorder=7)
        ax.axvline(0.0, color="0.4", lw=0.8, ls=":", zorder=1)
        ax.set_xlim(yedges[0], yedges[-1])
        ax.set_ylim(xedges[0], xedges[-1])
        ax.set_xlabel("lateral (m), + right of the target line")
        ax.grid(alpha=0.25)
    a95, b95, _ = shots.ellipse("landing", 95)
    axes[0].set_title(
        "(a) landing: where the ball first meets the ground\n"
        f"carry {_fmt(row['carry_m_mean'])} ± {_fmt(row['carry_m_std'])} m, lateral "
        f"{_fmt(row['carry_lateral_m_mean'])} ± {_fmt(row['carry_lateral_m_std'])} m\n"
        f"95 % ellipse {_fmt(a95)} x {_fmt(b95)} m",
        fontsize=9.5,
    )
    axes[1].set_title(
        "(b) at rest, after the bounces and the roll\n"
        f"total {_fmt(row['total_m_mean'])} ± {_fmt(row['total_m_std'])} m, lateral "
        f"{_fmt(row['final_y_m_mean'])} ± {_fmt(row['final_y_m_std'])} m\n"
        f"95 % ellipse {_fmt(row['ellipse95_semi_major_m'])} x "
        f"{_fmt(row['ellipse95_semi_minor_m'])} m at {_fmt(row['ellipse95_angle_deg'], '.0f')} "
        f"deg\n95 % of the finishes within {_fmt(row['distance_r95_m'])} m of the target",
        fontsize=9.5,
    )
    axes[0].set_ylabel("downrange (m), along the target line")
    if shots.scatter:
        handles = [
            _legend_line(
                marker="o",
                ls="none",
                color=FLIGHT_COLOUR,
                label=f"landing (all {shots.n_ok:,} ok shots)",
            ),
            _legend_line(marker="o", ls="none", color=RUN_COLOUR, label="at rest"),
        ]
    else:
        handles = []
    handles += [
        _legend_line(color="black", ls="--", lw=1.2, label="68 % ellipse"),
        _legend_line(color="black", ls="-", lw=1.6, label="95 % ellipse"),
        _legend_line(color="black", marker="+", ms=11, mew=1.6, ls="none", label="mean"),
        _legend_line(color="0.4", ls=":", lw=0.8, label="target line"),
        _legend_line(
            color=TARGET_COLOUR,
            marker="*",
            ms=13,
            mec="white",
            ls="none",
            label="target" if run.explicit_target else "target (the mean finish)",
        ),
    ]
    beyond = max(shots.beyond.values())
    if beyond and not shots.scatter:
        handles.append(
            _legend_line(ls="none", label=f"({beyond:,} shots beyond the binned area, not drawn)")
        )
    if shots.n_failed:
        handles.append(_legend_line(ls="none", label=f"({shots.n_failed:,} failed shots left out)"))
    fig.legend(
        handles=handles, loc="outside lower center", ncols=len(handles), fontsize=8.5, frameon=False
    )
    if mesh is not None:
        bin_x = xedges[1] - xedges[0]
        bin_y = yedges[1] - yedges[0]
        fig.colorbar(
            mesh,
            ax=list(axes),
            shrink=0.85,
            label=f"shots per {bin_y:.2g} m x {bin_x:.2g} m bin (all {shots.n_ok:,} ok shots)",
        )
    _fit_equal(fig, axes)
    return fig


def distances_figure(run, row, shots):
    """Histograms of carry, run and total (one point)."""
    fig = _figure("distances", run, "carry, run and total", row)
    axes = fig.subplots(1, len(DISTANCES))
    for ax, (name, title) in zip(axes, DISTANCES, strict=True):
        edges = shots.edges[name]
        share = 100.0 * shots.hist[name] / max(shots.n_ok, 1)
        colour = RUN_COLOUR if name != "carry_m" else FLIGHT_COLOUR
        ax.stairs(share, edges, fill=True, color=colour, alpha=0.75, label="ok shots")
        mean = row[f"{name}_mean"]
        if math.isfinite(mean):
            ax.axvline(mean, color="black", lw=1.5, label=f"mean {_fmt(mean)} m")
        p05, p95 = row[f"{name}_p05"], row[f"{name}_p95"]
        if math.isfinite(p05):
            ax.axvline(
                p05, color="black", lw=1.0, ls="--", label=f"5 %, 95 %: {_fmt(p05)}, {_fmt(p95)} m"
            )
            ax.axvline(p95, color="black", lw=1.0, ls="--")
        ax.set_xlabel(f"{title} (m)")
        ax.set_ylabel(f"shots per {edges[1] - edges[0]:.2g} m bin (%)")
        heading = f"{title}: sd {_fmt(row[f'{name}_std'], '.2f')} m"
        if shots.outside[name]:
            heading += f"\n({shots.outside[name]:,} shots beyond the axis not shown)"
        ax.set_title(heading, fontsize=10)
        ax.set_xlim(edges[0], edges[-1])
        ax.set_ylim(0.0, 1.3 * max(float(share.max()), 1e-9))
        top = ax.secondary_xaxis("top", functions=(lambda m: m / YARD_M, lambda yd: yd * YARD_M))
        top.set_xlabel("yd", fontsize=8)
        top.tick_params(labelsize=8)
        ax.grid(alpha=0.25)
        ax.legend(fontsize=8, loc="upper left", framealpha=0.85)
    return fig


def trajectories_figure(run, row, paths):
    """Side and top views of the sampled trajectories (one point)."""
    fig = _figure("trajectories", run, "sampled trajectories", row)
    side, top = fig.subplots(2, 1, sharex=True, height_ratios=(1.0, 1.0))
    for _, x, y, z, phase in paths:
        flight = np.flatnonzero(phase == "flight")
        land = int(flight[-1]) if len(flight) else 0
        for ax, h in ((side, z), (top, y)):
            ax.plot(x[: land + 1], h[: land + 1], color=FLIGHT_COLOUR, lw=0.7, alpha=0.5)
            ax.plot(x[land:], h[land:], color=RUN_COLOUR, lw=0.9, alpha=0.7)
            ax.plot(x[-1], h[-1], ".", color="black", ms=2.5)
    every = run.provenance.get("trajectories_every")
    shown = f"{len(paths)} paths: the first {len(paths)} in trajectories.parquet"
    if every:
        shown += f" (every {every}th shot)"
    side.plot([], [], color=FLIGHT_COLOUR, label="flight")
    side.plot([], [], color=RUN_COLOUR, label="bounces and roll")
    side.plot([], [], ".", color="black", label="at rest")
    side.legend(loc="upper left", fontsize=8.5, title=shown, title_fontsize=8.5)
    side.set_title("side view", fontsize=10, loc="left")
    side.set_ylabel("height (m)")
    side.set_ylim(bottom=min(0.0, side.get_ylim()[0]))
    side.axhline(0.0, color="#a08660", lw=1.5, zorder=0)
    top.set_title(
        "top view, seen from above with the target to the right: a ball that goes right "
        "of the target line is drawn below it",
        fontsize=10,
        loc="left",
    )
    top.axhline(0.0, color="0.4", lw=0.8, ls=":")
    top.invert_yaxis()
    top.set_ylabel("lateral (m), + right (down)")
    for y, word in ((0.97, "left of the target line"), (0.03, "right of the target line")):
        top.text(
            0.005,
            y,
            word,
            transform=top.transAxes,
            fontsize=8,
            color="0.35",
            va="top" if y > 0.5 else "bottom",
        )
    top.set_xlabel("downrange (m), along the target line")
    for ax in (side, top):
        ax.grid(alpha=0.25)
    _note(
        side,
        f"apex {_fmt(row['apex_m_mean'])} m, carry {_fmt(row['carry_m_mean'])} m, "
        f"total {_fmt(row['total_m_mean'])} m (means of all ok shots)",
        loc="upper right",
    )
    return fig


# --- several points ----------------------------------------------------------------------------

_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d\s].*)?$")


def _numeric(values):
    """(floats, unit) when every value is a number with the same unit (or none), else None."""
    numbers, units = [], set()
    for v in values:
        if isinstance(v, int | float | np.integer | np.floating) and not isinstance(v, bool):
            numbers.append(float(v))
            units.add("")
            continue
        match = _QUANTITY.match(str(v))
        if not match:
            return None
        numbers.append(float(match[1]))
        units.add((match[2] or "").strip())
    if len(units) != 1:
        return None
    return np.array(numbers), units.pop()


def sweep_layout(run):
    """How the summary plot lays out the points: (x label, x value per point (float) or None,
    tick labels per point, series: [(label, [row positions])]).

    x is the swept parameter with the most values (a number with its unit where it can be),
    else the group; every other swept parameter and the group make the series.
    """
    summary = run.summary
    keys = list(run.sweep_keys)
    groups = [str(g) for g in summary["group"]]
    if not keys:
        return "group", None, groups, [("", list(range(len(summary))))]
    parsed = {k: _numeric(list(summary[k])) for k in keys}
    distinct = {k: len(set(map(str, summary[k]))) for k in keys}
    x_key = max(keys, key=lambda k: (distinct[k], parsed[k] is not None))
    others = [k for k in keys if k != x_key]
    if parsed[x_key] is not None:
        values, unit = parsed[x_key]
        x_label = f"{x_key} ({unit})" if unit else x_key
    else:
        values, x_label = None, x_key
    ticks = [str(v) for v in summary[x_key]]
    series = {}
    for i, row in enumerate(summary.to_dict("records")):
        parts = [row["group"]] if row["group"] else []
        parts += [f"{k}={row[k]}" for k in others]
        series.setdefault(", ".join(parts), []).append(i)
    return x_label, values, ticks, list(series.items())


# (title, [(column, marker, colour of a single series, legend label)], y label); the columns of
# a distance are drawn as the mean with bars from p05 to p95.
_SUMMARY_PANELS = (
    (
        "(a) carry and total: mean, 5-95 % bars",
        (("carry_m", "o", FLIGHT_COLOUR, "carry"), ("total_m", "s", RUN_COLOUR, "total")),
        "distance along the target line (m)",
    ),
    (
        "(b) run, landing to rest: mean, 5-95 % bars",
        (("run_m", "o", RUN_COLOUR, "run"),),
        "run (m)",
    ),
    (
        "(c) finish across the target line: mean, 5-95 % bars",
        (("final_y_m", "o", RUN_COLOUR, "lateral at rest"),),
        "lateral at rest (m), + right",
    ),
    (
        "(d) 95 % ellipse of the finish",
        (
            ("ellipse95_semi_major_m", "o", "#2ca02c", "semi-major"),
            ("ellipse95_semi_minor_m", "v", "#9467bd", "semi-minor"),
        ),
        "semi-axis (m)",
    ),
)


def summary_figure(run):
    """The summary statistics against the swept parameter, or per group."""
    x_label, values, ticks, series = sweep_layout(run)
    what = "summary per group" if x_label == "group" else f"summary against {x_label}"
    fig = _figure("summary", run, what)
    axes = fig.subplots(2, 2, sharex=True).ravel()
    summary = run.summary
    categorical = values is None
    if categorical:
        order = list(dict.fromkeys(ticks))
        x = np.array([order.index(t) for t in ticks], dtype=float)
        step = 1.0
    else:
        x = values
        distinct = np.unique(x)
        step = float(np.min(np.diff(distinct))) if len(distinct) > 1 else 1.0
    single = len(series) == 1
    for ax, (title, quantities, ylabel) in zip(axes, _SUMMARY_PANELS, strict=True):
        slots = len(series) * len(quantities)
        width = 0.5 * step / slots if slots > 1 else 0.0
        for k, (_, rows) in enumerate(series):
            rows = sorted(rows, key=lambda i: x[i])
            for j, (q, marker, colour, _) in enumerate(quantities):
                slot = k * len(quantities) + j
                xs = x[rows] + (slot - 0.5 * (slots - 1)) * width
                column = q if q.startswith("ellipse") else f"{q}_mean"
                y = summary[column].to_numpy(dtype=float)[rows]
                error = None
                if not q.startswith("ellipse"):
                    lo = summary[f"{q}_p05"].to_numpy(dtype=float)[rows]
                    hi = summary[f"{q}_p95"].to_numpy(dtype=float)[rows]
                    # max(0, .): a point whose shots are all alike has its mean and
                    # percentiles equal only to rounding
                    error = np.maximum(np.vstack([y - lo, hi - y]), 0.0)
                ax.errorbar(
                    xs,
                    y,
                    yerr=error,
                    fmt=marker,
                    ls="none" if categorical else "-",
                    lw=1.0,
                    ms=5,
                    capsize=3,
                    color=colour if single else _colour(k, len(series)),
                )
        if len(quantities) > 1:
            ax.legend(
                handles=[
                    _legend_line(marker=m, ls="none", color=c if single else "black", label=n)
                    for _, m, c, n in quantities
                ],
                fontsize=8,
                framealpha=0.85,
            )
        ax.set_title(title, fontsize=10, loc="left")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.25)
    axes[2].axhline(0.0, color="0.4", lw=0.8, ls=":")
    if not single:
        fig.legend(
            handles=[
                _legend_line(color=_colour(k, len(series)), marker="o", label=label)
                for k, (label, _) in enumerate(series)
            ],
            loc="outside lower center",
            ncols=min(len(series), 4),
            fontsize=8.5,
            frameon=False,
        )
    for ax in axes[2:]:
        ax.set_xlabel(x_label)
    if categorical:
        many = len(order) > 4
        for ax in axes[2:]:
            ax.set_xticks(
                range(len(order)),
                order,
                rotation=30 if many else 0,
                ha="right" if many else "center",
            )
        axes[0].set_xlim(-0.6, len(order) - 0.4)
    return fig


def finish_figure(run):
    """Mean finish and 95 % ellipse of every point on one top view, labelled in a column on
    the right."""
    fig = _figure("finish", run, "where each point finishes: mean and 95 % ellipse")
    ax = fig.subplots()
    xs, ys, marks = [], [], []
    for k, row in enumerate(run.summary.to_dict("records")):
        colour = _colour(k, run.points)
        mx, my = row["final_x_m_mean"], row["final_y_m_mean"]
        if not (math.isfinite(mx) and math.isfinite(my)):
            continue
        a, b, angle = (row[f"ellipse95_{f}"] for f in ("semi_major_m", "semi_minor_m", "angle_deg"))
        _draw_ellipse(ax, mx, my, a, b, angle, 95, colour=colour)
        dx, dy = _ellipse_extent(a, b, angle)
        xs += [mx - dx, mx + dx]
        ys += [my - dy, my + dy]
        ax.plot(my, mx, "+", color=colour, ms=8, mew=1.5)
        marks.append((mx, my, colour, f"{row['point']}: {_short_label(run, row)}"))
        if run.explicit_target:
            ax.plot(
                row["target_y_m"],
                row["target_x_m"],
                "*",
                color=TARGET_COLOUR,
                ms=10,
                mec="white",
                mew=0.6,
                zorder=8,
            )
            xs.append(row["target_x_m"])
            ys.append(row["target_y_m"])
    ylo, yhi = _span(ys, pad=0.1)
    xlo, xhi = _span(xs, pad=0.05)
    ax.axvline(0.0, color="0.4", lw=0.8, ls=":")
    ax.set_xlim(ylo, yhi + 0.45 * (yhi - ylo))  # room for the labels on the right
    ax.set_ylim(xlo, xhi)
    ax.set_xlabel("lateral (m), + right of the target line")
    ax.set_ylabel("downrange (m), along the target line")
    ax.grid(alpha=0.25)
    title = "+ mean finish of each point, its 95 % ellipse (summary.parquet)"
    if run.explicit_target:
        title += "; * target"
    ax.set_title(title, fontsize=10)
    _fit_equal(fig, [ax])
    # The labels: one column right of every ellipse, in downrange order, at least a line apart.
    box = ax.get_position()
    metres_per_inch = (ax.get_ylim()[1] - ax.get_ylim()[0]) / (box.height * fig.get_figheight())
    gap = 0.15 * metres_per_inch
    column = yhi + 0.03 * (yhi - ylo)
    placed = []
    for mx, my, colour, text in sorted(marks, key=lambda m: m[0]):
        y = mx if not placed else max(mx, placed[-1] + gap)
        placed.append(y)
        ax.annotate(
            text,
            (my, mx),
            xytext=(column, y),
            textcoords="data",
            fontsize=7.5,
            color=colour,
            va="center",
            arrowprops={"arrowstyle": "-", "color": colour, "lw": 0.5, "alpha": 0.6},
        )
    return fig


# --- the set of plots --------------------------------------------------------------------------


def _point_name(run, point):
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
        stem = _point_name(run, point)
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
                    f"{label}side and top views of {len(paths)} sampled trajectories (the "
                    "first in trajectories.parquet).",
                    trajectories_figure(run, row, paths),
                )


def png_bytes(fig, dpi):
    """The PNG of a Figure at ``dpi``: its size in inches times the dpi, in pixels."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    return buffer.getvalue()


def _writable_folder(out_dir):
    out_dir = Path(out_dir)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        probe = out_dir / ".mcrun-write-test"
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as err:
        if exits.is_name_too_long(err):
            raise  # the command line's one line for every path too long
        raise PlotError(f"-o: cannot write to {out_dir}: {reader.reason_of(err)}") from None
    return out_dir


def write_plots(
    run_dir, out_dir=None, dpi=DEFAULT_PLOT_DPI, scatter_max=SCATTER_MAX_SHOTS, point_figures=None
):
    """Write the PNGs of a run folder into ``out_dir`` (default RUN_DIR/plots); return
    [(path, caption)]. ``point_figures``: as ``figures``."""
    run = open_run(run_dir)
    require_matplotlib()
    out_dir = _writable_folder(run.beside(PLOTS_FOLDER) if out_dir is None else out_dir)
    written = []
    for stem, caption, fig in figures(run, scatter_max, point_figures=point_figures):
        path = out_dir / f"{stem}.png"
        try:
            path.write_bytes(png_bytes(fig, dpi))
        except OSError as err:
            raise PlotError(f"cannot write {path}: {reader.reason_of(err)}") from None
        written.append((path, caption))
    return written


# --- command line ------------------------------------------------------------------------------
