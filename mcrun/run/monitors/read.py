"""Reading a launch-monitor session: the bytes of an export (or mcrun's own CSV or Parquet) into
the file's own table and its launches and the device's results in SI.

What real files hold and how it is read: a UTF-8 byte-order mark (dropped); bytes that are not
UTF-8 (read as Latin-1); a ``sep=,`` first line (its separator used); Square Golf's ``Dates,...``
line and the blank line after it (skipped); a unit row under the header (``[mph]``, ``[km/h]``,
``[m]``: it governs); units in names (``Ball Speed (mph)``); directions written ``13.8 L``,
``R2.1`` or ``4.9<non-breaking space>R`` (left negative); spin as back and side spin (total =
hypot, axis = atan2(side, back); also where the total and the axis are sent as 0); sentinels for
"not measured" (NaN); a blank file and a file with a header only (refused, one line).
"""

import csv
import io
import json
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun.quantities import InputError
from mcrun.run.monitors import formats
from mcrun.run.monitors.native import (
    KIND,
    check_field_counts,
    check_file,
    device_columns,
    launch_columns,
    read_launch_table,
)
from mcrun.units import KINDS, UnitError, parse_quantity

LAUNCH = ("ball_speed", "launch_angle", "spin", "spin_axis", "azimuth")
DEVICE = ("carry", "total", "apex", "descent_angle", "carry_side", "total_side")

_KNOWN = f"; or an export of a format mcrun knows: {formats.known()}"

# Unit spellings of exports that mcrun.units does not know.
_UNIT_ALIASES = {"yds": "yd", "[]": "", "deg/s": "", "-": ""}


@dataclass(frozen=True)
class Session:
    """A session read: ``frame`` (the file's own columns and rows), ``format`` (a name of
    ``formats.NAMES``) and ``detected`` (False when forced), ``launch`` and ``device``
    (quantity -> SI array per row, NaN where not measured; only the quantities the file
    gives), ``sources`` and ``units`` (quantity -> the file's column it came from and that
    column's unit), ``club`` (the club of each row, or None) and ``club_column``."""

    path: str
    format: str
    detected: bool
    frame: pd.DataFrame
    launch: dict
    device: dict
    sources: dict
    units: dict
    club: np.ndarray | None
    club_column: str | None

    @property
    def title(self):
        fmt = formats.BY_NAME.get(self.format)
        return fmt.title if fmt else "mcrun columns"


def read_session(path, format=None):
    """The ``Session`` of the file at ``path``; ``format`` forces one of ``formats.NAMES``
    (default: detected from the header). InputError, one line naming the file, otherwise."""
    path = Path(path)
    check_file(path)
    if format is not None and format not in formats.NAMES:
        raise InputError(f"{path}: unknown format {format!r}; known: {', '.join(formats.NAMES)}")
    source = str(path)
    if format == formats.NATIVE:
        return session_of_frame(read_launch_table(path), source, format)
    if path.suffix.lower() in (".parquet", ".pq"):
        return session_of_frame(read_launch_table(path), source, format)
    text = _decode(path)
    if text.lstrip().startswith("{"):
        if format not in (None, "gspro"):
            raise InputError(f"{path}: JSON messages, not a {formats.BY_NAME[format].title} CSV")
        frame, units = _json_lines(path, text)
        return _session(frame, source, "gspro", format is None, {}, units)
    header, units, sep, body, skip = _split(path, text)
    names = [formats.split_name(c)[0] for c in header]
    fmt = formats.BY_NAME.get(format) if format else formats.detect(names)
    if fmt is None:
        # Neither an export's header nor mcrun's columns: say what was found and what is known.
        launch_columns(pd.DataFrame(columns=[c.strip() for c in header]), source, _KNOWN)
        return session_of_frame(read_launch_table(path), source, None)
    lines = enumerate(io.StringIO(body))
    check_field_counts(path, (text for k, text in lines if text.strip() and (k != 1 or not skip)))
    try:
        frame = pd.read_csv(
            io.StringIO(body),
            sep=sep,
            skipinitialspace=True,
            index_col=False,
            skiprows=skip,
            low_memory=False,
        )
    except Exception as err:  # noqa: BLE001 - any reader failure is a bad file for the user
        first = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
        raise InputError(f"{path}: cannot read it as a {fmt.title} export: {first}") from None
    frame = _tidy(frame)
    if len(frame) == 0:
        raise InputError(f"{path}: no shots: the file has a header only")
    file_units = {str(c): formats.split_name(c)[1] for c in frame.columns}
    for name, unit in zip(header, units or (), strict=False):
        if unit and " ".join(name.split()) in file_units:
            file_units[" ".join(name.split())] = unit
    return _session(frame, source, fmt.name, format is None, file_units, None)


def session_of_frame(frame, source, format=None):
    """The Session of a table already read: mcrun's own columns, or (by its header or
    ``format``) an export's."""
    names = [formats.split_name(c)[0] for c in frame.columns]
    fmt = formats.BY_NAME.get(format) if format else formats.detect(names)
    if fmt is not None:
        units = {str(c): formats.split_name(c)[1] for c in frame.columns}
        return _session(frame, source, fmt.name, format is None, units, None)
    found = launch_columns(frame, source, _KNOWN)
    found.update(device_columns(frame, source))
    launch, device, sources, units = {}, {}, {}, {}
    for quantity, (column, unit) in found.items():
        units[quantity] = unit
        factor, offset = KINDS[KIND[quantity]][1][unit]
        values = pd.to_numeric(frame[column], errors="coerce").to_numpy(dtype=float)
        (launch if quantity in LAUNCH else device)[quantity] = values * factor + offset
        sources[quantity] = column
    club, club_column = _club(frame, ("club",))
    return Session(
        source,
        formats.NATIVE,
        format is None,
        frame,
        launch,
        device,
        sources,
        units,
        club,
        club_column,
    )


# --- the text ------------------------------------------------------------------------------


def _decode(path):
    """The file's text: UTF-8 (without its byte-order mark), else Latin-1."""
    data = path.read_bytes()
    if not data.strip():
        raise InputError(f"{path}: no shots: the file is empty")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    return text.removeprefix("\ufeff")


def _fields(line, sep):
    return next(csv.reader([line], delimiter=sep, skipinitialspace=True), [])


def _split(path, text):
    """(header fields, unit-row units or None, separator, the text from the header on, the
    rows pandas skips after the header (the unit row)) of a CSV export."""
    sep = ","
    start = 0
    seen = 0
    header = None
    while start < len(text):
        end = text.find("\n", start)
        end = len(text) if end < 0 else end + 1
        line = text[start:end].strip("\r\n")
        if not line.strip() or line.startswith("#"):
            start = end
            continue
        if seen == 0 and line.lower().startswith("sep=") and len(line) >= 5:
            sep = line[4]
            seen += 1
            start = end
            continue
        if seen == 0 and line.startswith("Dates,"):  # Square Golf's first line
            seen += 1
            start = end
            continue
        header = _fields(line, sep)
        break
    if header is None:
        raise InputError(f"{path}: no shots: the file is empty")
    body = text[start:]
    second_end = body.find("\n", body.find("\n") + 1)
    lines = body[: second_end if second_end >= 0 else len(body)].splitlines()
    units = None
    skip = None
    if len(lines) > 1:
        row = _fields(lines[1], sep)
        filled = [f.strip() for f in row if f.strip()]
        if filled and all(f.startswith("[") and f.endswith("]") for f in filled):
            units = [f.strip().strip("[]").strip() for f in row]
            skip = [1]
    return header, units, sep, body, skip


def _tidy(frame):
    """The columns named as in the file (spaces and a byte-order mark stripped); the empty
    column a trailing comma makes dropped."""
    names = [" ".join(str(c).replace("\ufeff", "").split()) for c in frame.columns]
    frame.columns = names
    empty = [c for c in names if (not c or c.startswith("Unnamed:")) and frame[c].isna().all()]
    return frame.drop(columns=empty)


def _json_lines(path, text):
    """(the messages as a flat table, the distance unit per row) of a log of GSPro Open
    Connect messages, one JSON object per line."""
    records = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        try:
            record = json.loads(line)
        except json.JSONDecodeError as err:
            raise InputError(
                f"{path}: line {number}: not a JSON message ({err.msg}); expected one GSPro "
                "Open Connect message per line"
            ) from None
        if not isinstance(record, dict):
            raise InputError(f"{path}: line {number}: not a JSON object")
        records.append(record)
    frame = pd.json_normalize(records)
    units = frame["Units"].astype(str).str.strip().str.lower() if "Units" in frame else None
    if units is not None:
        bad = ~units.isin(["yards", "meters", "metres", "nan"])
        if bad.any():
            k = int(np.flatnonzero(bad.to_numpy())[0])
            raise InputError(
                f"{path}: message {k + 1}: Units {frame['Units'].iloc[k]!r}: expected Yards or "
                "Meters"
            )
        units = np.where(units.isin(["meters", "metres"]), "m", "yd")
    return frame, units


# --- the values ----------------------------------------------------------------------------

_DIRECTION = re.compile(
    r"^\s*(?P<pre>[LR])?\s*(?P<num>[+-]?(?:\d+(?:\.\d*)?|\.\d+))\s*(?P<post>[LR])?\s*$",
    re.IGNORECASE,
)


def numbers(series):
    """The numbers of a column, NaN where empty or unreadable; ``13.8 L``, ``L0.8`` negative,
    ``4.9 R``, ``R2.1`` positive (the non-breaking space read as a space)."""
    if pd.api.types.is_numeric_dtype(series.dtype) and not pd.api.types.is_bool_dtype(series):
        return np.array(series.to_numpy(dtype=float, na_value=np.nan))
    values = np.array(pd.to_numeric(series, errors="coerce"), dtype=float)
    text = series.astype("string").str.replace("\u00a0", " ", regex=False)
    left = np.isnan(values) & text.notna().to_numpy()
    if left.any():
        parts = text[left].str.extract(_DIRECTION)
        magnitude = np.abs(pd.to_numeric(parts["num"], errors="coerce").to_numpy(dtype=float))
        side = parts["pre"].fillna(parts["post"]).str.upper()
        sign = np.where(side == "L", -1.0, 1.0)
        plain = side.isna().to_numpy()
        raw = pd.to_numeric(parts["num"], errors="coerce").to_numpy(dtype=float)
        values[left] = np.where(plain, raw, sign * magnitude)
    return values


def _factor(path, column, kind, unit):
    """SI factor of ``unit`` (a unit of ``kind``); InputError naming the file and the column."""
    try:
        return parse_quantity(f"1 {unit}", kind)
    except UnitError:
        raise InputError(
            f"{path}: column {column!r}: unit {unit!r} is not a {kind} unit mcrun reads "
            f"({', '.join(KINDS[kind][1])})"
        ) from None


def _column(frame, names, wanted):
    """The first column of ``frame`` whose normalised name is among ``wanted``, or None."""
    for name in wanted:
        if name in names:
            return names[name]
    return None


def _club(frame, wanted):
    names = {formats.split_name(c)[0]: c for c in frame.columns}
    column = _column(frame, names, wanted)
    if column is None:
        return None, None
    club = frame[column].astype("string").str.strip().fillna("").to_numpy(dtype=object)
    return club, column


def _session(frame, source, name, detected, file_units, row_units):
    """A Session of an export's table: its quantities in SI by the format's columns."""
    fmt = formats.BY_NAME[name]
    names = {}
    for c in frame.columns:
        names.setdefault(formats.split_name(c)[0], c)
    values, sources, units = {}, {}, {}
    for quantity, wanted in fmt.columns.items():
        column = _column(frame, names, wanted)
        if column is None:
            continue
        kind = KIND[quantity]
        raw = numbers(frame[column])
        for sentinel in fmt.sentinels:
            raw[raw == sentinel] = np.nan
        unit = file_units.get(str(column)) or fmt.units.get(quantity) or fmt.units[kind]
        unit = _UNIT_ALIASES.get(unit.lower(), unit) or fmt.units[kind]
        if row_units is not None and kind == "length":
            factor = np.where(row_units == "m", 1.0, parse_quantity("1 yd", "length"))
        else:
            factor = _factor(source, column, kind, unit)
        units[quantity] = unit
        values[quantity] = raw * factor
        sources[quantity] = column
    missing = [q for q in ("ball_speed", "launch_angle") if q not in values]
    if "spin" not in values and not {"back_spin", "side_spin"} <= values.keys():
        missing.append("spin")
    if missing:
        found = ", ".join(map(str, frame.columns)) or "none"
        raise InputError(
            f"{source}: a {fmt.title} export needs a column for {', '.join(missing)} "
            f"({'; '.join(fmt.columns[q][0] for q in missing)}); found {found}"
        )
    _spin_from_components(values, sources, units)
    launch = {q: values[q] for q in LAUNCH if q in values}
    device = {q: values[q] for q in DEVICE if q in values}
    club, club_column = _club(frame, fmt.club)
    return Session(source, name, detected, frame, launch, device, sources, units, club, club_column)


def _spin_from_components(values, sources, units):
    """Total spin and axis from back and side spin where the file gives those and not the
    total (or sends the total as 0): total = hypot(back, side), axis = atan2(side, back),
    positive to the right."""
    back, side = values.pop("back_spin", None), values.pop("side_spin", None)
    if back is None or side is None:
        return
    total = np.hypot(back, side)
    axis = np.arctan2(side, back)
    spin = values.get("spin")
    derive = np.ones(len(total), dtype=bool) if spin is None else ~(spin > 0.0)
    derive &= np.isfinite(total)
    if spin is None:
        values["spin"] = total
        sources["spin"] = f"{sources['back_spin']}, {sources['side_spin']}"
        units["spin"] = units["back_spin"]
    else:
        values["spin"] = np.where(derive, total, spin)
    given = values.get("spin_axis")
    if given is None:
        values["spin_axis"] = axis
        sources["spin_axis"] = f"{sources['back_spin']}, {sources['side_spin']}"
        units["spin_axis"] = "rad"
    else:
        # Where the axis is missing, or sent as 0 beside a total sent as 0.
        fill = (~np.isfinite(given) | (derive & (given == 0.0))) & np.isfinite(axis)
        values["spin_axis"] = np.where(fill, axis, given)
