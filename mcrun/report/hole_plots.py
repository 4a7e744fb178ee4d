"""The pictures of a run on a hole: the hole map with the shots over it, and the zone shares.

A run on a hole (a scenario with ``[hole]``) writes each shot's zones and each point's zone
shares (``p_finish_<zone>``, ``p_landing_<zone>`` with their 95 % Wilson intervals) in its
summary. ``mcrun plot`` and ``mcrun report`` draw, per point, ``pointNN-hole.png``: the hole
map (``hole_map.draw_hole``: the zones, the contours, the tee and the pin, the map's
attribution) zoomed on the shots and the green, with

- the landing and finish positions of a fixed, deterministic sample: the first
  ``HOLE_DOTS_PER_POINT`` shots of the point that reached the ground (the shots are
  independent draws, so the first ones are a sample of them all); a shot that ended in a
  penalty area, out of bounds or off the map is drawn where it ended, as a cross;
- zoomed on the sample (1 % to 99 % of its positions, every shot that ended), the 95 %
  ellipse, the green that holds the pin and the pin, plus a margin;
- the 50 % and 95 % ellipses of the finish (``stats.ellipse`` of summary.parquet's covariance
  of the ok shots' finish, about their mean: the 95 % one is the summary's ``ellipse95_*``);
- the pin, the aim line from the tee, and the target when it is not the pin;
- beside the map, the share of the shots that finish and land in each zone, with the 95 %
  interval (summary.parquet).

The map, the pin and each point's aim are what the run recorded (``RunFolder.hole_map`` and
``RunFolder.geometry``, ``mcrun.results.geometry``): the scenario and the hole's map and
elevation files are not read again, and may have moved. A run written before runs recorded
their geometry is still drawn, without the map, and says so (``NO_MAP``).
"""

import math

import numpy as np

from mcrun import status as status_codes
from mcrun.hole.osm import ATTRIBUTION
from mcrun.report import style
from mcrun.report.run_view import BATCH_ROWS, SCATTER_MAX_SHOTS, ellipse_extent, span
from mcrun.results import stats
from mcrun.results.on_hole import ZONE_NAMES

HOLE_DOTS_PER_POINT = SCATTER_MAX_SHOTS
HOLE_ELLIPSE_LEVELS = (50, 95)
ZOOM_PAD = 0.15  # share of the shots' and the green's span added on each side
ZOOM_MIN_PAD_M = 8.0
# The zones a shot can finish or land in, as summary.parquet names them.
_HOLE_SHOT_COLUMNS = (
    "point",
    "status",
    "carry_m",
    "carry_lateral_m",
    "final_x_m",
    "final_y_m",
)
ENDED_COLOUR = "#7a0000"
AIM_COLOUR = "#6a1b9a"
HOLE_LINE_COLOUR = "white"
# Why a run on a hole is drawn without its map.
NO_MAP = "the run records no hole map (it was written before runs recorded their geometry)"


def is_hole_run(run):
    """Whether the run was played on a hole (its summary has the zone shares)."""
    return "p_finish_green" in run.summary.columns and "finish_zone" in run.folder.shot_columns


def hole_of(run):
    """(hole map, None) of a hole run, as it recorded it (a ``geometry.HoleMap``), or (None,
    reason) when it records none."""
    hole_map = run.hole_map()
    return (hole_map, None) if hole_map is not None else (None, NO_MAP)


def aim_of(run, point):
    """The aim (rad, + right of the line to the pin) ``point`` was played with, as the run
    recorded it; None when it records none."""
    geometry = run.geometry
    return None if geometry is None else geometry.aim_rad(point)


def start_of(run, point):
    """Where ``point``'s shots were struck ((x, y) m in the hole's frame), as the run recorded
    it: the tee unless the point started elsewhere (and for a run that records no geometry)."""
    geometry = run.geometry
    return (0.0, 0.0) if geometry is None else geometry.start_xy(point)


def attribution_of(run):
    """The attribution of the run's map: the recorded hole's, else the OSM one when the
    scenario names a map (the zones come from it), else None."""
    hole_map, _ = hole_of(run)
    if hole_map is not None:
        return hole_map.facts.attribution
    text = run.provenance.get("scenario_text") or ""
    return ATTRIBUTION if "[hole]" in text else None


# --- the shares ---------------------------------------------------------------------------------


def zone_shares(row, where):
    """[(zone, share, lo95, hi95)] of ``where`` ("finish" or "landing") for every zone of the
    summary row, in ``ZONE_NAMES`` order."""
    out = []
    for zone in ZONE_NAMES:
        key = f"p_{where}_{zone}"
        if key in row:
            out.append((zone, row[key], row[f"{key}_lo95"], row[f"{key}_hi95"]))
    return out


def percent(value, spec=".1f"):
    """A share as a percentage ("70.8"), "-" when missing."""
    if value is None or not math.isfinite(float(value)):
        return "-"
    return format(100.0 * float(value) + 0.0, spec)


def interval(lo, hi, spec=".1f"):
    """A 95 % interval of shares as "68.8-72.8"."""
    return f"{percent(lo, spec)}-{percent(hi, spec)}"


# --- the shots ----------------------------------------------------------------------------------


def read_hole_shots(run, point, limit=HOLE_DOTS_PER_POINT):
    """The first ``limit`` shots of ``point`` that reached the ground: dict of arrays
    ``landing`` (n, 2), ``final`` (n, 2) (downrange, lateral; NaN rows where the shot has
    none) and ``status``."""
    parts = {"landing": [], "final": [], "status": []}
    taken = 0
    x0, y0 = start_of(run, point)  # carry is measured from there
    for batch in run.folder.shot_batches(point, _HOLE_SHOT_COLUMNS, BATCH_ROWS):
        landed = np.isfinite(batch["carry_m"]) & np.isfinite(batch["carry_lateral_m"])
        keep = np.flatnonzero(landed)[: limit - taken]
        landing = np.column_stack([batch["carry_m"] + x0, batch["carry_lateral_m"] + y0])
        parts["landing"].append(landing[keep])
        parts["final"].append(np.column_stack([batch["final_x_m"], batch["final_y_m"]])[keep])
        parts["status"].append(batch["status"][keep])
        taken += len(keep)
        if taken >= limit:
            break
    if not taken:
        return {"landing": np.empty((0, 2)), "final": np.empty((0, 2)), "status": np.empty(0)}
    return {k: np.concatenate(v) for k, v in parts.items()}


def finish_ellipses(row):
    """{level: (semi-major, semi-minor, angle deg)} of the finish, ``HOLE_ELLIPSE_LEVELS``,
    from the summary row's covariance of the ok shots' finish."""
    cov = (row.get("cov_xx_m2"), row.get("cov_xy_m2"), row.get("cov_yy_m2"))
    out = {}
    for level in HOLE_ELLIPSE_LEVELS:
        if int(row["n_ok"]) > 1 and all(v is not None and math.isfinite(v) for v in cov):
            out[level] = stats.ellipse(*cov, level)[:3]
        else:
            out[level] = (math.nan, math.nan, math.nan)
    return out


def hole_view(row, shots, hole):
    """((downrange lo, hi), (lateral lo, hi)) of the map: the sampled shots (1-99 %), the
    95 % ellipse, the green that holds the pin and the pin, plus a margin."""
    xs, ys = [], []
    for key in ("landing", "final"):
        xy = shots[key][np.isfinite(shots[key]).all(axis=1)]
        if len(xy):
            xs += list(np.percentile(xy[:, 0], (1, 99)))
            ys += list(np.percentile(xy[:, 1], (1, 99)))
    ended = np.isin(shots["status"], status_codes.HOLE_STATUSES)
    xy = shots["final"][ended]
    xy = xy[np.isfinite(xy).all(axis=1)]
    xs += list(xy[:, 0])  # every shot that ended in a penalty area, out of bounds, off the map
    ys += list(xy[:, 1])
    a, b, angle = (row[f"ellipse95_{f}"] for f in ("semi_major_m", "semi_minor_m", "angle_deg"))
    dx, dy = ellipse_extent(a, b, angle)
    mx, my = row["final_x_m_mean"], row["final_y_m_mean"]
    xs += [mx - dx, mx + dx, row["target_x_m"]]
    ys += [my - dy, my + dy, row["target_y_m"]]
    if hole is not None:
        xs.append(hole.pin_xy[0])
        ys.append(hole.pin_xy[1])
        box = hole.facts.green_box_m
        if box is not None:
            xs += [box[0], box[1]]
            ys += [box[2], box[3]]
    spans = []
    for values in (xs, ys):
        lo, hi = span(values, pad=0.0)
        pad = max(ZOOM_PAD * (hi - lo), ZOOM_MIN_PAD_M)
        spans.append((lo - pad, hi + pad))
    return tuple(spans)


# --- the figure ---------------------------------------------------------------------------------


def hole_figure(run, row, shots):
    """The hole map of one point with its landing and finish clouds, the 50 % and 95 %
    ellipses of the finish, the pin, the aim line and the zone shares."""
    hole, reason = hole_of(run)
    aim_rad = aim_of(run, int(row["point"]))
    x0, y0 = start_of(run, int(row["point"]))
    fig = style.new_figure("hole", run, "where the balls land and finish on the hole", row)
    ax, side = fig.subplots(1, 2, width_ratios=(2.1, 1.0))
    if hole is not None:
        from mcrun.report.hole_map import draw_hole

        draw_hole(hole, ax)
        legend = ax.get_legend()
        if legend is not None:
            legend.remove()
    else:
        ax.set_facecolor("0.96")
        ax.text(
            0.5,
            0.5,
            f"no map:\n{reason}",
            transform=ax.transAxes,
            ha="center",
            va="center",
            fontsize=8,
            color="0.3",
            wrap=True,
        )
        ax.set_xlabel("lateral (m), + right of the tee-pin line")
        ax.set_ylabel("downrange (m), from the tee towards the pin")
    (xlo, xhi), (ylo, yhi) = hole_view(row, shots, hole)
    ok = shots["status"] == status_codes.OK
    ended = np.isin(shots["status"], status_codes.HOLE_STATUSES)
    many = len(ok) > 1000
    size, alpha = (6, 0.6) if many else (10, 0.75)
    landing, final = shots["landing"], shots["final"]
    ax.scatter(
        landing[:, 1],
        landing[:, 0],
        s=size,
        color=style.FLIGHT_COLOUR,
        alpha=alpha,
        lw=0,
        rasterized=True,
        zorder=4,
    )
    ax.scatter(
        final[ok, 1],
        final[ok, 0],
        s=size,
        color=style.RUN_COLOUR,
        alpha=alpha,
        lw=0,
        rasterized=True,
        zorder=5,
    )
    if ended.any():
        ax.scatter(
            final[ended, 1],
            final[ended, 0],
            s=14,
            marker="x",
            color=ENDED_COLOUR,
            lw=0.9,
            rasterized=True,
            zorder=5,
        )
    centre = (row["final_x_m_mean"], row["final_y_m_mean"])
    for level, (a, b, angle) in finish_ellipses(row).items():
        style.draw_ellipse(ax, *centre, a, b, angle, level)
    ax.plot(centre[1], centre[0], "+", color="black", ms=11, mew=1.6, zorder=7)
    if aim_rad is not None:
        reach = 2.0 * max(abs(xhi), abs(xlo), abs(yhi), abs(ylo), 1.0)
        ax.plot(
            [y0, y0 + reach * math.sin(aim_rad)],
            [x0, x0 + reach * math.cos(aim_rad)],
            color=AIM_COLOUR,
            lw=1.2,
            ls="-.",
            zorder=3,
        )
    target = (row["target_x_m"], row["target_y_m"])
    target_drawn = hole is None or not _target_is_pin(row, hole)
    if target_drawn:
        ax.plot(
            target[1],
            target[0],
            marker="*",
            ms=14,
            color=style.TARGET_COLOUR,
            mec="white",
            mew=0.8,
            ls="none",
            zorder=8,
        )
    ax.set_aspect("auto")
    ax.set_xlim(ylo, yhi)
    ax.set_ylim(xlo, xhi)
    ax.set_title(_map_title(run, row, hole, shots), fontsize=9)
    if (x0, y0) != (0.0, 0.0):
        ax.plot(y0, x0, "o", color="white", mec="black", ms=7, zorder=8)
    _legend(fig, ax, hole, shots, ended, (xlo, xhi, ylo, yhi), target_drawn=target_drawn,
            from_tee=(x0, y0) == (0.0, 0.0))  # fmt: skip
    _shares_table(side, row)
    style.fit_equal(fig, [ax])
    return fig


def _map_title(run, row, hole, shots):
    facts = None if hole is None else hole.facts
    name = (facts.name or facts.source) if facts is not None else "the hole"
    if facts is not None and facts.par is not None:
        name += f", par {facts.par}"
    length = f", {facts.length_m:.0f} m tee to pin" if facts is not None else ""
    return (
        f"{name}{length}\nthe first {len(shots['status']):,} shots of the point; 50 % and 95 % "
        f"ellipses of the ok shots' finish\n95 % of the finishes within "
        f"{style.fmt(row['distance_r95_m'])} m of the "
        + ("pin" if hole is not None and _target_is_pin(row, hole) else "target")
    )


def _target_is_pin(row, hole):
    return (
        math.hypot(row["target_x_m"] - hole.pin_xy[0], row["target_y_m"] - hole.pin_xy[1]) <= 0.01
    )


def _legend(fig, ax, hole, shots, ended, view, target_drawn, from_tee=True):
    from matplotlib.colors import to_rgb
    from matplotlib.patches import Patch

    from mcrun.report.hole_map import ZONE_COLOURS

    handles = []
    if hole is not None:
        t = hole
        kinds = hole.zone_kinds
        xlo, xhi, ylo, yhi = view
        ny, nx = t.zone.shape
        i0, i1 = (int(np.clip((v - t.y0_m) / t.cell_m, 0, ny)) for v in (ylo, yhi))
        j0, j1 = (int(np.clip((v - t.x0_m) / t.cell_m, 0, nx)) for v in (xlo, xhi))
        seen = np.unique(t.zone[i0 : i1 + 1, j0 : j1 + 1])
        handles += [
            Patch(color=to_rgb(ZONE_COLOURS[kinds[k]]), label=kinds[k].replace("_", " "))
            for k in seen
        ]
    line = style.legend_line
    handles += [
        line(marker="o", ls="none", color=style.FLIGHT_COLOUR, label="landing"),
        line(marker="o", ls="none", color=style.RUN_COLOUR, label="at rest (ok)"),
    ]
    if ended.any():
        handles.append(
            line(
                marker="x",
                ls="none",
                color=ENDED_COLOUR,
                label=f"ended in a penalty area, out of bounds or off the map ({ended.sum():,})",
            )
        )
    handles += [
        line(color="black", ls="--", lw=1.2, label="50 % ellipse"),
        line(color="black", ls="-", lw=1.6, label="95 % ellipse"),
        line(color="black", marker="+", ms=11, mew=1.6, ls="none", label="mean finish"),
    ]
    if hole is not None:
        handles += [
            line(marker="^", color="red", mec="black", ms=9, ls="none", label="pin"),
            line(
                color=AIM_COLOUR,
                ls="-.",
                lw=1.2,
                label="aim line from the tee" if from_tee else "aim line from the start",
            ),
        ]
        if hole.facts.line_xy is not None:
            from matplotlib.patheffects import withStroke

            handles.append(
                line(
                    color=HOLE_LINE_COLOUR,
                    ls="--",
                    lw=0.8,
                    path_effects=[withStroke(linewidth=2.4, foreground="0.35")],
                    label="hole line (map)",
                )
            )
    if target_drawn:
        handles.append(
            line(
                marker="*", ms=13, color=style.TARGET_COLOUR, mec="white", ls="none", label="target"
            )
        )
    fig.legend(
        handles=handles,
        loc="outside lower center",
        ncols=min(len(handles), 5),
        fontsize=8,
        frameon=False,
    )


def _shares_table(ax, row):
    """The finish and landing share of each zone with its 95 % interval, as a table."""
    ax.axis("off")
    finish = {z: (p, lo, hi) for z, p, lo, hi in zone_shares(row, "finish")}
    landing = {z: (p, lo, hi) for z, p, lo, hi in zone_shares(row, "landing")}
    cells = []
    for zone in ZONE_NAMES:
        if zone not in finish and zone not in landing:
            continue
        f = finish.get(zone, (math.nan,) * 3)
        g = landing.get(zone, (math.nan,) * 3)
        cells.append(
            [
                zone.replace("_", " "),
                percent(f[0]),
                interval(f[1], f[2]),
                percent(g[0]),
                interval(g[1], g[2]),
            ]
        )
    table = ax.table(
        cellText=cells,
        colLabels=["zone", "finish %", "95 % interval", "landing %", "95 % interval"],
        loc="upper center",
        cellLoc="right",
        colLoc="center",
    )
    table.auto_set_font_size(False)
    table.set_fontsize(7.5)
    table.scale(1.0, 1.35)
    for (r, c), cell in table.get_celld().items():
        cell.set_linewidth(0.4)
        if r == 0:
            cell.set_facecolor("#eeeeee")
        if c == 0:
            cell.set_text_props(ha="left")
            cell.PAD = 0.05
    table.auto_set_column_width(list(range(5)))
    n_shots, n_landed = int(row["n_shots"]), int(row.get("n_landed", row["n_shots"]))
    ax.set_title(
        "where the shots finish and land\n(summary.parquet, Wilson 95 % intervals)",
        fontsize=9,
    )
    ax.text(
        0.0,
        0.02,
        f"finish: share of all {n_shots:,} shots\nlanding: share of the {n_landed:,} that landed",
        transform=ax.transAxes,
        fontsize=7.5,
        va="bottom",
        color="0.3",
    )


def point_figures(run, row, label, stem):
    """The hole's figure of a point (``plots.figures``' ``point_figures``): none on a plane."""
    if not is_hole_run(run):
        return
    sample = read_hole_shots(run, int(row["point"]))
    yield (
        f"{stem}-hole",
        f"{label}the hole map with the landing and finish positions of the first "
        f"{len(sample['status']):,} shots, the 50 % and 95 % ellipses of the finish, "
        "the pin and the aim line, and the share of the shots that finish and land in "
        "each zone with its 95 % interval.",
        hole_figure(run, row, sample),
    )
