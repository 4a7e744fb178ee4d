"""hole.elevation: GeoTIFF DEMs, ESRI ASCII grids and survey points, read back at points between
their nodes against the function their heights were made from; bad files in one line.

Every fixture samples a plane, in lon/lat degrees or in UTM metres, which bilinear interpolation
(and linear interpolation over triangles) reproduces exactly: the heights read back agree with
the plane to float rounding (1e-9 m on heights of ~300 m, allowing for pyproj's round trip of
lon/lat to UTM, ~1e-9 m, times a gradient of 0.02)."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from mcrun.hole.elevation import ElevationError, load_elevation

pyproj = pytest.importorskip("pyproj")
tifffile = pytest.importorskip("tifffile")

USGS = Path(__file__).parent.parent / "scenarios" / "holes" / "usgs-3dep-points-alpharetta-ga.csv"
TOL_M = 1e-9

# A grid of 7 columns x 5 rows over a hole near Zagreb, in lon/lat ...
LON_W, LAT_N, DLON, DLAT = 15.95, 45.81, 2e-4, 1.5e-4
# ... and in UTM zone 33N (EPSG:32633), metres.
E_W, N_N, CELL = 500_000.0, 5_073_000.0, 5.0
UTM = pyproj.Transformer.from_crs("EPSG:32633", "EPSG:4326", always_xy=True)


def plane_lonlat(lon, lat):
    return 300.0 + 1000.0 * (lon - LON_W) - 2000.0 * (lat - LAT_N)


def plane_utm(e, n):
    return 120.0 + 0.01 * (e - E_W) - 0.02 * (n - N_N)


def geokeys(raster_type, model, code):
    """A GeoKey directory: model type, raster type and the EPSG code of the system."""
    code_key = 2048 if model == 2 else 3072
    return (1, 1, 0, 3, 1024, 0, 1, model, 1025, 0, 1, raster_type, code_key, 0, 1, code)


def write_tiff(path, data, keys=None, scale=None, tie=None, matrix=None, nodata=None):
    tags = []
    if scale is not None:
        tags.append((33550, "d", 3, scale, True))
        tags.append((33922, "d", 6, tie, True))
    if matrix is not None:
        tags.append((34264, "d", 16, matrix, True))
    if keys is not None:
        tags.append((34735, "H", len(keys), keys, True))
    if nodata is not None:
        tags.append((42113, "s", 0, nodata, True))
    tifffile.imwrite(path, data, extratags=tags)
    return path


def lonlat_tiff(tmp_path, raster_type, name="dem.tif"):
    """A north-up lon/lat GeoTIFF of the lon/lat plane, its values placed as ``raster_type``
    says (1: at the pixels' centres, 2: at the raster points), tied at its NW corner."""
    shift = 0.5 if raster_type == 1 else 0.0
    cols, rows = np.meshgrid(np.arange(7) + shift, np.arange(5) + shift)
    data = plane_lonlat(LON_W + cols * DLON, LAT_N - rows * DLAT)
    return write_tiff(
        tmp_path / name,
        data,
        geokeys(raster_type, 2, 4326),
        scale=(DLON, DLAT, 0.0),
        tie=(0.0, 0.0, 0.0, LON_W, LAT_N, 0.0),
    )


def between_nodes(rng, lo, hi, n=200):
    return rng.uniform(lo, hi, n)


@pytest.mark.parametrize("raster_type", [1, 2])
def test_geotiff_lonlat_reads_its_plane_between_nodes(tmp_path, raster_type):
    dem = load_elevation(lonlat_tiff(tmp_path, raster_type))
    shift = 0.5 if raster_type == 1 else 0.0
    lon0, lat1 = LON_W + shift * DLON, LAT_N - shift * DLAT
    lon1, lat0 = lon0 + 6 * DLON, lat1 - 4 * DLAT
    assert dem.bounds_lonlat() == pytest.approx((lon0, lat0, lon1, lat1), abs=1e-12)
    rng = np.random.default_rng(1)
    lon, lat = rng.uniform(lon0, lon1, 300), rng.uniform(lat0, lat1, 300)
    np.testing.assert_allclose(dem.height_m(lon, lat), plane_lonlat(lon, lat), rtol=0, atol=TOL_M)
    # Outside the nodes' extent there is no height.
    outside = dem.height_m([lon0 - 1e-7, lon1 + 1e-7, lon0, lon0], [lat0, lat0, lat0 - 1e-7, 80])
    assert np.all(np.isnan(outside))
    assert dem.source == "dem.tif" and dem.crs == "EPSG:4326"
    assert "GeoTIFF DEM (PixelIs" + ("Area" if raster_type == 1 else "Point") in str(dem)


def test_pixel_is_area_stands_half_a_pixel_in_from_pixel_is_point(tmp_path):
    # The same values read as PixelIsArea stand half a pixel east and south of where PixelIsPoint
    # puts them: at a point, the one grid's height is the other's half a pixel back.
    area = load_elevation(lonlat_tiff(tmp_path, 1, "a.tif"))
    values = np.flipud(area.heights_m)
    point_path = write_tiff(
        tmp_path / "p.tif",
        values,
        geokeys(2, 2, 4326),
        scale=(DLON, DLAT, 0.0),
        tie=(0.0, 0.0, 0.0, LON_W, LAT_N, 0.0),
    )
    point = load_elevation(point_path)
    lon, lat = LON_W + 2.3 * DLON, LAT_N - 1.6 * DLAT
    # Half a pixel in lon is 500 DLON of height, in lat 1000 DLAT (the plane's gradient).
    expected = point.height_m(lon, lat) - 1000.0 * 0.5 * DLON - 2000.0 * 0.5 * DLAT
    assert area.height_m(lon, lat) == pytest.approx(expected, abs=TOL_M)
    assert area.height_m(lon, lat) - point.height_m(lon, lat) == pytest.approx(-0.25, abs=TOL_M)


def utm_grid(raster_type=1):
    shift = 0.5 if raster_type == 1 else 0.0
    cols, rows = np.meshgrid(np.arange(9) + shift, np.arange(6) + shift)
    return plane_utm(E_W + cols * CELL, N_N - rows * CELL)


def utm_points(rng, n=300, shift=0.5):
    e = rng.uniform(E_W + shift * CELL, E_W + (8 + shift) * CELL, n)
    n_ = rng.uniform(N_N - (5 + shift) * CELL, N_N - shift * CELL, n)
    lon, lat = UTM.transform(e, n_)
    return e, n_, lon, lat


def test_geotiff_utm_reads_its_plane_at_lonlat(tmp_path):
    path = write_tiff(
        tmp_path / "utm.tif",
        utm_grid(),
        geokeys(1, 1, 32633),
        scale=(CELL, CELL, 0.0),
        tie=(0.0, 0.0, 0.0, E_W, N_N, 0.0),
    )
    dem = load_elevation(path)
    assert dem.crs == "EPSG:32633" and dem.spacing_m == (CELL, CELL)
    e, n, lon, lat = utm_points(np.random.default_rng(2))
    np.testing.assert_allclose(dem.height_m(lon, lat), plane_utm(e, n), rtol=0, atol=TOL_M)
    lon_min, lat_min, lon_max, lat_max = dem.bounds_lonlat()
    assert lon_min <= lon.min() and lon.max() <= lon_max
    assert lat_min <= lat.min() and lat.max() <= lat_max


def test_geotiff_model_transformation_south_up_and_nodata(tmp_path):
    # Rows running north (a positive pixel height), placed by ModelTransformation; one node
    # nodata in float32, as GDAL writes its lowest float.
    rows_north = np.flipud(utm_grid()).astype(np.float32)
    low = np.float32(-3.4028234663852886e38)
    rows_north[2, 3] = low
    y_south = N_N - 6 * CELL
    matrix = (CELL, 0, 0, E_W, 0, CELL, 0, y_south, 0, 0, 0, 0, 0, 0, 0, 1)
    path = write_tiff(
        tmp_path / "south-up.tif",
        rows_north,
        geokeys(1, 1, 32633),
        matrix=matrix,
        nodata="-3.4028234663852886e+38",
    )
    dem = load_elevation(path)
    e, n, lon, lat = utm_points(np.random.default_rng(3))
    h = dem.height_m(lon, lat)
    # The node [2, 3] counted from the south stands at E_W + 3.5 CELL, y_south + 2.5 CELL: the
    # four cells around it have no height, the rest read the plane (to float32 rounding of
    # heights of ~120 m: 8e-6 m).
    near = (np.abs(e - (E_W + 3.5 * CELL)) < CELL) & (np.abs(n - (y_south + 2.5 * CELL)) < CELL)
    assert near.sum() > 0 and np.all(np.isnan(h[near]))
    np.testing.assert_allclose(h[~near], plane_utm(e, n)[~near], rtol=0, atol=1e-5)
    assert "1 nodes without a height" in str(dem)


def test_geotiff_integer_heights_in_feet(tmp_path):
    data = np.array([[100, 110], [120, 130]], dtype=np.int16)
    keys = (1, 1, 0, 3, 1024, 0, 1, 2, 2048, 0, 1, 4326, 4099, 0, 1, 9002)
    path = write_tiff(
        tmp_path / "feet.tif", data, keys, scale=(1e-4, 1e-4, 0), tie=(0, 0, 0, 10, 50, 0)
    )
    dem = load_elevation(path)
    # PixelIsArea: the NW value (100 ft) at the NW pixel's centre, 110 ft east of it and 120 ft
    # south; a quarter of a pixel east and south of it, 100 + 10 / 4 + 20 / 4 ft.
    assert dem.height_m(10.00005, 49.99995) == pytest.approx(30.48, abs=1e-9)
    assert dem.height_m(10.000075, 49.999925) == pytest.approx(107.5 * 0.3048, abs=1e-9)
    assert dem.height_m(10.0001, 49.9999) == pytest.approx(115 * 0.3048, abs=1e-9)


def asc_text(x_key, x, y_key, y, values, cellsize="cellsize 5", nodata=None):
    rows, cols = values.shape
    head = [f"ncols {cols}", f"nrows {rows}", f"{x_key} {x!r}", f"{y_key} {y!r}", cellsize]
    if nodata is not None:
        head.append(f"NODATA_value {nodata}")
    return "\n".join(head + [" ".join(repr(float(v)) for v in row) for row in values]) + "\n"


def test_ascii_grid_with_prj_reads_utm_plane(tmp_path):
    values = utm_grid()
    values[0, 0] = -9999.0
    path = tmp_path / "utm.asc"
    # The lower-left corner of the lower-left cell; values at the cells' centres.
    path.write_text(asc_text("xllcorner", E_W, "yllcorner", N_N - 6 * CELL, values, nodata=-9999))
    (tmp_path / "utm.prj").write_text(pyproj.CRS("EPSG:32633").to_wkt("WKT1_ESRI"))
    dem = load_elevation(path)
    assert dem.crs == "EPSG:32633"
    e, n, lon, lat = utm_points(np.random.default_rng(4))
    h = dem.height_m(lon, lat)
    nw = (e < E_W + 1.5 * CELL) & (n > N_N - 1.5 * CELL)  # the cell next to the nodata node
    assert nw.sum() > 0 and np.all(np.isnan(h[nw]))
    np.testing.assert_allclose(h[~nw], plane_utm(e, n)[~nw], rtol=0, atol=TOL_M)


def test_ascii_grid_crs_argument_and_centres(tmp_path):
    values = utm_grid()
    path = tmp_path / "centres.asc"
    x_c, y_c = E_W + 0.5 * CELL, N_N - 5.5 * CELL
    path.write_text(asc_text("xllcenter", x_c, "yllcenter", y_c, values, "dx 5\ndy 5"))
    with pytest.raises(ElevationError, match="centres.asc: coordinates x 500002"):
        load_elevation(path)  # UTM metres with no .prj and no crs
    dem = load_elevation(path, crs="EPSG:32633")
    e, n, lon, lat = utm_points(np.random.default_rng(5))
    np.testing.assert_allclose(dem.height_m(lon, lat), plane_utm(e, n), rtol=0, atol=TOL_M)


def test_ascii_grid_lonlat_without_prj(tmp_path):
    cols, rows = np.meshgrid(np.arange(7), np.arange(5))
    values = plane_lonlat(LON_W + cols * DLON, LAT_N - rows * DLAT)
    path = tmp_path / "lonlat.asc"
    text = asc_text("xllcenter", LON_W, "yllcenter", LAT_N - 4 * DLAT, values)
    path.write_text(text.replace("cellsize 5", f"dx {DLON!r}\ndy {DLAT!r}"))
    dem = load_elevation(path)
    assert dem.crs == "EPSG:4326"
    rng = np.random.default_rng(6)
    lon = rng.uniform(LON_W, LON_W + 6 * DLON, 200)
    lat = rng.uniform(LAT_N - 4 * DLAT, LAT_N, 200)
    np.testing.assert_allclose(dem.height_m(lon, lat), plane_lonlat(lon, lat), rtol=0, atol=TOL_M)
    # 2e-4 deg of longitude at 45.8 deg N and 1.5e-4 deg of latitude, in metres.
    dx_m = math.radians(DLON) * 6_371_008.8 * math.cos(math.radians(LAT_N - 2 * DLAT))
    assert dem.spacing_m == pytest.approx((dx_m, math.radians(DLAT) * 6_371_008.8), rel=1e-12)


def test_points_on_a_lattice_are_the_grid(tmp_path):
    rng = np.random.default_rng(7)
    cols, rows = np.meshgrid(np.arange(7), np.arange(5))
    lon, lat = (LON_W + cols * DLON).ravel(), (LAT_N - rows * DLAT).ravel()
    z = plane_lonlat(lon, lat)
    lon, lat, z = lon.tolist(), lat.tolist(), z.tolist()
    order = rng.permutation(len(lon))[:-1]  # shuffled, one node left out
    lines = ["lon,lat,elevation"]
    lines += [f"{lon[k]!r},{lat[k]!r},{z[k]!r}" for k in order.tolist()]
    path = tmp_path / "lattice.csv"
    path.write_text("\n".join(lines) + "\n")
    dem = load_elevation(path)
    assert dem.heights_m.shape == (5, 7)
    assert dem.spacing_m[1] == pytest.approx(math.radians(DLAT) * 6_371_008.8, rel=1e-9)
    assert "34 survey points on a lattice" in str(dem) and "1 of 1 missing nodes filled" in str(dem)
    # Every node is the point's own height, unchanged; the missing one is filled from its
    # neighbours, which for a plane is the plane.
    lon, lat, z = np.array(lon), np.array(lat), np.array(z)
    node_rows, node_cols = 4 - rows.ravel()[order], cols.ravel()[order]  # the grid runs north
    assert np.all(dem.heights_m[node_rows, node_cols] == z[order])
    np.testing.assert_allclose(dem.height_m(lon[order], lat[order]), z[order], rtol=0, atol=TOL_M)
    lo, la = rng.uniform(LON_W, LON_W + 6 * DLON, 200), rng.uniform(LAT_N - 4 * DLAT, LAT_N, 200)
    np.testing.assert_allclose(dem.height_m(lo, la), plane_lonlat(lo, la), rtol=0, atol=TOL_M)


def test_scattered_points_are_triangulated_onto_a_grid(tmp_path):
    rng = np.random.default_rng(8)
    e = rng.uniform(E_W, E_W + 200.0, 400)
    n = rng.uniform(N_N - 100.0, N_N, 400)
    path = tmp_path / "survey.csv"
    rows = [f"{a!r},{b!r},{plane_utm(a, b)!r}" for a, b in zip(e.tolist(), n.tolist(), strict=True)]
    path.write_text("x,y,z\n" + "\n".join(rows) + "\n")
    dem = load_elevation(path, crs="EPSG:32633")
    assert "400 scattered survey points gridded linearly" in str(dem)
    # The grid's spacing is the points' mean spacing: sqrt(hull area / n), the hull a little
    # smaller than the 200 m x 100 m box the points were drawn in.
    spacing = np.array(dem.spacing_m)
    assert np.all((spacing > 0.9 * math.sqrt(200 * 100 / 400)) & (spacing <= math.sqrt(50)))
    from scipy.spatial import Delaunay

    inside = Delaunay(np.stack([e, n], axis=1))
    qe = rng.uniform(E_W - 100.0, E_W + 300.0, 2000)  # over the survey and around it
    qn = rng.uniform(N_N - 150.0, N_N + 50.0, 2000)
    lon, lat = UTM.transform(qe, qn)
    h = dem.height_m(lon, lat)
    hull = inside.find_simplex(np.stack([qe, qn], axis=1)) >= 0
    # A height needs the four nodes around the point, inside the (convex) hull: so the point is
    # in the hull, where the interpolated plane is the plane. The cells the hull's edge crosses
    # have none: a band about a cell wide, 600 m x 6.9 m of the hull's 19,500 m^2 (80 % left).
    ok = np.isfinite(h)
    assert np.all(hull[ok]) and ok.sum() > 0.7 * hull.sum()
    np.testing.assert_allclose(h[ok], plane_utm(qe, qn)[ok], rtol=0, atol=1e-8)


def test_usgs_points_are_a_lattice_read_back_exactly():
    data = np.loadtxt(USGS, delimiter=",", skiprows=1)
    dem = load_elevation(USGS)
    # 2,494 of the 2,500 nodes of a 50 x 50 lattice, 0.000145 deg (13.4 m) by 1.70e-5 deg
    # (1.89 m); the 6 missing nodes are filled linearly.
    assert dem.heights_m.shape == (50, 50)
    assert dem.spacing_m == pytest.approx((13.37, 1.891), abs=0.01)
    assert "2494 survey points on a lattice" in str(dem)
    assert "6 of 6 missing nodes filled" in str(dem)
    assert np.all(np.isfinite(dem.heights_m))
    # Every point's height is a node's, unchanged; at the point it is read back to within the
    # rounding of its coordinates against the lattice's (1e-11 of a cell).
    ix = np.rint((data[:, 0] - dem.x0) / dem.dx).astype(int)
    iy = np.rint((data[:, 1] - dem.y0) / dem.dy).astype(int)
    assert np.all(dem.heights_m[iy, ix] == data[:, 2])
    np.testing.assert_allclose(dem.height_m(data[:, 0], data[:, 1]), data[:, 2], atol=1e-9)
    assert np.nanmin(dem.heights_m) == data[:, 2].min() == pytest.approx(312.825, abs=1e-3)
    assert np.nanmax(dem.heights_m) == data[:, 2].max() == pytest.approx(323.545, abs=1e-3)
    assert dem.bounds_lonlat() == (
        data[:, 0].min(),
        data[:, 1].min(),
        pytest.approx(data[:, 0].max(), abs=1e-12),
        pytest.approx(data[:, 1].max(), abs=1e-12),
    )


def one_line_error(path, crs=None):
    with pytest.raises(ElevationError) as err:
        load_elevation(path, crs)
    message = str(err.value)
    assert "\n" not in message and message.startswith(Path(path).name + ": ")
    return message


def test_bad_files_say_so_in_one_line(tmp_path):
    def file(name, text):
        (tmp_path / name).write_text(text)
        return tmp_path / name

    assert "no such file" in one_line_error(tmp_path / "none.tif")
    assert "is a folder: allowed is a .tif/.tiff, .asc or .csv file" in one_line_error(tmp_path)
    assert "allowed are .tif/.tiff" in one_line_error(file("dem.xyz", "1 2 3\n"))
    # GeoTIFF
    assert "not a readable TIFF" in one_line_error(file("text.tif", "not a tiff\n"))
    plain = write_tiff(tmp_path / "plain.tif", np.zeros((3, 3)))
    assert "no GeoKeyDirectory tag (34735)" in one_line_error(plain)
    placed = {"scale": (1.0, 1.0, 0.0), "tie": (0, 0, 0, E_W, N_N, 0)}
    user = write_tiff(tmp_path / "user.tif", np.zeros((3, 3)), geokeys(1, 1, 32767), **placed)
    assert "ProjectedCSTypeGeoKey is 32767 (user-defined)" in one_line_error(user)
    assert load_elevation(user, crs="EPSG:32633").crs == "EPSG:32633"  # the way out it names
    unknown = write_tiff(tmp_path / "unknown.tif", np.zeros((3, 3)), geokeys(1, 1, 1234), **placed)
    assert "'EPSG:1234' is not a coordinate system pyproj knows" in one_line_error(unknown)
    empty = write_tiff(
        tmp_path / "empty.tif", np.full((3, 3), -9999.0), geokeys(1, 1, 32633), nodata="-9999",
        **placed,
    )  # fmt: skip
    assert "every height is nodata" in one_line_error(empty)
    turned = (1, 0.5, 0, E_W, 0, -1, 0, N_N, 0, 0, 0, 0, 0, 0, 0, 1)
    rotated = write_tiff(
        tmp_path / "rotated.tif", np.zeros((3, 3)), geokeys(1, 1, 32633), matrix=turned
    )
    assert "rotated" in one_line_error(rotated)
    fill = np.zeros((3, 3), np.float32)
    fill[1, 2] = np.finfo(np.float32).min  # a fill value that no GDAL_NODATA tag marks
    unmarked = write_tiff(tmp_path / "fill.tif", fill, geokeys(1, 1, 32633), **placed)
    assert (
        f"the node at x {E_W + 2.5:.10g}, y {N_N - 1.5:.10g} has a height of -3.40282e+38 m: "
        "allowed are heights -500 to 9000 m (a missing height is nodata)"
    ) in one_line_error(unmarked)
    rgb = write_tiff(tmp_path / "rgb.tif", np.zeros((3, 3, 3), np.uint8), geokeys(1, 1, 32633))
    assert "allowed is one band of heights" in one_line_error(rgb)
    # ESRI ASCII grid
    grid = np.arange(6.0).reshape(2, 3) + 101.5
    good = asc_text("xllcorner", 15.0, "yllcorner", 45.0, grid, "cellsize 0.001")
    assert "header field 'ncols' is missing" in one_line_error(
        file("a.asc", good.replace("ncols 3\n", ""))
    )
    assert "ncols = 'three': allowed is a positive integer" in one_line_error(
        file("b.asc", good.replace("ncols 3", "ncols three"))
    )
    assert "cellsize = '-1': allowed is a positive number" in one_line_error(
        file("c.asc", good.replace("cellsize 0.001", "cellsize -1"))
    )
    assert "5 heights where ncols x nrows = 3 x 2 = 6" in one_line_error(
        file("d.asc", good.replace("106.5", ""))
    )
    assert "height 'x' is not a number" in one_line_error(file("e.asc", good.replace("106.5", "x")))
    assert "has a height of 1e+300 m: allowed are heights -500 to 9000 m" in one_line_error(
        file("e2.asc", good.replace("106.5", "1e300"))
    )
    assert "unknown header key 'cols'" in one_line_error(file("f.asc", "cols 3\n" + good))
    assert "the grid has 3 x 1 nodes" in one_line_error(
        file("g.asc", good.replace("nrows 2", "nrows 1").replace("104.5 105.5 106.5", ""))
    )
    assert "is not a coordinate system pyproj knows" in one_line_error(
        file("h.asc", good), crs="EPSG:0"
    )
    # Survey points
    assert "allowed are lon_deg,lat_deg,elevation_m" in one_line_error(
        file("a.csv", "east,north,h\n1,2,3\n")
    )
    assert "no crs is given" in one_line_error(file("b.csv", "x,y,z\n1,2,3\n2,3,4\n4,1,5\n"))
    assert "0 points with a height: allowed is at least 3" in one_line_error(
        file("c.csv", "lon,lat,elevation\n")
    )
    assert "row 3 column elevation = 'high': allowed is a number" in one_line_error(
        file("d.csv", "lon,lat,elevation\n15,45,100\n15.1,45,high\n15,45.1,100\n")
    )
    for height in ("1e300", "-1e6", "inf"):
        assert (
            f"row 3 column elevation = {float(height):g} m: allowed are heights -500 to 9000 m"
        ) in one_line_error(
            file("h.csv", f"lon,lat,elevation\n15,45,100\n15.1,45,{height}\n15,45.1,100\n")
        )
    assert "the points lie on one line" in one_line_error(
        file("e.csv", "lon,lat,elevation\n15,45,1\n15.1,45.2,2\n15.3,45.6,3\n15.31,45.62,3\n")
    )
    assert "allowed are longitudes in [-180, 180]" in one_line_error(
        file("f.csv", "lon,lat,elevation\n500000,5000000,1\n500010,5000000,1\n500000,5000010,1\n")
    )
    # Two height columns (a GPS altitude beside a surveyed elevation): which is meant is not
    # guessed; numbers within 1 cm in both are one column, the first's blanks filled from the
    # other. A column named twice, in any case (pandas read the second 'alt' as 'alt.1', and
    # the first was read silently), is refused.
    assert (
        "columns elevation_m and alt give the same thing and differ by more than 0.01 (row 3: "
        "2, 40)"
    ) in one_line_error(
        file("g.csv", "lon,lat,elevation_m,alt\n15,45,1,1\n15.1,45,2,40\n15,45.1,3,3\n")
    )
    same = load_elevation(file("i.csv", "lon,lat,alt,elevation\n15,45,1,1.004\n15.1,45,,2\n"
                                        "15,45.1,3,3\n"))  # fmt: skip
    assert same.height_m(15.0, 45.1) == pytest.approx(3.0)
    assert same.height_m(15.1, 45.0) == pytest.approx(2.0)
    for header, says in (("alt,alt", "'alt' twice: "), ("ALT,alt", "'alt' twice (as 'ALT' and")):
        assert f"j.csv: column {says}" in one_line_error(
            file("j.csv", f"lon,lat,{header}\n15,45,1,5\n15.1,45,2,5\n15,45.1,3,5\n")
        )


def test_missing_optional_packages_say_how_to_install(tmp_path, monkeypatch):
    tif = lonlat_tiff(tmp_path, 1)
    asc = tmp_path / "utm.asc"
    asc.write_text(asc_text("xllcorner", E_W, "yllcorner", N_N, utm_grid()))
    monkeypatch.setitem(sys.modules, "tifffile", None)
    monkeypatch.setitem(sys.modules, "pyproj", None)
    assert "reading a GeoTIFF needs tifffile: pip install 'mcrun[hole]'" in one_line_error(tif)
    assert "needs pyproj to be placed: pip install 'mcrun[hole]'" in one_line_error(
        asc, crs="EPSG:32633"
    )


def test_a_compression_tifffile_cannot_decode_alone_names_imagecodecs(tmp_path):
    try:
        import imagecodecs  # noqa: F401
    except ImportError:
        pass
    else:
        pytest.skip("imagecodecs decodes LZW: the message is not needed")
    path = lonlat_tiff(tmp_path, 1, "lzw.tif")
    raw = path.read_bytes()
    # The Compression tag (259, SHORT, 1 value) says 1, none; make it say 5, LZW, as GDAL writes.
    entry = (259).to_bytes(2, "little") + (3).to_bytes(2, "little") + (1).to_bytes(4, "little")
    assert raw.count(entry + (1).to_bytes(4, "little")) == 1
    path.write_bytes(
        raw.replace(entry + (1).to_bytes(4, "little"), entry + (5).to_bytes(4, "little"))
    )
    assert "its compression needs the imagecodecs package: pip install imagecodecs" in (
        one_line_error(path)
    )


MAPS = Path(__file__).parent / "data" / "maps"


@pytest.mark.parametrize(
    "header",
    ["lon,lat,alt", "longitude,latitude,elevation", "Longitude, Latitude, Altitude", "lng,lat,ele"],
)
def test_common_point_headers_are_read(tmp_path, header):
    # tests/data/maps/points-lon-lat-alt.csv: a 4 x 4 lattice of a plane under lon,lat,alt.
    text = (MAPS / "points-lon-lat-alt.csv").read_text().splitlines()
    path = tmp_path / "points.csv"
    path.write_text("\n".join([header, *text[1:]]) + "\n")
    data = np.loadtxt(MAPS / "points-lon-lat-alt.csv", delimiter=",", skiprows=1)
    dem = load_elevation(path)
    assert "16 survey points on a lattice, 4 x 4 nodes" in str(dem)
    np.testing.assert_allclose(dem.height_m(data[:, 0], data[:, 1]), data[:, 2], atol=1e-9)


def test_conflicting_copies_of_a_point_are_refused_naming_its_rows():
    # tests/data/maps/points-conflicting-copies.csv: lon 15.9002, lat 45.78015 at rows 7, 8
    # and 14, once 500 m high among points of about 100 m (averaged, it was 233.5 m).
    message = one_line_error(MAPS / "points-conflicting-copies.csv")
    assert message == (
        "points-conflicting-copies.csv: the point lon 15.9002, lat 45.78015 is given 3 times "
        "with different heights (100.25, 500, 100.25 m, rows 7, 8, 14): allowed is one height "
        "per point (copies within 0.01 m are merged): remove the wrong copies"
    )


def test_identical_copies_of_a_point_are_one_point(tmp_path):
    lines = (MAPS / "points-lon-lat-alt.csv").read_text().splitlines()
    path = tmp_path / "copies.csv"
    path.write_text("\n".join([*lines, lines[6], lines[6], lines[2]]) + "\n")
    dem = load_elevation(path)
    assert "16 survey points on a lattice" in str(dem)
    assert dem.height_m(15.9002, 45.78015) == pytest.approx(100.25, abs=1e-9)


def test_conflicting_points_on_one_lattice_node_are_refused(tmp_path):
    # Two points 1e-13 deg apart (the rounding of an export) are one node: 100.25 and 120 m.
    lines = (MAPS / "points-lon-lat-alt.csv").read_text().splitlines()
    path = tmp_path / "near.csv"
    path.write_text("\n".join([*lines, "15.9002000000001,45.78015,120.0"]) + "\n")
    message = one_line_error(path)
    assert "is given 2 times (points within 1e-6 of a lattice step are one node)" in message
    assert "different heights (100.25, 120 m, rows 7, 18)" in message
