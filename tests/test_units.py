"""Tests of mcrun.units: published conversions, spellings, vectors, column names, bad input."""

import math

import numpy as np
import pytest

from mcrun.units import (
    KINDS,
    UnitError,
    foreign_digits,
    from_column_name,
    meant_quoted,
    parse_quantity,
    parse_vector,
    shown,
    to_unit,
)

# --- published conversions -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "kind", "expected", "abs_tol"),
    [
        ("167 mph", "speed", 74.65568, 1e-12),  # 1 mph = 0.44704 m/s exactly
        ("100 km/h", "speed", 27.777777777777778, 1e-12),
        ("10 ft/s", "speed", 3.048, 1e-12),
        ("10 kn", "speed", 5.144444444444445, 1e-12),  # 1 kn = 1852 m/h
        ("74.3", "speed", 74.3, 0.0),
        ("2686 rpm", "spin", 281.28, 0.01),
        ("10 rps", "spin", 20.0 * math.pi, 1e-12),
        ("300 rad/s", "spin", 300.0, 0.0),
        ("12", "angle", math.radians(12.0), 1e-15),  # bare angle is degrees
        ("180 deg", "angle", math.pi, 1e-15),
        ("0.2 rad", "angle", 0.2, 0.0),
        ("275 yd", "length", 251.46, 1e-9),
        ("10 ft", "length", 3.048, 1e-12),
        ("12 in", "length", 0.3048, 1e-12),
        ("42.67 mm", "length", 0.04267, 1e-12),
        ("4.267 cm", "length", 0.04267, 1e-12),
        ("45.93 g", "mass", 0.04593, 1e-12),
        ("1.62 oz", "mass", 0.0459262274625, 1e-12),  # 1 oz = 28.349523125 g exactly
        ("20", "temperature", 293.15, 1e-9),  # bare temperature is Celsius
        ("20 C", "temperature", 293.15, 1e-9),
        ("68 F", "temperature", 293.15, 1e-9),
        ("32 F", "temperature", 273.15, 1e-9),
        ("-40 F", "temperature", 233.15, 1e-9),  # -40 F = -40 C
        ("300 K", "temperature", 300.0, 0.0),
        ("29.92 inHg", "pressure", 101320.6, 1.0),
        ("1 atm", "pressure", 101325.0, 0.0),
        ("1013.25 hPa", "pressure", 101325.0, 1e-9),
        ("1013.25 mbar", "pressure", 101325.0, 1e-9),
        ("101.325 kPa", "pressure", 101325.0, 1e-9),
        ("101325", "pressure", 101325.0, 0.0),
        ("50%", "fraction", 0.5, 1e-15),
        ("0.5", "fraction", 0.5, 0.0),
    ],
)
def test_published_conversions(text, kind, expected, abs_tol):
    assert parse_quantity(text, kind) == pytest.approx(expected, rel=1e-12, abs=abs_tol)


def test_exact_factors():
    units = {kind: table for kind, (_, table) in KINDS.items()}
    assert units["speed"]["mph"] == (0.44704, 0.0)
    assert units["length"]["yd"] == (0.9144, 0.0)
    assert units["length"]["ft"] == (0.3048, 0.0)
    assert units["length"]["in"] == (0.0254, 0.0)
    assert units["mass"]["oz"] == (0.028349523125, 0.0)
    assert units["pressure"]["inHg"] == (3386.389, 0.0)
    assert units["spin"]["rpm"][0] == pytest.approx(2.0 * math.pi / 60.0, rel=1e-15)


def test_bare_units():
    assert {kind: bare for kind, (bare, _) in KINDS.items()} == {
        "speed": "m/s",
        "angle": "deg",
        "spin": "rad/s",
        "length": "m",
        "mass": "kg",
        "temperature": "C",
        "pressure": "Pa",
        "fraction": "fraction",
        "time": "s",
    }
    for bare, table in KINDS.values():
        assert bare in table


@pytest.mark.parametrize(
    ("value", "kind", "expected"),
    [
        (74.3, "speed", 74.3),
        (167, "speed", 167.0),
        (12, "angle", math.radians(12.0)),
        (20.0, "temperature", 293.15),
        (0.3, "fraction", 0.3),
    ],
)
def test_numbers_are_in_the_bare_unit(value, kind, expected):
    result = parse_quantity(value, kind)
    assert type(result) is float
    assert result == pytest.approx(expected, rel=1e-12)


# --- spellings ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "kind", "same_as"),
    [
        ("167mph", "speed", "167 mph"),
        ("167   mph", "speed", "167 mph"),
        ("  167 mph  ", "speed", "167 mph"),
        ("167 MPH", "speed", "167 mph"),
        ("167 Mph", "speed", "167 mph"),
        ("74.3m/s", "speed", "74.3"),
        ("74.3 mps", "speed", "74.3"),
        ("74.3 M/S", "speed", "74.3"),
        ("100 kph", "speed", "100 km/h"),
        ("100 kmh", "speed", "100 km/h"),
        ("100 KM/H", "speed", "100 km/h"),
        ("100 km / h", "speed", "100 km/h"),
        ("10 fps", "speed", "10 ft/s"),
        ("10 knots", "speed", "10 kn"),
        ("10 degrees", "angle", "10 deg"),
        ("10 degree", "angle", "10 deg"),
        ("10°", "angle", "10 deg"),
        ("10 °", "angle", "10 deg"),
        ("10 DEG", "angle", "10"),
        ("0.1 RAD", "angle", "0.1 rad"),
        ("300 radps", "spin", "300 rad/s"),
        ("300", "spin", "300 rad/s"),
        ("2686RPM", "spin", "2686 rpm"),
        ("10 rev/s", "spin", "10 rps"),
        ("275 yards", "length", "275 yd"),
        ("275 yard", "length", "275 yd"),
        ("275 YD", "length", "275 yd"),
        ("10 feet", "length", "10 ft"),
        ("3 IN", "length", "3 in"),
        ("45.93 G", "mass", "45.93 g"),
        ("1.62 OZ", "mass", "1.62 oz"),
        ("0.04593 KG", "mass", "0.04593"),
        ("20 degC", "temperature", "20 C"),
        ("20 °C", "temperature", "20 C"),
        ("20°c", "temperature", "20 C"),
        ("20 deg C", "temperature", "20 C"),
        ("20 c", "temperature", "20"),
        ("68 degF", "temperature", "68 F"),
        ("68°F", "temperature", "68 F"),
        ("68 f", "temperature", "68 F"),
        ("293.15 k", "temperature", "20"),
        ("1013 HPA", "pressure", "1013 hPa"),
        ("1013 MBar", "pressure", "1013 hPa"),
        ("29.92 INHG", "pressure", "29.92 inHg"),
        ("29.92inhg", "pressure", "29.92 inHg"),
        ("101325 pa", "pressure", "101325"),
        ("101.325 KPA", "pressure", "1 atm"),
        ("50 percent", "fraction", "50%"),
        ("50 %", "fraction", "0.5"),
    ],
)
def test_aliases_spacing_and_case(text, kind, same_as):
    assert parse_quantity(text, kind) == pytest.approx(parse_quantity(same_as, kind), rel=1e-12)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("+5", 5.0),
        ("-5", -5.0),
        (".5", 0.5),
        ("5.", 5.0),
        ("1e2", 100.0),
        ("1.5E-1", 0.15),
        ("-1e1 mph", -4.4704),
    ],
)
def test_number_forms(text, expected):
    assert parse_quantity(text, "speed") == pytest.approx(expected, rel=1e-12)


# --- vectors -----------------------------------------------------------------------------------


def test_vector_bare():
    assert parse_vector("5,0", "speed") == (5.0, 0.0)
    assert parse_vector(" 5 , -3 ", "speed") == (5.0, -3.0)


def test_vector_with_units():
    east, north = parse_vector("10mph,-3mph", "speed")
    assert east == pytest.approx(4.4704, rel=1e-12)
    assert north == pytest.approx(-1.34112, rel=1e-12)
    assert parse_vector("10 mph, -3 MPH", "speed") == pytest.approx((4.4704, -1.34112))
    # Each component carries its own unit.
    assert parse_vector("10mph,3m/s", "speed") == pytest.approx((4.4704, 3.0))


def test_vector_sizes_and_sequences():
    assert parse_vector("1,2,3", "length", size=3) == (1.0, 2.0, 3.0)
    assert parse_vector("7 yd", "length", size=1) == pytest.approx((6.4008,))
    assert parse_vector((5.0, 0), "speed") == (5.0, 0.0)
    assert parse_vector(["10 mph", "0 mph"], "speed") == pytest.approx((4.4704, 0.0))


def test_vector_result_is_tuple_of_floats():
    result = parse_vector("5,0", "speed")
    assert isinstance(result, tuple)
    assert all(type(x) is float for x in result)


# --- output units ------------------------------------------------------------------------------


def test_to_unit_published():
    assert to_unit(74.65568, "speed", "mph") == pytest.approx(167.0, rel=1e-12)
    assert to_unit(251.46, "length", "yd") == pytest.approx(275.0, rel=1e-12)
    assert to_unit(293.15, "temperature", "C") == pytest.approx(20.0, abs=1e-9)
    assert to_unit(293.15, "temperature", "F") == pytest.approx(68.0, abs=1e-9)
    assert to_unit(math.pi, "angle", "deg") == pytest.approx(180.0, rel=1e-15)
    assert to_unit(0.25, "fraction", "%") == pytest.approx(25.0, rel=1e-15)
    # Aliases and case are accepted.
    assert to_unit(74.65568, "speed", "MPH") == pytest.approx(167.0, rel=1e-12)
    assert to_unit(3.0, "speed", "mps") == 3.0
    assert to_unit(0.9144, "length", "yards") == pytest.approx(1.0, rel=1e-15)


@pytest.mark.parametrize(
    ("kind", "unit"), [(kind, unit) for kind, (_, table) in KINDS.items() for unit in table]
)
@pytest.mark.parametrize("number", [-40.0, 0.0, 1.0, 167.25, 2686.0])
def test_round_trip_every_unit(kind, unit, number):
    si = parse_quantity(f"{number} {unit}", kind)
    assert to_unit(si, kind, unit) == pytest.approx(number, rel=1e-12, abs=1e-9)


def test_to_unit_unknown_unit():
    with pytest.raises(UnitError, match=r"unknown speed unit 'mpg': expected one of mph, m/s"):
        to_unit(1.0, "speed", "mpg")
    with pytest.raises(UnitError):
        to_unit(1.0, "length", "rpm")  # a unit of another kind


# --- column names ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("column", "expected"),
    [
        ("ball_speed_mph", ("ball_speed", "speed", "mph")),
        ("club_speed_mps", ("club_speed", "speed", "m/s")),
        ("ball_speed_kph", ("ball_speed", "speed", "km/h")),
        ("ball_speed_fps", ("ball_speed", "speed", "ft/s")),
        ("spin_rpm", ("spin", "spin", "rpm")),
        ("spin_radps", ("spin", "spin", "rad/s")),
        ("launch_deg", ("launch", "angle", "deg")),
        ("spin_axis_rad", ("spin_axis", "angle", "rad")),
        ("carry_yd", ("carry", "length", "yd")),
        ("carry_m", ("carry", "length", "m")),
        ("apex_ft", ("apex", "length", "ft")),
        ("offline_cm", ("offline", "length", "cm")),
        ("diameter_mm", ("diameter", "length", "mm")),
        ("mass_kg", ("mass", "mass", "kg")),
        ("mass_g", ("mass", "mass", "g")),
        ("temperature_c", ("temperature", "temperature", "C")),
        ("temperature_f", ("temperature", "temperature", "F")),
        ("temperature_k", ("temperature", "temperature", "K")),
        ("pressure_pa", ("pressure", "pressure", "Pa")),
        ("pressure_hpa", ("pressure", "pressure", "hPa")),
        ("humidity_pct", ("humidity", "fraction", "%")),
        ("Ball_Speed_MPH", ("Ball_Speed", "speed", "mph")),
    ],
)
def test_from_column_name(column, expected):
    assert from_column_name(column) == expected
    base, kind, unit = expected
    assert unit in KINDS[kind][1]


@pytest.mark.parametrize(
    "column", ["ball_speed", "carry", "mph", "_mph", "", "launch_angle", "carry_yds", "carry-yd"]
)
def test_from_column_name_without_suffix(column):
    assert from_column_name(column) is None


def test_column_value_round_trip():
    base, kind, unit = from_column_name("ball_speed_mph")
    assert parse_quantity(f"167 {unit}", kind) == pytest.approx(74.65568, rel=1e-12)


# --- malformed input ---------------------------------------------------------------------------

BAD_SCALARS = [
    ("", "speed"),
    ("   ", "speed"),
    ("abc", "speed"),
    ("mph", "speed"),
    ("12 parsecs", "length"),
    ("167mpg", "speed"),
    ("167 mph", "length"),  # a unit of another kind
    ("1,000", "length"),
    ("74,3", "speed"),
    ("1_000", "length"),
    ("5 5", "speed"),
    ("5mph mph", "speed"),
    ("nan", "speed"),
    ("NaN", "speed"),
    ("inf", "speed"),
    ("-inf", "speed"),
    ("Infinity", "speed"),
    ("1e999", "speed"),
    ("-1e999 mph", "speed"),
    ("1e308 atm", "pressure"),  # finite number, overflows in SI
    (math.nan, "speed"),
    (math.inf, "angle"),
    (-math.inf, "temperature"),
    (10**400, "length"),
    (None, "speed"),
    (True, "speed"),
    ([5.0], "speed"),
]


def _one_line(exc_info) -> str:
    message = str(exc_info.value)
    assert message
    assert "\n" not in message and "\r" not in message
    return message


@pytest.mark.parametrize(("value", "kind"), BAD_SCALARS)
def test_malformed_scalar_raises_unit_error(value, kind):
    with pytest.raises(UnitError) as exc_info:
        parse_quantity(value, kind)
    message = _one_line(exc_info)
    assert message.startswith("cannot read ")
    assert f" as a {kind}" in message or f" as an {kind}" in message


@pytest.mark.parametrize(("value", "kind"), BAD_SCALARS)
def test_malformed_scalar_names_the_option(value, kind):
    with pytest.raises(UnitError) as exc_info:
        parse_quantity(value, kind, name="--ball-speed")
    assert _one_line(exc_info).startswith("--ball-speed: cannot read ")


def test_unit_error_is_value_error():
    with pytest.raises(ValueError):
        parse_quantity("abc", "speed")


def test_message_for_unknown_unit():
    with pytest.raises(UnitError) as exc_info:
        parse_quantity("167mpg", "speed", name="--ball-speed")
    assert str(exc_info.value) == (
        "--ball-speed: cannot read '167mpg' as a speed: expected a number with an optional unit "
        "(mph, m/s, km/h, ft/s, kn); a bare number is m/s"
    )


def test_message_states_golf_bare_units():
    with pytest.raises(UnitError, match=r"as an angle: .*a bare number is degrees$"):
        parse_quantity("12 parsecs", "angle")
    with pytest.raises(UnitError, match=r"a bare number is degrees Celsius$"):
        parse_quantity("hot", "temperature")


@pytest.mark.parametrize("value", ["nan", "inf", "1e999", math.nan, math.inf])
def test_message_for_non_finite(value):
    with pytest.raises(UnitError, match=r": not a finite number$"):
        parse_quantity(value, "speed")


def test_multiline_input_gives_one_line_message():
    with pytest.raises(UnitError) as exc_info:
        parse_quantity("12\nparsecs", "length", name="--carry")
    assert _one_line(exc_info).startswith("--carry: cannot read '12\\nparsecs' as a length")


BAD_VECTORS = [
    ("1,2,3", 2),
    ("1", 2),
    ("", 2),
    ("5,", 2),
    (",5", 2),
    ("5;0", 2),
    ("5 0", 2),
    ("5,abc", 2),
    ("5,12 parsecs", 2),
    ("nan,0", 2),
    ("0,inf", 2),
    ("10,-3 mph", 2),  # a unit on some components only
    ("10 mph,-3", 2),
    ("1,2", 3),
    ((1.0, 2.0, 3.0), 2),
    ((1.0, math.nan), 2),
    (None, 2),
    (5.0, 2),
]


@pytest.mark.parametrize(("value", "size"), BAD_VECTORS)
def test_malformed_vector_raises_unit_error(value, size):
    with pytest.raises(UnitError) as exc_info:
        parse_vector(value, "speed", size=size)
    assert _one_line(exc_info).startswith("cannot read ")
    with pytest.raises(UnitError) as exc_info:
        parse_vector(value, "speed", name="--wind", size=size)
    assert _one_line(exc_info).startswith("--wind: cannot read ")


def test_vector_messages():
    with pytest.raises(UnitError) as exc_info:
        parse_vector("1,2,3", "speed", name="--wind")
    assert str(exc_info.value) == (
        "--wind: cannot read '1,2,3' as a speed vector: expected 2 comma-separated components "
        "(e.g. '0,0'), got 3"
    )
    with pytest.raises(UnitError, match=r"component 2 \('abc'\): expected a number"):
        parse_vector("5,abc", "speed", name="--wind")
    with pytest.raises(UnitError, match=r"give a unit on every component or on none"):
        parse_vector("10,-3 mph", "speed", name="--wind")


# --- programming errors ------------------------------------------------------------------------


def test_unknown_kind_is_a_plain_value_error():
    for call in (
        lambda: parse_quantity("1", "acceleration"),
        lambda: parse_vector("1,2", "acceleration"),
        lambda: to_unit(1.0, "acceleration", "m/s2"),
    ):
        with pytest.raises(ValueError, match="unknown kind 'acceleration'") as exc_info:
            call()
        assert not isinstance(exc_info.value, UnitError)


@pytest.mark.parametrize("size", [0, -1, 2.0])
def test_bad_vector_size(size):
    with pytest.raises(ValueError, match="size must be a positive integer"):
        parse_vector("1,2", "speed", size=size)


# --- degrees sign, digits, values in messages --------------------------------------------------


@pytest.mark.parametrize(
    ("text", "kind", "same_as"),
    [
        ("10°", "angle", "10deg"),
        ("10 °", "angle", "10 deg"),
        ("-2.5°", "angle", "-2.5deg"),
        ("20°C", "temperature", "20 C"),
        ("10º", "angle", "10deg"),  # the ordinal sign, a degree sign on some keyboards
        ("20 ºC", "temperature", "20 C"),
        ("68ºF", "temperature", "68 F"),
    ],
)
def test_degree_sign_is_degrees(text, kind, same_as):
    """``°`` is accepted on purpose (documented in docs/shots.md): ``10°`` is ``10deg``."""
    assert parse_quantity(text, kind) == parse_quantity(same_as, kind)


@pytest.mark.parametrize(
    ("value", "kind", "digit"),
    [
        ("１６７mph", "speed", "１"),  # full-width digits: float() reads them
        ("１６７", "speed", "１"),
        ("10.٥", "angle", "٥"),  # Arabic-Indic five
        ("２６８６ rpm", "spin", "２"),
    ],
)
def test_only_ascii_digits(value, kind, digit):
    """Python's float() reads any Unicode decimal digit; the unit reader refuses them in one
    line saying that only ASCII digits are accepted."""
    with pytest.raises(UnitError) as exc_info:
        parse_quantity(value, kind, name="--ball-speed")
    assert _one_line(exc_info) == (
        f"--ball-speed: cannot read {value!r} as {'an' if kind == 'angle' else 'a'} {kind}: "
        f"only ASCII digits (0-9) are accepted, not {digit!r}"
    )
    with pytest.raises(UnitError, match="only ASCII digits"):
        parse_vector(f"{value},0", kind)


@pytest.mark.parametrize(
    ("value", "kind", "dash"),
    [
        ("\u22123", "temperature", "\u2212"),  # the minus sign a word processor writes
        ("\u22123 \u00b0C", "temperature", "\u2212"),
        ("\u201390", "angle", "\u2013"),  # an en dash
        ("\uff0d5 mph", "speed", "\uff0d"),  # full width
    ],
)
def test_a_dash_that_looks_like_a_minus_is_named(value, kind, dash):
    """A minus sign that is not ASCII's '-' is refused naming it (it was "expected a number with
    an optional unit", as if the unit were wrong); the replay's reason for a cell says so too."""
    with pytest.raises(UnitError) as exc_info:
        parse_quantity(value, kind, name="--x")
    assert _one_line(exc_info).endswith(
        f"{dash!r} (U+{ord(dash):04X}) is not read as a minus sign: type '-'"
    )
    with pytest.raises(UnitError, match="is not read as a minus sign"):
        parse_vector(f"1,{value}", kind)


@pytest.mark.parametrize("text", ["\u2014", "N\u2013A", "12\u201315"])
def test_a_dash_that_is_not_a_sign_is_not_called_one(text):
    """A dash a cell holds for no reading, or one between two numbers, is not a minus sign:
    not told to be typed as '-'."""
    assert foreign_digits(text) is None
    with pytest.raises(UnitError) as exc_info:
        parse_quantity(text, "speed", name="--x")
    assert "minus sign" not in _one_line(exc_info)


def test_values_in_messages_are_plain_numbers():
    """numpy 2's reprs (np.float64(nan)) do not reach a message: numbers read as typed."""
    np = pytest.importorskip("numpy")
    assert shown(np.float64("nan")) == "nan"
    assert shown(np.float64(1.5)) == "1.5"
    assert shown(np.float32(0.1)) == "0.1"
    assert shown(np.int64(3)) == "3"
    assert shown(np.bool_(True)) == "True"
    assert shown([np.float64(1.0), 2]) == "[1.0, 2]"
    assert shown("167 mpg") == "'167 mpg'"
    with pytest.raises(UnitError) as exc_info:
        parse_quantity(np.float64("nan"), "speed", name="--ball-speed")
    assert str(exc_info.value) == "--ball-speed: cannot read nan as a speed: not a finite number"


def test_a_bare_number_out_of_range_is_told_the_units_that_bring_it_in():
    """``meant_quoted``: the quoted units (rpm; mph, km/h) in which a bare SI number out of its
    range is within it; none for a number within it, or within it in no such unit."""
    assert meant_quoted(2686.0, "spin", 0.0, 2000.0) == ("rpm",)  # 281.3 rad/s
    assert meant_quoted(26860.0, "spin", 0.0, 2000.0) == ()  # 2812.8 rad/s
    assert meant_quoted(281.0, "spin", 0.0, 2000.0) == ()  # within its range
    assert meant_quoted(250.0, "speed", 0.5, 120.0) == ("mph", "km/h")  # 111.8, 69.4
    assert meant_quoted(300.0, "speed", 0.5, 120.0) == ("km/h",)  # 134.1 m/s in mph
    assert meant_quoted(500.0, "length", 0.0, 400.0) == ()  # no quoted unit


def test_a_whole_number_of_every_exact_type_is_read_exactly():
    """A Decimal, a Fraction or a long double of 2**53 + 1 went through a float to 2**53; bytes
    and NumPy's True were read as numbers, and a timedelta64 raised a TypeError."""
    import decimal
    import fractions

    from mcrun.units import TOO_LARGE, whole_number

    big = 2**53 + 1
    assert whole_number(decimal.Decimal(big)) == (big, "")
    assert whole_number(fractions.Fraction(big)) == (big, "")
    if np.finfo(np.longdouble).nmant > 52:  # (where a long double holds 2**53 + 1: x86)
        assert whole_number(np.longdouble(2**53) + 1) == (big, "")
    for refused in (b"12", bytearray(b"12"), np.True_, np.complex128(10), np.timedelta64(7, "s"),
                    fractions.Fraction(3, 2), decimal.Decimal("NaN")):  # fmt: skip
        assert whole_number(refused) == (None, ""), refused
    assert whole_number("0e2000") == (0, "")  # (0 however large its exponent)
    assert whole_number("1e999999999") == (None, TOO_LARGE)  # (refused at once)
    assert whole_number("9" * 5000) == (None, TOO_LARGE)
