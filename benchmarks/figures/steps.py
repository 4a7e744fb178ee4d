"""Accuracy vs step: carry and total error against DOP853 versus the RK4 step, for a driver, a
7-iron and a pitching wedge (the TrackMan 2019 PGA Tour averages), and the kernel's speed at
each step: what the default step is chosen from."""

import math
from importlib import resources

import numpy as np

from benchmarks.common import MPH, RPM, best_of, cm, outputs, rate, threads_available, timing
from benchmarks.reference import reference_shot
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import CARRY, COLUMN, STATUS, TOTAL
from mcrun.engine.shot import DEFAULT_DT_S
from mcrun.physics import aero
from mcrun.status import NAMES as STATUS_NAMES

TRACKMAN = resources.files("mcrun") / "data" / "trackman_tour_averages_2019.csv"
STEP_SHOTS = (("PGA", "Driver"), ("PGA", "7-iron"), ("PGA", "PW"))


def trackman_shots():
    """(label, ball speed m/s, launch angle rad, spin rad/s) of the STEP_SHOTS clubs."""
    with TRACKMAN.open() as f:
        lines = [line for line in f if not line.startswith("#")]
    header = lines[0].strip().split(",")
    table = {}
    for line in lines[1:]:
        record = dict(zip(header, line.strip().split(","), strict=True))
        table[(record["tour"], record["club"])] = record
    shots = []
    for key in STEP_SHOTS:
        r = table[key]
        shots.append(
            (
                f"{key[0]} {key[1]}",
                float(r["ball_mph"]) * MPH,
                math.radians(float(r["launch_deg"])),
                float(r["spin_rpm"]) * RPM,
            )
        )
    return shots


def measure(config, inputs):
    """Carry and total error vs the RK4 step, and the kernel's speed at each step."""
    template = inputs.first(1)[0]
    # The reference (reference.py) flies the quadratic models; the Reynolds models' steps,
    # the default's among them, are checked against DOP853 in tests/test_accuracy.py.
    model = aero.model_id("trackman2019")
    shots = []
    for label, speed, angle, spin in trackman_shots():
        row = template.copy()
        row[COLUMN["ball_speed_mps"]] = speed
        row[COLUMN["launch_angle_rad"]] = angle
        row[COLUMN["spin_radps"]] = spin
        row[COLUMN["azimuth_rad"]] = 0.0
        row[COLUMN["spin_axis_rad"]] = 0.0
        row[COLUMN["aero_model"]] = model
        ref = reference_shot(row)
        shots.append((label, row, ref))

    rate_rows = inputs.first(config.step_rate_n)
    rate_out = outputs(rate_rows.shape[0])
    simulate_batch(inputs.first(1000), outputs(1000))

    table = []
    for dt in config.step_dts:
        grid = np.asfortranarray(np.stack([row for _, row, _ in shots]))
        grid[:, COLUMN["dt_s"]] = dt
        out = simulate_batch(grid)
        entry = {"dt_s": dt, "carry_error_cm": {}, "total_error_cm": {}, "status": {}}
        for k, (label, _, ref) in enumerate(shots):
            entry["carry_error_cm"][label] = 100.0 * abs(out[k, CARRY] - ref["carry_m"])
            entry["total_error_cm"][label] = 100.0 * abs(out[k, TOTAL] - ref["total_m"])
            entry["status"][label] = STATUS_NAMES.get(int(out[k, STATUS]), "?")
        rate_rows[:, COLUMN["dt_s"]] = dt
        times = best_of(
            {dt: lambda: simulate_batch(rate_rows, rate_out)}, config.repeats, config.budget_s
        )
        entry.update({"kernel_" + k: v for k, v in timing(rate_rows.shape[0], times[dt]).items()})
        table.append(entry)
    return {
        "model": aero.DEFAULT_MODEL,
        "default_dt_s": DEFAULT_DT_S,
        "conditions": "pga-driver scenario's air and turf (20 C, sea level, 50 % humidity, "
        "fairway preset), no wind, no spin axis",
        "shots": [
            {
                "label": label,
                "ball_speed_mps": row[COLUMN["ball_speed_mps"]],
                "launch_angle_deg": math.degrees(row[COLUMN["launch_angle_rad"]]),
                "spin_rpm": row[COLUMN["spin_radps"]] / RPM,
                "reference_carry_m": ref["carry_m"],
                "reference_total_m": ref["total_m"],
            }
            for label, row, ref in shots
        ],
        "threads": threads_available(),
        "rows": table,
    }


def targets(r):
    return []


def markdown(r):
    labels = [s["label"] for s in r["shots"]]
    short = [label.split(" ", 1)[1] for label in labels]
    lines = [
        f"### Accuracy vs step: RK4 with {r['model']}, error against DOP853 (rtol 1e-12), in cm",
        "",
        "Shots: the TrackMan 2019 PGA Tour averages ("
        + "; ".join(
            f"{s['label']}: {s['ball_speed_mps'] / MPH:.0f} mph, {s['launch_angle_deg']:.1f} deg, "
            f"{s['spin_rpm']:.0f} rpm, carry {s['reference_carry_m']:.2f} m, "
            f"total {s['reference_total_m']:.2f} m"
            for s in r["shots"]
        )
        + f"), {r['conditions']}. Total = flight + the kernel's run from that landing. "
        f"Speed: the kernel on pga-driver shots, {r['threads']} threads.",
        "",
        "| dt (s) | "
        + " | ".join(f"{s} carry" for s in short)
        + " | "
        + " | ".join(f"{s} total" for s in short)
        + " | kernel shots/s |",
        "|---" * (2 + 2 * len(labels)) + "|",
    ]
    for row in r["rows"]:
        mark = " (default)" if row["dt_s"] == r["default_dt_s"] else ""
        lines.append(
            f"| {row['dt_s']:g}{mark} | "
            + " | ".join(cm(row["carry_error_cm"][k]) for k in labels)
            + " | "
            + " | ".join(cm(row["total_error_cm"][k]) for k in labels)
            + f" | {rate(row['kernel_shots_per_s'])} |"
        )
    return lines
