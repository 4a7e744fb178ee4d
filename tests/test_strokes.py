"""Expected strokes and strokes gained (mcrun.strokes): the Tour baseline's rows, its
interpolation and the assumptions where it has no row, checked by hand; the penalties by the
Rules; the per-point means, standard errors and parts; a user's baseline and its errors."""

import math

import numpy as np
import pandas as pd
import pytest

from mcrun import status
from mcrun.hole.hole import hole_from_table
from mcrun.strokes import (
    OUTCOMES,
    BaselineError,
    check_lie_of_zone,
    load_baseline,
    point_strokes,
    score_shots,
    start_of,
    tour_baseline,
)
from mcrun.strokes.baseline import DEFAULT_BASELINE_PATH, HOLE_RADIUS_M

YD = 0.9144
FT = 0.3048
TOUR = tour_baseline()


def e(lie, distance_m):
    return float(TOUR.expected(lie, distance_m))


# Broadie (2012) Table 9 as the reference gives it: yards, then tee, fairway, rough, sand and
# recovery (a blank tee cell: the table has no tee row there); and the green's putts by feet.
TABLE_9 = """
 10      2.18 2.34 2.43 3.45
 20      2.40 2.59 2.53 3.51
 30      2.52 2.70 2.66 3.57
 40      2.60 2.78 2.82 3.71
 50      2.66 2.87 2.92 3.79
 60      2.70 2.91 3.15 3.83
 70      2.72 2.93 3.21 3.84
 80      2.75 2.96 3.24 3.84
 90      2.77 2.99 3.24 3.82
100 2.92 2.80 3.02 3.23 3.80
120 2.99 2.85 3.08 3.21 3.78
140 2.97 2.91 3.15 3.22 3.80
160 2.99 2.98 3.23 3.28 3.81
180 3.05 3.08 3.31 3.40 3.82
200 3.12 3.19 3.42 3.55 3.87
220 3.17 3.32 3.53 3.70 3.92
240 3.25 3.45 3.64 3.84 3.97
260 3.45 3.58 3.74 3.93 4.03
280 3.65 3.69 3.83 4.00 4.10
300 3.71 3.78 3.90 4.04 4.20
320 3.79 3.84 3.95 4.12 4.31
340 3.86 3.88 4.02 4.26 4.44
360 3.92 3.95 4.11 4.41 4.56
380 3.96 4.03 4.21 4.55 4.66
400 3.99 4.11 4.30 4.69 4.75
420 4.02 4.19 4.40 4.83 4.84
440 4.08 4.27 4.49 4.97 4.94
460 4.17 4.34 4.58 5.11 5.03
480 4.28 4.42 4.68 5.25 5.13
500 4.41 4.50 4.77 5.40 5.22
520 4.54 4.58 4.87 5.54 5.32
540 4.65 4.66 4.96 5.68 5.41
560 4.74 4.74 5.06 5.82 5.51
580 4.79 4.82 5.15 5.96 5.60
600 4.82 4.89 5.25 6.10 5.70
"""
PUTT_FEET = [3, 4, 5, 6, 7, 8, 9, 10, 15, 20, 30, 40, 50, 60, 90]
PUTTS = [1.04, 1.13, 1.23, 1.34, 1.42, 1.50, 1.56, 1.61, 1.78, 1.87, 1.98, 2.06, 2.14, 2.21, 2.40]


def table_9_rows():
    """(lie, yards, strokes) of every off-green row of TABLE_9."""
    rows = []
    for line in TABLE_9.strip().splitlines():
        yards, *values = line.split()
        lies = ("tee", "fairway", "rough", "sand", "recovery")[-len(values) :]
        rows += [(lie, int(yards), float(v)) for lie, v in zip(lies, values, strict=True)]
    return rows


# --- the baseline ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "lie, distance_yd, strokes",
    # Rows of Broadie (2012) Table 9 as the reference quotes them.
    [
        ("tee", 100, 2.92),
        ("tee", 446 - 46, 3.99),
        ("fairway", 20, 2.40),
        ("fairway", 240, 3.45),
        ("rough", 180, 3.31),
        ("sand", 60, 3.15),
        ("sand", 600, 6.10),
        ("recovery", 300, 4.20),
    ],
)
def test_rows_are_the_table(lie, distance_yd, strokes):
    assert e(lie, distance_yd * YD) == pytest.approx(strokes, abs=1e-12)


def test_putts_rows_are_the_table():
    got = TOUR.expected("green", np.array(PUTT_FEET) * FT)
    np.testing.assert_allclose(got, PUTTS, atol=1e-12)


def test_every_row_of_the_table_is_reproduced():
    """The package's table is the full Table 9: every row of the reference, exactly at its own
    distance, and no row more."""
    rows = table_9_rows()
    assert len(rows) == 26 + 4 * 35
    for lie, yards, strokes in rows:
        assert e(lie, yards * YD) == strokes, (lie, yards)
    for lie in ("tee", "fairway", "rough", "sand", "recovery"):
        yards = [y for name, y, _ in rows if name == lie]
        np.testing.assert_allclose(TOUR.distance_m[lie], np.array(yards) * YD, rtol=1e-12)
    np.testing.assert_allclose(TOUR.distance_m["green"], np.array(PUTT_FEET) * FT, rtol=1e-12)
    np.testing.assert_array_equal(TOUR.expected("green", np.array(PUTT_FEET) * FT), PUTTS)


@pytest.mark.parametrize(
    "lie, distance, unit, strokes",
    [
        ("rough", 150, YD, (3.15 + 3.23) / 2),  # halfway between 140 and 160 yd
        ("sand", 450, YD, (4.97 + 5.11) / 2),
        ("recovery", 290, YD, (4.10 + 4.20) / 2),
        ("tee", 110, YD, (2.92 + 2.99) / 2),
        ("fairway", 35, YD, (2.52 + 2.60) / 2),
        ("green", 7.5, FT, (1.42 + 1.50) / 2),
        ("green", 12, FT, 1.61 + 2 / 5 * (1.78 - 1.61)),
    ],
)
def test_interpolation_between_rows(lie, distance, unit, strokes):
    assert e(lie, distance * unit) == pytest.approx(strokes, abs=1e-12)


def test_published_checks():
    """The PGA Tour's worked example: 446 yd from the tee 4.100, 116 yd in the fairway 2.825, a
    putt of 16 ft 11 in 1.826. The example uses the Tour's own, later baseline; linear
    interpolation in the full Table 9 gives 4.107, 2.840 and 1.815 (the reference), each within
    0.02 of the example, as close as the two baselines agree (docs/strokes.md)."""
    tee = e("tee", 446 * YD)
    fairway = e("fairway", 116 * YD)
    putt = e("green", (16 + 11 / 12) * FT)
    # By hand, from the rows around each distance.
    assert tee == pytest.approx(4.08 + 6 / 20 * (4.17 - 4.08), abs=1e-12)  # 4.1070
    assert fairway == pytest.approx(2.80 + 16 / 20 * (2.85 - 2.80), abs=1e-12)  # 2.8400
    assert putt == pytest.approx(1.78 + (11 / 12 + 1) / 5 * (1.87 - 1.78), abs=1e-12)  # 1.8145
    # The reference's interpolated values, and the published ones within 0.02.
    assert tee == pytest.approx(4.107, abs=0.001)
    assert fairway == pytest.approx(2.840, abs=0.001)
    assert putt == pytest.approx(1.815, abs=0.001)
    assert abs(tee - 4.100) < 0.02
    assert abs(fairway - 2.825) < 0.02
    assert abs(putt - 1.826) < 0.02
    # The example's strokes gained by its first two shots (+0.275, -0.001), to 0.1.
    assert tee - fairway - 1 == pytest.approx(4.100 - 2.825 - 1, abs=0.1)
    assert fairway - putt - 1 == pytest.approx(2.825 - 1.826 - 1, abs=0.05)


def test_short_putts_and_the_hole():
    assert e("green", 0.0) == 0.0
    assert e("green", HOLE_RADIUS_M) == 0.0  # 2.125 in: the ball is in
    assert e("green", HOLE_RADIUS_M + 1e-6) == 1.0
    assert e("green", 0.5 * FT) == 1.0
    assert e("green", 1 * FT) == 1.0
    assert e("green", 2 * FT) == pytest.approx((1.0 + 1.04) / 2, abs=1e-12)


def test_a_green_table_from_0_m_still_holes_the_ball_in_the_cup():
    """A baseline whose green rows start at 0 m (no tap-in row added): a ball within the cup's
    radius is holed, 0.0, alone or among balls beyond it; beyond it, the table's line."""
    from mcrun.strokes.baseline import LIES, Baseline

    tour = tour_baseline()
    distance_m, strokes = dict(tour.distance_m), dict(tour.strokes)
    distance_m["green"], strokes["green"] = np.array([0.0, 1.0, 10.0]), np.array([1.0, 1.5, 2.0])
    base = Baseline("0 m", distance_m, strokes)
    green = LIES.index("green")
    values = base.expected_by_code(np.full(3, green), np.array([0.5 * HOLE_RADIUS_M, 0.5, 5.0]))
    assert values.tolist() == [0.0, 1.25, pytest.approx(1.5 + 4.0 / 18.0, abs=1e-12)]
    assert base.expected("green", 0.5 * HOLE_RADIUS_M) == 0.0
    assert base.expected_by_code(np.full(2, green), np.array([0.5, 5.0]))[0] == 1.25


def test_off_the_green_below_10_yd_is_the_putt_plus_the_lies_step():
    # The step of each lie over a 30 ft (10 yd) putt, 1.98: fairway 0.20, rough 0.36, sand 0.45,
    # recovery 1.47; at 5 yd (15 ft, a putt of 1.78):
    assert e("fairway", 5 * YD) == pytest.approx(1.78 + 0.20, abs=1e-12)
    assert e("rough", 5 * YD) == pytest.approx(1.78 + 0.36, abs=1e-12)
    assert e("sand", 5 * YD) == pytest.approx(1.78 + 0.45, abs=1e-12)
    assert e("recovery", 5 * YD) == pytest.approx(1.78 + 1.47, abs=1e-12)
    # Continuous at the first row, and never below a stroke plus the step at the hole.
    assert e("rough", 10 * YD - 1e-9) == pytest.approx(2.34, abs=1e-9)
    assert e("fairway", 0.0) == pytest.approx(1.0 + 0.20, abs=1e-12)
    # The tee below its first row (100 yd) is the fairway.
    assert e("tee", 60 * YD) == pytest.approx(2.70, abs=1e-12)


def test_above_the_last_rows_the_last_two_rows_line():
    assert e("fairway", 650 * YD) == pytest.approx(4.89 + 50 / 20 * (4.89 - 4.82), abs=1e-12)
    assert e("green", 120 * FT) == pytest.approx(2.40 + 30 / 30 * (2.40 - 2.21), abs=1e-12)


def test_vectorised_over_lies_and_distances():
    lies = np.array(["tee", "green", "sand", "fairway"])
    got = TOUR.expected(lies, np.array([100 * YD, 10 * FT, 60 * YD, np.nan]))
    np.testing.assert_allclose(got[:3], [2.92, 1.61, 3.15], atol=1e-12)
    assert np.isnan(got[3])
    with pytest.raises(ValueError, match="lie 'grass': allowed: tee, fairway"):
        TOUR.expected("grass", 10.0)
    with pytest.raises(ValueError, match=r"distance_m -3: allowed: 0 or more, finite \(m\)"):
        TOUR.expected(lies, np.array([100 * YD, -3.0, 60 * YD, -5.0]))
    with pytest.raises(ValueError, match="distance_m -0.5: allowed: 0 or more"):
        TOUR.expected_by_code(0, -0.5)
    with pytest.raises(ValueError, match="distance_m inf: allowed: 0 or more, finite"):
        TOUR.expected("rough", np.inf)
    with pytest.raises(ValueError, match=r"distance_m 'ten': allowed: numbers \(m\)"):
        TOUR.expected("rough", "ten")
    # Text of digits was read as metres, True as 1 m, a date as 72.7 strokes.
    for given in ("100", True, np.datetime64("2020-01-01"), np.array([True])):
        with pytest.raises(ValueError, match=r"^distance_m .*: allowed: numbers \(m\)$"):
            TOUR.expected("fairway", given)
    for code, says in ((6, "lie code 6: allowed: 0 to 5"), (1.5, "lie codes of type float64")):
        with pytest.raises(ValueError, match=says):
            TOUR.expected_by_code([0, code], [10.0, 10.0])


# --- a user's baseline -------------------------------------------------------------------------


def test_a_users_baseline(tmp_path):
    """The package's table with every value 0.5 stroke higher reads back as such."""
    lines = DEFAULT_BASELINE_PATH.read_text(encoding="utf-8").splitlines()
    out = []
    for line in lines:
        if line.startswith("#") or line.startswith("lie,"):
            out.append(line)
        else:
            *head, strokes = line.split(",")
            out.append(",".join([*head, f"{float(strokes) + 0.5:.2f}"]))
    path = tmp_path / "scratch.csv"
    path.write_text("\n".join(out) + "\n", encoding="utf-8")
    mine = load_baseline(path)
    assert float(mine.expected("fairway", 116 * YD)) == pytest.approx(2.84 + 0.5, abs=1e-12)
    assert float(mine.expected("green", 10 * FT)) == pytest.approx(2.11, abs=1e-12)
    # Saved by Excel as "CSV UTF-8": a byte-order mark before the first line (it read as a
    # column named '\ufeff# Expected strokes...').
    path.write_text("\n".join(out) + "\n", encoding="utf-8-sig")
    assert float(load_baseline(path).expected("fairway", 116 * YD)) == pytest.approx(3.34)


GOOD_HEADER = "lie,distance_yd,distance_ft,expected_strokes"


def _table(tmp_path, rows, header=GOOD_HEADER):
    """A baseline CSV: two good rows of every lie, then ``rows``."""
    good = [f"{lie},{d},,{v}" for lie in ("tee", "fairway", "rough", "sand", "recovery")
            for d, v in ((100, 3.0), (200, 3.2))]  # fmt: skip
    good += ["green,,3,1.04", "green,,10,1.6"]
    path = tmp_path / "mine.csv"
    path.write_text("\n".join(["# my baseline", header, *good, *rows]) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize(
    "rows, header, message",
    [
        (
            [],
            "lie,distance_m,distance_ft,expected_strokes",
            r"mine\.csv: line 2: unknown column 'distance_m'; the columns are lie, distance_yd",
        ),
        (
            [],
            "lie,distance_yd,distance_ft",
            r"mine\.csv: line 2: no column 'expected_strokes'; the columns are",
        ),
        (
            ["grass,50,,2.5"],
            GOOD_HEADER,
            r"mine\.csv: line 15: lie 'grass' is not a lie; allowed: tee, fairway, rough, sand, "
            r"recovery, green",
        ),
        (
            ["rough,50,5,2.5"],
            GOOD_HEADER,
            r"mine\.csv: line 15: give one of distance_yd and distance_ft",
        ),
        (["rough,,,2.5"], GOOD_HEADER, r"line 15: give one of distance_yd and distance_ft"),
        (
            ["rough,fifty,,2.5"],
            GOOD_HEADER,
            r"line 15: distance_yd 'fifty' is not a number; allowed: a distance above 0",
        ),
        (["rough,-5,,2.5"], GOOD_HEADER, r"line 15: distance_yd -5; allowed: above 0"),
        (
            ["green,,2,0.9"],
            GOOD_HEADER,
            r"line 15: expected_strokes 0\.9; allowed: 1 to 20 \(a ball not in the hole",
        ),
        (["sand,50,,nan"], GOOD_HEADER, r"line 15: expected_strokes 'nan' is not finite"),
        (
            ["sand,200,,3.3"],
            GOOD_HEADER,
            r"line 15: a second sand row at 200 yd \(line 10\); allowed: one row per lie",
        ),
        (["sand,50,,2.5,9"], GOOD_HEADER, r"line 15: 5 fields; allowed: 4"),
        ([], GOOD_HEADER + ",expected_strokes", r"line \d+: column 'expected_strokes' twice"),
    ],
)
def test_a_users_baseline_errors(tmp_path, rows, header, message):
    with pytest.raises(BaselineError, match=message) as raised:
        load_baseline(_table(tmp_path, rows, header))
    assert "\n" not in str(raised.value)
    assert str(raised.value).startswith(str(tmp_path / "mine.csv"))


def test_a_baseline_that_is_not_a_path_is_named():
    """``load_baseline(None)`` or ``(5)``: a BaselineError naming it (an AttributeError before)."""
    for wrong in (None, 5):
        with pytest.raises(BaselineError, match=rf"^baseline {wrong}: allowed: a CSV file's path"):
            load_baseline(wrong)


def test_a_users_baseline_needs_every_lie(tmp_path):
    path = tmp_path / "short.csv"
    path.write_text(f"{GOOD_HEADER}\nfairway,100,,2.8\nfairway,200,,3.2\n", encoding="utf-8")
    with pytest.raises(BaselineError, match=r"short\.csv: 0 tee rows; allowed: 2 or more"):
        load_baseline(path)
    with pytest.raises(BaselineError, match=r"absent\.csv: cannot be read as a UTF-8 CSV"):
        load_baseline(tmp_path / "absent.csv")


# --- after each shot ---------------------------------------------------------------------------


def _shots(rows):
    """A shots table from (status, finish_zone, pin_distance_m, penalty_x_m, penalty_y_m)."""
    frame = pd.DataFrame(
        rows, columns=["status", "finish_zone", "pin_distance_m", "penalty_x_m", "penalty_y_m"]
    )
    frame["finish_zone"] = frame["finish_zone"].astype("category")
    frame["final_x_m"] = np.nan
    frame["final_y_m"] = np.nan
    return frame


OK, WATER, OOB = status.OK, status.IN_PENALTY_AREA, status.OUT_OF_BOUNDS_STATUS
PIN = (150.0, 0.0)  # a pin 150 m down the x axis


def test_a_holed_shot_gains_its_start_less_one():
    shots = _shots([(OK, "green", 0.0, np.nan, np.nan), (OK, "green", 0.01, np.nan, np.nan)])
    got = score_shots(shots, pin_xy_m=PIN, start_lie="fairway", start_distance_m=160 * YD)
    assert (got["expected_strokes_after"] == 0.0).all()
    np.testing.assert_allclose(got["strokes_gained"], 2.98 - 1.0, atol=1e-12)
    assert (got["penalty_strokes"] == 0.0).all()


def test_a_water_ball_one_stroke_and_a_drop_where_it_crossed():
    # From the tee at 180 yd (3.05); the ball crossed into the water 40 yd short of the pin.
    ref_x = PIN[0] - 40 * YD
    shots = _shots([(WATER, "water", 35.0, ref_x, 0.0)])
    # Without a hole the drop is in the rough: 40 yd rough, 2.78.
    got = score_shots(shots, pin_xy_m=PIN, start_lie="tee", start_distance_m=180 * YD)
    assert got["penalty_strokes"].iloc[0] == 1.0
    assert got["lie_after"].iloc[0] == "rough"
    assert got["distance_after_m"].iloc[0] == pytest.approx(40 * YD, abs=1e-9)
    assert got["expected_strokes_after"].iloc[0] == pytest.approx(1 + 2.78, abs=1e-12)
    assert got["strokes_gained"].iloc[0] == pytest.approx(3.05 - 1 - 3.78, abs=1e-12)
    # On a hole whose ground there is fairway the drop is on it: 40 yd fairway, 2.60.
    fairway = hole_from_table({"length_m": PIN[0], "width_m": 40.0}, ".", "t")
    got = score_shots(shots, fairway, start_lie="tee", start_distance_m=180 * YD)
    assert got["lie_after"].iloc[0] == "fairway"
    assert got["strokes_gained"].iloc[0] == pytest.approx(3.05 - 1 - (1 + 2.60), abs=1e-12)
    rough = hole_from_table({"length_m": PIN[0], "width_m": 40.0, "surface": "rough"}, ".", "t")
    got = score_shots(shots, rough, start_lie="tee", start_distance_m=180 * YD)
    assert got["lie_after"].iloc[0] == "rough"


def test_a_water_ball_replays_when_stroke_and_distance_is_better():
    # From 100 yd in the fairway (2.80), the ball crossed into water 140 yd from the pin (past
    # it): the drop (rough 140 yd, 3.15) is worse than the shot again: 1 + 2.80.
    shots = _shots([(WATER, "water", 130.0, PIN[0] + 140 * YD, 0.0)])
    got = score_shots(shots, pin_xy_m=PIN, start_lie="fairway", start_distance_m=100 * YD)
    assert got["lie_after"].iloc[0] == "fairway"
    assert got["distance_after_m"].iloc[0] == pytest.approx(100 * YD)
    assert got["strokes_gained"].iloc[0] == pytest.approx(-2.0, abs=1e-12)


@pytest.mark.parametrize("code, zone", [(OOB, "out_of_bounds"), (status.OFF_MAP, "off_map")])
@pytest.mark.parametrize("lie, distance_yd", [("tee", 446), ("fairway", 116), ("rough", 30)])
def test_out_of_bounds_is_stroke_and_distance(code, zone, lie, distance_yd):
    """Rule 18.2: one penalty stroke and the shot again from where it was played, so
    E(after) = 1 + E(start) and the shot gains E(start) - 1 - (1 + E(start)) = -2."""
    shots = _shots([(code, zone, 80.0, 90.0, 30.0)])
    got = score_shots(shots, pin_xy_m=PIN, start_lie=lie, start_distance_m=distance_yd * YD)
    assert got["expected_strokes_after"].iloc[0] == pytest.approx(1 + e(lie, distance_yd * YD))
    assert got["strokes_gained"].iloc[0] == pytest.approx(-2.0, abs=1e-12)
    assert got["outcome"].iloc[0] == zone


@pytest.mark.parametrize(
    "zone, distance_m, overrides, strokes",
    [
        ("bunker", 100 * YD, None, 3.23),  # sand
        ("tee", 100 * YD, None, 2.80),  # a ball on a tee is played as fairway
        ("fringe", 10 * YD, None, 2.18),  # fringe as fairway, 10 yd
        ("fringe", 10 * YD, {"fringe": "green"}, 1.98),  # as a putt of 30 ft
        ("rough", 60 * YD, {"rough": "recovery"}, 3.83),
        ("rough", 60 * YD, None, 2.91),
    ],
)
def test_lies_of_the_zones(zone, distance_m, overrides, strokes):
    shots = _shots([(OK, zone, distance_m, np.nan, np.nan)])
    got = score_shots(
        shots, pin_xy_m=PIN, start_lie="tee", start_distance_m=180 * YD, lie_of_zone=overrides
    )
    assert got["expected_strokes_after"].iloc[0] == pytest.approx(strokes, abs=1e-12)


def test_lie_of_zone_errors():
    with pytest.raises(ValueError, match="lie_of_zone: zone 'water': allowed: rough, fairway"):
        check_lie_of_zone({"water": "rough"})
    with pytest.raises(ValueError, match="lie_of_zone.rough: lie 'trees': allowed: tee,"):
        check_lie_of_zone({"rough": "trees"})


def test_status_names_read_as_codes():
    codes = _shots([(OK, "green", 3.0, np.nan, np.nan), (OOB, "out_of_bounds", 9, 1.0, 2.0)])
    names = codes.drop(columns="status").assign(status_name=[status.NAMES[OK], status.NAMES[OOB]])
    kw = dict(pin_xy_m=PIN, start_lie="tee", start_distance_m=180 * YD)
    pd.testing.assert_frame_equal(score_shots(codes, **kw), score_shots(names, **kw))


def test_start_of_a_hole():
    hole = hole_from_table({"length_m": 120.0, "width_m": 30.0}, ".", "t")
    assert start_of(hole) == ("fairway", 120.0)


# --- per point ---------------------------------------------------------------------------------


def test_point_means_standard_errors_and_parts():
    """From 160 yd in the fairway (2.98): putts of 10 ft (1.61) and 30 ft (1.98), rough at
    20 yd (2.59), out of bounds (1 + 2.98 = 3.98, the ball 60 yd from the pin where it went
    out), and a shot the kernel did not finish (left out, counted)."""
    shots = _shots(
        [
            (OK, "green", 10 * FT, np.nan, np.nan),
            (OK, "green", 30 * FT, np.nan, np.nan),
            (OK, "rough", 20 * YD, np.nan, np.nan),
            (OOB, "out_of_bounds", 60 * YD, 10.0, 30.0),
            (status.NOT_STOPPED, "fairway", 50.0, np.nan, np.nan),
        ]
    )
    scored = score_shots(shots, pin_xy_m=PIN, start_lie="fairway", start_distance_m=160 * YD)
    assert scored["outcome"].iloc[4] == "failed" and np.isnan(scored["strokes_gained"].iloc[4])
    row = point_strokes(scored)
    assert (row["n_shots"], row["n_scored"], row["n_failed"]) == (5, 4, 1)
    assert row["expected_strokes_start"] == pytest.approx(2.98)
    # Mean 10.16 / 4 = 2.54; deviations -0.93, -0.56, 0.05, 1.44, squares sum 3.2546.
    se = math.sqrt(3.2546 / 3) / math.sqrt(4)
    assert row["expected_strokes_after_mean"] == pytest.approx(2.54, abs=1e-12)
    assert row["expected_strokes_after_se"] == pytest.approx(se, abs=1e-12)
    assert row["strokes_gained_mean"] == pytest.approx(2.98 - 1 - 2.54, abs=1e-12)
    assert row["strokes_gained_se"] == pytest.approx(se, abs=1e-12)
    # Parts: green 0.5 x 1.795, rough 0.25 x 2.59, out of bounds 0.25 x 3.98.
    assert row["p_green"] == 0.5 and row["p_rough"] == 0.25 and row["p_out_of_bounds"] == 0.25
    assert row["expected_strokes_after_green"] == pytest.approx(1.795, abs=1e-12)
    assert row["expected_strokes_after_part_green"] == pytest.approx(0.8975, abs=1e-12)
    assert row["expected_strokes_after_part_rough"] == pytest.approx(0.6475, abs=1e-12)
    assert row["expected_strokes_after_part_out_of_bounds"] == pytest.approx(0.995, abs=1e-12)
    parts = sum(row[f"expected_strokes_after_part_{o}"] for o in OUTCOMES)
    assert parts == pytest.approx(row["expected_strokes_after_mean"], abs=1e-12)
    assert row["p_water"] == 0.0 and math.isnan(row["expected_strokes_after_water"])
    # Lie costs over the fairway at the same distance: rough 2.59 - 2.40; out of bounds
    # 3.98 - 2.70 (fairway at 60 yd); the putts none.
    assert row["lie_cost_part_rough"] == pytest.approx(0.25 * 0.19, abs=1e-12)
    assert row["lie_cost_part_out_of_bounds"] == pytest.approx(0.25 * 1.28, abs=1e-12)
    assert row["lie_cost_part_green"] == pytest.approx(0.0, abs=1e-12)
    assert row["lie_cost_mean"] == pytest.approx((0.19 + 1.28) / 4, abs=1e-12)


# --- red and yellow penalty areas (Rule 17.1d) --------------------------------------------------


def _hole_with(zones, extent_m=(-10.0, 250.0, -60.0, 60.0)):
    """A hole without a map: the pin at (200, 0), ``zones`` ((kind, [ring]) in its frame),
    rough elsewhere on the grid over ``extent_m``."""
    from mcrun.hole.hole import Hole, _turfs

    return Hole(source="t", frame=None, pin_xy=(200.0, 0.0), zones=zones, boundary=[],
                extent_m=extent_m, cell_m=0.5, turf=_turfs({}, "t"))  # fmt: skip


def _box(x0, x1, y0, y1):
    return [np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)]


def _score_on(hole, kind, ref_xy):
    shots = _shots([(WATER, kind, 30.0, *ref_xy)])
    return score_shots(shots, hole, start_lie="tee", start_distance_m=200.0).iloc[0]


@pytest.mark.parametrize("pond_to_the_grid_edge", [True, False])
def test_a_yellow_area_gives_no_lateral_drop(pond_to_the_grid_edge):
    """A pond along the right of the fairway, the ball crossing into it at the fairway's edge
    21.5 m from the pin: red drops there, on the fairway (Rule 17.1d(3)); yellow may not, and
    the line back from the pin through the crossing runs through the pond, then off the grid
    (stroke and distance: the shot again from the tee) or into rough beyond it."""
    y_far = 60.0 if pond_to_the_grid_edge else 45.0
    zones = [("fairway", _box(-10.0, 250.0, -20.0, 20.0))]
    ref = (190.0, 19.0)
    red = _score_on(_hole_with([*zones, ("water", _box(0.0, 220.0, 20.0, y_far))]), "water", ref)
    yellow_hole = _hole_with([*zones, ("water_yellow", _box(0.0, 220.0, 20.0, y_far))])
    yellow = _score_on(yellow_hole, "water_yellow", ref)
    assert red["lie_after"] == "fairway"
    assert red["expected_strokes_after"] == pytest.approx(1 + e("fairway", math.hypot(10, 19)))
    assert yellow["outcome"] == "water_yellow" and yellow["penalty_strokes"] == 1.0
    assert yellow["expected_strokes_after"] > red["expected_strokes_after"] + 0.4
    if pond_to_the_grid_edge:
        assert yellow["expected_strokes_after"] == pytest.approx(1 + e("tee", 200.0), abs=1e-12)
        assert yellow["distance_after_m"] == 200.0 and yellow["lie_after"] == "tee"
    else:
        # Beyond the pond, on the line: its first point in play, 45 / sin(62.2 deg) from the pin.
        assert yellow["lie_after"] == "rough"
        assert yellow["distance_after_m"] == pytest.approx(45.0 * math.hypot(10, 19) / 19, abs=1.0)
        d = yellow["distance_after_m"]
        assert yellow["expected_strokes_after"] == pytest.approx(1 + e("rough", d), abs=1e-12)


def test_back_on_the_line_picks_the_best_point_behind_the_crossing():
    """A pond across the fairway from 150 m to 170 m, with 10 m of rough in front of it (140 m
    to 150 m, the fairway before that): a ball crossing into it at 149.5 m drops back on the
    line; the first fairway point behind (60.5 m to 61 m from the pin) beats the rough nearer
    the pond (51.5 m: 2.90 against 2.71 from the fairway, Broadie's table)."""
    zones = [
        ("fairway", _box(-10.0, 140.0, -20.0, 20.0)),
        ("fairway", _box(170.0, 250.0, -20.0, 20.0)),
        ("water_yellow", _box(150.0, 170.0, -30.0, 30.0)),
    ]
    got = _score_on(_hole_with(zones), "water_yellow", (149.5, 0.0))
    assert got["lie_after"] == "fairway"
    assert 60.0 <= got["distance_after_m"] <= 61.5
    d = got["distance_after_m"]
    assert got["expected_strokes_after"] == pytest.approx(1 + e("fairway", d), abs=1e-12)
    assert e("fairway", d) < e("rough", 51.5)
    # Red may drop laterally at the crossing, in the rough there, or go back on the line too.
    zones[2] = ("water", zones[2][1])
    red = _score_on(_hole_with(zones), "water", (149.5, 0.0))
    assert red["expected_strokes_after"] == pytest.approx(got["expected_strokes_after"])


def test_a_penalty_area_ball_is_scored_by_the_kind_it_finished_in():
    """The status says penalty area, the finish zone which one; a finish zone that names none
    is a red area (Rule 17.1: one the committee has not marked is red)."""
    assert {"water", "water_yellow"} <= set(OUTCOMES)
    shots = _shots(
        [(WATER, "water_yellow", 35.0, 100.0, 0.0), (WATER, "fairway", 35.0, 100.0, 0.0)]
    )
    got = score_shots(shots, pin_xy_m=PIN, start_lie="tee", start_distance_m=180 * YD)
    assert list(got["outcome"]) == ["water_yellow", "water"]
    # Without a hole: yellow has only stroke and distance, red its drop in the rough.
    assert got["expected_strokes_after"].iloc[0] == pytest.approx(1 + e("tee", 180 * YD))
    assert got["expected_strokes_after"].iloc[1] == pytest.approx(1 + e("rough", 50.0))


def test_the_tour_baseline_cannot_be_changed_by_a_caller():
    """tour_baseline() is one object for the process: a caller's change to its rows changed
    every later score (fairway 100 m: 2.823, then 3.823), without a word."""
    import pickle

    from mcrun.strokes import tour_baseline

    before = float(tour_baseline().expected("fairway", 100.0))
    rows = tour_baseline().strokes
    with pytest.raises(ValueError, match="read-only"):
        rows["fairway"][:] += 1.0
    with pytest.raises(TypeError, match="a Baseline's rows cannot be changed"):
        rows["rough"] = rows["rough"] + 5.0
    assert float(tour_baseline().expected("fairway", 100.0)) == before
    sent = pickle.loads(pickle.dumps(tour_baseline()))  # (as a Dask worker gets it)
    assert not sent.strokes["rough"].flags.writeable
    assert float(sent.expected("fairway", 100.0)) == before
