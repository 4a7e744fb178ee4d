"""``mcrun report RUN_DIR``: one self-contained HTML page of a finished run.

The page holds the scenario (its TOML text, from the provenance), the summary tables (one row
per point, the unit in each header; on a hole, each zone's share first and the map's
attribution), every plot of ``mcrun plot`` embedded as a PNG data URI,
and the provenance (seed, N, versions, times, threads, backend, the summary's conventions). Inline
CSS, no script, no link to anything outside the page (its only links are to its own sections),
so that it can be mailed to someone who will not run Python. The plots are drawn one at a time
and encoded at once; the run, local or Dask, is read as ``mcrun plot`` reads it
(``mcrun.report.plots``, through ``mcrun.results.reader``).
"""

import base64
import html
import json
import math
from pathlib import Path

import numpy as np

from mcrun.report import hole_plots
from mcrun.report.plots import figures
from mcrun.report.run_view import (
    SCATTER_MAX_SHOTS,
    TRAJECTORIES_PER_POINT,
    PlotError,
    check_unchanged,
    open_run,
)
from mcrun.report.style import png_bytes, require_matplotlib
from mcrun.results import geometry, output, stats
from mcrun.results.output import REPORT_FILE
from mcrun.results.reader import reason_of

DEFAULT_REPORT_DPI = 100
REPORT_SUFFIXES = (".html", ".htm")

# --- the report --------------------------------------------------------------------------------

_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", Helvetica, Arial, sans-serif;
  margin: 2em auto; max-width: 1250px; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
.question { font-size: 1.15em; font-style: italic; color: #444; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.88em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.55em; }
th { background: #f2f2f2; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.text { text-align: left; } caption { text-align: left; font-weight: bold; padding: 0.3em 0; }
pre { background: #f7f7f7; border: 1px solid #ddd; padding: 0.8em; overflow-x: auto;
  font-size: 0.85em; }
figure { margin: 1.5em 0; } figure img { max-width: 100%; height: auto; border: 1px solid #eee; }
figcaption { font-size: 0.9em; color: #444; } .wide { overflow-x: auto; }
nav ul { columns: 2; } .small { font-size: 0.85em; color: #555; }
.attribution { font-size: 0.9em; }
"""


def _esc(value):
    return html.escape(str(value), quote=True)


def _num(value, spec):
    if value is None:
        return "-"
    if isinstance(value, int | np.integer):
        return f"{int(value):,}" if spec == "," else format(int(value), spec.replace(",", ""))
    value = float(value)
    if not math.isfinite(value):
        return "-"
    return format(value + 0.0, spec)


def _table(caption, groups, rows, note="", numeric_text=False):
    """An HTML table: ``groups`` [(group header, [(column header, key, format)])], ``rows``
    dicts. A group header spans its columns (a quantity with its unit over its statistics).
    ``numeric_text``: text cells after the first column are numbers already formatted."""
    two_rows = any(g for g, _ in groups)
    out = ['<div class="wide"><table>', f"<caption>{_esc(caption)}</caption>", "<thead><tr>"]
    for group, columns in groups:
        if two_rows and group:
            out.append(f'<th colspan="{len(columns)}">{_esc(group)}</th>')
        elif two_rows:
            out += [f'<th rowspan="2">{_esc(c[0])}</th>' for c in columns]
        else:
            out += [f"<th>{_esc(c[0])}</th>" for c in columns]
    out.append("</tr>")
    if two_rows:
        out.append("<tr>")
        out += [f"<th>{_esc(c[0])}</th>" for g, columns in groups if g for c in columns]
        out.append("</tr>")
    out.append("</thead><tbody>")
    for row in rows:
        out.append("<tr>")
        first = True
        for _, columns in groups:
            for _, key, spec in columns:
                value = row.get(key)
                if spec is None:
                    kind = "num" if numeric_text and not first else "text"
                    out.append(f'<td class="{kind}">{_esc(value if value else "-")}</td>')
                else:
                    out.append(f'<td class="num">{_esc(_num(value, spec))}</td>')
                first = False
        out.append("</tr>")
    out.append("</tbody></table></div>")
    if note:
        out.append(f'<p class="small">{_esc(note)}</p>')
    return "\n".join(out)


def _point_columns(run):
    columns = [("point", "point", "d"), ("label", "label", None)] if run.points > 1 else []
    return ("", columns) if columns else None


def _stat_columns(name, mean_spec=".2f", percentiles=("p05", "p50", "p95")):
    columns = [("mean", f"{name}_mean", mean_spec), ("sd", f"{name}_std", mean_spec)]
    columns += [(f"{p[1:].lstrip('0') or '0'} %", f"{name}_{p}", mean_spec) for p in percentiles]
    return columns


def zone_tables(run):
    """A run on a hole: per point, the share of the shots that finish and land in each zone
    with its 95 % interval (summary.parquet), and the attribution of the map; "" on a plane."""
    if not hole_plots.is_hole_run(run):
        return ""
    out = []
    for row in run.summary.to_dict("records"):
        finish = {z: (p, lo, hi) for z, p, lo, hi in hole_plots.zone_shares(row, "finish")}
        landing = {z: (p, lo, hi) for z, p, lo, hi in hole_plots.zone_shares(row, "landing")}
        rows = []
        for zone in hole_plots.ZONE_NAMES:
            if zone not in finish and zone not in landing:
                continue
            f = finish.get(zone, (math.nan,) * 3)
            g = landing.get(zone, (math.nan,) * 3)
            rows.append(
                {
                    "zone": zone.replace("_", " "),
                    "finish": hole_plots.percent(f[0]),
                    "finish_ci": hole_plots.interval(f[1], f[2]),
                    "landing": hole_plots.percent(g[0]),
                    "landing_ci": hole_plots.interval(g[1], g[2]),
                }
            )
        n_landed = int(row.get("n_landed", row["n_shots"]))
        point = f"point {int(row['point'])} ({row['label']}): " if run.points > 1 else ""
        out.append(
            _table(
                f"{point}where the shots finish and land on the hole",
                [
                    ("", [("zone", "zone", None)]),
                    (
                        f"finish, of all {int(row['n_shots']):,} shots (%)",
                        [("share", "finish", None), ("95 % interval", "finish_ci", None)],
                    ),
                    (
                        f"landing, of the {n_landed:,} that landed (%)",
                        [("share", "landing", None), ("95 % interval", "landing_ci", None)],
                    ),
                ],
                rows,
                numeric_text=True,
            )
        )
    out.append(
        '<p class="small">Intervals: Wilson 95 %. A shot that lands or rolls into a penalty area '
        "or out of bounds ends there, in that zone; off map: it left the hole's grid.</p>"
    )
    out.append(_attribution(run))
    return "\n".join(out)


def _attribution(run):
    text = hole_plots.attribution_of(run)
    if not text:
        return ""
    hole, reason = hole_plots.hole_of(run)
    facts = None if hole is None else hole.facts
    source = f" ({Path(facts.map_source).name})" if facts is not None and facts.map_source else ""
    line = f'<p class="attribution">Map data{_esc(source)}: {_esc(text)}.</p>'
    if reason:
        line += f'<p class="small">No hole map: {_esc(reason)}.</p>'
    return line


def summary_tables(run):
    """The summary as HTML tables, one row per point, the unit in each header; a run on a
    hole first, its zone shares."""
    rows = run.summary.to_dict("records")
    for row in rows:
        row["ok_of_shots"] = f"{int(row['n_ok']):,} / {int(row['n_shots']):,}"
    head = [g for g in (_point_columns(run),) if g]
    tables = [zone_tables(run)] if hole_plots.is_hole_run(run) else []
    tables.append(
        _table(
            "Distances along the target line: mean, standard deviation and percentiles over "
            "the ok shots",
            [
                *head,
                ("", [("ok / shots", "ok_of_shots", None)]),
                ("carry (m)", _stat_columns("carry_m")),
                ("run, landing to rest (m)", _stat_columns("run_m")),
                ("total, at rest (m)", _stat_columns("total_m")),
            ],
            rows,
        )
    )
    tables.append(
        _table(
            "Across the target line, height and landing (+ right of the target line)",
            [
                *head,
                ("landing lateral (m)", _stat_columns("carry_lateral_m")),
                ("lateral at rest (m)", _stat_columns("final_y_m")),
                ("apex (m)", _stat_columns("apex_m", percentiles=("p50",))),
                (
                    "landing angle from the vertical (deg)",
                    _stat_columns("landing_angle_deg", ".1f", ("p50",)),
                ),
                ("first bounce height (m)", _stat_columns("first_bounce_height_m", ".3f", ())),
            ],
            rows,
        )
    )
    ellipse = []
    for level in stats.ELLIPSE_LEVELS:
        ellipse.append(
            (
                f"{level} % ellipse of the finish",
                [
                    ("semi-major (m)", f"ellipse{level}_semi_major_m", ".2f"),
                    ("semi-minor (m)", f"ellipse{level}_semi_minor_m", ".2f"),
                    ("angle (deg)", f"ellipse{level}_angle_deg", ".1f"),
                    ("area (m²)", f"ellipse{level}_area_m2", ".1f"),
                ],
            )
        )
    tables.append(
        _table(
            "Dispersion of the final position",
            [
                *head,
                *ellipse,
                (
                    "distance to the target",
                    [
                        ("target x (m)", "target_x_m", ".2f"),
                        ("target y (m)", "target_y_m", ".2f"),
                        ("mean (m)", "distance_mean_m", ".2f"),
                        ("50 % within (m)", "distance_r50_m", ".2f"),
                        ("95 % within (m)", "distance_r95_m", ".2f"),
                    ],
                ),
            ],
            rows,
            note="Ellipse angle: of the major axis, from the target line towards the right "
            "(90 deg: the spread is across the line). Target: the scenario's, else the "
            "point's mean finish.",
        )
    )
    status_columns = [c for c in run.summary.columns if c.startswith("n_")]
    tables.append(
        _table(
            "Shots by status",
            [*head, ("", [(c[2:].replace("_", " "), c, ",") for c in status_columns])],
            rows,
        )
    )
    tables.append(_drivers_table(run, rows, head))
    return "\n".join(tables)


def _top_shares(row, prefix, top=3):
    shares = {
        k[len(prefix) :]: v
        for k, v in row.items()
        if k.startswith(prefix) and isinstance(v, float) and math.isfinite(v)
    }
    best = sorted(shares.items(), key=lambda kv: -kv[1])[:top]
    return ", ".join(f"{k} {100.0 * v:.0f} %" for k, v in best) or "-"


def _drivers_table(run, rows, head):
    for row in rows:
        for y in stats.DRIVEN:
            row[f"drivers_{y}"] = _top_shares(row, f"{y}_share_")
        row["drivers_run_m"] = _top_shares(row, "run_m_share_")
    return _table(
        "What drives the spread",
        [
            *head,
            (
                "",
                [
                    ("total: share of the variance", "drivers_total_m", None),
                    ("total: R²", "total_m_r2", ".2f"),
                    ("lateral at rest: share of the variance", "drivers_final_y_m", None),
                    ("lateral: R²", "final_y_m_r2", ".2f"),
                    ("run explained alone by", "drivers_run_m", None),
                ],
            ),
        ],
        rows,
        note="Shares: squared standardised regression coefficients on the sampled inputs "
        "(they add up to R² for independent inputs); the run: squared correlation with each "
        "landing quantity.",
    )


def _full_summary(run):
    """Every column of summary.parquet, one row per column, one column per point."""
    summary = run.summary
    out = ['<div class="wide"><table><thead><tr><th>column</th>']
    out += [f"<th>point {int(p)}</th>" for p in summary["point"]]
    out.append("</tr></thead><tbody>")
    for column in summary.columns:
        out.append(f'<tr><td class="text">{_esc(column)}</td>')
        for value in summary[column]:
            if isinstance(value, float | np.floating):
                out.append(f'<td class="num">{_esc(_num(value, ".6g"))}</td>')
            elif isinstance(value, int | np.integer):
                out.append(f'<td class="num">{int(value)}</td>')
            else:
                out.append(f'<td class="text">{_esc(value)}</td>')
        out.append("</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


_PROVENANCE_ORDER = (
    "scenario_name",
    "scenario_path",
    "seed",
    "n",
    "points",
    "groups",
    "block_size",
    "models",
    "versions",
    "start_time_utc",
    "elapsed_s",
    "threads",
    "chunk_size",
    "backend",
    "trajectories_every",
    "format_version",
)


def _recorded_map(value):
    """One line for the recorded hole map (``geometry.MAP_KEY``): its grid, not its bytes."""
    if not isinstance(value, dict):
        return json.dumps(value)
    heights = " and heights" if value.get("height_m") else ""
    return (
        f"zones{heights} on a grid of {value.get('nx')} x {value.get('ny')} nodes, "
        f"{value.get('cell_m')} m apart, from x = {value.get('x0_m')} m, y = {value.get('y0_m')} m"
    )


def _provenance_table(run):
    provenance = {k: v for k, v in run.provenance.items() if k not in ("scenario_text", "file")}
    keys = [k for k in _PROVENANCE_ORDER if k in provenance]
    keys += sorted(k for k in provenance if k not in keys)
    out = ["<table><thead><tr><th>key</th><th>value</th></tr></thead><tbody>"]
    for key in keys:
        value = provenance[key]
        if key == "versions" and isinstance(value, dict):
            text = ", ".join(f"{k} {v}" for k, v in value.items())
        elif key == geometry.MAP_KEY:
            text = _recorded_map(value)
        elif key == "elapsed_s" and isinstance(value, int | float):
            text = f"{value:g} s (start of the run to summary.parquet written)"
        elif isinstance(value, str):
            text = value
        else:
            text = json.dumps(value)
        out.append(f'<tr><td class="text">{_esc(key)}</td><td class="text">{_esc(text)}</td></tr>')
    out.append("</tbody></table>")
    return "\n".join(out)


def report_html(run, dpi=DEFAULT_REPORT_DPI, scatter_max=SCATTER_MAX_SHOTS):
    """The report of an open run: one self-contained HTML page (str)."""
    p = run.provenance
    versions = p.get("versions") if isinstance(p.get("versions"), dict) else {}
    figures_html = []
    for stem, caption, fig in figures(run, scatter_max, point_figures=hole_plots.point_figures):
        data = base64.b64encode(png_bytes(fig, dpi)).decode("ascii")
        figures_html.append(
            f'<figure id="plot-{_esc(stem)}"><img alt="{_esc(stem)}" '
            f'src="data:image/png;base64,{data}">'
            f"<figcaption><b>{_esc(stem)}</b>: {_esc(caption)}</figcaption></figure>"
        )
    facts = [
        f"{int(p['n']):,} shots per point" if p.get("n") is not None else None,
        f"{run.points} point" + ("s" if run.points != 1 else ""),
        f"seed {p['seed']}" if p.get("seed") is not None else None,
        f"run {p['start_time_utc']}" if p.get("start_time_utc") else None,
        f"{p['elapsed_s']:g} s on {p.get('threads', '?')} "
        f"thread{'' if p.get('threads') == 1 else 's'} ({p.get('backend', '?')})"
        if isinstance(p.get("elapsed_s"), int | float)
        else None,
        f"mcrun {versions['mcrun']}" if isinstance(versions.get("mcrun"), str) else None,
    ]
    if not p:  # (its files rewritten by a tool that keeps no key-value metadata)
        facts = ["no mcrun provenance in the files (rewritten by another tool?): the scenario, "
                 "seed and versions are unknown", *facts[:2]]  # fmt: skip
    facts = ", ".join(f for f in facts if f)
    how = (
        f"How the plots read the shots: positions are drawn as dots (every shot) for a point "
        f"of at most {scatter_max:,} ok shots, else as a binned density of all of them; the "
        "histograms count every ok shot; trajectories are the first "
        f"{TRAJECTORIES_PER_POINT} paths of each point in trajectories.parquet."
    )
    if hole_plots.is_hole_run(run):
        how += (
            " The hole maps draw the first "
            f"{hole_plots.HOLE_DOTS_PER_POINT:,} shots of each point that reached the ground."
        )
    title = f"mcrun report: {run.name}"
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{_esc(title)}</title>",
        f"<style>{_CSS}</style></head><body>",
        f"<h1>{_esc(run.name)}</h1>",
    ]
    if run.question:
        parts.append(f'<p class="question">{_esc(run.question)}</p>')
    parts += [
        f"<p>{_esc(facts)}. Run folder: <code>{_esc(run.path)}</code>.</p>",
        '<nav><ul><li><a href="#summary">Summary</a></li><li><a href="#plots">Plots</a></li>'
        '<li><a href="#scenario">Scenario</a></li><li><a href="#provenance">Provenance</a>'
        "</li></ul></nav>",
        '<h2 id="summary">Summary</h2>',
        summary_tables(run),
        "<details><summary>Every column of summary.parquet</summary>",
        _full_summary(run),
        "</details>",
        '<h2 id="plots">Plots</h2>',
        f'<p class="small">{_esc(how)}</p>',
        *figures_html,
        _attribution(run) if hole_plots.is_hole_run(run) else "",
        '<h2 id="scenario">Scenario</h2>',
        f"<p>{_esc(p.get('scenario_path', ''))}</p>",
        f"<pre>{_esc(p.get('scenario_text', ''))}</pre>",
        '<h2 id="provenance">Provenance</h2>',
        _provenance_table(run),
        f'<p class="small">Written by mcrun report from {_esc(run.path)}.</p>',
        "</body></html>",
    ]
    return "\n".join(parts) + "\n"


def write_report(run_dir, path=None, dpi=DEFAULT_REPORT_DPI, scatter_max=SCATTER_MAX_SHOTS):
    """Write the HTML report of a run folder to ``path`` (default RUN_DIR/report.html,
    replaced if it exists). The destination is checked before anything is drawn, and the page
    is written under a temporary name and renamed into place when complete."""
    run = open_run(run_dir)
    require_matplotlib("report")
    path = Path(run.beside(REPORT_FILE) if path is None else path)
    if path.suffix.lower() not in REPORT_SUFFIXES and not path.is_dir():  # (a folder: below)
        raise PlotError(f"-o {path}: the report is an HTML page: give a file ending in "
                        f"{' or '.join(REPORT_SUFFIXES)}")  # fmt: skip
    destination = output.AtomicFile(path, force=True)
    try:
        destination.__enter__()  # refuses a folder or an unwritable place, creates the parents
    except output.OutputError as err:
        raise PlotError(f"-o: {err}") from None
    try:
        text = report_html(run, dpi, scatter_max)
        check_unchanged(run, run_dir, "the report was")
        destination.tmp.write_text(text, encoding="utf-8")
        destination.commit()
    except OSError as err:
        raise PlotError(f"-o: cannot write {path}: {reason_of(err)}") from None
    finally:
        destination.__exit__(None, None, None)  # removes the temporary file unless committed
    return path


# --- command line ------------------------------------------------------------------------------
