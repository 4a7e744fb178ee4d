"""Replaying measured shots: each shot of a launch-monitor session, simulated as given.

``replay`` takes a session (a file, read by ``mcrun.run.monitors``: a device's export detected
from its header or forced with ``format``, or mcrun's own columns ``ball_speed_mph``,
``launch_deg``, ``spin_rpm``...; or a DataFrame), and flies every row, without sampling, on the
turf and in the weather given once for the whole session: what the session would have given on
another course or another day. The rows run through the same batch kernel as a Monte Carlo run.

A row with a missing value or a value outside ``mcrun.quantities.RANGES``, or one the reader
could not use (``Session.reasons``: a cell that is not a number, a summary row, a row cut
short), is not simulated: it keeps its place with status ``invalid_input`` and its reason in
``invalid_reason`` (a column only where some row is invalid; a session often holds a misread
shot, and one bad row should not stop the others). A session with no valid row is refused.

The output keeps the file's own columns (renamed ``input_<name>``
where a name is also an output column), then ``club`` (where the file names the club), the
launch in SI-named columns, the device's own results where the file has them
(``device_carry_m``...), the outcome of ``schema.OUTCOME_FIELDS``, ``descent_angle_deg`` (from
the horizontal, as devices give it), the model minus the device (``model_minus_device_carry_m``
...) and status_name, with the provenance (and the format read) in the Parquet metadata.

``replay_file`` also writes the session per club beside the Parquet (``table_paths``):
``STEM-clubs.csv``, ``mcrun.run.clubs.club_summary``, and, where the file holds the device's
results, ``STEM-device.csv``, ``mcrun.run.clubs.device_comparison``.
"""

import re
import time
from contextlib import ExitStack
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun import status
from mcrun.api import DEFAULTS, conditions_inputs
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import OUTCOME_FIELDS, encode_outcomes, pack
from mcrun.physics.constants import DEG
from mcrun.quantities import InputError, by_path, column_and_factor
from mcrun.results import output
from mcrun.run import clubs
from mcrun.run.monitors import Session, read_session, session_of_frame
from mcrun.run.monitors.formats import split_name
from mcrun.run.monitors.native import KIND, names_shown
from mcrun.units import UnitError, foreign_digits, shown, to_unit

# The launch columns of the output, by quantity (scenario.FILE_COLUMNS): (name, SI -> factor).
LAUNCH_COLUMNS = {
    q: column_and_factor(f"launch.{q}")
    for q in ("ball_speed", "launch_angle", "spin", "spin_axis", "azimuth")
}


CHUNK = 65536
"""Shots flown at a time by ``replay``."""

# A column of the air a session was measured in, by its name (the unit taken off, spaces for
# underscores): a Garmin R10's Temperature, Air Pressure, Relative Humidity and Air Density,
# Awesome Golf's Altitude, temperature_f in a file of mcrun's columns. Kept as written and not
# read (the shots are flown in the conditions' air), which a note says. The whole name must be
# one: "Temperature Adjusted Carry" or "Elevation Change" is none.
_AIR_COLUMN = re.compile(
    r"^(?:(?:air|ambient|outside|atmospheric|station|barometric|relative) )?"
    r"(?:temperature|temp|pressure|density|humidity|rh|altitude|elevation)"
    r"(?: (?:c|f|k|pa|hpa|kpa|mbar|inhg|pct|percent|kgpm3|m|ft))?$"
)
# The conditions that set the air (``api.conditions_inputs``' keywords), as a note names them.
_AIR_GIVEN = {
    "temperature_c": "temperature",
    "pressure_pa": "pressure",
    "altitude_m": "altitude",
    "relative_humidity": "humidity",
    "air_density_kgpm3": "air density",
}


def _air_note(session, air, conditions):
    """A note naming the session's columns of the air, which are not read, and the air the
    shots are flown in instead (``air``: the kernel's conditions; ``conditions``: those given,
    each named, and the defaults of the others); None where the session has none."""
    names = [
        str(c) for c in session.frame.columns
        if _AIR_COLUMN.match(split_name(str(c).replace("_", " "))[0])
    ]  # fmt: skip
    if not names:
        return None
    given = [k for k in _AIR_GIVEN if conditions.get(k) is not None]
    defaults = {
        "temperature_c": f"{DEFAULTS['temperature_c']:g} C",
        "pressure_pa": f"{DEFAULTS['pressure_pa']:g} Pa",
        "relative_humidity": f"{100 * DEFAULTS['relative_humidity']:g} %",
    }
    set_by = {*given, *(["pressure_pa"] if "altitude_m" in given else [])}  # (the altitude's)
    left = [v for k, v in defaults.items() if k not in set_by]
    if "air_density_kgpm3" in given or not left:
        how = "as given"
    else:
        named = " and ".join(_AIR_GIVEN[k] for k in given)
        how = (
            f"{named} given, {', '.join(left)} by default" if named else
            f"the default ({', '.join(left)})"
        )  # fmt: skip
        how += (
            ": give the session's temperature, pressure or altitude, and humidity, or its air "
            "density, to fly it in its own"
        )
    return (
        f"{session.path}: its air ({names_shown(names)}) is kept as written, not read: every "
        f"shot is flown in air of {air['air_density_kgpm3']:.4g} kg/m^3, {how}"
    )


# The device's results and the model's, by quantity: (device column, SI -> factor, model column).
DEVICE_COLUMNS = {
    "carry": ("device_carry_m", 1.0, "carry_m"),
    "total": ("device_total_m", 1.0, "total_m"),
    "apex": ("device_apex_m", 1.0, "apex_m"),
    "descent_angle": ("device_descent_angle_deg", 1.0 / DEG, "descent_angle_deg"),
    "carry_side": ("device_carry_side_m", 1.0, "carry_lateral_m"),
    "total_side": ("device_total_side_m", 1.0, "final_y_m"),
}


def launches(session):
    """(SI arrays by quantity, valid row mask) of the measured launches of a ``Session``: a
    quantity the file does not give is 0 (spin axis, azimuth); a value missing or outside
    its range (``mcrun.quantities``), or a reason the reader gave (``Session.reasons``), makes
    its row invalid."""
    n = len(session.frame)
    valid = np.ones(n, dtype=bool) if session.reasons is None else session.reasons == ""
    values = {}
    for quantity in LAUNCH_COLUMNS:
        si = session.launch.get(quantity, np.zeros(n))
        lo, hi = by_path(f"launch.{quantity}").limits
        valid &= np.isfinite(si) & (si >= lo) & (si <= hi)
        values[quantity] = si
    return values, valid


def invalid_reasons(session, values, valid, most=None):
    """Why each row is invalid ("" for the valid ones): the reader's reason, else the first
    launch value missing (its cell empty or not a number) or outside its range; only for the
    first ``most`` rows that need one when given."""
    n = len(session.frame)
    reasons = np.full(n, "", dtype=object)
    if session.reasons is not None:
        reasons[:] = session.reasons
    rows = np.flatnonzero(~valid & (reasons == ""))[:most]
    for quantity in LAUNCH_COLUMNS:
        if rows.size == 0:
            break
        si = values[quantity][rows]
        column = session.sources.get(quantity, quantity)
        lo, hi = by_path(f"launch.{quantity}").limits
        missing = ~np.isfinite(si)
        outside = ~missing & ((si < lo) | (si > hi))
        unit = session.units.get(quantity, "")
        kind = KIND[quantity]
        for row in rows[missing]:
            cell = session.frame[column].iloc[row] if column in session.frame else None
            if cell is None or pd.isna(cell):
                why = "empty"
            elif isinstance(cell, float | np.floating):  # read as a number: inf ("1e999")
                why = f"{cell} is not a finite number"
            else:  # (with why, where it looks like a number and is not one: "−167")
                foreign = foreign_digits(str(cell))
                why = f"{shown(str(cell), 30)} not read" + (f": {foreign}" if foreign else "")
            reasons[row] = f"{column}: {why}"
        for row, value in zip(rows[outside], si[outside], strict=True):
            reasons[row] = f"{column}: {_in_unit(value, kind, unit)} is outside " + (
                f"[{_in_unit(lo, kind, unit)}, {_in_unit(hi, kind, unit)}]"
            )
        rows = rows[~(missing | outside)]
    return reasons


def _in_unit(value_si, kind, unit):
    """An SI value in the file's unit for a message ("250 mph"), in SI where it has none."""
    try:
        return f"{to_unit(value_si, kind, unit):.6g} {unit}"
    except (UnitError, ValueError, KeyError):
        return f"{value_si:.6g} (SI)"


def check_some_valid(session, values, valid):
    """InputError naming the file when no row of ``session`` can fly: the rows and the first
    row's reason."""
    if valid.any():
        return
    reasons = invalid_reasons(session, values, valid, most=1)
    n = len(valid)
    raise InputError(
        f"{session.path}: no valid shot in its {n} row{'s' * (n != 1)}; row 1: {reasons[0]}"
    )


def replay(shots, source=None, format=None, **conditions):
    """Simulate every measured shot of ``shots`` (a ``monitors.Session``, a DataFrame, or a
    path to a session file; ``format`` forces the export's format, ``monitors.NAMES``).

    ``conditions``: the keyword arguments of ``api.conditions_inputs`` (turf, slope_deg,
    aero_model, wind_mps, temperature_c, altitude_m, ...), the same for every shot, as for
    ``api.simulate``. Returns a DataFrame, one row per shot (see the module
    docstring); rows with an unusable launch get status invalid_input.
    """
    if isinstance(shots, str | Path):
        shots = read_session(shots, format)
    elif isinstance(shots, pd.DataFrame):
        source = source or "the shots"
        if len(shots) == 0:
            raise InputError(f"{source}: no shots: the table has no rows")
        shots = session_of_frame(shots, source, format)
    elif not isinstance(shots, Session):  # (an AttributeError before)
        raise InputError(f"shots {shown(shots)}: allowed: a Session, a DataFrame or a file's path")
    session = shots
    values, valid = launches(session)
    check_some_valid(session, values, valid)
    n = len(session.frame)
    launch = {
        "ball_speed_mps": values["ball_speed"],
        "launch_angle_rad": values["launch_angle"],
        "spin_radps": values["spin"],
        "spin_axis_rad": values["spin_axis"],
        "azimuth_rad": values["azimuth"],
    }
    air = conditions_inputs(**conditions)
    encoded = _fly(air, launch, valid)

    frame = {"row": np.arange(n, dtype=np.int64)}
    launch_names = [name for name, _ in LAUNCH_COLUMNS.values()]
    device_names = [DEVICE_COLUMNS[q][0] for q in session.device]
    compared = [f"model_minus_{DEVICE_COLUMNS[q][0]}" for q in session.device]
    add_club = session.club is not None and session.club_column != "club"
    taken = {"row", "status_name", "invalid_reason", "descent_angle_deg", *launch_names}
    taken |= set(OUTCOME_FIELDS)
    taken |= {*device_names, *compared} | ({"club"} if add_club else set())
    for column in session.frame.columns:
        name = str(column)
        frame[f"input_{name}" if name in taken else name] = session.frame[
            column
        ].array  # no copy (strings: 0.4 GB a million rows)
    if add_club:
        frame["club"] = session.club
    for quantity, (name, factor) in LAUNCH_COLUMNS.items():
        frame[name] = values[quantity] * factor
    for quantity, si in session.device.items():
        name, factor, _ = DEVICE_COLUMNS[quantity]
        frame[name] = si * factor
    for name, (column, missing) in encoded.items():
        if name in frame:  # launch_angle_deg: the measured launch above
            continue
        frame[name] = column if missing is None else pd.arrays.IntegerArray(column, missing)
    frame["descent_angle_deg"] = 90.0 - encoded["landing_angle_deg"][0]
    for quantity in session.device:
        name, _, model = DEVICE_COLUMNS[quantity]
        frame[f"model_minus_{name}"] = np.asarray(frame[model], dtype=float) - frame[name]
    frame["status_name"] = pd.Categorical.from_codes(
        encoded["status"][0].astype(int), [status.NAMES[k] for k in sorted(status.NAMES)]
    )
    if not valid.all():
        frame["invalid_reason"] = invalid_reasons(session, values, valid).astype(str)
    result = pd.DataFrame(frame, copy=False)  # the columns as made, not copied into blocks
    result.attrs["format"] = session.format
    result.attrs["format_title"] = session.title
    result.attrs["format_detected"] = session.detected
    result.attrs["notes"] = list(session.notes) + [
        note for note in [_air_note(session, air, conditions)] if note is not None
    ]
    return result


def _fly(conditions, launch, valid):
    """The outcomes of the launches, ``schema.encode_outcomes``'s columns, flown ``CHUNK``
    shots at a time (each shot alone in the kernel: the same numbers however they are cut),
    so that the kernel's inputs and outputs stay small beside the session."""
    n = valid.size
    encoded = {}
    for start in range(0, max(n, 1), CHUNK):
        rows = slice(start, min(start + CHUNK, n))
        m = rows.stop - rows.start
        part = {name: values[rows] for name, values in launch.items()}
        # An unusable row reaches the kernel as a NaN speed, which it answers invalid_input.
        out = simulate_batch(pack({**conditions, **part}, m, invalid=~valid[rows]))
        for name, (column, missing) in encode_outcomes(out).items():
            if name not in encoded:
                encoded[name] = (
                    np.empty(n, dtype=column.dtype),
                    None if missing is None else np.empty(n, dtype=bool),
                )
            encoded[name][0][rows] = column
            if missing is not None:
                encoded[name][1][rows] = missing
    return encoded


def table_paths(destination, device=True):
    """{table: path} of the per-club tables written beside the replay output ``destination``:
    ``STEM-clubs.csv`` and, with ``device``, ``STEM-device.csv``."""
    destination = Path(destination)
    kinds = ("clubs", "device") if device else ("clubs",)
    return {k: destination.with_name(f"{destination.stem}-{k}.csv") for k in kinds}


def replay_file(source, destination, force=False, format=None, **conditions):
    """Replay the shots of the file ``source`` (``format`` forces the export's format) and write
    ``destination`` (Parquet) atomically, with the provenance in its metadata, and the per-club
    tables beside it (``table_paths``; every file is checked before any is written, and all are
    renamed into place together). Returns the DataFrame written; ``frame.attrs["written"]``
    lists the paths."""
    started = time.perf_counter()
    start_time = datetime.now(UTC).isoformat(timespec="seconds")
    source = Path(source)
    session = read_session(source, format)
    check_some_valid(session, *launches(session))  # before anything is written
    tables = table_paths(destination, device=bool(session.device))
    with ExitStack() as stack:
        target = stack.enter_context(output.AtomicFile(destination, force=force))
        targets = {
            k: stack.enter_context(output.AtomicFile(path, force=force))
            for k, path in tables.items()
        }
        frame = replay(session, **conditions)
        metadata = {
            "format_version": output.FORMAT_VERSION,
            "backend": "local",
            "file": "replay",
            "source_path": str(source),
            "source_format": session.format,
            "n": len(frame),
            "conditions": {k: _plain(v) for k, v in conditions.items()},
            "versions": output.versions(),
            "threads": _threads(),
            "start_time_utc": start_time,
            "elapsed_s": round(time.perf_counter() - started, 3),
        }
        output.write_table(target.tmp, frame, output.encode_provenance(metadata))
        clubs.club_summary(frame).to_csv(targets["clubs"].tmp, index=False)
        if "device" in targets:
            clubs.device_comparison(frame).to_csv(targets["device"].tmp, index=False)
        for each in (target, *targets.values()):
            each.commit()
    frame.attrs["written"] = [Path(destination), *tables.values()]
    return frame


def _threads():
    import numba

    return numba.get_num_threads()


def _plain(value):
    """A JSON-able copy of a condition (a Turf becomes a dict of its fields)."""
    if hasattr(value, "_asdict"):
        return {k: _plain(v) for k, v in value._asdict().items()}
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, int | float | str | bool) or value is None:
        return value
    return str(value)
