"""``mcrun hole``: the holes of a course map, one hole described and drawn, its errors."""

from pathlib import Path

import pytest

from mcrun.cli import main

HOLES = Path(__file__).resolve().parent.parent / "scenarios" / "holes"


def test_a_course_map_lists_its_holes(capsys):
    assert main(["hole", str(HOLES / "riverside-zagreb.osm.geojson")]) == 0
    out = capsys.readouterr().out.splitlines()
    rows = [line.split() for line in out[2:-1]]
    assert len(rows) == 18 and [int(r[0]) for r in rows] == list(range(1, 19))
    assert rows[1][3:] == ["168.4", "184.2"]  # hole 2: m and yd
    assert "OpenStreetMap contributors, ODbL" in out[-1]


def test_a_hole_file_is_described_and_drawn(capsys, tmp_path):
    png = tmp_path / "hole.png"
    assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "length tee-pin: 168.4 m (184.2 yd)" in out and "par: 3" in out
    assert "(c) OpenStreetMap contributors, ODbL" in out and "ground: flat" in out
    areas = {
        line.split()[0]: float(line.split()[1])
        for line in out.split("zone areas on the grid (m^2):\n")[1].splitlines()
        if line.startswith("  ")
    }
    grid = out.split("grid: ")[1].split()
    assert sum(areas.values()) == pytest.approx(int(grid[0]) * int(grid[2]) * 0.25, abs=8)
    assert areas["water"] > 2000 and areas["green"] > 500
    assert png.stat().st_size > 20_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_a_hole_of_the_map_chosen_on_the_command_line(capsys):
    assert main(["hole", str(HOLES / "riverside-zagreb.osm.geojson"), "--hole", "11"]) == 0
    assert "length tee-pin: 136.6 m" in capsys.readouterr().out


def test_errors_are_one_line_and_exit_2(capsys):
    code = main(["hole", str(HOLES / "riverside-zagreb.osm.geojson"), "--hole", "40"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert err.startswith("mcrun: error: ") and "the map has 18 golf=hole lines" in err
    code = main(["hole", str(HOLES / "riverside-zagreb.osm.geojson"), "--plot", "x.png"])
    assert code == 2 and "choose it with --hole N" in capsys.readouterr().err
