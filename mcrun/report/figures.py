"""The figures of a run: per point, its positions seen from above, its distances and its
sampled trajectories; for several points, the summary against the swept parameter or per group
and every point's finish on one top view. Each takes what ``mcrun.report.run_view`` read and
returns a matplotlib Figure.
"""

import math
import re

import numpy as np

from mcrun.errors import InputError
from mcrun.report.run_view import DISTANCES, ellipse_extent, span
from mcrun.report.style import (
    FLIGHT_COLOUR,
    RUN_COLOUR,
    TARGET_COLOUR,
    YARD_M,
    colour_of,
    draw_ellipse,
    fit_equal,
    fmt,
    legend_line,
    new_figure,
    note,
    short_label,
)
from mcrun.results import stats
from mcrun.units import KINDS, parse_quantity, to_unit

# --- one point ---------------------------------------------------------------------------------


def positions_figure(run, row, shots):
    """Landing and final positions, their 68/95 % ellipses and the target (one point)."""
    fig = new_figure("positions", run, "where the balls land and finish, seen from above", row)
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
            draw_ellipse(ax, centre[0], centre[1], a, b, angle, level)
        ax.plot(centre[1], centre[0], "+", color="black", ms=11, mew=1.6, zorder=7)
        ax.axvline(0.0, color="0.4", lw=0.8, ls=":", zorder=1)
        ax.set_xlim(yedges[0], yedges[-1])
        ax.set_ylim(xedges[0], xedges[-1])
        ax.set_xlabel("lateral (m), + right of the target line")
        ax.grid(alpha=0.25)
    a95, b95, _ = shots.ellipse("landing", 95)
    axes[0].set_title(
        "(a) landing: where the ball first meets the ground\n"
        f"carry {fmt(row['carry_m_mean'])} ± {fmt(row['carry_m_std'])} m, lateral "
        f"{fmt(row['carry_lateral_m_mean'])} ± {fmt(row['carry_lateral_m_std'])} m\n"
        f"95 % ellipse {fmt(a95)} x {fmt(b95)} m",
        fontsize=9.5,
    )
    axes[1].set_title(
        "(b) at rest, after the bounces and the roll\n"
        f"total {fmt(row['total_m_mean'])} ± {fmt(row['total_m_std'])} m, lateral "
        f"{fmt(row['final_y_m_mean'])} ± {fmt(row['final_y_m_std'])} m\n"
        f"95 % ellipse {fmt(row['ellipse95_semi_major_m'])} x "
        f"{fmt(row['ellipse95_semi_minor_m'])} m at {fmt(row['ellipse95_angle_deg'], '.0f')} "
        f"deg\n95 % of the finishes within {fmt(row['distance_r95_m'])} m of the target",
        fontsize=9.5,
    )
    axes[0].set_ylabel("downrange (m), along the target line")
    if shots.scatter:
        handles = [
            legend_line(
                marker="o",
                ls="none",
                color=FLIGHT_COLOUR,
                label=f"landing (all {shots.n_ok:,} ok shots)",
            ),
            legend_line(marker="o", ls="none", color=RUN_COLOUR, label="at rest"),
        ]
    else:
        handles = []
    handles += [
        legend_line(color="black", ls="--", lw=1.2, label="68 % ellipse"),
        legend_line(color="black", ls="-", lw=1.6, label="95 % ellipse"),
        legend_line(color="black", marker="+", ms=11, mew=1.6, ls="none", label="mean"),
        legend_line(color="0.4", ls=":", lw=0.8, label="target line"),
        legend_line(
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
            legend_line(ls="none", label=f"({beyond:,} shots beyond the binned area, not drawn)")
        )
    if shots.n_failed:
        handles.append(legend_line(ls="none", label=f"({shots.n_failed:,} failed shots left out)"))
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
    fit_equal(fig, axes)
    return fig


def distances_figure(run, row, shots):
    """Histograms of carry, run and total (one point)."""
    fig = new_figure("distances", run, "carry, run and total", row)
    axes = fig.subplots(1, len(DISTANCES))
    for ax, (name, title) in zip(axes, DISTANCES, strict=True):
        edges = shots.edges[name]
        share = 100.0 * shots.hist[name] / max(shots.n_ok, 1)
        colour = RUN_COLOUR if name != "carry_m" else FLIGHT_COLOUR
        ax.stairs(share, edges, fill=True, color=colour, alpha=0.75, label="ok shots")
        mean = row[f"{name}_mean"]
        if math.isfinite(mean):
            ax.axvline(mean, color="black", lw=1.5, label=f"mean {fmt(mean)} m")
        p05, p95 = row[f"{name}_p05"], row[f"{name}_p95"]
        if math.isfinite(p05):
            ax.axvline(
                p05, color="black", lw=1.0, ls="--", label=f"5 %, 95 %: {fmt(p05)}, {fmt(p95)} m"
            )
            ax.axvline(p95, color="black", lw=1.0, ls="--")
        ax.set_xlabel(f"{title} (m)")
        ax.set_ylabel(f"shots per {edges[1] - edges[0]:.2g} m bin (%)")
        heading = f"{title}: sd {fmt(row[f'{name}_std'], '.2f')} m"
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
    fig = new_figure("trajectories", run, "sampled trajectories", row)
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
    note(
        side,
        f"apex {fmt(row['apex_m_mean'])} m, carry {fmt(row['carry_m_mean'])} m, "
        f"total {fmt(row['total_m_mean'])} m (means of all ok shots)",
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
    if len(units) == 1:
        return np.array(numbers), units.pop()
    if "" in units:  # (a bare number beside numbers with units: its unit unknown)
        return None
    # Units of one kind (["0 mph", "10 mph", "5 m/s"]): each in the first value's unit, in
    # order (drawn as categories in the order given, 5 m/s was drawn after 10 mph).
    first = (_QUANTITY.match(str(values[0]))[2] or "").strip()
    for kind in KINDS:
        try:
            si = [parse_quantity(str(v), kind) for v in values]
            return np.array([to_unit(x, kind, first) for x in si]), first
        except InputError:
            continue
    return None


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
    fig = new_figure("summary", run, what)
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
                    color=colour if single else colour_of(k, len(series)),
                )
        if len(quantities) > 1:
            ax.legend(
                handles=[
                    legend_line(marker=m, ls="none", color=c if single else "black", label=n)
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
                legend_line(color=colour_of(k, len(series)), marker="o", label=label)
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
    fig = new_figure("finish", run, "where each point finishes: mean and 95 % ellipse")
    ax = fig.subplots()
    xs, ys, marks = [], [], []
    for k, row in enumerate(run.summary.to_dict("records")):
        colour = colour_of(k, run.points)
        mx, my = row["final_x_m_mean"], row["final_y_m_mean"]
        if not (math.isfinite(mx) and math.isfinite(my)):
            continue
        a, b, angle = (row[f"ellipse95_{f}"] for f in ("semi_major_m", "semi_minor_m", "angle_deg"))
        draw_ellipse(ax, mx, my, a, b, angle, 95, colour=colour)
        dx, dy = ellipse_extent(a, b, angle)
        xs += [mx - dx, mx + dx]
        ys += [my - dy, my + dy]
        ax.plot(my, mx, "+", color=colour, ms=8, mew=1.5)
        marks.append((mx, my, colour, f"{row['point']}: {short_label(run, row)}"))
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
    ylo, yhi = span(ys, pad=0.1)
    xlo, xhi = span(xs, pad=0.05)
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
    fit_equal(fig, [ax])
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
