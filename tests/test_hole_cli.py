"""``mcrun hole``: the holes of a course map, one hole described and drawn, its errors."""

from pathlib import Path

import pytest

from mcrun.cli import main

HOLES = Path(__file__).resolve().parent.parent / "scenarios" / "holes"
MAPS = Path(__file__).resolve().parent / "data" / "maps"


def test_a_course_map_lists_its_holes(capsys):
    assert main(["hole", str(HOLES / "riverside-zagreb.osm.geojson")]) == 0
    out = capsys.readouterr().out.splitlines()
    rows = [line.split() for line in out[2:-1]]
    assert len(rows) == 18 and [int(r[0]) for r in rows] == list(range(1, 19))
    assert rows[1][3:5] == ["168.4", "184.2"]  # hole 2: m and yd
    assert " ".join(rows[1][5:]) == "Riverside Golf Zagreb, Natjecateljsko igralište, hole 2"
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
    assert areas["water_yellow"] > 2000 and areas["green"] > 500
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


def test_a_country_extract_lists_every_hole_by_its_course_and_marks_the_bad_one(capsys):
    # Two courses far apart (tests/data/maps/two-courses.geojson, hand-made like an Overpass
    # country export); South Park Golf's hole 2 (4th in the file) ends 51 m past its green.
    assert main(["hole", str(MAPS / "two-courses.geojson")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].endswith("two-courses.geojson: 5 holes on 2 courses (choose one with --hole N)")
    rows = out[2:7]
    titles = [row[38:].split("  ! ")[0] for row in rows]
    assert titles == [
        "North Links, hole 1",
        "North Links, hole 2",
        "South Park Golf, hole 1",  # its name tag is "1"
        "South Park Golf, hole 2",
        "South Park Golf, hole 3: Island Green",  # ref 3, name "Island Green"
    ]
    assert [row.split()[3] for row in rows] == ["323.6", "153.3", "303.5", "-", "143.2"]
    assert "!" not in "".join(rows[:3] + rows[4:])
    assert "  ! the pin [" in rows[3] and "(51.1 m from the nearest)" in rows[3]
    assert out[7].startswith("1 of 5 holes cannot be played as mapped (marked !)")
    assert "OpenStreetMap contributors, ODbL" in out[-1]


def test_a_hole_of_a_country_extract_is_titled_by_its_own_course(capsys):
    assert main(["hole", str(MAPS / "two-courses.geojson"), "--hole", "5"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("South Park Golf, hole 3: Island Green\n") and "par: 3" in out
    code = main(["hole", str(MAPS / "two-courses.geojson"), "--hole", "4"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "(51.1 m from the nearest)" in err


def test_a_kml_given_as_a_map_or_a_hole_is_named_as_kml(capsys, tmp_path):
    kml = tmp_path / "course.kml"
    kml.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n<kml xmlns="http://www.opengis.net/kml/2.2">'
        "<Document><Placemark><name>Hole 1</name><LineString><coordinates>15.89,45.77,0 "
        "15.891,45.771,0</coordinates></LineString></Placemark></Document></kml>\n"
    )
    for args in (["hole", str(kml)], ["hole", str(kml), "--hole", "1"]):
        assert main(args) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "not valid TOML" not in err
        assert f"{kml}: is a KML file (Google Earth), not a hole" in err
        assert "GeoJSON FeatureCollection (.geojson, .json)" in err and "ogr2ogr" in err
    named_json = tmp_path / "course.geojson"
    named_json.write_bytes(kml.read_bytes())
    assert main(["hole", str(named_json)]) == 2
    err = capsys.readouterr().err
    assert "course.geojson: is a KML file (Google Earth), not a course map" in err


def test_an_interrupted_hole_plot_leaves_no_picture(capsys, tmp_path, monkeypatch):
    """Ctrl-C while the map is drawn to its file: no picture under its final name (a 0-byte
    one would stand for a map that is not there), nor a temporary one; the next run writes it."""
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    savefig = Figure.savefig

    def interrupted(self, fname, *args, **kwargs):
        Path(fname).write_bytes(b"\x89PNG")  # Ctrl-C half way through the file
        raise KeyboardInterrupt

    monkeypatch.setattr(Figure, "savefig", interrupted)
    target = tmp_path / "hole2.png"
    assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(target)]) == 130
    assert list(tmp_path.iterdir()) == []
    monkeypatch.setattr(Figure, "savefig", savefig)
    assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(target)]) == 0
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    capsys.readouterr()
    # A picture there is replaced only with --force (a user's file was written over).
    target.write_bytes(b"mine")
    assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(target)]) == 2
    assert "already exists: use --force to replace it" in capsys.readouterr().err
    assert target.read_bytes() == b"mine"
    assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(target), "--force"]) == 0
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_plot_of_an_unknown_picture_format_is_one_line(capsys, tmp_path):
    """--plot map.xyz: matplotlib knows no such format; one line naming the option and the
    formats allowed, exit 2, nothing written (it was a traceback)."""
    target = tmp_path / "map.xyz"
    assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(target)]) == 2
    out, err = capsys.readouterr()
    assert err.count("\n") == 1 and "--plot" in err and ".png" in err, err
    assert out == ""  # refused before the hole is described
    assert list(tmp_path.iterdir()) == []


def test_a_picture_that_cannot_be_written_is_refused_before_the_description(capsys, tmp_path):
    """A folder where the picture goes, or a file where its folder goes: refused in one line
    naming --plot before the hole is described (the description came first, then the error)."""
    (tmp_path / "dir.png").mkdir()
    (tmp_path / "a-file").write_text("")
    for plot, says in ((tmp_path / "dir.png", "is a folder; give a file name"),
                       (tmp_path / "a-file" / "x.png", "a-file is not a folder")):  # fmt: skip
        assert main(["hole", str(HOLES / "riverside-2.toml"), "--plot", str(plot)]) == 2
        out, err = capsys.readouterr()
        assert out == "" and err.startswith(f"mcrun: error: --plot {plot}: ") and says in err
