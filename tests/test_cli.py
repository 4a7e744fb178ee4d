"""The command line, ``mcrun shot | bounce | models | turfs``: it must give exactly what the
Python API gives for the same inputs, reproduce the paper's numbers through its options, and
turn every bad input into one line ``mcrun: error: ...`` on stderr with exit code 2.

Most tests call ``main([...])`` in the test process; one runs the installed console script.
"""

import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun import api, cli, status
from mcrun.engine.schema import PLANE_FIELDS
from mcrun.physics import aero, turf

MPH = 0.44704  # m/s, exact
RPM = 2.0 * math.pi / 60.0  # rad/s

# A drive as a launch monitor reports it: 167 mph, 10.9 deg, 2686 rpm (TrackMan 2019 PGA Tour
# average driver).
DRIVE_ARGS = ["--ball-speed", "167mph", "--launch", "10.9", "--spin", "2686rpm"]
DRIVE_KWARGS = dict(
    ball_speed_mps=167 * MPH, launch_angle_deg=10.9, spin_radps=2686 * RPM
)  # 74.65568 m/s, 281.277 rad/s


def run(capsys, *argv):
    """(exit code, stdout, stderr) of ``mcrun argv``."""
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def table(text):
    """{field: value text} of a printed table (name, value, optional golf units)."""
    rows = {}
    for line in text.splitlines():
        name, value = line.split()[:2]
        rows[name] = value
    return rows


def assert_outcome_equal(got, expected, rel=1e-9):
    """Every outcome field of ``got`` (from JSON: null for NaN) equals ``expected``."""
    assert set(got) == set(PLANE_FIELDS) | {"status_name"}
    for name in PLANE_FIELDS:
        want = expected[name]
        if isinstance(want, float) and math.isnan(want):
            assert got[name] is None, name
        else:
            assert got[name] == pytest.approx(want, rel=rel, abs=1e-12), name


# --- shot ----------------------------------------------------------------------------------------


def test_shot_json_equals_api(capsys):
    """``--ball-speed 167mph --launch 10.9 --spin 2686rpm`` is simulate(74.65568 m/s, 10.9 deg,
    281.277 rad/s): every field to 1e-9 relative, status ok, nothing on stderr."""
    code, out, err = run(capsys, "shot", *DRIVE_ARGS, "--json")
    assert code == 0 and err == ""
    assert len(out.strip().splitlines()) == 1
    got = json.loads(out)
    expected = api.simulate(**DRIVE_KWARGS)
    assert_outcome_equal(got, expected.outcome)
    assert got["launch_speed_mps"] == pytest.approx(74.65568, rel=1e-12)
    assert got["launch_spin_radps"] == pytest.approx(281.2773, rel=1e-6)
    assert got["status_name"] == "ok" and got["status"] == status.OK
    assert math.copysign(1.0, got["carry_lateral_m"]) == 1.0  # (-0.0 before: the table's 0.0)


def test_shot_table_equals_api(capsys):
    """The default table shows every outcome field with the API's value to its 3 decimals,
    and the status by name."""
    code, out, err = run(capsys, "shot", *DRIVE_ARGS)
    assert code == 0 and err == ""
    rows = table(out)
    expected = api.simulate(**DRIVE_KWARGS).outcome
    assert set(rows) == set(PLANE_FIELDS)
    for name in PLANE_FIELDS:
        if name == "status":
            assert rows[name] == "ok"
        else:
            assert float(rows[name]) == pytest.approx(expected[name], abs=5.1e-4), name
    assert "(167.0 mph)" in out and "(2686 rpm)" in out


def test_shot_club_delivery_driver_55_mps(capsys):
    """Penner (2001) club model, driver M = 0.200 kg, loft 13.3 deg, 55 m/s (targets.md):
    ball launch 74.3 m/s, about 10.7 deg, 397 rad/s, each within 1 %."""
    code, out, _ = run(
        capsys, "shot", "--club-speed", "55", "--club-mass", "0.2", "--loft", "13.3", "--json"
    )
    assert code == 0
    got = json.loads(out)
    assert got["launch_speed_mps"] == pytest.approx(74.3, rel=0.01)
    assert got["launch_angle_deg"] == pytest.approx(10.7, rel=0.01)
    assert got["launch_spin_radps"] == pytest.approx(397.0, rel=0.01)
    # The default club mass is the driver's 0.200 kg and units are read: 200g, 123.03mph.
    code, out2, _ = run(
        capsys, "shot", "--club-speed", "123.0315mph", "--club-mass", "200g", "--loft",
        "13.3deg", "--json",
    )  # fmt: skip
    assert code == 0
    assert json.loads(out2)["launch_speed_mps"] == pytest.approx(got["launch_speed_mps"], 1e-6)


def test_shot_conditions_equal_api(capsys):
    """Turf, slope, wind (with a leading minus and units), weather and model options reach
    simulate() as the same SI keyword arguments."""
    argv = [
        "shot", *DRIVE_ARGS, "--azimuth", "-2.5deg", "--spin-axis", "4",
        "--turf", "fairway", "--mu", "0.3", "--stimp", "10ft", "--slope", "2",
        "--fall-line", "-90", "--aero", "ferguson2022", "--cd-scale", "1.05",
        "--wind", "-3mph,2mph", "--wind-profile", "log", "--wind-height", "10m",
        "--wind-param", "3cm", "--temperature", "68F", "--altitude", "1000ft",
        "--humidity", "30%", "--dt", "0.005", "--json",
    ]  # fmt: skip
    code, out, err = run(capsys, *argv)
    assert code == 0 and err == ""
    expected = api.simulate(
        **DRIVE_KWARGS,
        azimuth_deg=-2.5,
        spin_axis_deg=4.0,
        turf=api.resolve_turf("fairway", mu=0.3, stimp_m=3.048),
        slope_deg=2.0,
        fall_line_deg=-90.0,
        aero_model="ferguson2022",
        cd_scale=1.05,
        wind_mps=(-3 * MPH, 2 * MPH),
        wind_profile="log",
        wind_reference_height_m=10.0,
        wind_profile_parameter=0.03,
        temperature_c=20.0,
        altitude_m=304.8,
        relative_humidity=0.3,
        dt_s=0.005,
    )
    assert_outcome_equal(json.loads(out), expected.outcome)
    assert json.loads(out)["carry_lateral_m"] < 0.0  # pushed 2.5 deg left of the target line


def test_shot_trajectory_csv(capsys, tmp_path):
    """``--trajectory FILE`` writes the path (t_s, x_m, y_m, z_m, phase) ending at the rest
    point the outcome reports."""
    path = tmp_path / "drive.csv"
    code, out, _ = run(capsys, "shot", *DRIVE_ARGS, "--trajectory", str(path), "--json")
    assert code == 0
    got = json.loads(out)
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["t_s", "x_m", "y_m", "z_m", "phase"]
    assert set(frame["phase"]) == {"flight", "bounce", "roll"}
    assert frame["x_m"].iloc[-1] == pytest.approx(got["final_x_m"], abs=1e-6)
    assert frame["t_s"].iloc[-1] == pytest.approx(got["total_time_s"], abs=1e-6)


def test_shot_not_stopped_is_reported_not_an_error(capsys):
    """Uphill 10 deg, steeper than atan(rho_g) = 7.5 deg of the paper's green: the ball never
    stops. The outcome is printed with its status (exit 0) and one warning line on stderr."""
    code, out, err = run(
        capsys, "shot", "--club-speed", "55", "--loft", "13.3", "--slope", "10",
        "--fall-line", "180", "--json",
    )  # fmt: skip
    assert code == 0
    got = json.loads(out)
    assert got["status_name"] == "not_stopped" and got["status"] == status.NOT_STOPPED
    assert got["total_m"] < 0.0  # rolled back down the slope past the tee
    assert len(err.splitlines()) == 1
    assert err.startswith("mcrun: warning:") and "not_stopped" in err
    code, out, err = run(
        capsys, "shot", "--club-speed", "55", "--loft", "13.3", "--slope", "10",
        "--fall-line", "180",
    )  # fmt: skip
    assert code == 0 and table(out)["status"] == "not_stopped" and len(err.splitlines()) == 1


# --- bounce --------------------------------------------------------------------------------------


def test_bounce_drive_35_mps_club_json(capsys):
    """Penner (2002), drive from a 35 m/s club: lands 26.8 m/s at 68.0 deg with 224 rad/s,
    mu 0.40. Paper: mu_c = 0.23 (within 0.01), leaves rolling, first bounce 2.82 m (1 %)."""
    code, out, err = run(
        capsys, "bounce", "--speed", "26.8", "--angle", "68", "--spin", "224", "--json"
    )
    assert code == 0 and err == ""
    got = json.loads(out)
    assert got["mu_c"] == pytest.approx(0.23, abs=0.01)
    assert got["mode"] == "rolling"
    assert got["hop_height_m"] == pytest.approx(2.82, rel=0.01)
    expected = api.bounce_once(26.8, 68.0, 224.0, turf="green")
    assert got.pop("mode") == expected.pop("mode")
    assert got == pytest.approx(expected, rel=1e-9)


def test_bounce_nine_iron_firm_green_table(capsys):
    """Penner (2002) Fig. 8: the 9-iron landing (23.8 m/s at 34.0 deg, 1000 rad/s) on the firm
    green (mu 0.25 < mu_c 0.33) slides and bounces forward with backspin; critical backspin
    of eq. (10) 903 rad/s. Units are read: 53.24mph, 9549rpm."""
    code, out, err = run(
        capsys, "bounce", "--speed", "53.239mph", "--angle", "34deg", "--spin", "9549.3rpm",
        "--turf", "green", "--mu", "0.25",
    )  # fmt: skip
    assert code == 0 and err == ""
    rows = table(out)
    assert rows["mode"] == "sliding"
    assert float(rows["mu_c"]) == pytest.approx(0.33, abs=0.01)
    assert float(rows["rebound_angle_deg"]) > 0.0  # forward
    assert float(rows["rebound_spin_radps"]) > 0.0  # still backspin
    assert float(rows["critical_backspin_radps"]) == pytest.approx(903.0, rel=0.01)


# --- listings ------------------------------------------------------------------------------------


def test_models_lists_every_model_and_marks_the_default(capsys):
    code, out, _ = run(capsys, "models")
    assert code == 0
    for name in aero.MODELS:
        assert name in out
    assert f"{aero.DEFAULT_MODEL}  (default)" in out
    code, out, _ = run(capsys, "models", "--json")
    listed = json.loads(out)
    assert [m["name"] for m in listed] == list(aero.MODELS)
    assert [m["name"] for m in listed if m["default"]] == [aero.DEFAULT_MODEL]


def test_turfs_lists_presets_and_marks_estimates(capsys):
    code, out, _ = run(capsys, "turfs", "--json")
    assert code == 0
    listed = {t["name"]: t for t in json.loads(out)}
    assert set(listed) == set(turf.PRESETS)
    for name, preset in turf.PRESETS.items():
        assert listed[name]["rho_g"] == preset.rho_g
        assert (listed[name]["source"] == "estimate") == (name in turf.ESTIMATED_PRESETS)
    # The paper's rho_g = 0.131 is a Stimp of about 1.82 m (6.0 ft).
    assert listed["green"]["stimp_m"] == pytest.approx(1.82, abs=0.01)
    code, out, _ = run(capsys, "turfs")
    assert code == 0 and len(out.splitlines()) == 1 + len(turf.PRESETS)


# --- bad input -----------------------------------------------------------------------------------

BAD_SHOTS = {
    "nan speed": ["--ball-speed", "nan", "--launch", "10.9", "--spin", "2686rpm"],
    "speed out of range": ["--ball-speed", "500", "--launch", "10.9", "--spin", "2686rpm"],
    "unknown unit": ["--ball-speed", "167mpg", "--launch", "10.9", "--spin", "2686rpm"],
    "unknown turf": [*DRIVE_ARGS, "--turf", "lava"],
    "unknown model": [*DRIVE_ARGS, "--aero", "nosuch"],
    "negative spin": ["--ball-speed", "167mph", "--launch", "10.9", "--spin", "-5"],
    "ball and club": [*DRIVE_ARGS, "--club-speed", "40", "--loft", "13.3"],
    "missing spin": ["--ball-speed", "167mph", "--launch", "10.9"],
    "nothing given": [],
    "half a club": ["--club-speed", "40"],
    "mixed wind units": [*DRIVE_ARGS, "--wind", "10mph,-3"],
    "wind too strong": [*DRIVE_ARGS, "--wind", "60,0"],
    "bad number": [*DRIVE_ARGS, "--mu", "abc"],
    "bad friction": [*DRIVE_ARGS, "--mu", "-0.1"],
    "bad wind profile": [*DRIVE_ARGS, "--wind-profile", "sine"],
    "a parameter for the uniform wind": [*DRIVE_ARGS, "--wind-param", "5"],
    "pressure and altitude": [*DRIVE_ARGS, "--pressure", "1000hPa", "--altitude", "100"],
    "humidity over 100 %": [*DRIVE_ARGS, "--humidity", "150%"],
    "temperature unit": [*DRIVE_ARGS, "--temperature", "20X"],
    "unwritable trajectory": [*DRIVE_ARGS, "--trajectory", "/dev/null/t.csv"],
    "unknown option": [*DRIVE_ARGS, "--bogus"],
    "option without value": [*DRIVE_ARGS, "--wind"],
}


@pytest.mark.parametrize("argv", BAD_SHOTS.values(), ids=BAD_SHOTS.keys())
def test_bad_shot_input_is_one_line_and_exit_2(capsys, argv):
    code, out, err = run(capsys, "shot", *argv)
    assert code == 2
    assert out == ""
    assert len(err.splitlines()) == 1
    assert err.startswith("mcrun: error: ")


def test_a_thread_count_numba_cannot_start_with_is_one_line():
    """NUMBA_NUM_THREADS=0 raised Numba's ValueError, a traceback, as the package imported
    Numba; now the command line says so before anything imports it (as a new process)."""
    env = {**os.environ, "NUMBA_NUM_THREADS": "0"}
    done = subprocess.run(
        [sys.executable, "-c", "from mcrun.cli import main; raise SystemExit(main())", "shot"],
        env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr == (
        "mcrun: error: NUMBA_NUM_THREADS='0': allowed: a whole number 1 or more (the threads "
        "the kernels run on; unset, every core)\n"
    )


def test_a_cache_folder_numba_cannot_write_is_one_line(tmp_path, monkeypatch, capsys):
    """Numba passes over a NUMBA_CACHE_DIR it cannot write without a word (a read-only cache
    of compiled kernels was said to be loaded, and the kernels were the ones beside the
    sources), and where it can write a cache nowhere its first compile was a RuntimeError, a
    traceback: each is one line, exit code 2."""
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(blocker / "cache"))
    assert cli.main(["turfs"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert err.startswith(f"mcrun: error: NUMBA_CACHE_DIR='{blocker / 'cache'}': cannot write ")
    assert err.endswith("allowed: a folder this user can write (Numba passes over one it "
                        "cannot), or unset\n")  # fmt: skip
    monkeypatch.setenv("NUMBA_CACHE_DIR", "~/numba-cache")  # (Numba made a folder named ~)
    assert cli.main(["turfs"]) == 2 and "~ is not expanded" in capsys.readouterr().err
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "made" / "cache"))  # (made, as Numba)
    assert cli.main(["turfs"]) == 0 and (tmp_path / "made" / "cache").is_dir()
    capsys.readouterr()

    # Numba finding no folder to cache in (its own locators replaced by one that finds none):
    # its RuntimeError as the kernels' modules import, a traceback before.
    (tmp_path / "nowhere.py").write_text(
        "class NoLocator:\n"
        "    @classmethod\n"
        "    def from_function(cls, py_func, py_file):\n"
        "        return None\n"
    )
    env = {**os.environ, "NUMBA_CACHE_LOCATOR_CLASSES": "nowhere.NoLocator"}
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), env.get("PYTHONPATH", "")])
    env.pop("NUMBA_CACHE_DIR", None)
    done = subprocess.run(
        [sys.executable, "-c", "from mcrun.cli import main; raise SystemExit(main())", "turfs"],
        env=env, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.startswith("mcrun: error: Numba can write its cache of the compiled")
    assert done.stderr.count("\n") == 1


@pytest.mark.parametrize(
    "command, argv, says",
    [
        ("shot", ["--ball-speed", "0", "--launch", "11", "--spin", "280"],
         "--ball-speed (ball_speed_mps) = 0 is outside the allowed range [0.5, 120]"),
        ("shot", ["--club-speed", "40", "--loft", "100"],
         "--loft (loft_deg) = 100 is outside the allowed range [0, 70]"),
        ("bounce", ["--speed", "20", "--angle", "95", "--spin", "100"],
         "--angle (impact_angle_deg) = 95 is outside the allowed range [0, 89.9]"),
        ("bounce", ["--speed", "20", "--angle", "45", "--spin", "1e9"],
         "--spin (backspin_radps) = 1e+09 is outside the allowed range [-2000, 2000]"),
        # (1e9 m ran a shot that never stopped; 0.01mm named a rho_g never given)
        ("shot", [*DRIVE_ARGS, "--stimp", "1e9ft"],
         "--stimp 1e9ft: allowed: 0.33 ft to 19.7 ft (a Stimpmeter reading)"),
        # A Stimp reading in bare numbers is feet to its users: 5 was read as 5 m (16.4 ft).
        ("shot", [*DRIVE_ARGS, "--stimp", "5"], "--stimp 5: give its unit, e.g. 10ft"),
        # The conditions' range errors named the API's field alone.
        ("shot", [*DRIVE_ARGS, "--slope", "89"],
         "--slope (slope_deg) = 89 is outside the allowed range [0, 45]"),
        # A bare spin or speed is SI; one in range only in rpm or mph was meant in it.
        ("shot", ["--ball-speed", "167", "--launch", "11", "--spin", "2686rpm"],
         "--ball-speed (ball_speed_mps) = 167 is outside the allowed range [0.5, 120] (a bare "
         "number is m/s: for 167 mph, give 167mph; for 167 km/h, give 167km/h)"),
        # (as typed, not rounded; with its unit, or out of range in rpm too, no advice)
        ("shot", ["--ball-speed", "60mph", "--launch", "30", "--spin", "12345.67"],
         "--spin (spin_radps) = 12345.7 is outside the allowed range [0, 2000] (a bare number "
         "is rad/s: for 12345.67 rpm, give 12345.67rpm)"),
        ("shot", ["--ball-speed", "60mph", "--launch", "30", "--spin", "8000rad/s"],
         "--spin (spin_radps) = 8000 is outside the allowed range [0, 2000]"),
        ("shot", ["--ball-speed", "60mph", "--launch", "30", "--spin", "80000"],
         "--spin (spin_radps) = 80000 is outside the allowed range [0, 2000]"),
        ("shot", ["--ball-speed", "60mph", "--launch", "30", "--spin", "8000"],
         "--spin (spin_radps) = 8000 is outside the allowed range [0, 2000] (a bare number is "
         "rad/s: for 8000 rpm, give 8000rpm)"),
        ("bounce", ["--speed", "20", "--angle", "45", "--spin", "3000"],
         "--spin (backspin_radps) = 3000 is outside the allowed range [-2000, 2000] (a bare "
         "number is rad/s: for 3000 rpm, give 3000rpm)"),
        ("shot", [*DRIVE_ARGS, "--humidity", "50"],
         "--humidity 50: allowed: a share from 0 to 1 (for 50 %, give 0.5 or 50%)"),
        # (with its unit, no such advice: 150% is not 1.5 %)
        ("shot", [*DRIVE_ARGS, "--humidity", "150%"],
         "--humidity (relative_humidity) = 1.5 is outside the allowed range [0, 1]"),
        ("shot", ["--ball-speed", "60"],
         "a ball launch needs --launch, --spin (or a club delivery: --club-speed and --loft)"),
        # Ignored before: the same numbers with or without them.
        ("shot", [*DRIVE_ARGS, "--wind", "5,0", "--wind-height", "2"],
         "--wind-height: is for --wind-profile log or power (a uniform wind is the same at "
         "every height)"),
        ("shot", [*DRIVE_ARGS, "--air-density", "1.2", "--altitude", "3000"],
         "--altitude: the air's density is given (--air-density), which is all the pressure "
         "sets: give one or the other"),
        ("shot", [*DRIVE_ARGS, "--trajectory", "-"],
         "--trajectory -: a file's path (the shot's table goes to stdout)"),
        # An empty value: -o '' wrote into the current folder, --plot '' drew nothing.
        ("shot", [*DRIVE_ARGS, "--trajectory", ""],
         "--trajectory: empty: give a value (see 'mcrun shot --help')"),
        ("scenarios", ["--dir", " "], "--dir: empty: give a value (see 'mcrun scenarios --help')"),
        ("paper", ["-o", ""], "-o: empty: give a value (see 'mcrun paper --help')"),
        ("paper", ["-o", "p", "--dpi", "٧٢"], "argument --dpi: '٧٢': only ASCII digits (0-9) "
         "are accepted, not '٧' (see 'mcrun paper --help')"),
        ("shot", [*DRIVE_ARGS, "--stimp", "0.01mm"],
         "--stimp 0.01mm: allowed: 0.33 ft to 19.7 ft (a Stimpmeter reading)"),
    ],
)  # fmt: skip
def test_a_value_out_of_range_names_its_option(capsys, command, argv, says):
    """The API's range errors name its values (ball_speed_mps); the command names the option
    that gave it too."""
    code, out, err = run(capsys, command, *argv)
    assert (code, out, err) == (2, "", f"mcrun: error: {says}\n")


def test_a_trajectory_is_parquet_by_its_name_and_other_names_are_refused(capsys, tmp_path):
    """``--trajectory t.parquet`` writes Parquet, the CSV's values to the last bit (it wrote a
    CSV under that name); a name of another suffix is refused before the shot is flown."""
    csv_path, parquet_path = tmp_path / "t.csv", tmp_path / "t.parquet"
    for path in (csv_path, parquet_path):
        assert run(capsys, "shot", *DRIVE_ARGS, "--trajectory", str(path))[0] == 0
    written, read = pd.read_parquet(parquet_path), pd.read_csv(csv_path)
    assert list(written.columns) == list(read.columns)
    for column in ("t_s", "x_m", "y_m", "z_m"):
        np.testing.assert_array_equal(written[column].to_numpy(), read[column].to_numpy())
    assert list(written["phase"].astype(str)) == list(read["phase"])
    code, out, err = run(capsys, "shot", *DRIVE_ARGS, "--trajectory", str(tmp_path / "t.txt"))
    assert (code, out) == (2, "") and err.endswith("(or .csv.gz, .csv.bz2...) or .parquet\n")
    assert not (tmp_path / "t.txt").exists()
    assert run(capsys, "shot", *DRIVE_ARGS, "--trajectory", str(tmp_path / "t.csv.gz"))[0] == 0
    pd.testing.assert_frame_equal(pd.read_csv(tmp_path / "t.csv.gz"), read)


def test_a_trajectory_s_missing_folder_is_made(capsys, tmp_path):
    """As every command's output: a folder that is missing is made (it was refused)."""
    path = tmp_path / "paths" / "drive.csv"
    code, _, _ = run(capsys, "shot", *DRIVE_ARGS, "--trajectory", str(path))
    assert code == 0 and path.read_text().startswith("t_s,x_m,y_m,z_m,phase")


def test_a_trajectory_that_cannot_be_written_is_refused_before_the_shot(
    capsys, tmp_path, monkeypatch
):
    monkeypatch.setattr(api, "simulate", lambda **k: pytest.fail("the shot was flown"))
    (tmp_path / "a-file").write_text("")
    for path, says in ((tmp_path / "a-file" / "t.csv", "is not a folder"),
                       (tmp_path, "is a folder; give a file name")):  # fmt: skip
        code, out, err = run(capsys, "shot", *DRIVE_ARGS, "--trajectory", str(path))
        assert code == 2 and out == "" and err.count("\n") == 1
        assert err.startswith(f"mcrun: error: --trajectory {path}: ") and says in err


BAD_BOUNCES = {
    "angle from the vertical over 90": ["--speed", "26.8", "--angle", "95", "--spin", "224"],
    "missing angle": ["--speed", "26.8", "--spin", "224"],
    "unknown turf": ["--speed", "26.8", "--angle", "68", "--spin", "224", "--turf", "lava"],
    "infinite spin": ["--speed", "26.8", "--angle", "68", "--spin", "inf"],
}


@pytest.mark.parametrize("argv", BAD_BOUNCES.values(), ids=BAD_BOUNCES.keys())
def test_bad_bounce_input_is_one_line_and_exit_2(capsys, argv):
    code, out, err = run(capsys, "bounce", *argv)
    assert (code, out, len(err.splitlines())) == (2, "", 1)
    assert err.startswith("mcrun: error: ")


def test_bounce_input_ranges_are_those_of_the_api(capsys):
    """mcrun bounce checks its angle and backspin against api.RANGES, as every input."""
    for name, value in (("impact_angle_deg", 89.95), ("backspin_radps", -2000.5)):
        lo, hi = api.RANGES[name]
        angle, spin = (value, 224.0) if name == "impact_angle_deg" else (68.0, value)
        with pytest.raises(api.InputError, match=rf"{name} = .* \[{lo:g}, {hi:g}\]"):
            api.bounce_once(26.8, angle, spin)
    api.bounce_once(26.8, api.RANGES["impact_angle_deg"][1], api.RANGES["backspin_radps"][0])
    _, _, err = run(capsys, "bounce", "--speed", "26.8", "--angle", "95", "--spin", "224")
    assert "impact_angle_deg" in err and "[0, 89.9]" in err
    # A roll's resistance was taken and did nothing to the impact.
    for field in ("rho_g", "stimp_m"):
        with pytest.raises(api.InputError, match=rf"^{field}: the roll's resistance, which one"):
            api.bounce_once(26.8, 68.0, 224.0, **{field: 3.0})


def test_the_api_names_an_unknown_argument_and_a_turf_that_is_none():
    """A misspelt keyword or a turf's field given to ``simulate`` (a TypeError naming a private
    function), and a turf that is neither a name nor a Turf (an AttributeError): InputError
    naming it and what is allowed; ``resolve_turf`` checks a Stimp reading's range."""
    launch = {"launch_angle_deg": 11.0, "spin_radps": 280.0}
    for given, name in (({"ball_speed": 70.0}, "ball_speed"), ({"mu": 0.3}, "mu")):
        with pytest.raises(api.InputError, match=rf"^unknown argument '{name}'; allowed: "
                           "ball_speed_mps, launch_angle_deg"):  # fmt: skip
            api.simulate(**{"ball_speed_mps": 70.0, **launch, **given})
    for wrong in (None, 3):
        with pytest.raises(api.InputError, match=rf"^turf {wrong}: allowed: a preset's name"):
            api.simulate(ball_speed_mps=70.0, turf=wrong, **launch)
    with pytest.raises(api.InputError, match=r"^stimp_m = 1e\+09 is outside .*\[0.1, 6\]"):
        api.resolve_turf("green", stimp_m=1e9)


def test_a_turf_is_numbers_and_rolls_a_hop_below_its_critical_height():
    """A Turf whose field is text or a bool is refused (text was a TypeError of a comparison),
    and a critical height of 0, which the kernel takes for an invalid input (every shot
    invalid_input, exit 0, from a scenario that validated), is out of range."""
    launch = {"ball_speed_mps": 50.0, "launch_angle_deg": 20.0, "spin_radps": 500.0}
    green = turf.PRESETS["green"]
    cases = (
        ("mu", "0.4", "must be a number, got '0.4'"),
        ("rho_g", True, "must be a number, got True"),
        ("critical_height_m", 0.0, "= 0.0 is outside [0.0001, 1.0]"),
    )
    for field, value, says in cases:
        with pytest.raises(api.InputError, match=rf"^turf {field} {re.escape(says)}$"):
            api.simulate(**launch, turf=green._replace(**{field: value}))
    low = api.simulate(**launch, turf=green._replace(critical_height_m=1e-4)).outcome
    assert low["status"] == status.OK


def test_a_club_delivery_launches_within_a_launch_s_ranges():
    """A loft of 0 with a club of 1 kg launched the ball at 137.6 m/s, a launch refused when
    given directly (at most 120 m/s)."""
    says = r"^the club's delivery launches the ball with ball_speed_mps = 137.6, outside the "
    with pytest.raises(api.InputError, match=says + r"allowed range \[0.5, 120\]$"):
        api.simulate(club_speed_mps=90.0, loft_deg=0.0, club_mass_kg=1.0)
    assert api.simulate(club_speed_mps=45.0, loft_deg=13.3).outcome["status"] == status.OK


def test_the_api_takes_its_wind_as_two_numbers_in_order():
    """A set (no order: {5.0, 0.0} flew as a crosswind), text (split into its characters: "50"
    flew as (5, 0)), one number or three are refused, and a number beyond a float (10**400, an
    OverflowError before) is not finite; a list, a tuple or an array of two flies alike."""
    launch = {"ball_speed_mps": 74.66, "launch_angle_deg": 10.9, "spin_radps": 281.3}
    for wind in ({5.0, 0.0}, "50", "5,0", 5.0, (1.0, 2.0, 3.0), {"x": 1.0}):
        with pytest.raises(api.InputError, match=r"^wind_mps .*: allowed: two numbers \(m/s\)"):
            api.simulate(**launch, wind_mps=wind)
    with pytest.raises(api.InputError, match=r"^wind_mps must be finite, got 1000"):
        api.simulate(**launch, wind_mps=(10**400, 0.0))
    with pytest.raises(api.InputError, match=r"^ball_speed_mps must be finite, got 1000"):
        api.simulate(**{**launch, "ball_speed_mps": 10**400})
    tail = api.simulate(**launch, wind_mps=(5.0, 0.0)).outcome
    for wind in ([5.0, 0.0], np.array([5.0, 0.0]), (5, 0)):
        assert api.simulate(**launch, wind_mps=wind).outcome == tail
    assert tail["final_y_m"] == api.simulate(**launch).outcome["final_y_m"]


def test_the_api_refuses_a_bool_text_or_nan_where_a_number_goes():
    """``simulate(ball_speed_mps=True)`` (flown at 1 m/s), a wind profile's parameter that is
    NaN (a refused shot, not an error) or text (a TypeError), a turf's field as text (a
    ValueError), a number as text: InputError naming the argument."""
    launch = {"ball_speed_mps": 70.0, "launch_angle_deg": 11.0, "spin_radps": 280.0}
    with pytest.raises(api.InputError, match=r"^ball_speed_mps must be a number, got True$"):
        api.simulate(**{**launch, "ball_speed_mps": True})
    for given, says in ((float("nan"), "must be finite, got nan"), ("x", "must be a number")):
        with pytest.raises(api.InputError, match=rf"^wind_profile_parameter {says}"):
            api.simulate(**launch, wind_profile="power", wind_profile_parameter=given)
    with pytest.raises(api.InputError, match=r"^turf mu must be a number, got 'x'$"):
        api.resolve_turf("green", mu="x")
    with pytest.raises(api.InputError, match=r"^wind_profile_parameter: the power profile with "
                       r"an exponent of 1 from a reference height of 0.1 m makes the wind at 50 m "
                       r"500 times the reference wind; allowed: at most 4 \("):  # fmt: skip
        api.simulate(**launch, wind_profile="power", wind_reference_height_m=0.1,
                     wind_profile_parameter=1.0)  # fmt: skip
    # The atmosphere's profiles fly: a power law's steepest exponent from 10 m, a log law over
    # a forest's roughness, the 1/7 law from a handheld 2 m reading.
    atmosphere = (("power", 10.0, 0.6), ("log", 10.0, 2.0), ("power", 2.0, 1 / 7))
    for profile, height, parameter in atmosphere:
        assert api.simulate(**launch, wind_mps=(5.0, 0.0), wind_profile=profile,
                            wind_reference_height_m=height,
                            wind_profile_parameter=parameter).outcome["status"] == 0  # fmt: skip
    # A uniform wind has no reference height nor parameter: given, they were ignored.
    for given in ("wind_reference_height_m", "wind_profile_parameter"):
        with pytest.raises(api.InputError, match=rf"^{given}: is for wind_profile 'log' or "):
            api.simulate(**launch, wind_mps=(5.0, 0.0), **{given: 2.0})
    # Text is not a number, "70" no more than "70 m/s" (which was refused where "70" flew).
    for given in ("70", "70 m/s", np.str_("70")):
        with pytest.raises(api.InputError, match=r"^ball_speed_mps must be a number, got "):
            api.simulate(**{**launch, "ball_speed_mps": given})
    with pytest.raises(api.InputError, match=r"^wind_profile_parameter must be a number, got "):
        api.simulate(**launch, wind_mps=(-5.0, 2.0), wind_profile="power",
                     wind_profile_parameter="0.1")  # fmt: skip


def test_the_api_names_a_file_argument_that_is_not_a_path():
    """``replay``, ``read_session``, ``load_hole`` and ``load_elevation`` given None or a
    number (a TypeError or AttributeError before): their one-line error naming it."""
    from mcrun.hole.elevation import ElevationError, load_elevation
    from mcrun.hole.errors import HoleError
    from mcrun.hole.hole import load_hole
    from mcrun.run.monitors import read_session
    from mcrun.run.replay import replay

    cases = [
        (replay, api.InputError, "shots {}: allowed: a Session, a DataFrame or a file's path"),
        (read_session, api.InputError, "session {}: allowed: a launch-monitor export's path"),
        (load_hole, HoleError, "hole {}: allowed: a hole file's path"),
        (load_elevation, ElevationError, "elevation {}: allowed: a .tif/.tiff, .asc or .csv"),
    ]
    for function, error, says in cases:
        for wrong in (None, 123):
            with pytest.raises(error, match="^" + re.escape(says.format(wrong))):
                function(wrong)


def test_error_messages_name_the_problem(capsys):
    """The one line says what is wrong and what is allowed."""
    _, _, err = run(capsys, "shot", "--ball-speed", "500", "--launch", "10.9", "--spin", "1")
    assert "ball_speed_mps" in err and "[0.5, 120]" in err
    _, _, err = run(capsys, "shot", *DRIVE_ARGS, "--turf", "lava")
    assert "lava" in err and "green" in err
    _, _, err = run(capsys, "shot", "--ball-speed", "167mpg", "--launch", "10.9", "--spin", "1")
    assert "--ball-speed" in err and "mph" in err


def test_no_command_and_help(capsys):
    code, out, err = run(capsys)
    assert (code, out, len(err.splitlines())) == (2, "", 1)
    code, out, err = run(capsys, "shot", "--help")
    assert code == 0 and err == ""
    for text in ("positive to the right", "tailwind", "bare: deg", "bare: m/s", "rpm"):
        assert text in out


def test_installed_console_script_exits_2_without_traceback():
    """The installed ``mcrun`` script: a NaN ball speed is one error line and exit code 2."""
    script = shutil.which("mcrun") or str(Path(sys.executable).parent / "mcrun")
    result = subprocess.run(
        [script, "shot", "--ball-speed", "nan", "--launch", "10.9", "--spin", "2686rpm"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2
    assert result.stdout == ""
    assert "Traceback" not in result.stderr
    assert result.stderr.splitlines() == [
        "mcrun: error: --ball-speed: cannot read 'nan' as a speed: not a finite number"
    ]


# --- compiling -----------------------------------------------------------------------------------


def test_run_says_the_compile_apart_from_its_rate(tmp_path, capsys, monkeypatch):
    """When the kernel is not in numba's cache, the command line compiles it before the run,
    says so and how long it took on stderr; the run's line gives its own time and rate."""
    monkeypatch.setattr(cli, "_kernel_cached", lambda kind, kernels=("batch",): False)
    scenario = Path(__file__).parents[1] / "scenarios" / "pga-driver.toml"
    code, out, err = run(
        capsys, "run", str(scenario), "-n", "200", "-o", str(tmp_path / "run"), "--quiet"
    )
    assert code == 0, err
    lines = err.splitlines()
    assert len(lines) == 2 and lines[0].startswith("mcrun: compiling the kernels"), err
    assert re.fullmatch(r"mcrun: compiled the kernels in \d+ s", lines[1]), err
    rate = re.search(r"^200 shots in (\d+\.\d) s \(([\d,]+) shots/s", out, re.MULTILINE)
    assert rate is not None, out
    assert float(rate[1]) < 5.0  # the run of 200 shots alone, not a compile


def test_run_on_a_hole_says_the_terrain_kernels_compile(tmp_path, capsys, monkeypatch):
    """A run on a hole whose terrain's kernel is not compiled: that compile is said, with its
    time, before the run (it was silent for 62 s once), and the run's time and rate are its
    own; the plane's kernel, which it does not run, is not compiled."""
    from mcrun.cli import run as run_command
    from mcrun.engine import warmup

    events = []

    def not_cached(ground, kernels=("batch",)):
        return events.append(ground) or False

    monkeypatch.setattr(cli, "_kernel_cached", not_cached)

    def warm_up(grounds, kernels=("batch",)):
        events.append(("compile", grounds))
        return (warmup.WarmUp(grounds[0], 61.6, False),)

    monkeypatch.setattr(warmup, "warm_up", warm_up)
    run_scenario = run_command.local.run_scenario
    monkeypatch.setattr(
        run_command.local,
        "run_scenario",
        lambda *a, **k: events.append("run") or run_scenario(*a, **k),
    )
    code, out, err = run(
        capsys, "run", "par3-over-water", "-n", "200", "-o", str(tmp_path / "run"), "--quiet"
    )
    assert code == 0, err
    assert events == ["terrain", ("compile", ("terrain",)), "run"]
    assert err.splitlines() == [
        "mcrun: compiling the kernel for a hole's ground (first run on a hole after install; "
        "cached for the next runs)",
        "mcrun: compiled the kernel for a hole's ground in 62 s",
    ]
    rate = re.search(r"^200 shots in (\d+\.\d) s", out, re.MULTILINE)
    assert rate is not None and float(rate[1]) < 30.0, out


def test_a_run_on_the_plane_compiles_no_terrain_kernel(tmp_path, capsys, monkeypatch):
    asked = []

    def cached(ground, kernels=("batch",)):
        return asked.append(ground) or True

    monkeypatch.setattr(cli, "_kernel_cached", cached)
    code, _, err = run(
        capsys, "run", "pga-driver", "-n", "100", "-o", str(tmp_path / "run"), "--quiet"
    )
    assert code == 0 and err == "" and asked == ["plane"]


def test_compile_of_the_single_shot_kernel(capsys, monkeypatch):
    monkeypatch.setattr(cli, "_kernel_cached", lambda kind, kernels=("batch",): False)
    code, out, err = run(capsys, "shot", *DRIVE_ARGS, "--json")
    assert code == 0 and json.loads(out)["status_name"] == "ok"
    assert re.fullmatch(
        r"mcrun: compiling the kernels [^\n]*\nmcrun: compiled the kernels in \d+ s\n", err
    ), err


def test_ctrl_c_in_validate_is_one_line_and_exit_130(capsys, monkeypatch):
    """Ctrl-C during a long ``mcrun validate`` (here while it describes the points) ends like
    Ctrl-C in ``mcrun run``: one line on stderr, exit code 130, no traceback."""
    from mcrun.cli import run as run_command

    def interrupted(scenario):
        raise KeyboardInterrupt

    monkeypatch.setattr(run_command, "describe", interrupted)
    try:
        code, out, err = run(capsys, "validate", "pga-driver")
    except KeyboardInterrupt:
        pytest.fail("Ctrl-C escaped mcrun validate as a traceback")
    assert code == 130 and out == ""
    assert err == "mcrun: interrupted\n"


def test_only_ascii_digits_and_the_degree_sign(capsys):
    """``１６７mph`` (full-width digits, which float() reads) is refused in one line, for a
    quantity and for a plain number; ``10.9°`` is ``10.9deg``."""
    cases = [
        ("--ball-speed", "１６７mph", ["--launch", "10.9", "--spin", "2686rpm"]),
        ("--mu", "０.４", DRIVE_ARGS),
    ]
    for option, value, others in cases:
        code, out, err = run(capsys, "shot", *others, option, value)
        assert code == 2 and out == ""
        assert err == (
            f"mcrun: error: {option}: cannot read {value!r} as "
            f"{'a speed' if option == '--ball-speed' else 'a number'}: "
            f"only ASCII digits (0-9) are accepted, not {value[0]!r}\n"
        )
    degrees = ["--ball-speed", "167mph", "--launch", "10.9°", "--spin", "2686rpm", "--json"]
    code, out, err = run(capsys, "shot", *degrees)
    assert code == 0 and json.loads(out)["launch_angle_deg"] == 10.9


def test_not_stopped_warning_names_the_ground(capsys):
    """On level ground with rho_g 0 the ball never stops rolling (it ends not_stopped at the
    roll's bounds): the warning says so and talks of no slope; on a slope steeper than
    atan(rho_g) it names the slope."""
    code, out, err = run(capsys, "shot", *DRIVE_ARGS, "--rho-g", "0")
    assert code == 0 and table(out)["status"] == "not_stopped"
    assert err == (
        "mcrun: warning: the shot ended with status not_stopped: still rolling after 120 s or "
        "1000 m (with no rolling resistance, rho_g 0, a ball on level ground never stops "
        "rolling)\n"
    )
    code, out, err = run(capsys, "shot", *DRIVE_ARGS, "--turf", "green", "--slope", "10")
    assert code == 0 and table(out)["status"] == "not_stopped"
    assert err.startswith("mcrun: warning: the shot ended with status not_stopped: ")
    assert "(on a slope of 10 deg, steeper than atan(rho_g) = 7.5 deg, the ball never stops)" in err


# --- layout --------------------------------------------------------------------------------------


def test_only_the_command_line_reads_arguments_and_prints_errors():
    """The command line sits on top: no module outside mcrun/cli imports it or argparse, and
    the line ``mcrun: error:`` is written in cli/__init__.py alone (its error handler and its
    parser's usage errors)."""
    import ast

    package = Path(cli.__file__).parents[1]
    writers = set()
    for path in sorted(package.rglob("*.py")):
        name = path.relative_to(package).as_posix()
        text = path.read_text(encoding="utf-8")
        if 'f"mcrun: error: ' in text or '"mcrun: error: "' in text:
            writers.add(name)
        if name.startswith("cli/"):
            continue
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Import):
                imported = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                imported = [node.module or ""]
                if node.module == "mcrun":
                    imported += [f"mcrun.{alias.name}" for alias in node.names]
            else:
                continue
            for module in imported:
                assert module != "argparse", name
                assert module != "mcrun.cli" and not module.startswith("mcrun.cli."), name
    assert writers == {"cli/__init__.py"}


@pytest.mark.parametrize(
    "argv, kernels",
    [
        (["shot", "--ball-speed", "60", "--launch", "12", "--spin", "600"], ("batch",)),
        (["shot", "--ball-speed", "60", "--launch", "12", "--spin", "600", "--trajectory",
          "PATH"], ("traced",)),
        (["run", "pga-driver", "-n", "100", "--trajectories", "10", "-o", "PATH"],
         ("batch", "traced")),
    ],
)  # fmt: skip
def test_a_command_compiles_the_kernels_it_runs(argv, kernels, tmp_path, capsys, monkeypatch):
    """A shot that records its path runs the traced kernel (alone: the batch kernel carries no
    recording), and a run that writes trajectories runs it too, which a fresh install compiles:
    it is asked for (and said) before the command's work, not compiled silently within it."""
    asked = []

    def cached(ground, kernels=("batch",)):
        return asked.append((ground, kernels)) or True

    monkeypatch.setattr(cli, "_kernel_cached", cached)
    argv = [str(tmp_path / "out.csv") if a == "PATH" else a for a in argv]
    assert cli.main([*argv, "--quiet"] if argv[0] == "run" else argv) == 0
    capsys.readouterr()
    assert asked[0] == ("plane", kernels)


def test_a_seed_is_named_as_typed_and_said_as_the_integer_read(capsys):
    """``aim --seed`` named its API's "seed"; ``putt`` printed the seed as typed ("1.5e3")."""
    code, _, err = run(capsys, "aim", "par3-over-water", "-n", "10", "--seed", "0x10")
    assert (code, err) == (2, "mcrun: error: --seed must be an integer >= 0, got '0x10'\n")
    code, out, _ = run(capsys, "putt", "--distance", "10ft", "-n", "100", "--seed", "1.5e3")
    assert code == 0 and out.splitlines()[0].endswith("n 100, seed 1500")


def test_a_whole_number_in_digits_is_read_exactly():
    """A seed or a count written as text is read as written: through a float, --seed
    9007199254740993 (2**53 + 1) ran, and was recorded, as 9007199254740992. A float beyond
    2**53 says to write it in digits; beyond an int64, refused."""
    from mcrun.cli.options import whole
    from mcrun.run.plan import positive_int

    assert positive_int("9007199254740993", "seed", 0) == 2**53 + 1
    assert whole("9007199254740993", "--seed", 0) == 2**53 + 1
    assert positive_int("1e6", "n") == whole("1e6", "-n", 1) == 1_000_000
    # A text is read exactly, with an exponent or a point too: through a float, "2**53 + 1.0"
    # ran seed 2**53 and "7.0000000000000001" seed 7.
    assert positive_int("9007199254740993.0", "seed", 0) == 2**53 + 1
    assert whole("9.007199254740993e15", "--seed", 0) == 2**53 + 1
    assert positive_int("1e17", "seed", 0) == whole("1e17", "--seed", 0) == 10**17
    with pytest.raises(api.InputError, match=r"^seed must be an integer >= 0"):
        positive_int("7.0000000000000001", "seed", 0)
    with pytest.raises(api.InputError, match=r"^--seed '6.9999999999999999': allowed: a whole"):
        whole("6.9999999999999999", "--seed", 0)
    with pytest.raises(api.InputError, match=r"^seed must be an integer up to 2\*\*63 - 1"):
        positive_int("1e30", "seed", 0)
    # A float beyond 2**53 is no one integer: it says to write it in digits.
    with pytest.raises(api.InputError, match=r"^seed 1e\+30: allowed: a whole number from 0 "
                       r"to 2\*\*63 - 1 \(beyond 2\*\*53, in digits"):  # fmt: skip
        positive_int(1e30, "seed", 0)
    with pytest.raises(api.InputError, match=r"^n must be an integer up to 2\*\*63 - 1"):
        positive_int(str(2**63), "n")
    with pytest.raises(api.InputError, match=r"from 0 to 2\*\*63 - 1$"):
        whole(str(10**400), "--seed", 0)  # (an OverflowError of math.isfinite)
    # A digit separator, as parse_quantity refuses it: -n 1_000 ran 1,000 shots and 3_80 380.
    for read in (lambda t: positive_int(t, "n"), lambda t: whole(t, "-n", 1)):
        with pytest.raises(api.InputError, match=r"'3_80': '_' is not read in a number"):
            read("3_80")


def test_a_whole_number_in_other_digits_is_refused():
    """Python's int and float read '١٢' (Arabic) and '１２' (full width) as 12: a seed or a
    count that looks like a number and is not the one typed is refused, as a quantity is."""
    from mcrun.cli.options import whole
    from mcrun.run.plan import positive_int

    with pytest.raises(api.InputError, match=r"^--seed '١٢': only ASCII digits \(0-9\)"):
        whole("١٢", "--seed", 0)
    with pytest.raises(api.InputError, match=r"^n '１２': only ASCII digits \(0-9\)"):
        positive_int("１２", "n")


def test_the_api_refuses_what_is_not_its_argument(tmp_path):
    """Each a one-line InputError: a text where a bool goes (trajectory="no" traced a path),
    a scenario that is not one (an AttributeError), a folder that is not a path (a TypeError),
    a seed that is not a whole number (putt(seed=None) drew a new seed each call)."""
    from mcrun.putting import putt
    from mcrun.run.local import run_scenario

    with pytest.raises(api.InputError, match=r"^trajectory 'no': allowed: True or False$"):
        api.simulate(ball_speed_mps=70, launch_angle_deg=12, spin_radps=280, trajectory="no")
    with pytest.raises(api.InputError, match=r"^scenario None: allowed: a scenario file"):
        run_scenario(None, n=10, progress=False)
    with pytest.raises(api.InputError, match=r"^out_dir 5: allowed: a folder's path$"):
        run_scenario("pga-driver", n=10, out_dir=5, progress=False)
    # force="no" replaced an earlier run (any text is true); announce=5 failed after the
    # output folder was made.
    with pytest.raises(api.InputError, match=r"^force 'no': allowed: True or False$"):
        run_scenario("pga-driver", n=10, out_dir=tmp_path / "r", progress=False, force="no")
    with pytest.raises(api.InputError, match=r"^progress 'no': allowed: True or False$"):
        run_scenario("pga-driver", n=10, out_dir=tmp_path / "r", progress="no")
    with pytest.raises(api.InputError, match=r"^announce 5: allowed: a function"):
        run_scenario("pga-driver", n=10, out_dir=tmp_path / "r", progress=False, announce=5)
    assert not (tmp_path / "r").exists()
    for seed in (None, True, 2**64):
        with pytest.raises(api.InputError, match=r"^seed .*: allowed: a whole number from 0"):
            putt(3.0, 3.3, 0.01, 0.0, n=20, seed=seed)
