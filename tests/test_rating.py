"""A course rated by simulating the model players (``mcrun.play.rating``, ``mcrun rate``): the
handicap system's formulas, the rounds drawn from the holes' plays, the made-up open course,
and ``mcrun rate`` end to end on a small one with its one-line errors."""

import contextlib
import io
import json

import numpy as np
import pandas as pd
import pytest

from mcrun.cli import main
from mcrun.cli.rate import course_holes, holes_wanted
from mcrun.hole.synthetic import PAR_MIX, YARD_M, open_course, pars_for
from mcrun.play.rating import (
    BETTER_HALF,
    EXPECTED,
    CourseRating,
    HoleScore,
    course_rounds,
    par_by_length,
    slope_rating,
)
from mcrun.quantities import InputError
from mcrun.results import output


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
    """The rounds: the holes' plays drawn independently (their sum's variance the sum of
    theirs, within 5 %), the same for the same seed; the better half's mean below the
    expected score, which is the holes' sum."""
    means = [4.3, 3.4, 5.2, 4.6] * 4 + [4.1, 3.2]
    scores = {"scratch": _scores("scratch", means), "bogey": _scores("bogey", np.add(means, 1.1))}
    rating = CourseRating([None] * 18, ("scratch", "bogey"), scores, seed=7)
    expected = rating.rating("scratch", EXPECTED)
    assert expected == pytest.approx(sum(s.expected_strokes for s in scores["scratch"]))
    assert rating.rating("scratch", BETTER_HALF) < expected - 1.0
    variance = sum(s.scores.var() for s in scores["scratch"])
    assert rating.rounds["scratch"].var() == pytest.approx(variance, rel=0.05)
    again = course_rounds(scores["scratch"], 10_000, 7)
    np.testing.assert_array_equal(again, rating.rounds["scratch"])
    assert rating.slope(EXPECTED) == slope_rating(round(expected, 1),
                                                  round(rating.rating("bogey"), 1))  # fmt: skip


def test_holes_are_chosen_as_written():
    assert holes_wanted(None, 3) == [1, 2, 3]
    assert holes_wanted("1-3, 7,9-10", 18) == [1, 2, 3, 7, 9, 10]
    for bad in ("0-3", "5-2", "19", "a"):
        with pytest.raises(InputError, match="--holes"):
            holes_wanted(bad, 18)


def test_an_open_course_is_the_length_and_pars_it_was_made_of(tmp_path):
    """18 straight holes adding up to 6,500 yd (within 0.5 %, tee to pin), the pars of the mix,
    read back as a course map."""
    (tmp_path / "open.geojson").write_text(json.dumps(open_course(6500)))
    numbers, holes, by_length = course_holes(tmp_path / "open.geojson")
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
    assert f"expected: Course Rating {cr:.1f}, Bogey Rating {br:.1f}\n" in printed


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--holes", "3"], "--holes '3': allowed: hole numbers 1-2"),
        (["-n", "1"], "-n '1': allowed: a whole number of at least 2"),
        (["--putts", "0"], "--putts '0'"),
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


def _rate_open(tmp_path, name, **course):
    """The scratch and bogey expected strokes on a made-up 400-yd par 4 (small settings)."""
    from mcrun.play.rating import rate

    path = tmp_path / f"{name}.geojson"
    path.write_text(json.dumps(open_course(400, pars=(4,), **course)))
    _, holes, _ = course_holes(path, putting={"n": 8, "resolution_m": 2.0})
    rating = rate(holes, n=12, seed=3, coarse_m=15.0, fine_m=6.0, plays=200)
    return [rating.rating(p) for p in ("scratch", "bogey")]


def test_water_where_the_bogey_player_lands_costs_him_more_and_wider_fairways_cost_less(tmp_path):
    """The system's obstacles as it says they move a rating: water across the hole from 150 to
    185 m (where the bogey player's drive of 200 yd, 183 m, comes down; the scratch player's
    carries it) raises the bogey player's score more than the scratch player's; fairways 80 m
    wide instead of 40 lower both."""
    open_scratch, open_bogey = _rate_open(tmp_path, "open")
    wet_scratch, wet_bogey = _rate_open(tmp_path, "wet", water={1: (150.0, 185.0)})
    wide_scratch, wide_bogey = _rate_open(tmp_path, "wide", fairway_width_m=80.0)
    assert wet_bogey - open_bogey > wet_scratch - open_scratch + 0.05
    assert wet_bogey > open_bogey
    assert wide_scratch < open_scratch and wide_bogey < open_bogey


def test_a_scorecard_moves_each_tee_up_its_line(tmp_path, capsys):
    """A scorecard (hole,yards) puts each tee that far from the end of its hole's line; a tee
    set longer than the line, a hole missing from it, a bad row: one line, exit 2."""
    course = tmp_path / "open.geojson"
    course.write_text(json.dumps(open_course(540, pars=(3, 4))))
    card = tmp_path / "white.csv"
    card.write_text("hole,yards\n1,180\n2,300\n")
    numbers, holes, _ = course_holes(course, scorecard=card)
    assert numbers == [1, 2]
    assert [h.length_m / YARD_M for h in holes] == pytest.approx([180.0, 300.0], abs=0.5)
    assert [h.par for h in holes] == [3, 4]
    for text, message in [
        ("hole,yards\n1,180\n2,400\n", "hole 2: 400 yd is longer than the hole's line"),
        ("hole,yards\n1,180\n", "no row for hole 2"),
        ("hole,yards\n1,180\n3,300\n", "row 3: hole 3: allowed: each hole of the map once"),
        ("hole,yards\n1,far\n", "row 2: hole '1', yards 'far'"),
        ("hole,length\n1,180\n", "the columns hole,yards"),
    ]:
        card.write_text(text)
        out = tmp_path / "r.parquet"
        code = main(["rate", str(course), "--holes", "1-2", "--scorecard", str(card), "-o",
                     str(out)])  # fmt: skip
        err = capsys.readouterr().err
        assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err
        assert not out.exists()


def test_a_rating_on_dask_is_the_local_rating(tmp_path):
    """Each solve's shots flown on a local Dask cluster of two workers (a par 3, small
    settings): the same rating, bit for bit (expected strokes, their errors, every play)."""
    from distributed import Client

    from mcrun.play.rating import rate
    from mcrun.run import distributed

    path = tmp_path / "open.geojson"
    path.write_text(json.dumps(open_course(200, pars=(3,))))
    _, holes, _ = course_holes(path, putting={"n": 8, "resolution_m": 2.0})
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
