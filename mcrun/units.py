"""User-given quantities with optional units, read into SI floats.

The physics core works in SI only; this module is the edge where numbers typed by a user (command
line options, scenario files, CSV columns) become SI floats, and where SI results go back out.

A quantity is a number with an optional unit, e.g. ``"167mph"``, ``"167 mph"``, ``"74.3"``,
``"74.3 m/s"``. Unit names are case-insensitive and spaces inside them are ignored; ``°`` is
degrees (``"10°"`` is ``"10deg"``, ``"20°C"`` is ``"20C"``), and so is ``º``, the ordinal sign
that Spanish and Portuguese keyboards give for it. Digits are ASCII only (``"１６７"``
in full-width digits is refused, though Python's ``float`` reads it). A bare number
is taken in the kind's *bare unit*, which is SI except for two golf conventions:

- angles: a bare number is in **degrees** (``"12"`` is 12 deg, not 12 rad);
- temperatures: a bare number is in **degrees Celsius** (``"20"`` is 293.15 K).

Kinds and their SI units: speed (m/s), angle (rad), spin (rad/s), length (m), mass (kg),
temperature (K), pressure (Pa), fraction (dimensionless, 1 = 100 %), time (s).
"""

import decimal
import math
import numbers
import os
import re
import unicodedata
from pathlib import Path

import numpy as np

from mcrun.errors import InputError

__all__ = [
    "KINDS",
    "UNIT_SUFFIXES",
    "UnitError",
    "foreign_digits",
    "from_column_name",
    "is_number",
    "parse_quantity",
    "parse_vector",
    "shown",
    "to_unit",
]


class UnitError(InputError):
    """A quantity given by the user cannot be read; the message is one line meant for the user."""


_DEG = math.pi / 180.0
_REV = 2.0 * math.pi
_F_FACTOR = 5.0 / 9.0

KINDS: dict[str, tuple[str, dict[str, tuple[float, float]]]] = {
    # kind: (bare unit, {unit: (factor, offset)}), SI value = number * factor + offset.
    "speed": (
        "m/s",
        {
            "mph": (0.44704, 0.0),  # exact: 1609.344 m / 3600 s
            "m/s": (1.0, 0.0),
            "km/h": (1.0 / 3.6, 0.0),
            "ft/s": (0.3048, 0.0),
            "kn": (1852.0 / 3600.0, 0.0),  # international knot, exact
        },
    ),
    "angle": ("deg", {"deg": (_DEG, 0.0), "rad": (1.0, 0.0)}),
    "spin": ("rad/s", {"rad/s": (1.0, 0.0), "rpm": (_REV / 60.0, 0.0), "rps": (_REV, 0.0)}),
    "length": (
        "m",
        {
            "m": (1.0, 0.0),
            "cm": (0.01, 0.0),
            "mm": (0.001, 0.0),
            "yd": (0.9144, 0.0),  # exact (international yard, 1959)
            "ft": (0.3048, 0.0),
            "in": (0.0254, 0.0),
        },
    ),
    "mass": ("kg", {"kg": (1.0, 0.0), "g": (0.001, 0.0), "oz": (0.028349523125, 0.0)}),
    "temperature": (
        "C",
        {
            "C": (1.0, 273.15),
            "F": (_F_FACTOR, 273.15 - 32.0 * _F_FACTOR),
            "K": (1.0, 0.0),
        },
    ),
    "pressure": (
        "Pa",
        {
            "Pa": (1.0, 0.0),
            "hPa": (100.0, 0.0),
            "mbar": (100.0, 0.0),
            "kPa": (1000.0, 0.0),
            "inHg": (3386.389, 0.0),  # at 0 C, the unit of US altimeter settings
            "atm": (101325.0, 0.0),
        },
    ),
    "fraction": ("fraction", {"fraction": (1.0, 0.0), "%": (0.01, 0.0)}),
    "time": ("s", {"s": (1.0, 0.0), "ms": (0.001, 0.0)}),
}
"""Kind -> (bare unit, {unit: (factor, offset)}); SI value = number * factor + offset."""

# Other spellings of the units in KINDS, per kind: alias -> unit. Matched case-insensitively.
_ALIASES: dict[str, dict[str, str]] = {
    "speed": {
        "mps": "m/s",
        "kph": "km/h",
        "kmh": "km/h",
        "fps": "ft/s",
        "knot": "kn",
        "knots": "kn",
    },
    # (º, the ordinal sign, is the degree sign on Spanish and Portuguese keyboards)
    "angle": {
        "degree": "deg",
        "degrees": "deg",
        "°": "deg",
        "º": "deg",
        "radian": "rad",
        "radians": "rad",
    },
    "spin": {"radps": "rad/s", "rev/s": "rps"},
    "length": {
        "yard": "yd",
        "yards": "yd",
        "feet": "ft",
        "foot": "ft",
        "inch": "in",
        "inches": "in",
    },
    "mass": {},
    "temperature": {
        "degC": "C",
        "°C": "C",
        "ºC": "C",
        "celsius": "C",
        "degF": "F",
        "°F": "F",
        "ºF": "F",
        "fahrenheit": "F",
        "kelvin": "K",
    },
    "pressure": {},
    "fraction": {"percent": "%", "pct": "%"},
    "time": {"sec": "s", "second": "s", "seconds": "s"},
}

# Human wording of the bare unit, where the unit name alone would read badly in a message.
_BARE_WORDS = {
    "angle": "degrees",
    "temperature": "degrees Celsius",
    "fraction": "a fraction (0.5 = 50%)",
}

# Column-name suffix token -> (kind, unit in KINDS).
_COLUMN_SUFFIXES: dict[str, tuple[str, str]] = {
    "mps": ("speed", "m/s"),
    "mph": ("speed", "mph"),
    "kph": ("speed", "km/h"),
    "kmh": ("speed", "km/h"),
    "fps": ("speed", "ft/s"),
    "kn": ("speed", "kn"),
    "deg": ("angle", "deg"),
    "rad": ("angle", "rad"),
    "radps": ("spin", "rad/s"),
    "rpm": ("spin", "rpm"),
    "m": ("length", "m"),
    "cm": ("length", "cm"),
    "mm": ("length", "mm"),
    "yd": ("length", "yd"),
    "ft": ("length", "ft"),
    "kg": ("mass", "kg"),
    "g": ("mass", "g"),
    "c": ("temperature", "C"),
    "f": ("temperature", "F"),
    "k": ("temperature", "K"),
    "pa": ("pressure", "Pa"),
    "hpa": ("pressure", "hPa"),
    "pct": ("fraction", "%"),
    "s": ("time", "s"),
    "ms": ("time", "ms"),
}
# The unit suffixes a column's or a key's name may end with (``from_column_name``).
UNIT_SUFFIXES = tuple(_COLUMN_SUFFIXES)


def _key(unit: str) -> str:
    """Lookup key of a unit name: lower case, no whitespace."""
    return "".join(unit.split()).lower()


def _build_lookup() -> dict[str, dict[str, str]]:
    lookup: dict[str, dict[str, str]] = {}
    for kind, (bare, units) in KINDS.items():
        assert bare in units, (kind, bare)
        table: dict[str, str] = {}
        names = [(u, u) for u in units] + list(_ALIASES[kind].items())
        for name, unit in names:
            assert unit in units, (kind, unit)
            assert _key(name) not in table, (kind, name)
            table[_key(name)] = unit
        lookup[kind] = table
    return lookup


_LOOKUP = _build_lookup()

_NUMBER = re.compile(
    r"\s*(?P<num>[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)\s*(?P<unit>.*?)\s*",
    re.DOTALL,
)


# Dashes that look like a minus sign and are not ASCII's '-': the minus sign, hyphens, dashes,
# the small and the full-width hyphen-minus.
MINUS_LIKE = "\u2212\u2010\u2011\u2012\u2013\u2014\u2015\ufe63\uff0d"
# One where a number's sign goes: before a digit or a point, at the start, after a blank or an
# exponent's e ("−3", "1e−3"; not a cell's "—" for no reading, nor "12–15").
_MINUS_LIKE_SIGN = re.compile(rf"(?:^|(?<=[\s,;(\[eE]))([{MINUS_LIKE}])(?=[0-9.])")


def foreign_digits(text: str) -> str | None:
    """Why ``text`` cannot be read when it holds a decimal digit other than 0-9 (``１６７``, full
    width), else None. Python's ``float`` reads any Unicode decimal digit, but a value that
    looks like a number and is not the one typed is refused: only ASCII digits are accepted.
    So is a digit separator: Python's ``int`` and ``float`` read "1_000" as 1000 (and "3_80" as
    380), which ``parse_quantity`` refuses, and a dash that looks like a minus where a sign
    goes (``MINUS_LIKE``)."""
    digit = next((c for c in text if c.isdecimal() and not c.isascii()), None)
    if digit is not None:
        return f"only ASCII digits (0-9) are accepted, not {digit!r}"
    sign = _MINUS_LIKE_SIGN.search(text)
    if sign is not None:  # (a word processor's or a spreadsheet's minus: "−3" was "not a unit")
        dash = sign.group(1)
        return f"{dash!r} (U+{ord(dash):04X}) is not read as a minus sign: type '-'"
    if "_" in text:
        return "'_' is not read in a number (write 1000, or 1e3)"
    return None


class _Unreadable(Exception):
    """Internal: why one value cannot be read (the reason part of a UnitError message)."""


def _check_kind(kind: str) -> None:
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r}: expected one of {', '.join(KINDS)}")


def _unit_list(kind: str) -> str:
    return ", ".join(KINDS[kind][1])


def _expected(kind: str) -> str:
    bare = _BARE_WORDS.get(kind, KINDS[kind][0])
    return f"expected a number with an optional unit ({_unit_list(kind)}); a bare number is {bare}"


def article(word: str) -> str:
    """The indefinite article of ``word``: "an angle", "a speed"."""
    return "an" if word[0] in "aeiou" else "a"


def _prefix(name: str | None) -> str:
    return "" if name is None else " ".join(str(name).split()) + ": "


# The largest whole number a float holds exactly: "1e17" cannot say which integer it means.
EXACT_FLOAT_MOST = 2**53
INEXACT = "inexact"  # ``whole_number``'s reason for a number beyond EXACT_FLOAT_MOST via a float
# ``whole_number``'s reason for a number of over 1,000 digits (its int would be costly to make)
TOO_LARGE = "allowed: a whole number of at most 19 digits (this one has over 1,000)"


def whole_number(value: object) -> tuple[int | None, str]:
    """(``value`` as the int it writes, ""), or (None, why not): an int (not a bool), a float
    of an integral value up to ``EXACT_FLOAT_MOST``, or a text read exactly, in digits or as a
    number such as "1e6" or "7.0" (through a float, 2**53 + 1 was 2**53, and "2**53 + 1.0" or
    "7.0000000000000001" were whole). Why not: ``INEXACT`` for a larger float,
    ``foreign_digits``' reason for a text in other digits (float read "١٢" as 12),
    ``TOO_LARGE`` for a text beyond 10**1000 (its int would be costly to make), "" for anything
    else. A Decimal or a Fraction is read exactly too, and a long double as far as it holds."""
    if isinstance(value, bool | np.bool_ | bytes | bytearray | complex | np.complexfloating):
        return None, ""  # (not a number of one: float() read b"1_000", np.True_ as 1)
    if isinstance(value, numbers.Integral):
        try:
            return int(value), ""
        except TypeError:  # (a NumPy timedelta64 is Integral, and int() refuses it)
            return None, ""
    if isinstance(value, str):
        foreign = foreign_digits(value)
        if foreign:
            return None, foreign
        try:
            return int(value), ""
        except ValueError:
            pass
        try:
            value = decimal.Decimal(value)  # (not a float: read exactly; "1e999999" is cheap)
        except decimal.InvalidOperation:
            return None, ""
    if isinstance(value, numbers.Rational):  # (a Fraction, read exactly)
        return (int(value), "") if value.denominator == 1 else (None, "")
    if isinstance(value, decimal.Decimal):
        if not value.is_finite() or value != value.to_integral_value():
            return None, ""
        if not value.is_zero() and value.adjusted() > 1000:
            return None, TOO_LARGE
        return int(value), ""
    if isinstance(value, np.floating) and np.finfo(value.dtype).nmant > 52:  # (a long double)
        exact_enough = bool(np.isfinite(value)) and value == np.floor(value)
        return (int(value), "") if exact_enough else (None, "")
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
        return None, ""
    if not (math.isfinite(number) and number.is_integer()):
        return None, ""
    if abs(number) > EXACT_FLOAT_MOST:
        return None, INEXACT
    return int(number), ""


def whole_numbers_allowed(least: int, most: int | None = None, inexact: bool = False) -> str:
    """What a message says is allowed for a whole number from ``least`` to ``most`` (an
    int64's largest where None); ``inexact``: it was given through a float beyond 2**53
    (``whole_number``'s ``INEXACT``), which must be written in digits."""
    top = "2**63 - 1" if most is None else most
    beyond = " (beyond 2**53, in digits: a float is not one integer there)" * inexact
    return f"a whole number from {least} to {top}{beyond}"


def control_free(text: str) -> str:
    """``text`` without its control and format characters (an escape sequence, a
    right-to-left override, a line break): what it prints as."""
    return "".join(c for c in text if unicodedata.category(c)[0] != "C")


def path_of(value: object, what: str, allowed: str, error: type = InputError) -> Path:
    """``value`` as a Path, where it is text or a path; else ``error``, one line: ``{what}
    {value}: allowed: {allowed}`` (``Path(None)`` raises a TypeError naming no argument)."""
    if not isinstance(value, str | os.PathLike) or (isinstance(value, str) and not value.strip()):
        raise error(f"{what} {shown(value)}: allowed: {allowed}")  # ("" was the current folder)
    return Path(value)


def float_or_nan(value: object) -> float:
    """``value`` as a float where it is a number; NaN for text (``float("20")`` reads 20), a
    bool (``float(True)`` is 1), bytes, or what ``float`` refuses or overflows on."""
    if isinstance(value, str | bytes | bool | np.bool_):
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        return math.nan


def is_number(value: object) -> bool:
    """A real number (a Python or NumPy int or float), not a bool: ``float(True)`` is 1."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def shown(value: object, limit: int = 80) -> str:
    """``value`` as a message shows it: a number plainly (``1.5``, ``nan``, ``3``, where numpy
    2's repr gives ``np.float64(1.5)``), a list or tuple of them the same, anything else by its
    repr (a string in quotes); cut to ``limit`` characters."""
    text = _plain(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _plain(value: object) -> str:
    if isinstance(value, bool) or getattr(value, "dtype", None) is not None and value.dtype == "?":
        return str(bool(value))
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return str(value)  # numpy's str is the plain shortest form: 1.5, nan, 0.1 (float32)
    if isinstance(value, list | tuple):
        inner = ", ".join(_plain(v) for v in value)
        return f"[{inner}]" if isinstance(value, list) else f"({inner}{',' * (len(value) == 1)})"
    return repr(value)


def _read(value: object, kind: str) -> tuple[float, bool]:
    """Read one quantity; return (SI value, whether a unit was given) or raise _Unreadable."""
    if isinstance(value, str):
        foreign = foreign_digits(value)
        if foreign is not None:
            raise _Unreadable(foreign)
        match = _NUMBER.fullmatch(value)
        if match is None:
            try:
                number = float(value)  # "nan", "inf", "-Infinity"
            except ValueError:
                raise _Unreadable(_expected(kind)) from None
            if not math.isfinite(number):
                raise _Unreadable("not a finite number")
            raise _Unreadable(_expected(kind))  # e.g. "1_000": float() reads it, we do not
        number = float(match["num"])
        unit_text = match["unit"]
        if unit_text:
            unit = _LOOKUP[kind].get(_key(unit_text))
            if unit is None:
                raise _Unreadable(_expected(kind))
        else:
            unit = KINDS[kind][0]
    elif isinstance(value, numbers.Real) and not isinstance(value, bool):
        try:
            number = float(value)
        except OverflowError:
            raise _Unreadable("not a finite number") from None
        unit_text = ""
        unit = KINDS[kind][0]
    else:
        raise _Unreadable(f"not a number or a string; {_expected(kind)}")
    if not math.isfinite(number):
        raise _Unreadable("not a finite number")
    factor, offset = KINDS[kind][1][unit]
    si = number * factor + offset
    if not math.isfinite(si):
        raise _Unreadable("the value is too large")
    return si, bool(unit_text)


def read_quantity(value: str | float, kind: str, name: str | None = None) -> tuple[float, bool]:
    """``parse_quantity``'s SI value, and whether ``value`` gave its unit (False for a bare
    number, read in the kind's bare unit); UnitError as ``parse_quantity``'s."""
    _check_kind(kind)
    try:
        return _read(value, kind)
    except _Unreadable as exc:
        raise UnitError(
            f"{_prefix(name)}cannot read {shown(value)} as {article(kind)} {kind}: {exc}"
        ) from None


def parse_quantity(value: str | float, kind: str, name: str | None = None) -> float:
    """Read a quantity with an optional unit into SI.

    Parameters
    ----------
    value : str, int or float
        E.g. ``"167mph"``, ``"167 mph"``, ``"74.3"``, ``74.3``. Numbers and unitless strings are
        in the bare unit of `kind` (SI, but degrees for angles and Celsius for temperatures).
    kind : str
        A key of `KINDS`: speed, angle, spin, length, mass, temperature, pressure or fraction.
    name : str, optional
        Name of the option or field (e.g. ``"--ball-speed"``), put at the start of error messages.

    Returns
    -------
    float
        The value in SI: m/s, rad, rad/s, m, kg, K, Pa, or a dimensionless fraction.

    Raises
    ------
    UnitError
        If the value is malformed, has an unknown unit, or is not finite.
    """
    return read_quantity(value, kind, name)[0]


def parse_vector(
    value: str | tuple | list, kind: str, name: str | None = None, size: int = 2
) -> tuple[float, ...]:
    """Read a comma-separated vector of quantities into SI, e.g. a wind ``"10mph,-3mph"``.

    Each component may carry its own unit, but either all components or none must have one, so
    that ``"10,-3 mph"`` is refused rather than read as 10 m/s and -3 mph.

    Parameters
    ----------
    value : str, or sequence of str or numbers
        E.g. ``"5,0"`` (bare unit), ``"10mph,-3mph"``, ``"10 mph, -3 mph"`` or ``(5.0, 0.0)``.
    kind : str
        A key of `KINDS`, as for `parse_quantity`.
    name : str, optional
        Name of the option or field, put at the start of error messages.
    size : int, default 2
        Number of components required.

    Returns
    -------
    tuple of float
        The `size` components in SI units.

    Raises
    ------
    UnitError
        If the number of components is wrong or a component cannot be read.
    """
    _check_kind(kind)
    if not isinstance(size, int) or size < 1:
        raise ValueError(f"size must be a positive integer, got {size!r}")
    head = f"{_prefix(name)}cannot read {shown(value)} as {article(kind)} {kind} vector"
    if isinstance(value, str):
        parts: list[object] = value.split(",")
    elif isinstance(value, (tuple, list)):
        parts = list(value)
    else:
        raise UnitError(f"{head}: expected {size} comma-separated components")
    if len(parts) != size:
        example = ",".join(["0"] * size)
        raise UnitError(
            f"{head}: expected {size} comma-separated components (e.g. {example!r}), "
            f"got {len(parts)}"
        )
    values: list[float] = []
    with_unit: list[bool] = []
    for i, part in enumerate(parts, start=1):
        try:
            si, has_unit = _read(part, kind)
        except _Unreadable as exc:
            raise UnitError(f"{head}: component {i} ({shown(part)}): {exc}") from None
        values.append(si)
        with_unit.append(has_unit)
    if any(with_unit) and not all(with_unit):
        raise UnitError(
            f"{head}: some components have a unit and some do not; give a unit on every "
            f"component or on none (a bare number is {_BARE_WORDS.get(kind, KINDS[kind][0])})"
        )
    return tuple(values)


def to_unit(value_si: float, kind: str, unit: str) -> float:
    """Convert an SI value to a unit, the inverse of `parse_quantity`.

    Parameters
    ----------
    value_si : float
        Value in SI units (m/s, rad, rad/s, m, kg, K, Pa, fraction).
    kind : str
        A key of `KINDS`.
    unit : str
        A unit of `kind` or one of its aliases, case-insensitive (e.g. ``"mph"``, ``"YD"``).

    Returns
    -------
    float
        The value in `unit`. Non-finite values pass through unchecked.

    Raises
    ------
    UnitError
        If `unit` is not a unit of `kind`.
    """
    _check_kind(kind)
    canonical = _LOOKUP[kind].get(_key(unit)) if isinstance(unit, str) else None
    if canonical is None:
        raise UnitError(f"unknown {kind} unit {shown(unit)}: expected one of {_unit_list(kind)}")
    factor, offset = KINDS[kind][1][canonical]
    return (float(value_si) - offset) / factor


def canonical_unit(kind: str, unit: str) -> str | None:
    """``unit`` of ``kind`` as `KINDS` names it (from any spelling: ``"MPH"``, ``"kph"``), or
    None where it is none of its units."""
    return _LOOKUP[kind].get(_key(unit)) if kind in _LOOKUP else None


def column_suffix(kind: str, unit: str) -> str | None:
    """The suffix of a key or column name (`UNIT_SUFFIXES`) that gives ``unit`` of ``kind`` (any
    spelling of it), or None (``spin``, ``"rps"``)."""
    canonical = canonical_unit(kind, unit)
    return next((k for k, v in _COLUMN_SUFFIXES.items() if v == (kind, canonical)), None)


# The units a quantity is quoted in where its bare number is read in SI: a spin in rpm and a
# speed in mph or km/h, as launch monitors give them.
QUOTED_UNITS: dict[str, tuple[str, ...]] = {"spin": ("rpm",), "speed": ("mph", "km/h")}


def meant_quoted(number: float, kind: str, low: float, high: float) -> tuple[str, ...]:
    """The units ``kind`` is quoted in (`QUOTED_UNITS`) in which ``number``, a bare number read
    in SI outside [``low``, ``high``] (SI), is within it (``spin = 2686``, read as 2686 rad/s
    and meant in rpm); () where it is within it, or in none of them."""
    if low <= number <= high:
        return ()
    return tuple(
        unit
        for unit in QUOTED_UNITS.get(kind, ())
        if low <= number * KINDS[kind][1][unit][0] + KINDS[kind][1][unit][1] <= high
    )


def quoted_hint(typed: str, kind: str, quoted: tuple[str, ...], write) -> str:
    """The advice, for a message, to a bare number ``typed`` that ``meant_quoted`` says was
    meant in one of ``quoted``: `` (a bare number is rad/s: for 8000 rpm, give 8000rpm)``, each
    unit's value written by ``write(typed, unit)`` as the input takes it; "" for none."""
    if not quoted:
        return ""
    ways = "; ".join(f"for {typed} {unit}, give {write(typed, unit)}" for unit in quoted)
    return f" (a bare number is {KINDS[kind][0]}: {ways})"


def from_column_name(column_name: str) -> tuple[str, str, str] | None:
    """Recognise a unit suffix in a column name.

    Parameters
    ----------
    column_name : str
        E.g. ``"ball_speed_mph"``, ``"spin_rpm"``, ``"carry_yd"``, ``"temperature_c"``. The suffix
        follows the last underscore and is matched case-insensitively; known suffixes are
        ``UNIT_SUFFIXES``: mps, mph, kph, kmh, fps, kn, deg, rad, radps, rpm, m, cm, mm, yd, ft,
        kg, g, c, f, k, pa, hpa, pct, s, ms.

    Returns
    -------
    tuple of (str, str, str) or None
        ``(base_name, kind, unit)``, with `unit` the unit's name in `KINDS` (``"mps"`` gives
        ``"m/s"``, ``"c"`` gives ``"C"``, ``"pct"`` gives ``"%"``), e.g. ``"ball_speed_mph"`` ->
        ``("ball_speed", "speed", "mph")``. None if there is no recognised suffix or no base.
    """
    base, sep, suffix = column_name.strip().rpartition("_")
    if not sep or not base:
        return None
    found = _COLUMN_SUFFIXES.get(suffix.lower())
    if found is None:
        return None
    kind, unit = found
    return base, kind, unit
