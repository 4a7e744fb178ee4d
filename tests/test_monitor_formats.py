"""Launch-monitor exports (mcrun.run.monitors): one fixture per format in ``tests/data/monitors``,
written as the devices and apps write them (a BOM, a ``sep=`` line, a unit row, units in the
names, L/R directions, Latin-1 bytes, metric and imperial unit rows, back and side spin,
sentinels), each read to the SI values computed here by hand from the numbers in the file.
Exact unit factors: 1 mph = 0.44704 m/s, 1 km/h = 1/3.6 m/s, 1 yd = 0.9144 m, 1 ft = 0.3048 m,
1 rpm = 2 pi/60 rad/s; values compared to 1e-12 relative.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from mcrun.api import InputError
from mcrun.run.monitors import NAMES, read_session

DATA = Path(__file__).parent / "data" / "monitors"
MPH, KMH, YD, FT = 0.44704, 1.0 / 3.6, 0.9144, 0.3048
RPM, DEG = 2.0 * math.pi / 60.0, math.pi / 180.0
NAN = math.nan


def back_side(back, side):
    """(total spin rad/s, axis rad) from back and side spin in rpm: hypot and atan2."""
    return math.hypot(back, side) * RPM, math.atan2(side, back)


# The 7-iron and the driver of every file: (ball speed, launch, spin, axis, azimuth) and the
# device's (carry, total, apex, descent, carry side, total side), SI, NaN where not given.
IRON_MPH = (120.0 * MPH, 16.3 * DEG, 7097 * RPM, 2.5 * DEG, -1.2 * DEG)
DRIVER_MPH = (167.0 * MPH, 10.9 * DEG, 2686 * RPM, -3.0 * DEG, 0.5 * DEG)
IRON_DEVICE = (172.0 * YD, 180.5 * YD, 98.0 * FT, 50.0 * DEG, 3.1 * YD, 3.8 * YD)
DRIVER_DEVICE = (275.0 * YD, 295.2 * YD, 95.4 * FT, 38.1 * DEG, -10.2 * YD, -11.0 * YD)
SKY_IRON = back_side(7090, 310)
SKY_DRIVER = back_side(2682, -140)

CASES = {
    # file: (format, clubs, {quantity: [row values]})
    "trackman.csv": ("trackman", ["7 Iron", "Driver"], (IRON_MPH, DRIVER_MPH), None),
    "trackman-normalized.csv": (
        "trackman-normalized",
        ["7 Iron", "Driver"],
        (IRON_MPH, DRIVER_MPH),
        {"total": [181.0 * YD, 296.0 * YD], "total_side": [3.9 * YD, -11.4 * YD]},
    ),
    "garmin-r10-metric.csv": (
        "garmin-r10",
        ["7 Iron", "Driver"],
        (
            (193.1 * KMH, 16.3 * DEG, 6910 * RPM, 2.5 * DEG, -1.2 * DEG),
            (268.8 * KMH, 10.9 * DEG, 2684 * RPM, -9.2 * DEG, 0.5 * DEG),
        ),
        {
            "carry": [157.3, 251.5],
            "total": [164.0, 270.0],
            "apex": [27.4, 29.1],
            "carry_side": [2.8, -10.1],
            "total_side": [3.5, -10.8],
        },
    ),
    "garmin-r10-imperial.csv": (
        "garmin-r10",
        ["7 Iron"],
        (IRON_MPH,),
        {"carry": [172.0 * YD], "apex": [30.0 * YD], "total_side": [3.8 * YD]},
    ),
    "rapsodo-mlm2pro.csv": (
        "rapsodo-mlm2pro",
        ["7i", "Driver", "PW"],
        (
            (120.0 * MPH, 16.3 * DEG, 7097 * RPM, 2.5 * DEG, -1.2 * DEG),
            DRIVER_MPH,
            (102.0 * MPH, 24.2 * DEG, NAN, NAN, 0.0),
        ),
        {
            "carry": [172.0 * YD, 275.0 * YD, NAN],
            # Apex in feet (a real MLM2PRO export; read as yards it was 3x the flight's).
            "apex": [98.0 * FT, 95.4 * FT, NAN],
            "carry_side": [3.1 * YD, -10.2 * YD, NAN],
            "descent_angle": [50.0 * DEG, 38.1 * DEG, NAN],
        },
    ),
    "skytrak.csv": (
        "skytrak",
        ["7 Iron", "Driver"],
        (
            (120.0 * MPH, 16.3 * DEG, 7097 * RPM, SKY_IRON[1], -1.2 * DEG),
            # No total spin in the file: it follows from back and side spin.
            (167.0 * MPH, 10.9 * DEG, SKY_DRIVER[0], SKY_DRIVER[1], 0.5 * DEG),
        ),
        {"apex": [32.7 * YD, 31.8 * YD], "carry_side": [3.1 * YD, -10.2 * YD]},
    ),
    "flightscope-mevo.csv": (
        "flightscope-mevo",
        ["7 Iron", "Driver"],
        (
            (120.0 * MPH, 16.3 * DEG, 7097 * RPM, None, None),
            (167.0 * MPH, 10.9 * DEG, 2686 * RPM, None, None),
        ),
        {"carry": [172.0 * YD, 275.0 * YD], "apex": [98.0 * FT, 95.4 * FT]},
    ),
    "flightscope-mevo-plus.csv": (
        "flightscope-mevo-plus",
        ["7 Iron", "Driver"],
        (
            IRON_MPH,
            (167.0 * MPH, 10.9 * DEG, 2686 * RPM, 4.9 * DEG, -13.8 * DEG),
        ),
        {"carry_side": [3.1 * YD, 4.9 * YD], "descent_angle": [50.0 * DEG, 38.1 * DEG]},
    ),
    "foresight-fsx.csv": (
        "foresight-fsx",
        ["7 Iron", "Driver"],
        (
            (53.6, 16.3 * DEG, 7097 * RPM, back_side(7090, 310)[1], -1.2 * DEG),
            (74.7, 10.9 * DEG, 2686 * RPM, back_side(2682, -140)[1], 0.5 * DEG),
        ),
        # 16777215: the driver's descent angle was not measured.
        {"carry": [157.3, 251.5], "descent_angle": [50.0 * DEG, NAN], "carry_side": [2.8, -9.3]},
    ),
    "square-golf.csv": (
        "square-golf",
        ["7I", "DR"],
        (IRON_MPH, DRIVER_MPH),
        {"apex": [32.7 * YD, 31.8 * YD], "carry_side": [3.1 * YD, -10.2 * YD]},
    ),
    "awesome-golf.csv": (
        "awesome-golf",
        ["7 Iron", "Driver"],
        (IRON_MPH, DRIVER_MPH),
        {
            "carry": [172.0 * YD, 275.0 * YD],
            "apex": [98.0 * FT, 95.4 * FT],
            "carry_side": [3.1 * YD, -10.2 * YD],
            "total_side": [3.8 * YD, -11.0 * YD],
        },
    ),
    "gspro.jsonl": (
        "gspro",
        None,
        (
            (147.5 * MPH, 14.3 * DEG, 2250 * RPM, -13.2 * DEG, 2.3 * DEG),
            # Total spin and axis sent as 0: from back and side spin.
            (120.0 * MPH, 16.3 * DEG, *back_side(7090, 310), -1.2 * DEG),
        ),
        {"carry": [256.5 * YD, 157.3]},  # the second message in Meters
    ),
}
LAUNCH = ("ball_speed", "launch_angle", "spin", "spin_axis", "azimuth")


@pytest.mark.parametrize("name", sorted(CASES))
def test_each_format_reads_to_the_hand_computed_si_values(name):
    fmt, clubs, rows, device = CASES[name]
    session = read_session(DATA / name)
    assert session.format == fmt and session.detected
    assert (None if session.club is None else list(session.club)) == clubs
    for k, quantity in enumerate(LAUNCH):
        want = [row[k] for row in rows]
        if want[0] is None:
            assert quantity not in session.launch, quantity  # the format does not give it
            continue
        np.testing.assert_allclose(
            session.launch[quantity], want, rtol=1e-12, atol=0.0, err_msg=quantity
        )
    if device is None:
        device = dict(
            zip(
                ("carry", "total", "apex", "descent_angle", "carry_side", "total_side"),
                zip(IRON_DEVICE, DRIVER_DEVICE, strict=True),
                strict=True,
            )
        )
    for quantity, want in device.items():
        np.testing.assert_allclose(
            session.device[quantity], want, rtol=1e-12, atol=0.0, err_msg=quantity
        )


def test_every_format_has_a_fixture_and_forcing_it_reads_the_same():
    assert sorted({case[0] for case in CASES.values()} | {"mcrun"}) == sorted(NAMES)
    forced = read_session(DATA / "trackman.csv", format="trackman")
    assert not forced.detected
    np.testing.assert_array_equal(
        forced.launch["spin"], read_session(DATA / "trackman.csv").launch["spin"]
    )


def test_the_files_own_columns_are_kept_as_written():
    """Names as in the file (the Foresight spaces and trailing comma gone, the degree sign of
    Latin-1 read), values as written (an L/R direction stays text)."""
    foresight = read_session(DATA / "foresight-fsx.csv").frame
    assert list(foresight.columns[:3]) == ["Shot ID", "Club", "Club head Speed (m/s)"]
    assert foresight.columns[-1] == "Vert Impact (mm)" and foresight.shape == (2, 24)
    mevo = read_session(DATA / "flightscope-mevo.csv").frame
    assert "Launch Angle V (°)" in mevo.columns
    plus = read_session(DATA / "flightscope-mevo-plus.csv").frame
    assert list(plus["Launch H"]) == ["1.2 L", "13.8 L"]
    normalized = read_session(DATA / "trackman-normalized.csv").frame
    assert normalized["Spin Rate Type"].tolist() == ["Measured", "Estimated"]
    assert normalized["Carry Flat - Length (Sim)"].tolist() == [171.2, 276.3]


def test_unknown_blank_and_header_only_files_are_one_line(tmp_path):
    unknown = tmp_path / "unknown.csv"
    unknown.write_text("Shot,Speed (kph),Angle\n1,190,12\n", encoding="utf-8")
    blank = tmp_path / "blank.csv"
    blank.write_text("\n\n", encoding="utf-8")
    header_only = tmp_path / "header.csv"
    lines = (DATA / "trackman.csv").read_text(encoding="utf-8").splitlines()
    header_only.write_text("\n".join(lines[:2]) + "\n", encoding="utf-8")
    bad_unit = tmp_path / "bad-unit.csv"
    bad_unit.write_text("\n".join([lines[0], lines[1].replace("[mph]", "[furlong/h]"), lines[2]]))
    bad_json = tmp_path / "bad.jsonl"
    bad_json.write_text('{not json\n{"BallData": \n', encoding="utf-8")
    cases = [
        (blank, "no shots: the file is empty"),
        (header_only, "no shots: the file has a header only"),
        (bad_json, "no shots: line 1: not a JSON message"),
    ]
    for path, needle in cases:
        with pytest.raises(InputError) as info:
            read_session(path)
        message = str(info.value)
        assert "\n" not in message and message.startswith(f"{path}: "), message
        assert needle in message, message
    with pytest.raises(InputError) as info:
        read_session(unknown)
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{unknown}: ")
    assert "no recognisable column for ball_speed, launch_angle, spin" in message
    assert "found Shot, Speed (kph), Angle" in message
    assert all(name in message for name in NAMES), message
    with pytest.raises(InputError, match="column 'Ball Speed': unit 'furlong/h' is not a speed"):
        read_session(bad_unit)
