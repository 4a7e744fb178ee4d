"""Groups struck from elsewhere on the hole (``hole.start`` in a group, or in ``[hole]``): the
shots start on the ground there, are aimed at the pin unless the group says, are scored from
there (the expected strokes of its lie and distance), and the run records where each point
started. Mistakes in a start are one line, exit 2, nothing written."""

import math
import textwrap

import numpy as np
import pytest

from mcrun.cli import main
from mcrun.hole.zones import PENALTY_ZONES, ZONE_KINDS
from mcrun.results.reader import open_run
from mcrun.run import aim, local
from mcrun.run import scenario as sc
from mcrun.run.scenario import ScenarioError
from mcrun.status import OK
from mcrun.strokes import tour_baseline

# One launch, no spread: every shot of a point is the same shot.
WEDGE = """
[launch]
ball_speed = "100 mph"
launch_angle = "24 deg"
spin = "8000 rpm"
"""
# A flat fairway, 300 m from the tee to the pin.
FAIRWAY = """
[hole]
length_m = 300.0
width_m = 80.0
surface = "fairway"
"""
APPROACH = """
[[group]]
name = "from the tee"

[[group]]
name = "approach"
hole.start = [120.0, 0.0]
"""


def write(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture(scope="module")
def approach_run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("starts")
    path = write(tmp, FAIRWAY + WEDGE + APPROACH)
    result = local.run_scenario(path, n=50, out_dir=tmp / "run", progress=False)
    return result.shots(), result.summary(), open_run(tmp / "run")


def test_a_group_struck_from_elsewhere_is_the_tee_shot_moved(approach_run):
    """On flat, uniform ground the approach is the tee shot moved 120 m up the line: the same
    carry and run (1 um), its finish 120 m further."""
    shots, _, _ = approach_run
    tee = shots[shots["group"] == "from the tee"].reset_index(drop=True)
    approach = shots[shots["group"] == "approach"].reset_index(drop=True)
    assert (tee["status"] == OK).all() and (approach["status"] == OK).all()
    for name in ("carry_m", "carry_lateral_m", "total_m", "apex_m", "run_m"):
        assert np.allclose(approach[name], tee[name], rtol=0.0, atol=1e-6), name
    assert np.allclose(approach["final_x_m"], tee["final_x_m"] + 120.0, rtol=0.0, atol=1e-6)
    assert np.allclose(approach["final_y_m"], tee["final_y_m"], rtol=0.0, atol=1e-6)


def test_a_group_is_scored_from_its_start(approach_run):
    """Strokes gained = E(start) - 1 - E(after), E(start) the Tour's from the fairway (the
    rectangle's one zone, the tee's too) at 300 m for the tee shot and 180 m for the approach."""
    shots, summary, _ = approach_run
    base = tour_baseline()
    for group, distance in (("from the tee", 300.0), ("approach", 180.0)):
        e_start = float(base.expected("fairway", distance))
        one = shots[shots["group"] == group]
        gained = e_start - 1.0 - one["expected_strokes_after"].to_numpy()
        assert np.allclose(one["strokes_gained"], gained, rtol=0.0, atol=1e-12), group
        row = summary[summary["group"] == group].iloc[0]
        assert row["expected_strokes_start"] == pytest.approx(e_start, abs=1e-12)


def test_the_run_records_where_each_point_started(approach_run):
    _, _, run = approach_run
    geometry = run.geometry
    assert geometry.starts_xy_m == ((0.0, 0.0), (120.0, 0.0))
    assert geometry.start_xy(1) == (120.0, 0.0)
    assert geometry.aim_deg == (0.0, 0.0)  # both at the pin, on the line


def test_a_start_off_the_line_aims_at_the_pin(tmp_path):
    """A group at (150, 20) aims at the pin (300, 0) unless it says: its shots (no spread)
    finish on the line from its start to the pin (1 mm), and with ``hole.aim`` on the line to
    that aim instead."""
    text = (
        FAIRWAY
        + WEDGE
        + """
    [[group]]
    name = "right side"
    hole.start = [150.0, 20.0]

    [[group]]
    name = "aimed"
    hole.start = [150.0, 20.0]
    hole.aim = [250.0, 30.0]
    """
    )
    shots, _ = local.run_dataframes(write(tmp_path, text), n=4)
    for group, (ax, ay) in (("right side", (300.0, 0.0)), ("aimed", (250.0, 30.0))):
        one = shots[shots["group"] == group]
        dx, dy = one["final_x_m"] - 150.0, one["final_y_m"] - 20.0
        cross = dx * (ay - 20.0) - dy * (ax - 150.0)
        assert np.abs(cross / math.hypot(ax - 150.0, ay - 20.0)).max() < 1e-3, group


def _water_point():
    hole = sc.load(sc.library_folder() / "par3-over-water.toml").hole
    t = hole.terrain()
    codes = [ZONE_KINDS.index(kind) for kind in PENALTY_ZONES]
    iy, ix = np.argwhere(np.isin(t.zone, codes))[0]
    return [float(t.x0_m + ix * t.cell_m), float(t.y0_m + iy * t.cell_m)]


@pytest.mark.parametrize(
    "text, message",
    [
        (FAIRWAY + WEDGE + '[[group]]\nname = "a"\nhole.start = [900.0, 0.0]\n',
         "group[0].hole.start: [900.0, 0.0] is off the hole's map"),
        (FAIRWAY + WEDGE + '[[group]]\nname = "a"\nhole.start = [100.0, 0.0]\n'
         "hole.aim = [50.0, 0.0]\n", "group[0].hole.aim: must be [x_m, y_m] ahead of the start"),
        # (at the pin, its default aim: the message named hole.aim, which was not given)
        (FAIRWAY + WEDGE + '[[group]]\nname = "a"\nhole.start = [300.0, 0.0]\n',
         "group[0].hole.start: [300.0, 0.0] is not short of the pin [300.0, 0.0]"),
        (FAIRWAY + WEDGE + '[[group]]\nname = "a"\nhole.start = "tee"\n',
         "group[0].hole.start: must be [x_m, y_m]"),
        (FAIRWAY + WEDGE + '[[group]]\nname = "a"\nhole.tee = [1.0, 2.0]\n',
         "group[0].hole.tee: unknown key; allowed: start, aim"),
        (WEDGE + '[[group]]\nname = "a"\nhole.start = [10.0, 0.0]\n',
         "group[0].hole: a group's start and aim are on a hole"),
        (FAIRWAY + "start = [400.0, 0.0]\n" + WEDGE, "hole.start: [400.0, 0.0] is off the"),
    ],
)  # fmt: skip
def test_bad_starts_give_one_line(tmp_path, capsys, text, message):
    path = write(tmp_path, text)
    with pytest.raises(ScenarioError, match=message.replace("[", r"\[").replace("]", r"\]")):
        sc.load(path)
    out = tmp_path / "run"
    assert main(["run", str(path), "-n", "10", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and message in err and str(path) in err
    assert not out.exists()


def test_a_start_in_a_penalty_area_is_refused(tmp_path):
    library = sc.library_folder()
    text = (library / "par3-over-water.toml").read_text()
    path = tmp_path / "s.toml"
    path.write_text(
        text.replace("[hole]", f"[hole]\nstart = {_water_point()}", 1).replace(
            '"holes/', f'"{library}/holes/'
        )
    )
    with pytest.raises(ScenarioError, match=r"hole.start: .* is in a penalty area \(water"):
        sc.load(path)


def test_the_aim_search_runs_from_the_start(tmp_path):
    """From a start other than the tee the search flies from there: its bearings are about the
    line from the start to the pin, its expected strokes from the start are the fairway's at
    its distance; groups starting at two places are refused."""
    text = FAIRWAY + "start = [150.0, 20.0]\n" + WEDGE
    scenario = sc.load(write(tmp_path, text))
    result = aim.search(scenario, n=50, offsets_m=[-5.0, 0.0, 5.0])
    assert result.start_xy_m == (150.0, 20.0) and not result.from_tee
    assert result.pin_distance_m == pytest.approx(math.hypot(150.0, 20.0), abs=1e-12)
    assert result.line_rad == pytest.approx(math.atan2(-20.0, 150.0), abs=1e-15)
    e = float(tour_baseline().expected("fairway", math.hypot(150.0, 20.0)))
    assert result.expected_start == pytest.approx(e, abs=1e-12)
    two = write(tmp_path, FAIRWAY + WEDGE + APPROACH)
    with pytest.raises(aim.AimError, match="compares its clubs from one place"):
        aim.check(sc.load(two))
