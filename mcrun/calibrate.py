"""Calibration of the aerodynamic models against measured shots (``mcrun calibrate``).

The measurements are the TrackMan 2019 PGA Tour and LPGA Tour averages shipped in
``mcrun/data/trackman_tour_averages_2019.csv``: for each club, the average ball speed, launch
angle and spin, and the average carry, apex (max height) and land angle they give. TrackMan
says altitude and weather were not taken into account, so every shot is flown in the package's
standard air (20 C, 101325 Pa, 50 % RH), without wind, with zero azimuth and spin axis, at the
default step.

``predict`` flies the table's launches with a model, ``errors`` compares the result with the
table (residual = simulated - measured), and ``fit`` refits the quadratic form of
``aero.QUADRATIC_COEFFICIENTS`` (C_D = a0 + a1 S + a2 S^2, C_L = b0 + b1 S + b2 S^2, S clipped
at s_max) by least squares; its output is the ``trackman2019`` row of that table.
"""

import math
import time
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun.api import InputError, check_range, conditions_inputs
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import APEX as APEX_FIELD
from mcrun.engine.schema import CARRY, pack
from mcrun.engine.schema import LANDING_ANGLE as LANDING_ANGLE_FIELD
from mcrun.engine.shot import DEFAULT_DT_S
from mcrun.physics import aero
from mcrun.physics.constants import DEG, STANDARD_HUMIDITY, STANDARD_PRESSURE_PA
from mcrun.units import parse_quantity, shown

DEFAULT_DATA = resources.files("mcrun") / "data" / "trackman_tour_averages_2019.csv"

# Columns of the measured table, in the units TrackMan publishes.
MEASURED_COLUMNS = (
    "tour",
    "club",
    "ball_mph",
    "launch_deg",
    "spin_rpm",
    "max_height_yd",
    "land_deg",
    "carry_yd",
)

# Standard conditions the table is flown in (TrackMan: altitude and weather not accounted for).
STANDARD_CONDITIONS = dict(
    temperature_c=20.0, pressure_pa=STANDARD_PRESSURE_PA, relative_humidity=STANDARD_HUMIDITY
)

# Models compared by ``--compare``: every model, in the order aero.MODELS lists them.
COMPARED_MODELS = tuple(aero.MODELS)

# Measurement scales that turn residuals into comparable numbers (the fit's weights, and the
# denominators of the ``scaled_rms`` score). They are the size of the mismatch one should expect
# between a tour average and one shot flown from the average launch, not the monitor's precision:
# - carry 1.5 m: the table rounds to whole yards (+-0.46 m), and an average of shots is not the
#   shot of the average launch; +-1 % of carry from unrecorded weather and altitude is 1-3 m;
# - apex 1 m: whole yards (+-0.46 m), plus the same averaging, on a quantity of 20-30 m;
# - land angle 1 deg: whole degrees (+-0.5 deg), plus the averaging; 1 deg of land angle is
#   about what 1 m of apex changes at the end of a 150-250 m flight.
CARRY_SCALE_M = 1.5
APEX_SCALE_M = 1.0
LAND_ANGLE_SCALE_DEG = 1.0

# Physically sensible range of C_D and C_L over the spin ratios the fit is checked on.
COEFFICIENT_BAND = (0.05, 0.6)
BAND_SPIN_RATIOS = np.linspace(0.05, 0.6, 56)
# The fit's unknowns: C_D and C_L at these spin ratios (a well-conditioned basis of the
# quadratics, bounded to COEFFICIENT_BAND), and s_max, bounded to S_MAX_BOUNDS. The launches of
# the table span S 0.08-0.49 and their flights S 0.08-1.0 (S grows as the ball slows).
NODE_SPIN_RATIOS = np.array([0.1, 0.3, 0.5])
S_MAX_BOUNDS = (0.3, 1.0)
FIXED_S_MAX = 0.75


def _fail(message):
    raise InputError(" ".join(str(message).split()))


def load_measured(path=None):
    """Read a table of measured tour averages into SI.

    Parameters
    ----------
    path : str or Path, optional
        CSV with the columns of ``MEASURED_COLUMNS`` (lines starting with '#' are comments);
        default the shipped TrackMan 2019 table.

    Returns
    -------
    DataFrame
        tour, club, ball_speed_mps, launch_angle_deg, spin_radps, carry_m, apex_m and
        land_angle_deg (above the horizontal), one row per club.

    Raises
    ------
    InputError
        One line naming the file and what is wrong: missing or unreadable file, missing
        columns, or a value that is not a number in its documented range.
    """
    path = DEFAULT_DATA if path is None else Path(path)
    try:
        raw = pd.read_csv(path, comment="#", skipinitialspace=True)
    except FileNotFoundError:
        _fail(f"measured table {path}: no such file")
    except (OSError, UnicodeDecodeError) as err:
        _fail(f"measured table {path}: cannot read it ({err.__class__.__name__}: {err})")
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as err:
        _fail(f"measured table {path}: not a readable CSV ({err})")
    raw.columns = [str(c).strip() for c in raw.columns]
    missing = [c for c in MEASURED_COLUMNS if c not in raw.columns]
    if missing:
        _fail(
            f"measured table {path}: missing column(s) {', '.join(missing)}; "
            f"needs {', '.join(MEASURED_COLUMNS)}"
        )
    if raw.empty:
        _fail(f"measured table {path}: no rows")
    mph = parse_quantity("1 mph", "speed")
    rpm = parse_quantity("1 rpm", "spin")
    yd = parse_quantity("1 yd", "length")
    frame = pd.DataFrame(
        {"tour": raw["tour"].astype(str).str.strip(), "club": raw["club"].astype(str).str.strip()}
    )
    # Launches must be inside the documented input ranges (api.RANGES); outcomes positive,
    # and the land angle (above the horizontal) below 90 deg.
    for column, name, factor, checked in (
        ("ball_mph", "ball_speed_mps", mph, "ball_speed_mps"),
        ("launch_deg", "launch_angle_deg", 1.0, "launch_angle_deg"),
        ("spin_rpm", "spin_radps", rpm, "spin_radps"),
        ("carry_yd", "carry_m", yd, None),
        ("max_height_yd", "apex_m", yd, None),
        ("land_deg", "land_angle_deg", 1.0, 90.0),
    ):
        values = pd.to_numeric(raw[column], errors="coerce")
        bad = ~np.isfinite(values.to_numpy(dtype=float))
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            _fail(
                f"measured table {path}, data row {row + 1}, column {column}: "
                f"{shown(raw[column].iloc[row])} is not a finite number"
            )
        values = values.to_numpy(dtype=float) * factor
        for row, value in enumerate(values):
            try:
                if isinstance(checked, str):
                    check_range(checked, value)
                elif not 0.0 < value < (checked or math.inf):
                    bound = "" if checked is None else f" and below {checked:g}"
                    raise InputError(f"{value / factor:g} must be positive{bound}")
            except InputError as err:
                _fail(f"measured table {path}, data row {row + 1}, column {column}: {err}")
        frame[name] = values
    return frame


def _quadratic_model(model_name):
    return model_name in aero.MODELS and not np.isnan(
        aero.QUADRATIC_COEFFICIENTS[aero.model_id(model_name), 0]
    )


def predict(model_name, frame, table=None):
    """Fly the launches of ``frame`` (``load_measured``) with an aerodynamic model.

    Parameters
    ----------
    model_name : str
        A key of ``aero.MODELS``.
    frame : DataFrame
        ball_speed_mps, launch_angle_deg, spin_radps per row (tour and club are carried over).
    table : ndarray, optional
        Coefficients of the quadratic models, default ``aero.QUADRATIC_COEFFICIENTS``; a fit
        passes a modified copy.

    Returns
    -------
    DataFrame
        tour, club (when given), carry_m, apex_m and land_angle_deg (above the horizontal,
        90 deg minus the kernel's landing angle from the vertical), in the rows of ``frame``.
    """
    if table is None:
        table = aero.QUADRATIC_COEFFICIENTS
    table = np.ascontiguousarray(table, dtype=np.float64)
    fixed = conditions_inputs(
        turf="green", dt_s=DEFAULT_DT_S, aero_model=model_name, **STANDARD_CONDITIONS
    )
    launch = {
        "ball_speed_mps": frame["ball_speed_mps"].to_numpy(dtype=float),
        "launch_angle_rad": frame["launch_angle_deg"].to_numpy(dtype=float) * DEG,
        "spin_radps": frame["spin_radps"].to_numpy(dtype=float),
    }
    out = simulate_batch(pack({**fixed, **launch}, len(frame)), table=table)
    result = pd.DataFrame(
        {
            "carry_m": out[:, CARRY],
            "apex_m": out[:, APEX_FIELD],
            "land_angle_deg": 90.0 - out[:, LANDING_ANGLE_FIELD],
        },
        index=frame.index,
    )
    for key in ("club", "tour"):
        if key in frame:
            result.insert(0, key, frame[key])
    return result


@dataclass(frozen=True)
class Errors:
    """Residuals (simulated - measured) per club, and their RMSE per tour and overall."""

    model: str
    per_club: pd.DataFrame
    rmse: pd.DataFrame


def _scaled_residuals(measured, simulated):
    return np.concatenate(
        [
            (simulated["carry_m"].to_numpy() - measured["carry_m"].to_numpy()) / CARRY_SCALE_M,
            (simulated["apex_m"].to_numpy() - measured["apex_m"].to_numpy()) / APEX_SCALE_M,
            (simulated["land_angle_deg"].to_numpy() - measured["land_angle_deg"].to_numpy())
            / LAND_ANGLE_SCALE_DEG,
        ]
    )


def errors(model_name, frame, table=None):
    """Compare a model with the measured table.

    Returns
    -------
    Errors
        ``per_club``: tour, club and, for carry (m), apex (m) and land angle (deg above the
        horizontal), the measured value, the simulated one and the error (simulated - measured).
        ``rmse``: one row per tour and one for all (index 'all'): carry_rmse_m, apex_rmse_m,
        land_angle_rmse_deg, the mean errors (bias) and ``scaled_rms``, the root mean square of
        all three residuals in their measurement scales (the quantity ``fit`` minimises).
    """
    simulated = predict(model_name, frame, table)
    per_club = pd.DataFrame({"tour": frame["tour"], "club": frame["club"]})
    for name, unit in (("carry", "m"), ("apex", "m"), ("land_angle", "deg")):
        key = f"{name}_{unit}"
        per_club[f"{name}_measured_{unit}"] = frame[key]
        per_club[f"{name}_simulated_{unit}"] = simulated[key]
        per_club[f"{name}_error_{unit}"] = simulated[key] - frame[key]
    rows = {}
    tours = list(dict.fromkeys(frame["tour"]))
    for tour in [*tours, "all"]:
        pick = per_club if tour == "all" else per_club[per_club["tour"] == tour]
        scaled = _scaled_residuals(frame.loc[pick.index], simulated.loc[pick.index])
        row = {}
        for name, unit in (("carry", "m"), ("apex", "m"), ("land_angle", "deg")):
            err = pick[f"{name}_error_{unit}"].to_numpy()
            row[f"{name}_rmse_{unit}"] = float(np.sqrt(np.mean(err**2)))
            row[f"{name}_bias_{unit}"] = float(np.mean(err))
        row["scaled_rms"] = float(np.sqrt(np.mean(scaled**2)))
        rows[tour] = row
    rmse = pd.DataFrame.from_dict(rows, orient="index")
    rmse.index.name = "tour"
    return Errors(model_name, per_club.reset_index(drop=True), rmse)


def _lagrange_matrix(nodes):
    """M with (c0, c1, c2) = M @ (values at the nodes) for the quadratic through them."""
    vandermonde = np.vander(np.asarray(nodes, dtype=float), 3, increasing=True)
    return np.linalg.inv(vandermonde)


def _node_values(row):
    powers = np.vander(NODE_SPIN_RATIOS, 3, increasing=True)
    return np.concatenate([powers @ row[0:3], powers @ row[3:6]])


def _row_from_unknowns(x, s_max):
    to_coefficients = _lagrange_matrix(NODE_SPIN_RATIOS)
    cd = to_coefficients @ x[0:3]
    cl = to_coefficients @ x[3:6]
    return np.concatenate([cd, cl, [x[6] if s_max is None else s_max]])


def curves(row, spin_ratios):
    """C_D and C_L of a quadratic row (a0, a1, a2, b0, b1, b2, s_max) at the given S."""
    s = np.minimum(np.asarray(spin_ratios, dtype=float), row[6])
    return row[0] + s * (row[1] + s * row[2]), row[3] + s * (row[4] + s * row[5])


def band_violation(row):
    """How far C_D(S) and C_L(S) leave COEFFICIENT_BAND for S in [0.05, 0.6] (0 inside)."""
    lo, hi = COEFFICIENT_BAND
    cd, cl = curves(row, BAND_SPIN_RATIOS)
    both = np.concatenate([cd, cl])
    return float(max(0.0, lo - both.min(), both.max() - hi))


def round_significant(values, digits=4):
    """Round each value to ``digits`` significant digits."""
    out = []
    for v in np.asarray(values, dtype=float):
        if v == 0.0 or not math.isfinite(v):
            out.append(float(v))
        else:
            out.append(round(float(v), digits - 1 - math.floor(math.log10(abs(v)))))
    return np.array(out)


@dataclass(frozen=True)
class FitResult:
    """Outcome of ``fit``: the fitted row (4 significant digits), the errors before and after."""

    row: np.ndarray
    start: str
    s_max_fitted: bool
    seconds: float
    evaluations: int
    before: Errors
    after: Errors
    message: str


def fit(frame, start="ferguson2022", s_max=None):
    """Least-squares fit of the quadratic C_D(S), C_L(S) to measured carry, apex and land angle.

    The residuals are scaled by CARRY_SCALE_M, APEX_SCALE_M and LAND_ANGLE_SCALE_DEG. The
    unknowns are C_D and C_L at S = 0.1, 0.3, 0.5 (the six coefficients, in a better-conditioned
    basis), each bounded to [0.05, 0.6], and s_max within S_MAX_BOUNDS, unless ``s_max`` is given
    (then it is held there, e.g. 0.75 as ferguson2022). A penalty keeps C_D(S) and C_L(S) inside
    [0.05, 0.6] for all S in [0.05, 0.6], not only at the nodes. Deterministic: the same start
    gives the same row.

    Parameters
    ----------
    frame : DataFrame
        ``load_measured`` output.
    start : str
        A quadratic model whose row starts the fit.
    s_max : float, optional
        Hold the clip of S at this value instead of fitting it.

    Returns
    -------
    FitResult
        ``row`` = (a0, a1, a2, b0, b1, b2, s_max) rounded to 4 significant digits; ``before`` and
        ``after`` are ``errors`` of the start row and of the rounded row.
    """
    try:
        from scipy.optimize import least_squares
    except ImportError:
        raise InputError(
            "fitting needs scipy: install the calibrate extra, pip install 'mcrun[calibrate]'"
        ) from None
    if not _quadratic_model(start):
        _fail(
            f"cannot start a fit from '{start}': choose a quadratic model "
            f"({', '.join(m for m in aero.MODELS if _quadratic_model(m))})"
        )
    target = aero.TRACKMAN2019
    table = aero.QUADRATIC_COEFFICIENTS.copy()
    start_row = table[aero.model_id(start)].copy()
    lo, hi = COEFFICIENT_BAND
    x0 = _node_values(start_row)
    lower = np.full(6, lo)
    upper = np.full(6, hi)
    if s_max is None:
        x0 = np.append(x0, start_row[6])
        lower = np.append(lower, S_MAX_BOUNDS[0])
        upper = np.append(upper, S_MAX_BOUNDS[1])
    x0 = np.clip(x0, lower + 1e-9, upper - 1e-9)

    def residuals(x):
        row = _row_from_unknowns(x, s_max)
        table[target] = row
        simulated = predict("trackman2019", frame, table)
        res = _scaled_residuals(frame, simulated)
        # A shot that does not land (absurd coefficients) counts as far off.
        res = np.where(np.isfinite(res), res, 1e3)
        # Penalty, zero inside the band: 0.001 out of the band weighs as one scale unit.
        return np.append(res, band_violation(row) / 1e-3)

    table[target] = start_row
    before = errors("trackman2019", frame, table)
    began = time.perf_counter()
    solution = least_squares(
        residuals,
        x0,
        bounds=(lower, upper),
        method="trf",
        diff_step=1e-6,
        x_scale=np.abs(x0),
        xtol=1e-10,
        ftol=1e-10,
    )
    seconds = time.perf_counter() - began
    row = round_significant(_row_from_unknowns(solution.x, s_max), 4)
    table[target] = row
    after = errors("trackman2019", frame, table)
    return FitResult(
        row=row,
        start=start,
        s_max_fitted=s_max is None,
        seconds=seconds,
        evaluations=int(solution.nfev),
        before=Errors(start, before.per_club, before.rmse),
        after=after,
        message=str(solution.message),
    )


def row_literal(row):
    """The row as Python source, to paste into ``aero.QUADRATIC_COEFFICIENTS``."""
    return "[" + ", ".join(f"{v:.4g}" for v in row) + "],"
