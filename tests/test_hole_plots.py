"""The pictures of a run on a hole: ``pointNN-hole.png`` in ``mcrun plot`` and ``mcrun report``,
the zone shares in the report, the map's attribution; a run on a plane draws what it drew.

Two small hole runs, made once per module: the library's par3-over-water (one point, the hole
file found beside the scenario) and the same hole aimed right of the pin, towards the water,
swept over two temperatures (two points, some shots in the water). The hole kernel compiles
once and is cached.
"""

import html
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from mcrun import status as status_codes
from mcrun.cli import main
from mcrun.hole.osm import ATTRIBUTION
from mcrun.report import hole_plots, run_view, style
from mcrun.report import html as report
from mcrun.results import output, stats
from mcrun.run.local import run_scenario

pytest.importorskip("matplotlib")  # the optional extra mcrun[plot]

LIBRARY = Path(__file__).resolve().parent.parent / "scenarios"
DPI = 40
N = 500


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """{name: run folder}: "library" (par3-over-water, one point), "aimed" (aimed at the
    water right of the green, two points), "plane" (a plane, one point)."""
    root = tmp_path_factory.mktemp("hole-plots")
    text = (LIBRARY / "par3-over-water.toml").read_text(encoding="utf-8")
    hole_file = (LIBRARY / "holes" / "riverside-2.toml").as_posix()
    aimed = text.replace(
        'file = "holes/riverside-2.toml"', f'file = "{hole_file}"\naim = [160.0, 12.0]'
    ).replace('name = "par3-over-water"', 'name = "par3-aimed-right"')
    aimed += '\n[sweep]\n"weather.temperature" = ["10 C", "30 C"]\n'
    (root / "aimed.toml").write_text(aimed, encoding="utf-8")
    made = {
        "library": run_scenario(
            LIBRARY / "par3-over-water.toml", n=N, out_dir=root / "library", progress=False
        ),
        "aimed": run_scenario(root / "aimed.toml", n=N, out_dir=root / "aimed", progress=False),
        "plane": run_scenario(
            LIBRARY / "pga-driver.toml", n=300, out_dir=root / "plane", progress=False
        ),
    }
    return {name: result.out_dir for name, result in made.items()}


@pytest.fixture(scope="module")
def pages(runs):
    """{name: the HTML report}."""
    out = {}
    for name, run_dir in runs.items():
        path = run_dir.parent / f"{name}.html"
        assert main(["report", str(run_dir), "-o", str(path), "--dpi", str(DPI)]) == 0
        out[name] = path.read_text(encoding="utf-8")
    return out


def assert_drawn(rgb):
    grey = rgb.mean(axis=2)
    assert grey.std() > 0.05
    assert (grey < 0.5).mean() > 0.005
    colours = np.unique((rgb.reshape(-1, 3) * 255).round().astype(np.uint8), axis=0)
    assert len(colours) > 50


def shots_of(run_dir, point):
    frame = pq.read_table(
        run_dir / output.SHOTS_FILE,
        columns=["point", "status", "carry_m", "final_x_m", "final_y_m", "finish_zone"],
    ).to_pandas()
    return frame[frame["point"] == point].reset_index(drop=True)


# --- mcrun plot ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("library", {"point00-positions", "point00-distances", "point00-hole"}),
        (
            "aimed",
            {"summary", "finish"}
            | {f"point0{k}-{kind}" for k in (0, 1) for kind in ("positions", "distances", "hole")},
        ),
        ("plane", {"point00-positions", "point00-distances"}),
    ],
)
def test_a_hole_run_adds_the_hole_figure_and_a_plane_run_is_unchanged(
    runs, tmp_path, name, expected
):
    from matplotlib.image import imread

    out = tmp_path / "plots"
    assert main(["plot", str(runs[name]), "-o", str(out), "--dpi", str(DPI)]) == 0
    assert {p.stem for p in out.iterdir()} == expected
    for path in out.iterdir():
        image = imread(path)
        kind = path.stem.split("-")[-1] if path.stem.startswith("point") else path.stem
        width_in, height_in = style.FIGURE_SIZES_IN[kind]
        assert image.shape[:2] == (round(height_in * DPI), round(width_in * DPI)), path.name
        assert_drawn(image[..., :3])


def figure_of(run_dir, point):
    run = run_view.open_run(run_dir)
    row = run.summary.loc[run.summary["point"] == point].iloc[0].to_dict()
    sample = hole_plots.read_hole_shots(run, point)
    return run, row, sample, hole_plots.hole_figure(run, row, sample)


@pytest.mark.parametrize("point", [0, 1])
def test_the_hole_figure_draws_the_shots_the_ellipses_and_the_shares(runs, point):
    from matplotlib.collections import PathCollection
    from matplotlib.patches import Ellipse

    run, row, sample, fig = figure_of(runs["aimed"], point)
    shots = shots_of(runs["aimed"], point)
    ax, side = fig.axes[:2]
    # the clouds: every shot of the point (N < the dot limit), the ended ones as crosses
    assert len(sample["status"]) == N == int(np.isfinite(shots["carry_m"]).sum())
    ended = shots["status"].isin(status_codes.HOLE_STATUSES)
    assert ended.sum() == round(row["p_finish_water_yellow"] * N) > 0  # golf=water_hazard
    clouds = [c for c in ax.collections if isinstance(c, PathCollection)]
    assert [len(c.get_offsets()) for c in clouds] == [N, N - ended.sum(), ended.sum()]
    np.testing.assert_allclose(
        clouds[2].get_offsets(), shots.loc[ended, ["final_y_m", "final_x_m"]].to_numpy()
    )
    # the 50 % and 95 % ellipses of the finish: the summary's covariance, about its mean
    ellipses = sorted((p for p in ax.patches if isinstance(p, Ellipse)), key=lambda p: p.width)
    assert len(ellipses) == 2
    a50, b50, _, _ = stats.ellipse(row["cov_xx_m2"], row["cov_xy_m2"], row["cov_yy_m2"], 50)
    assert ellipses[0].width == pytest.approx(2 * a50)
    assert ellipses[0].height == pytest.approx(2 * b50)
    assert ellipses[1].width == pytest.approx(2 * row["ellipse95_semi_major_m"])
    assert ellipses[1].angle == pytest.approx(90.0 - row["ellipse95_angle_deg"])
    assert ellipses[1].center == pytest.approx((row["final_y_m_mean"], row["final_x_m_mean"]))
    # the view: the pin, the green and every shot that ended are in it
    hole, reason = hole_plots.hole_of(run)
    aim_rad = hole_plots.aim_of(run, point)
    assert reason is None and aim_rad == pytest.approx(np.arctan2(12.0, 160.0))
    (y0, y1), (x0, x1) = ax.get_xlim(), ax.get_ylim()
    gx0, gx1, gy0, gy1 = hole.facts.green_box_m
    assert x0 < gx0 < hole.pin_xy[0] < gx1 < x1 and y0 < gy0 < gy1 < y1
    ends = shots.loc[ended]
    assert ((ends["final_x_m"] > x0) & (ends["final_x_m"] < x1)).all()
    assert ((ends["final_y_m"] > y0) & (ends["final_y_m"] < y1)).all()
    assert x1 - x0 < 80.0  # zoomed on the shots, not the whole hole
    # the attribution on the map, the shares beside it
    assert ATTRIBUTION in [t.get_text() for t in ax.texts]
    table = side.tables[0]
    cells = {}
    for (r, c), cell in table.get_celld().items():
        cells.setdefault(r, {})[c] = cell.get_text().get_text()
    rows = {cells[r][0]: [cells[r][c] for c in range(1, 5)] for r in cells if r > 0}
    for zone in ("green", "water_yellow", "rough"):
        p = f"p_finish_{zone}"
        q = f"p_landing_{zone}"
        assert rows[zone.replace("_", " ")] == [
            f"{100 * row[p]:.1f}",
            f"{100 * row[p + '_lo95']:.1f}-{100 * row[p + '_hi95']:.1f}",
            f"{100 * row[q]:.1f}",
            f"{100 * row[q + '_lo95']:.1f}-{100 * row[q + '_hi95']:.1f}",
        ]
    assert set(rows) == {z.replace("_", " ") for z in hole_plots.ZONE_NAMES}


def test_a_hole_run_that_records_no_map_is_drawn_without_it(runs):
    """A run written before runs recorded their geometry: no map, the figure and the page say
    why, the map's attribution is still given (the scenario names a map)."""
    run = run_view.open_run(runs["library"])
    for key in ("geometry", "hole_map"):
        del run.provenance[key]
    hole, reason = hole_plots.hole_of(run)
    assert hole is None and hole_plots.aim_of(run, 0) is None and reason == hole_plots.NO_MAP
    row = run.summary.iloc[0].to_dict()
    fig = hole_plots.hole_figure(run, row, hole_plots.read_hole_shots(run, 0))
    assert any(hole_plots.NO_MAP in t.get_text() for t in fig.axes[0].texts)
    page = report.report_html(run, dpi=DPI)
    assert f"Map data: {ATTRIBUTION}." in page and "No hole map" in page


# --- mcrun report -------------------------------------------------------------------------------


def zone_rows(page, caption):
    """{zone: [finish share, its interval, landing share, its interval]} of the table with
    ``caption``."""
    table = page.split(f"<caption>{html.escape(caption)}</caption>")[1].split("</table>")[0]
    rows = {}
    for body in re.findall(r"<tr>\n(.*?)\n</tr>", table, flags=re.S):
        cells = re.findall(r'<td class="(?:text|num)">([^<]*)</td>', body)
        if cells:
            rows[cells[0]] = cells[1:]
    return rows


@pytest.mark.parametrize("name", ["library", "aimed"])
def test_the_report_lists_the_zone_shares_and_the_attribution(runs, pages, name):
    page = pages[name]
    summary = pd.read_parquet(runs[name] / output.SUMMARY_FILE)
    for point, row in summary.iterrows():
        caption = "where the shots finish and land on the hole"
        if len(summary) > 1:
            caption = f"point {point} ({row['label']}): {caption}"
        rows = zone_rows(page, caption)
        assert set(rows) == {z.replace("_", " ") for z in hole_plots.ZONE_NAMES}
        for zone in hole_plots.ZONE_NAMES:
            p, q = f"p_finish_{zone}", f"p_landing_{zone}"
            assert rows[zone.replace("_", " ")] == [
                f"{100 * row[p]:.1f}",
                f"{100 * row[p + '_lo95']:.1f}-{100 * row[p + '_hi95']:.1f}",
                f"{100 * row[q]:.1f}",
                f"{100 * row[q + '_lo95']:.1f}-{100 * row[q + '_hi95']:.1f}",
            ], (point, zone)
        assert f"of all {N:,} shots (%)" in page
        assert f'id="plot-point{point:02d}-hole"' in page
    green = summary.loc[0, "p_finish_green"]
    assert 0.0 < green < 1.0
    assert (
        f'<p class="attribution">Map data (riverside-zagreb.osm.geojson): {ATTRIBUTION}.</p>'
        in page
    )


def test_the_report_of_a_plane_run_has_no_hole(pages):
    page = pages["plane"]
    assert "where the shots finish and land" not in page
    assert "OpenStreetMap" not in page and "-hole" not in page
    assert set(re.findall(r'id="plot-([^"]+)"', page)) == {
        "point00-positions",
        "point00-distances",
    }
