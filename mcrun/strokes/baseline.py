"""Expected strokes to hole out by lie and distance: the PGA Tour baseline of Broadie (2012) or a
table of the user's, interpolated linearly in distance.

The package's table, ``mcrun/data/pga_tour_baseline_broadie2012.csv``, is the full table of
M. Broadie, "Assessing Golfer Performance on the PGA TOUR", Interfaces 42(2), 146-165 (2012),
Appendix A, Table 9. A baseline CSV has the columns ``lie,distance_yd,distance_ft,
expected_strokes``, one of the two distances per row, ``#`` comment lines anywhere, and at least
two rows for every lie of ``LIES``.

Where the table has no row (docs/strokes.md, "The baseline"):

- between rows: linear in distance; above a lie's last row: the line through its last two rows;
- off the green, below a lie's first row: the putt from the same distance plus the lie's step
  over the putt at that first row (10 yd: fairway +0.20, rough +0.36, sand +0.45, recovery +1.47
  in the Tour table); the tee below its first row (100 yd) is the fairway;
- on the green: 0 within the hole's radius (the ball is in), 1.0 from there to 1 ft, linear from
  1 ft to the first row (3 ft: 1.04).

Distances are in metres inside (``expected(lie, distance_m)``); yards and feet only in the CSV.
"""

import csv
import math
import os
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from mcrun.errors import InputError
from mcrun.units import KINDS, is_number, shown

__all__ = [
    "DEFAULT_BASELINE_PATH",
    "FOOT_M",
    "HOLE_RADIUS_M",
    "LIES",
    "YARD_M",
    "Baseline",
    "BaselineError",
    "load_baseline",
    "tour_baseline",
]

LIES = ("tee", "fairway", "rough", "sand", "recovery", "green")
OFF_GREEN_LIES = LIES[:5]
COLUMNS = ("lie", "distance_yd", "distance_ft", "expected_strokes")

YARD_M = KINDS["length"][1]["yd"][0]
FOOT_M = KINDS["length"][1]["ft"][0]
# The hole is 4.25 in (108 mm) across (Rules of Golf, Definitions, "Hole"): a ball at rest with
# its centre within the radius is in.
HOLE_RADIUS_M = 4.25 * 0.0254 / 2.0
# Tour players hole putts of about a foot every time: 1 stroke from the hole's edge to 1 ft.
TAP_IN_M = FOOT_M

DEFAULT_BASELINE_PATH = resources.files("mcrun") / "data" / "pga_tour_baseline_broadie2012.csv"
MAX_STROKES = 20.0


class BaselineError(InputError):
    """A baseline table cannot be used; the message is one line meant for the user."""


class _ReadOnlyRows(dict):
    """A lie's rows that cannot be changed: the Tour's baseline is one object for the whole
    process (``tour_baseline``), and a change to its rows changed every later score. Pickled
    (a Dask worker is sent one), it is made read-only again (``_read_only``)."""

    def _refuse(self, *args, **kwargs):
        raise TypeError("a Baseline's rows cannot be changed: make another Baseline")

    __setitem__ = __delitem__ = update = pop = popitem = clear = setdefault = _refuse

    def __reduce__(self):
        return (_read_only, (dict(self),))


def _read_only(rows):
    """``rows`` (lie -> values) as read-only arrays of floats in a ``_ReadOnlyRows``."""
    frozen = {}
    for lie, values in rows.items():
        array = np.array(values, dtype=float)  # (a copy: the caller's stays theirs)
        array.setflags(write=False)
        frozen[lie] = array
    return _ReadOnlyRows(frozen)


@dataclass(frozen=True)
class Baseline:
    """Expected strokes to hole out: per lie, the rows' distances (m, increasing) and values,
    read-only."""

    source: str
    distance_m: dict  # lie -> np.ndarray of the rows' distances (m)
    strokes: dict  # lie -> np.ndarray of the rows' expected strokes

    def __post_init__(self):
        object.__setattr__(self, "distance_m", _read_only(self.distance_m))
        object.__setattr__(self, "strokes", _read_only(self.strokes))

    def expected(self, lie, distance_m):
        """Expected strokes to hole out from ``distance_m`` (m, to the hole) in ``lie`` (one of
        ``LIES``, or an array of them, as ``distance_m``). Vectorised; NaN where the distance
        is NaN; ValueError for a distance that is negative, infinite or not a number."""
        d = _distances(distance_m)
        lies = np.asarray(lie)
        if lies.ndim == 0:
            return self._one(str(lies), d)
        lies, d = np.broadcast_arrays(lies, d)
        out = np.full(d.shape, np.nan)
        left = np.ones(d.shape, dtype=bool)
        for name in LIES:
            chosen = lies == name
            if chosen.any():
                out[chosen] = self._one(name, d[chosen])
                left &= ~chosen
        if left.any():
            self._one(str(lies[left][0]), d[left][:1])  # (the message of an unknown lie)
        return out

    def expected_by_code(self, codes, distance_m):
        """``expected`` with the lies given by their index in ``LIES`` (an int array; ValueError
        for another)."""
        d = _distances(distance_m)
        codes, d = np.broadcast_arrays(_lie_codes(codes), d)
        out = np.full(d.shape, np.nan)
        for k, name in enumerate(LIES):
            chosen = codes == k
            if chosen.any():
                out[chosen] = self._one(name, d[chosen])
        return out

    def _one(self, lie, d):
        if lie not in LIES:
            raise ValueError(f"lie {lie!r}: allowed: {', '.join(LIES)}")
        if lie == "green":
            return self._green(d)
        rows_d, rows_v = self.distance_m[lie], self.strokes[lie]
        below = d < rows_d[0]
        if not below.any():  # (the rows' values alone: the same numbers, half the work)
            return _linear(rows_d, rows_v, d)
        out = _linear(rows_d, rows_v, np.where(below, rows_d[0], d))
        if lie == "tee":
            return np.where(below, self._one("fairway", d), out)
        step = rows_v[0] - self._green(rows_d[0])
        # A ball off the green takes a stroke at least: its putt never counts less than 1.
        return np.where(below, np.maximum(self._green(d), 1.0) + step, out)

    def _green(self, d):
        rows_d, rows_v = self.distance_m["green"], self.strokes["green"]
        if rows_d[0] > TAP_IN_M:
            rows_d, rows_v = np.r_[TAP_IN_M, rows_d], np.r_[1.0, rows_v]
        d = np.asarray(d, dtype=float)
        short, holed = d < rows_d[0], d <= HOLE_RADIUS_M
        if not (short.any() or holed.any()):  # (the same numbers without the np.where)
            return _linear(rows_d, rows_v, d)
        out = _linear(rows_d, rows_v, np.maximum(d, rows_d[0]))
        out = np.where(short, np.minimum(rows_v[0], 1.0), out)
        return np.where(holed, 0.0, out)


def _distances(distance_m):
    """``distance_m`` as a float array; ValueError naming the first that is not a number, 0 or
    more (m; NaN passes, valued NaN)."""
    given = np.asarray(distance_m)
    if given.dtype.kind not in "iuf" and not (given.dtype == object and all(
            is_number(v) or v is None for v in given.flat)):  # fmt: skip
        # (text "100" was 100 m, True 1 m, a date 72.7 strokes)
        raise ValueError(f"distance_m {shown(distance_m)}: allowed: numbers (m)")
    try:
        d = np.asarray(distance_m, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"distance_m {shown(distance_m)}: allowed: numbers (m)") from None
    bad = (d < 0.0) | np.isinf(d)
    if bad.any():
        raise ValueError(f"distance_m {d[bad].flat[0]:g}: allowed: 0 or more, finite (m)")
    return d


def _lie_codes(codes):
    """``codes`` as an array of indices in ``LIES``; ValueError naming the first that is not."""
    codes = np.asarray(codes)
    if codes.dtype.kind not in "iu":
        raise ValueError(f"lie codes of type {codes.dtype}: allowed: integers (indices in LIES)")
    if codes.size and not 0 <= codes.min() <= codes.max() < len(LIES):
        bad = codes[(codes < 0) | (codes >= len(LIES))].flat[0]
        raise ValueError(f"lie code {bad}: allowed: 0 to {len(LIES) - 1} (an index in LIES)")
    return codes


def _linear(x, y, at):
    """Linear interpolation through (x, y), extended above the last point by the line through
    the last two; ``at`` at or above x[0]."""
    out = np.interp(at, x, y)
    above = at > x[-1]
    if not above.any():
        return np.asarray(out)
    slope = (y[-1] - y[-2]) / (x[-1] - x[-2])
    return np.where(above, y[-1] + slope * (at - x[-1]), out)


def _number(text, where, column, allowed):
    try:
        value = float(text)
    except ValueError:
        raise BaselineError(
            f"{where}: {column} {text!r} is not a number; allowed: {allowed}"
        ) from None
    if not math.isfinite(value):
        raise BaselineError(f"{where}: {column} {text!r} is not finite; allowed: {allowed}")
    return value


def load_baseline(path):
    """The Baseline of the CSV at ``path`` (columns ``lie,distance_yd,distance_ft,
    expected_strokes``; docs/strokes.md). Raises BaselineError, one line naming the file, the
    line and column, and what is allowed."""
    name = str(path)
    # A str or Path, or an importlib.resources Traversable (the package's table).
    if not (isinstance(path, str | os.PathLike) or hasattr(path, "read_text")):
        raise BaselineError(f"baseline {shown(path)}: allowed: a CSV file's path")
    source = Path(path) if isinstance(path, str | os.PathLike) else path
    try:
        text = source.read_text(encoding="utf-8-sig")  # (a BOM, as Excel writes)
    except (OSError, UnicodeDecodeError) as error:
        raise BaselineError(
            f"{name}: cannot be read as a UTF-8 CSV ({error.__class__.__name__})"
        ) from None
    lines = [(k, line) for k, line in enumerate(text.splitlines(), 1)]
    lines = [(k, line) for k, line in lines if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise BaselineError(f"{name}: no header; allowed columns: {', '.join(COLUMNS)}")
    reader = csv.reader([line for _, line in lines])
    header = [h.strip() for h in next(reader)]
    if sorted(header) != sorted(COLUMNS):
        unknown = [h for h in header if h not in COLUMNS]
        twice = [c for c in COLUMNS if header.count(c) > 1]
        missing = [c for c in COLUMNS if c not in header]
        what = (
            f"unknown column {unknown[0]!r}"
            if unknown
            else f"column {twice[0]!r} twice"
            if twice
            else f"no column {missing[0]!r}"
        )
        raise BaselineError(
            f"{name}: line {lines[0][0]}: {what}; the columns are {', '.join(COLUMNS)}"
        )
    rows = {lie: [] for lie in LIES}
    for (k, _), fields in zip(lines[1:], reader, strict=True):
        where = f"{name}: line {k}"
        if len(fields) != len(header):
            raise BaselineError(f"{where}: {len(fields)} fields; allowed: {len(header)}")
        row = dict(zip(header, (f.strip() for f in fields), strict=True))
        lie = row["lie"]
        if lie not in LIES:
            raise BaselineError(f"{where}: lie {lie!r} is not a lie; allowed: {', '.join(LIES)}")
        if bool(row["distance_yd"]) == bool(row["distance_ft"]):
            raise BaselineError(f"{where}: give one of distance_yd and distance_ft")
        column = "distance_yd" if row["distance_yd"] else "distance_ft"
        distance = _number(row[column], where, column, "a distance above 0")
        if distance <= 0.0:
            raise BaselineError(f"{where}: {column} {row[column]}; allowed: above 0")
        strokes = _number(
            row["expected_strokes"], where, "expected_strokes", f"1 to {MAX_STROKES:g}"
        )
        if not 1.0 <= strokes <= MAX_STROKES:
            raise BaselineError(
                f"{where}: expected_strokes {row['expected_strokes']}; allowed: 1 to "
                f"{MAX_STROKES:g} (a ball not in the hole takes a stroke at least)"
            )
        distance_m = distance * (YARD_M if column == "distance_yd" else FOOT_M)
        for other_k, other_m, _ in rows[lie]:
            if math.isclose(other_m, distance_m, rel_tol=1e-9):
                raise BaselineError(
                    f"{where}: a second {lie} row at {row[column]} {column[-2:]} "
                    f"(line {other_k}); allowed: one row per lie and distance"
                )
        rows[lie].append((k, distance_m, strokes))
    for lie in LIES:
        if len(rows[lie]) < 2:
            raise BaselineError(
                f"{name}: {len(rows[lie])} {lie} rows; allowed: 2 or more for every lie "
                f"({', '.join(LIES)})"
            )
    distance_m, strokes = {}, {}
    for lie in LIES:
        ordered = sorted(rows[lie], key=lambda r: r[1])
        distance_m[lie] = np.array([r[1] for r in ordered])
        strokes[lie] = np.array([r[2] for r in ordered])
    return Baseline(source=name, distance_m=distance_m, strokes=strokes)


_TOUR = None


def tour_baseline():
    """The PGA Tour baseline of the package (Broadie 2012, Table 9), loaded once."""
    global _TOUR
    if _TOUR is None:
        _TOUR = load_baseline(DEFAULT_BASELINE_PATH)
        _TOUR = Baseline("PGA Tour, Broadie (2012) Table 9", _TOUR.distance_m, _TOUR.strokes)
    return _TOUR
