"""A replayed session per club: the spread of each club (a gapping table) and how the model
flies the shots against the device that measured them.

Both read the frame of ``mcrun.run.replay.replay``: its ``club`` column (or one group, "all",
where the file names no club), the outcome of the shots that ended ``ok`` and the
``model_minus_device_*`` columns. Everything is in SI, the unit in the column names.
"""

import numpy as np
import pandas as pd

from mcrun import status
from mcrun.quantities import InputError
from mcrun.units import shown

ALL = "all"
"""The group of every shot, in the comparison; and the one club of a file without clubs."""

# Quantities of the per-club summary: (name in the summary, column of the replay frame).
SPREAD = (("carry_m", "carry_m"), ("total_m", "total_m"), ("side_m", "final_y_m"))
PERCENTILES = (10, 50, 90)


def _check(frame, columns=("status",)):
    """InputError, one line, unless ``frame`` is a DataFrame with ``columns``."""
    allowed = "allowed: the frame of mcrun.run.replay.replay"
    if not isinstance(frame, pd.DataFrame):
        raise InputError(f"frame {shown(frame)}: {allowed}")
    missing = [c for c in columns if c not in frame.columns]
    if missing:
        raise InputError(f"frame: no column {missing[0]!r}: {allowed}")


NO_CLUB = "(no club)"
"""The group of the shots whose club is missing or blank in a file that names clubs."""


def club_labels(frame):
    """The club of each row of a replay frame, as text (NO_CLUB where missing or blank: a row
    of no name in the tables before; ALL without clubs)."""
    _check(frame)
    if "club" in frame:
        names = frame["club"].astype("string")
        blank = (names.isna() | (names.str.strip() == "")).to_numpy(dtype=bool)
        return np.where(blank, NO_CLUB, names.fillna("").to_numpy(dtype=object))
    return np.full(len(frame), ALL, dtype=object)


def club_summary(frame):
    """One row per club, longest mean carry first: shots, shots ok, and of the shots ok the
    mean, sd (n - 1) and 10th, 50th, 90th percentiles of carry, total and side (the rest
    position, positive right), and ``gap_m``: the club's mean carry minus the next club's."""
    _check(frame, ("status", *(column for _, column in SPREAD)))
    clubs = club_labels(frame)
    ok = frame["status"].to_numpy() == status.OK
    rows = []
    if not len(frame):  # (a club chosen that the session does not hold)
        parts = ("mean", "sd", *(f"p{p}" for p in PERCENTILES))
        names = [f"{name}_{part}" for name, _ in SPREAD for part in parts]
        return pd.DataFrame(columns=["club", "shots", "shots_ok", *names, "gap_m"])
    for club in dict.fromkeys(clubs):
        mine = clubs == club
        row = {"club": club, "shots": int(mine.sum()), "shots_ok": int((mine & ok).sum())}
        for name, column in SPREAD:
            values = frame[column].to_numpy(dtype=float)[mine & ok]
            some = values.size > 0
            row[f"{name}_mean"] = float(values.mean()) if some else np.nan
            row[f"{name}_sd"] = float(values.std(ddof=1)) if values.size > 1 else np.nan
            for p in PERCENTILES:
                row[f"{name}_p{p}"] = float(np.percentile(values, p)) if some else np.nan
        rows.append(row)
    table = pd.DataFrame(rows).sort_values("carry_m_mean", ascending=False, kind="stable")
    table["gap_m"] = table["carry_m_mean"] - table["carry_m_mean"].shift(-1)
    return table.reset_index(drop=True)


def device_comparison(frame):
    """The model minus the device, per club and for all shots (club "all"), per quantity the
    device gives: shots compared (ok, and measured by the device), bias (mean difference) and
    RMSE. Empty when the file holds none of the device's results."""
    club_labels(frame)  # (a frame it can read)
    columns = [c for c in frame.columns if str(c).startswith("model_minus_device_")]
    if not columns:
        return pd.DataFrame(columns=["club", "quantity", "shots", "bias", "rmse"])
    clubs = club_labels(frame)
    ok = frame["status"].to_numpy() == status.OK
    groups = [(ALL, np.ones(len(frame), dtype=bool))]
    if "club" in frame:
        groups += [(club, clubs == club) for club in dict.fromkeys(clubs)]
    rows = []
    for club, mine in groups:
        for column in columns:
            diff = frame[column].to_numpy(dtype=float)[mine & ok]
            diff = diff[np.isfinite(diff)]
            rows.append(
                {
                    "club": club,
                    "quantity": column.removeprefix("model_minus_device_"),
                    "shots": diff.size,
                    "bias": float(diff.mean()) if diff.size else np.nan,
                    "rmse": float(np.sqrt(np.mean(diff**2))) if diff.size else np.nan,
                }
            )
    return pd.DataFrame(rows)
