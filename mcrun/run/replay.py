"""Replaying measured shots: each shot of a launch-monitor session, simulated as given.

``replay`` takes a table of measured launches (a CSV or Parquet file, or a DataFrame), with
columns recognised by name and unit suffix exactly as a scenario's ``launch.file``
(``scenario.launch_columns``: ``ball_speed_mph``, ``launch_deg``, ``spin_rpm``, optional
``spin_axis_deg`` and ``azimuth_deg``, ...), and flies every row, without sampling, on the turf
and in the weather given once for the whole session: what the session would have given on
another course or another day. The rows run through the same batch kernel as a Monte Carlo run.

A row with a missing value or a value outside ``mcrun.api.RANGES`` is not simulated: it keeps
its place with status ``invalid_input`` (a session often holds a misread shot; one bad row
should not stop the others). The output keeps the file's own columns (renamed ``input_<name>``
where a name is also an output column), then the launch in SI-named columns, the outcome of
``schema.OUTCOME_FIELDS`` and status_name, with the provenance in the Parquet metadata.
"""

import time
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun import status
from mcrun.api import InputError, conditions_inputs
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import OUTCOME_FIELDS, encode_outcomes, pack
from mcrun.physics.constants import DEG
from mcrun.results import output
from mcrun.run.scenario import PARAMETERS, launch_columns, read_launch_table
from mcrun.units import KINDS

# The launch columns of the output, by quantity (scenario.FILE_COLUMNS): (name, SI -> factor).
LAUNCH_COLUMNS = {
    "ball_speed": ("ball_speed_mps", 1.0),
    "launch_angle": ("launch_angle_deg", 1.0 / DEG),
    "spin": ("spin_radps", 1.0),
    "spin_axis": ("spin_axis_deg", 1.0 / DEG),
    "azimuth": ("azimuth_deg", 1.0 / DEG),
}


def launches(frame, source="the shots"):
    """(SI arrays by quantity, valid row mask) of the measured launches in ``frame``."""
    found = launch_columns(frame, source)
    n = len(frame)
    valid = np.ones(n, dtype=bool)
    values = {}
    for quantity in LAUNCH_COLUMNS:
        if quantity in found:
            column, unit = found[quantity]
            kind = PARAMETERS["launch"][quantity].kind
            raw = pd.to_numeric(frame[column], errors="coerce").to_numpy(dtype=float)
            factor, offset = KINDS[kind][1][unit]
            si = raw * factor + offset
        else:
            si = np.zeros(n)
        lo, hi = PARAMETERS["launch"][quantity].limits
        valid &= np.isfinite(si) & (si >= lo) & (si <= hi)
        values[quantity] = si
    return values, valid


def replay(shots, source=None, **conditions):
    """Simulate every measured shot of ``shots`` (a DataFrame, or a CSV/Parquet path).

    ``conditions``: the keyword arguments of ``api.conditions_inputs`` (turf, slope_deg,
    aero_model, wind_mps, temperature_c, altitude_m, ...), the same for every shot, as for
    ``api.simulate``. Returns a DataFrame, one row per shot (see the module
    docstring); rows with an unusable launch get status invalid_input.
    """
    if isinstance(shots, str | Path):
        source = source or str(shots)
        shots = read_launch_table(shots)
    source = source or "the shots"
    if len(shots) == 0:
        raise InputError(f"{source}: no shots: the table has no rows")
    values, valid = launches(shots, source)
    n = len(shots)
    launch = {
        "ball_speed_mps": values["ball_speed"],
        "launch_angle_rad": values["launch_angle"],
        "spin_radps": values["spin"],
        "spin_axis_rad": values["spin_axis"],
        "azimuth_rad": values["azimuth"],
    }
    # An unusable row reaches the kernel as a NaN speed, which it answers with invalid_input.
    out = simulate_batch(pack({**conditions_inputs(**conditions), **launch}, n, invalid=~valid))

    frame = {"row": np.arange(n, dtype=np.int64)}
    launch_names = [name for name, _ in LAUNCH_COLUMNS.values()]
    taken = {"row", "status_name", *launch_names, *OUTCOME_FIELDS}
    for column in shots.columns:
        name = str(column)
        frame[f"input_{name}" if name in taken else name] = shots[column].to_numpy()
    for quantity, (name, factor) in LAUNCH_COLUMNS.items():
        frame[name] = values[quantity] * factor
    encoded = encode_outcomes(out)
    for name, (values, missing) in encoded.items():
        if name in frame:  # launch_angle_deg: the measured launch above
            continue
        frame[name] = values if missing is None else pd.arrays.IntegerArray(values, missing)
    frame["status_name"] = pd.Categorical.from_codes(
        encoded["status"][0].astype(int), [status.NAMES[k] for k in sorted(status.NAMES)]
    )
    return pd.DataFrame(frame)


def replay_file(source, destination, force=False, **conditions):
    """Replay the shots of the file ``source`` and write ``destination`` (Parquet) atomically,
    with the provenance in its metadata. Returns the DataFrame written."""
    started = time.perf_counter()
    start_time = datetime.now(UTC).isoformat(timespec="seconds")
    source = Path(source)
    shots = read_launch_table(source)
    with output.AtomicFile(destination, force=force) as target:
        frame = replay(shots, source=str(source), **conditions)
        metadata = {
            "format_version": 1,
            "backend": "local",
            "file": "replay",
            "source_path": str(source),
            "n": len(frame),
            "conditions": {k: _plain(v) for k, v in conditions.items()},
            "versions": output.versions(),
            "threads": _threads(),
            "start_time_utc": start_time,
            "elapsed_s": round(time.perf_counter() - started, 3),
        }
        output.write_table(target.tmp, frame, output.encode_provenance(metadata))
        target.commit()
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
