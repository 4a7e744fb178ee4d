"""Expected strokes left after each shot of a run on a hole, the strokes gained by it, and per
point their means with standard errors and the part of each outcome in them.

The rules (docs/strokes.md):

- the next shot's lie is that of the zone the ball finished in (``LIE_OF_ZONE``: fringe and a
  tee other than the start are played as fairway, a bunker as sand), which ``lie_of_zone``
  overrides (e.g. ``{"rough": "recovery"}`` under trees); its distance the ball's to the pin;
- a penalty area (Rule 17.1d; its kind is the finish zone: ``water`` red, ``water_yellow``
  yellow; a ball whose finish zone names neither is in a red one): one penalty stroke, then the
  best of the relief its colour allows, from the point where the ball last crossed into it (the
  reference point, penalty_x_m, penalty_y_m):
  - stroke and distance (both colours): the shot again from its start;
  - back on the line (both colours, with a hole): a drop on the line from the pin through the
    reference point, as far behind it as the player likes; the distance chosen is the one of
    least expected strokes among the points every ``BACK_STEP_M`` from ``BACK_STEP_M`` to
    ``BACK_MAX_M`` behind it that are in play on the hole (not a penalty area, out of bounds or
    off the grid), each valued with the lie of its zone (``LIE_OF_ZONE``, overrides applied)
    and its distance to the pin;
  - lateral (red only): a drop at the reference point (its distance to the pin, as the drop is
    within two club lengths no nearer the hole), from the fairway when that point is on mown
    grass (fairway, tee, fringe or green) and from the rough otherwise (without a hole: the
    rough);
- out of bounds (Rule 18.2) and off the hole's map: stroke and distance, 1 + E(start);
- other statuses (the kernel's bounds: invalid_input, not_landed, too_many_bounces,
  not_stopped) are left out of the means and counted (``n_failed``).

Strokes gained by a shot = E(start) - 1 - E(after), E(after) including the penalty stroke.
"""

import math

import numpy as np
import pandas as pd

from mcrun import status
from mcrun.hole.zones import LIE_OF_ZONE, MOWN_ZONES, PENALTY_ZONES, ZONE_KINDS
from mcrun.strokes.baseline import LIES, tour_baseline

__all__ = [
    "LIE_OF_ZONE",
    "OUTCOMES",
    "PUTTING_COLUMNS",
    "SHOT_COLUMNS",
    "check_lie_of_zone",
    "point_strokes",
    "score_shots",
    "start_of",
]

# The lie of the next shot from each zone the ball can stay in (``hole.zones.ZONES``).
IN_PLAY_ZONES = tuple(LIE_OF_ZONE)
# Where a water ball's reference point lies on mown grass, it is dropped on the fairway.
_MOWN = MOWN_ZONES
OUTCOMES = (*IN_PLAY_ZONES, *PENALTY_ZONES, "out_of_bounds", "off_map")
# The penalty areas with a lateral drop (Rule 17.1d(3)): red ones.
LATERAL_ZONES = ("water",)
# Back on the line: the drops looked at, every BACK_STEP_M up to BACK_MAX_M behind the
# reference point (m), and how many water balls are valued at a time.
BACK_STEP_M = 1.0
BACK_MAX_M = 100.0
_BACK_CHUNK = 8192
FAILED = "failed"

SHOT_COLUMNS = (
    "outcome",  # the finish zone, or water / out_of_bounds / off_map; failed: left out
    "lie_after",  # the lie of the next shot (LIES)
    "distance_after_m",  # its distance to the pin (m)
    "penalty_strokes",
    "expected_strokes_after",  # strokes still to play after the shot, penalty included
    "strokes_gained",  # E(start) - 1 - expected_strokes_after
    "lie_cost_strokes",  # expected_strokes_after - E(the same distance from fairway / green)
)


def check_lie_of_zone(overrides, where="lie_of_zone"):
    """``LIE_OF_ZONE`` with ``overrides`` ({zone: lie}) applied; ValueError, one line, for a
    zone that is not in play or a lie that is not one of ``LIES``."""
    lies = dict(LIE_OF_ZONE)
    for zone, lie in (overrides or {}).items():
        if zone not in LIE_OF_ZONE:
            raise ValueError(f"{where}: zone {zone!r}: allowed: {', '.join(IN_PLAY_ZONES)}")
        if lie not in LIES:
            raise ValueError(f"{where}.{zone}: lie {lie!r}: allowed: {', '.join(LIES)}")
        lies[zone] = lie
    return lies


def start_of(hole, start_xy_m=(0.0, 0.0), codes=False):
    """(lie, distance_m) of a shot from ``start_xy_m`` on the hole (its frame; default the
    tee, (0, 0)): "tee" on a tee, else the lie of the zone there; the distance to the pin.
    With arrays of x and y (one start a shot), arrays of lies and distances; with ``codes``,
    the lies as their index in ``LIES`` (what ``score_shots`` takes fastest)."""
    x, y = (np.asarray(v, dtype=float) for v in start_xy_m)
    lies = _START_LIE_CODE[hole.zone_at(np.atleast_1d(x), np.atleast_1d(y))]
    distance = np.hypot(x - hole.pin_xy[0], y - hole.pin_xy[1])
    if not codes:
        lies = np.array(LIES)[lies]
    if x.ndim == 0:
        return (int(lies[0]) if codes else str(lies[0])), float(distance)
    return lies, distance


# The lie of a shot struck from each zone (by code; the last: off the grid, the rough).
_START_LIE_CODE = np.array(
    [LIES.index("tee" if zone == "tee" else LIE_OF_ZONE.get(zone, "rough")) for zone in ZONE_KINDS]
    + [LIES.index("rough")]
)


FINISH_ZONES = (*ZONE_KINDS, "off_map")  # the finish zones a shot can have (``results.on_hole``)


def _codes(values, names):
    """The index in ``names`` of each value of a column of strings (pandas, pyarrow, numpy;
    categorical or not); -1 where missing or not one of them."""
    if hasattr(values, "to_pandas"):
        values = values.to_pandas()
    if isinstance(values, pd.Series):
        values = values.array
    if isinstance(values, pd.Categorical):
        return np.asarray(values.set_categories(list(names)).codes, dtype=np.int64)
    return np.asarray(pd.Categorical(np.asarray(values, dtype=object), categories=list(names))
                      .codes, dtype=np.int64)  # fmt: skip


def _floats(shots, name, n):
    """The column ``name`` as float64; NaN when the table has none."""
    if name not in shots:
        return np.full(n, np.nan)
    values = shots[name]
    if hasattr(values, "to_pylist"):
        values = values.to_numpy(zero_copy_only=False)
    return np.asarray(values, dtype=float)


def _outcome_codes(shots):
    """The outcome of each shot as its index in OUTCOMES (-1: FAILED), from its status and
    finish zone."""
    zone = _codes(shots["finish_zone"], FINISH_ZONES)
    if "status" in shots:
        state = np.asarray(shots["status"], dtype=np.int64)  # the codes themselves
    else:
        names = _codes(shots["status_name"], tuple(status.NAMES.values()))
        state = np.where(names >= 0, np.array(list(status.NAMES))[names], -1)
    code_of = {name: code for code, name in status.NAMES.items()}
    ok = state == code_of[status.NAMES[status.OK]]
    outcome = np.full(len(zone), -1, dtype=np.int64)
    for z in (*IN_PLAY_ZONES, *PENALTY_ZONES, "out_of_bounds"):
        outcome[ok & (zone == FINISH_ZONES.index(z))] = OUTCOMES.index(z)
    # A ball in a penalty area: the kind its finish zone names, else red (Rule 17.1).
    in_area = state == code_of[status.NAMES[status.IN_PENALTY_AREA]]
    outcome[in_area] = OUTCOMES.index("water")
    for z in PENALTY_ZONES:
        outcome[in_area & (zone == FINISH_ZONES.index(z))] = OUTCOMES.index(z)
    outcome[state == code_of[status.NAMES[status.OUT_OF_BOUNDS_STATUS]]] = OUTCOMES.index(
        "out_of_bounds"
    )
    off_map = zone == FINISH_ZONES.index("off_map")
    off = (state == code_of[status.NAMES[status.OFF_MAP]]) | (ok & off_map)
    outcome[off] = OUTCOMES.index("off_map")
    return outcome


def _outcomes(shots):
    """The outcome of each shot (OUTCOMES or FAILED) from its status and finish zone."""
    return np.array([*OUTCOMES, FAILED], dtype=object)[_outcome_codes(shots)]


def _back_on_the_line(hole, base, lies, rx, ry, pin_x, pin_y):
    """Back-on-the-line relief (Rule 17.1d(2)) of balls that crossed into a penalty area at
    (rx, ry): (expected strokes, lie code in LIES, distance to the pin (m)) of the best drop on
    the line from the pin through (rx, ry), BACK_STEP_M to BACK_MAX_M behind (rx, ry) every
    BACK_STEP_M, among the points in play on ``hole`` (each with the lie of its zone, ``lies``,
    and its distance to the pin); inf (and the lie -1) where no point of the line is in play."""
    behind = np.arange(BACK_STEP_M, BACK_MAX_M + 0.5 * BACK_STEP_M, BACK_STEP_M)
    lie_of_code = np.array(
        [LIES.index(lies[k]) if k in lies else -1 for k in ZONE_KINDS] + [-1], dtype=np.int64
    )  # the last entry: off the grid (zone_at's -1)
    e = np.full(len(rx), np.inf)
    lie = np.full(len(rx), -1, dtype=np.int64)
    distance = np.full(len(rx), np.nan)
    for start in range(0, len(rx), _BACK_CHUNK):
        part = slice(start, start + _BACK_CHUNK)
        dx, dy = rx[part] - pin_x, ry[part] - pin_y
        d0 = np.hypot(dx, dy)
        ux, uy = dx / np.maximum(d0, 1e-9), dy / np.maximum(d0, 1e-9)
        d = d0[:, None] + behind[None, :]  # to the pin, along the line
        codes = lie_of_code[hole.zone_at(pin_x + ux[:, None] * d, pin_y + uy[:, None] * d)]
        valued = base.expected_by_code(np.maximum(codes, 0), d)
        valued[(codes < 0) | ~np.isfinite(valued)] = np.inf
        k = np.argmin(valued, axis=1)
        rows = np.arange(len(k))
        e[part] = valued[rows, k]
        found = np.isfinite(e[part])
        lie[part] = np.where(found, codes[rows, k], -1)
        distance[part] = np.where(found, d[rows, k], np.nan)
    return e, lie, distance


def _lie_codes(lies):
    """The index in LIES of ``lies`` (a name, names, or their indices already)."""
    lies = np.asarray(lies)
    if np.issubdtype(lies.dtype, np.integer):
        if lies.size and not ((lies >= 0) & (lies < len(LIES))).all():
            raise ValueError(f"start_lie codes must be within [0, {len(LIES) - 1}]")
        return lies.astype(np.int64)
    names, inverse = np.unique(lies.astype(str), return_inverse=True)
    unknown = [name for name in names if name not in LIES]
    if unknown:
        raise ValueError(f"start_lie {unknown[0]!r}: allowed: {', '.join(LIES)}")
    return np.array([LIES.index(name) for name in names], dtype=np.int64)[inverse]


def score_shots(
    shots,
    hole=None,
    *,
    pin_xy_m=None,
    start_lie=None,
    start_distance_m=None,
    baseline=None,
    lie_of_zone=None,
    putting=None,
):
    """Per shot of a run on a hole: a DataFrame of ``SHOT_COLUMNS``, one row per shot in order.

    ``shots``: columns (a DataFrame, or a mapping of arrays) ``finish_zone``, ``status`` (codes)
    or ``status_name``, ``pin_distance_m``, ``final_x_m``, ``final_y_m``, ``penalty_x_m``,
    ``penalty_y_m`` (hole frame, m). ``hole``: a ``mcrun.hole.Hole``, for the pin, the start
    (``start_of``) and the zone of a water ball's reference point; without one, give
    ``pin_xy_m`` and the start, and water balls drop in the rough. ``start_lie`` (``LIES``) and
    ``start_distance_m`` override the hole's start; each may be one value or one per shot
    (shots struck from different places: ``start_of`` gives both; the lies may be their
    indices in ``LIES``). ``baseline``: a
    ``Baseline``, the Tour's by default. ``lie_of_zone``: {zone: lie} overrides of
    ``LIE_OF_ZONE``. ``putting``: a green's expected-putts map (``putting.green_map.GreenMap``,
    or anything with its ``value_at``): a ball at rest on the green (where the map has a value)
    is valued by it, not by the baseline's putts, and the frame gets ``PUTTING_COLUMNS``
    (``p_one_putt``, ``p_three_putt``: NaN off the green).
    """
    base = baseline or tour_baseline()
    lies = check_lie_of_zone(lie_of_zone)
    if hole is not None:
        pin_xy_m = hole.pin_xy if pin_xy_m is None else pin_xy_m
        lie0, distance0 = start_of(hole)
        start_lie = lie0 if start_lie is None else start_lie
        start_distance_m = distance0 if start_distance_m is None else start_distance_m
    if pin_xy_m is None or start_lie is None:
        raise ValueError("score_shots: give a hole, or pin_xy_m and start_lie")
    outcome = _outcome_codes(shots)
    n = len(outcome)
    if start_distance_m is None:
        start_distance_m = math.hypot(*pin_xy_m)
    code, distance = _lie_codes(start_lie), np.asarray(start_distance_m, dtype=float)
    start_code, start_distance_m = np.broadcast_to(code, (n,)), np.broadcast_to(distance, (n,))
    if code.size == 1 and distance.size == 1:  # one start: valued once
        e_start = np.full(n, base.expected_by_code(code.reshape(1), distance.reshape(1))[0])
    else:
        e_start = base.expected_by_code(start_code, start_distance_m)
    pin_x, pin_y = pin_xy_m
    d_final = _floats(shots, "pin_distance_m", n)
    missing = ~np.isfinite(d_final)
    if missing.any():
        fx, fy = _floats(shots, "final_x_m", n), _floats(shots, "final_y_m", n)
        d_final = np.where(missing, np.hypot(fx - pin_x, fy - pin_y), d_final)

    lie_after = np.full(n, -1, dtype=np.int64)  # index in LIES
    distance_after = np.full(n, np.nan)
    penalty = np.zeros(n)
    expected_after = np.full(n, np.nan)

    for zone in IN_PLAY_ZONES:
        lie_after[outcome == OUTCOMES.index(zone)] = LIES.index(lies[zone])
    in_play = (outcome >= 0) & (outcome < len(IN_PLAY_ZONES))
    distance_after[in_play] = d_final[in_play]
    expected_after[in_play] = base.expected_by_code(lie_after[in_play], d_final[in_play])
    putts = None
    if putting is not None:
        putts = _putts_by_map(putting, shots, outcome, n)
        mapped = np.isfinite(putts[0])
        expected_after[mapped] = putts[0][mapped]

    # Stroke and distance: one penalty stroke, the shot again from its start.
    again = (outcome == OUTCOMES.index("out_of_bounds")) | (outcome == OUTCOMES.index("off_map"))
    lie_after[again] = start_code[again]
    distance_after[again] = start_distance_m[again]
    penalty[again] = 1.0
    expected_after[again] = 1.0 + e_start[again]

    water = np.isin(outcome, [OUTCOMES.index(z) for z in PENALTY_ZONES])
    if water.any():
        rx = _floats(shots, "penalty_x_m", n)[water]
        ry = _floats(shots, "penalty_y_m", n)[water]
        unknown = ~(np.isfinite(rx) & np.isfinite(ry))
        rx = np.where(unknown, _floats(shots, "final_x_m", n)[water], rx)
        ry = np.where(unknown, _floats(shots, "final_y_m", n)[water], ry)
        # Stroke and distance, then each relief the area's colour allows where it is better.
        best_e = e_start[water]
        best_lie = start_code[water]
        best_m = start_distance_m[water]
        if hole is not None:
            e_back, lie_back, back_m = _back_on_the_line(hole, base, lies, rx, ry, pin_x, pin_y)
            better = e_back < best_e
            best_e = np.where(better, e_back, best_e)
            best_lie = np.where(better, lie_back, best_lie)
            best_m = np.where(better, back_m, best_m)
        drop_lie = np.full(len(rx), LIES.index("rough"), dtype=np.int64)
        if hole is not None:
            codes = hole.zone_at(rx, ry)
            mown = np.isin(codes, [ZONE_KINDS.index(z) for z in _MOWN])
            drop_lie[mown] = LIES.index("fairway")
        drop_m = np.hypot(rx - pin_x, ry - pin_y)
        e_drop = base.expected_by_code(drop_lie, drop_m)
        red = np.isin(outcome[water], [OUTCOMES.index(z) for z in LATERAL_ZONES])
        lateral = red & (e_drop <= best_e)
        lie_after[water] = np.where(lateral, drop_lie, best_lie)
        distance_after[water] = np.where(lateral, drop_m, best_m)
        penalty[water] = 1.0
        expected_after[water] = 1.0 + np.where(lateral, e_drop, best_e)

    scored = outcome >= 0
    penalty[~scored] = np.nan
    reference_lie = np.where(outcome == OUTCOMES.index("green"), LIES.index("green"),
                             LIES.index("fairway"))  # fmt: skip
    reference = base.expected_by_code(reference_lie, d_final)
    if putts is not None:
        reference = np.where(np.isfinite(putts[0]), putts[0], reference)
    frame = pd.DataFrame(
        {
            "outcome": pd.Categorical.from_codes(
                np.where(scored, outcome, len(OUTCOMES)), [*OUTCOMES, FAILED]
            ),
            "lie_after": pd.Categorical.from_codes(lie_after, list(LIES)),
            "distance_after_m": distance_after,
            "penalty_strokes": penalty,
            "expected_strokes_after": expected_after,
            "strokes_gained": e_start - 1.0 - expected_after,
            "lie_cost_strokes": np.where(scored, expected_after - reference, np.nan),
        }
    ).assign(expected_strokes_start=e_start)
    if putts is not None:
        frame["p_one_putt"], frame["p_three_putt"] = putts[1], putts[2]
    return frame


PUTTING_COLUMNS = ("p_one_putt", "p_three_putt")


def _putts_by_map(putting, shots, outcome, n):
    """(expected putts, one-putt share, share of three or more) of each ball at rest on the
    green by the map ``putting``; NaN for the others and where the map has no value."""
    out = [np.full(n, np.nan) for _ in range(3)]
    green = outcome == OUTCOMES.index("green")
    if green.any():
        x, y = _floats(shots, "final_x_m", n)[green], _floats(shots, "final_y_m", n)[green]
        for k, values in enumerate(putting.value_at(x, y)):
            out[k][green] = values
    return out


def _mean_se(values):
    n = len(values)
    mean = float(values.mean()) if n else math.nan
    se = float(values.std(ddof=1) / math.sqrt(n)) if n > 1 else math.nan
    return mean, se


def point_strokes(scored):
    """Per point: a dict of its shots' (``score_shots``) means with standard errors and the part
    of each outcome in them.

    ``n_shots``, ``n_scored``, ``n_failed``; ``expected_strokes_start``;
    ``expected_strokes_after_mean``/``_se`` and ``strokes_gained_mean``/``_se`` (strokes; the
    standard error of the mean, sample standard deviation / sqrt(n_scored)); ``lie_cost_mean``
    (strokes above the same distances from the fairway, or the green for balls on it); per
    outcome O of ``OUTCOMES``: ``p_O`` (share of the scored shots), ``expected_strokes_after_O``
    (their mean), ``expected_strokes_after_part_O`` (p_O x that mean: the parts sum to the mean)
    and ``lie_cost_part_O`` (p_O x their mean lie cost: the parts sum to ``lie_cost_mean``).
    """
    outcome = scored["outcome"].to_numpy()
    ok = outcome != FAILED
    after = scored["expected_strokes_after"].to_numpy()[ok]
    gained = scored["strokes_gained"].to_numpy()[ok]
    cost = scored["lie_cost_strokes"].to_numpy()[ok]
    n = int(ok.sum())
    start = scored["expected_strokes_start"].to_numpy()
    row = {
        "n_shots": len(outcome),
        "n_scored": n,
        "n_failed": len(outcome) - n,
        "expected_strokes_start": float(start[0]) if len(start) else math.nan,
    }
    row["expected_strokes_after_mean"], row["expected_strokes_after_se"] = _mean_se(after)
    row["strokes_gained_mean"], row["strokes_gained_se"] = _mean_se(gained)
    row["lie_cost_mean"] = float(cost.mean()) if n else math.nan
    for name in OUTCOMES:
        chosen = outcome[ok] == name
        k = int(chosen.sum())
        p = k / n if n else math.nan
        row[f"p_{name}"] = p
        row[f"expected_strokes_after_{name}"] = float(after[chosen].mean()) if k else math.nan
        row[f"expected_strokes_after_part_{name}"] = p * after[chosen].mean() if k else 0.0
        row[f"lie_cost_part_{name}"] = p * cost[chosen].mean() if k else 0.0
    return row
