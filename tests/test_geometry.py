"""Runs that record their geometry (``mcrun.results.geometry``): a run on a library hole records
the frame, the tee, the pin, the aim and each point's target that its scenario gave, checked
from first principles (the pin's lon/lat from the recorded frame, its distance and bearing from
the tee on the WGS84 ellipsoid, the aim from the scenario's aim point); the report draws the
hole's map from that record when the scenario and the map files are gone; a run written before
the geometry was recorded still plots, without a map and saying so; the aim table carries the
same record."""

import math
import shutil
import tomllib
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

from mcrun.cli import main
from mcrun.hole.osm import ATTRIBUTION
from mcrun.hole.zones import ZONE_KINDS
from mcrun.results import geometry, output, reader
from mcrun.run import aim
from mcrun.run import scenario as sc
from mcrun.run.local import run_scenario
from mcrun.run.scenario import hole_table

LIBRARY = Path(__file__).resolve().parent.parent / "scenarios"
N = 200
DPI = 30
# WGS84
A_M = 6378137.0
E2 = (1.0 / 298.257223563) * (2.0 - 1.0 / 298.257223563)


def local_metres(lon0, lat0, lon, lat):
    """(east, north) m of (lon, lat) from (lon0, lat0) on the WGS84 ellipsoid, by its radii of
    curvature at the mean latitude: within 1e-5 of the distance over a hole's 400 m."""
    phi = math.radians(0.5 * (lat0 + lat))
    w = math.sqrt(1.0 - E2 * math.sin(phi) ** 2)
    meridian = A_M * (1.0 - E2) / w**3
    normal = A_M / w
    return (
        math.radians(lon - lon0) * normal * math.cos(phi),
        math.radians(lat - lat0) * meridian,
    )


@pytest.fixture(scope="module")
def par4(tmp_path_factory):
    """par4-tee-shot (aimed 20 m left of the line at 260 m), run from a copy of the scenario
    and its hole files, which are then removed: (run folder, the scenario as loaded)."""
    root = tmp_path_factory.mktemp("geometry")
    shutil.copytree(LIBRARY / "holes", root / "holes")
    shutil.copy(LIBRARY / "par4-tee-shot.toml", root / "par4-tee-shot.toml")
    scenario = sc.load(root / "par4-tee-shot.toml")
    terrain = scenario.hole.terrain()
    result = run_scenario(root / "par4-tee-shot.toml", n=N, out_dir=root / "run", progress=False)
    shutil.rmtree(root / "holes")
    (root / "par4-tee-shot.toml").unlink()
    hole_table._HOLES.clear()  # no cached hole either: only the run's record is left
    return result.out_dir, scenario, terrain


def test_a_run_records_the_frame_tee_pin_aim_and_targets_its_scenario_gave(par4):
    run_dir, scenario, _ = par4
    folder = reader.open_run(run_dir)
    g = folder.geometry
    assert g.on_hole and g.tee_xy_m == (0.0, 0.0)
    # The pin in the frame: on the +x axis, as far from the tee as the hole is long.
    hole = scenario.hole
    assert g.pin_xy_m[1] == 0.0
    assert math.hypot(*g.pin_xy_m) == pytest.approx(hole.length_m, abs=1e-9)
    # The frame on the Earth: the recorded origin and heading put the pin where the map has it,
    # at the distance and bearing the ellipsoid gives between the tee's and the pin's lon/lat.
    tee_lon, tee_lat = hole.tee_lonlat
    pin_lon, pin_lat = hole.pin_lonlat
    assert (g.frame.origin_lon_deg, g.frame.origin_lat_deg) == (tee_lon, tee_lat)
    east, north = local_metres(tee_lon, tee_lat, pin_lon, pin_lat)
    assert math.hypot(east, north) == pytest.approx(g.pin_xy_m[0], rel=1e-5)
    # (The bearing at the tee: the chord's, less half the meridians' convergence over it.)
    convergence = (pin_lon - tee_lon) * math.sin(math.radians(0.5 * (tee_lat + pin_lat)))
    bearing = math.degrees(math.atan2(east, north)) - 0.5 * convergence
    assert bearing == pytest.approx(g.frame.heading_deg, abs=2e-5)
    lon, lat = g.frame.to_lonlat(*g.pin_xy_m)
    assert (float(lon), float(lat)) == pytest.approx((pin_lon, pin_lat), abs=1e-9)
    # The aim: the bearing of the scenario's aim point, [260, -20] m, 4.4 deg left; the same
    # for every point, with its sense said.
    aim_x, aim_y = tomllib.loads(scenario.text)["hole"]["aim"]
    assert g.aim_deg == pytest.approx([math.degrees(math.atan2(aim_y, aim_x))] * len(g.aim_deg))
    assert g.aim_deg[0] == pytest.approx(-4.3987, abs=1e-4)
    assert "+ right" in folder.provenance["geometry"]["aim_sense"]
    # Each point's target: the pin by default, as the summary has it.
    for point, target in enumerate(g.targets_xy_m):
        row = folder.summary.iloc[point]
        assert target == pytest.approx(g.pin_xy_m)
        assert target == pytest.approx((row["target_x_m"], row["target_y_m"]))
    assert g.hole.name == hole.name and g.hole.par == 4 and g.hole.attribution == ATTRIBUTION


def test_the_recorded_map_is_the_grid_the_shots_were_played_on(par4):
    run_dir, _, terrain = par4
    hole_map = reader.open_run(run_dir).hole_map()
    assert hole_map.zone_kinds == ZONE_KINDS
    np.testing.assert_array_equal(hole_map.zone, terrain.zone)
    np.testing.assert_array_equal(hole_map.height_m, terrain.height_m)
    assert (hole_map.x0_m, hole_map.y0_m, hole_map.cell_m) == (
        terrain.x0_m,
        terrain.y0_m,
        terrain.cell_m,
    )
    # The pin's node is green, inside the recorded green's box.
    px, py = hole_map.pin_xy
    ix = round((px - hole_map.x0_m) / hole_map.cell_m)
    iy = round((py - hole_map.y0_m) / hole_map.cell_m)
    assert ZONE_KINDS[hole_map.zone[iy, ix]] == "green"
    x0, x1, y0, y1 = hole_map.facts.green_box_m
    assert x0 < px < x1 and y0 < py < y1
    # Only summary.parquet holds the map; every file holds the geometry; the shots' columns
    # are those of a run on a hole.
    shots = output.read_provenance(run_dir / output.SHOTS_FILE)
    assert geometry.MAP_KEY not in shots and geometry.GEOMETRY_KEY in shots
    assert geometry.read_geometry(shots) == reader.open_run(run_dir).geometry
    assert len(pq.read_metadata(run_dir / output.SUMMARY_FILE).metadata[b"mcrun.hole_map"]) < 1e5


def test_the_report_draws_the_map_from_the_record_without_the_scenario_files(par4, tmp_path):
    pytest.importorskip("matplotlib")
    from mcrun.report import hole_plots, run_view

    run_dir, scenario, _ = par4
    assert not Path(scenario.path).exists()
    run = run_view.open_run(run_dir)
    hole_map, reason = hole_plots.hole_of(run)
    assert reason is None and hole_map is not None
    row = run.summary.iloc[0].to_dict()
    fig = hole_plots.hole_figure(run, row, hole_plots.read_hole_shots(run, 0))
    ax = fig.axes[0]
    assert len(ax.images) == 1  # the zones
    assert ATTRIBUTION in [t.get_text() for t in ax.texts]
    # the aim line, on the recorded bearing
    aim_line = [line for line in ax.lines if line.get_color() == hole_plots.AIM_COLOUR][0]
    y, x = aim_line.get_data()
    assert math.degrees(math.atan2(y[1], x[1])) == pytest.approx(run.geometry.aim_deg[0])
    out = tmp_path / "plots"
    assert main(["plot", str(run_dir), "-o", str(out), "--dpi", str(DPI)]) == 0
    assert (out / "point00-hole.png").is_file()
    assert output.PLOT_NAME.fullmatch("point00-hole.png")  # (what --force may delete)
    page = tmp_path / "report.html"
    assert main(["report", str(run_dir), "-o", str(page), "--dpi", str(DPI)]) == 0
    text = page.read_text(encoding="utf-8")
    assert "riverside-zagreb.osm.geojson" in text and "No hole map" not in text


def strip_geometry(run_dir, to):
    """A copy of the run folder as runs were written before they recorded their geometry."""
    shutil.copytree(run_dir, to)
    for name in (output.SHOTS_FILE, output.SUMMARY_FILE):
        table = pq.read_table(to / name)
        kept = {
            k: v
            for k, v in table.schema.metadata.items()
            if k not in (b"mcrun.geometry", b"mcrun.hole_map", b"mcrun.question")
        }
        pq.write_table(table.replace_schema_metadata(kept), to / name)
    return to


def test_a_run_written_before_it_recorded_its_geometry_plots_without_a_map(par4, tmp_path):
    pytest.importorskip("matplotlib")
    from mcrun.report import hole_plots, run_view

    old = strip_geometry(par4[0], tmp_path / "old")
    folder = reader.open_run(old)
    assert folder.geometry is None and folder.hole_map() is None
    run = run_view.open_run(old)
    assert run.question.startswith("Where do tour drives finish")  # from the scenario text
    fig = hole_plots.hole_figure(
        run, run.summary.iloc[0].to_dict(), hole_plots.read_hole_shots(run, 0)
    )
    notes = [t.get_text() for t in fig.axes[0].texts]
    assert any(hole_plots.NO_MAP in t for t in notes) and not fig.axes[0].images
    out = tmp_path / "plots"
    assert main(["plot", str(old), "-o", str(out), "--dpi", str(DPI)]) == 0
    assert (out / "point00-hole.png").is_file()
    page = tmp_path / "old.html"
    assert main(["report", str(old), "-o", str(page), "--dpi", str(DPI)]) == 0
    text = page.read_text(encoding="utf-8")
    assert f"No hole map: {hole_plots.NO_MAP}." in text and f"Map data: {ATTRIBUTION}." in text


def test_a_plane_run_records_its_targets_and_no_map(tmp_path):
    result = run_scenario(LIBRARY / "pga-driver.toml", n=N, out_dir=tmp_path / "r", progress=False)
    folder = reader.open_run(result.out_dir)
    g = folder.geometry
    assert g.surface == "plane" and g.pin_xy_m is None and g.hole is None
    assert g.aim_deg == (0.0,) and not g.frame.on_earth
    assert folder.hole_map() is None
    assert geometry.MAP_KEY not in folder.provenance


def test_the_aim_table_carries_the_geometry(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "aims.parquet"
    argv = ["aim", "par3-over-water", "-n", str(N), "--offsets", "-3,0,3", "-o", str(out)]
    assert main([*argv, "--plot", str(tmp_path / "aims.png")]) == 0
    assert (tmp_path / "aims.png").stat().st_size > 0
    provenance = output.read_provenance(out)
    assert provenance["file"] == "aim" and provenance["n"] == N
    assert provenance["baseline"] == aim.TOUR_BASELINE
    g = geometry.read_geometry(provenance)
    hole = sc.load(sc.find("par3-over-water")).hole
    assert g.on_hole and g.pin_xy_m == pytest.approx(hole.pin_xy)
    assert g.aim_deg == (0.0,)  # the scenario aims at the pin: the offsets are about it
    hole_map = geometry.read_hole_map(provenance)
    np.testing.assert_array_equal(hole_map.zone, hole.terrain().zone)
    # the table's bearings are in the frame's sense: + right of the line to the pin
    table = pq.read_table(out).to_pandas()
    right = table[table["aim_offset_m"] == 3.0].iloc[0]
    assert right["aim_bearing_deg"] == pytest.approx(
        math.degrees(math.atan2(3.0, math.hypot(*g.pin_xy_m)))
    )
