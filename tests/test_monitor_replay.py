"""A device's export replayed (``mcrun replay``, mcrun.run.replay) and summarised per club
(mcrun.run.clubs), and resampled by a scenario's ``launch.file`` with a club filter: every shot
of an export flies exactly as the single-shot API flies its hand-converted launch; the device's
results sit beside the model's with their difference; the per-club statistics and the model
minus the device are the numbers computed here by hand; mistakes are one line, exit 2, nothing
written."""

import math
import os
import shutil
import tracemalloc
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun.api import InputError, simulate
from mcrun.cli import main
from mcrun.results import output
from mcrun.run import clubs, replay
from mcrun.run import scenario as sc
from mcrun.status import INVALID_INPUT, OK

DATA = Path(__file__).parent / "data" / "monitors"
MPH, YD, FT, RPM = 0.44704, 0.9144, 0.3048, 2.0 * math.pi / 60.0

# The TrackMan fixture's two shots: mph, deg, rpm, deg, deg; its carry (yd) and apex (ft).
TRACKMAN = [
    ("7 Iron", 120.0, 16.3, 7097, 2.5, -1.2, 172.0, 98.0),
    ("Driver", 167.0, 10.9, 2686, -3.0, 0.5, 275.0, 95.4),
]


def test_an_export_replays_as_the_single_shot_api_flies_it():
    frame = replay.replay(DATA / "trackman.csv", turf="fairway", temperature_c=25.0)
    assert frame.attrs["format"] == "trackman" and frame.attrs["format_detected"]
    assert list(frame["row"]) == [0, 1] and list(frame["club"]) == ["7 Iron", "Driver"]
    assert list(frame["Club"]) == ["7 Iron", "Driver"]  # the file's own columns are kept
    assert list(frame["Ball Speed"]) == [120.0, 167.0]
    for k, (_, speed, launch, spin, axis, azimuth, carry_yd, apex_ft) in enumerate(TRACKMAN):
        want = simulate(
            ball_speed_mps=speed * MPH,
            launch_angle_deg=launch,
            spin_radps=spin * RPM,
            spin_axis_deg=axis,
            azimuth_deg=azimuth,
            turf="fairway",
            temperature_c=25.0,
        ).outcome
        got = frame.iloc[k]
        assert got["status"] == OK
        for name in ("carry_m", "carry_lateral_m", "apex_m", "total_m", "final_y_m"):
            assert got[name] == pytest.approx(want[name], rel=1e-12, abs=1e-12), (k, name)
        assert got["device_carry_m"] == carry_yd * YD
        assert got["device_apex_m"] == pytest.approx(apex_ft * FT, rel=1e-12)
        assert got["model_minus_device_carry_m"] == got["carry_m"] - carry_yd * YD
        # The device's descent angle is from the horizontal, mcrun's landing angle from the
        # vertical.
        assert got["descent_angle_deg"] == 90.0 - want["landing_angle_deg"]


def test_a_session_s_air_is_named_as_not_read():
    """A Garmin R10 export records the air of every shot (Temperature, Air Pressure, Relative
    Humidity, Air Density) and Awesome Golf its Altitude: kept as written and not read, which a
    note says, with the density the shots are flown in."""
    notes = replay.replay(DATA / "garmin-r10-metric.csv").attrs["notes"]
    assert notes[-1] == (
        f"{DATA / 'garmin-r10-metric.csv'}: its air (Air Density, Temperature, Air Pressure, "
        "Relative Humidity) is kept as written, not read: every shot is flown in air of 1.199 "
        "kg/m^3, the default (20 C, 101325 Pa, 50 %): give the session's temperature, pressure "
        "or altitude, and humidity, or its air density, to fly it in its own"
    )
    given = replay.replay(DATA / "awesome-golf.csv", air_density_kgpm3=1.1).attrs["notes"]
    assert given[-1].endswith(": its air (Altitude) is kept as written, not read: every shot is "
                              "flown in air of 1.1 kg/m^3, as given")  # fmt: skip
    assert not any("air" in n for n in replay.replay(DATA / "trackman.csv").attrs["notes"])
    # Part of the air given: the note says which, and the rest's defaults (it said "given").
    part = replay.replay(DATA / "garmin-r10-metric.csv", relative_humidity=0.8).attrs["notes"]
    assert "air of 1.196 kg/m^3, humidity given, 20 C, 101325 Pa by default: give" in part[-1]
    # A column of a result named after the air is none ("Temperature Adjusted Carry").
    frame = pd.DataFrame({
        "ball_speed_mph": [150.0], "launch_deg": [12.0], "spin_rpm": [2500.0],
        "Temperature Adjusted Carry": [250.0], "Elevation Change": [3.0],
    })  # fmt: skip
    assert not replay.replay(frame).attrs["notes"]


def test_a_shot_without_spin_is_invalid_and_the_others_fly():
    frame = replay.replay(DATA / "rapsodo-mlm2pro.csv")
    assert list(frame["status"]) == [OK, OK, INVALID_INPUT]
    assert math.isnan(frame["carry_m"].iloc[2]) and math.isnan(frame["device_carry_m"].iloc[2])


def test_club_summary_and_device_comparison_by_hand():
    """Club A: carries 100, 110, 120 (one more shot failed), sides -1, 0, 4; club B: 80, 90.
    A: mean 110, sd 10, p10 102 (linear between 100 and 110), gap to B 110 - 85 = 25.
    Model minus device: A +1, -3, +2 (bias 0, rmse sqrt(14/3)); B -2 (one shot measured)."""
    frame = pd.DataFrame(
        {
            "club": ["A", "A", "A", "A", "B", "B"],
            "status": [OK, OK, OK, INVALID_INPUT, OK, OK],
            "carry_m": [100.0, 110.0, 120.0, np.nan, 80.0, 90.0],
            "total_m": [105.0, 115.0, 125.0, np.nan, 90.0, 100.0],
            "final_y_m": [-1.0, 0.0, 4.0, np.nan, 2.0, 2.0],
            "model_minus_device_carry_m": [1.0, -3.0, 2.0, np.nan, -2.0, np.nan],
        }
    )
    summary = clubs.club_summary(frame).set_index("club")
    a, b = summary.loc["A"], summary.loc["B"]
    assert (a["shots"], a["shots_ok"], b["shots_ok"]) == (4, 3, 2)
    assert a["carry_m_mean"] == 110.0 and a["carry_m_sd"] == pytest.approx(10.0, rel=1e-15)
    assert a["carry_m_p10"] == pytest.approx(102.0, rel=1e-15) and a["carry_m_p50"] == 110.0
    assert a["side_m_mean"] == 1.0 and a["total_m_p90"] == pytest.approx(123.0, rel=1e-15)
    assert list(summary.index) == ["A", "B"]
    assert a["gap_m"] == 25.0 and math.isnan(b["gap_m"])
    table = clubs.device_comparison(frame).set_index(["club", "quantity"])
    a = table.loc[("A", "carry_m")]
    assert (a["shots"], a["bias"]) == (3, 0.0)
    assert a["rmse"] == pytest.approx(math.sqrt(14.0 / 3.0), rel=1e-15)
    every = table.loc[("all", "carry_m")]
    assert every["shots"] == 4 and every["bias"] == pytest.approx(-0.5, rel=1e-15)
    assert every["rmse"] == pytest.approx(math.sqrt(18.0 / 4.0), rel=1e-15)
    assert table.loc[("B", "carry_m")]["shots"] == 1
    for table in (clubs.club_summary, clubs.device_comparison):
        with pytest.raises(InputError, match="frame None: allowed: the frame of mcrun.run.replay"):
            table(None)  # (a TypeError before)
        with pytest.raises(InputError, match="^frame: no column 'status': allowed: the frame"):
            table(pd.DataFrame())  # (the frame's repr, over three lines, before)
    with pytest.raises(InputError, match="^frame: no column 'carry_m'"):
        clubs.club_summary(frame[["status"]])  # (a KeyError before)
    none = clubs.club_summary(frame.iloc[:0])  # a club the session has not: no row
    assert len(none) == 0 and list(none.columns) == list(clubs.club_summary(frame).columns)


def test_a_club_without_a_compared_shot_prints_dashes(tmp_path, capsys):
    """A text line under an export's rows (a footer such as "Exported by ...") is a shot
    without a launch, of no club ("(no club)"): its rows of the model-minus-device table have
    no shots, printed as '-' ('+nan' before)."""
    path = tmp_path / "footer.csv"
    path.write_bytes((DATA / "garmin-r10-metric.csv").read_bytes() + b"Exported by the app\n")
    assert main(["replay", str(path), "-o", str(tmp_path / "f.parquet")]) == 0
    out = capsys.readouterr().out
    assert "nan" not in out
    assert "(no club)       carry_m      0      -     -" in out


def test_cli_says_the_format_prints_the_clubs_and_keeps_the_device(tmp_path, capsys):
    out = tmp_path / "replayed.parquet"
    code = main(["replay", str(DATA / "skytrak.csv"), "-o", str(out)])
    stdout, stderr = capsys.readouterr()
    assert code == 0, stderr
    assert stdout.startswith(f"read {DATA / 'skytrak.csv'}: SkyTrak (detected)\n")
    assert "per club" in stdout and "model minus device" in stdout
    frame = pd.read_parquet(out)
    assert "Push/Pull (deg L-/R+)" in frame.columns and "device_carry_side_m" in frame.columns
    assert output.read_provenance(out)["source_format"] == "skytrak"
    line = next(s for s in stdout.splitlines() if s.startswith("all ") and " carry_m " in s)
    diff = frame["carry_m"] - frame["device_carry_m"]
    assert line.split()[-2:] == [
        f"{diff.mean():+.2f}",
        f"{math.sqrt((diff**2).mean()):.2f}",
    ]


def test_cli_bad_exports_are_one_line_exit_2_nothing_written(tmp_path, capsys):
    unknown = tmp_path / "unknown.csv"
    unknown.write_text("Shot,Speed (kph),Angle\n1,190,12\n", encoding="utf-8")
    export = tmp_path / "skytrak.csv"
    shutil.copy(DATA / "skytrak.csv", export)
    empty = tmp_path / "empty.csv"
    empty.write_text("", encoding="utf-8")
    out = str(tmp_path / "out.parquet")
    cases = [
        ([str(unknown)], "found Shot, Speed (kph), Angle; or an export of a format mcrun knows"),
        ([str(export), "--format", "garmin-r10"], "a Garmin Approach R10 export needs a column"),
        ([str(export), "--format", "nope"], "argument --format: invalid choice"),
        ([str(empty)], "no shots: the file is empty"),
    ]
    before = sorted(os.listdir(tmp_path))
    for argv, needle in cases:
        code = main(["replay", *argv, "-o", out])
        stdout, stderr = capsys.readouterr()
        assert code == 2 and stdout == "", (argv, stderr)
        assert stderr.startswith("mcrun: error: ") and stderr.count("\n") == 1, stderr
        assert needle in stderr, stderr
        assert sorted(os.listdir(tmp_path)) == before


def write(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_scenario_resamples_one_club_of_an_export(tmp_path):
    shutil.copy(DATA / "garmin-r10-metric.csv", tmp_path / "session.csv")
    text = '[launch]\nfile = "session.csv"\nclub = "driver"\n'
    spec = sc.load(write(tmp_path, text)).points[0].params["launch.file"]
    assert spec.n_rows == 1
    np.testing.assert_allclose(spec.columns["ball_speed"], [268.8 / 3.6], rtol=1e-12)
    np.testing.assert_allclose(spec.columns["spin"], [2684 * RPM], rtol=1e-12)
    path = write(tmp_path, '[launch]\nfile = "session.csv"\nclub = "5 Wood"\n')
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == (
        f"{path}: launch.club: {tmp_path / 'session.csv'}: no shot of club '5 Wood'; "
        "its clubs: 7 Iron, Driver"
    ).replace("launch.club", "launch.file")
    path = write(tmp_path, '[launch]\nfile = "session.csv"\nformat = "mevo"\n')
    with pytest.raises(sc.ScenarioError, match=r"launch.format: must be one of trackman"):
        sc.load(path)
    path = write(
        tmp_path,
        '[launch]\nball_speed = "70 m/s"\nlaunch_angle = 12\nspin = 300\nclub = "Driver"\n',
    )
    with pytest.raises(sc.ScenarioError, match=r"launch.club: only allowed with launch.file"):
        sc.load(path)


def test_bad_cells_fly_the_other_shots_and_say_why(tmp_path, capsys):
    """A SkyTrak export with ``--`` in a speed cell and a footer row: the good shots fly as in
    the clean file, the others keep their place as invalid_input with their reason; a clean
    file's output has no reason column."""
    lines = (DATA / "skytrak.csv").read_text(encoding="utf-8-sig").splitlines()
    dashes = lines[2].replace(",167.0,", ",--,")
    footer = "Average,,,,143.5,-0.4,13.6,4886,85,4891,223.5,237.9,-3.6,32.3,44.1"
    path = tmp_path / "skytrak.csv"
    path.write_text("\n".join([lines[0], lines[1], dashes, footer]) + "\n", encoding="utf-8")
    frame = replay.replay(path)
    clean = replay.replay(DATA / "skytrak.csv")
    assert "invalid_reason" not in clean.columns
    assert list(frame["status"]) == [OK, INVALID_INPUT, INVALID_INPUT]
    assert list(frame["invalid_reason"]) == [
        "",
        "Ball Speed (mph): '--' is not a number",
        "a summary row ('Average'), not a shot",
    ]
    assert frame["carry_m"].iloc[0] == clean["carry_m"].iloc[0]
    out = tmp_path / "out.parquet"
    assert main(["replay", str(path), "-o", str(out), "--quiet"]) == 0
    stderr = capsys.readouterr().err
    assert stderr.count("\n") == 1
    assert stderr.rstrip().endswith("row 2: Ball Speed (mph): '--' is not a number")
    assert list(pd.read_parquet(out)["invalid_reason"]) == list(frame["invalid_reason"])


def test_gspro_log_replays_its_shots(tmp_path, capsys):
    out = tmp_path / "log.parquet"
    code = main(["replay", str(DATA / "gspro-connector.log"), "-o", str(out), "--quiet"])
    stdout, stderr = capsys.readouterr()
    assert code == 0, stderr
    assert "GSPro Open Connect (JSON lines) (detected)" in stdout
    frame = pd.read_parquet(out)
    assert list(frame["status"]) == [OK, OK, OK, INVALID_INPUT]
    want = simulate(ball_speed_mps=147.5 * MPH, launch_angle_deg=14.3, spin_radps=2250 * RPM,
                    spin_axis_deg=-13.2, azimuth_deg=2.3).outcome  # fmt: skip
    assert frame["carry_m"].iloc[0] == pytest.approx(want["carry_m"], rel=1e-12)
    assert "4 message(s) without ball data skipped" in stderr


def test_gspro_fields_of_several_types_mark_their_shots_and_write(tmp_path, capsys):
    """A connector's messages whose field is text or a bool in one message and a number in the
    next (``"n/a"``, ``true``), an integer beyond a float, a field not read (ClubData): each
    shot with a value that is not a number is invalid_input with its reason, the others fly,
    the file is written (a pyarrow traceback before, exit 1)."""
    ball = '"VLA": 12, "TotalSpin": 2500, "SpinAxis": 0, "HLA": 0'
    messages = [
        f'{{"BallData": {{"Speed": "fast", {ball}}}, "ClubData": {{"Speed": true}}}}',
        f'{{"BallData": {{"Speed": 150, {ball}, "CarryDistance": "n/a"}}}}',
        f'{{"BallData": {{"Speed": true, {ball}, "CarryDistance": 250}}, '
        '"ClubData": {"Speed": 100}}',
        f'{{"BallData": {{"Speed": 1{"0" * 400}, {ball}}}}}',
    ]
    log = tmp_path / "mixed.jsonl"
    log.write_text("\n".join(messages) + "\n", encoding="utf-8")
    out = tmp_path / "mixed.parquet"
    assert main(["replay", str(log), "-o", str(out), "--quiet"]) == 0, capsys.readouterr().err
    frame = pd.read_parquet(out)
    assert list(frame["status"]) == [INVALID_INPUT, OK, INVALID_INPUT, INVALID_INPUT]
    assert frame["invalid_reason"].iloc[0] == "BallData.Speed: 'fast' is not a number"
    assert frame["invalid_reason"].iloc[2] == "BallData.Speed: 'True' is not a number"
    assert frame["invalid_reason"].iloc[3].startswith("BallData.Speed: '1000")
    want = simulate(ball_speed_mps=150 * MPH, launch_angle_deg=12.0, spin_radps=2500 * RPM)
    assert frame["carry_m"].iloc[1] == pytest.approx(want.outcome["carry_m"], rel=1e-12)


def test_a_cell_with_a_minus_that_is_not_ascii_s_says_so(tmp_path, capsys):
    """A spreadsheet's minus sign (U+2212) in a cell: the shot is invalid_input and its reason
    names the sign (it said only "'\u2212167' not read")."""
    table = tmp_path / "m.csv"
    table.write_text("ball_speed_mph,launch_deg,spin_rpm,azimuth_deg\n"
                     "167,10.9,2686,1\n167,10.9,2686,\u22121\n", encoding="utf-8")  # fmt: skip
    out = tmp_path / "m.parquet"
    assert main(["replay", str(table), "-o", str(out), "--quiet"]) == 0, capsys.readouterr().err
    frame = pd.read_parquet(out)
    assert list(frame["status"]) == [OK, INVALID_INPUT]
    assert frame["invalid_reason"].iloc[1] == (
        "azimuth_deg: '\u22121' not read: '\u2212' (U+2212) is not read as a minus sign: type '-'"
    )


def test_files_without_a_valid_shot_are_refused_one_line_nothing_written(tmp_path, capsys):
    """An export whose 20 rows are all blank; one whose every row is a footer; binary bytes;
    a 20,000-column header: one line naming the file, exit 2, nothing written, no traceback,
    never the file's bytes."""
    header = (DATA / "skytrak.csv").read_text(encoding="utf-8-sig").splitlines()[0]
    blank = tmp_path / "blank-rows.csv"
    blank.write_text(header + "\n" + ",,,,,,,,,,,,,,\n" * 20, encoding="utf-8")
    binary = tmp_path / "binary.csv"
    binary.write_bytes(b"\x00" * 5400)
    wide = tmp_path / "wide.csv"
    wide.write_text(",".join(f"c{k}" for k in range(20_000)) + "\n" + "1," * 19_999 + "1\n")
    out = tmp_path / "out.parquet"
    cases = [
        (blank, f"{blank}: no valid shot in its 20 rows; row 1: Ball Speed (mph): empty"),
        (binary, f"{binary}: not a text file"),
        (wide, f"{wide}: no recognisable column for ball_speed"),
    ]
    before = sorted(os.listdir(tmp_path))
    for path, start in cases:
        code = main(["replay", str(path), "-o", str(out)])
        stdout, stderr = capsys.readouterr()
        assert code == 2 and stdout == "", (path, stderr[:300])
        assert stderr.startswith(f"mcrun: error: {start}"), stderr[:300]
        assert stderr.count("\n") == 1 and len(stderr) < 600, stderr[:300]
        assert sorted(os.listdir(tmp_path)) == before


def garmin_session(path, rows):
    """A Garmin R10 export of ``rows`` shots: the imperial fixture's shot, its speed varied."""
    lines = (DATA / "garmin-r10-imperial.csv").read_text(encoding="utf-8-sig").splitlines()
    head, row = lines[:2], lines[2]
    body = (row.replace(",120.0,", f",{110 + k % 200 / 10:.1f},") for k in range(rows))
    path.write_text("\ufeff" + "\n".join([*head, *body]) + "\n", encoding="utf-8")
    return path


def test_a_long_session_is_flown_in_chunks_and_its_memory_bounded(tmp_path, monkeypatch):
    """The shots flown CHUNK at a time give the same numbers as all at once; replaying an
    export costs at most 1.1 kB of Python and numpy memory a row (the file's strings shared,
    the kernel's arrays a chunk at a time: 1.7 kB a row before; a million rows of this export,
    163 MB, peaked at 2.3 GB resident, now 1.06 GB)."""
    path = garmin_session(tmp_path / "long.csv", 30_000)
    replay.replay(DATA / "garmin-r10-imperial.csv")  # the kernel compiled or loaded
    tracemalloc.start()
    try:
        whole = replay.replay(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak / len(whole) < 1100, peak / len(whole)
    monkeypatch.setattr(replay, "CHUNK", 7)
    small = replay.replay(garmin_session(tmp_path / "short.csv", 40))
    pd.testing.assert_frame_equal(small, whole.iloc[:40], check_exact=True)


def test_a_number_too_large_to_be_a_float_is_said_as_such(tmp_path):
    """Garmin's ``1e999`` in a speed cell reads as an infinite number: the row is invalid and
    says so, not that 'inf' could not be read."""
    lines = (DATA / "garmin-r10-metric.csv").read_text(encoding="utf-8-sig").splitlines()
    cells = lines[2].split(",")
    cells[9] = "1e999"  # Ball Speed
    path = tmp_path / "garmin.csv"
    path.write_text("\n".join([lines[0], lines[1], ",".join(cells), lines[3]]) + "\n")
    frame = replay.replay(path)
    assert list(frame["status"]) == [INVALID_INPUT, OK]
    assert frame["invalid_reason"].iloc[0] == "Ball Speed: inf is not a finite number"
