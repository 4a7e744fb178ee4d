"""The kernel's schemas: ``pack`` builds its inputs, ``encode_outcomes`` types its outcomes."""

import math

import numpy as np
import pytest

from mcrun import api, status
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import (
    COLUMN,
    INPUT_DEFAULTS,
    INPUT_FIELDS,
    N_INPUT,
    PLANE_FIELDS,
    encode_outcomes,
    outcome_record,
    pack,
)
from mcrun.physics.constants import DEG
from mcrun.results.output import ShotsWriter


def _required(n):
    """Every input without a default: a 7-iron (53.6 m/s, 16.3 deg, 739 rad/s) on the green."""
    row, _ = api.shot_inputs(ball_speed_mps=53.6, launch_angle_deg=16.3, spin_radps=739.0)
    return {
        name: np.full(n, row[0, COLUMN[name]])
        for name in INPUT_FIELDS
        if name not in INPUT_DEFAULTS
    }


def test_pack_fills_the_defaults_in_fortran_order():
    inputs = pack(_required(3), 3)
    assert inputs.shape == (3, N_INPUT) and inputs.flags.f_contiguous
    assert inputs.dtype == np.float64
    for name, value in INPUT_DEFAULTS.items():
        assert (inputs[:, COLUMN[name]] == value).all(), name


def test_pack_defaults_are_those_of_the_api():
    """A shot given without its optional arguments packs to the API's row, bit for bit."""
    row, _ = api.shot_inputs(ball_speed_mps=53.6, launch_angle_deg=16.3, spin_radps=739.0)
    assert pack(_required(1), 1).tobytes() == row.tobytes()


def test_pack_refuses_unknown_and_missing_names():
    with pytest.raises(ValueError, match="unknown kernel input.*spin_rpm"):
        pack({**_required(2), "spin_rpm": 3000.0}, 2)
    columns = _required(2)
    del columns["dt_s"]
    with pytest.raises(ValueError, match="missing kernel input.*dt_s"):
        pack(columns, 2)


def test_pack_into_a_view_and_invalid_rows():
    """``out`` is filled in place; an invalid row gets a NaN speed, which the kernel answers
    with invalid_input while the others fly."""
    whole = np.zeros((4, N_INPUT), order="F")
    invalid = np.array([False, True])
    packed = pack(_required(2), 2, out=whole[1:3], invalid=invalid)
    assert packed.base is whole or np.shares_memory(packed, whole)
    assert math.isnan(whole[2, COLUMN["ball_speed_mps"]]) and whole[1, 0] == 53.6
    assert (whole[[0, 3]] == 0.0).all()
    out = simulate_batch(whole[1:3])
    assert out[0, -1] == status.OK and out[1, -1] == status.INVALID_INPUT


def test_shot_inputs_launch_in_radians_and_the_angle_as_given():
    row, angle_deg = api.shot_inputs(
        ball_speed_mps=74.6, launch_angle_deg=10.9, spin_radps=281.0, azimuth_deg=-2.0
    )
    assert angle_deg == 10.9
    assert row.shape == (1, N_INPUT)
    assert row[0, COLUMN["launch_angle_rad"]] == 10.9 * DEG
    assert row[0, COLUMN["azimuth_rad"]] == -2.0 * DEG


def _ok_and_invalid():
    """The kernel's outcomes of a 7-iron that flies and of one it refuses."""
    return simulate_batch(pack(_required(2), 2, invalid=np.array([False, True])))


def test_encode_outcomes_types_and_masks():
    encoded = encode_outcomes(_ok_and_invalid())
    assert list(encoded) == list(PLANE_FIELDS)
    bounces, missing = encoded["bounces"]
    assert bounces.dtype == np.int32 and list(missing) == [False, True] and bounces[1] == 0
    assert bounces[0] >= 1
    codes, none = encoded["status"]
    assert codes.dtype == np.int8 and none is None
    assert list(codes) == [status.OK, status.INVALID_INPUT]
    carry, none = encoded["carry_m"]
    assert carry.dtype == np.float64 and none is None and math.isnan(carry[1])


def test_a_shot_that_did_not_get_that_far_has_no_bounces_in_the_api_as_in_parquet():
    """bounces is None in the API's dict (JSON null) where Parquet holds a null, not -1."""
    out = _ok_and_invalid()
    table = ShotsWriter(None, [], ["g"], ["p"], {}).table(0, 0, {}, out)
    records = [outcome_record(out, i) for i in range(2)]
    assert [r["bounces"] for r in records] == table.column("bounces").to_pylist()
    assert records[1]["bounces"] is None and isinstance(records[0]["bounces"], int)
    assert records[1]["status"] == status.INVALID_INPUT and math.isnan(records[1]["carry_m"])
    assert [r["status"] for r in records] == table.column("status").to_pylist()
