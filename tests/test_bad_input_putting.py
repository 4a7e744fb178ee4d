"""Bad input to putting (``mcrun putt``, a hole's green valued by its map): each ends with one
line on stderr naming the file and the field and what is allowed, exit code 2 and nothing
written; a damaged cached map is built again with a warning."""

import math
import re

import numpy as np
import pytest

from mcrun import putting
from mcrun.cli import COMMAND_MODULES, main
from mcrun.errors import InputError
from mcrun.hole.hole import load_hole
from mcrun.physics.turf import stimp_from_rho_g
from mcrun.putting import calibration, on_hole
from mcrun.putting import green as putting_green
from mcrun.putting.putter import PUTTERS, Putter
from mcrun.putting.roll import Surface, grid_slope
from mcrun.results.output import read_provenance
from mcrun.strokes.baseline import FOOT_M

HOLE = """
length_m = 12.0
width_m = 12.0
margin_m = 4.0
surface = "green"
shape = {{ kind = "tilted_plane", slope_deg = {slope_deg}, fall_line_deg = 180.0 }}
putting = {{ model = "{model}", resolution_m = 2.0, n = 20 }}

[turf.green]
rho_g = {rho_g}
"""

SCENARIO = """
[scenario]
name = "chip"
shots = 20
seed = 1

[hole]
file = "hole.toml"
start = [2.0, 0.0]

[launch]
ball_speed = "14 mph"
launch_angle = "30 deg"
spin = "3000 rpm"
"""

RHO_11FT = 0.0713


def _hole(tmp_path, slope_deg=1.0, rho_g=RHO_11FT, model="physics"):
    path = tmp_path / "hole.toml"
    path.write_text(HOLE.format(slope_deg=slope_deg, rho_g=rho_g, model=model))
    return path


def _one_line(capsys, *says):
    captured = capsys.readouterr()
    err = captured.err
    assert err.count("\n") == 1 and err.startswith("mcrun: error: "), err
    for text in says:
        assert text in err, err
    return captured


def _written(tmp_path):
    return sorted(p.name for p in tmp_path.iterdir() if p.name not in ("hole.toml", "s.toml"))


# --- 1. a green with no rolling resistance -------------------------------------------------------


def test_stimp_of_a_green_without_rolling_resistance_is_infinite():
    assert stimp_from_rho_g(0.0) == math.inf
    assert stimp_from_rho_g(0.131) == pytest.approx(1.82, abs=0.01)
    np.testing.assert_array_equal(stimp_from_rho_g(np.array([0.0, 0.5])) > 0, [True, True])


@pytest.mark.parametrize("rho_g", [0.0, 1e-6, 0.03, 0.5])
def test_putt_refuses_a_green_whose_speed_is_not_a_green_s(tmp_path, capsys, rho_g):
    hole = _hole(tmp_path, rho_g=rho_g)
    assert main(["putt", "--hole", str(hole), "-o", str(tmp_path / "m.parquet")]) == 2
    _one_line(capsys, "hole.toml: 'turf.green.rho_g' = ", "allowed for a green to putt on",
              "3 ft to 20 ft")  # fmt: skip
    assert _written(tmp_path) == []


@pytest.mark.parametrize("command", [["run", "s.toml", "-o", "run"], ["aim", "s.toml"]])
def test_a_run_refuses_a_putted_green_with_no_rolling_resistance(tmp_path, capsys, monkeypatch,
                                                                 command):  # fmt: skip
    _hole(tmp_path, rho_g=0.0)
    (tmp_path / "s.toml").write_text(SCENARIO)
    monkeypatch.chdir(tmp_path)
    assert main(command) == 2
    _one_line(capsys, "s.toml [hole]: 'turf.green.rho_g' = 0 ")
    assert _written(tmp_path) == []


def test_a_green_without_rolling_resistance_is_a_hole_s_where_it_is_not_putted_on(tmp_path):
    """Under the baseline's putts (``putting = "table"``) the green's turf is any turf."""
    hole = on_hole.check_putting(load_hole(_hole(tmp_path, rho_g=0.0, model="table")))
    assert hole.turf["green"].rho_g == 0.0
    lo, hi = putting_green.RHO_G_RANGE
    assert lo == pytest.approx(0.0392, abs=1e-4) and hi == pytest.approx(0.2614, abs=1e-4)


# --- 2. a damaged cached map ---------------------------------------------------------------------


def _damage(path, how):
    raw = path.read_bytes()
    if how == "truncated":
        path.write_bytes(raw[: len(raw) // 2])
    elif how == "empty":
        path.write_bytes(b"")
    else:  # a byte flipped in the middle of the arrays
        b = bytearray(raw)
        b[len(b) // 2] ^= 0xFF
        path.write_bytes(bytes(b))


@pytest.mark.parametrize("how", ["truncated", "empty", "flipped"])
def test_a_damaged_cached_map_is_built_again_with_a_warning(tmp_path, capsys, monkeypatch, how):
    monkeypatch.setenv("MCRUN_CACHE_DIR", str(tmp_path / "cache"))
    hole = load_hole(_hole(tmp_path))
    on_hole._MEMORY.clear()  # built here, in this test's cache folder
    built = on_hole.map_of_hole(hole)
    (path,) = (tmp_path / "cache" / "greens").glob("*.npz")
    _damage(path, how)
    on_hole._MEMORY.clear()
    capsys.readouterr()
    again = on_hole.map_of_hole(hole)
    err = capsys.readouterr().err
    warning = [line for line in err.splitlines() if line.startswith("mcrun: warning:")]
    assert len(warning) == 1 and str(path) in warning[0] and "building it again" in warning[0]
    np.testing.assert_array_equal(again.expected_putts, built.expected_putts)
    on_hole._MEMORY.clear()  # the file was replaced: read back without a word
    read = on_hole.map_of_hole(hole)
    assert "mcrun:" not in capsys.readouterr().err
    np.testing.assert_array_equal(read.expected_putts, built.expected_putts)


def test_the_cache_key_holds_the_putter_s_parameters(tmp_path, monkeypatch):
    from mcrun.putting.green import green_of_hole

    hole = load_hole(_hole(tmp_path))
    spec = hole.putting
    green = green_of_hole(hole, spec["cell_m"], spec["elevation"], spec["elevation_crs"])
    key = on_hole._key(green, spec)
    monkeypatch.setitem(PUTTERS, "tour", Putter("tour", 2.0, PUTTERS["tour"].speed_sd_pct))
    assert on_hole._key(green, spec) != key


# --- 3. a green steeper than its stopping slope everywhere ---------------------------------------


def test_least_slope_is_the_green_s_least_gradient():
    least_slope = putting_green.least_slope
    xs = np.arange(0.0, 5.01, 0.5)
    x, y = np.meshgrid(xs, xs)
    on = np.ones(x.shape, np.uint8)
    plane = Surface(0.05 * x - 0.02 * y, on, 0.0, 0.0, 0.5)
    assert least_slope(plane) == pytest.approx(math.hypot(0.05, 0.02))
    bowl = Surface(((x - 2.25) ** 2 + (y - 1.75) ** 2) / 20.0, on, 0.0, 0.0, 0.5)
    assert least_slope(bowl) == 0.0  # its bottom at a cell's centre, between nodes
    # Off centre: the bilinear surface's least slope, as the roll's own slope finds it on a
    # fine sample of the green.
    bowl = Surface(((x - 2.3) ** 2 + (y - 1.6) ** 2) / 20.0, on, 0.0, 0.0, 0.5)
    fine = np.linspace(0.0, 5.0, 201)
    sampled = min(grid_slope(a, b, bowl)[0] for a in fine for b in fine)
    assert least_slope(bowl) == pytest.approx(sampled, abs=1e-12)
    assert sampled > 0.01
    assert least_slope(Surface(x, np.zeros(x.shape, np.uint8), 0.0, 0.0, 0.5)) == math.inf


def test_putt_refuses_a_green_on_which_no_ball_can_rest(tmp_path, capsys):
    hole = _hole(tmp_path, slope_deg=10.0)  # 17.6 %, the Stimp 11 ft green's stopping slope 7.1 %
    assert main(["putt", "--hole", str(hole), "-o", str(tmp_path / "m.parquet"),
                 "--plot", str(tmp_path / "m.png")]) == 2  # fmt: skip
    _one_line(capsys, "hole.toml: the green is steeper than its stopping slope everywhere",
              "17.6 %", "7.1 %", "'turf.green.rho_g' = 0.0713")  # fmt: skip
    assert _written(tmp_path) == []


@pytest.mark.parametrize("command", [["run", "s.toml", "-o", "run"],
                                     ["play", "tour", "s.toml", "-o", "p.parquet"],
                                     ["play", "tour", "hole.toml", "-o", "p.parquet"]])  # fmt: skip
def test_runs_and_play_refuse_a_green_on_which_no_ball_can_rest(tmp_path, capsys, monkeypatch,
                                                               command):  # fmt: skip
    _hole(tmp_path, slope_deg=10.0)
    (tmp_path / "s.toml").write_text(SCENARIO)
    monkeypatch.chdir(tmp_path)
    assert main(command) == 2
    source = "hole.toml" if command[2] == "hole.toml" else "s.toml [hole]"
    _one_line(capsys, f"{source}: the green is steeper than its stopping slope everywhere")
    assert _written(tmp_path) == []


def test_the_library_green_can_be_putted_on():
    from mcrun.run import scenario as sc

    hole = load_hole(sc.library_folder() / "holes" / "riverside-18-green.toml")
    assert on_hole.check_putting(hole) is hole


# --- 4. a Stimp reading or a slope out of range ----------------------------------------------


@pytest.mark.parametrize(
    "options, says",
    [
        (["--stimp", "1e6ft"], "--stimp 1e6ft: allowed: 3 ft to 20 ft"),
        (["--stimp", "2ft"], "--stimp 2ft: allowed: 3 ft to 20 ft"),
        (["--stimp", "7m"], "--stimp 7m: allowed: 3 ft to 20 ft"),
        (["--slope", "1e6deg"], "--slope 1e6deg: allowed: 0 to 20 % (11.3 deg)"),
        (["--slope", "12deg"], "--slope 12deg: allowed: 0 to 20 % (11.3 deg)"),
        (["--slope", "-1deg"], "--slope -1deg: allowed: 0 to 20 %"),
    ],
)
def test_putt_refuses_a_stimp_or_slope_no_green_has(capsys, options, says):
    assert main(["putt", "--distance", "10ft", "-n", "20", *options]) == 2
    captured = _one_line(capsys, says)
    assert captured.out == ""


def test_putt_refuses_a_hole_s_stimp_out_of_range(tmp_path, capsys):
    hole = _hole(tmp_path)
    assert main(["putt", "--hole", str(hole), "-o", str(tmp_path / "m.parquet"),
                 "--stimp", "1e6ft"]) == 2  # fmt: skip
    _one_line(capsys, "--stimp 1e6ft: allowed: 3 ft to 20 ft")
    assert _written(tmp_path) == []


# --- 5. %% in the help ---------------------------------------------------------------------------


@pytest.mark.parametrize("command", sorted(COMMAND_MODULES))
def test_no_help_prints_a_doubled_percent_sign(capsys, command):
    assert main([command, "--help"]) == 0
    out = capsys.readouterr().out
    assert "%%" not in out
    if command == "putt":
        assert "--slope 2% --direction 90" in out and "3ft to 20ft" in out


# --- 6. --stimp with --hole ----------------------------------------------------------------------


def test_putt_on_a_hole_applies_stimp_and_says_so(tmp_path, capsys, monkeypatch):
    hole = _hole(tmp_path, slope_deg=10.0)  # no rest at 11 ft; at 4 ft (7.1 % -> 19.6 %) there is
    out = tmp_path / "m.parquet"
    assert main(["putt", "--hole", str(hole), "-o", str(out), "--stimp", "4ft"]) == 0
    err = capsys.readouterr().err
    assert "Stimp 4.0 ft (--stimp; the hole's green: 11.0 ft)" in err
    provenance = read_provenance(out)
    assert provenance["stimp_m"] == pytest.approx(4 * FOOT_M)
    assert provenance["stimp_from"] == "--stimp"
    assert provenance["read"] == "own" and "(own read)" in err


def test_putt_on_a_hole_reads_as_read_says(tmp_path, capsys):
    """``--read best`` maps the green with the search's reads, said on stderr and in the file."""
    hole = _hole(tmp_path, slope_deg=10.0)
    out = tmp_path / "m.parquet"
    assert main(["putt", "--hole", str(hole), "-o", str(out), "--stimp", "4ft", "--read",
                 "best", "-n", "20"]) == 0  # fmt: skip
    assert "(best read)" in capsys.readouterr().err
    assert read_provenance(out)["read"] == "best"


@pytest.mark.parametrize(
    ("field", "value", "says"),
    [
        ("line_sd_deg", math.nan, "line_sd_deg nan: allowed: a number from 0 to 10 deg"),
        ("speed_sd_pct", 1e4, "speed_sd_pct 10000.0: allowed: a number from 0 to 50 %"),
        ("pace_m", -0.43, "pace_m -0.43: allowed: a number from 0 to 3 m"),
        ("pace_slope_share", 5.0, "pace_slope_share 5.0: allowed: a number from 0 to 1"),
        ("read_sd_pct", "0.4", "read_sd_pct '0.4': allowed: a number from 0 to 50 % of slope"),
    ],
)
def test_a_putter_s_errors_are_in_range(field, value, says):
    """A Putter built by hand was putted as it was: NaN errors struck every putt to the cap
    (make 0 %, 10 putts, exit 0), a negative pace was a SystemError of the compiled read."""
    fields = {"name": "x", "line_sd_deg": 1.0, "speed_sd_pct": 3.3, field: value}
    with pytest.raises(InputError, match=re.escape(f"Putter {says}")):
        Putter(**fields)


# --- 5. a putt that does not finish, and the putting API's other arguments ----------------------


def test_putts_counted_at_the_cap_are_said(capsys):
    """3 m downhill on a 7 % slope at Stimp 11 (its stopping slope 7.13 %): a miss rolls on past
    the roll's 60 s, each counted as 10 putts (6.8 on average, exit 0), without a word."""
    assert main(["putt", "--distance", "3m", "--slope", "7%", "-n", "200"]) == 0
    captured = capsys.readouterr()
    assert "average putts:   6.805" in captured.out
    assert captured.err.startswith("mcrun: warning: 64.5 % of the holings-out were counted as 10 "
                                   "putts: a ball still rolling after 60 s")  # fmt: skip
    assert "stopping slope, 7.13 %" in captured.err
    assert main(["putt", "--distance", "3m", "--slope", "3%", "-n", "200"]) == 0
    assert capsys.readouterr().err == ""


def test_a_rate_of_0_or_100_percent_in_a_few_putts_is_said_to_say_little(capsys):
    """``-n 2``: "100.0 % +- 0.0" and exit 0, as sure as a million putts; now a warning with the
    exact one-sided 95 % bound, 1 - 0.05^(1/2) = 78 points (100 putts and more: none)."""
    assert main(["putt", "--distance", "10ft", "-n", "2"]) == 0
    captured = capsys.readouterr()
    assert "make rate:       100.0 % +- 0.0" in captured.out
    assert captured.err == (
        "mcrun: warning: the make rate and the three-putt rate are 0 or 100 % in all 2 putts: a "
        "standard error of 0 says nothing there; at 95 % the rate may be 78 points from it; more "
        "putts (-n) tell more\n"
    )


@pytest.mark.parametrize(
    ("call", "says"),
    [
        (lambda: putting.putt(10**400, 3.353, 0.02, 90.0, n=20),
         r"^distance_m 1000000.*\.\.\.: allowed: a finite number$"),
        (lambda: putting.putt(3.0, 3.353, 0.02, 90.0, n=10**400), r"^n 10000.*: allowed: a whole"),
        (lambda: putting.check_stimp("11ft"), r"^stimp_m '11ft': allowed: a number \(m\)$"),
        (lambda: putting.check_stimp(np.array([3.0, 4.0])), r"^stimp_m array\(\[3., 4.\]\)"),
        (lambda: calibration.calibration_table("tour", 10),
         r"^putter 'tour': allowed: a Putter"),
        (lambda: calibration.tour_holeouts(PUTTERS["tour"], 2.5), r"^n 2.5: allowed: a whole"),
        (lambda: calibration.slope_checks(PUTTERS["tour"], 1), r"^n 1: allowed: a whole number "
                                                               r"from 2 to 100000$"),
        (lambda: calibration.tour_holeouts(PUTTERS["tour"], 10, seed=-1), r"^seed -1: allowed"),
        # A NaN or negative drift gave a perfect green's numbers, to every digit.
        (lambda: calibration.calibration_table(PUTTERS["tour"], 10, drift_mm_per_m=math.nan),
         r"^drift_mm_per_m nan: allowed: 0 to 34 mm/m$"),
        (lambda: calibration.slope_checks(PUTTERS["tour"], 10, drift_mm_per_m=-5.0),
         r"^drift_mm_per_m -5.0: allowed: 0 to 34 mm/m$"),
    ],
)  # fmt: skip
def test_the_putting_api_names_an_argument_that_is_not_one(call, says):
    """An OverflowError formatting the message, TypeErrors of comparisons, numpy's errors."""
    with pytest.raises(InputError, match=says):
        call()


@pytest.mark.parametrize(
    ("options", "says"),
    [
        (["--drift", "４.９"], "--drift ４.９: cannot read it as a number: only ASCII digits"),
        (["--drift", "1_0"], "--drift 1_0: cannot read it as a number: '_' is not read in a "
                             "number"),
        (["-n", "1_000"], "-n '1_000': '_' is not read in a number"),
        (["--force"], "--force: is for a green's map"),
        # The range of a value converted: named by its field and the value converted.
        (["--slope", "2"], "--slope 2: allowed: 0 to 20 %"),
        (["--direction", "1e308"], "--direction 1e308: allowed: a finite number"),
        (["--distance", "inf"], "--distance: cannot read 'inf' as a length: not a finite"),
    ],
)  # fmt: skip
def test_putt_reads_its_numbers_as_every_option_does(capsys, options, says):
    """--drift read ４.９ as 4.9 and 1_0 as 10, -n 1_000 as 1000 (``parse_quantity`` refuses
    both); --force on a plane green was taken and did nothing; "slope 200 %" and "direction
    inf deg" named no option, "--distance inf" was asked for its unit."""
    assert main(["putt", "--distance", "10ft", "-n", "20", *options]) == 2
    assert _one_line(capsys, says).out == ""
