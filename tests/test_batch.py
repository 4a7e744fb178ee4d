"""The shot loop in lanes: each shot comes out bit for bit as it does alone.

``batch.simulate_batch`` flies shots of a quadratic aerodynamic model in uniform wind in
vectorised lanes and every other shot in lanes of the general form; every shot must come out
bit for bit as it does alone (a batch of one row, which is the single-shot API, with its path
recorded or not), whatever the mix of shots, their order, the number of threads and the
chunking; and the two forms of lanes give the same numbers for a shot both can fly.
"""

import itertools

import numba
import numpy as np
import pytest

from mcrun import api, ground
from mcrun.engine import flight_lanes, tables
from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.rolling import roll_out
from mcrun.engine.schema import COLUMN, N_INPUT, N_OUTCOME
from mcrun.engine.shot import default_dt_s
from mcrun.executor import Executor
from mcrun.physics import aero
from mcrun.physics.flight import WIND_PROFILES, FlightParams, QuadraticContext
from mcrun.physics.roll import roll_out_short
from mcrun.physics.turf import PRESETS
from mcrun.status import MAX_ROLL_DISTANCE_M, MAX_ROLL_TIME_S, NOT_STOPPED

N = 400


def mixed_inputs(n, seed=3):
    """Shots of every model and wind profile, on slopes and turfs, with some invalid rows."""
    rng = np.random.default_rng(seed)
    x = np.empty((n, N_INPUT), order="F")
    col = {name: x[:, k] for name, k in COLUMN.items()}
    col["ball_speed_mps"][:] = rng.uniform(25, 80, n)
    col["launch_angle_rad"][:] = np.radians(rng.uniform(2, 40, n))
    col["azimuth_rad"][:] = np.radians(rng.normal(0, 3, n))
    col["spin_radps"][:] = rng.uniform(150, 1200, n)
    col["spin_axis_rad"][:] = np.radians(rng.normal(0, 8, n))
    rho, nu = api.air_properties()
    col["air_density_kgpm3"][:] = rho
    col["kinematic_viscosity_m2ps"][:] = nu
    col["aero_model"][:] = rng.integers(0, len(aero.MODELS), n)
    col["cd_scale"][:] = rng.uniform(0.9, 1.1, n)
    col["cl_scale"][:] = rng.uniform(0.9, 1.1, n)
    col["wind_x_mps"][:] = rng.normal(0, 3, n)
    col["wind_right_mps"][:] = rng.normal(0, 3, n)
    profiles = rng.choice([0, 0, 0, WIND_PROFILES["log"], WIND_PROFILES["power"]], n)
    col["wind_profile"][:] = profiles
    col["wind_reference_height_m"][:] = 10.0
    col["wind_profile_parameter"][:] = np.where(profiles == WIND_PROFILES["log"], 0.03, 1 / 7)
    turfs = list(PRESETS.values())
    for k, turf in enumerate(rng.choice(len(turfs), n)):
        for field, value in turfs[turf]._asdict().items():
            col[field][k] = value
    col["slope_rad"][:] = np.radians(rng.choice([0.0, 0.0, 1.5, 4.0], n))
    col["fall_line_rad"][:] = np.radians(rng.uniform(-180, 180, n))
    col["dt_s"][:] = [default_dt_s("uniform" if p == 0 else "log") for p in profiles]
    col["start_x_m"][:] = np.where(rng.random(n) < 0.5, 0.0, rng.uniform(-50, 200, n))
    col["start_y_m"][:] = np.where(col["start_x_m"] == 0.0, 0.0, rng.uniform(-30, 30, n))
    col["ball_speed_mps"][::37] = np.nan  # invalid rows
    col["spin_radps"][5::41] = -1.0
    return x


@pytest.fixture(scope="module")
def inputs():
    return mixed_inputs(N)


@pytest.fixture(scope="module")
def alone(inputs):
    """Each row simulated alone, one call per shot, its path recorded (the single-shot API's
    ``trajectory=True``)."""
    return np.concatenate([simulate_traced(inputs[i : i + 1])[0] for i in range(len(inputs))])


def same(a, b):
    return np.array_equal(a, b, equal_nan=True)


def test_batch_equals_each_shot_alone_bit_for_bit(inputs, alone):
    assert same(simulate_batch(inputs), alone)


def test_recording_the_path_changes_nothing(inputs, alone):
    """A shot alone without its path (``mcrun shot``) is the same as with it."""
    for i in range(0, len(inputs), 7):
        assert same(simulate_batch(inputs[i : i + 1]), alone[i : i + 1]), i


def test_general_lanes_fly_a_quadratic_shot_as_the_quadratic_lanes(inputs):
    """The two forms of flight lanes (``flight.derivatives_quadratic`` in vectorised lanes,
    ``flight.derivatives`` for any model and wind) give the same numbers for the shots both
    can fly: every quadratic shot in uniform wind flown by each."""
    n = len(inputs)
    rows = np.asfortranarray(inputs)
    outs = []
    for general in (False, True):
        out = np.full((n, N_OUTCOME), np.nan, order="F")
        kinds = np.array([flight_lanes.flight_kind(rows, i, out) for i in range(n)], dtype=np.int8)
        _fly_quadratic_kind(rows, kinds, out, general)
        outs.append(out[kinds == flight_lanes.QUADRATIC])
    assert len(outs[0]) > 100
    assert same(outs[0], outs[1])


@numba.njit(cache=True)
def _fly_quadratic_kind(rows, kinds, out, general):
    """The shots of the quadratic kind flown by the quadratic lanes or the general ones. (A
    function of this module calls them so that its compilation is cached: a lanes' function is
    a closure over dispatchers, whose cache key is new in every process.)"""
    n = rows.shape[0]
    landings = np.empty((n, tables.N_LANDING))
    pending = np.empty(n, dtype=np.int64)
    no_path, untraced = np.empty((0, 5)), np.full(4, -1.0)
    table = aero.QUADRATIC_COEFFICIENTS
    if general:
        flight_lanes.fly_general(rows, kinds, flight_lanes.QUADRATIC, 0, n, table, out, landings,
                                 pending, 0, no_path, untraced, None)  # fmt: skip
    else:
        flight_lanes.fly_quadratic(rows, kinds, flight_lanes.QUADRATIC, 0, n, table, out,
                                   landings, pending, 0, no_path, untraced, None)  # fmt: skip


def test_mix_is_real(alone, inputs):
    """The rows exercise both paths and every status the mix should give."""
    quadratic = np.isin(inputs[:, COLUMN["aero_model"]], aero.QUADRATIC_MODELS)
    uniform = inputs[:, COLUMN["wind_profile"]] == 0
    assert 0.2 < np.mean(quadratic & uniform) < 0.8
    assert set(np.unique(alone[:, -1])) >= {0.0, 1.0}  # ok and invalid_input


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.determinism
def test_any_order_and_thread_count(inputs, alone, threads):
    """Reversed rows and another thread count change nothing."""
    previous = numba.get_num_threads()
    numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
    try:
        reversed_out = simulate_batch(np.asfortranarray(inputs[::-1]))
    finally:
        numba.set_num_threads(previous)
    assert same(reversed_out[::-1], alone)


def test_short_roll_is_roll_out_on_level_ground():
    """``roll.roll_out_short``, the roll out of the lanes, gives ``roll_out``'s rest bit for
    bit on level ground, and hands a ball on a slope back to it."""
    rng = np.random.default_rng(7)
    turf = PRESETS["fairway"]
    no_trajectory = np.empty((0, 5))
    for _ in range(200):
        v = (rng.uniform(0.0, 8.0), rng.normal(0.0, 1.0), rng.uniform(-2.0, 0.0))
        w = tuple(rng.normal(0.0, 150.0, 3))
        x, y, t, short = roll_out_short(
            1.0, 2.0, 0.0, *v, *w, 0.0, 0.0, 1.0, turf.mu, turf.rho_g, 3.0
        )
        level = ground.Plane(0.0, 0.0, 1.0, turf)
        want = roll_out(1.0, 2.0, 0.0, *v, *w, None, level, 3.0, no_trajectory, 0,
                        3.0, 0.01)  # fmt: skip
        assert short
        assert (x, y, t) == (want[0], want[1], want[3])
        slope = np.radians(4.0)
        n = (np.sin(slope), 0.0, np.cos(slope))
        assert not roll_out_short(1.0, 2.0, 0.0, *v, *w, *n, turf.mu, turf.rho_g, 3.0)[3]


def test_a_short_roll_past_the_roll_s_bounds_is_handed_back():
    """A roll that one step of each phase ends, but past MAX_ROLL_TIME_S or MAX_ROLL_DISTANCE_M
    (a slide on ice), is not short: ``roll_out`` ends it at the bound, NOT_STOPPED (the lanes
    kept the rest 152 s or 1,170 m away, ``ok``)."""
    no_trajectory = np.empty((0, 5))
    for mu, rho_g, speed, spin, bound in [
        (0.0065, 0.0005, 2.0, -300.0, "time"),  # rests after 152 s
        (0.0065, 0.05, 16.0, 0.0, "distance"),  # rests 1,170 m away after 104 s
    ]:
        turf = PRESETS["green"]._replace(mu=mu, rho_g=rho_g)
        v, w = (speed, 0.0, 0.0), (0.0, spin, 0.0)
        assert not roll_out_short(0.0, 0.0, 0.0, *v, *w, 0.0, 0.0, 1.0, mu, rho_g, 0.0)[3]
        level = ground.Plane(0.0, 0.0, 1.0, turf)
        x, _, _, t, status, *_ = roll_out(0.0, 0.0, 0.0, *v, *w, None, level, 0.0,
                                          no_trajectory, 0, 0.0, 0.01)  # fmt: skip
        assert status == NOT_STOPPED
        if bound == "time":
            assert t == MAX_ROLL_TIME_S
        else:
            assert x == pytest.approx(MAX_ROLL_DISTANCE_M, abs=1e-9)


def test_one_compiled_layout_for_any_number_of_rows(inputs, alone):
    """Numba types an array of fewer than two rows as C-contiguous: a batch of 0 or 1 rows
    (the warm-up before a run's clock starts, a point's last chunk of one shot) must not
    compile the kernel a second time during the run, and gives each shot's results alone."""
    from mcrun.engine.batch import _batch_task

    for n in (0, 1, 2, 50):
        assert same(simulate_batch(inputs[:n]), alone[:n]), n
    out = np.empty((1, N_OUTCOME), order="F")
    assert simulate_batch(inputs[3:4], out) is out and same(out, alone[3:4])
    # One compiled layout of the rows per kind of ground (a plane, and a hole's Terrain when
    # another test ran one).
    plane = [sig for sig in _batch_task.signatures if str(sig[-1]) == "none"]
    assert len(plane) == 1, _batch_task.signatures


def test_every_row_of_a_table_is_its_own():
    """Each lane table's rows are declared once, by name (``tables.rows``), and read as its
    fields (``LANE.X``, ``BOUNCE.X``): within a table their numbers strictly increase from 0
    up to its size, so that no two rows share one (a row given twice silently moves one
    table's rows onto another's); the flight's contexts lie on the lane table's rows kept for
    them (the spin axis and the constants), in their types' order."""
    for table in (tables.LANE, tables.BOUNCE, tables.INCIDENCE, tables.REBOUND, tables.LANDING,
                  tables.TRACER):  # fmt: skip
        assert table[0] == 0 and all(a < b for a, b in itertools.pairwise(table)), table
    assert tables.QUADRATIC_ROWS.axis_x == tables.LANE.AXIS_X
    assert tables.QUADRATIC_ROWS.N == tables.LANE.DT
    assert tables.GENERAL_ROWS[0] == tables.LANE.CONSTANTS
    assert tables.GENERAL_ROWS.N <= tables.LANE.DT
    assert tables.QUADRATIC_ROWS._fields[:-1] == QuadraticContext._fields
    assert tables.GENERAL_ROWS._fields[:-1] == FlightParams._fields


# Run as Python (``NUMBA_DISABLE_JIT=1``): the same shots on a Plane and on a terrain of
# slopes with a penalty area, written to a file.
_AS_PYTHON = """
import sys

import numpy as np

from mcrun import ground
from mcrun.engine.backend import simulate_batch

data = np.load(sys.argv[1])
terrain = ground.make_terrain(
    0.0, -60.0, 5.0, data["height"], data["zone"], data["turf"], data["penalty"]
)
np.savez(sys.argv[2], plane=simulate_batch(data["rows"]),
         terrain=simulate_batch(data["rows"], terrain=terrain))
"""


def test_the_shot_loop_steps_through_as_python(inputs, tmp_path):
    """With NUMBA_DISABLE_JIT=1 the shot loop is plain Python, for a developer to step through
    (the ground's questions pick their answer by the value of ``terrain``, and no lane divides
    by zero): the same numbers as compiled, to the bit, on a Plane and on a hole's terrain of
    slopes with a penalty area, for every model, wind profile and status of the mix."""
    import os
    import subprocess
    import sys

    rows = np.asfortranarray(inputs[:40])
    X, Y = np.meshgrid(np.arange(0.0, 301.0, 5.0), np.arange(-60.0, 61.0, 5.0))
    height = 0.02 * X + 1.5 * np.sin(X / 40.0) * np.cos(Y / 30.0)
    zone = (np.hypot(X - 150.0, Y) < 20.0).astype(np.int8)
    turf = np.array([list(PRESETS["fairway"]), list(PRESETS["green"])])
    penalty = np.array([ground.IN_PLAY, ground.PENALTY_AREA], np.int8)
    np.savez(tmp_path / "in.npz", rows=rows, height=height, zone=zone, turf=turf, penalty=penalty)
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    subprocess.run(
        [sys.executable, "-c", _AS_PYTHON, str(tmp_path / "in.npz"), str(tmp_path / "out.npz")],
        env=env, check=True, timeout=600,
    )  # fmt: skip
    as_python = np.load(tmp_path / "out.npz")
    terrain = ground.make_terrain(0.0, -60.0, 5.0, height, zone, turf, penalty)
    on_terrain = simulate_batch(rows, terrain=terrain)
    assert same(as_python["plane"], simulate_batch(rows))
    assert same(as_python["terrain"], on_terrain)
    assert {0.0, 1.0} <= set(np.unique(on_terrain[:, -1]))  # ok and invalid_input


@pytest.mark.determinism
def test_a_batch_is_the_same_on_every_thread_on_one_and_as_tasks(inputs):
    """The engine's batch on every thread, on one, and cut into tasks of the executor (each
    part's shots on the task's own thread): bit for bit."""
    whole = simulate_batch(inputs)
    previous = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = simulate_batch(inputs)
    finally:
        numba.set_num_threads(previous)
    cuts = range(0, len(inputs), 150)
    parts = Executor(threads=2).map(lambda a: simulate_batch(inputs[a : a + 150]), cuts)
    assert same(whole, one)
    assert same(whole, np.concatenate(parts))
