"""The table of a shot's inputs (``mcrun.quantities``): each quantity written once, and the
single shot and the runs turning it into the same kernel columns."""

import inspect

import numpy as np
import pytest

from mcrun import api, quantities
from mcrun.engine.schema import COLUMN, INPUT_FIELDS
from mcrun.physics.constants import DEG
from mcrun.physics.turf import PRESETS
from mcrun.run import plan, sampling
from mcrun.run import scenario as sc
from mcrun.units import KINDS

SCENARIO_ROWS = [q for q in quantities.QUANTITIES if q.paths]


def test_every_kernel_column_named_by_the_table_is_the_kernels():
    named = [q.kernel for q in quantities.QUANTITIES if q.kernel is not None]
    assert sorted(set(named) - set(COLUMN)) == []
    assert len(named) == len(set(named))


def test_the_table_is_read_by_the_scenario_and_the_plan():
    for q in SCENARIO_ROWS:
        for path in q.paths:
            section, _, name = path.partition(".")
            assert section in quantities.SECTIONS
            param = sc.PARAMETERS[section][name]
            assert (param.kind, param.limits, param.choices) == (q.kind, q.limits, q.choices)
            if q.kind != "choice" and not q.constant_only:
                assert plan.DRIVER_COLUMNS[path] == q.column
    assert quantities.InputError is api.InputError
    assert issubclass(sc.ScenarioError, quantities.InputError)


def test_every_kind_and_sampled_column_is_known():
    for q in quantities.QUANTITIES:
        assert q.kind in (*KINDS, "number", "choice"), q.column
        if q.kind != "choice" and q.paths:
            assert q.column in quantities.SAMPLED_ORDER, q.column
    assert len(set(quantities.SAMPLED_ORDER)) == len(quantities.SAMPLED_ORDER)


def test_the_limits_are_the_ranges_in_si():
    lo, hi = quantities.by_column("temperature_c").limits
    assert (lo, hi) == (-40.0 + 273.15, 55.0 + 273.15)
    assert quantities.by_column("slope_deg").limits == (0.0, 45.0 * DEG)
    assert quantities.by_column("mu").limits == quantities.RANGES["mu"]


@pytest.mark.parametrize(
    ("func", "column"),
    [
        (api.air_properties, "temperature_c"),
        (api.air_properties, "relative_humidity"),
        (api.flight_params, "cd_scale"),
        (api.flight_params, "cl_scale"),  # (a wind's reference height: None, for a uniform wind)
        (api.conditions_inputs, "slope_deg"),
        (api.conditions_inputs, "turf"),
        (api.shot_inputs, "azimuth_deg"),
    ],
)
def test_the_apis_defaults_are_the_tables(func, column):
    default = inspect.signature(func).parameters[column].default
    assert default == quantities.DEFAULTS[column]
    assert type(default) is type(quantities.DEFAULTS[column])


def test_defaults_depend_on_the_choices():
    chosen = {"turf.preset": "fairway", "weather.wind_profile": "log"}
    assert quantities.default_of("turf.mu", chosen) == PRESETS["fairway"].mu
    assert quantities.default_of("weather.wind_profile_parameter", chosen) == 0.03
    assert quantities.default_of("weather.altitude", chosen) is None
    values = quantities.with_defaults({"turf.preset": "rough"}, ("turf",))
    assert values["turf.restitution"] == 1.0
    assert "turf.stimp" not in values


def test_a_scenario_of_constants_gives_the_kernel_inputs_of_the_api(tmp_path):
    """The single shot and a run share ``kernel_columns``: the same inputs to the bit."""
    path = tmp_path / "s.toml"
    path.write_text(
        "[scenario]\nshots = 3\nblock_size = 3\n"
        "[club]\nspeed = 45.0\nloft = 10.5\nazimuth = -1.5\n"
        '[turf]\npreset = "fairway"\nmu = 0.3\nslope = 2.0\nfall_line = 30.0\n'
        "[weather]\nwind_speed = 0.0\ntemperature = 31.0\naltitude = 1600.0\nhumidity = 0.3\n"
        "[models]\ncd_scale = 1.1\n"
    )
    s = sc.load(path)
    inputs, sampled = sampling.sample(s, s.points[0], 0, 3)
    one, _ = api.shot_inputs(
        club_speed_mps=45.0,
        loft_deg=10.5,
        azimuth_deg=-1.5,
        turf=api.resolve_turf("fairway", mu=0.3),
        slope_deg=2.0,
        fall_line_deg=30.0,
        temperature_c=31.0,
        altitude_m=1600.0,
        relative_humidity=0.3,
        cd_scale=1.1,
    )
    for k, name in enumerate(INPUT_FIELDS):
        assert np.array_equal(inputs[:, k], np.repeat(one[:, k], 3)), name
    assert sampled["mu"][0] == 0.3
    assert np.isnan(sampled["club_speed_mps"]).sum() == 0


def test_kernel_columns_of_arrays_and_of_floats_agree():
    base = quantities.with_defaults(
        {
            "launch.ball_speed": 70.0,
            "launch.launch_angle": 12.0 * DEG,
            "launch.spin": 300.0,
            "weather.wind_speed": 4.0,
            "weather.wind_direction": 1.0,
        }
    )
    scalar = quantities.kernel_columns(base)
    arrays = quantities.kernel_columns(
        {k: np.full(4, v) if isinstance(v, float) else v for k, v in base.items()}
    )
    for name, value in scalar.items():
        assert np.array_equal(np.broadcast_to(value, (4,)), np.broadcast_to(arrays[name], (4,)))
    # Every kernel input but where the shot is struck, which the run sets (default the tee).
    struck = {"start_x_m", "start_y_m"}
    assert sorted(quantities.kernel_part(scalar)) == sorted(set(INPUT_FIELDS) - struck)
