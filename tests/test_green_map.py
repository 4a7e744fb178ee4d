"""Putting on a green's contour (mcrun.putting: ``roll_on``, ``green``, ``green_map``,
``on_hole``): the roll on a grid of heights against the plane's closed forms and an independent
integration on a curved green, the green's edge, the expected-putts map against the plane's
holing-out, its independence of the thread count, and a hole whose green is valued by its map
(``[hole] putting = "physics"``)."""

import math
import textwrap

import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp

from mcrun.cli import main
from mcrun.hole.hole import load_hole
from mcrun.physics.constants import G_MPS2
from mcrun.physics.turf import STIMP_LAUNCH_SPEED_MPS, rho_g_from_stimp
from mcrun.putting import putt
from mcrun.putting.green import Green
from mcrun.putting.green_map import MAP_DT_S, expected_putts_map, read_candidates
from mcrun.putting.on_hole import map_of_hole
from mcrun.putting.roll import (
    DT_S,
    LANES,
    MAX_TIME_S,
    ROLL_STATUS,
    STATUS_NOT_STOPPED,
    STATUS_OFF_GREEN,
    STATUS_STOPPED,
    Surface,
    roll,
    roll_core,
    roll_lanes,
    roll_on,
)
from mcrun.putting.stroke import PuttGreen
from mcrun.results.reader import open_run
from mcrun.run import local
from mcrun.strokes import score_shots
from mcrun.strokes.baseline import FOOT_M

K = 5.0 / 7.0 * G_MPS2
RHO_11FT = float(rho_g_from_stimp(11 * FOOT_M))


def plane_surface(slope, fall_rad, half_m=30.0, cell_m=0.25, on=None):
    """A grid of a plane falling at ``slope`` towards ``fall_rad`` (from +x towards +y)."""
    xs = np.arange(-half_m, half_m + cell_m / 2, cell_m)
    x, y = np.meshgrid(xs, xs)
    height = -slope * (x * math.cos(fall_rad) + y * math.sin(fall_rad))
    mask = np.ones(x.shape, np.uint8) if on is None else on(x, y).astype(np.uint8)
    return Surface(height, mask, float(xs[0]), float(xs[0]), cell_m)


@pytest.mark.parametrize("dt_s, ds_m, tol_m", [(DT_S, 0.0, 1e-9), (MAP_DT_S, 0.125, 1e-4)])
def test_a_putt_on_a_grid_of_a_plane_is_the_plane_s_putt(dt_s, ds_m, tol_m):
    """1.5 m/s across a 2 % plane falling to +y on a 0.25 m grid: where it stops is the plane
    roll's (the plane's own steps: to 1 nm; the map's longer steps: to 0.1 mm)."""
    surface = plane_surface(0.02, math.pi / 2)
    ref = roll(0.0, 0.0, 1.5, 0.0, 0.02, 0.0, 1.0, RHO_11FT, 1e3, 0.0, False, DT_S, MAX_TIME_S)
    got = roll_on(0.0, 0.0, 1.5, 0.0, surface, RHO_11FT, 1e3, 0.0, False, dt_s, MAX_TIME_S, ds_m)
    assert got[0] == ref[0] == STATUS_STOPPED
    assert ref[2] > 0.2  # it breaks by decimetres
    assert math.hypot(got[1] - ref[1], got[2] - ref[2]) < tol_m


def test_the_stimpmeter_on_a_level_grid_rolls_the_green_s_reading():
    """1.83 m/s on a level grid of a Stimp 11 ft green rolls 11 ft, within 1 mm."""
    got = roll_on(0.0, 0.0, STIMP_LAUNCH_SPEED_MPS, 0.0, plane_surface(0.0, 0.0), RHO_11FT, 1e3,
                  0.0, False, MAP_DT_S, MAX_TIME_S, 0.125)  # fmt: skip
    assert got[0] == STATUS_STOPPED and abs(got[1] - 11 * FOOT_M) < 0.001


def test_a_putt_across_a_bowl_follows_an_independent_integration():
    """A bowl z = r^2 / (2 R), R = 100 m, on a 0.1 m grid: a putt struck at 2 m/s from 4 m off
    its bottom, across it, stops where scipy's DOP853 on the bowl's exact gradient says
    (a = (5/7) g (sin b f - rho_g cos b v_hat)), within 2 cm (the grid's bilinear slope)."""
    radius, cell = 100.0, 0.1
    xs = np.arange(-12.0, 12.0 + cell / 2, cell)
    x, y = np.meshgrid(xs, xs)
    surface = Surface((x * x + y * y) / (2 * radius), np.ones(x.shape, np.uint8), -12.0, -12.0,
                      cell)  # fmt: skip

    def rhs(t, u):
        gx, gy = u[0] / radius, u[1] / radius
        s = math.hypot(gx, gy)
        cos_b, sin_b = 1 / math.sqrt(1 + s * s), s / math.sqrt(1 + s * s)
        fx, fy = (-gx / s, -gy / s) if s > 0 else (0.0, 0.0)
        speed = math.hypot(u[2], u[3])
        return [u[2], u[3], K * (sin_b * fx - RHO_11FT * cos_b * u[2] / speed),
                K * (sin_b * fy - RHO_11FT * cos_b * u[3] / speed)]  # fmt: skip

    def slow(t, u):
        return math.hypot(u[2], u[3]) - 1e-5

    slow.terminal = True
    ref = solve_ivp(rhs, (0, 60), [-4.0, -4.0, 2.0, 0.6], method="DOP853", rtol=1e-10,
                    atol=1e-12, events=slow)  # fmt: skip
    got = roll_on(-4.0, -4.0, 2.0, 0.6, surface, RHO_11FT, 1e3, 0.0, False, MAP_DT_S, MAX_TIME_S,
                  cell / 2)  # fmt: skip
    assert got[0] == STATUS_STOPPED
    assert math.hypot(got[1] - ref.y[0, -1], got[2] - ref.y[1, -1]) < 0.02
    assert abs(ref.y[1, -1] - (-4.0)) > 0.5  # the bowl bends it by decimetres


def test_a_putt_that_leaves_the_green_stops_at_its_edge():
    """A green that ends at x = 3 m: a putt struck hard along +x leaves it there (the nearest
    node off the green: within half a cell past the edge)."""
    surface = plane_surface(0.0, 0.0, on=lambda x, y: x <= 3.0)
    got = roll_on(0.0, 0.0, 3.0, 0.0, surface, RHO_11FT, 1e3, 0.0, False, MAP_DT_S, MAX_TIME_S,
                  0.125)  # fmt: skip
    assert got[0] == STATUS_OFF_GREEN
    assert 3.0 < got[1] <= 3.0 + 0.125 + 0.125 + 1e-9


@pytest.mark.parametrize("n, max_time_s", [(600, MAX_TIME_S), (600, 2.5), (3, MAX_TIME_S),
                                           (5, 0.0)])  # fmt: skip
def test_putts_rolled_side_by_side_are_each_the_putt_rolled_alone(n, max_time_s):
    """``roll_lanes`` (the map's putts, ``LANES`` at a time) against ``roll_core`` one putt at a
    time, on a 4 m disc sloping 2 % with the drift: every status (holed, at rest, off the
    green, still rolling at the time limit), and where each ended, bit for bit."""
    green = disc_green(slope=0.02)
    g = PuttGreen(green.surface, 0.0, 1.0, 0.0, green.rho_g, 0.01, MAP_DT_S, 0.125)
    hx, hy = 0.8, -0.4
    rng = np.random.default_rng(n)
    x, y = rng.uniform(-3.0, 3.0, n), rng.uniform(-3.0, 3.0, n)
    heading = np.arctan2(hy - y, hx - x) + rng.normal(0.0, 0.1, n)
    speed = rng.uniform(0.0, 3.0, n)
    vx, vy = speed * np.cos(heading), speed * np.sin(heading)
    keys = rng.integers(0, 2**63, n).astype(np.uint64)
    status, end_x, end_y = np.zeros(n, np.int64), np.zeros(n), np.zeros(n)
    roll_lanes(x, y, vx, vy, keys, g.slope_tan, g.fall_x, g.fall_y, g.rho_g, hx, hy, g.dt_s,
               max_time_s, g.surface, g.ds_max_m, g.drift_sd, status, end_x, end_y)  # fmt: skip
    alone = np.array([_rolled(x[i], y[i], vx[i], vy[i], keys[i], hx, hy, g, max_time_s)
                      for i in range(n)])  # fmt: skip
    assert np.array_equal(status, alone[:, 0])
    assert end_x.tobytes() == alone[:, 1].tobytes() and end_y.tobytes() == alone[:, 2].tobytes()
    if n > LANES:  # every status, but the time limit's only under a short limit
        unlimited = {STATUS_NOT_STOPPED} if max_time_s == MAX_TIME_S else set()
        assert set(status) == set(ROLL_STATUS) - unlimited


@njit(cache=True)
def _rolled(x, y, vx, vy, key, hx, hy, g, max_time_s):
    """``roll_core``'s (status, x, y) of a putt with the cup, the drift and ``max_time_s``."""
    out = roll_core(x, y, vx, vy, g.slope_tan, g.fall_x, g.fall_y, g.rho_g, hx, hy, True,
                    g.dt_s, max_time_s, g.surface, g.ds_max_m, 0.0, 0.0, g.drift_sd,
                    key)  # fmt: skip
    return out[0], out[1], out[2]


def disc_green(radius_m=4.0, slope=0.0, stimp_ft=11.0):
    surface = plane_surface(slope, math.pi, half_m=radius_m + 1.0,
                            on=lambda x, y: np.hypot(x, y) <= radius_m)  # fmt: skip
    return Green(surface, (0.0, 0.0), float(rho_g_from_stimp(stimp_ft * FOOT_M)), "disc")


@pytest.fixture(scope="module")
def flat_map():
    return expected_putts_map(disc_green(), n=400, seed=1, resolution_m=1.0, threads=2)


def test_the_map_on_a_flat_green_agrees_with_the_plane_s_holing_out(flat_map):
    """From 3 m on a flat Stimp 11 ft green: the map's expected putts and one-putt share
    against ``putting.putt`` with the putter's own read (the map's) on 4,000 holings-out,
    within three standard errors of their difference and 0.01."""
    ref = putt(3.0, 11 * FOOT_M, 0.0, 0.0, n=4000, seed=5, read=False)
    values, one, _ = flat_map.value_at(np.array([-3.0, 0.0]), np.array([0.0, 3.0]))
    se = math.hypot(float(flat_map.expected_putts_se[np.isfinite(flat_map.expected_putts_se)]
                          .max()), ref.average_putts_se)  # fmt: skip
    for v, p in zip(values, one, strict=True):
        assert abs(v - ref.average_putts) < 3 * se + 0.01
        assert abs(p - ref.make_rate) < 3 * math.sqrt(ref.make_rate * (1 - ref.make_rate) / 400)
    assert flat_map.sweep_change < 0.01


@pytest.mark.determinism
def test_the_map_is_the_same_on_one_thread_and_on_two(flat_map):
    one = expected_putts_map(disc_green(), n=400, seed=1, resolution_m=1.0, threads=1)
    for name in ("expected_putts", "expected_putts_se", "p_one_putt", "read_aim_deg"):
        np.testing.assert_array_equal(getattr(one, name), getattr(flat_map, name))


def test_a_flat_green_s_map_is_symmetric_about_the_hole(flat_map):
    """On the level every direction is the same: the map at (x, y) and (-x, -y) agree within
    their standard errors' sum (the errors are common, the geometry mirrored)."""
    v = flat_map.expected_putts
    se = flat_map.expected_putts_se
    ok = np.isfinite(v) & np.isfinite(v[::-1, ::-1])
    assert (np.abs(v - v[::-1, ::-1])[ok] <= 3 * (se + se[::-1, ::-1])[ok] + 1e-12).all()


HOLE = """
length_m = 12.0
width_m = 12.0
margin_m = 4.0
surface = "green"
shape = {{ kind = "tilted_plane", slope_deg = 1.0, fall_line_deg = 180.0 }}
putting = {putting}

[turf.green]
rho_g = 0.0713
"""


def _hole(tmp_path, putting):
    path = tmp_path / f"{abs(hash(putting))}.toml"
    path.write_text(HOLE.format(putting=putting))
    return load_hole(path)


def test_physics_putting_values_a_ball_on_the_green_by_the_map(tmp_path, monkeypatch):
    """``putting = "physics"``: a ball at rest on the green is worth the map's expected putts
    there; its one-putt and three-putt shares come with it; the map is built once, then read
    from the cache folder."""
    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    hole = _hole(tmp_path, '{ model = "physics", resolution_m = 2.0, n = 60 }')
    built = map_of_hole(hole)
    assert list((tmp_path / "cache" / "greens").glob("*.npz"))
    from mcrun.putting import on_hole

    on_hole._MEMORY.clear()
    again = map_of_hole(hole)
    np.testing.assert_array_equal(again.expected_putts, built.expected_putts)
    x = np.array([9.0, 14.0, 12.0])
    y = np.array([0.0, 0.0, 3.0])
    shots = {"finish_zone": np.array(["green"] * 3), "status": np.zeros(3, np.int64),
             "final_x_m": x, "final_y_m": y, "pin_distance_m": np.hypot(x - 12.0, y),
             "penalty_x_m": np.full(3, np.nan), "penalty_y_m": np.full(3, np.nan)}  # fmt: skip
    scored = score_shots(shots, hole, putting=built)
    value, one, three = built.value_at(x, y)
    np.testing.assert_array_equal(scored["expected_strokes_after"].to_numpy(), value)
    np.testing.assert_array_equal(scored["p_one_putt"].to_numpy(), one)
    np.testing.assert_array_equal(scored["p_three_putt"].to_numpy(), three)
    table = score_shots(shots, _hole(tmp_path, '"table"'))
    assert "p_one_putt" not in table
    assert not np.array_equal(table["expected_strokes_after"].to_numpy(), value)


CHIP = """
[scenario]
name = "chip"
shots = 40
seed = 1

[hole]
file = "{hole}"
start = [2.0, 0.0]

[launch]
ball_speed = {{ dist = "normal", mean = "14 mph", sd = "1 mph" }}
launch_angle = "30 deg"
spin = "3000 rpm"
"""


def test_a_run_with_physics_putting_writes_the_putting_shares(tmp_path, monkeypatch):
    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    hole = tmp_path / "hole.toml"
    hole.write_text(HOLE.format(putting='{ model = "physics", resolution_m = 2.0, n = 60 }'))
    scenario = tmp_path / "s.toml"
    scenario.write_text(CHIP.format(hole=hole.name))
    result = local.run_scenario(scenario, out_dir=tmp_path / "run", progress=False)
    shots, summary = result.shots(), result.summary()
    on = shots["finish_zone"].astype(str) == "green"
    assert on.sum() > 10
    assert np.isfinite(shots.loc[on, "p_one_putt"]).all()
    assert summary.loc[0, "n_on_green"] == on.sum()
    assert summary.loc[0, "p_one_putt_green"] == pytest.approx(shots.loc[on, "p_one_putt"].mean())
    assert open_run(tmp_path / "run") is not None


@pytest.mark.parametrize(
    "putting, says",
    [
        ('"exact"', "'putting.model' = 'exact': choose table, physics"),
        ('{ model = "physics", putter = "pro" }', "'putting.putter' = 'pro': choose"),
        ('{ model = "physics", n = 1 }', "'putting.n' = 1 must be a whole number"),
        ('{ model = "physics", speed = 2 }', "'putting.speed': unknown key"),
        ('{ model = "physics", read = "perfect" }', "'putting.read' = 'perfect': choose own, best"),
        (
            '{ model = "physics", drift_mm_per_m = 40 }',
            "'putting.drift_mm_per_m' = 40 must be a number in [0, 34]",
        ),
    ],
)
def test_bad_putting_settings_give_one_line(tmp_path, capsys, putting, says):
    path = tmp_path / "hole.toml"
    path.write_text(HOLE.format(putting=putting))
    assert main(["hole", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert says in err and len(err.splitlines()) == 1


def test_a_physics_putting_run_on_dask_is_the_local_run(tmp_path, monkeypatch):
    """The same run on a local Dask cluster: every shot, its putting shares and the summary's,
    bit for bit (each worker reads the map its own process built or the cache folder holds)."""
    pytest.importorskip("distributed")
    from mcrun.results.reader import read_shots
    from mcrun.run import distributed

    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    hole = tmp_path / "hole.toml"
    hole.write_text(HOLE.format(putting='{ model = "physics", resolution_m = 2.0, n = 60 }'))
    scenario = tmp_path / "s.toml"
    scenario.write_text(CHIP.format(hole=hole.name))
    local.run_scenario(scenario, out_dir=tmp_path / "local", progress=False, chunk_size=16)
    distributed.run_scenario(scenario, out_dir=tmp_path / "dask", progress=False, chunk_size=16,
                             workers=2)  # fmt: skip
    a, b = read_shots(tmp_path / "local"), read_shots(tmp_path / "dask")
    assert np.isfinite(a["p_one_putt"]).sum() > 10
    import pandas as pd

    pd.testing.assert_frame_equal(a, b, check_exact=True)
    sa = pd.read_parquet(tmp_path / "local" / "summary.parquet")
    sb = pd.read_parquet(tmp_path / "dask" / "summary.parquet")
    for name in ("n_on_green", "p_one_putt_green", "p_three_putt_green"):
        assert sa.loc[0, name] == sb.loc[0, name]


def test_a_putt_down_the_fall_line_holds_its_line_better_than_one_up_it():
    """Why this model finds putts from above the hole no harder than from below: with the same
    start-line error (1.5 deg), a 3 m putt straight down a 3 % Stimp 11 ft plane passes closer to
    the hole's centre than the same putt straight up it (gravity adds speed along the fall line
    only, so a downhill ball's heading turns back towards it and an uphill ball's away), each
    struck to finish 0.43 m past on the straight line (v^2 = 2 a (L + 0.43))."""
    s, d, err = 0.03, 3.0, math.radians(1.5)
    cos_b, sin_b = 1 / math.sqrt(1 + s * s), s / math.sqrt(1 + s * s)
    miss = {}
    for name, fall in (("down", 0.0), ("up", math.pi)):
        a = K * (RHO_11FT * cos_b - sin_b * math.cos(fall))
        v = math.sqrt(2 * a * (d + 0.43))
        out = roll(0.0, 0.0, v * math.cos(err), v * math.sin(err), s, math.cos(fall),
                   math.sin(fall), RHO_11FT, d, 0.0, False, DT_S, MAX_TIME_S)  # fmt: skip
        miss[name] = out[4]
    assert miss["down"] < miss["up"] - 0.005
    assert miss["up"] > d * math.tan(err)  # the uphill ball's error grows past the straight line


def test_a_survey_of_the_green_alone_gives_its_contour(tmp_path):
    """``[hole.putting] elevation``: survey points of Riverside 18's green only (a plane rising
    3 % towards the east), the hole itself flat: the green's slope is the survey's, 3 %
    towards the east, within 0.1 % at the pin; a survey that misses the green is refused in one
    line."""
    from mcrun.putting.green import GreenError, green_of_hole

    hole_file = tmp_path / "green.toml"
    library = sc_folder() / "holes"
    pin_lon, pin_lat = load_hole(library / "riverside-18-green.toml").pin_lonlat
    lon, lat = np.meshgrid(np.linspace(pin_lon - 0.0008, pin_lon + 0.0008, 41),
                           np.linspace(pin_lat - 0.0006, pin_lat + 0.0006, 31))  # fmt: skip
    east_m = (lon - pin_lon) * 111_320.0 * math.cos(math.radians(pin_lat))
    rows = ["lon,lat,alt"] + [f"{a:.7f},{b:.7f},{100.0 + 0.03 * e:.4f}"
                              for a, b, e in zip(lon.ravel(), lat.ravel(), east_m.ravel(),
                                                 strict=True)]  # fmt: skip
    (tmp_path / "survey.csv").write_text("\n".join(rows) + "\n")
    hole_file.write_text(
        textwrap.dedent(f"""
        map = "{library / "riverside-zagreb.osm.geojson"}"
        hole = 18
        tee = [15.895075, 45.779224]
        margin_m = 30.0
        putting = {{ model = "physics", elevation = "survey.csv" }}
    """)
    )
    hole = load_hole(hole_file)
    green = green_of_hole(hole, None, hole.putting["elevation"], None)
    from mcrun.putting.roll import grid_slope

    slope, fx, fy = grid_slope(*green.pin_xy_m, green.surface)
    # East in the hole's frame: its direction from the frame's own conversion.
    x0, y0 = hole.frame.to_xy(pin_lon, pin_lat)
    x1, y1 = hole.frame.to_xy(pin_lon + 0.0001, pin_lat)
    ex, ey = np.array([x1 - x0, y1 - y0]) / math.hypot(x1 - x0, y1 - y0)
    assert abs(slope - 0.03) < 0.001
    assert fx * ex + fy * ey < -0.999  # it falls towards the west
    (tmp_path / "survey.csv").write_text("lon,lat,alt\n15.0,45.0,1\n15.001,45.0,1\n15.0,45.001,1\n"
                                         "15.001,45.001,1\n")  # fmt: skip
    with pytest.raises(GreenError, match="does not cover the green"):
        green_of_hole(hole, None, hole.putting["elevation"], None)


def sc_folder():
    from mcrun.run import scenario as sc

    return sc.library_folder()


def test_a_changed_putter_of_the_same_name_builds_a_new_map(tmp_path, monkeypatch):
    """The map's cache is keyed on the putter's parameters, not its name: the Tour putter with
    other errors (a recalibration) builds a map of its own, with other values; the same
    parameters under another name find the first one."""
    import dataclasses

    from mcrun.putting import on_hole
    from mcrun.putting.putter import PUTTERS

    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    on_hole._MEMORY.clear()
    hole = _hole(tmp_path, '{ model = "physics", resolution_m = 2.0, n = 40 }')
    first = map_of_hole(hole)
    folder = tmp_path / "cache" / "greens"
    assert len(list(folder.glob("*.npz"))) == 1
    tour = PUTTERS["tour"]
    other = dataclasses.replace(tour, line_sd_deg=2 * tour.line_sd_deg)
    monkeypatch.setitem(PUTTERS, "tour", other)
    on_hole._MEMORY.clear()
    second = map_of_hole(hole)
    assert len(list(folder.glob("*.npz"))) == 2
    assert not np.array_equal(np.nan_to_num(first.expected_putts),
                              np.nan_to_num(second.expected_putts))  # fmt: skip
    monkeypatch.setitem(PUTTERS, "tour", tour)
    monkeypatch.setitem(PUTTERS, "twin", dataclasses.replace(tour, name="twin"))
    on_hole._MEMORY.clear()
    twin = map_of_hole(hole, putter="twin")
    assert len(list(folder.glob("*.npz"))) == 2
    np.testing.assert_array_equal(twin.expected_putts, first.expected_putts)


def test_a_map_that_cannot_be_cached_leaves_no_part_and_says_so(tmp_path, monkeypatch, capsys):
    """A full cache disk as the map is saved: the part written stayed (one a process, each run
    building the map again without a word); now it is removed and one line says why."""
    import errno

    from mcrun.putting import on_hole

    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    on_hole._MEMORY.clear()
    saved = np.savez

    def full_disk(file, **arrays):
        saved(file, **arrays)  # (the part written, then the disk full)
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(on_hole.np, "savez", full_disk)
    built = map_of_hole(_hole(tmp_path, '{ model = "physics", resolution_m = 2.0, n = 40 }'))
    assert built.expected_putts.size and not list((tmp_path / "cache" / "greens").iterdir())
    said = [line for line in capsys.readouterr().err.splitlines() if "cannot be cached" in line]
    assert said == [f"mcrun: warning: the expected-putts map cannot be cached in "
                    f"{tmp_path / 'cache' / 'greens'} (No space left on device): it is built "
                    "again by each run"]  # fmt: skip


def test_the_map_s_read_is_the_hole_s_and_keys_its_cache(tmp_path, monkeypatch):
    """``[hole.putting] read``: the putter's own read by default, the best of the search's
    reads with "best", each a map of its own in the cache; the best read's expected putts are
    nowhere more than the own read's (its candidates include the own read's pace on the
    centre line it perceives, on the same errors) beyond the later putts' sampling."""
    from mcrun.putting import on_hole
    from mcrun.putting.putter import PUTTERS

    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    on_hole._MEMORY.clear()
    own = map_of_hole(_hole(tmp_path, '{ model = "physics", resolution_m = 2.0, n = 40 }'))
    best = map_of_hole(_hole(tmp_path, '{ model = "physics", resolution_m = 2.0, n = 40, '
                             'read = "best" }'))  # fmt: skip
    assert own.settings["read"] == "own" and best.settings["read"] == "best"
    assert len(list((tmp_path / "cache" / "greens").glob("*.npz"))) == 2
    ok = own.valid & best.valid & (own.expected_putts > 0)  # (a node in the hole: no putt)
    assert (np.unique(own.read_pace_m[ok]) == [PUTTERS["tour"].pace_m]).all()
    assert (best.expected_putts[ok] <= own.expected_putts[ok] + 0.05).all()
    assert best.expected_putts[ok].mean() < own.expected_putts[ok].mean()


@pytest.mark.parametrize("read", ["own", "best"])
def test_on_the_library_s_green_below_the_hole_is_cheaper_than_above(read):
    """Riverside 18's green (2 % back to front, Stimp 11 ft), the Tour putter with its read
    error and the green's drift: from 2, 3, 5 and 8 m straight below the pin the expected putts
    are fewer than from as far straight above it, each putt read as the map reads it and holed
    out on 4000 common errors (antithetic). With the putter's own read (the map's default)
    above is dearer by 0.023, 0.022, 0.030 and 0.027 putts: 2.2, 1.9, 3.0 and 3.2 times the
    paired difference's standard error (about 0.01); held to 1.5 at every distance. With the
    best of the search's reads by 0.012 (1.1: not significantly), 0.021 (1.9), 0.031 (3.0)
    and 0.029 (3.3); held to 0 at 2 and 3 m, 2 at 5 and 8. Before the read error and the
    drift it was cheaper by 0.03-0.14."""
    from mcrun.putting.green import green_of_hole
    from mcrun.putting.putter import PUTTERS, putter_errors
    from mcrun.putting.read import READ_NODES, search
    from mcrun.putting.rest import hole_out_values
    from mcrun.putting.stroke import PuttGreen, stroke_of
    from mcrun.run import scenario as sc

    green = green_of_hole(load_hole(sc.library_folder() / "holes" / "riverside-18-green.toml"))
    s = green.surface
    on = PuttGreen(s, 0.0, 1.0, 0.0, green.rho_g, green.drift_sd, MAP_DT_S, s.cell_m / 2.0)
    n = 4000
    z, keys = putter_errors(n, 0)
    rest = hole_out_values(z, keys)
    px, py = green.pin_xy_m
    tour = PUTTERS["tour"]
    paces, steps = read_candidates(read, tour)
    for d in (2.0, 3.0, 5.0, 8.0):
        putts = {}
        for name, x in (("below", px - d), ("above", px + d)):
            putts[name] = np.zeros(n)
            search(x, py, px, py, on, stroke_of(tour), z, keys, rest, paces, steps,
                   np.zeros((len(paces) + len(steps), 3)), putts[name],
                   np.zeros(len(READ_NODES)))  # fmt: skip
        gap = putts["above"] - putts["below"]
        se = gap.std(ddof=1) / math.sqrt(n)
        least = 1.5 if read == "own" else (0.0 if d < 5.0 else 2.0)
        assert gap.mean() > least * se, (d, gap.mean(), se)


def test_a_hole_s_scores_never_build_its_green_s_map(monkeypatch):
    """Scoring shots on a hole whose green its map values (``results.on_hole.scores``) has no
    side effect: the map is the run layer's to prepare (``run.plan.putting_of``); without it the
    scoring is refused, and no map is built."""
    from mcrun.engine.schema import N_OUTCOME
    from mcrun.putting import on_hole as putting_on_hole
    from mcrun.results import on_hole
    from mcrun.run import scenario as sc

    hole = load_hole(sc.library_folder() / "holes" / "riverside-18-green.toml")

    def built(*args, **kwargs):
        raise AssertionError("a map was built while scoring")

    monkeypatch.setattr(putting_on_hole, "expected_putts_map", built)
    outcomes = np.zeros((4, N_OUTCOME), order="F")
    with pytest.raises(ValueError, match="map_of_hole"):
        on_hole.scores(hole, outcomes)
