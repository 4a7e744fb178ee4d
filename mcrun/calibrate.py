"""Calibration of the aerodynamic models against measured shots (``mcrun calibrate``).

The measurements are the TrackMan 2019 PGA Tour and LPGA Tour averages shipped in
``mcrun/data/trackman_tour_averages_2019.csv``: for each club, the average ball speed, launch
angle and spin, and the average carry, apex (max height) and land angle they give. TrackMan
says altitude and weather were not taken into account, so every shot is flown in the package's
standard air (20 C, 101325 Pa, 50 % RH), without wind, with zero azimuth and spin axis, at the
default step.

``predict`` flies the table's launches with a model, ``errors`` compares the result with the
table (residual = simulated - measured), and ``fit`` refits a form of
``aero.QUADRATIC_COEFFICIENTS`` (C_D = a0 + a1 S + a2 S^2, C_L = b0 + b1 S + b2 S^2, S clipped
at s_max, plus for a Reynolds model the scale of its low-Re drag rise) by least squares; its
output is that model's row of the table. ``cross_validate`` judges a form by how it predicts
clubs it was not fitted to: leave one club out, and one tour fitted to predict the other.
"""

import math
import time
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from mcrun.api import conditions_inputs
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import APEX as APEX_FIELD
from mcrun.engine.schema import CARRY, pack
from mcrun.engine.schema import LANDING_ANGLE as LANDING_ANGLE_FIELD
from mcrun.engine.shot import DEFAULT_DT_S
from mcrun.physics import aero
from mcrun.physics.constants import DEG
from mcrun.quantities import DEFAULTS, InputError, check_range
from mcrun.run.monitors.native import check_field_counts
from mcrun.units import control_free, parse_quantity, shown

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
STANDARD_CONDITIONS = {
    name: DEFAULTS[name] for name in ("temperature_c", "pressure_pa", "relative_humidity")
}

# The names of the errors' rows that are not a tour's (and a transfer's "A->B").
RESERVED_TOURS = ("all", "fit (training)")
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
        names = pd.read_csv(path, comment="#", header=None, nrows=1, dtype=str)
    except FileNotFoundError:
        _fail(f"measured table {path}: no such file")
    except (OSError, UnicodeDecodeError) as err:
        _fail(f"measured table {path}: cannot read it ({err.__class__.__name__}: {err})")
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as err:
        _fail(f"measured table {path}: not a readable CSV ({err})")
    written = [str(c).strip() for c in names.iloc[0].fillna("")]
    twice = [c for k, c in enumerate(written) if c in written[:k]]
    if twice:  # (pandas read the second as 'carry_yd.1': the first was used, silently)
        _fail(f"measured table {path}: column {twice[0]} twice: allowed: each column once")
    missing = [c for c in MEASURED_COLUMNS if c not in written]
    if missing:
        _fail(
            f"measured table {path}: missing column(s) {', '.join(missing)}; "
            f"needs {', '.join(MEASURED_COLUMNS)}"
        )
    check_field_counts(path)  # (pandas took an extra field's row for an index: shifted)
    try:
        raw = pd.read_csv(path, comment="#", skipinitialspace=True)
    except (pd.errors.ParserError, pd.errors.EmptyDataError) as err:
        _fail(f"measured table {path}: not a readable CSV ({err})")
    raw.columns = [str(c).strip() for c in raw.columns]
    if raw.empty:
        _fail(f"measured table {path}: no rows")
    mph = parse_quantity("1 mph", "speed")
    rpm = parse_quantity("1 rpm", "spin")
    yd = parse_quantity("1 yd", "length")
    for column in ("tour", "club"):  # (an empty cell was the tour "nan", its rows NaN)
        empty = raw[column].isna().to_numpy() | (raw[column].astype(str).str.strip() == "")
        if empty.any():
            row = int(np.flatnonzero(empty)[0])
            _fail(f"measured table {path}, data row {row + 1}, column {column}: empty: allowed: "
                  "a name")  # fmt: skip
    frame = pd.DataFrame(
        {"tour": raw["tour"].astype(str).str.strip(), "club": raw["club"].astype(str).str.strip()}
    )
    for column in ("tour", "club"):  # (an escape sequence reached the terminal)
        bad = frame[column].map(lambda t: isinstance(t, str) and control_free(t) != t)
        if bad.any():
            row = int(np.flatnonzero(bad.to_numpy())[0])
            _fail(f"measured table {path}, data row {row + 1}, column {column}: "
                  f"{shown(frame[column].iloc[row])} holds control characters")  # fmt: skip
    # Launches must be inside the documented input ranges (quantities.RANGES); outcomes positive
    # and below what a golf shot reaches (500 yd of carry, 150 yd of apex), and the land angle
    # (above the horizontal) below 90 deg.
    for column, name, factor, checked in (
        ("ball_mph", "ball_speed_mps", mph, "ball_speed_mps"),
        ("launch_deg", "launch_angle_deg", 1.0, "launch_angle_deg"),
        ("spin_rpm", "spin_radps", rpm, "spin_radps"),
        ("carry_yd", "carry_m", yd, 500.0 * yd),
        ("max_height_yd", "apex_m", yd, 150.0 * yd),
        ("land_deg", "land_angle_deg", 1.0, 90.0),
    ):
        given = raw[column]  # (a cell TRUE or FALSE was read as 1 or 0)
        numeric = given.where(given.map(lambda v: not isinstance(v, bool | np.bool_)))
        values = pd.to_numeric(numeric, errors="coerce")
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
                elif not 0.0 < value < checked:
                    bound = f" and below {checked / factor:g}"
                    raise InputError(f"{value / factor:g} must be positive{bound}")
            except InputError as err:
                _fail(f"measured table {path}, data row {row + 1}, column {column}: {err}")
        frame[name] = values
    clubs = frame["tour"] + " " + frame["club"]
    # A club written twice, as "Driver" and "driver " (case and spacing apart, one club).
    keys = clubs.map(lambda t: " ".join(t.split()).casefold())
    again = keys.duplicated().to_numpy()
    if again.any():  # (a fold of the cross-validation would hold its copy: leaked)
        row = int(np.flatnonzero(again)[0])
        first = int(np.flatnonzero((keys == keys.iloc[row]).to_numpy())[0])
        _fail(f"measured table {path}, data rows {first + 1} and {row + 1}: "
              f"{shown(clubs.iloc[first])} and {shown(clubs.iloc[row])} are one club: allowed: "
              "each tour's club once")  # fmt: skip
    for column in ("tour", "club"):
        for k, name in enumerate(frame[column]):
            reserved = (column == "tour" and name in RESERVED_TOURS) or "->" in name
            if reserved:  # (the cross-validation's rows: one was written over the other)
                _fail(f"measured table {path}, data row {k + 1}, column {column}: {name!r} is a "
                      "name of the errors' rows ('all', 'fit (training)', 'A->B' a tour's fit on "
                      "another): allowed: another name")  # fmt: skip
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


# The forms ``fit`` refits, each the model of that name: the quadratic C_D(S), C_L(S) with s_max
# (7 unknowns), plus, for a Reynolds model, the scale of its low-Re drag rise (one more). The
# spin decay of each form is held at its published value (aero.QUADRATIC_COEFFICIENTS columns
# 9-10): Smits and Smith's k = 2e-5, or 4 % per second.
FORMS = {
    "trackman2019": (),
    "trackman2019_exp": (),
    "trackman2019_lyu": (aero.C_LYU,),
    "trackman2019_lyu_exp": (aero.C_LYU,),
    "trackman2019_ramp": (aero.C_RAMP,),
}
# Names, bounds and start values of the columns a form fits beside the quadratic. The starts are
# the published rises: Lyu et al.'s as measured, libgolf's C_D 0.2 -> 0.5.
EXTRA_COLUMNS = {
    aero.C_LYU: ("c_lyu", (0.0, 3.0), 1.0),
    aero.C_RAMP: ("c_ramp", (0.0, 1.0), 0.3),
}
QUADRATIC_NAMES = ("a0", "a1", "a2", "b0", "b1", "b2", "s_max")


def parameter_names(form):
    """Names of the fitted parameters of ``form``, in the order of ``FitResult.parameters``."""
    return QUADRATIC_NAMES + tuple(EXTRA_COLUMNS[c][0] for c in FORMS[form])


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
    form: str = "trackman2019"

    @property
    def parameters(self):
        """The fitted parameters, by name (``parameter_names``)."""
        columns = list(range(7)) + list(FORMS[self.form])
        return dict(zip(parameter_names(self.form), map(float, self.row[columns]), strict=True))


def _check_enough(frame, form, s_max=None, fold=""):
    """InputError where ``frame`` holds fewer measurements (three a club: carry, apex and land
    angle) than ``form`` has parameters to fit: a fit of one club printed a row to ship."""
    unknowns = len(parameter_names(form)) - (s_max is not None)
    least = -(-unknowns // 3)
    if len(frame) < least:
        raise InputError(
            f"{fold}{len(frame)} club(s) give {3 * len(frame)} measurements for the "
            f"{unknowns} parameters of {form}: allowed: at least {least} clubs"
            + (" in every fold" if fold else "")
        )


def _check_form(form):
    if form not in FORMS:
        _fail(f"cannot fit the form '{form}': choose one of {', '.join(FORMS)}")


def fit(frame, start="ferguson2022", s_max=None, form="trackman2019"):
    """Least-squares fit of a form's C_D(S, Re), C_L(S) to measured carry, apex and land angle.

    The residuals are scaled by CARRY_SCALE_M, APEX_SCALE_M and LAND_ANGLE_SCALE_DEG. The
    unknowns are C_D and C_L at S = 0.1, 0.3, 0.5 (the six coefficients of the quadratics, in a
    better-conditioned basis), each bounded to [0.05, 0.6], and s_max within S_MAX_BOUNDS, unless
    ``s_max`` is given (then it is held there, e.g. 0.75 as ferguson2022), and the scale of the
    form's low-Re drag rise, if it has one (``EXTRA_COLUMNS``). A penalty keeps C_D(S) and C_L(S)
    inside [0.05, 0.6] for all S in [0.05, 0.6], not only at the nodes. Deterministic: the same
    start gives the same row.

    Parameters
    ----------
    frame : DataFrame
        ``load_measured`` output.
    start : str
        A quadratic model whose row starts the fit (the rise starts at its published size).
    s_max : float, optional
        Hold the clip of S at this value instead of fitting it.
    form : str
        A key of ``FORMS``: the model whose row is fitted.

    Returns
    -------
    FitResult
        ``row`` = the form's row of ``aero.QUADRATIC_COEFFICIENTS`` rounded to 4 significant
        digits; ``before`` and ``after`` are ``errors`` of the start row and of the rounded row.
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
    _check_form(form)
    _check_enough(frame, form, s_max)
    target = aero.model_id(form)
    extras = FORMS[form]
    table = aero.QUADRATIC_COEFFICIENTS.copy()
    start_row = table[target].copy()
    start_row[:7] = table[aero.model_id(start)][:7]
    for column in extras:
        start_row[column] = EXTRA_COLUMNS[column][2]
    lo, hi = COEFFICIENT_BAND
    x0 = _node_values(start_row)
    lower = np.full(6, lo)
    upper = np.full(6, hi)
    if s_max is None:
        x0 = np.append(x0, start_row[6])
        lower = np.append(lower, S_MAX_BOUNDS[0])
        upper = np.append(upper, S_MAX_BOUNDS[1])
    n_quadratic = x0.size
    for column in extras:
        _, (a, b), _ = EXTRA_COLUMNS[column]
        x0 = np.append(x0, start_row[column])
        lower = np.append(lower, a)
        upper = np.append(upper, b)
    x0 = np.clip(x0, lower + 1e-9, upper - 1e-9)

    def make_row(x):
        row = start_row.copy()
        row[:7] = _row_from_unknowns(x[:n_quadratic], s_max)
        for j, column in enumerate(extras):
            row[column] = x[n_quadratic + j]
        return row

    def residuals(x):
        row = make_row(x)
        table[target] = row
        simulated = predict(form, frame, table)
        res = _scaled_residuals(frame, simulated)
        # A shot that does not land (absurd coefficients) counts as far off.
        res = np.where(np.isfinite(res), res, 1e3)
        # Penalty, zero inside the band: 0.001 out of the band weighs as one scale unit.
        return np.append(res, band_violation(row) / 1e-3)

    table[target] = start_row
    before = errors(form, frame, table)
    began = time.perf_counter()
    solution = least_squares(
        residuals,
        x0,
        bounds=(lower, upper),
        method="trf",
        diff_step=1e-6,
        x_scale=np.maximum(np.abs(x0), 0.05),
        xtol=1e-10,
        ftol=1e-10,
    )
    seconds = time.perf_counter() - began
    row = round_significant(make_row(solution.x), 4)
    table[target] = row
    after = errors(form, frame, table)
    return FitResult(
        row=row,
        start=start,
        s_max_fitted=s_max is None,
        seconds=seconds,
        evaluations=int(solution.nfev),
        before=Errors(start, before.per_club, before.rmse),
        after=after,
        message=str(solution.message),
        form=form,
    )


def row_literal(row):
    """The row as Python source, to paste into ``aero.QUADRATIC_COEFFICIENTS``."""
    return "[" + ", ".join(f"{v:.4g}" for v in row) + "],"


# --- cross-validation ----------------------------------------------------------------------


@dataclass(frozen=True)
class CrossValidation:
    """How a form predicts clubs it was not fitted to.

    ``held_out``: one row per club of the table, the error (simulated - measured) of its carry
    (m), apex (m) and land angle (deg) when the form is fitted to the other 22 clubs (leave one
    club out). ``rmse``: RMSE and bias of those errors per tour and overall, and the RMSE of the
    tour transfers (fit on one tour, predict the other; rows 'PGA->LPGA' and 'LPGA->PGA').
    ``parameters``: the fitted parameters of every fold (rows: the club left out, then the two
    transfers, then 'all', the fit to every club). ``seconds``: time of all the fits.
    """

    form: str
    held_out: pd.DataFrame
    rmse: pd.DataFrame
    parameters: pd.DataFrame
    seconds: float


def _rmse_row(errors_frame):
    row = {}
    for name, unit in (("carry", "m"), ("apex", "m"), ("land_angle", "deg")):
        err = errors_frame[f"{name}_error_{unit}"].to_numpy()
        row[f"{name}_rmse_{unit}"] = float(np.sqrt(np.mean(err**2)))
        row[f"{name}_bias_{unit}"] = float(np.mean(err))
    return row


def cross_validate(frame, form="trackman2019", start="ferguson2022"):
    """Cross-validate ``form``: leave one club out (each of the table's rows in turn), and fit
    on one tour to predict the other. Every fold is fitted from the same start (``fit``).

    Returns
    -------
    CrossValidation
    """
    _check_form(form)
    _check_enough(frame.iloc[1:], form, fold="cross-validation: ")
    tours = list(dict.fromkeys(frame["tour"]))
    if len(tours) == 2:  # each tour's fit predicts the other (checked before any fold)
        for tour in tours:
            _check_enough(frame[frame["tour"] == tour], form,
                          fold=f"cross-validation, the fit on tour {tour} alone: ")  # fmt: skip
    began = time.perf_counter()
    target = aero.model_id(form)
    names = parameter_names(form)
    held_out = []
    parameters = {}

    def predict_with(result, rows):
        table = aero.QUADRATIC_COEFFICIENTS.copy()
        table[target] = result.row
        return errors(form, rows, table).per_club

    for i in range(len(frame)):
        keep = frame.drop(index=frame.index[i])
        result = fit(keep, start=start, form=form)
        held_out.append(predict_with(result, frame.iloc[[i]]))
        label = f"{frame['tour'].iloc[i]} {frame['club'].iloc[i]}"
        parameters[label] = [result.parameters[n] for n in names]
    held_out = pd.concat(held_out, ignore_index=True)
    rows = {}
    tours = list(dict.fromkeys(frame["tour"]))
    for tour in [*tours, "all"]:
        pick = held_out if tour == "all" else held_out[held_out["tour"] == tour]
        rows[tour] = _rmse_row(pick)
    if len(tours) == 2:
        for a, b in (tours, tours[::-1]):
            result = fit(frame[frame["tour"] == a], start=start, form=form)
            rows[f"{a}->{b}"] = _rmse_row(predict_with(result, frame[frame["tour"] == b]))
            parameters[f"{a}->{b}"] = [result.parameters[n] for n in names]
    result = fit(frame, start=start, form=form)
    parameters["all"] = [result.parameters[n] for n in names]
    rows["fit (training)"] = _rmse_row(result.after.per_club)
    rmse = pd.DataFrame.from_dict(rows, orient="index")
    rmse.index.name = "fold"
    parameters = pd.DataFrame.from_dict(parameters, orient="index", columns=list(names))
    parameters.index.name = "fold"
    return CrossValidation(form, held_out, rmse, parameters, seconds=time.perf_counter() - began)


def parameter_stability(cv):
    """Mean, standard deviation and range of each fitted parameter over the leave-one-club-out
    folds, and the largest relative change of C_D and C_L (at S = 0.1, 0.3, 0.5) between a fold
    and the fit to every club: how much one club moves the fit."""
    folds = cv.parameters.drop(index=["all", *[i for i in cv.parameters.index if "->" in i]])
    summary = pd.DataFrame(
        {
            "all": cv.parameters.loc["all"],
            "mean": folds.mean(),
            "std": folds.std(ddof=0),
            "min": folds.min(),
            "max": folds.max(),
        }
    )
    return summary
