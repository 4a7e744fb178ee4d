"""Reading a launch-monitor session: the bytes of an export (or mcrun's own CSV or Parquet) into
the file's own table and its launches and the device's results in SI.

What real files hold and how it is read: a UTF-8 byte-order mark (dropped; also one encoded
twice, ``ï»¿``, as a file read as Latin-1 and saved as UTF-8 has it); UTF-16 with its mark;
bytes that are not UTF-8 (read as Latin-1); a ``sep=,`` first line (its separator used),
else the header's separator (a comma, or a semicolon or a tab as Excel saves in locales
whose decimal mark is a comma, where decimal commas are read: ``45,3``, ``13,8 L``);
Square Golf's ``Dates,...`` line and the blank line after it (skipped); a unit row under the
header (``[mph]``, ``[km/h]``, ``[m]``: it governs, column by column, a repeated name too);
units in names (``Ball Speed (mph)``); directions written ``13.8 L``, ``R2.1`` or
``4.9<non-breaking space>R`` (left negative); spin as back and side spin (total = hypot, axis
= atan2(side, back); also where the total and the axis are sent as 0); sentinels for "not
measured" (NaN); GSPro Open Connect messages as connectors log them (behind a log prefix,
other lines between, heartbeats skipped, Python's ``repr`` of a message too).

A row the reader cannot use keeps its place with its reason (``Session.reasons``): a launch
cell that is not a number or an L/R direction (``--``, ``T7091``, a second unit row, a
multi-line cell), a summary row (``Average``...), the last row cut short (fewer fields than the
rows before it and no line end), a logged message that is not JSON. Refused, one short line
naming the file (never its bytes): a blank file, a header only, binary bytes, a column given
twice in units that disagree.
"""

import ast
import codecs
import csv
import dataclasses
import json
import math
import re
from dataclasses import dataclass

import numpy as np
import pandas as pd

from mcrun.quantities import InputError
from mcrun.run.monitors import formats
from mcrun.run.monitors.native import (
    KIND,
    check_field_counts,
    check_file,
    device_columns,
    first_line,
    launch_columns,
    names_shown,
    read_launch_table,
)
from mcrun.units import KINDS, UnitError, parse_quantity, path_of, shown

LAUNCH = ("ball_speed", "launch_angle", "spin", "spin_axis", "azimuth")
DEVICE = ("carry", "total", "apex", "descent_angle", "carry_side", "total_side")
# The device's results a golf shot can have (SI): outside, a result is not measured (a carry
# of -1,234.5 yd made the model's bias +1,348 m); a carry or a total of 0 too (what devices
# write for a result they did not measure).
DEVICE_RANGES = {
    "carry": (0.0, 500.0),
    "total": (0.0, 600.0),
    "apex": (0.0, 150.0),
    "descent_angle": (0.0, math.pi / 2),
    "carry_side": (-300.0, 300.0),
    "total_side": (-300.0, 300.0),
}

_KNOWN = f"; or an export of a format mcrun knows: {formats.known()}"

# Unit spellings of exports that mcrun.units does not know.
_UNIT_ALIASES = {"yds": "yd", "[]": "", "deg/s": "", "-": ""}


@dataclass(frozen=True)
class Session:
    """A session read: ``frame`` (the file's own columns and rows), ``format`` (a name of
    ``formats.NAMES``) and ``detected`` (False when forced), ``launch`` and ``device``
    (quantity -> SI array per row, NaN where not measured; only the quantities the file
    gives), ``sources`` and ``units`` (quantity -> the file's column it came from and that
    column's unit), ``club`` (the club of each row, or None) and ``club_column``;
    ``reasons`` (per row, why the reader cannot use it, "" where it can; None: every row
    read) and ``notes`` (what the reader chose and a user should know, one line each)."""

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
    reasons: np.ndarray | None = None
    notes: tuple = ()

    @property
    def title(self):
        fmt = formats.BY_NAME.get(self.format)
        return fmt.title if fmt else "mcrun columns"


def read_session(path, format=None):
    """The ``Session`` of the file at ``path``; ``format`` forces one of ``formats.NAMES``
    (default: detected from the header). InputError, one line naming the file, otherwise."""
    path = path_of(path, "session", "a launch-monitor export's path")
    check_file(path)
    if format is not None and format not in formats.NAMES:
        raise InputError(f"{path}: unknown format {format!r}; known: {', '.join(formats.NAMES)}")
    source = str(path)
    if format == formats.NATIVE:
        return session_of_frame(read_launch_table(path), source, format)
    if path.suffix.lower() in (".parquet", ".pq"):
        return session_of_frame(read_launch_table(path), source, format)
    head, encoding, lead = _decode(path, _HEAD)
    if _is_messages(head, format):
        return _session_of_messages(path, format)
    # Lines ended by CR alone (Excel for Mac's "CSV (Macintosh)") read as by "\n", each one
    # character still: the same offsets into the file.
    newline = None if "\r" in head and "\n" not in head else ""
    if newline is None:
        head = head.replace("\r", "\n")
    header, units, sep, offset, skip = _split(path, head)
    names = [formats.split_name(c)[0] for c in header]
    fmt = formats.BY_NAME.get(format) if format else formats.detect(names)
    if fmt is None:
        if format is None and _is_messages(_decode(path)[0], format):  # a long log's first lines
            return _session_of_messages(path, format)
        # Neither an export's header nor mcrun's columns: say what was found and what is known.
        launch_columns(pd.DataFrame(columns=[c.strip() for c in header]), source, _KNOWN)
        # mcrun's own columns, as a spreadsheet saves them too (semicolons or tabs, "7,097").
        comma = _decimal_comma(head[offset:], sep)
        if sep == "," and not comma:
            frame = read_launch_table(path)
        else:
            frame = _tidy(
                _read_table(path, encoding, lead + offset, sep, skip, None, newline, text=True)
            )
        frame, notes = _in_locale(frame, comma, sep, path)
        session = session_of_frame(frame, source, None)
        return dataclasses.replace(session, notes=(*notes, *session.notes))
    comma = _decimal_comma(head[offset:], sep)
    text = sep != "," or comma  # (the cells as text, read as numbers by the file's locale)
    try:
        frame = _read_table(path, encoding, lead + offset, sep, skip, fmt, newline, text)
    except UnicodeDecodeError:  # UTF-8 at its start only: the file is Latin-1
        head, encoding, lead = _decode(path, _HEAD, "latin-1")
        frame = _read_table(path, encoding, lead + offset, sep, skip, fmt, newline, text)
    if len(frame) == 0:
        raise InputError(f"{path}: no shots: the file has a header only")
    frame, notes = _in_locale(frame, comma, sep, path)
    # Each column's unit by its place (a name given twice may have two units): the unit row,
    # else the unit in the name.
    file_units = {}
    for k, column in enumerate(frame.columns):
        unit = units[k].strip() if units is not None and k < len(units) else ""
        name = header[k] if k < len(header) else column
        file_units[_tidy_name(column)] = unit or formats.split_name(name)[1]
    frame = _tidy(frame)
    reasons = np.full(len(frame), "", dtype=object)
    cut = _cut_short(path, encoding, sep, len(header))
    if cut:
        reasons[-1] = cut
    return _session(frame, source, fmt.name, format is None, file_units, None, reasons, notes)


def _in_locale(frame, comma, sep, path):
    """(frame, notes): the frame's numbers read as the file's locale writes them (``comma``:
    with decimal commas, ``_decimal_comma``), and a note of the separator and the decimal
    mark where either is not the comma and the point of most exports."""
    # (Where commas separate the fields, a quoted "7,097" is a spreadsheet's grouped 7097.)
    frame = _plain_numbers(frame, comma, every=sep != "," or comma)
    if sep == "," and not comma:
        return frame, []
    mark = ("with a decimal comma (thousands grouped by points)" if comma else
            "with a decimal point (thousands grouped by commas)")  # fmt: skip
    shown_sep = "tabs" if sep == "\t" else repr(sep)
    return frame, [f"{path}: fields separated by {shown_sep}; numbers {mark}"]


def _session_of_messages(path, format):
    if format not in (None, "gspro"):
        raise InputError(f"{path}: JSON messages, not a {formats.BY_NAME[format].title} CSV")
    frame, units, reasons, notes = _messages(path, _decode(path)[0])
    return _session(frame, str(path), "gspro", format is None, {}, units, reasons, notes)


def _read_table(path, encoding, start, sep, skip, fmt, newline="", text=False):
    """The table of an export from the header on (``start`` characters into the file), read
    by pandas from the file itself (a copy of its text in memory would cost several times
    the file); the rows checked for extra fields first. ``newline``: ``open``'s (None for a
    file whose lines end with CR alone); ``text``: every cell as text (for ``_in_locale``;
    pandas would take ``7.097`` for 7.097 where the decimal mark is a comma)."""
    with open(path, encoding=encoding, newline=newline) as file:
        file.read(start)
        lines = enumerate(file)
        check_field_counts(
            path, (text for k, text in lines if text.strip() and (k != 1 or not skip)), sep
        )
    with open(path, encoding=encoding, newline=newline) as file:
        file.read(start)
        try:
            return pd.read_csv(
                file,
                sep=sep,
                skipinitialspace=True,
                index_col=False,
                skiprows=skip,
                low_memory=False,
                dtype=str if text else None,
            )
        except UnicodeDecodeError:
            raise
        except (pd.errors.ParserError, ValueError, csv.Error, OverflowError) as err:
            raise InputError(
                f"{path}: cannot read it as a {fmt.title if fmt else 'mcrun columns'} export: "
                f"{first_line(err)}"
            ) from None


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
    notes = []
    device = _possible(device, sources, units, source, frame, notes)
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
        notes=tuple(notes),
    )


# --- the text ------------------------------------------------------------------------------


# The byte-order mark as read, and as written again by an app that read it as Latin-1 (once,
# twice).
_MARKS = ("\ufeff", "\u00ef\u00bb\u00bf", "\u00c3\u00af\u00c2\u00bb\u00c2\u00bf")
_SAMPLE = 65536  # characters looked at for binary bytes
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")


_HEAD = 1 << 20  # bytes of a CSV export read to find its encoding, header and unit row


def _decode(path, most=None, encoding=None):
    """(text, encoding, marks) of the file, or of its first ``most`` bytes: UTF-16 with its
    byte-order mark, UTF-8, else Latin-1 (or ``encoding``); the byte-order marks at its start
    dropped from the text (``drop_marks``), ``marks`` their length in characters. InputError
    for an empty file or binary bytes, one short line."""
    with open(path, "rb") as file:
        data = file.read() if most is None else file.read(most)
        more = most is not None and file.read(1) != b""
    if not data.strip() and not more:
        raise InputError(f"{path}: no shots: the file is empty")
    if encoding is None and data.startswith((b"\xff\xfe", b"\xfe\xff")):
        encoding = "utf-16"
    candidates = [encoding] if encoding else ["utf-8", "latin-1"]
    for encoding in candidates:
        try:
            text = codecs.getincrementaldecoder(encoding)().decode(data, final=not more)
            break
        except UnicodeDecodeError:
            if encoding != "utf-8":
                raise InputError(f"{path}: not a text file: broken {encoding.upper()}") from None
    stripped = drop_marks(text)
    sample = stripped[:_SAMPLE]
    control = len(_CONTROL.findall(sample))
    if "\x00" in sample or control > max(8, len(sample) // 100):
        raise InputError(
            f"{path}: not a text file ({control} control bytes in its first {len(sample)} "
            "characters); expected a launch monitor's CSV export, its JSON messages, or a "
            "Parquet file"
        )
    return stripped, encoding, len(text) - len(stripped)


def drop_marks(text):
    """``text`` without the byte-order marks at its start (``_MARKS``)."""
    while True:
        for mark in _MARKS:
            if text.startswith(mark):
                text = text[len(mark) :]
                break
        else:
            return text


def _fields(line, sep, path=""):
    try:
        return next(csv.reader([line], delimiter=sep, skipinitialspace=True), [])
    except csv.Error as err:  # a field over the csv module's limit
        raise InputError(f"{path}: cannot read it as CSV: {first_line(err)}") from None


_TAIL = 65536  # bytes read at a file's end to see whether its last row is whole


def _cut_short(path, encoding, sep, width):
    """The reason the last row of the export at ``path`` is not a shot when the file ends
    inside it: no line end after it and fewer fields than the header and than the row before
    (an export cut mid-row: its last value may be cut mid-number); else ""."""
    with open(path, "rb") as file:
        size = file.seek(0, 2)
        if encoding == "utf-16" or size <= _TAIL:
            file.seek(0)
        else:
            file.seek(size - _TAIL)
        data = file.read()
    text = data.decode(encoding, errors="replace")
    if text.endswith(("\n", "\r")):
        return ""
    lines = [line for line in text.splitlines()[-2:] if line.strip()]
    if len(lines) < 2:
        return ""
    last = len(_fields(lines[-1], sep, path))
    before = len(_fields(lines[-2], sep, path))
    if last < width and last < before:
        return f"{_NOT_A_SHOT[1]}{last} of {width} fields, no line end)"
    return ""


def _split(path, text):
    """(header fields, unit-row units or None, separator, where the header starts in
    ``text``, the rows pandas skips after the header (the unit row)) of a CSV export."""
    sep, given = ",", False
    start = 0
    seen = 0
    header = None
    while start < len(text):
        end = text.find("\n", start)
        end = len(text) if end < 0 else end + 1
        # (After a sep= line, byte-order marks are not the file's first bytes: dropped here.)
        line = drop_marks(text[start:end].strip("\r\n"))
        if not line.strip() or line.startswith("#"):
            start = end
            continue
        if seen == 0 and line.lower().startswith("sep=") and len(line) >= 5:
            sep, given = line[4], True
            seen += 1
            start = end
            continue
        if seen == int(given) and line.startswith(("Dates,", "Dates;", "Dates\t")):  # Square
            seen += 1
            start = end
            continue
        if not given:  # no sep= line: the separator the header is written with
            sep = separator_of(line)
        header = _fields(line, sep, path)
        break
    if header is None:
        raise InputError(f"{path}: no shots: the file is empty")
    body = text[start : start + _SAMPLE]
    second_end = body.find("\n", body.find("\n") + 1)
    lines = body[: second_end if second_end >= 0 else len(body)].splitlines()
    units = None
    skip = None
    if len(lines) > 1:
        row = _fields(lines[1], sep, path)
        filled = [f.strip() for f in row if f.strip()]
        if filled and all(f.startswith("[") and f.endswith("]") for f in filled):
            units = [f.strip().strip("[]").strip() for f in row]
            skip = [1]
    return header, units, sep, start, skip


# A comma; a semicolon, as Excel writes a CSV where the decimal mark is a comma; a tab, as in
# Excel's "Unicode Text" (UTF-16).
_SEPARATORS = (",", ";", "\t")
# A cell that is a number (or an L/R direction) with decimals after a comma or a point, and
# one whose mark may as well group thousands (``7,097``: 7.097 or 7097).
_SIDE = r"\s*[LR]?\s*"
_COMMA_NUMBER = re.compile(rf"^{_SIDE}[+-]?\d+,\d+{_SIDE}$", re.IGNORECASE)
_POINT_NUMBER = re.compile(rf"^{_SIDE}[+-]?\d+\.\d+{_SIDE}$", re.IGNORECASE)
# (A group of thousands never starts with 0: ``0,025`` is a decimal.)
_GROUPED = re.compile(rf"^{_SIDE}[+-]?[1-9]\d{{0,2}}[.,]\d{{3}}{_SIDE}$", re.IGNORECASE)
# A number as a file of decimal commas writes it (thousands grouped by points or not), and one
# with thousands grouped by commas as a file of decimal points writes it.
_DECIMAL_COMMA = re.compile(
    rf"^({_SIDE}[+-]?)([1-9]\d{{0,2}}(?:\.\d{{3}})+|\d+)(?:,(\d+))?({_SIDE})$", re.IGNORECASE
)
_THOUSANDS_COMMA = re.compile(
    rf"^({_SIDE}[+-]?)([1-9]\d{{0,2}}(?:,\d{{3}})+)((?:\.\d+)?{_SIDE})$", re.IGNORECASE
)


def separator_of(header):
    """The separator of a header line: of ``_SEPARATORS``, the one that splits it into the
    most fields (a comma on a tie)."""
    counts = [len(_fields(header, sep)) for sep in _SEPARATORS]
    return _SEPARATORS[counts.index(max(counts))]


def _decimal_comma(body, sep):
    """Whether the rows in ``body`` (text after the header) write numbers with a decimal
    comma: where more cells are numbers with a comma (``45,3``, ``13,8 L``; where commas
    separate the fields, quoted, as Google Sheets writes them in such a locale) than with a
    point (a date ``01.05.2024`` is neither), and on a tie where semicolons separate them
    (Excel's separator where the decimal mark is a comma). A mark before three digits
    (``7,097``, ``7.097``; not ``0,025``) may group thousands: it counts for neither."""
    comma = point = 0
    for fields in csv.reader(body.splitlines()[:200], delimiter=sep):
        for cell in fields:
            if _GROUPED.match(cell):
                continue
            comma += _COMMA_NUMBER.match(cell) is not None
            point += _POINT_NUMBER.match(cell) is not None
    return comma > point or (comma == point and sep == ";")


def _plain_numbers(frame, decimal_comma, every=True):
    """The frame's text cells that are numbers written as the file's locale writes them, in
    Python's way: with decimal commas, ``45,3`` as 45.3 and ``7.097`` (thousands grouped by
    points) as 7097; with decimal points, ``7,097`` as 7097. A column whose every cell is then
    a number is a column of numbers, as the same export with commas between its fields
    reads. Not ``every`` column: only those with a comma in a cell (a comma-separated file's
    text columns are left alone)."""
    pattern = _DECIMAL_COMMA if decimal_comma else _THOUSANDS_COMMA

    def plain(value):
        if not isinstance(value, str):
            return value
        found = pattern.match(value)
        if found is None:
            return value
        if decimal_comma:
            side, whole, decimals, end = found.groups()
            return f"{side}{whole.replace('.', '')}{'.' + decimals if decimals else ''}{end}"
        side, whole, end = found.groups()
        return f"{side}{whole.replace(',', '')}{end}"

    for column in frame.columns:
        series = frame[column]
        if series.dtype == object or pd.api.types.is_string_dtype(series.dtype):
            if not every and not series.astype("string").str.contains(",", regex=False).any():
                continue
            series = series.map(plain)
            numbers = pd.to_numeric(series, errors="coerce")
            frame[column] = numbers if numbers.notna().sum() == series.notna().sum() else series
    return frame


def _tidy_name(column):
    return " ".join(drop_marks(str(column)).replace("\ufeff", "").split())


def _tidy(frame):
    """The columns named as in the file (spaces and a byte-order mark stripped); the empty
    column a trailing comma makes dropped."""
    names = [_tidy_name(c) for c in frame.columns]
    frame.columns = names
    empty = [c for c in names if (not c or c.startswith("Unnamed:")) and frame[c].isna().all()]
    return frame.drop(columns=empty)


def _is_messages(text, format):
    """Whether ``text`` holds GSPro Open Connect messages: forced, JSON from its start, or the
    messages' ``BallData`` in a log that is no CSV export."""
    if format == "gspro" or text.lstrip().startswith("{"):
        return True
    return format is None and ('"BallData"' in text or "'BallData'" in text)


_DECODER = json.JSONDecoder()
# The ball data's keys as the API spells them; connectors vary the case (``Backspin``).
_BALL_KEYS = {
    k.lower(): k
    for k in ("Speed", "SpinAxis", "TotalSpin", "BackSpin", "SideSpin", "HLA", "VLA")
    + ("CarryDistance",)
}
_LITERAL_MOST = 100_000  # characters of a logged Python dict read back at most


def _ball_data(record):
    """The ball data of a message (keys compared in lower case), or None: a heartbeat, a
    reply, a message without ball data."""
    keys = {str(k).lower(): k for k in record}
    ball = record.get(keys.get("balldata"))
    options = record.get(keys.get("shotdataoptions"))
    if isinstance(options, dict):
        flags = {str(k).lower(): v for k, v in options.items()}
        if flags.get("isheartbeat") is True or flags.get("containsballdata") is False:
            return None
    return ball if isinstance(ball, dict) and ball else None


def _python_literal(text, start, end):
    """The dict a Python logger wrote with ``repr`` (single quotes, True/False) at
    ``text[start:end]``, or None."""
    chunk = text[start:end].rstrip()
    stop = chunk.rfind("}")
    if stop < 0 or stop > _LITERAL_MOST or "BallData" not in chunk:
        return None
    try:
        value = ast.literal_eval(chunk[: stop + 1])
    except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError):
        return None
    return value if isinstance(value, dict) else None


def _messages(path, text):
    """(the shot messages as a flat table, the distance unit per row, the reason per row,
    notes) of GSPro Open Connect messages: one JSON object per line, or a connector's log of
    them (each behind a prefix, other lines between, messages spread over lines). Messages
    without ball data (heartbeats, replies) are skipped; a message that starts a line but is
    not JSON keeps a row with its reason."""
    records, reasons = [], []
    skipped = 0
    pos, line, counted = 0, 1, 0
    while True:
        k = text.find("{", pos)
        if k < 0:
            break
        line += text.count("\n", counted, k)
        counted = k
        line_start = text.rfind("\n", 0, k) + 1
        line_end = text.find("\n", k)
        line_end = len(text) if line_end < 0 else line_end
        try:
            record, end = _DECODER.raw_decode(text, k)
        except (json.JSONDecodeError, RecursionError) as err:
            record, end = _python_literal(text, k, line_end), line_end
            if record is None:
                starts_line = not text[line_start:k].strip()
                if starts_line or "BallData" in text[k:line_end]:
                    message = getattr(err, "msg", "nested too deep")
                    records.append({})
                    reasons.append(f"line {line}: not a JSON message ({message})")
                pos = line_end + 1
                continue
        pos = end
        if not isinstance(record, dict):
            continue
        ball = _ball_data(record)
        if ball is None:
            skipped += 1
            continue
        ball = {_BALL_KEYS.get(str(k).lower(), k): v for k, v in ball.items()}
        record = dict(
            ("BallData", ball) if str(k).lower() == "balldata" else (k, v)
            for k, v in record.items()
        )
        records.append(record)
        reasons.append("")
    if not any(reason == "" for reason in reasons):
        if reasons:
            raise InputError(f"{path}: no shots: {reasons[0]}")
        raise InputError(
            f"{path}: no shots: no GSPro Open Connect message with ball data "
            f"({skipped} without: heartbeats, replies)"
        )
    frame = _one_type_a_column(pd.json_normalize(records))
    units = None
    if "Units" in frame:
        units = frame["Units"].fillna("").astype(str).str.strip().str.lower()
        bad = ~units.isin(["yards", "meters", "metres", "", "nan"])
        if bad.any():
            k = int(np.flatnonzero(bad.to_numpy())[0])
            raise InputError(
                f"{path}: message {k + 1}: Units {shown(frame['Units'].iloc[k], 30)}: "
                "expected Yards or Meters"
            )
        units = np.where(units.isin(["meters", "metres"]), "m", "yd")
    notes = ()
    if skipped:
        notes = (f"{path}: {skipped} message(s) without ball data skipped (heartbeats, replies)",)
    return frame, units, np.array(reasons, dtype=object), notes


def _one_type_a_column(frame):
    """``frame`` with each column of Python objects that are not all text (a connector writing
    ``"n/a"`` or ``true`` in one message and a number in the next, an integer beyond 64 bits, a
    list) as text, its empty cells left empty: read as numbers, the text is what it is (a
    shot's unreadable value), and the table is one Parquet can hold."""
    for name in frame.columns:
        column = frame[name]
        if column.dtype != object:
            continue
        filled = column.notna()
        if not all(isinstance(v, str) for v in column[filled]):
            frame[name] = column.where(~filled, column[filled].map(str))
    return frame


# --- the values ----------------------------------------------------------------------------

_DIRECTION = re.compile(
    r"^\s*(?P<pre>[LR])?\s*(?P<num>[+-]?(?:\d+(?:\.\d*)?|\.\d+))\s*(?P<post>[LR])?\s*$",
    re.IGNORECASE,
)


_SUMMARY = {
    "average", "avg", "avg.", "mean", "median", "std. dev.", "std. dev", "std dev", "stdev",
    "std", "standard deviation", "sd", "min", "min.", "minimum", "max", "max.", "maximum",
    "total", "totals", "sum", "count", "consistency",
}  # fmt: skip
"""The first cell or the club of an export's summary rows (its footer): not shots."""

_DUPLICATE_RTOL = 0.02  # two columns of one quantity agree when their SI values do to 2 %


def numbers(series):
    """The numbers of a column, NaN where empty or unreadable; ``13.8 L``, ``L0.8`` negative,
    ``4.9 R``, ``R2.1`` positive (the non-breaking space read as a space)."""
    return _numbers(series)[0]


def _float_or_nan(value):
    """``value`` as a float (inf beyond a float's range), NaN where it is not a number."""
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf
    except (TypeError, ValueError):
        return math.nan


def _numbers(series):
    """(numbers, unreadable) of a column: ``numbers``, and where a cell holds text that is
    neither a number nor an L/R direction (``--``, ``T7091``, ``[mph]``)."""
    n = len(series)
    if pd.api.types.is_numeric_dtype(series.dtype) and not pd.api.types.is_bool_dtype(series):
        return np.array(series.to_numpy(dtype=float, na_value=np.nan)), np.zeros(n, dtype=bool)
    try:
        values = np.array(pd.to_numeric(series, errors="coerce"), dtype=float)
    except OverflowError:  # an integer beyond a float's range (a JSON message's 1e400 written out)
        values = np.array([_float_or_nan(v) for v in series], dtype=float)
    text = series.astype("string").str.replace("\u00a0", " ", regex=False).str.strip()
    filled = (text.fillna("") != "").to_numpy(dtype=bool)
    left = np.isnan(values) & filled
    if left.any():
        parts = text[left].str.extract(_DIRECTION)
        raw = pd.to_numeric(parts["num"], errors="coerce").to_numpy(dtype=float)
        side = parts["pre"].fillna(parts["post"]).fillna("").str.upper().to_numpy(dtype=object)
        sign = np.where(side == "L", -1.0, 1.0)
        values[left] = np.where(side == "", raw, sign * np.abs(raw))
    return values, np.isnan(values) & filled


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


def _column_groups(frame):
    """{normalised name: [columns]} of a table, a name given twice together (pandas names the
    second ``Ball Speed.1``)."""
    present = {str(c) for c in frame.columns}
    groups = {}
    for column in frame.columns:
        name = str(column)
        base, dot, number = name.rpartition(".")
        if dot and number.isdigit() and base in present:
            name = base
        groups.setdefault(formats.split_name(name)[0], []).append(column)
    return groups


def _choose(source, quantity, candidates, default, notes):
    """The (column, unit, SI values, unreadable) read for ``quantity`` among the columns that
    give it: the one in the app's default unit, else the first, its empty cells filled from
    the others; InputError when two disagree (a unit written wrong or missing), a note that
    the choice was made otherwise."""
    if len(candidates) == 1:
        return candidates[0]
    chosen = next((c for c in candidates if c[1].lower() == default.lower()), candidates[0])
    for other in candidates:
        if other is chosen:
            continue
        both = np.isfinite(chosen[2]) & np.isfinite(other[2])
        close = np.isclose(chosen[2][both], other[2][both], rtol=_DUPLICATE_RTOL, atol=1e-3)
        if not close.all():
            row = int(np.flatnonzero(both)[np.flatnonzero(~close)[0]])
            raise InputError(
                f"{source}: columns {chosen[0]!r} ({chosen[1]}) and {other[0]!r} "
                f"({other[1]}) both give {quantity} and disagree (row {row + 1}: "
                f"{chosen[2][row]:.6g} and {other[2][row]:.6g} in SI): a unit is missing or "
                "wrong; keep one column"
            )
    others = ", ".join(f"{c[0]!r} ({c[1]})" for c in candidates if c is not chosen)
    notes.append(
        f"{source}: {quantity} is in {len(candidates)} columns that agree; read "
        f"{chosen[0]!r} ({chosen[1]}), and {others} where it is empty"
    )
    column, unit, si, bad = chosen
    si = si.copy()
    for other in candidates:
        fill = ~np.isfinite(si) & np.isfinite(other[2])
        si[fill] = other[2][fill]
        bad = bad & ~fill
    return column, unit, si, bad


def _possible(device, sources, units, source, frame, notes):
    """The device's results with those no golf shot can have (``DEVICE_RANGES``) read as not
    measured, each column's count and first row in a note."""
    for quantity, si in device.items():
        lo, hi = DEVICE_RANGES[quantity]
        above = si > lo if quantity in ("carry", "total") else si >= lo  # (0: not measured)
        impossible = ~np.isnan(si) & ~(above & (si <= hi))  # (inf too)
        if impossible.any():
            row = int(np.flatnonzero(impossible)[0])
            column = sources[quantity]
            notes.append(
                f"{source}: {int(impossible.sum())} value(s) of {column} no shot can have "
                f"(row {row + 1}: {shown(str(frame[column].iloc[row]), 30)} {units[quantity]}), "
                "read as not measured"
            )
            device[quantity] = np.where(impossible, np.nan, si)
    return device


def _session(frame, source, name, detected, file_units, row_units, reasons=None, notes=()):
    """A Session of an export's table: its quantities in SI by the format's columns."""
    fmt = formats.BY_NAME[name]
    groups = _column_groups(frame)
    notes = list(notes)
    n = len(frame)
    reasons = np.full(n, "", dtype=object) if reasons is None else reasons
    values, sources, units, unreadable = {}, {}, {}, {}
    for quantity, wanted in fmt.columns.items():
        columns = next((groups[w] for w in wanted if w in groups), None)
        if columns is None:
            continue
        kind = KIND[quantity]
        default = fmt.units.get(quantity) or fmt.units[kind]
        candidates = []
        for column in columns:
            raw, bad = _numbers(frame[column])
            for sentinel in fmt.sentinels:
                raw[raw == sentinel] = np.nan
            unit = file_units.get(str(column)) or default
            unit = _UNIT_ALIASES.get(unit.lower(), unit) or fmt.units[kind]
            if row_units is not None and kind == "length":
                factor = np.where(row_units == "m", 1.0, parse_quantity("1 yd", "length"))
            else:
                factor = _factor(source, column, kind, unit)
            candidates.append((column, unit, raw * factor, bad))
        column, unit, si, bad = _choose(source, quantity, candidates, default, notes)
        units[quantity] = unit
        values[quantity] = si
        sources[quantity] = column
        unreadable[quantity] = bad
    missing = [q for q in ("ball_speed", "launch_angle") if q not in values]
    if "spin" not in values and not {"back_spin", "side_spin"} <= values.keys():
        missing.append("spin")
    if missing:
        raise InputError(
            f"{source}: a {fmt.title} export needs a column for {', '.join(missing)} "
            f"({'; '.join(fmt.columns[q][0] for q in missing)}); found "
            f"{names_shown(frame.columns)}"
        )
    read_from = {q: [q] for q in LAUNCH}
    for q in ("spin", "spin_axis"):
        read_from[q] += ["back_spin", "side_spin"]
    sides = {q: sources[q] for q in ("back_spin", "side_spin") if q in sources}
    _spin_from_components(values, sources, units)
    launch = {q: values[q] for q in LAUNCH if q in values}
    device = _possible(
        {q: values[q] for q in DEVICE if q in values}, sources, units, source, frame, notes
    )
    for quantity, si in launch.items():
        for part in read_from[quantity]:
            if part not in unreadable:
                continue
            column = sources.get(part) if part in sources else sides.get(part)
            rows = np.flatnonzero(unreadable[part] & ~np.isfinite(si) & (reasons == ""))
            for row in rows:
                cell = shown(str(frame[column].iloc[row]), 30)
                reasons[row] = f"{column}: {cell} is not a number"
    _mark_summary_rows(frame, fmt, reasons)
    club, club_column = _club(frame, fmt.club)
    return Session(
        source,
        name,
        detected,
        frame,
        launch,
        device,
        sources,
        units,
        club,
        club_column,
        reasons,
        tuple(notes),
    )


# The reasons of the rows that are not shots at all (an export's summary rows, a last row the
# file ends inside), as against shots with a cell that cannot be read.
_NOT_A_SHOT = ("a summary row (", "the last row is cut short (")


def not_a_shot(reasons):
    """Which rows of ``reasons`` (``Session.reasons``) are not shots at all: an export's summary
    rows and a last row cut short. A launch file skips them; it refuses a shot it cannot read."""
    if reasons is None:
        return None
    return np.array([str(r).startswith(_NOT_A_SHOT) for r in reasons], dtype=bool)


def _mark_summary_rows(frame, fmt, reasons):
    """Give the summary rows of an export (``Average``, ``Std. Dev.``... in its first column or
    its club column) their reason: they are not shots."""
    if len(frame.columns) == 0:
        return
    groups = _column_groups(frame)
    columns = [frame.columns[0]]
    columns += [groups[w][0] for w in fmt.club if w in groups]
    for column in dict.fromkeys(columns):
        cells = frame[column]
        if pd.api.types.is_numeric_dtype(cells.dtype):
            continue
        text = cells.astype("string").str.strip().str.lower()
        summary = text.isin(_SUMMARY).fillna(False).to_numpy(dtype=bool) & (reasons == "")
        for row in np.flatnonzero(summary):
            reasons[row] = f"{_NOT_A_SHOT[0]}{shown(str(cells.iloc[row]), 30)}), not a shot"


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
