"""A course rated by simulating the model players (``mcrun.play.rating``, ``mcrun rate``): the
handicap system's formulas (the Slope, the length rating and the plays-as yardage, par by
length), the rounds drawn from the holes' plays, the made-up open course, the map's tee boxes
and its holes' order, and ``mcrun rate`` end to end on small courses (men's and women's players,
obstacles, elevation, Dask) with its one-line errors."""

import contextlib
import io
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun.cli import main
from mcrun.cli.rate import course_holes, holes_wanted
from mcrun.hole.synthetic import PAR_MIX, YARD_M, open_course, pars_for
from mcrun.play.rating import (
    BETTER_HALF,
    DAY_FORM,
    EXPECTED,
    CourseRating,
    HoleScore,
    better_half_gap,
    course_rounds,
    fit_day_form,
    length_rating,
    par_by_length,
    plays_as_yd,
    slope_rating,
)
from mcrun.quantities import InputError
from mcrun.results import output

COURSE = Path(__file__).resolve().parents[1] / "scenarios/holes/riverside-zagreb.osm.geojson"


def test_the_slope_rating_is_the_system_s():
    """5.381 (men) and 4.24 (women) times Bogey less Course Rating, rounded, in 55-155: a bogey
    man 21 strokes behind is a course of standard difficulty (113)."""
    assert slope_rating(72.0, 93.0) == 113
    assert slope_rating(70.1, 90.4) == round(5.381 * 20.3)
    assert slope_rating(72.0, 93.0, women=True) == round(4.24 * 21.0)
    assert slope_rating(70.0, 71.0) == 55 and slope_rating(60.0, 100.0) == 155


def test_par_by_length_follows_the_guide():
    lengths_yd = (150, 250, 251, 470, 471, 600)
    assert [par_by_length(yd * YARD_M) for yd in lengths_yd] == [3, 3, 4, 4, 5, 5]
    lengths_yd = (150, 210, 211, 395, 396, 500)
    assert [par_by_length(yd * YARD_M, women=True) for yd in lengths_yd] == [3, 3, 4, 4, 5, 5]


def test_the_length_rating_and_the_plays_as_yardage_are_the_system_s():
    """The manual's scratch man: 6,000 yd rate 68.2 and 6,400 yd 70.0 (to one decimal); the
    others' rules (the reference's); 9 holes half the strokes; plays-as turns them round."""
    assert round(length_rating("scratch", 6000.0), 1) == 68.2
    assert round(length_rating("scratch", 6400.0), 1) == 70.0
    assert length_rating("bogey", 6400.0) == pytest.approx(6400 / 160 + 50.7)
    assert length_rating("scratch-woman", 5400.0) == pytest.approx(5400 / 180 + 40.1)
    assert length_rating("bogey-woman", 5400.0) == pytest.approx(5400 / 120 + 51.3)
    assert length_rating("scratch", 3000.0, holes=9) == pytest.approx(3000 / 220 + 40.9 / 2)
    for player in ("scratch", "bogey", "scratch-woman", "bogey-woman"):
        for holes in (9, 18):
            rating = length_rating(player, 6123.0, holes)
            assert plays_as_yd(player, rating, holes) == pytest.approx(6123.0)


def _scores(player, means):
    """HoleScores whose plays are 1,000 draws of two stroke counts about ``means``."""
    rng = np.random.default_rng(1)
    out = []
    for k, m in enumerate(means, start=1):
        low = int(np.floor(m))
        plays = low + (rng.random(1000) < m - low)
        out.append(HoleScore(k, player, float(plays.mean()), 0.01, "Driver", plays, 0, 0.0))
    return out


def test_the_better_half_is_below_the_expected_score_and_the_rounds_are_reproducible():
    """The rounds: without the day's form the holes' plays drawn independently (their sum's
    variance the sum of theirs, within 5 %), the same for the same seed; the rating's rounds
    those of the player's day form; the better half's mean below the expected score, which is
    the holes' sum."""
    means = [4.3, 3.4, 5.2, 4.6] * 4 + [4.1, 3.2]
    scores = {"scratch": _scores("scratch", means), "bogey": _scores("bogey", np.add(means, 1.1))}
    rating = CourseRating([None] * 18, ("scratch", "bogey"), scores, seed=7)
    expected = rating.rating("scratch", EXPECTED)
    assert expected == pytest.approx(sum(s.expected_strokes for s in scores["scratch"]))
    assert rating.rating("scratch", BETTER_HALF) < expected - 1.0
    variance = sum(s.scores.var() for s in scores["scratch"])
    independent = course_rounds(scores["scratch"], 10_000, 7)
    assert independent.var() == pytest.approx(variance, rel=0.05)
    np.testing.assert_array_equal(independent, course_rounds(scores["scratch"], 10_000, 7))
    again = course_rounds(scores["scratch"], 10_000, 7, DAY_FORM["scratch"])
    np.testing.assert_array_equal(again, rating.rounds["scratch"])
    assert rating.slope(EXPECTED) == slope_rating(round(expected, 1),
                                                  round(rating.rating("bogey"), 1))  # fmt: skip


def _normal_scores(sd, holes=18, plays=20_000):
    rng = np.random.default_rng(3)
    return [HoleScore(k, "scratch", 4.0, 0.0, "Driver", rng.normal(4.0, sd, plays), 0, 0.0)
            for k in range(1, holes + 1)]  # fmt: skip


def test_the_day_s_form_spreads_the_rounds_as_a_gaussian_copula_does():
    """Holes whose plays are normal (SD s), joined by a day form rho: each hole's scores the
    same draws as without it (the rounds' mean unchanged, to rounding), the rounds' variance
    18 s^2 (1 + 17 rho) (their correlation rho) within 5 %; the better half 0.798 of their SD
    below the average (the mean of a normal's lower half, within 3 %); a day form fitted to a
    gap of 3 strokes is the rho that gives it (within 0.02), none for a gap no rho gives; a rho
    outside [0, 1) refused."""
    sd = 0.6
    scores = _normal_scores(sd)
    alone = course_rounds(scores, 20_000, 11)
    for rho in (0.1, 0.3):
        rounds = course_rounds(scores, 20_000, 11, rho)
        assert rounds.mean() == pytest.approx(alone.mean(), abs=1e-9)
        assert rounds.var() == pytest.approx(18 * sd**2 * (1 + 17 * rho), rel=0.05)
        gap = better_half_gap(scores, 11, rho, rounds=20_000)
        assert gap == pytest.approx(0.7979 * np.sqrt(18 * sd**2 * (1 + 17 * rho)), rel=0.03)
    rho = ((3.0 / 0.7979) ** 2 / (18 * sd**2) - 1.0) / 17.0
    assert fit_day_form([scores], 11, gap=3.0) == pytest.approx(rho, abs=0.02)
    assert fit_day_form([scores], 11, gap=0.5) == 0.0
    with pytest.raises(ValueError, match="no day form"):
        fit_day_form([scores], 11, gap=100.0)
    for bad in (-0.1, 1.0):
        with pytest.raises(ValueError, match="day_form"):
            course_rounds(scores, 10, 11, bad)


def test_holes_are_chosen_as_written():
    assert holes_wanted(None, 3) == [1, 2, 3]
    assert holes_wanted("1-3, 7,9-10", 18) == [1, 2, 3, 7, 9, 10]
    # (int() read "١٢" as 12 and "1_2" as 12: ASCII digits only, as every whole number)
    for bad in ("0-3", "5-2", "19", "a", "1-", "-3", "1-2-3", "١٢", "1_2", "1-1_8"):
        with pytest.raises(InputError, match="--holes"):
            holes_wanted(bad, 18)


def test_an_open_course_is_the_length_and_pars_it_was_made_of(tmp_path):
    """18 straight holes adding up to 6,500 yd (within 0.5 %, tee to pin), the pars of the mix,
    read back as a course map."""
    (tmp_path / "open.geojson").write_text(json.dumps(open_course(6500)))
    numbers, holes, by_length, _ = course_holes(tmp_path / "open.geojson")
    assert numbers == list(range(1, 19)) and by_length == []
    assert [h.par for h in holes] == list(PAR_MIX) == list(pars_for(18))
    assert sum(h.length_m for h in holes) / YARD_M == pytest.approx(6500, rel=0.005)


@pytest.fixture(scope="module")
def rated(tmp_path_factory):
    """``mcrun rate`` on a made-up course of a par 3 and a par 4 (its second hole with water
    from 150 to 185 m), small settings, what the obstacles cost and the picture."""
    folder = tmp_path_factory.mktemp("rate")
    course = folder / "open.geojson"
    course.write_text(json.dumps(open_course(540, pars=(3, 4), water={2: (150.0, 185.0)})))
    out = folder / "rating.parquet"
    small = ["-n", "6", "--plays", "300", "--coarse", "20m", "--fine", "6m", "--putts", "8",
             "--green-resolution", "2m"]  # fmt: skip
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        code = main(["rate", str(course), *small, "--obstacles", "--plot",
                     str(folder / "rating.png"), "-o", str(out)])  # fmt: skip
    return code, out, course, printed.getvalue()


def test_mcrun_rate_rates_a_course_and_writes_a_row_per_hole_and_player(rated):
    code, out, _, printed = rated
    assert code == 0
    frame = pd.read_parquet(out)
    assert list(frame["player"]) == ["scratch", "scratch", "bogey", "bogey"]
    assert list(frame["hole"]) == [1, 2, 1, 2] and list(frame["par"]) == [3, 4, 3, 4]
    s, b = (frame[frame["player"] == p].set_index("hole") for p in ("scratch", "bogey"))
    # the bogey player is worse on every hole, by a stroke or so
    assert ((b["expected_strokes"] - s["expected_strokes"]).between(0.3, 2.0)).all()
    shares = frame.filter(like="strokes_").drop(columns=["expected_strokes_se"], errors="ignore")
    np.testing.assert_allclose(shares.filter(regex=r"^strokes_\d+$").sum(axis=1), 1.0)
    meta = output.read_provenance(out)
    assert meta["file"] == "rating" and meta["holes"] == 2
    cr, br = meta["scratch_rating_expected"], meta["bogey_rating_expected"]
    assert cr == round(s["expected_strokes"].sum(), 1) and br > cr
    assert "slope_rating_expected" not in meta  # a Slope Rating is of 18 holes
    # the first hole has no obstacles: the same solve again; the water costs the bogey player
    assert (s.loc[1, "obstacles_strokes"], b.loc[1, "obstacles_strokes"]) == (0.0, 0.0)
    assert b.loc[2, "obstacles_strokes"] > 0.1
    assert (out.parent / "rating.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "scratch_plays_as_yd_expected" not in meta  # a length rating is of 9 or 18 holes
    assert f"expected: Course Rating {cr:.1f}, Bogey Rating {br:.1f}\n" in printed
    assert "(par 7; the length rating and the plays-as yardage are of 9 or 18 holes" in printed


def test_mcrun_rate_rates_for_the_women_s_model_players(tmp_path):
    """``--women``: the women's model players and the women's par by length (a 230-yd hole of
    a map without par is their par 4, a man's par 3), said in the file's metadata."""
    course = open_course(230, pars=(3,))
    for feature in course["features"]:
        feature["properties"].pop("par", None)
    (tmp_path / "one.geojson").write_text(json.dumps(course))
    out = tmp_path / "women.parquet"
    with contextlib.redirect_stdout(io.StringIO()):
        code = main(["rate", str(tmp_path / "one.geojson"), "--women", "-n", "6", "--plays",
                     "300", "--coarse", "20m", "--fine", "6m", "--putts", "8",
                     "--green-resolution", "2m", "-o", str(out)])  # fmt: skip
    assert code == 0
    frame = pd.read_parquet(out)
    assert list(frame["player"]) == ["scratch-woman", "bogey-woman"]
    assert list(frame["par"]) == [4, 4]
    meta = output.read_provenance(out)
    assert meta["women"] is True and meta["holes"] == 1
    # What the file's rows depend on, to run it again: the solves' settings and the versions.
    assert (meta["n"], meta["plays"], meta["holes_rated"]) == (6, 300, [1])
    assert {"coarse_m", "fine_m"} <= set(meta) and meta["versions"]["mcrun"]
    assert meta["greens"] == {"read": "own", "n": 8, "seed": 0, "resolution_m": 2.0,
                              "drift_mm_per_m": 4.9}  # fmt: skip
    assert meta["day_form"] == {p: DAY_FORM[p] for p in ("scratch-woman", "bogey-woman")}
    rating = meta["scratch_woman_rating_expected"]
    assert rating == round(frame["expected_strokes"].iloc[0], 1)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--holes", "3"], "--holes '3': allowed: hole numbers 1-2"),
        (["-n", "1"], "-n '1': allowed: a whole number from 2 to 2**63 - 1"),
        (["--putts", "0"], "--putts '0'"),
        (["--putts", "1e9"], "--putts '1e9': allowed: a whole number from 2 to 100000"),
        (["--elevation-crs", "EPSG:32633"], "--elevation-crs: is for --elevation"),
        (
            ["--elevation", "/nonexistent.tif"],
            "--elevation /nonexistent.tif: no such file: allowed: a GeoTIFF",
        ),
        # One play a hole: every round the same, its better half its average, without a word.
        (["--plays", "1"], "--plays 1: allowed: a whole number of at least 100 for a rating"),
    ],
)
def test_bad_arguments_end_in_one_line(rated, tmp_path, capsys, args, message):
    course = rated[2]
    out = tmp_path / "r.parquet"
    code = main(["rate", str(course), "-o", str(out), *args])
    err = capsys.readouterr().err
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_a_map_without_holes_ends_in_one_line(tmp_path, capsys):
    course = open_course(400, pars=(4,))
    course["features"] = [f for f in course["features"] if f["properties"].get("golf") != "hole"]
    (tmp_path / "none.geojson").write_text(json.dumps(course))
    code = main(["rate", str(tmp_path / "none.geojson")])
    err = capsys.readouterr().err
    assert code == 2 and "no golf=hole LineString" in err and len(err.strip().splitlines()) == 1


def _rate_open(tmp_path, name, elevation=None, **course):
    """The scratch and bogey expected strokes on a made-up 400-yd par 4 (small settings), on
    the ground of ``elevation`` where given."""
    from mcrun.play.rating import rate

    path = tmp_path / f"{name}.geojson"
    path.write_text(json.dumps(open_course(400, pars=(4,), **course)))
    _, holes, *_ = course_holes(path, putting={"n": 8, "resolution_m": 2.0}, elevation=elevation)
    rating = rate(holes, n=12, seed=3, coarse_m=15.0, fine_m=6.0, plays=200)
    return [rating.rating(p) for p in ("scratch", "bogey")]


@pytest.fixture(scope="module")
def open_400(tmp_path_factory):
    """``_rate_open`` of the open hole itself."""
    return _rate_open(tmp_path_factory.mktemp("open"), "open")


def test_water_where_the_bogey_player_lands_costs_him_more_and_wider_fairways_cost_less(
    tmp_path, open_400
):
    """The system's obstacles as it says they move a rating: water across the hole from 150 to
    185 m (where the bogey player's drive of 200 yd, 183 m, comes down; the scratch player's
    carries it) raises the bogey player's score more than the scratch player's; fairways 80 m
    wide instead of 40 lower both."""
    open_scratch, open_bogey = open_400
    wet_scratch, wet_bogey = _rate_open(tmp_path, "wet", water={1: (150.0, 185.0)})
    wide_scratch, wide_bogey = _rate_open(tmp_path, "wide", fairway_width_m=80.0)
    assert wet_bogey - open_bogey > wet_scratch - open_scratch + 0.05
    assert wet_bogey > open_bogey
    assert wide_scratch < open_scratch and wide_bogey < open_bogey


def test_a_course_uphill_plays_longer(tmp_path, open_400):
    """``elevation``: the same 400-yd hole climbing 8 % from its tee to 30 m short of its pin
    (29 m up; its green level), a lattice of survey points (a CSV of lon, lat, elevation) 10 m
    apart: both players' scores rise, by more than 0.15 strokes (the same shots flown)."""
    from mcrun.hole.synthetic import _lonlat

    length = 400 * YARD_M
    rows = ["lon,lat,elevation"]
    for x in np.arange(-100.0, length + 101.0, 10.0):
        for y in np.arange(-100.0, 101.0, 10.0):
            lon, lat = _lonlat(x, y)
            rows.append(f"{lon},{lat},{0.08 * min(max(x, 0.0), length - 30.0):.3f}")
    (tmp_path / "uphill.csv").write_text("\n".join(rows) + "\n")
    up = _rate_open(tmp_path, "uphill", elevation=tmp_path / "uphill.csv")
    for flat, climbing in zip(open_400, up, strict=True):
        assert climbing > flat + 0.15


def test_a_scorecard_moves_each_tee_up_its_line(tmp_path, capsys):
    """A scorecard (hole,yards) puts each tee that far from the end of its hole's line; a tee
    set longer than the line, a hole missing from it, a bad row: one line, exit 2."""
    course = tmp_path / "open.geojson"
    course.write_text(json.dumps(open_course(540, pars=(3, 4))))
    card = tmp_path / "white.csv"
    card.write_text("hole,yards\n1,180\n2,300\n")
    numbers, holes, *_ = course_holes(course, scorecard=card)
    assert numbers == [1, 2]
    assert [h.length_m / YARD_M for h in holes] == pytest.approx([180.0, 300.0], abs=0.5)
    assert [h.par for h in holes] == [3, 4]
    card.write_text("Hole; Yards\n1;180\n\n2;300\n")  # a spreadsheet's, in its locale
    assert course_holes(course, scorecard=card)[1][1].length_m == holes[1].length_m
    for text, message in [
        ("hole,yards\n1,180\n2,400\n", "hole 2: 400 yd is longer than the hole's line"),
        ("hole,yards\n1,180\n", "no row for hole 2"),
        ("hole,yards\n1,180\n3,300\n", "row 3: hole 3: allowed: each hole of the map once"),
        ("hole,yards\n1,far\n", "row 2: hole '1', yards 'far'"),
        ("hole,length\n1,180\n", "the columns hole,yards and a row per hole; found hole,length"),
        ("hole,yards,yards\n1,180,150\n2,300,280\n", "column 'yards' twice"),
        ("hole,yards\n1,180,5\n2,300\n", "row 2: 3 fields: allowed: hole,yards"),  # (180 before)
        ("hole,yards\n1,1_80\n2,300\n", "row 2: hole '1', yards '1_80'"),  # (read as 180)
    ]:
        card.write_text(text)
        out = tmp_path / "r.parquet"
        code = main(["rate", str(course), "--holes", "1-2", "--scorecard", str(card), "-o",
                     str(out)])  # fmt: skip
        err = capsys.readouterr().err
        assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err
        assert not out.exists()


def test_a_rating_on_dask_is_the_local_rating(tmp_path):
    """Each player's hole solved on a worker of a local Dask cluster of two (a par 3, small
    settings): the same rating, bit for bit (expected strokes, their errors, every play)."""
    from distributed import Client

    from mcrun.play.rating import rate
    from mcrun.run import distributed

    path = tmp_path / "open.geojson"
    path.write_text(json.dumps(open_course(200, pars=(3,))))
    _, holes, *_ = course_holes(path, putting={"n": 8, "resolution_m": 2.0})
    settings = dict(n=4, seed=5, coarse_m=20.0, fine_m=8.0, plays=100)
    local = rate(holes, **settings)
    cluster = distributed.local_cluster(2)
    try:
        with Client(cluster) as client:
            there = rate(holes, client=client, **settings)
    finally:
        cluster.close()
    for player in local.players:
        for a, b in zip(local.scores[player], there.scores[player], strict=True):
            assert (a.expected_strokes, a.expected_strokes_se) == (
                b.expected_strokes,
                b.expected_strokes_se,
            )
            np.testing.assert_array_equal(a.scores, b.scores)


def _with_tees(course, tees):
    """``course`` (a made-up course map) with square tee areas 10 m a side centred at
    ``tees``: [(hole number, x_m along its line from its tee)] (holes lie HOLE_SPACING_M
    apart, each from west to east)."""
    from mcrun.hole.synthetic import HOLE_SPACING_M, _ring

    for number, x in tees:
        y = (number - 1) * HOLE_SPACING_M
        ring = _ring([(x - 5, y - 5), (x + 5, y - 5), (x + 5, y + 5), (x - 5, y + 5)])
        course["features"].append(
            {
                "type": "Feature",
                "properties": {"golf": "tee"},
                "geometry": {"type": "Polygon", "coordinates": ring},
            }
        )
    return course


def test_the_map_s_tee_boxes_are_each_hole_s_from_the_back(tmp_path):
    """``hole_tees``: each tee area counts for the hole whose line passes nearest, back to
    front (one drawn 20 m behind the line's start is the back tee); ``--tees K`` takes each
    hole's K-th from the back, ``forward`` its front one, and a hole with fewer takes its front
    one and says so."""
    from mcrun.hole.osm import read_course
    from mcrun.hole.tees import hole_tees

    course = _with_tees(open_course(540, pars=(3, 4)), [(1, 40.0), (1, -20.0), (2, 60.0)])
    path = tmp_path / "tees.geojson"
    path.write_text(json.dumps(course))
    boxes = hole_tees(read_course(path))
    assert sorted(boxes) == [1, 2] and [len(boxes[1]), len(boxes[2])] == [3, 2]
    _, back, *_ = course_holes(path)
    lengths = [h.length_m for h in back]
    for tees, moved in [(1, (-20.0, 0.0)), (2, (0.0, 60.0)), (3, (40.0, 60.0)),
                        ("forward", (40.0, 60.0))]:  # fmt: skip
        _, holes, _, notes = course_holes(path, tees=tees)
        expected = [length - x for length, x in zip(lengths, moved, strict=True)]
        assert [h.length_m for h in holes] == pytest.approx(expected, abs=0.3), tees
        assert notes == (["hole 2 has 2 tee box(es): its front one"] if tees == 3 else [])


def test_riverside_s_tee_boxes(tmp_path):
    """The library's course map: 66 of its 67 tee areas on 18 holes, two to four a hole, the
    back one where the hole's line starts (within 2 m), the others farther along it."""
    from mcrun.hole.geo import Frame
    from mcrun.hole.osm import read_course
    from mcrun.hole.tees import hole_tees

    course = read_course(COURSE)
    boxes = hole_tees(course)
    assert sorted(boxes) == list(range(1, 19))
    assert sum(len(t) for t in boxes.values()) == 66
    assert all(2 <= len(t) <= 4 for t in boxes.values())
    for number, tees in boxes.items():
        line = course.hole(f"#{number}")
        frame = Frame(*line.lonlat[-1], 0.0)
        to_pin = [float(np.hypot(*frame.to_xy(*tee))) for tee in tees]
        assert np.hypot(*Frame(*line.lonlat[0], 0.0).to_xy(*tees[0])) < 2.0, number
        assert to_pin == sorted(to_pin, reverse=True), number


@pytest.mark.parametrize(("args", "message"), [
    (["--tees", "front"], "--tees 'front': allowed: back"),
    (["--tees", "2", "--scorecard", "card.csv"], "--tees and --scorecard: give one tee set"),
])  # fmt: skip
def test_a_bad_tee_set_ends_in_one_line(rated, tmp_path, capsys, args, message):
    out = tmp_path / "r.parquet"
    code = main(["rate", str(rated[2]), "-o", str(out), *args])
    err = capsys.readouterr().err
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


def test_the_holes_are_numbered_by_their_refs_else_taken_in_the_map_s_order(tmp_path):
    """``play_order``: holes whose refs are 1-N by their refs, whatever the map's order;
    without refs in the map's order, said with the walks from each green to the next tee (the
    library's course: 39-127 m), doubted where one is over 300 m (the made-up course's holes
    lie side by side, each green about 400 m from the next tee)."""
    from mcrun.cli.rate import play_order
    from mcrun.hole.osm import read_course

    course = open_course(1200, pars=(4, 4, 4))
    lines = [f for f in course["features"] if f["properties"].get("golf") == "hole"]
    for line, ref in zip(lines, ("2", "3", "1"), strict=True):
        line["properties"]["ref"] = ref
    (tmp_path / "refs.geojson").write_text(json.dumps(course))
    assert play_order(read_course(tmp_path / "refs.geojson")) == ({2: 1, 3: 2, 1: 3}, None)
    for line in lines:
        del line["properties"]["ref"]
    (tmp_path / "none.geojson").write_text(json.dumps(course))
    order, note = play_order(read_course(tmp_path / "none.geojson"))
    assert order == {1: 1, 2: 2, 3: 3}
    assert "hole 2's tee is 4" in note and "the map's order may not be the course's" in note
    order, note = play_order(read_course(COURSE))
    assert order == {k: k for k in range(1, 19)}
    assert note.endswith("taken in its order (each green 39-127 m from the next tee)")


def test_a_map_of_two_courses_or_a_hole_drawn_twice_is_not_one_course(tmp_path):
    """A map of two courses 178 km apart was rated as one (Course Rating 11.0 for five holes of
    both); a hole's line copied in the map was rated twice. Holes chosen across courses are
    rated, with a note."""
    two = Path(__file__).parent / "data" / "maps" / "two-courses.geojson"
    with pytest.raises(InputError, match=r"two-courses.geojson: its holes lie on 2 courses "
                       r"\(North Links: holes 1-2; South Park Golf: holes 3-5\): a rating is of "
                       r"one course; allowed: its holes, chosen with --holes$"):  # fmt: skip
        course_holes(two)
    numbers, holes, _, notes = course_holes(two, "1-2")
    assert numbers == [1, 2] and not any("courses" in note for note in notes)
    notes = course_holes(two, "2-3")[3]
    assert notes[-1] == ("the holes rated lie on 2 courses of the map (North Links: hole 2; "
                         "South Park Golf: hole 3)")  # fmt: skip
    course = open_course(700, pars=(4, 3))
    hole = next(f for f in course["features"] if f["properties"].get("golf") == "hole")
    course["features"].append(json.loads(json.dumps(hole)))
    (tmp_path / "twice.geojson").write_text(json.dumps(course))
    with pytest.raises(InputError, match=r"twice.geojson: holes 1 and 3 are one golf=hole line "
                       r"drawn twice \(the same points\)"):  # fmt: skip
        course_holes(tmp_path / "twice.geojson")


def test_plan_rating_names_holes_numbers_and_players_it_cannot_rate():
    """A hole number given twice was solved once, the other dropped (a rating of two holes
    with one's scores); a player given twice, once; n = 0 and a spacing of 0 ran at the
    defaults; a Hole alone or no holes were a TypeError or an IndexError."""
    from mcrun.hole.hole import load_hole
    from mcrun.play import PlayerError
    from mcrun.play.rating import plan_rating
    from mcrun.run import scenario as sc

    hole = load_hole(sc.library_folder() / "holes" / "riverside-2.toml")
    for given, says in (
        ({"holes": [hole, hole], "numbers": [1, 1]}, r"^numbers \[1, 1\]: allowed: one whole"),
        ({"holes": [hole], "numbers": ["7"]}, r"^numbers \['7'\]: allowed: one whole number"),
        ({"holes": [hole], "players": ["scratch", "scratch"]}, r"^players \['scratch', 'scr"),
        ({"holes": [hole], "players": []}, r"^players \[\]: allowed: one or more players"),
        ({"holes": hole}, r"^holes Hole\(.*: allowed: a list of the course's holes$"),
        ({"holes": []}, r"^holes \[\]: allowed: a list"),
        ({"holes": [hole], "n": 0}, r"^n 0: allowed: a whole number of at least 2$"),
        ({"holes": [hole], "fine_m": 0}, r"^fine_m 0: allowed: a number of metres, at least 1"),
    ):  # fmt: skip
        with pytest.raises(PlayerError, match=says):
            plan_rating(plays=100, **given)
