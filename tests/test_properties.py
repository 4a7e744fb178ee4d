"""Properties that must hold for every input in the documented ranges (hypothesis).

- a bounce never creates energy (translational plus rotational), in 3D, on tilted ground, for
  any turf that ``turf.check_turf`` accepts;
- a shot always ends with a known status, and an "ok" shot has finite outcome fields;
- mirror symmetry: the mirror image of a shot (spin axis, azimuth, crosswind, fall line
  negated) lands and stops at the mirror image of its points.

Derandomized with modest example counts, so that CI runs the same cases every time.
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mcrun import status
from mcrun.api import RANGES, simulate
from mcrun.physics.aero import MODELS
from mcrun.physics.bounce import bounce
from mcrun.physics.constants import BALL_INERTIA_FACTOR, BALL_RADIUS_M
from mcrun.physics.turf import LIMITS, PRESETS, Turf, check_turf

SETTINGS = settings(
    max_examples=150,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)
FEW = settings(SETTINGS, max_examples=60)


def in_range(name, **kwargs):
    lo, hi = RANGES[name]
    return st.floats(lo, hi, allow_nan=False, **kwargs)


def unit_vectors():
    return st.tuples(*(st.floats(-1.0, 1.0),) * 3).filter(lambda v: 1e-3 < np.linalg.norm(v))


@st.composite
def turfs(draw):
    """Any turf inside ``check_turf``'s limits: restitution coefficients as in eq. (5), up to
    their documented bound, with e(v) not growing with speed."""
    e0 = draw(st.floats(-9.9, 9.9))
    e1 = draw(st.floats(-9.9, 0.0))
    e2 = draw(st.floats(-9.9, 9.9))
    # The slope e1 + 2 e2 v of (5a) stays <= 0 up to the break.
    longest = 200.0 if e2 <= 0.0 else min(200.0, -e1 / (2.0 * e2))
    e_break = draw(st.floats(0.0, 0.999)) * longest
    at_break = e0 + e1 * e_break + e2 * e_break * e_break
    return check_turf(
        Turf(
            mu=draw(st.floats(0.0, 2.0)),
            softness=draw(st.floats(0.0, 5.0)),
            e0=e0,
            e1=e1,
            e2=e2,
            e_break_speed_mps=e_break,
            e_high=draw(st.floats(0.0, 1.0)) * min(max(at_break, 0.0), 1.0),
            rho_g=draw(st.floats(0.0, 5.0)),
            critical_height_m=draw(st.floats(*LIMITS["critical_height_m"])),
        )
    )


def kinetic_energy_per_mass(v, w):
    """(1/2) |v|^2 + (1/2) (2/5) r^2 |w|^2, per kilogram of ball."""
    return 0.5 * float(np.dot(v, v)) + 0.5 * BALL_INERTIA_FACTOR * BALL_RADIUS_M**2 * float(
        np.dot(w, w)
    )


@SETTINGS
@given(
    speed=st.floats(0.1, 120.0),
    direction=unit_vectors(),
    spin=st.floats(0.0, 2000.0),
    spin_axis=unit_vectors(),
    slope_deg=in_range("slope_deg"),
    fall_line_deg=in_range("fall_line_deg"),
    turf=turfs(),
)
def test_bounce_creates_no_energy(
    speed, direction, spin, spin_axis, slope_deg, fall_line_deg, turf
):
    """Penner's bounce (3D form of eqs. 2-8) never returns more kinetic energy than it got: the
    normal impulse has e <= 1 and the friction impulse only ever reduces the slip."""
    slope = math.radians(slope_deg)
    fall = math.radians(fall_line_deg)
    n = np.array([math.sin(slope) * math.cos(fall), math.sin(slope) * math.sin(fall)])
    n = np.append(n, math.cos(slope))
    v = speed * np.asarray(direction) / np.linalg.norm(direction)
    if v @ n > 0.0:
        v = v - 2.0 * (v @ n) * n  # the ball moves into the ground
    if v @ n > -1e-6 * speed:
        v = v - 1e-3 * speed * n
    w = spin * np.asarray(spin_axis) / np.linalg.norm(spin_axis)
    before = kinetic_energy_per_mass(v, w)
    out = bounce(*v, *w, *n, turf)
    after = kinetic_energy_per_mass(np.array(out[0:3]), np.array(out[3:6]))
    assert all(math.isfinite(x) for x in out[:9])
    assert after <= before * (1.0 + 1e-12)
    # The restitution of eq. (5) stays in [0, 1] for any coefficients check_turf accepts.
    assert 0.0 <= out[7] <= 1.0


@FEW
@given(
    speed=in_range("ball_speed_mps"),
    angle=in_range("launch_angle_deg"),
    azimuth=in_range("azimuth_deg"),
    spin=in_range("spin_radps"),
    axis=in_range("spin_axis_deg"),
    wind=st.tuples(st.floats(-35.0, 35.0), st.floats(-35.0, 35.0)),
    profile=st.sampled_from(["uniform", "log", "power"]),
    model=st.sampled_from(sorted(MODELS)),
    turf=st.sampled_from(sorted(PRESETS)),
    slope=in_range("slope_deg"),
    fall_line=in_range("fall_line_deg"),
    density=in_range("air_density_kgpm3"),
    dt=st.floats(1e-3, RANGES["dt_s"][1]),
)
def test_shot_always_ends_with_a_status(
    speed, angle, azimuth, spin, axis, wind, profile, model, turf, slope, fall_line, density, dt
):
    """Any shot inside ``api.RANGES`` ends with a known status, and an "ok" one has every
    outcome field finite; on a slope under half the steepest its turf holds, it ends "ok"
    (``rolls_to_rest``). (Steps below 1 ms are in range too; they only cost time.)"""
    out = simulate(
        ball_speed_mps=speed,
        launch_angle_deg=angle,
        azimuth_deg=azimuth,
        spin_radps=spin,
        spin_axis_deg=axis,
        wind_mps=wind,
        wind_profile=profile,
        aero_model=model,
        turf=turf,
        slope_deg=slope,
        fall_line_deg=fall_line,
        air_density_kgpm3=density,
        dt_s=dt,
    ).outcome
    assert out["status"] in status.NAMES
    if out["status"] == status.OK:
        assert all(math.isfinite(v) for v in out.values()), out
    if rolls_to_rest(slope, turf):
        assert out["status"] == status.OK, out


def tipping(slope_deg, turf):
    """tan(slope) / rho_g: under 1 the turf's rolling resistance holds a ball on the slope
    (physics.md: only a slope steeper than atan(rho_g) keeps it going), over 1 it does not."""
    return math.tan(math.radians(slope_deg)) / PRESETS[turf].rho_g


def rolls_to_rest(slope_deg, turf):
    """A slope under half the steepest its turf holds: down it the roll still slows at half
    the rate it does on level ground, at least (5/7) g rho_g / 2 (0.46 m/s^2 on the green),
    and any ball in range stops well inside the roll's bounds (120 s, 1000 m)."""
    return tipping(slope_deg, turf) < 0.5


def test_the_share_of_shots_that_end_ok_is_that_of_the_slopes_that_hold_them():
    """400 shots drawn (seeded) over the ranges of ``test_shot_always_ends_with_a_status``: the
    slope uniform in 0-45 deg, the turf among the presets. A ball ends "ok" where its turf holds
    it on the slope, and only there, so that the share of "ok" shots lies between the share
    drawn under half the tipping slope (every one of those must stop; expected
    mean(atan(rho_g / 2)) / 45 deg = 0.20 over the presets) and the share drawn under the
    tipping slope (expected mean(atan(rho_g)) / 45 deg = 0.37). A kernel that let every shot
    roll on (``not_stopped``) or stopped every ball fails it."""
    rng = np.random.default_rng(21)
    names = sorted(PRESETS)
    models = sorted(MODELS)
    ended, holds, gentle = [], [], []
    for _ in range(400):
        turf = names[rng.integers(len(names))]
        slope = rng.uniform(*RANGES["slope_deg"])
        out = simulate(
            ball_speed_mps=rng.uniform(*RANGES["ball_speed_mps"]),
            launch_angle_deg=rng.uniform(*RANGES["launch_angle_deg"]),
            azimuth_deg=rng.uniform(*RANGES["azimuth_deg"]),
            spin_radps=rng.uniform(*RANGES["spin_radps"]),
            spin_axis_deg=rng.uniform(*RANGES["spin_axis_deg"]),
            wind_mps=tuple(rng.uniform(-35.0, 35.0, 2)),
            wind_profile=("uniform", "log", "power")[rng.integers(3)],
            aero_model=models[rng.integers(len(models))],
            turf=turf,
            slope_deg=slope,
            fall_line_deg=rng.uniform(*RANGES["fall_line_deg"]),
            air_density_kgpm3=rng.uniform(*RANGES["air_density_kgpm3"]),
            dt_s=rng.uniform(1e-3, RANGES["dt_s"][1]),
        ).outcome
        ended.append(out["status"] == status.OK)
        holds.append(tipping(slope, turf) < 1.0)
        gentle.append(rolls_to_rest(slope, turf))
    ended, holds, gentle = map(np.array, (ended, holds, gentle))
    assert 0.15 < gentle.mean() < 0.25 and 0.32 < holds.mean() < 0.42  # the draw is as expected
    assert ended[gentle].all()
    assert not ended[~holds].any()
    assert gentle.mean() <= ended.mean() <= holds.mean()


def mirrored(kwargs):
    m = dict(kwargs)
    m["spin_axis_deg"] = -kwargs["spin_axis_deg"]
    m["azimuth_deg"] = -kwargs["azimuth_deg"]
    m["wind_mps"] = (kwargs["wind_mps"][0], -kwargs["wind_mps"][1])
    m["fall_line_deg"] = -kwargs["fall_line_deg"]
    return m


def assert_mirror_images(a, b):
    assert a["status"] == b["status"]
    for key in ("carry_m", "apex_m", "landing_speed_mps", "run_m", "total_m", "final_x_m"):
        assert b[key] == pytest.approx(a[key], abs=1e-9), key
    for key in ("carry_lateral_m", "final_y_m"):
        assert b[key] == pytest.approx(-a[key], abs=1e-9), key
    assert b["bounces"] == a["bounces"]


@FEW
@given(
    speed=st.floats(20.0, 80.0),
    angle=st.floats(5.0, 45.0),
    azimuth=in_range("azimuth_deg"),
    spin=st.floats(100.0, 1200.0),
    axis=in_range("spin_axis_deg"),
    wind=st.tuples(st.floats(-15.0, 15.0), st.floats(-15.0, 15.0)),
    profile=st.sampled_from(["uniform", "log"]),
    turf=st.sampled_from(["green", "firm_green", "fairway"]),
)
def test_mirror_symmetry(speed, angle, azimuth, spin, axis, wind, profile, turf):
    """Spin axis -a, azimuth -b and crosswind -w give the mirror image of +a, +b, +w: equal
    carry and total, lateral and final y negated, to 1e-9 m (level ground)."""
    kwargs = dict(
        ball_speed_mps=speed,
        launch_angle_deg=angle,
        azimuth_deg=azimuth,
        spin_radps=spin,
        spin_axis_deg=axis,
        wind_mps=wind,
        wind_profile=profile,
        turf=turf,
        fall_line_deg=0.0,
    )
    assert_mirror_images(simulate(**kwargs).outcome, simulate(**mirrored(kwargs)).outcome)


@FEW
@given(
    speed=st.floats(20.0, 80.0),
    angle=st.floats(5.0, 45.0),
    spin=st.floats(100.0, 1200.0),
    axis=st.floats(-30.0, 30.0),
    slope=st.floats(0.0, 2.0),  # see test_ball_stops_on_a_gentle_downhill for steeper ones
    fall_line=in_range("fall_line_deg"),
    turf=st.sampled_from(["green", "firm_green", "fairway"]),
)
def test_slope_mirror_symmetry(speed, angle, spin, axis, slope, fall_line, turf):
    """On a slope, the fall line +c and -c (with the spin axis negated too) give mirror-image
    runs: equal run and total, final y negated, to 1e-9 m."""
    kwargs = dict(
        ball_speed_mps=speed,
        launch_angle_deg=angle,
        azimuth_deg=0.0,
        spin_radps=spin,
        spin_axis_deg=axis,
        wind_mps=(0.0, 0.0),
        turf=turf,
        slope_deg=slope,
        fall_line_deg=fall_line,
    )
    a = simulate(**kwargs).outcome
    assert a["status"] == status.OK
    assert_mirror_images(a, simulate(**mirrored(kwargs)).outcome)


def test_slope_symmetry_is_not_vacuous():
    """The slope changes the run, and a fall line to the right moves the ball right: the
    symmetry above compares different shots, not a slope the kernel ignores."""
    base = dict(ball_speed_mps=60.0, launch_angle_deg=12.0, spin_radps=300.0, slope_deg=2.0)
    level = simulate(**{**base, "slope_deg": 0.0}).outcome
    right = simulate(**base, fall_line_deg=90.0).outcome
    left = simulate(**base, fall_line_deg=-90.0).outcome
    assert right["final_y_m"] > 0.1
    assert left["final_y_m"] == pytest.approx(-right["final_y_m"], abs=1e-9)
    assert abs(level["final_y_m"]) < 1e-9


@pytest.mark.parametrize("slope_deg", [3.0, 5.0])
def test_ball_stops_on_a_gentle_downhill(slope_deg):
    """physics.md: only a slope steeper than atan(rho_g) (7.5 deg on the green) keeps the ball
    going; a drive onto a gentler downhill comes to rest."""
    out = simulate(
        ball_speed_mps=70.0, launch_angle_deg=11.0, spin_radps=280.0, slope_deg=slope_deg
    ).outcome
    assert out["status"] == status.OK


# --- fast and shallow impacts: eq. (8) extrapolated, and bounded ----------------------------


@SETTINGS
@given(
    speed=st.floats(0.1, 120.0),
    angle_deg=st.floats(0.0, 89.99),
    topspin=st.floats(0.0, 2000.0),
    sidespin=st.floats(-2000.0, 2000.0),
    turf=turfs(),
)
def test_no_backspin_no_backward_bounce(speed, angle_deg, topspin, sidespin, turf):
    """A ball without backspin never bounces backwards off level turf, however fast and shallow
    it comes in and whatever the turf: bounce.no_return_tilt bounds eq. (8). (Unbounded, a
    61 m/s impact at 86.5 deg came back at 20 m/s.)"""
    a = math.radians(angle_deg)
    v = (speed * math.sin(a), 0.0, -speed * math.cos(a))
    # Core frame (y to the left): backspin is about -y, so topspin is about +y.
    w = (0.0, topspin, sidespin)
    out = bounce(*v, *w, 0.0, 0.0, 1.0, turf)
    assert out[0] >= -1e-9 * speed


@FEW
@given(
    speed=in_range("ball_speed_mps"),
    angle=in_range("launch_angle_deg"),
    turf=st.sampled_from(sorted(PRESETS)),
)
def test_no_backspin_shot_never_comes_back(speed, angle, turf):
    """A shot without spin on level ground rests at or beyond its landing point: run >= 0.
    (``--ball-speed 90 --launch 2 --spin 30`` ran -13.3 m; a drive launched at -10 deg ended at
    -31 m.)"""
    out = simulate(ball_speed_mps=speed, launch_angle_deg=angle, spin_radps=0.0, turf=turf).outcome
    assert out["status"] == status.OK
    assert out["run_m"] >= -1e-9


def totals(**kwargs):
    name, values = next((k, v) for k, v in kwargs.items() if isinstance(v, np.ndarray))
    return np.array([simulate(**{**kwargs, name: x}).total_m for x in values])


@pytest.mark.parametrize("turf", ["green", "fairway", "rough"])
@pytest.mark.parametrize(
    "launch_deg, spin_radps", [(8.0, 0.0), (10.9, 281.0), (20.0, 600.0), (35.0, 900.0)]
)
def test_total_grows_with_ball_speed(turf, launch_deg, spin_radps):
    """Hit harder, at the same launch and spin, and the ball finishes further (20-90 m/s), from a
    knuckling line drive to a wedge. (Balls driven into the ground are the exception docs/limits.md
    states: there eq. (8) itself, inside its bound, turns more of a faster ball's
    speed upwards.)"""
    t = totals(
        ball_speed_mps=np.linspace(20.0, 90.0, 29),
        launch_angle_deg=launch_deg,
        spin_radps=spin_radps,
        turf=turf,
    )
    assert np.all(np.diff(t) > 0.0), t


def test_total_falls_with_rolling_resistance_and_grows_with_tailwind():
    """Eq. (9): more rolling resistance, a shorter roll; a tailwind carries the ball further."""
    drive = dict(ball_speed_mps=74.66, launch_angle_deg=10.9, spin_radps=281.3)
    fairway = PRESETS["fairway"]
    by_rho = [
        simulate(**drive, turf=fairway._replace(rho_g=rho_g)).total_m
        for rho_g in np.linspace(0.05, 0.6, 12)
    ]
    assert np.all(np.diff(by_rho) < 0.0), by_rho
    by_wind = [simulate(**drive, wind_mps=(w, 0.0)).total_m for w in np.linspace(-10, 10, 11)]
    assert np.all(np.diff(by_wind) > 0.0), by_wind


@pytest.mark.parametrize("slope_deg", np.arange(0.0, 5.01, 0.2))
def test_tour_drive_ends_on_a_sloped_green(slope_deg):
    """The Tour drive onto a green sloped 0-5 deg (downhill, along the target line) comes to
    rest: at 2.4 deg its hops died out after 102 impacts, past the old bound of 100, and every
    outcome, carry included, was NaN."""
    out = simulate(
        ball_speed_mps=74.66,
        launch_angle_deg=10.9,
        spin_radps=281.3,
        turf="green",
        slope_deg=slope_deg,
        aero_model="trackman2019",  # the model of the drive that failed
    ).outcome
    assert out["status"] == status.OK
    assert out["carry_m"] == pytest.approx(246.3, abs=0.1)
    assert out["total_m"] > out["carry_m"]


def test_a_failed_run_keeps_the_flight():
    """A shot whose bouncing hits the safety bound keeps its flight's outcome (carry, landing);
    only the run's fields are NaN. (They were all NaN, carry included.)"""
    from mcrun.engine import schema, shot

    out = np.zeros((1, schema.N_OUTCOME))
    shot.write_landing(out, 0, 230.0, -4.0, 6.5, 30.0, 27.8, 50.3, 221.0)
    shot.write_run(
        out, 0, 230.0, 260.0, -5.0, 0.0, 14.0, status.TOO_MANY_BOUNCES, 1000, 1.8, 6.0, np.nan,
        np.nan,
    )  # fmt: skip
    row = dict(zip(schema.OUTCOME_FIELDS, out[0], strict=True))
    assert row["status"] == status.TOO_MANY_BOUNCES
    assert (row["carry_m"], row["carry_lateral_m"], row["landing_speed_mps"]) == (230.0, 4.0, 27.8)
    assert all(math.isnan(row[k]) for k in schema.OUTCOME_FIELDS[schema.BOUNCES : schema.STATUS])
