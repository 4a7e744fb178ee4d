"""``mcrun replay``'s per-club tables written beside its Parquet (``STEM-clubs.csv``,
``STEM-device.csv``), equal to ``mcrun.run.clubs``'s; and its pictures per club (``--plot``,
``mcrun plot REPLAY.parquet``): one PNG per plot of the figure's size, a one-line error
naming ``pip install 'mcrun[plot]'`` without matplotlib, nothing written."""

import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun.cli import main
from mcrun.report import replay_plots
from mcrun.run import clubs, replay

DATA = Path(__file__).parent / "data" / "monitors"


def session(path):
    """A session of three clubs in mcrun's own columns, without the device's results."""
    rows = []
    for club, speed_mph, launch_deg, spin_rpm in (
        ("Driver", 160.0, 11.0, 2700.0),
        ("7 Iron", 118.0, 16.5, 7000.0),
        ("PW", 100.0, 24.0, 9000.0),
    ):
        for k in range(8):
            rows.append(
                {
                    "club": club,
                    "ball_speed_mph": speed_mph + (k - 3.5) * 0.8,
                    "launch_deg": launch_deg + 0.2 * (k % 3),
                    "spin_rpm": spin_rpm + 60.0 * (k % 4),
                    "azimuth_deg": 0.5 * (k - 4),
                }
            )
    pd.DataFrame(rows).to_csv(path, index=False)
    return path


def one_line_error(capsys, code, *needles):
    out, err = capsys.readouterr()
    assert code == 2 and out == "", err
    assert err.startswith("mcrun: error: ") and err.count("\n") == 1, err
    for needle in needles:
        assert needle in err, err


def test_the_tables_beside_the_output_are_clubs_tables(tmp_path, capsys):
    out = tmp_path / "replayed.parquet"
    assert main(["replay", str(DATA / "trackman-normalized.csv"), "-o", str(out)]) == 0
    stdout, _ = capsys.readouterr()
    frame = pd.read_parquet(out)
    for name, table in (
        ("replayed-clubs.csv", clubs.club_summary(frame)),
        ("replayed-device.csv", clubs.device_comparison(frame)),
    ):
        assert f"wrote {tmp_path / name}\n" in stdout
        written = pd.read_csv(tmp_path / name, keep_default_na=False, na_values=[""])
        assert list(written.columns) == list(table.columns)
        text = [c for c in ("club", "quantity") if c in table]
        for column in text:
            assert list(written[column]) == list(table[column])
        for column in table.columns.drop(text):
            # Written with Python's shortest round-trip repr: equal to the last bit.
            np.testing.assert_array_equal(
                written[column].to_numpy(dtype=float), table[column].to_numpy(dtype=float)
            )
    device = pd.read_csv(tmp_path / "replayed-device.csv")
    carry = device[(device["club"] == "all") & (device["quantity"] == "carry_m")].iloc[0]
    diff = frame["carry_m"] - frame["device_carry_m"]
    assert carry["bias"] == pytest.approx(diff.mean(), rel=1e-15)
    assert carry["rmse"] == pytest.approx(np.sqrt((diff**2).mean()), rel=1e-15)


def test_shots_without_a_club_are_one_group_named_so(tmp_path):
    """A blank or missing club cell in a file that names clubs: one group, "(no club)" (a row
    of no name in the tables before), its shots the blank and the missing ones."""
    source = tmp_path / "session.csv"
    source.write_text(
        "club,ball_speed_mph,launch_deg,spin_rpm\nDriver,150,12,2800\n ,120,16,7000\n,121,16,7000\n"
    )
    frame = replay.replay(source)
    table = clubs.club_summary(frame)
    assert list(table["club"]) == ["Driver", clubs.NO_CLUB]
    assert list(table["shots"]) == [1, 2]


def test_report_of_a_replayed_file_points_to_plot(tmp_path, capsys):
    """``mcrun report`` of a file of ``mcrun replay`` said "is not a folder: give the folder
    that 'mcrun run' wrote"; it says to draw it with ``mcrun plot``, which takes it."""
    out = tmp_path / "r.parquet"
    assert main(["replay", str(session(tmp_path / "s.csv")), "-o", str(out), "--quiet"]) == 0
    capsys.readouterr()
    code = main(["report", str(out)])
    one_line_error(capsys, code, "a file of 'mcrun replay'", f"'mcrun plot {out}'")


def test_a_file_without_the_devices_results_has_no_device_table(tmp_path):
    source = session(tmp_path / "session.csv")
    frame = replay.replay_file(source, tmp_path / "r.parquet")
    assert sorted(os.listdir(tmp_path)) == ["r-clubs.csv", "r.parquet", "session.csv"]
    assert frame.attrs["written"] == [tmp_path / "r.parquet", tmp_path / "r-clubs.csv"]
    table = pd.read_csv(tmp_path / "r-clubs.csv")
    assert list(table["club"]) == ["Driver", "7 Iron", "PW"]
    assert table["shots"].tolist() == [8, 8, 8]
    mine = frame[frame["club"] == "7 Iron"]["carry_m"]
    assert table["carry_m_mean"][1] == pytest.approx(mine.mean(), rel=1e-15)
    assert table["carry_m_sd"][1] == pytest.approx(mine.std(ddof=1), rel=1e-14)
    assert table["gap_m"][0] == pytest.approx(
        table["carry_m_mean"][0] - table["carry_m_mean"][1], rel=1e-15
    )


def test_an_existing_table_is_kept_without_force_and_nothing_is_written(tmp_path, capsys):
    source = session(tmp_path / "session.csv")
    (tmp_path / "r-clubs.csv").write_text("mine\n", encoding="utf-8")
    code = main(["replay", str(source), "-o", str(tmp_path / "r.parquet")])
    one_line_error(capsys, code, "r-clubs.csv already exists: use --force")
    assert sorted(os.listdir(tmp_path)) == ["r-clubs.csv", "session.csv"]
    assert (tmp_path / "r-clubs.csv").read_text(encoding="utf-8") == "mine\n"
    assert main(["replay", str(source), "-o", str(tmp_path / "r.parquet"), "--force"]) == 0
    assert pd.read_csv(tmp_path / "r-clubs.csv")["shots"].sum() == 24


def png_size(path):
    from matplotlib.image import imread

    image = imread(path)
    assert image[..., :3].std() > 0.05  # not blank
    return image.shape[1], image.shape[0]


def test_replay_plot_draws_the_clubs_and_the_device(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    out = tmp_path / "tm.parquet"
    argv = ["replay", str(DATA / "trackman-normalized.csv"), "-o", str(out), "--plot"]
    assert main([*argv, "--dpi", "50"]) == 0
    stdout, _ = capsys.readouterr()
    for name in ("tm-clubs.png", "tm-device.png"):
        assert f"wrote {tmp_path / name}\n" in stdout
    width = replay_plots.FIGURE_WIDTH_IN * 50
    assert png_size(tmp_path / "tm-clubs.png") == (width, replay_plots.CLUBS_HEIGHT_IN * 50)
    # Six quantities the export gives, two a row: three rows.
    assert png_size(tmp_path / "tm-device.png") == (
        width,
        round(3 * replay_plots.DEVICE_ROW_HEIGHT_IN * 50),
    )
    # An existing plot is kept without --force, and nothing else is written.
    out.unlink()
    code = main([*argv, "--dpi", "50"])
    one_line_error(capsys, code, "tm-clubs.png already exists: use --force")
    assert not out.exists()
    # mcrun plot of a replay's Parquet draws the same pictures, into -o.
    assert main([*argv, "--force"]) == 0
    capsys.readouterr()
    assert main(["plot", str(out), "-o", str(tmp_path / "pics"), "--dpi", "50"]) == 0
    stdout, _ = capsys.readouterr()
    assert sorted(os.listdir(tmp_path / "pics")) == ["tm-clubs.png", "tm-device.png"]
    assert stdout == "".join(f"wrote {tmp_path / 'pics' / n}\n" for n in sorted(os.listdir(
        tmp_path / "pics")))  # fmt: skip


def test_plot_of_a_session_without_device_or_clubs(tmp_path):
    pytest.importorskip("matplotlib")
    source = session(tmp_path / "session.csv")
    frame = pd.read_csv(source).drop(columns="club")
    frame.to_csv(source, index=False)
    written = replay_plots.write_replay_plots(replay.replay(source), tmp_path / "r.parquet", dpi=40)
    assert written == [tmp_path / "r-clubs.png"]  # one group, "all"; no device
    png_size(written[0])


def test_a_club_named_outside_the_font_and_shots_that_all_fail_are_one_warning(tmp_path, capsys):
    """Clubs named in Japanese or with an emoji: matplotlib warned once a character, each with
    its source line, and an empty legend where no shot ended ok; now one line says which
    characters are drawn as boxes, and the panel says no shot ended ok."""
    pytest.importorskip("matplotlib")
    source = tmp_path / "session.csv"
    source.write_text(
        "club,ball_speed_mph,launch_deg,spin_rpm,carry_yd\n"
        "7番アイアン,120,16,7000,160\n\N{GOLFER}Driver,150,12,2800,240\n",
        encoding="utf-8",
    )
    out = tmp_path / "r.parquet"
    argv = ["replay", str(source), "-o", str(out), "--plot", "--quiet", "--dpi", "40"]
    assert main([*argv, "--turf", "green", "--slope", "30"]) == 0
    lines = capsys.readouterr().err.splitlines()
    said = [line for line in lines if "not in the font" in line]
    assert len(said) == 1 and said[0].startswith("mcrun: warning: 5 character(s) not in the font")
    assert said[0].endswith("drawn as boxes: 番 ア イ ン \N{GOLFER}")
    assert all(line.startswith("mcrun: warning: ") for line in lines), lines
    assert not any("legend" in line for line in lines)
    png_size(tmp_path / "r-clubs.png")


def test_replay_plot_without_matplotlib_is_one_line_and_writes_nothing(
    tmp_path, monkeypatch, capsys
):
    source = session(tmp_path / "session.csv")
    for name in ("matplotlib", "matplotlib.figure", "matplotlib.backends.backend_agg"):
        monkeypatch.setitem(sys.modules, name, None)
    code = main(["replay", str(source), "-o", str(tmp_path / "r.parquet"), "--plot"])
    one_line_error(capsys, code, "needs matplotlib", "pip install 'mcrun[plot]'")
    assert os.listdir(tmp_path) == ["session.csv"]


def test_an_interrupted_replay_plot_leaves_no_picture(tmp_path, monkeypatch):
    """Ctrl-C while the second picture is drawn: neither picture is left, under its final name
    or a temporary one (all or nothing, as a run's files)."""
    pytest.importorskip("matplotlib")
    from mcrun.report import style

    source = tmp_path / "session.csv"  # a TrackMan export: with the device's results
    source.write_bytes((Path(__file__).parent / "data" / "monitors" / "trackman.csv").read_bytes())
    frame = replay.replay(source)
    assert len(replay_plots.figures(frame, "r")) == 2  # the clubs and the device
    drawn = []
    png_bytes = style.png_bytes

    def second_interrupted(fig, dpi):
        drawn.append(fig)
        if len(drawn) == 2:
            raise KeyboardInterrupt
        return png_bytes(fig, dpi)

    monkeypatch.setattr(style, "png_bytes", second_interrupted)
    with pytest.raises(KeyboardInterrupt):
        replay_plots.write_replay_plots(frame, tmp_path / "r.parquet", dpi=40)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["session.csv"]


def test_replay_plot_interrupted_says_what_was_written(tmp_path, monkeypatch, capsys):
    """Ctrl-C while `mcrun replay --plot` draws: the replay's files are in place (written
    before the pictures), and the one line says so, not "nothing was written"."""
    pytest.importorskip("matplotlib")
    from mcrun.report import style

    source = session(tmp_path / "session.csv")

    def interrupted(fig, dpi):
        raise KeyboardInterrupt

    monkeypatch.setattr(style, "png_bytes", interrupted)
    out = tmp_path / "r.parquet"
    assert main(["replay", str(source), "-o", str(out), "--plot"]) == 130
    err = capsys.readouterr().err
    assert err.startswith(f"mcrun: interrupted: wrote {out}") and "pictures were not" in err, err
    assert out.exists() and not list(tmp_path.glob("*.png"))


def test_plot_of_a_damaged_replay_file_is_one_line(tmp_path, capsys):
    """A replay's Parquet without a column the pictures draw, with text in it, or with no
    rows; a Parquet file that mcrun replay did not write: one line each, nothing drawn, where
    they ended in a KeyError or said "is not a folder"."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    pytest.importorskip("matplotlib")
    out = tmp_path / "tm.parquet"
    assert main(["replay", str(DATA / "trackman-normalized.csv"), "-o", str(out), "--quiet"]) == 0
    capsys.readouterr()
    table = pq.read_table(out)
    k = table.schema.get_field_index("carry_m")
    text = pa.array(table["carry_m"].to_numpy().astype(str))
    cases = {
        "no_carry": (table.drop_columns(["carry_m"]), "no_carry.parquet was not written by "
                     "mcrun replay: no column carry_m"),
        "text": (table.set_column(k, "carry_m", text), "text.parquet: column carry_m is "),
        "empty": (table.slice(0, 0), "empty.parquet: no shots to draw"),
        "bare": (table.replace_schema_metadata(None), "bare.parquet is a file but not one that "
                 "mcrun replay wrote (its provenance says file = None"),
    }  # fmt: skip
    for name, (damaged, says) in cases.items():
        path = tmp_path / f"{name}.parquet"
        pq.write_table(damaged, path)
        code = main(["plot", str(path), "-o", str(tmp_path / name), "--dpi", "30"])
        one_line_error(capsys, code, says)
        assert not (tmp_path / name).exists()
