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

import math
import time
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun import api, status
from mcrun.api import InputError
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN, N_INPUT, OUTCOME_FIELDS
from mcrun.engine.shot import default_dt_s
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


def conditions_inputs(
    turf="green",
    slope_deg=0.0,
    fall_line_deg=0.0,
    dt_s=None,
    **conditions,
):
    """The kernel input columns that do not depend on the launch, checked by ``mcrun.api``
    exactly as ``api.simulate`` checks them (``conditions``: ``api.flight_params``'s)."""
    turf = api.resolve_turf(turf)
    params = api.flight_params(**conditions)
    return {
        "air_density_kgpm3": params.air_density_kgpm3,
        "kinematic_viscosity_m2ps": params.kinematic_viscosity_m2ps,
        "aero_model": float(params.aero_model),
        "cd_scale": params.cd_scale,
        "cl_scale": params.cl_scale,
        "wind_x_mps": params.wind_x_mps,
        "wind_right_mps": -params.wind_y_mps,  # FlightParams is in the core's frame, y left
        "wind_profile": float(params.wind_profile),
        "wind_reference_height_m": params.wind_reference_height_m,
        "wind_profile_parameter": params.wind_profile_parameter,
        "mu": turf.mu,
        "softness": turf.softness,
        "e0": turf.e0,
        "e1": turf.e1,
        "e2": turf.e2,
        "e_break_speed_mps": turf.e_break_speed_mps,
        "e_high": turf.e_high,
        "rho_g": turf.rho_g,
        "critical_height_m": turf.critical_height_m,
        "slope_rad": api.check_range("slope_deg", slope_deg) * DEG,
        "fall_line_rad": api.check_range("fall_line_deg", fall_line_deg) * DEG,
        "dt_s": api.check_range(
            "dt_s",
            default_dt_s(conditions.get("wind_profile", "uniform")) if dt_s is None else dt_s,
        ),
    }


def replay(shots, source=None, **conditions):
    """Simulate every measured shot of ``shots`` (a DataFrame, or a CSV/Parquet path).

    ``conditions``: turf, slope_deg, fall_line_deg, dt_s and the keyword arguments of
    ``api.flight_params`` (aero_model, wind_mps, temperature_c, altitude_m, ...), the same for
    every shot, as for ``api.simulate``. Returns a DataFrame, one row per shot (see the module
    docstring); rows with an unusable launch get status invalid_input.
    """
    if isinstance(shots, str | Path):
        source = source or str(shots)
        shots = read_launch_table(shots)
    source = source or "the shots"
    if len(shots) == 0:
        raise InputError(f"{source}: no shots: the table has no rows")
    values, valid = launches(shots, source)
    fixed = conditions_inputs(**conditions)
    n = len(shots)
    inputs = np.empty((n, N_INPUT), order="F")
    for name, value in fixed.items():
        inputs[:, COLUMN[name]] = value
    inputs[:, COLUMN["ball_speed_mps"]] = values["ball_speed"]
    inputs[:, COLUMN["launch_angle_rad"]] = values["launch_angle"]
    inputs[:, COLUMN["spin_radps"]] = values["spin"]
    inputs[:, COLUMN["spin_axis_rad"]] = values["spin_axis"]
    inputs[:, COLUMN["azimuth_rad"]] = values["azimuth"]
    # An unusable row reaches the kernel as a NaN speed, which it answers with invalid_input.
    inputs[~valid, COLUMN["ball_speed_mps"]] = math.nan
    out = simulate_batch(inputs)

    frame = {"row": np.arange(n, dtype=np.int64)}
    launch_names = [name for name, _ in LAUNCH_COLUMNS.values()]
    taken = {"row", "status_name", *launch_names, *OUTCOME_FIELDS}
    for column in shots.columns:
        name = str(column)
        frame[f"input_{name}" if name in taken else name] = shots[column].to_numpy()
    for quantity, (name, factor) in LAUNCH_COLUMNS.items():
        frame[name] = values[quantity] * factor
    for k, name in enumerate(OUTCOME_FIELDS):
        if name in frame:  # launch_angle_deg: the measured launch above
            continue
        if name == "bounces":
            missing = ~np.isfinite(out[:, k])
            bounces = pd.array(np.where(missing, 0, out[:, k]).astype(np.int32), dtype="Int32")
            bounces[missing] = pd.NA
            frame[name] = bounces
        elif name == "status":
            frame[name] = out[:, k].astype(np.int8)
        else:
            frame[name] = out[:, k]
    codes = out[:, OUTCOME_FIELDS.index("status")].astype(int)
    frame["status_name"] = pd.Categorical.from_codes(
        codes, [status.NAMES[k] for k in sorted(status.NAMES)]
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
