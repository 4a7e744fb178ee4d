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
    pack,
)
from mcrun.physics.constants import DEG


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
