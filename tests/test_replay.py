"""Replaying measured shots (mcrun.run.replay, ``mcrun replay``): every row of a launch-monitor
file flown as given must be exactly the single-shot API's result for that launch in the same
conditions; a row with an unusable value gets status invalid_input; user errors exit 2 with one
line and write nothing.
"""

import math
import os
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun.api import simulate
from mcrun.cli import main
from mcrun.engine.schema import PLANE_FIELDS
from mcrun.results import output
from mcrun.run import replay
from mcrun.status import INVALID_INPUT, OK

MPH = 0.44704
RPM = 2.0 * math.pi / 60.0

# A session as a launch monitor exports it: units in the column names, a club column, the
# measured carry, and one misread shot (no spin).
SESSION = """\
club,ball_speed_mph,launch_deg,spin_rpm,spin_axis_deg,direction_deg,carry_yd
Driver,167.0,10.9,2686,2.5,-1.0,275
Driver,171.3,9.8,2410,-4.0,0.5,284
7 Iron,120.0,16.3,7097,1.0,0.0,172
PW,102.0,24.2,9304,0.0,2.0,136
Driver,165.0,11.5,,0.0,0.0,270
"""

CONDITIONS = dict(
    turf="fairway",
    wind_mps=(3.0, -2.0),
    temperature_c=30.0,
    altitude_m=1500.0,
    relative_humidity=0.3,
    aero_model="penner2002",
)
CLI_CONDITIONS = ["--turf", "fairway", "--wind", "3,-2", "--temperature", "30"]
CLI_CONDITIONS += ["--altitude", "1500", "--humidity", "30%", "--aero", "penner2002"]


def session_file(folder):
    path = Path(folder) / "session.csv"
    path.write_text(SESSION, encoding="utf-8")
    return path


def single(row):
    return simulate(
        ball_speed_mps=row["ball_speed_mph"] * MPH,
        launch_angle_deg=row["launch_deg"],
        spin_radps=row["spin_rpm"] * RPM,
        spin_axis_deg=row["spin_axis_deg"],
        azimuth_deg=row["direction_deg"],
        **CONDITIONS,
    ).outcome


def assert_rows_equal_single_shots(frame, rel):
    measured = pd.read_csv(pd.io.common.StringIO(SESSION))
    assert len(frame) == len(measured)
    for k, row in measured.iterrows():
        got = frame.iloc[k]
        if math.isnan(row["spin_rpm"]):
            assert got["status"] == INVALID_INPUT and got["status_name"] == "invalid_input"
            assert math.isnan(got["carry_m"]) and pd.isna(got["bounces"])
            continue
        want = single(row)
        assert got["status"] == OK == want["status"]
        for name in PLANE_FIELDS:
            if name in ("status", "launch_angle_deg"):
                continue
            assert got[name] == pytest.approx(want[name], rel=rel, abs=0.0), (k, name)
        assert got["launch_angle_deg"] == row["launch_deg"]
        assert got["ball_speed_mps"] == row["ball_speed_mph"] * MPH


def test_replay_equals_single_shots_bit_for_bit(tmp_path):
    """The Python API: the same conditions as simulate's keyword arguments, bit for bit."""
    frame = replay.replay(session_file(tmp_path), **CONDITIONS)
    assert_rows_equal_single_shots(frame, rel=0.0)
    # The session's own columns are kept beside the results.
    assert list(frame["club"]) == ["Driver", "Driver", "7 Iron", "PW", "Driver"]
    assert list(frame["carry_yd"]) == [275, 284, 172, 136, 270]
    assert list(frame["row"]) == [0, 1, 2, 3, 4]


def test_cli_replay_writes_parquet_with_provenance(tmp_path, capsys):
    """The command line reads the options' units (30 C through kelvin and back, so to 1e-12)."""
    source = session_file(tmp_path)
    out = tmp_path / "replayed.parquet"
    code = main(["replay", str(source), *CLI_CONDITIONS, "-o", str(out)])
    stdout, stderr = capsys.readouterr()
    assert code == 0, stderr
    assert f"wrote {out}" in stdout
    assert stderr.count("\n") == 1 and "1 shot(s) did not end ok" in stderr
    frame = pd.read_parquet(out)
    assert_rows_equal_single_shots(frame, rel=1e-12)
    meta = output.read_provenance(out)
    assert meta["file"] == "replay" and meta["source_path"] == str(source) and meta["n"] == 5
    assert meta["conditions"]["aero_model"] == "penner2002"
    assert meta["versions"] == output.versions()
    assert sorted(os.listdir(tmp_path)) == [
        "replayed-clubs.csv", "replayed-device.csv", "replayed.parquet", "session.csv"
    ]  # fmt: skip


def test_replay_bad_inputs_exit_2_and_write_nothing(tmp_path, capsys):
    source = session_file(tmp_path)
    garbage = tmp_path / "garbage.parquet"
    garbage.write_bytes(b"\x00\x01 not parquet")
    unknown = tmp_path / "unknown.csv"
    unknown.write_text("speed,angle,spin\n70,11,280\n")
    existing = tmp_path / "existing.parquet"
    existing.write_bytes(b"an earlier result")
    out = str(tmp_path / "out.parquet")
    cases = [
        ([str(tmp_path / "missing.csv"), "-o", out], "no such file"),
        ([str(garbage), "-o", out], "cannot read it as CSV or Parquet"),
        ([str(unknown), "-o", out], "no recognisable column for ball_speed"),
        ([str(source), "--wind", "3", "-o", out], "--wind"),
        ([str(source), "--turf", "moon", "-o", out], "unknown turf 'moon'"),
        ([str(source), "--temperature", "100", "-o", out], "temperature_c"),
        ([str(source), "--aero", "nope", "-o", out], "nope"),
        ([str(source), "-o", str(existing)], "--force"),
        ([str(source), "-o", str(tmp_path / "out.csv")], ".parquet"),
        ([str(source), "-o", str(source / "out.parquet")], "cannot write"),
    ]
    before = {p: p.stat().st_mtime_ns for p in tmp_path.iterdir()}
    for argv, needle in cases:
        code = main(["replay", *argv])
        stdout, stderr = capsys.readouterr()
        assert code == 2, argv
        assert stdout == "" and stderr.count("\n") == 1, (argv, stderr)
        assert stderr.startswith("mcrun: error: ") and needle in stderr, (argv, stderr)
        assert {p: p.stat().st_mtime_ns for p in tmp_path.iterdir()} == before, argv


def test_replay_parquet_source_and_force(tmp_path, capsys):
    """A Parquet session in SI units (ball_speed_mps, spin_radps) replays like the CSV; --force
    replaces an earlier output."""
    measured = pd.read_csv(pd.io.common.StringIO(SESSION)).dropna()
    si = pd.DataFrame(
        {
            "ball_speed_mps": measured["ball_speed_mph"] * MPH,
            "launch_angle_deg": measured["launch_deg"],
            "spin_radps": measured["spin_rpm"] * RPM,
        }
    )
    source = tmp_path / "session.parquet"
    si.to_parquet(source)
    out = tmp_path / "out.parquet"
    out.write_bytes(b"old")
    code = main(["replay", str(source), "-o", str(out), "--force"])
    assert code == 0, capsys.readouterr().err
    frame = pd.read_parquet(out)
    for k, row in si.reset_index(drop=True).iterrows():
        want = simulate(
            ball_speed_mps=row["ball_speed_mps"],
            launch_angle_deg=row["launch_angle_deg"],
            spin_radps=row["spin_radps"],
        ).outcome
        np.testing.assert_array_equal(
            frame.loc[k, ["carry_m", "total_m", "final_y_m"]].to_numpy(dtype=float),
            [want["carry_m"], want["total_m"], want["final_y_m"]],
        )


def test_replay_of_a_malformed_file_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys):
    """A file with a header only, or whose first data row has one field more than the header
    (pandas would take the first column as the index and shift every value), a folder: one
    line naming the file and what is wrong, exit 2, nothing written."""
    header, row = SESSION.splitlines()[:2]
    header_only = tmp_path / "header.csv"
    header_only.write_text(header + "\n")
    extra = tmp_path / "extra.csv"
    extra.write_text(f"{header}\n{row},9\n{SESSION.splitlines()[2]}\n")
    extra_later = tmp_path / "extra_later.csv"
    extra_later.write_text(f"{header}\n{row}\n{row},9\n")
    folder = tmp_path / "session.csv"
    folder.mkdir()
    out = tmp_path / "out.parquet"
    cases = [
        (header_only, "no shots: the file has a header only"),
        (extra, "row 1 has 8 fields, the header has 7"),
        (extra_later, "row 2 has 8 fields, the header has 7"),
        (folder, "is a directory, not a CSV or Parquet file"),
    ]
    before = sorted(os.listdir(tmp_path))
    for source, what in cases:
        code = main(["replay", str(source), "-o", str(out)])
        stdout, stderr = capsys.readouterr()
        assert code == 2 and stdout == "", (source, stderr)
        assert stderr == f"mcrun: error: {source}: {what}\n"
        assert sorted(os.listdir(tmp_path)) == before
    empty = pd.read_csv(header_only)
    with pytest.raises(replay.InputError, match="no shots"):
        replay.replay(empty, **CONDITIONS)
