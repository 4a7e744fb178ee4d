"""``mcrun calibrate``: the aerodynamic models against measured tour averages, or the refit of
one (``mcrun.calibrate``), as tables or JSON."""

import json

from mcrun.calibrate import (
    APEX_SCALE_M,
    BAND_SPIN_RATIOS,
    CARRY_SCALE_M,
    COEFFICIENT_BAND,
    COMPARED_MODELS,
    FORMS,
    LAND_ANGLE_SCALE_DEG,
    cross_validate,
    curves,
    errors,
    fit,
    load_measured,
    parameter_stability,
    row_literal,
)
from mcrun.cli.options import aero_model
from mcrun.physics import aero
from mcrun.quantities import InputError


def _records(frame):
    return json.loads(frame.to_json(orient="records"))


def _rmse_json(rmse):
    return {tour: {k: float(v) for k, v in row.items()} for tour, row in rmse.iterrows()}


def format_per_club(result):
    """Per-club error table of one model, as text."""
    p = result.per_club
    lines = [
        f"Model {result.model}: simulated - measured, per club",
        f"{'tour':<5} {'club':<7} | {'carry (m)':^23} | {'apex (m)':^20} | "
        f"{'land angle (deg)':^20}",
        f"{'':<5} {'':<7} | {'meas':>7} {'sim':>7} {'err':>7} | {'meas':>6} {'sim':>6} "
        f"{'err':>6} | {'meas':>6} {'sim':>6} {'err':>6}",
    ]
    for r in p.itertuples(index=False):
        lines.append(
            f"{r.tour:<5} {r.club:<7} | {r.carry_measured_m:7.1f} {r.carry_simulated_m:7.1f} "
            f"{r.carry_error_m:+7.1f} | {r.apex_measured_m:6.1f} {r.apex_simulated_m:6.1f} "
            f"{r.apex_error_m:+6.1f} | {r.land_angle_measured_deg:6.1f} "
            f"{r.land_angle_simulated_deg:6.1f} {r.land_angle_error_deg:+6.1f}"
        )
    return "\n".join(lines)


def format_rmse(results):
    """RMSE (and bias) per model and tour, as text; ``results`` maps model -> Errors."""
    lines = [
        f"{'model':<16} {'tour':<5} | {'carry RMSE (m)':>14} {'bias':>6} | "
        f"{'apex RMSE (m)':>13} {'bias':>6} | {'land RMSE (deg)':>15} {'bias':>6} | "
        f"{'scaled RMS':>10}"
    ]
    for model, result in results.items():
        for tour, r in result.rmse.iterrows():
            lines.append(
                f"{model:<16} {tour:<5} | {r.carry_rmse_m:14.2f} {r.carry_bias_m:+6.2f} | "
                f"{r.apex_rmse_m:13.2f} {r.apex_bias_m:+6.2f} | "
                f"{r.land_angle_rmse_deg:15.2f} {r.land_angle_bias_deg:+6.2f} | "
                f"{r.scaled_rms:10.3f}"
            )
    lines.append(
        f"bias = mean(simulated - measured); scaled RMS = RMS of all residuals in units of "
        f"{CARRY_SCALE_M:g} m carry, {APEX_SCALE_M:g} m apex, {LAND_ANGLE_SCALE_DEG:g} deg land "
        f"angle (lower is better)"
    )
    return "\n".join(lines)


def format_fit(result):
    """Summary of a fit, as text, ending with the row to paste into aero.py."""
    fitted = "fitted" if result.s_max_fitted else "held"
    cd, cl = curves(result.row, BAND_SPIN_RATIOS)
    rise = {(): "", (aero.C_LYU,): " + c_lyu D_lyu(Re)", (aero.C_RAMP,): " + c_ramp D_ramp(Re)"}
    lines = [
        f"Fit of {result.form}: C_D = a0 + a1 S + a2 S^2{rise[FORMS[result.form]]}, "
        f"C_L = b0 + b1 S + b2 S^2 (S clipped at s_max, {fitted})"
        f" from {result.start}: {result.evaluations} evaluations, {result.seconds:.2f} s",
        "  " + "  ".join(f"{n} = {v:.4g}" for n, v in result.parameters.items()),
        f"  over S in [0.05, 0.6]: C_D {cd.min():.3f}-{cd.max():.3f}, "
        f"C_L {cl.min():.3f}-{cl.max():.3f} (band {COEFFICIENT_BAND[0]:g}-{COEFFICIENT_BAND[1]:g})",
        "",
        format_rmse({f"{result.start}": result.before, "fitted": result.after}),
        "",
        f"Row for aero.QUADRATIC_COEFFICIENTS ({result.form}):",
        f"        {row_literal(result.row)}",
    ]
    return "\n".join(lines)


def format_cv(cv):
    """Cross-validation of one form, as text: RMSE and bias of the held-out predictions, the
    error of each club when left out, and the fitted parameters across the folds."""
    lines = [
        f"Form {cv.form}: cross-validated (each fold fitted afresh; {cv.seconds:.0f} s)",
        f"{'fold':<16} | {'carry RMSE (m)':>14} {'bias':>6} | {'apex RMSE (m)':>13} {'bias':>6} | "
        f"{'land RMSE (deg)':>15} {'bias':>6}",
    ]
    labels = {"all": "left out, all", "PGA": "left out, PGA", "LPGA": "left out, LPGA"}
    for fold, r in cv.rmse.iterrows():
        lines.append(
            f"{labels.get(fold, fold):<16} | {r.carry_rmse_m:14.2f} {r.carry_bias_m:+6.2f} | "
            f"{r.apex_rmse_m:13.2f} {r.apex_bias_m:+6.2f} | "
            f"{r.land_angle_rmse_deg:15.2f} {r.land_angle_bias_deg:+6.2f}"
        )
    lines += ["", "Each club predicted by the fit to the other clubs (simulated - measured):"]
    lines.append(
        f"{'tour':<5} {'club':<7} | {'carry (m)':>9} | {'apex (m)':>8} | {'land (deg)':>10}"
    )
    for r in cv.held_out.itertuples(index=False):
        lines.append(
            f"{r.tour:<5} {r.club:<7} | {r.carry_error_m:+9.2f} | {r.apex_error_m:+8.2f} | "
            f"{r.land_angle_error_deg:+10.2f}"
        )
    stability = parameter_stability(cv)
    lines += ["", "Fitted parameters: all clubs, and over the leave-one-club-out folds:"]
    lines.append(f"{'':<7} {'all':>9} {'mean':>9} {'std':>9} {'min':>9} {'max':>9}")
    for name, r in stability.iterrows():
        lines.append(
            f"{name:<7} {r['all']:9.4g} {r['mean']:9.4g} {r['std']:9.3g} {r['min']:9.4g} "
            f"{r['max']:9.4g}"
        )
    return "\n".join(lines)


def _cmd_calibrate(args):
    """Run ``mcrun calibrate``; returns the exit code (bad input raises InputError)."""
    if args.form is not None and not args.fit:
        raise InputError("--form: is for --fit (the form it refits)")
    aero_model(args.model, "--model")
    frame = load_measured(args.data)
    output = {}
    text = []
    if args.fit:
        form = args.form or (aero.DEFAULT_MODEL if aero.DEFAULT_MODEL in FORMS else "trackman2019")
        result = fit(frame, form=form)
        output["fit"] = {
            "form": result.form,
            "start": result.start,
            "s_max_fitted": result.s_max_fitted,
            "seconds": result.seconds,
            "evaluations": result.evaluations,
            "parameters": result.parameters,
            "row": [float(v) for v in result.row],
            "rmse_before": _rmse_json(result.before.rmse),
            "rmse_after": _rmse_json(result.after.rmse),
        }
        text.append(format_fit(result))
    if args.cv is not None:
        forms = args.cv or list(FORMS)
        output["cv"] = {}
        for form in forms:
            cv = cross_validate(frame, form=form)
            output["cv"][form] = {
                "rmse": _rmse_json(cv.rmse),
                "held_out": _records(cv.held_out),
                "parameters": {
                    fold: {k: float(v) for k, v in row.items()}
                    for fold, row in cv.parameters.iterrows()
                },
                "seconds": cv.seconds,
            }
            text.append(format_cv(cv))
    if args.compare:
        results = {m: errors(m, frame) for m in COMPARED_MODELS}
        output["compare"] = {m: _rmse_json(r.rmse) for m, r in results.items()}
        text.append(format_rmse(results))
    if not (args.fit or args.compare or args.cv is not None):
        result = errors(args.model, frame)
        output["model"] = args.model
        output["per_club"] = _records(result.per_club)
        output["rmse"] = _rmse_json(result.rmse)
        text.append(format_per_club(result) + "\n\n" + format_rmse({args.model: result}))
    if args.json:
        print(json.dumps(output, indent=2))
    else:
        print("\n\n".join(text))
    return 0


def register(subparsers):
    """Add the ``calibrate`` subcommand to an argparse subparsers object."""
    parser = subparsers.add_parser(
        "calibrate",
        help="compare the aerodynamic models with measured tour averages, or refit one",
        description=(
            "Fly the launches of a table of measured tour averages (default: TrackMan 2019 PGA "
            "and LPGA) in standard air (20 C, 101325 Pa, 50 % RH, no wind) and compare carry, "
            "apex and land angle with the measured ones."
        ),
    )
    parser.add_argument(
        "--data",
        metavar="PATH",
        default=None,
        help="CSV of measured averages (default: the shipped TrackMan 2019 table)",
    )
    parser.add_argument(
        "--model",
        default=aero.DEFAULT_MODEL,
        help=f"model of the per-club error table (default {aero.DEFAULT_MODEL})",
    )
    parser.add_argument(
        "--compare", action="store_true", help="RMSE of every model, per tour and overall"
    )
    parser.add_argument(
        "--fit",
        action="store_true",
        help="refit a form (--form) from ferguson2022 and print its row for aero.py",
    )
    parser.add_argument(
        "--form",
        choices=list(FORMS),
        help="the form --fit refits (default: the default model's)",
    )
    parser.add_argument(
        "--cv",
        nargs="*",
        choices=list(FORMS),
        metavar="FORM",
        default=None,
        help="cross-validate forms (default all): leave one club out, and fit one tour to "
        f"predict the other; forms: {', '.join(FORMS)}",
    )
    parser.add_argument("--json", action="store_true", help="print JSON instead of tables")
    parser.set_defaults(func=_cmd_calibrate)
