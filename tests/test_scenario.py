"""Scenario files (``mcrun.run.scenario``): the library, every schema error, units, groups and
sweeps."""

import math
import textwrap
from pathlib import Path

import numpy as np
import pytest

from mcrun.api import InputError
from mcrun.physics import turf
from mcrun.physics.constants import DEG
from mcrun.physics.launch import DEFAULT_CLUB_MASS_KG
from mcrun.run import scenario as sc
from mcrun.run.sampling import sample

LIBRARY = Path(__file__).resolve().parent.parent / "scenarios"
SESSION_CSV = Path(__file__).resolve().parent / "data" / "launch_monitor_session.csv"

BALL = """
[launch]
ball_speed = "167 mph"
launch_angle = "10.9 deg"
spin = "2686 rpm"
"""


def write(tmp_path, text, name="s.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


# --- the library -------------------------------------------------------------------------------


def test_library_folder_is_the_repository_scenarios(monkeypatch):
    monkeypatch.delenv(sc.ENV_LIBRARY, raising=False)
    assert sc.library_folder() == LIBRARY


def test_library_folder_env_override(monkeypatch, tmp_path):
    monkeypatch.setenv(sc.ENV_LIBRARY, str(tmp_path))
    assert sc.library_folder() == tmp_path
    monkeypatch.setenv(sc.ENV_LIBRARY, str(tmp_path / "missing"))
    with pytest.raises(sc.ScenarioError, match="MCRUN_SCENARIOS="):
        sc.library_folder()


EXPECTED_LIBRARY = {
    "pga-driver",
    "penner-fig4-drives",
    "penner-fig5-run-vs-launch-speed",
    "penner-fig6-irons",
    "penner-fig7-9iron-backspin",
    "penner-fig8-firm-green",
    "pga-tour-bag",
    "lpga-tour-bag",
    "amateur-slice",
    "wind-study",
    "altitude-study",
    "firm-vs-soft-greens",
}


def test_list_library_names_and_questions(monkeypatch):
    monkeypatch.delenv(sc.ENV_LIBRARY, raising=False)
    entries = sc.list_library()
    names = [name for name, _, _ in entries]
    assert names == sorted(names)
    assert EXPECTED_LIBRARY <= set(names)
    for name, path, question in entries:
        assert path == LIBRARY / f"{name}.toml"
        assert question.endswith("?"), name


@pytest.mark.parametrize("path", sorted(LIBRARY.glob("*.toml")), ids=lambda p: p.stem)
def test_library_scenario_validates_and_samples(path):
    """Every library file loads, starts with its question, and its points sample to finite,
    valid kernel inputs."""
    text = path.read_text(encoding="utf-8")
    assert text.startswith("# Question: ")
    s = sc.load(path)
    assert s.name == path.stem
    assert s.question == text.splitlines()[0].removeprefix("# Question: ")
    assert s.question == __import__("tomllib").loads(text)["scenario"]["question"]
    assert s.points
    for point in s.points:
        inputs, sampled = sample(s, point, 0, 500)
        assert np.isfinite(inputs).all(), point.label
        assert (inputs[:, 0] > 0).all()


def test_find_library_scenario_by_name(monkeypatch):
    monkeypatch.delenv(sc.ENV_LIBRARY, raising=False)
    assert sc.find("pga-driver") == LIBRARY / "pga-driver.toml"
    assert sc.load("pga-driver").name == "pga-driver"


def test_find_names_a_link_that_leads_nowhere(tmp_path):
    """A loop of links, or a link to a file removed, was "no such file"."""
    (tmp_path / "loop.toml").symlink_to(tmp_path / "loop.toml")
    (tmp_path / "gone.toml").symlink_to(tmp_path / "removed.toml")
    for name in ("loop.toml", "gone.toml"):
        with pytest.raises(sc.ScenarioError, match=r"\.toml: a link that leads to no file$"):
            sc.find(tmp_path / name)


def test_pga_driver_is_the_2019_table_average():
    """The reference scenario's means are the TrackMan 2019 PGA Tour driver row."""
    point = sc.load(LIBRARY / "pga-driver.toml").points[0]
    p = point.params
    assert p["launch.ball_speed"].args[0] == pytest.approx(167 * 0.44704, rel=1e-12)
    assert p["launch.launch_angle"].args[0] == pytest.approx(10.9 * DEG, rel=1e-12)
    assert p["launch.spin"].args[0] == pytest.approx(2686 * 2 * math.pi / 60, rel=1e-12)
    assert p["turf.preset"] == "fairway"
    assert p["launch.correlation"].names == ("ball_speed", "launch_angle", "spin")


def test_tour_bags_hold_every_club_of_the_table():
    import csv

    rows = [
        r
        for r in csv.DictReader(
            line
            for line in open(
                LIBRARY.parent / "mcrun" / "data" / "trackman_tour_averages_2019.csv",
                encoding="utf-8",
            )
            if not line.startswith("#")
        )
    ]
    for tour, name in (("PGA", "pga-tour-bag"), ("LPGA", "lpga-tour-bag")):
        s = sc.load(LIBRARY / f"{name}.toml")
        table = {r["club"]: r for r in rows if r["tour"] == tour}
        assert [p.group for p in s.points] == list(table)
        for point in s.points:
            row = table[point.group]
            speed = point.params["launch.ball_speed"]
            assert speed.args[0] == pytest.approx(float(row["ball_mph"]) * 0.44704)
            assert speed.args[1] / speed.args[0] == pytest.approx(0.009, abs=0.0004)


# --- schema errors ---------------------------------------------------------------------------

ERRORS = [
    # (name, file text, key path in the message, words of what is allowed)
    *(
        (
            f"name {name!r}",
            f"[scenario]\nname = {name!r}\n" + BALL,
            "scenario.name",
            "allowed is a name a run's folder can take (runs/<name>-<seed>)",
        )
        for name in ("../../etc/x", "a/b", "a\\b", "", "  ", ".hidden", "x" * 201)
    ),  # fmt: skip
    ("unknown top key", BALL + "[wether]\n", "wether", "allowed: scenario, launch"),
    (
        "unknown launch key",
        BALL + "spn = 1\n",
        "launch.spn",
        "allowed: ball_speed, launch_angle, spin",
    ),
    (
        "a group's dotted key quoted",
        BALL + '[[group]]\nname = "a"\n"launch.spin" = 3000\n',
        "group[0].launch.spin",
        "unknown key; allowed: name, target, hole, launch, club, turf, weather, models (write "
        "launch.spin unquoted: a dotted key)",
    ),
    (
        "unknown scenario key",
        "[scenario]\nshot = 5\n" + BALL,
        "scenario.shot",
        "allowed: name, question",
    ),
    (
        "wrong type shots",
        '[scenario]\nshots = "many"\n' + BALL,
        "scenario.shots",
        "must be an integer within [1, 2**63 - 1], got 'many'",
    ),
    (
        "a seed beyond an int64 (validated; a run blamed --seed, which no one typed)",
        "[scenario]\nseed = 9223372036854775808\n" + BALL,
        "scenario.seed",
        "must be an integer within [0, 2**63 - 1], got 9223372036854775808",
    ),
    (
        "an integer of 4,301 digits (a traceback of tomllib's)",
        "[scenario]\nseed = " + "9" * 4301 + "\n" + BALL,
        "not valid TOML",
        "Exceeds the limit (4300 digits)",
    ),
    (
        "wrong type bool",
        BALL.replace('"167 mph"', "true"),
        "launch.ball_speed",
        "must be a number or a string with a unit",
    ),
    (
        "list instead of a value",
        BALL.replace('"167 mph"', "[1, 2]"),
        "launch.ball_speed",
        "sweep a parameter in [sweep]",
    ),
    (
        "unknown unit",
        BALL.replace("167 mph", "167 mpg"),
        "launch.ball_speed",
        "mph, m/s, km/h",
    ),
    (
        "negative sd",
        BALL.replace('"2686 rpm"', '{ dist = "normal", mean = "2686 rpm", sd = "-5 rpm" }'),
        "launch.spin.sd",
        "must be >= 0, got -5 rpm (-0.523599 rad/s)",
    ),
    (
        "negative sigma",
        BALL.replace('"2686 rpm"', '{ dist = "lognormal", median = "2686 rpm", sigma = -0.1 }'),
        "launch.spin.sigma",
        "must be >= 0",
    ),
    (
        "uniform low >= high",
        BALL.replace('"10.9 deg"', '{ dist = "uniform", low = 12, high = 10 }'),
        "launch.launch_angle.low",
        "must be < high = 10 deg, got 12 deg",
    ),
    (
        "truncnormal low >= high",
        BALL.replace(
            '"10.9 deg"', '{ dist = "truncnormal", mean = 11, sd = 1, low = 12, high = 12 }'
        ),
        "launch.launch_angle.low",
        "must be < high",
    ),
    (
        "triangular mode outside",
        BALL.replace('"10.9 deg"', '{ dist = "triangular", low = 9, mode = 14, high = 13 }'),
        "launch.launch_angle.mode",
        "must be within [low, high] = [9 deg, 13 deg], got 14 deg",
    ),
    (
        "unknown distribution",
        BALL.replace('"10.9 deg"', '{ dist = "gaussian", mean = 11, sd = 1 }'),
        "launch.launch_angle.dist",
        "choose one of constant, normal, truncnormal, uniform, triangular, lognormal",
    ),
    (
        "distribution key",
        BALL.replace('"10.9 deg"', '{ dist = "normal", mean = 11, stdev = 1 }'),
        "launch.launch_angle.stdev",
        "allowed: dist, mean, sd",
    ),
    (
        "distribution missing key",
        BALL.replace('"10.9 deg"', '{ dist = "normal", mean = 11 }'),
        "launch.launch_angle.sd",
        "needs mean, sd",
    ),
    (
        "correlation of a non-normal",
        BALL + 'correlation = { names = ["ball_speed", "spin"], matrix = [[1, 0.5], [0.5, 1]] }\n',
        "launch.correlation.names",
        "ball_speed must be a normal distribution to be correlated",
    ),
    (
        "correlation unknown name",
        BALL.replace('"167 mph"', '{ dist = "normal", mean = "167 mph", sd = "1 mph" }')
        + 'correlation = { names = ["ball_speed", "smash"], matrix = [[1, 0.5], [0.5, 1]] }\n',
        "launch.correlation.names",
        "allowed: ball_speed, launch_angle, spin, azimuth, spin_axis",
    ),
    (
        "correlation not symmetric",
        "[launch]\n"
        'ball_speed = { dist = "normal", mean = "167 mph", sd = "1 mph" }\n'
        'launch_angle = "10.9 deg"\n'
        'spin = { dist = "normal", mean = "2686 rpm", sd = "20 rpm" }\n'
        'correlation = { names = ["ball_speed", "spin"], matrix = [[1, 0.5], [0.4, 1]] }\n',
        "launch.correlation.matrix",
        "must be symmetric",
    ),
    (
        "correlation diagonal",
        "[launch]\n"
        'ball_speed = { dist = "normal", mean = "167 mph", sd = "1 mph" }\n'
        'launch_angle = "10.9 deg"\n'
        'spin = { dist = "normal", mean = "2686 rpm", sd = "20 rpm" }\n'
        'correlation = { names = ["ball_speed", "spin"], matrix = [[2, 0.5], [0.5, 1]] }\n',
        "launch.correlation.matrix",
        "must have 1 on the diagonal",
    ),
    (
        "correlation not positive semi-definite",
        "[launch]\n"
        'ball_speed = { dist = "normal", mean = "167 mph", sd = "1 mph" }\n'
        'launch_angle = { dist = "normal", mean = "10.9 deg", sd = 1 }\n'
        'spin = { dist = "normal", mean = "2686 rpm", sd = "20 rpm" }\n'
        'correlation = { names = ["ball_speed", "launch_angle", "spin"], matrix = '
        "[[1, 0.9, -0.9], [0.9, 1, 0.9], [-0.9, 0.9, 1]] }\n",
        "launch.correlation.matrix",
        "must be positive semi-definite",
    ),
    (
        "correlation shape",
        "[launch]\n"
        'ball_speed = { dist = "normal", mean = "167 mph", sd = "1 mph" }\n'
        'launch_angle = "10.9 deg"\n'
        'spin = { dist = "normal", mean = "2686 rpm", sd = "20 rpm" }\n'
        'correlation = { names = ["ball_speed", "spin"], matrix = [[1, 0.5]] }\n',
        "launch.correlation.matrix",
        "must be a 2 x 2 list of lists of numbers",
    ),
    (
        "both launch and club",
        BALL + '[club]\nspeed = "45 m/s"\nloft = "13.3 deg"\n',
        "club.speed",
        "give the ball launch [launch] or the club delivery [club], not both",
    ),
    (
        "missing launch",
        '[turf]\npreset = "green"\n',
        "launch",
        "missing: give [launch] with ball_speed, launch_angle and spin",
    ),
    (
        "missing spin",
        BALL.replace('spin = "2686 rpm"', ""),
        "launch.spin",
        "a ball launch needs ball_speed, launch_angle and spin",
    ),
    (
        "club without loft",
        '[club]\nspeed = "45 m/s"\n',
        "club.loft",
        "a club delivery needs speed and loft",
    ),
    (
        "nonexistent resample file",
        '[launch]\nfile = "no-such-session.csv"\n',
        "launch.file",
        "no such file",
    ),
    ("unknown preset", BALL + '[turf]\npreset = "links"\n', "turf.preset", "green, firm_green"),
    (
        "unknown aero model",
        BALL + '[models]\naero = "bearman"\n',
        "models.aero",
        "must be one of ferguson2022",
    ),
    (
        "unknown bounce model",
        BALL + '[models]\nbounce = "daish"\n',
        "models.bounce",
        "must be one of penner2002",
    ),
    (
        "unknown wind profile",
        BALL + '[weather]\nwind_profile = "gusty"\n',
        "weather.wind_profile",
        "uniform, log, power",
    ),
    (
        "constant out of range",
        BALL.replace('"167 mph"', '"200 m/s"'),
        "launch.ball_speed",
        "must be within [0.5 m/s, 120 m/s], got 200 m/s",
    ),
    (
        "normal mean out of range",
        BALL.replace('"2686 rpm"', '{ dist = "normal", mean = -50, sd = 5 }'),
        "launch.spin.mean",
        "must be within [0 rad/s, 2000 rad/s]",
    ),
    (
        "truncnormal bound out of range",
        BALL + '[turf]\nmu = { dist = "truncnormal", mean = 0.4, sd = 0.1, low = -1, high = 1 }\n',
        "turf.mu.low",
        "must be within [0, 2]",
    ),
    (
        "temperature out of range",
        BALL + '[weather]\ntemperature = "80 C"\n',
        "weather.temperature",
        "must be within [-40 C, 55 C], got 80 C",
    ),
    (
        "a value in another unit than the bare one is said as written, then in the bare unit",
        BALL + '[weather]\ntemperature = "200 F"\n',
        "weather.temperature",
        "must be within [-40 C, 55 C], got 200 F (93.3333 C)",
    ),
    (
        "a key's unit is said with its number",
        BALL.replace('spin = "2686 rpm"', 'spin_rpm = { dist = "normal", mean = 2686, sd = -50 }'),
        "launch.spin_rpm.sd",
        "must be >= 0, got -50 rpm (-5.23599 rad/s)",
    ),
    (
        "uniform low >= high, in mph",
        BALL.replace('"167 mph"', '{ dist = "uniform", low = "170 mph", high = "160 mph" }'),
        "launch.ball_speed.low",
        "must be < high = 160 mph (71.5264 m/s), got 170 mph (75.9968 m/s)",
    ),
    (
        "rho_g and stimp",
        BALL + '[turf]\nrho_g = 0.1\nstimp = "10 ft"\n',
        "turf.stimp",
        "give turf.rho_g or turf.stimp, not both",
    ),
    (
        "a bare Stimp reading (6, meant in feet, was 6 m: 19.7 ft)",
        BALL + "[turf]\nstimp = 6\n",
        "turf.stimp",
        'give its unit, e.g. "10 ft" (a Stimp reading is quoted in feet',
    ),
    (
        "a bare Stimp spread",
        BALL + '[turf]\nstimp = { dist = "normal", mean = "10 ft", sd = 0.5 }\n',
        "turf.stimp.sd",
        "0.5: give its unit",
    ),
    (
        "altitude and pressure",
        BALL + '[weather]\naltitude = "1609 m"\npressure = "1013 hPa"\n',
        "weather.pressure",
        "give weather.altitude or weather.pressure, not both",
    ),
    (
        "a distribution for a constant-only setting",
        BALL + '[models]\ndt = { dist = "uniform", low = "1 ms", high = "10 ms" }\n',
        "models.dt",
        "must be a constant",
    ),
    (
        "unit in the key of the wrong kind",
        BALL.replace('spin = "2686 rpm"', "spin_mph = 5"),
        "launch.spin_mph",
        "spin takes units of a spin: rad/s, rpm, rps",
    ),
    (
        "unit in the key of the wrong kind, before a vowel",
        BALL.replace('launch_angle = "10.9 deg"', "launch_angle_mph = 5"),
        "launch.launch_angle_mph",
        "launch_angle takes units of an angle: deg, rad",
    ),
    (
        "a humidity of 50 (meant as 50 %)",
        BALL + "[weather]\nhumidity = 50\n",
        "weather.humidity",
        'must be within [0, 1], got 50 (a share: for 50 %, write "50 %")',
    ),
    (
        "a spin of 2686 (meant in rpm, as launch monitors give it; read as rad/s)",
        BALL.replace('spin = "2686 rpm"', "spin = { dist = 'normal', mean = 2686, sd = 27 }"),
        "launch.spin.mean",
        "must be within [0 rad/s, 2000 rad/s], got 2686 rad/s (a bare number is rad/s: in rpm, "
        'give every value of the table its unit ("2686 rpm"), or the key one: launch.spin_rpm '
        "= {...})",
    ),
    (
        "a ball speed of 167 (meant in mph)",
        BALL.replace('ball_speed = "167 mph"', "ball_speed = 167"),
        "launch.ball_speed",
        'got 167 m/s (a bare number is m/s: for 167 mph, give "167 mph"; for 167 km/h, give '
        '"167 km/h")',
    ),
    (
        "a table of values with and without a unit (the sd was 1 m/s, 2.2 mph)",
        BALL.replace('"167 mph"', '{ dist = "normal", mean = "167 mph", sd = 1 }'),
        "launch.ball_speed",
        "sd without a unit beside mean with one ('mph'): give every value its unit, or the key "
        "one: launch.ball_speed_mph = {...}; a bare number here is m/s",
    ),
    (
        "a table's values with and without a unit, in a sweep",
        BALL + '[sweep.launch]\nspin = [{ dist = "normal", mean = "2500 rpm", sd = 200 }]\n',
        'sweep."launch.spin"[0]',
        "sd without a unit beside mean with one ('rpm'): give every value its unit, or the key "
        "one: launch.spin_rpm = {...}; a bare number here is rad/s",
    ),
    (
        "a sweep of values with and without a unit (20 was 20 m/s)",
        BALL + '[sweep]\n"weather.wind_speed" = ["10 mph", 20]\n',
        'sweep."weather.wind_speed"[1]',
        "20 without a unit beside '10 mph': give every value its unit; a bare number here is m/s",
    ),
    (
        "a target with and without a unit (10 was 10 m)",
        '[scenario]\ntarget = ["250 yd", 10]\n' + BALL,
        "scenario.target[1]",
        "10 without a unit beside '250 yd': give both their unit, or neither (m)",
    ),
    (
        "a normal's sd wider than the whole range (a humidity's 5, meant as 5 %)",
        BALL + '[weather]\nhumidity = { dist = "normal", mean = 0.5, sd = 5 }\n',
        "weather.humidity.sd",
        "5 is wider than the whole allowed range [0, 1]: most draws would fall outside it",
    ),
    (
        "a distribution's name that is a list (a TypeError)",
        BALL.replace('"2686 rpm"', '{ dist = ["normal"], mean = "1 rpm", sd = "1 rpm" }'),
        "launch.spin.dist",
        "unknown distribution ['normal']; choose one of constant, normal",
    ),
    (
        "a value at its limit in the bare unit's rounding (said 'got 120 m/s')",
        BALL.replace('ball_speed = "167 mph"', "ball_speed = 120.0000001"),
        "launch.ball_speed",
        "must be within [0.5 m/s, 120 m/s], got 120.0000001 m/s",
    ),
    (
        "a unit in the value and in the key",
        BALL.replace('spin = "2686 rpm"', 'spin_rpm = "2686 rpm"'),
        "launch.spin_rpm",
        "the key gives the unit (rpm): give a bare number",
    ),
    (
        "given twice",
        BALL + "spin_rpm = 2500\n",
        "launch.spin_rpm",
        "launch.spin is given twice",
    ),
    (
        "group without a name",
        BALL + '[[group]]\nlaunch.spin = "3000 rpm"\n',
        "group[0].name",
        "every group needs a name",
    ),
    (
        "group name twice",
        BALL + '[[group]]\nname = "a"\n[[group]]\nname = "a"\n',
        "group[1].name",
        "is used twice",
    ),
    (
        "group unknown key",
        BALL + '[[group]]\nname = "a"\nlanch.spin = 5\n',
        "group[0].lanch",
        "allowed: name, target, hole, launch, club",
    ),
    (
        "group override out of range",
        BALL + '[[group]]\nname = "a"\nlaunch.spin = "-3 rad/s"\n',
        "group[0].launch.spin",
        "must be within [0 rad/s, 2000 rad/s]",
    ),
    ("sweep empty", BALL + '[sweep]\n"turf.mu" = []\n', 'sweep."turf.mu"', "non-empty list"),
    (
        "a value a sweep takes the place of, out of range (it was never read)",
        BALL + '[weather]\ntemperature = "500 K"\n[sweep]\n"weather.temperature" = ["10 C"]\n',
        "weather.temperature",
        "must be within [-40 C, 55 C], got 500 K (226.85 C)",
    ),
    (
        "a group's value a sweep takes the place of, unreadable",
        BALL + '[[group]]\nname = "a"\nweather.wind_speed = "10 mphh"\n'
        '[sweep]\n"weather.wind_speed" = ["1 m/s"]\n',
        "group[0].weather.wind_speed",
        "mphh",
    ),
    (
        "sweep bad key",
        BALL + '[sweep]\n"mu" = [0.4]\n',
        'sweep."mu"',
        "a sweep key is a parameter path section.name",
    ),
    (
        "sweep value out of range",
        BALL + '[sweep]\n"turf.mu" = [0.4, 3.0]\n',
        'sweep."turf.mu"[1]',
        "must be within [0, 2], got 3",
    ),
    (
        "target",
        '[scenario]\ntarget = "250 m"\n' + BALL,
        "scenario.target",
        "must be a pair [x, y] of lengths",
    ),
    (
        "target far away",
        '[scenario]\ntarget = ["1e300 m", "0 m"]\n' + BALL,
        "scenario.target[0]",
        "1e+300 m: allowed: -2000 m to 2000 m from the tee",
    ),
    (
        "log wind profile roughness",
        BALL + '[weather]\nwind_profile = "log"\nwind_profile_parameter = 20\n',
        "weather.wind_profile_parameter",
        "must be > 0 and below the reference height",
    ),
    (
        # A 5 m/s wind flown at 1,500 m/s at 30 m, the shots reported ok.
        "power wind profile from 0.1 m",
        BALL + '[weather]\nwind_profile = "power"\nwind_reference_height = "0.1 m"\n'
        "wind_profile_parameter = 1\n",
        "weather.wind_profile_parameter",
        "makes the wind at 50 m 500 times the reference wind; allowed: at most 4",
    ),
    (
        "log wind profile from within its roughness",
        BALL + '[weather]\nwind_profile = "log"\nwind_profile_parameter = 9.9\n',
        "weather.wind_profile_parameter",
        "a roughness length of 9.9 m from a reference height of 10 m makes the wind at 50 m 161",
    ),
    (
        "log wind profile's default roughness from 0.1 m",
        BALL + '[weather]\nwind_profile = "log"\nwind_reference_height = "0.1 m"\n',
        "weather.wind_reference_height",
        "makes the wind at 50 m 6.16 times",
    ),
    (
        "swept quoted and nested",
        BALL + '[sweep]\n"launch.spin" = ["2000 rpm", "2500 rpm"]\n[sweep.launch]\n'
        'spin = ["3000 rpm"]\n',
        'sweep."launch.spin"',
        "launch.spin is swept twice",
    ),
    (
        "a value swept twice",
        BALL + '[sweep]\n"launch.spin" = ["2000 rpm", "2500 rpm", "2000 rpm"]\n',
        'sweep."launch.spin"[2]',
        "'2000 rpm' is swept twice: give each value once",
    ),
    (
        "lognormal temperature",
        BALL + '[weather]\ntemperature = {dist="lognormal", median="-5 C", sigma=0.05}\n',
        "weather.temperature",
        "a temperature cannot be lognormal (it would spread in kelvin",
    ),
    (
        "hole file a number",
        BALL + "[hole]\nfile = 5\n",
        "hole.file",
        "must be a hole TOML file's path, got 5",  # (it said "cannot read .../5")
    ),
    (
        "hole file a course map",
        BALL + '[hole]\nfile = "holes/riverside-zagreb.osm.geojson"\n',
        "hole.file",
        'is a course map: give it as [hole] map = "FILE" with hole = N',
    ),
    (
        "hole file with a NUL",
        BALL + '[hole]\nfile = "holes/riverside-2.toml\\u0000x"\n',
        "hole.file",
        "a path cannot hold a NUL character",  # (a ValueError traceback)
    ),
    (
        "an escape sequence in the name",
        '[scenario]\nname = "x\\u001b]0;pwned\\u0007"\n' + BALL,
        "scenario.name",
        "allowed: text without control characters",
    ),
    (
        "a line break in the question",
        '[scenario]\nquestion = "why\\nnot"\n' + BALL,
        "scenario.question",
        "allowed: text without control characters",
    ),
    (
        "an escape sequence in a group's name",
        BALL + '[[group]]\nname = "a\\u001b[2Jb"\n',
        "group[0].name",
        "allowed: text without control characters",
    ),
    (
        "critical height 0",
        BALL + "[turf]\ncritical_height = 0\n",
        "turf.critical_height",
        "must be within [0.0001 m, 1 m], got 0 m",
    ),
    ("invalid TOML", BALL + "spin_axis = \n", "not valid TOML", "Invalid value"),
]


@pytest.mark.parametrize(("case", "text", "where", "allowed"), ERRORS, ids=[e[0] for e in ERRORS])
def test_schema_error_is_one_line_naming_file_key_and_what_is_allowed(
    tmp_path, case, text, where, allowed
):
    path = write(tmp_path, text)
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    message = str(info.value)
    assert isinstance(info.value, InputError)
    assert "\n" not in message
    assert message.startswith(f"{path}: {where}"), message
    assert allowed in message, message


def test_error_for_the_exact_contract_example(tmp_path):
    """engine.md: ``scenarios/x.toml: launch.spin.sd: must be >= 0, got -5 rad/s``."""
    path = write(tmp_path, BALL.replace('"2686 rpm"', '{ dist = "normal", mean = 300, sd = -5 }'))
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == f"{path}: launch.spin.sd: must be >= 0, got -5 rad/s"


def test_missing_scenario_file(tmp_path):
    path = tmp_path / "nowhere.toml"
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value).startswith(f"{path}: no such file")


def test_resample_file_without_recognisable_columns(tmp_path):
    (tmp_path / "shots.csv").write_text("speed,angle\n70,12\n", encoding="utf-8")
    path = write(tmp_path, '[launch]\nfile = "shots.csv"\n')
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: launch.file: ")
    assert "no recognisable column for ball_speed, launch_angle, spin" in message
    assert "found speed, angle" in message


def test_resample_file_with_a_bad_value(tmp_path):
    text = SESSION_CSV.read_text(encoding="utf-8").replace("2855", "-2855")
    (tmp_path / "shots.csv").write_text(text, encoding="utf-8")
    path = write(tmp_path, '[launch]\nfile = "shots.csv"\n')
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == (
        f"{path}: launch.file: {tmp_path / 'shots.csv'}: column 'spin_rpm' row 1: -2855 rpm is "
        "outside the allowed range [0 rad/s, 2000 rad/s]"
    )


def test_resample_file_malformed_or_a_folder(tmp_path):
    """``launch.file`` reads through the reader of ``mcrun replay``: a header only, a row with
    a field more than the header, a folder: one line naming the scenario, the key, the file
    and what is wrong."""
    lines = SESSION_CSV.read_text(encoding="utf-8").splitlines()
    header = next(line for line in lines if not line.startswith("#"))
    first = lines[lines.index(header) + 1]
    cases = {
        "header.csv": (header + "\n", "no shots: the file has a header only"),
        "extra.csv": (f"{header}\n{first},1.0\n", "row 1 has 6 fields, the header has 5"),
    }
    for name, (text, what) in cases.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
        path = write(tmp_path, f'[launch]\nfile = "{name}"\n')
        with pytest.raises(sc.ScenarioError) as info:
            sc.load(path)
        assert str(info.value) == f"{path}: launch.file: {tmp_path / name}: {what}"
    (tmp_path / "folder.csv").mkdir()
    path = write(tmp_path, '[launch]\nfile = "folder.csv"\n')
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == (
        f"{path}: launch.file: {tmp_path / 'folder.csv'}: is a directory, not a CSV or Parquet file"
    )


def test_resample_file_with_a_missing_value_shows_it_plainly(tmp_path):
    """The message shows the missing value as nan, not numpy 2's np.float64(nan)."""
    text = SESSION_CSV.read_text(encoding="utf-8").replace("2855", "")
    (tmp_path / "shots.csv").write_text(text, encoding="utf-8")
    path = write(tmp_path, '[launch]\nfile = "shots.csv"\n')
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == (
        f"{path}: launch.file: {tmp_path / 'shots.csv'}: column 'spin_rpm' row 1: not a number "
        "(nan); every row must be complete"
    )


@pytest.mark.parametrize(
    ("old", "new", "where"),
    [
        ('"10.9 deg"', '"１０.９ deg"', "launch.launch_angle"),  # a value with its unit
        ('spin = "2686 rpm"', 'spin_rpm = "２６８６"', "launch.spin_rpm"),  # the unit in the key
    ],
)
def test_full_width_digits_are_refused(tmp_path, old, new, where):
    """Python's float() reads full-width digits; a scenario value must use ASCII digits."""
    path = write(tmp_path, BALL.replace(old, new))
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    message = str(info.value)
    assert message.startswith(f"{path}: {where}: cannot read "), message
    assert "only ASCII digits (0-9) are accepted" in message, message


def test_degree_sign_in_a_scenario(tmp_path):
    a = sc.load(write(tmp_path, BALL.replace("10.9 deg", "10.9°"), "a.toml"))
    b = sc.load(write(tmp_path, BALL, "b.toml"))
    assert a.points[0].params["launch.launch_angle"] == b.points[0].params["launch.launch_angle"]


def test_correlation_broken_by_a_group_names_the_point(tmp_path):
    text = (
        "[launch]\n"
        'ball_speed = { dist = "normal", mean = "167 mph", sd = "1 mph" }\n'
        'launch_angle = "10.9 deg"\n'
        'spin = { dist = "normal", mean = "2686 rpm", sd = "20 rpm" }\n'
        'correlation = { names = ["ball_speed", "spin"], matrix = [[1, -0.3], [-0.3, 1]] }\n'
        '[[group]]\nname = "a"\n[[group]]\nname = "b"\nlaunch.spin = "3000 rpm"\n'
    )
    path = write(tmp_path, text)
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == (
        f"{path}: launch.correlation.names: spin must be a normal distribution to be correlated "
        "(launch.spin is a constant, at group[1].launch.spin) (point 'b')"
    )


def test_a_humidity_with_its_unit_gets_no_advice_on_its_unit(tmp_path):
    """``humidity = 50`` says to write "50 %"; ``"150 %"`` or ``humidity_pct = 150`` do not
    (the advice, "for 1.5 %, write '1.5 %'", would set 1.5 %)."""
    for text in ('humidity = "150 %"', "humidity_pct = 150"):
        with pytest.raises(InputError) as info:
            sc.load(write(tmp_path, BALL + f"[weather]\n{text}\n"))
        assert str(info.value).endswith("must be within [0, 1], got 150 % (1.5)"), text


# --- units in values and in key names ----------------------------------------------------------

IN_VALUES = """
[launch]
ball_speed = { dist = "normal", mean = "167 mph", sd = "1.5 mph" }
launch_angle = "10.9 deg"
spin = { dist = "truncnormal", mean = "2686 rpm", sd = "250 rpm", low = "2000 rpm", \
high = "3500 rpm" }
spin_axis = { dist = "uniform", low = "-5 deg", high = "5 deg" }
[turf]
stimp = "10 ft"
critical_height = "5 mm"
[weather]
temperature = { dist = "normal", mean = "68 F", sd = "9 F" }
wind_speed = { dist = "lognormal", median = "10 mph", sigma = 0.3 }
altitude = "5280 ft"
humidity = "40 %"
[models]
dt = "5 ms"
"""

IN_KEYS = """
[launch]
ball_speed_mph = { dist = "normal", mean = 167, sd = 1.5 }
launch_angle_deg = 10.9
spin_rpm = { dist = "truncnormal", mean = 2686, sd = 250, low = 2000, high = 3500 }
spin_axis_deg = { dist = "uniform", low = -5, high = 5 }
[turf]
stimp_ft = 10
critical_height_mm = 5
[weather]
temperature_f = { dist = "normal", mean = 68, sd = 9 }
wind_speed_mph = { dist = "lognormal", median = 10, sigma = 0.3 }
altitude_ft = 5280
humidity_pct = 40
[models]
dt_ms = 5
"""


def test_units_in_values_and_in_key_names_give_identical_specs(tmp_path):
    a = sc.load(write(tmp_path, IN_VALUES, "a.toml")).points[0].params
    b = sc.load(write(tmp_path, IN_KEYS, "b.toml")).points[0].params
    assert a == b
    # And the values are the SI ones; a temperature sd has no offset: 9 F is 5 K.
    assert a["weather.temperature"].args == pytest.approx((293.15, 5.0))
    assert a["turf.stimp"].value == pytest.approx(3.048)
    assert a["weather.altitude"].value == pytest.approx(1609.344)
    assert a["weather.humidity"].value == pytest.approx(0.4)
    assert a["models.dt"].value == pytest.approx(0.005)


def test_every_speed_unit_a_value_takes_may_end_a_key(tmp_path):
    """``wind_speed_kmh`` and ``_kn`` as ``"6 km/h"`` and ``"6 kn"`` (kmh was refused as an
    unknown key); a misspelt key's message lists the units a name may end with."""
    for key, value in (("wind_speed_kmh", "6 km/h"), ("wind_speed_kn", "6 kn")):
        a = sc.load(write(tmp_path, BALL + f"[weather]\n{key} = 6\n", "a.toml")).points[0]
        b = sc.load(write(tmp_path, BALL + f'[weather]\nwind_speed = "{value}"\n')).points[0]
        assert a.params["weather.wind_speed"] == b.params["weather.wind_speed"]
    assert b.params["weather.wind_speed"].value == pytest.approx(6 * 1852 / 3600)
    with pytest.raises(sc.ScenarioError, match=r"wind_sped_kmh: unknown key; allowed: .* the "
                       r"units: mps, mph, kph, kmh, fps, kn, deg, .*, ms\)$"):  # fmt: skip
        sc.load(write(tmp_path, BALL + "[weather]\nwind_sped_kmh = 6\n"))


def test_bare_values_are_si_but_degrees_and_celsius(tmp_path):
    text = """
    [launch]
    ball_speed = 74.3
    launch_angle = 12
    spin = 300
    [weather]
    temperature = 25
    """
    p = sc.load(write(tmp_path, text)).points[0].params
    assert p["launch.ball_speed"].value == 74.3
    assert p["launch.launch_angle"].value == 12 * DEG
    assert p["launch.spin"].value == 300.0
    assert p["weather.temperature"].value == pytest.approx(298.15)


def test_defaults(tmp_path):
    """Unset quantities take the single-shot API's defaults and the turf preset's fields."""
    s = sc.load(write(tmp_path, BALL))
    assert (s.shots, s.seed, s.block_size, s.name) == (100_000, 0, sc.DEFAULT_BLOCK_SIZE, "s")
    p = s.points[0].params
    assert p["turf.preset"] == "green"
    assert p["turf.mu"].value == 0.40
    assert p["turf.rho_g"].value == 0.131
    assert p["weather.pressure"].value == 101325.0
    assert p["weather.humidity"].value == 0.5
    assert p["weather.temperature"].value == 293.15
    assert p["models.aero"] == "trackman2019_lyu"
    assert p["models.dt"].value == 0.2  # the default step in uniform wind
    log = sc.load(write(tmp_path, BALL + '[weather]\nwind_profile = "log"\n'))
    assert log.points[0].params["models.dt"].value == 0.02  # and with a wind profile
    assert p["launch.azimuth"].value == 0.0
    assert s.points[0].label == "" and s.points[0].target_m is None


# --- groups and sweeps -------------------------------------------------------------------------

GROUPS_AND_SWEEP = """
[scenario]
target = ["150 m", "0 m"]
[launch]
ball_speed = "167 mph"
launch_angle = "10.9 deg"
spin = "2686 rpm"
[turf]
preset = "firm_green"
[[group]]
name = "driver"
[[group]]
name = "7-iron"
target = ["160 yd", "2 yd"]
launch.ball_speed = { dist = "normal", mean = "120 mph", sd = "1.5 mph" }
launch.spin = "7097 rpm"
[sweep]
"launch.spin" = ["809 rad/s", "1000 rad/s", "1200 rad/s"]
"turf.mu" = [0.40, 0.25]
"""


def test_groups_times_sweep_points_and_labels(tmp_path):
    s = sc.load(write(tmp_path, GROUPS_AND_SWEEP))
    assert len(s.points) == 2 * 3 * 2
    assert [p.index for p in s.points] == list(range(12))
    assert s.points[0].label == "driver | launch.spin=809 rad/s, turf.mu=0.4"
    assert s.points[1].label == "driver | launch.spin=809 rad/s, turf.mu=0.25"
    assert s.points[11].label == "7-iron | launch.spin=1200 rad/s, turf.mu=0.25"
    assert [p.group for p in s.points] == ["driver"] * 6 + ["7-iron"] * 6
    assert s.points[3].sweep == {"launch.spin": "1000 rad/s", "turf.mu": 0.25}
    for point in s.points:
        spin = float(point.sweep["launch.spin"].split()[0])
        # The sweep wins over the group's own spin; the group keeps its ball speed.
        assert point.params["launch.spin"].value == spin
        assert point.params["turf.mu"].value == point.sweep["turf.mu"]
        assert point.params["turf.preset"] == "firm_green"
        if point.group == "7-iron":
            assert point.params["launch.ball_speed"].dist == "normal"
            assert point.target_m == pytest.approx((160 * 0.9144, 2 * 0.9144))
        else:
            assert point.params["launch.ball_speed"].dist == "constant"
            assert point.target_m == (150.0, 0.0)


def test_swept_values_a_millionth_apart_have_labels_apart(tmp_path):
    """A swept number is labelled in six digits where they tell it apart (0.25), else in as many
    as it takes (both points of [0.1000001, 0.1000002] were labelled turf.mu=0.1)."""
    text = BALL + '[sweep]\n"turf.mu" = [0.1000001, 0.1000002, 0.25]\n'
    labels = [p.label for p in sc.load(write(tmp_path, text)).points]
    assert labels == ["turf.mu=0.1000001", "turf.mu=0.1000002", "turf.mu=0.25"]


def test_groups_alone_and_sweep_alone(tmp_path):
    groups = sc.load(write(tmp_path, GROUPS_AND_SWEEP.split("[sweep]")[0], "g.toml"))
    assert [p.label for p in groups.points] == ["driver", "7-iron"]
    sweep_only = BALL + '[sweep]\n"weather.altitude" = ["0 m", "1609 m"]\n'
    points = sc.load(write(tmp_path, sweep_only, "w.toml")).points
    assert [p.label for p in points] == ["weather.altitude=0 m", "weather.altitude=1609 m"]
    assert points[0].group == ""


def test_sweep_as_nested_tables_and_over_choices(tmp_path):
    text = BALL + '[sweep]\nturf.preset = ["green", "firm_green"]\n'
    points = sc.load(write(tmp_path, text)).points
    assert [p.params["turf.preset"] for p in points] == ["green", "firm_green"]
    assert [p.params["turf.mu"].value for p in points] == [0.40, 0.25]


def test_sweep_with_unit_in_the_key(tmp_path):
    text = BALL + '[sweep]\n"launch.spin_rpm" = [2500, 3000]\n'
    points = sc.load(write(tmp_path, text)).points
    assert [p.params["launch.spin"].value for p in points] == pytest.approx(
        [2500 * math.pi / 30, 3000 * math.pi / 30]
    )
    assert points[0].label == "launch.spin_rpm=2500"


def test_club_scenario_and_file_scenario(tmp_path):
    club = sc.load(write(tmp_path, '[club]\nspeed = "45 m/s"\nloft = 13.3\n', "c.toml"))
    point = club.points[0]
    assert point.mode == "club"
    assert point.params["club.mass"].value == DEFAULT_CLUB_MASS_KG == 0.200  # Penner's driver
    assert "launch.ball_speed" not in point.params
    text = f'[launch]\nfile = "{SESSION_CSV}"\njitter = {{ spin_rpm = 50 }}\n'
    resampled = sc.load(write(tmp_path, text, "f.toml")).points[0]
    assert resampled.mode == "file"
    spec = resampled.params["launch.file"]
    assert spec.n_rows == 20
    assert set(spec.columns) == {"ball_speed", "launch_angle", "spin", "spin_axis"}
    assert spec.jitter == {"spin": pytest.approx(50 * math.pi / 30)}
    assert resampled.params["launch.azimuth"].value == 0.0  # not in the file
    # A jitter's unknown key lists a jitter's keys (it listed [launch]'s: file, club, ...).
    bad = text.replace("spin_rpm = 50", "foo = 1")
    with pytest.raises(sc.ScenarioError, match=r"launch.jitter.foo: unknown key; allowed: "
                       r"ball_speed, launch_angle, spin, azimuth, spin_axis \(a unit"):  # fmt: skip
        sc.load(write(tmp_path, bad, "bad.toml"))
    with pytest.raises(sc.ScenarioError, match=r"launch.file: /dev/null: not a regular file"):
        sc.load(write(tmp_path, '[launch]\nfile = "/dev/null"\n', "null.toml"))


# The scenario's turf quantities that are fields of a Turf, by the field's name.
_TURF_FIELDS = {
    "mu": "mu",
    "softness": "softness",
    "rho_g": "rho_g",
    "critical_height": "critical_height_m",
}


@pytest.mark.parametrize("name", _TURF_FIELDS)
def test_turf_limits_are_those_of_check_turf(tmp_path, name):
    """A turf quantity is bounded in a scenario where check_turf bounds it: its upper limit
    loads, and a value above it is refused by both."""
    field = _TURF_FIELDS[name]
    lo, hi = turf.LIMITS[field]
    assert sc.PARAMETERS["turf"][name].limits == (lo, hi)
    turf.check_turf(turf.PRESETS["green"]._replace(**{field: hi}))
    with pytest.raises(ValueError, match=f"turf {field} = "):
        turf.check_turf(turf.PRESETS["green"]._replace(**{field: hi * 1.01}))
    sc.load(write(tmp_path, BALL + f"[turf]\n{name} = {hi}\n"))
    with pytest.raises(sc.ScenarioError, match=f"turf.{name}"):
        sc.load(write(tmp_path, BALL + f"[turf]\n{name} = {hi * 1.01}\n"))


def test_a_file_saved_with_a_byte_order_mark_reads_as_without(tmp_path):
    """A scenario saved with a UTF-8 byte-order mark (as Windows' Notepad may) is the same
    scenario, not "Invalid statement (at line 1, column 1)"."""
    plain = write(tmp_path, BALL)
    marked = tmp_path / "bom.toml"
    marked.write_bytes(b"\xef\xbb\xbf" + plain.read_bytes())
    assert sc.load(marked).points[0].params == sc.load(plain).points[0].params


def test_a_sweep_of_too_many_points_is_refused_before_one_is_built(tmp_path):
    """The points are counted from the lists' lengths (groups times the sweep's combinations):
    10^7 points took minutes and gigabytes to build before they were refused or run."""
    values = ", ".join(f'"{k} deg"' for k in range(-49, 51))  # 100 values
    text = (BALL + "[[group]]\nname = 'a'\n[[group]]\nname = 'b'\n[sweep]\n"
            f'"launch.azimuth" = [{values}]\n"launch.spin_axis" = [{values}]\n'
            '"turf.mu" = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]\n')  # fmt: skip
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(write(tmp_path, text))
    assert str(info.value).endswith(
        "s.toml: sweep: 120,000 points (2 groups x 60,000 of the sweep): allowed are at most "
        "100,000"
    )


def test_a_bare_value_out_of_range_in_the_quoted_units_too_gets_no_advice(tmp_path):
    """A spin of 26860 is out of range in rad/s and in rpm: the message ends with the value."""
    path = write(tmp_path, BALL.replace('spin = "2686 rpm"', "spin = 26860"))
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value) == (
        f"{path}: launch.spin: must be within [0 rad/s, 2000 rad/s], got 26860 rad/s"
    )


def test_a_table_of_values_in_the_bare_unit_and_without_one_is_read(tmp_path):
    """``mean = "10.9 deg", sd = 1``: both in degrees, the bare unit; read as before."""
    text = BALL.replace('"10.9 deg"', '{ dist = "normal", mean = "10.9 deg", sd = 1 }')
    angle = sc.load(write(tmp_path, text)).points[0].params["launch.launch_angle"]
    assert angle.args == pytest.approx((10.9 * DEG, DEG), rel=1e-15)


def test_a_bare_zero_beside_a_unit_is_zero_in_any(tmp_path):
    """A bare 0 beside a unit is read (0 rpm is 0 rad/s; a spread of 0 is 0 in any unit), but
    not a temperature's mean (0 C is no 0 F)."""
    for text in (
        BALL.replace('"2686 rpm"', '{ dist = "normal", mean = "2686 rpm", sd = 0 }'),
        BALL + '[weather]\nwind_speed = { dist = "uniform", low = 0, high = "10 mph" }\n',
        BALL + '[weather]\ntemperature = { dist = "normal", mean = "50 F", sd = 0 }\n',
        BALL + '[sweep]\n"weather.wind_speed" = ["10 mph", 0]\n',
    ):
        sc.load(write(tmp_path, text))
    text = BALL + '[weather]\ntemperature = { dist = "uniform", low = 0, high = "50 F" }\n'
    with pytest.raises(sc.ScenarioError, match=r"low without a unit beside high with one"):
        sc.load(write(tmp_path, text))


def test_a_sweep_value_s_line_break_is_no_line_break_of_its_label(tmp_path):
    """``"2686\\rrpm"`` is read as "2686 rpm"; its label carried the carriage return into the
    output (validate's lines, the summary's label)."""
    text = BALL + '[sweep]\n"launch.spin" = ["2686\\rrpm", "3000\\n\\trpm"]\n'
    points = sc.load(write(tmp_path, text)).points
    assert [p.label for p in points] == ["launch.spin=2686 rpm", "launch.spin=3000 rpm"]
