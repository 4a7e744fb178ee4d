"""Putting on a plane green (mcrun.putting): the roll against an independent integration and the
closed forms of a rolling sphere (Penner, "The physics of putting", Can. J. Phys. 80, 83 (2002)),
the Stimpmeter, the stopping slope, the cup's capture limit, the read, the Tour putter's
calibration against the PGA Tour's make rates and average putts, and ``mcrun putt``."""

import math
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mcrun.cli import main
from mcrun.physics.constants import G_MPS2
from mcrun.physics.turf import STIMP_LAUNCH_SPEED_MPS, rho_g_from_stimp
from mcrun.putting import putt
from mcrun.putting.calibration import (
    MAKE_TOLERANCE_PCT,
    PUTTS_TOLERANCE,
    SLOPE_TARGETS,
    calibration_table,
    slope_checks,
)
from mcrun.putting.cup import HOLE_RADIUS_M, V_CAPTURE_CENTRE_MPS
from mcrun.putting.greens import drift_sd
from mcrun.putting.putter import PUTTERS
from mcrun.putting.read import READ_NODES, line_at, read_lines
from mcrun.putting.roll import (
    DT_S,
    MAX_TIME_S,
    NO_SURFACE,
    STATUS_HOLED,
    STATUS_NOT_STOPPED,
    STATUS_STOPPED,
    roll,
    roll_core,
)
from mcrun.putting.stroke import (
    STRIKE_PART,
    centre_line,
    pace_speed_mps,
    plane_putt_green,
    strike_all,
    stroke_of,
)
from mcrun.quantities import InputError
from mcrun.strokes.baseline import FOOT_M

K = 5.0 / 7.0 * G_MPS2
FAR = 1000.0  # a hole far away: the cup plays no part


def _roll(v, heading_rad, slope_tan, fall_rad, rho_g, hole=(FAR, 0.0), cup=False):
    return roll(0.0, 0.0, v * math.cos(heading_rad), v * math.sin(heading_rad), slope_tan,
                math.cos(fall_rad), math.sin(fall_rad), rho_g, hole[0], hole[1], cup, DT_S,
                MAX_TIME_S)  # fmt: skip


def test_a_putt_across_a_tilted_plane_breaks_as_an_independent_integration_says():
    """1.5 m/s across a 2 % plane falling to the left, Stimp 11 ft: the stopping point of the
    RK4 roll against scipy's solve_ivp (DOP853, rtol 1e-10) of a = (5/7) g (sin b f - rho_g cos b
    v_hat), within 3 mm; the ball breaks left by decimetres."""
    rho_g, s = float(rho_g_from_stimp(11 * FOOT_M)), 0.02
    cos_b = 1.0 / math.sqrt(1.0 + s * s)
    sin_b = s * cos_b

    def rhs(t, u):
        speed = math.hypot(u[2], u[3])
        return [u[2], u[3], -K * rho_g * cos_b * u[2] / speed,
                K * (sin_b - rho_g * cos_b * u[3] / speed)]  # fmt: skip

    def slow(t, u):
        return math.hypot(u[2], u[3]) - 1e-5

    slow.terminal = True
    ref = solve_ivp(rhs, (0, 30), [0, 0, 1.5, 0], method="DOP853", rtol=1e-10, atol=1e-12,
                    events=slow)  # fmt: skip
    x_ref, y_ref = ref.y[0, -1], ref.y[1, -1]
    status, x, y, *_ = _roll(1.5, 0.0, s, math.pi / 2, rho_g)
    assert status == STATUS_STOPPED
    assert y_ref > 0.2  # breaks left, by decimetres
    assert math.hypot(x - x_ref, y - y_ref) < 0.003


@pytest.mark.parametrize("stimp_ft", [8.0, 11.0, 13.0])
def test_the_simulated_stimpmeter_rolls_the_green_s_stimp_reading(stimp_ft):
    """1.83 m/s on the level rolls the Stimp reading (USGA Stimpmeter), within 1 mm."""
    stimp_m = stimp_ft * FOOT_M
    status, x, y, *_ = _roll(STIMP_LAUNCH_SPEED_MPS, 0.0, 0.0, 0.0, rho_g_from_stimp(stimp_m))
    assert status == STATUS_STOPPED
    assert abs(x - stimp_m) < 0.001 and y == 0.0


def test_on_a_slope_steeper_than_the_stopping_slope_the_ball_never_rests():
    """Stimp 14 ft: the stopping slope atan(rho_g) is about 3 deg (Penner 2002, with the 5/7);
    a putt on a plane 0.1 % steeper never rests, 1 % less steep it stops."""
    rho_g = float(rho_g_from_stimp(14 * FOOT_M))
    assert 3.0 < math.degrees(math.atan(rho_g)) < 3.3
    assert _roll(1.0, 0.0, rho_g + 0.001, math.pi / 2, rho_g)[0] == STATUS_NOT_STOPPED
    assert _roll(1.0, 0.0, rho_g - 0.01, math.pi / 2, rho_g)[0] == STATUS_STOPPED


def _plane(slope_tan, fall_rad, stimp_ft=11.0, drift=0.0):
    rho_g = float(rho_g_from_stimp(stimp_ft * FOOT_M))
    return plane_putt_green(slope_tan, math.cos(fall_rad), math.sin(fall_rad), rho_g, drift,
                            DT_S)  # fmt: skip


def test_uphill_and_downhill_paces_follow_the_closed_form_on_the_fall_line():
    """On the fall line a rolling ball slows at (5/7) g (rho_g cos b +- sin b): the speed to roll
    3 m + 0.43 m up a 2 % slope and down it, from v^2 = 2 a d; the roll stops there within 2 mm,
    and the uphill putt needs the larger speed. The putter's pace with all the slope beyond the
    hole allowed for (share 1) is that speed; with none of it (share 0) the ball reaches the hole
    at the speed of a level green's 0.43 m: v^2 = 2 a L + 2 (5/7) g rho_g cos b p."""
    rho_g, s, d = float(rho_g_from_stimp(11 * FOOT_M)), 0.02, 3.43
    cos_b, sin_b = 1 / math.sqrt(1 + s * s), s / math.sqrt(1 + s * s)
    v_up = math.sqrt(2 * K * (rho_g * cos_b + sin_b) * d)
    v_down = math.sqrt(2 * K * (rho_g * cos_b - sin_b) * d)
    assert v_up > 1.3 * v_down
    for v, fall in ((v_up, math.pi), (v_down, 0.0)):
        status, x, y, *_ = _roll(v, 0.0, s, fall, rho_g)
        assert status == STATUS_STOPPED and abs(x - d) < 0.002
    # the putter's pace speed is the same closed form
    up, down = _plane(s, math.pi), _plane(s, 0.0)
    assert pace_speed_mps(0.0, 0.0, 3.0, 0.0, 0.43, 1.0, up, 0.0, 0.0) == pytest.approx(
        v_up, rel=1e-12
    )
    assert pace_speed_mps(0.0, 0.0, 3.0, 0.0, 0.43, 1.0, down, 0.0, 0.0) == pytest.approx(
        v_down, rel=1e-12
    )
    level = 2 * K * rho_g * cos_b * 0.43
    for green, sign in ((up, 1.0), (down, -1.0)):
        v = pace_speed_mps(0.0, 0.0, 3.0, 0.0, 0.43, 0.0, green, 0.0, 0.0)
        assert v**2 == pytest.approx(2 * K * (rho_g * cos_b + sign * sin_b) * 3.0 + level,
                                     rel=1e-12)  # fmt: skip


@pytest.mark.parametrize(
    "offset_frac, speed_mps, holed",
    [(0.0, 1.62, True), (0.0, 1.645, False), (0.5, 1.40, True), (0.5, 1.425, False)],
)
def test_capture_just_under_and_just_over_the_limit(offset_frac, speed_mps, holed):
    """The cup holds a ball crossing dead centre below about 1.63 m/s (Penner 2002), and one
    at offset b below that times the chord's fraction sqrt(1 - (b/R)^2) (Holmes 1991): at b =
    R/2, 1.41 m/s. The ball starts 1 mm short of the rim on the level (it loses < 0.001 m/s)."""
    rho_g = float(rho_g_from_stimp(11 * FOOT_M))
    b = offset_frac * HOLE_RADIUS_M
    hole = (math.sqrt(HOLE_RADIUS_M**2 - b * b) + 0.001, b)
    assert V_CAPTURE_CENTRE_MPS * math.sqrt(1 - offset_frac**2) == pytest.approx(
        {0.0: 1.63, 0.5: 1.412}[offset_frac], abs=0.001
    )
    status = _roll(speed_mps, 0.0, 0.0, 0.0, rho_g, hole=hole, cup=True)[0]
    assert (status == STATUS_HOLED) == holed


def _line(d, green, tilt=(0.0, 0.0)):
    speed = pace_speed_mps(0.0, 0.0, d, 0.0, 0.43, 1.0, green, *tilt)
    return centre_line(0.0, 0.0, d, 0.0, speed, green, *tilt)


def test_the_read_aims_against_the_break():
    """On a green falling to the left (90 deg) the putt breaks left, so the line through the
    hole's centre starts right of it (negative), and the mirror image left; straight up or down
    the fall line it is the line to the hole. A putter who misreads the green by a tilt that
    cancels its slope reads it level: straight at the hole."""
    d = 10 * FOOT_M
    left = _line(d, _plane(0.02, math.pi / 2))
    right = _line(d, _plane(0.02, -math.pi / 2))
    assert math.degrees(left) < -1.0 and right == pytest.approx(-left, abs=1e-4)
    assert abs(_line(d, _plane(0.02, math.pi))) < 1e-4
    assert abs(_line(d, _plane(0.02, math.pi / 2), (0.0, -0.02))) < 1e-4


def test_the_read_s_lines_between_its_nodes_are_the_searched_lines():
    """``read.read_lines`` interpolates each putt's perceived centre line from six: against
    the line searched on the green with the putt's own misread tilt, within 0.1 deg (5 mm at
    the hole) out to twice the Tour putter's read error, across a 2 % slope at 10 ft."""
    d, green = 10 * FOOT_M, _plane(0.02, math.pi / 3)
    stroke = stroke_of(PUTTERS["tour"])
    lines = read_lines(0.0, 0.0, d, 0.0, 0.43, green, stroke)
    assert len(lines) == len(READ_NODES)
    h = stroke.read_sd
    for tx, ty in ((2 * h, 0.0), (-1.5 * h, 1.5 * h), (0.0, -2 * h), (0.7 * h, 0.3 * h)):
        speed = pace_speed_mps(0.0, 0.0, d, 0.0, 0.43, stroke.pace_slope_share, green, tx, ty)
        exact = centre_line(0.0, 0.0, d, 0.0, speed, green, tx, ty)
        assert abs(math.degrees(line_at(lines, h, tx, ty) - exact)) < 0.1


def test_the_green_s_drift_spreads_a_rolling_ball_as_measured_on_bentgrass():
    """Pure bentgrass (4.9 mm per metre rolled at 3 m, Virginia Tech 2018): on a level Stimp
    11 ft green, balls rolled to stop at 3 m spread sideways by a standard deviation of 4.9 mm/m
    x 3 m, within 10 % (2000 balls: the estimate's own error is 1.6 %); mean 0 within 3 of its
    standard errors; the same key, the same walk."""
    rho_g = float(rho_g_from_stimp(11 * FOOT_M))
    v = math.sqrt(2 * K * rho_g * 3.0)
    sd = drift_sd(4.9)
    keys = np.random.default_rng(5).integers(0, 2**64, 2000, dtype=np.uint64)
    y = np.array([roll_core(0.0, 0.0, v, 0.0, 0.0, 1.0, 0.0, rho_g, 1e3, 0.0, False, DT_S,
                            MAX_TIME_S, NO_SURFACE, 0.0, 0.0, 0.0, sd, k)[2]
                  for k in keys])  # fmt: skip
    assert np.std(y) == pytest.approx(0.0049 * 3.0, rel=0.10)
    assert abs(np.mean(y)) < 3 * np.std(y) / math.sqrt(y.size)
    again = roll_core(0.0, 0.0, v, 0.0, 0.0, 1.0, 0.0, rho_g, 1e3, 0.0, False, DT_S, MAX_TIME_S,
                      NO_SURFACE, 0.0, 0.0, 0.0, sd, keys[0])  # fmt: skip
    assert again[2] == y[0]


def test_the_read_is_the_best_of_its_candidates_on_common_random_numbers():
    """The read's start line and pace give the least mean putts of every candidate it tried, on
    the same errors, and the result reproduces with its seed."""
    a = putt(10 * FOOT_M, 11 * FOOT_M, 0.02, 90.0, n=300, seed=3)
    b = putt(10 * FOOT_M, 11 * FOOT_M, 0.02, 90.0, n=300, seed=3)
    assert a.read == b.read and np.array_equal(a.putts, b.putts)
    assert a.read.mean_putts == min(m for _, _, m in a.read.tried)
    assert a.average_putts == pytest.approx(a.read.mean_putts)
    assert a.read.aim_deg < 0


def test_the_tour_putter_reproduces_the_tour_s_make_rates_and_average_putts():
    """On 3000 seeded Tour-like greens (Stimp 11-12 ft, slope 1-3 %, any direction, bentgrass
    drift): the make rate within 3 points of the Tour's at 3, 5, 10, 20 ft (standard error under
    0.9 points) and the average putts within 0.03 at 5, 10, 20, 30, 40 ft (standard error under
    0.012)."""
    for ft, make, make_se, tour_make, putts, putts_se, tour_putts in calibration_table(
        PUTTERS["tour"], 3000
    ):
        if tour_make is not None:
            assert make_se < 0.9 and abs(make - tour_make) <= MAKE_TOLERANCE_PCT, ft
        if tour_putts is not None:
            assert putts_se < 0.012 and abs(putts - tour_putts) <= PUTTS_TOLERANCE, ft


def test_the_tour_putter_putts_slopes_as_the_tour_does():
    """4000 putts each (the calibration's errors and greens): at 8 ft uphill putts holed 2.5-5
    points more often than downhill ones (Broadie 2019; the difference's standard error is 1.1
    points); at 10 ft with a 3 % slope at the hole the median leave of a miss 1.1 ft uphill and
    2.1 ft downhill, within 0.3 ft (Broadie 2020); 7 % (5-10 %) of 10-footers left short."""
    checks = slope_checks(PUTTERS["tour"], 4000)
    for key, (what, _, lo, hi) in SLOPE_TARGETS.items():
        assert lo <= checks[key] <= hi, (what, checks[key])


def test_mcrun_putt_prints_the_make_rate_and_the_read(capsys):
    argv = ["putt", "--distance", "10ft", "--stimp", "11ft", "--slope", "2%",
            "--direction", "90", "-n", "200"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "make rate:" in out and "average putts:" in out and "deg right of the hole" in out


@pytest.mark.parametrize(
    "options, says",
    [
        (["--distance", "10ft", "--slope", "9%"], "stopping slope"),
        (["--distance", "ten"], "--distance"),
        (["--distance", "1cm"], "distance"),
        (["--distance", "10ft", "-n", "1"], "-n"),
        (["--distance", "10ft", "-n", "1e9"], "-n '1e9': allowed: a whole number from 2 to 100000"),
        (["--distance", "10ft", "-n", "inf"], "-n 'inf': allowed: a whole number from 2 to 100000"),
        (["--distance", "10ft", "--stimp", "-3ft"], "Stimp"),
        (["--distance", "10ft", "--stimp", "3"], "--stimp 3: give its unit, e.g. 11ft"),
        (["--distance", "10"], "--distance 10: give its unit, e.g. 10ft"),  # (10 m or 10 ft?)
        (["--distance", "10ft", "--direction", "1e300"], "--direction 1e300: allowed: -360 to"),
        (["--distance", "10ft", "--drift", "40"], "--drift 40: allowed: 0 to 34"),
        (["--distance", "10ft", "--drift", "lots"], "--drift lots: allowed"),
        (["--distance", "10ft", "--read", "best"], "--read: is for a green's map (with --hole)"),
    ],
)
def test_mcrun_putt_refuses_bad_input_in_one_line(options, says, capsys):
    assert main(["putt", *options]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("mcrun: error:") and says in err


@pytest.mark.parametrize("n", [100_001, math.inf, math.nan, 2.5])
def test_putt_refuses_more_putts_than_a_hole_may_value(n):
    """``putt``'s n is that of a hole's ``[putting] n``: 100,001 would take minutes; an
    infinite n is refused as any other (``int`` of it would raise OverflowError)."""
    with pytest.raises(InputError, match=f"n {n}: allowed: a whole number from 2 to 100000"):
        putt(3.0, 3.3, 0.01, 0.0, n=n)


def test_putt_refuses_an_unknown_putter():
    with pytest.raises(InputError, match="allowed: tour, scratch, 15-handicap"):
        putt(3.0, 3.3, 0.01, 0.0, putter="pro")


@pytest.mark.determinism
def test_a_putt_is_the_same_on_one_thread_and_on_two():
    """The read's first putts (``stroke.strike_all``, 300 in two parts) and the hole-outs from
    where they stop (``rest._hole_outs``) run on every thread: each sample with its own errors,
    the same putts and the same read whatever the thread count."""
    import numba

    args = (3.0, 3.3, 0.02, 60.0)
    previous = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        one = putt(*args, n=300, seed=5)
    finally:
        numba.set_num_threads(previous)
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    try:
        two = putt(*args, n=300, seed=5)
    finally:
        numba.set_num_threads(previous)
    np.testing.assert_array_equal(one.putts, two.putts)
    assert one.read == two.read and one.average_putts == two.average_putts


def test_first_putts_struck_in_parts_on_threads_are_those_struck_in_one_go():
    """``strike_all`` on threads (a plane putt's parts of ``STRIKE_PART``) gives every putt the
    status and rest of the one lane loop a map's solver strikes them with, bit for bit: a
    putt's roll is its own, whatever part or lane it takes."""
    n = 2 * STRIKE_PART + 37
    rng = np.random.default_rng(11)
    green = plane_putt_green(0.03, 0.6, 0.8, rho_g_from_stimp(3.3), drift_sd(5.0), DT_S)
    speed, angle = 1.8 + 0.3 * rng.standard_normal(n), 0.05 * rng.standard_normal(n)
    inputs = (np.zeros(n), np.zeros(n), speed * np.cos(angle), speed * np.sin(angle),
              rng.integers(1, 2**63, n).astype(np.uint64), 3.0, 0.0, green)  # fmt: skip
    struck = {}
    for on_threads in (False, True):
        status, end_x, end_y = np.full(n, -9), np.full(n, np.nan), np.full(n, np.nan)
        strike_all(*inputs, status, end_x, end_y, on_threads)
        struck[on_threads] = status, end_x, end_y
    for alone, parts in zip(struck[False], struck[True], strict=True):
        np.testing.assert_array_equal(alone, parts)
    status = struck[True][0]
    assert (status == STATUS_HOLED).any() and (status == STATUS_STOPPED).any()


@pytest.mark.parametrize(
    "args, kwargs, says",
    [
        (("3", 3.3, 0.02, 0.0), {}, "distance_m '3': allowed: a number"),
        ((3.0, None, 0.02, 0.0), {}, "stimp_m None: allowed: a number"),
        ((3.0, 3.3, 0.02, "90"), {}, "direction_deg '90': allowed: a number"),
        ((3.0, 3.3, 0.02, 0.0), {"n": "100"}, "n '100': allowed: a number"),
        ((3.0, 3.3, 0.02, 0.0), {"putter": None}, "putter None: allowed: tour, scratch"),
        ((3.0, 3.3, 0.02, 0.0), {"read": "no"}, "read 'no': allowed: True or False"),
    ],
)
def test_putt_names_an_argument_of_the_wrong_type(args, kwargs, says):
    """A string or None where a number or a putter goes: InputError naming it (a TypeError of a
    comparison, or an AttributeError, before)."""
    with pytest.raises(InputError, match=f"^{re.escape(says)}"):
        putt(*args, **kwargs)
