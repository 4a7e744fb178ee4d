"""``mcrun paper -o DIR``: Penner (2002) Figs. 3-8 redrawn, and targets.md beside the paper.

The command runs once per module (small dpi). Its images must have the size asked for and show
something (pixel statistics); every number of its targets.md must be what the physics core
returns when called directly here, to the digits printed; and Fig. 8's backward runs must have
the paper's sign and order (1.11 m at 1000 rad/s, 4.74 m at 1200 rad/s, both back towards the
player).
"""

import math
import re

import numpy as np
import pytest

from mcrun import paper
from mcrun.api import bounce_once, simulate
from mcrun.cli import main
from mcrun.physics.bounce import critical_backspin_radps
from mcrun.physics.launch import launch_from_club
from mcrun.physics.turf import PRESETS

DPI = 40
FIGURES = ("fig3", "fig4", "fig5", "fig6", "fig7", "fig8")
PENNER_AIR = {"aero_model": "penner2002", "air_density_kgpm3": 1.204}


@pytest.fixture(scope="module")
def out_dir(tmp_path_factory):
    pytest.importorskip("matplotlib")  # the optional extra mcrun[plot]
    out = tmp_path_factory.mktemp("paper") / "figures"
    assert main(["paper", "-o", str(out), "--dpi", str(DPI)]) == 0
    return out


@pytest.fixture(scope="module")
def rows(out_dir):
    return paper.parse_targets_markdown((out_dir / "targets.md").read_text(encoding="utf-8"))


def row(rows, case_prefix, quantity_prefix):
    """The one row whose case and quantity start with the given prefixes."""
    found = [
        r
        for (case, quantity), r in rows.items()
        if case.startswith(case_prefix) and quantity.startswith(quantity_prefix)
    ]
    assert len(found) == 1, (case_prefix, quantity_prefix, len(found))
    return found[0]


def assert_printed(cell, value):
    """``cell`` is ``value`` rounded to the decimals printed."""
    decimals = len(cell.split(".")[1]) if "." in cell else 0
    assert float(cell) == pytest.approx(value, abs=0.5 * 10.0**-decimals + 1e-9), (cell, value)


def run_from_landing(speed, angle_deg, backspin, turf):
    summary, _ = paper.run_from_landing(speed, angle_deg, backspin, turf)
    return summary["final_x_m"], summary["first_bounce_length_m"]


# --- the files ---------------------------------------------------------------------------------


@pytest.mark.parametrize("name", FIGURES)
def test_figure_has_its_size_and_is_not_blank(out_dir, name):
    """Each PNG is the figure size times the dpi, and has content: grey levels that vary and
    more than a handful of distinct colours (text, axes, curves, antialiasing)."""
    from matplotlib.image import imread

    image = imread(out_dir / f"{name}.png")
    width_in, height_in = paper.FIGURE_SIZES_IN[name]
    assert image.shape[:2] == (round(height_in * DPI), round(width_in * DPI))
    rgb = image[..., :3]
    grey = rgb.mean(axis=2)
    assert grey.std() > 0.05
    assert (grey < 0.5).mean() > 0.005  # dark ink: text and lines
    colours = np.unique((rgb.reshape(-1, 3) * 255).round().astype(np.uint8), axis=0)
    assert len(colours) > 50


def test_targets_md_has_every_paper_value(rows):
    """Every row of the paper's table appears, with the paper's value as printed, and every
    qualitative finding (rolling/sliding, backward/forward, trends) matches."""
    assert len(rows) == len(paper.PAPER_VALUES)
    for _, case, quantity, value, decimals, source in paper.PAPER_VALUES:
        r = rows[case, quantity]
        assert r["source"] == source
        if value is None:
            assert r["paper"] == "—"
        elif isinstance(value, str):
            assert r["paper"] == value
        else:
            assert r["paper"] == f"{value:.{decimals}f}"
        if isinstance(value, str) and value != "negligible":
            assert r["mcrun - paper"] == "same", (case, quantity, r["mcrun"])


# --- the numbers, against direct calls of the core ----------------------------------------------


def test_bounce_rows_equal_the_bounce_model(rows):
    """Bounce model alone: the drives (mu_c 0.23 / 0.18, first bounce 2.82 / 1.17 m), the
    9-iron (critical backspin 903 rad/s; mu_c 0.28 / 0.33 / 0.38) and Haake's impact."""
    for prefix, impact in (
        ("drive, 35 m/s club", (26.8, 68.0, 224.0)),
        ("drive, 55 m/s club", (26.2, 46.2, 315.0)),
    ):
        b = bounce_once(*impact)
        assert_printed(row(rows, prefix, "mu_c")["mcrun"], b["mu_c"])
        assert_printed(row(rows, prefix, "first bounce height")["mcrun"], b["hop_height_m"])
        assert row(rows, prefix, "leaves")["mcrun"] == b["mode"]
    assert_printed(
        row(rows, "9-iron: lands", "critical backspin")["mcrun"],
        critical_backspin_radps(23.8, math.radians(34.0), PRESETS["green"]),
    )
    for w in (809, 1000, 1200):
        b = bounce_once(23.8, 34.0, w)
        assert_printed(row(rows, f"9-iron, {w} rad/s, green", "mu_c")["mcrun"], b["mu_c"])
    b = bounce_once(18.6, 44.4, 484.0)
    assert_printed(row(rows, "Haake:", "theta_c")["mcrun"], b["theta_c_deg"])
    assert_printed(row(rows, "Haake:", "mu_c")["mcrun"], b["mu_c"])
    assert_printed(row(rows, "Haake:", "e,")["mcrun"], b["e"])
    for prefix in ("Haake:", "Haake, measured"):
        assert_printed(row(rows, prefix, "rebound speed")["mcrun"], b["rebound_speed_mps"])
        assert_printed(row(rows, prefix, "rebound angle")["mcrun"], b["rebound_angle_deg"])
        assert_printed(row(rows, prefix, "rebound topspin")["mcrun"], -b["rebound_spin_radps"])


def test_launch_rows_equal_the_club_model(rows):
    """Launch: driver 0.200 kg at 13.3 deg, 35 / 55 m/s (48.8 / 74.3 m/s); irons 0.250 kg at
    40 m/s, 17 / 46 deg (56.6 / 42.5 m/s)."""
    for prefix, (club_speed, mass, loft) in (
        ("driver, 0.200 kg, loft 13.3 deg, 35 m/s", (35.0, 0.200, 13.3)),
        ("driver, 0.200 kg, loft 13.3 deg, 55 m/s", (55.0, 0.200, 13.3)),
        ("1-iron", (40.0, 0.250, 17.0)),
        ("9-iron, 0.250 kg", (40.0, 0.250, 46.0)),
    ):
        speed, angle, spin = launch_from_club(club_speed, mass, math.radians(loft))
        assert_printed(row(rows, prefix, "ball speed")["mcrun"], speed)
        assert_printed(row(rows, prefix, "launch angle")["mcrun"], math.degrees(angle))
        assert_printed(row(rows, prefix, "backspin")["mcrun"], spin)


def test_flight_rows_equal_the_simulated_landings(rows):
    """Flight with penner2002 in air of 1.204 kg/m^3 from the paper's four launches."""
    for prefix, launch in (
        ("driver 35 m/s:", (48.8, 10.7, 253.0)),
        ("driver 55 m/s:", (74.3, 10.7, 397.0)),
        ("1-iron: launch", (56.6, 13.8, 372.0)),
        ("9-iron: launch", (42.5, 35.4, 915.0)),
    ):
        out = simulate(
            ball_speed_mps=launch[0],
            launch_angle_deg=launch[1],
            spin_radps=launch[2],
            **PENNER_AIR,
        ).outcome
        assert_printed(row(rows, prefix, "landing speed")["mcrun"], out["landing_speed_mps"])
        assert_printed(row(rows, prefix, "landing angle")["mcrun"], out["landing_angle_deg"])
        assert_printed(row(rows, prefix, "landing backspin")["mcrun"], out["landing_spin_radps"])


def test_whole_run_rows_equal_the_simulated_runs(rows):
    """Figs. 4 and 6 from full shots (first bounce 2.82 / 1.17 m for the drives, 0.97 / 0.54 m
    for the 2- and 6-irons), Fig. 7 from the 9-iron's landing."""
    for v in (35, 45, 55):
        out = simulate(club_speed_mps=v, club_mass_kg=0.200, loft_deg=13.3, **PENNER_AIR).outcome
        prefix = f"Fig. 4, drive, {v} m/s"
        assert_printed(row(rows, prefix, "first bounce")["mcrun"], out["first_bounce_height_m"])
        assert_printed(row(rows, prefix, "run")["mcrun"], out["run_m"])
    for n in (2, 4, 6):
        loft = 17.0 + 3.625 * (n - 1)
        out = simulate(club_speed_mps=40.0, club_mass_kg=0.250, loft_deg=loft, **PENNER_AIR).outcome
        prefix = f"Fig. 6, {n}-iron (loft {loft:.3f} deg"
        assert_printed(row(rows, prefix, "impact angle")["mcrun"], out["landing_angle_deg"])
        assert_printed(row(rows, prefix, "first bounce")["mcrun"], out["first_bounce_height_m"])
    for w in (809, 1000, 1200):
        final_x, _ = run_from_landing(23.8, 34.0, w, "green")
        assert_printed(row(rows, f"Fig. 7, 9-iron landing, {w} rad/s", "rest")["mcrun"], final_x)


def test_fig8_backward_runs_have_the_papers_sign_and_order(rows):
    """Fig. 8, firm green (mu 0.25): negligible at 809 rad/s, then 1.11 m and 4.74 m back in the
    paper. Ours are what the shot loop gives (first hop's landing point to rest), positive (back
    towards the player), growing with spin, and the 809 rad/s one is negligible."""
    back = {}
    for w in (809, 1000, 1200):
        final_x, first_hop = run_from_landing(23.8, 34.0, w, "firm_green")
        r = row(rows, f"Fig. 8, 9-iron landing, {w} rad/s", "run back")
        assert_printed(r["mcrun"], first_hop - final_x)
        back[w] = float(r["mcrun"])
    assert row(rows, "Fig. 8, 9-iron landing, 809", "run back")["paper"] == "negligible"
    assert abs(back[809]) < paper.NEGLIGIBLE_M
    assert 0.0 < back[1000] < back[1200]
    for w, published in ((1000, "1.11"), (1200, "4.74")):
        r = row(rows, f"Fig. 8, 9-iron landing, {w} rad/s", "run back")
        assert r["paper"] == published
        diff = float(re.match(r"[+-][0-9.]+", r["mcrun - paper"]).group())
        assert diff == pytest.approx(back[w] - float(published), abs=1e-9)


# --- errors ------------------------------------------------------------------------------------


def test_missing_matplotlib_is_one_line(monkeypatch, tmp_path, capsys):
    """Without matplotlib the command says what to install, on one line, exit code 2."""
    monkeypatch.setitem(__import__("sys").modules, "matplotlib", None)
    assert main(["paper", "-o", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err == "mcrun: error: mcrun paper needs matplotlib: pip install 'mcrun[plot]'\n"
    assert not (tmp_path / "x").exists()


def test_unwritable_output_is_one_line(tmp_path, capsys):
    """An output folder that cannot be made (a file is in the way) ends with one line, exit 2."""
    pytest.importorskip("matplotlib")
    blocker = tmp_path / "file"
    blocker.write_text("")
    assert main(["paper", "-o", str(blocker / "figures")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcrun: error: -o: cannot write to ") and err.count("\n") == 1


@pytest.mark.parametrize("dpi", ["0", "5000", "high"])
def test_bad_dpi_is_a_usage_error(dpi, capsys):
    assert main(["paper", "-o", "x", "--dpi", dpi]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcrun: error: argument --dpi: ") and err.count("\n") == 1


def test_existing_figures_are_replaced_only_with_force(out_dir, tmp_path, capsys, monkeypatch):
    """-o DIR wrote over a user's targets.md and figures without a word; a folder where a
    figure goes was a traceback after half the figures were written."""
    before = (out_dir / "targets.md").read_bytes()
    assert main(["paper", "-o", str(out_dir), "--dpi", str(DPI)]) == 2
    err = capsys.readouterr().err
    assert err == (f"mcrun: error: -o {out_dir}: fig3.png already exists: use --force to "
                   "replace the figures and targets.md\n")  # fmt: skip
    assert (out_dir / "targets.md").read_bytes() == before
    (tmp_path / "p" / "fig8.png").mkdir(parents=True)
    assert main(["paper", "-o", str(tmp_path / "p"), "--force"]) == 2
    assert "p: fig8.png is a folder: allowed: a folder where fig8.png can be" in (
        capsys.readouterr().err
    )
    assert sorted(p.name for p in (tmp_path / "p").iterdir()) == ["fig8.png"]
    drawn = []
    monkeypatch.setattr(paper, "write_paper", lambda folder, dpi: drawn.append(folder) or [])
    assert main(["paper", "-o", str(out_dir), "--force"]) == 0 and drawn == [out_dir]
