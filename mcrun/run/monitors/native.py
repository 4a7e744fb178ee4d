"""mcrun's own launch files: CSV or Parquet with columns named by quantity and unit
(``ball_speed_mph``, ``launch_deg``, ``spin_rpm``, optional ``spin_axis_deg``, ``azimuth_deg``),
read as pandas reads a plain table. The exports of the devices are in ``formats`` and ``read``.
"""

import csv
import itertools
from pathlib import Path

import pandas as pd

from mcrun.quantities import InputError
from mcrun.units import from_column_name, shown

NAMES_SHOWN = 12
"""Column names a message lists at most (a garbled or 20,000-column header stays one short
line)."""


def names_shown(columns, most=NAMES_SHOWN):
    """The names of ``columns`` for a message: each cut to 40 characters with what cannot be
    printed escaped, at most ``most`` of them, then how many more; "none" when empty."""
    columns = list(columns)
    if not columns:
        return "none"
    shown_names = [_name_shown(c) for c in columns[:most]]
    more = len(columns) - most
    return ", ".join(shown_names) + (f" and {more} more" if more > 0 else "")


def _name_shown(name):
    text = str(name)
    if text.isprintable():
        return text if len(text) <= 40 else text[:37] + "..."
    return shown(text, 40)


# Columns of a launch-monitor file: quantity -> accepted base names (the unit is the suffix).
FILE_COLUMNS = {
    "ball_speed": ("ball_speed",),
    "launch_angle": ("launch", "launch_angle", "vertical_launch", "launch_vertical"),
    "spin": ("spin", "total_spin", "spin_rate"),
    "spin_axis": ("spin_axis",),
    "azimuth": ("azimuth", "direction", "launch_direction", "horizontal_launch"),
}

# The device's own results a native file may hold: quantity -> accepted base names.
DEVICE_COLUMNS = {
    "carry": ("carry",),
    "total": ("total",),
    "apex": ("apex", "peak_height", "max_height"),
    "descent_angle": ("descent_angle", "land_angle"),
    "carry_side": ("carry_side", "offline", "side"),
    "total_side": ("total_side",),
}

# Kind of every quantity a launch file can give (units.KINDS).
KIND = {
    "ball_speed": "speed",
    "launch_angle": "angle",
    "spin": "spin",
    "spin_axis": "angle",
    "azimuth": "angle",
    "back_spin": "spin",
    "side_spin": "spin",
    "carry": "length",
    "total": "length",
    "apex": "length",
    "descent_angle": "angle",
    "carry_side": "length",
    "total_side": "length",
}

REQUIRED = ("ball_speed", "launch_angle", "spin")


def launch_columns(frame, source="the shots", known=""):
    """{quantity: (column, unit)} of the launch columns of a launch-monitor table, recognised
    by name and unit (``units.from_column_name``); InputError naming ``source`` when a required
    one is missing or two give the same quantity. ``known``: the other formats, for the
    message."""
    found = _columns(frame, FILE_COLUMNS, source)
    missing = [q for q in REQUIRED if q not in found]
    if missing:
        names = names_shown(frame.columns)
        raise InputError(
            f"{source}: no recognisable column for {', '.join(missing)}; expected columns named "
            "with their unit (ball_speed_mph or _mps, launch_deg, spin_rpm or _radps; optional "
            f"spin_axis_deg, azimuth_deg), found {names}{known}"
        )
    return found


def device_columns(frame, source="the shots"):
    """{quantity: (column, unit)} of the device's results in a native table (``carry_yd``...)."""
    return _columns(frame, DEVICE_COLUMNS, source)


def _columns(frame, table, source):
    found = {}
    for column in frame.columns:
        parsed = from_column_name(str(column).strip().lower())
        if parsed is None:
            continue
        base, kind, unit = parsed
        for quantity, bases in table.items():
            if base in bases and KIND[quantity] == kind:
                if quantity in found:
                    raise InputError(
                        f"{source}: columns {found[quantity][0]!r} and {column!r} both give "
                        f"{quantity}; keep one"
                    )
                found[quantity] = (column, unit)
    return found


def check_file(path):
    """InputError naming ``path`` unless it is a file."""
    if path.is_dir():
        raise InputError(f"{path}: is a directory, not a CSV or Parquet file")
    if not path.is_file():
        what = "not a regular file (a device or a pipe)" if path.exists() else "no such file"
        raise InputError(f"{path}: {what}")


def text_encoding(path):
    """How a CSV's text is encoded: "utf-16" where it begins with a UTF-16 byte-order mark (a
    spreadsheet's "Unicode Text"), else "utf-8"."""
    with open(path, "rb") as file:
        return "utf-16" if file.read(2) in (b"\xff\xfe", b"\xfe\xff") else "utf-8"


def sep_line(path, encoding="utf-8"):
    """The separator a spreadsheet's first line names (``sep=,``, Excel's hint), or None."""
    with open(path, encoding=encoding, errors="replace", newline="") as file:
        first = file.readline().lstrip("\ufeff").rstrip("\r\n")
    return first[4] if first.lower().startswith("sep=") and len(first) == 5 else None


def _data_lines(path, encoding="utf-8"):
    """The lines of a CSV as pandas reads them with ``comment="#"``: the text after a ``#``
    outside quotes dropped, blank lines skipped."""
    with open(path, encoding=encoding, errors="replace", newline="") as file:
        for line in file:
            quoted = False
            for k, char in enumerate(line):
                if char == '"':
                    quoted = not quoted
                elif char == "#" and not quoted:
                    line = line[:k]
                    break
            if line.strip():
                yield line


def check_field_counts(path, lines=None, sep=","):
    """InputError when a data row has more fields than the header: pandas would take the
    first columns as the index (or drop the extra fields), shifting every value silently. A
    short row reads as missing values. ``lines``: the lines to check (default: the file's,
    comments dropped); the header first; ``sep``: their separator."""
    lines = _data_lines(path, text_encoding(path)) if lines is None else lines
    rows = csv.reader(lines, delimiter=sep, skipinitialspace=True)
    try:
        header = next(rows, None)
        if header is None:
            return
        for k, fields in enumerate(rows, start=1):
            if len(fields) > len(header):
                raise InputError(
                    f"{path}: row {k} has {len(fields)} fields, the header has {len(header)}"
                )
    except csv.Error as err:  # a NUL byte, a field over the csv module's limit
        raise InputError(f"{path}: cannot read it as CSV: {first_line(err)}") from None


def first_line(err, most=120):
    """The first line of an exception's message, cut to ``most`` characters (a reader's
    message may quote the file)."""
    text = str(err).strip()
    first = text.splitlines()[0] if text else type(err).__name__
    return first if len(first) <= most else first[: most - 3] + "..."


def read_launch_table(path):
    """A launch file (CSV or Parquet) as a DataFrame of at least one row; InputError naming the
    file if it is not a readable file, has no rows, or (CSV) a row with more fields than the
    header."""
    path = Path(path)
    check_file(path)
    parquet = path.suffix.lower() in (".parquet", ".pq")
    try:
        if parquet:
            frame = pd.read_parquet(path)
        else:
            encoding = text_encoding(path)
            sep = sep_line(path, encoding)  # (its line skipped, the separator it names used)
            lines = itertools.islice(_data_lines(path, encoding), 1 if sep else 0, None)
            check_field_counts(path, lines, sep or ",")
            frame = pd.read_csv(path, comment="#", skipinitialspace=True, index_col=False,
                                encoding=encoding, sep=sep or ",",
                                skiprows=1 if sep else None)  # fmt: skip
    except InputError:
        raise
    except pd.errors.EmptyDataError:
        raise InputError(f"{path}: no shots: the file is empty") from None
    except Exception as err:  # noqa: BLE001 - any reader failure is a bad file for the user
        raise InputError(f"{path}: cannot read it as CSV or Parquet: {first_line(err)}") from None
    if len(frame) == 0:
        what = "the file has no rows" if parquet else "the file has a header only"
        raise InputError(f"{path}: no shots: {what}")
    return frame
