"""``mcrun plot RUN_DIR`` and ``mcrun report RUN_DIR``: the pictures and the page of a run.

Three small runs, made once per module: a single point large enough to be drawn as a density
(the library's pga-driver, with trajectories), a sweep drawn as dots (firm-vs-soft-greens, two
points, trajectories, several row groups per point) and two groups with a target. Each command
must write its files; every image must have the figure size times the dpi and show something
(pixel statistics); what is drawn must be what the files hold (histogram counts, ellipses,
the first trajectories); shots.parquet must be read one row group and only the drawn columns at
a time; the report must reference nothing outside itself and hold the scenario and the summary
numbers; and every mistake a user can make must end in one line and exit code 2.
"""

import base64
import html
import re
import shutil
import struct
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from mcrun.cli import main
from mcrun.report import figures, plots, run_view, style
from mcrun.report import html as report
from mcrun.results import output, reader, stats
from mcrun.run import scenario as sc
from mcrun.run.local import run_scenario

pytest.importorskip("matplotlib")  # the optional extra mcrun[plot]

LIBRARY = Path(__file__).resolve().parent.parent / "scenarios"
DPI = 40
SINGLE_N = run_view.SCATTER_MAX_SHOTS + 1000  # above the dot limit: drawn as a density
SWEEP_N = 1200

GROUPS_TOML = """\
[scenario]
name = "two-wedges"
question = "Where do two wedges finish around a flag at 100 m?"
shots = 500
seed = 7
target = ["100 m", "0 m"]

[launch]
launch_angle = { dist = "normal", mean = "28 deg", sd = "1.5 deg" }
spin = { dist = "normal", mean = "9000 rpm", sd = "600 rpm" }
azimuth = { dist = "normal", mean = "0 deg", sd = "1.0 deg" }

[turf]
preset = "green"

[[group]]
name = "gap wedge"
launch.ball_speed = { dist = "normal", mean = "92 mph", sd = "1 mph" }

[[group]]
name = "sand wedge"
launch.ball_speed = { dist = "normal", mean = "85 mph", sd = "1 mph" }
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """{name: run folder}: single (density, trajectories), sweep (dots, trajectories, three row
    groups per point), groups (dots, explicit target, no trajectories)."""
    root = tmp_path_factory.mktemp("plots")
    scenario = root / "two-wedges.toml"
    scenario.write_text(GROUPS_TOML, encoding="utf-8")
    made = {
        "single": run_scenario(
            LIBRARY / "pga-driver.toml",
            n=SINGLE_N,
            out_dir=root / "single",
            trajectories_every=200,
            progress=False,
        ),
        "sweep": run_scenario(
            LIBRARY / "firm-vs-soft-greens.toml",
            n=SWEEP_N,
            out_dir=root / "sweep",
            chunk_size=SWEEP_N // 3,
            trajectories_every=100,
            progress=False,
        ),
        "groups": run_scenario(scenario, n=400, out_dir=root / "groups", progress=False),
    }
    return {name: result.out_dir for name, result in made.items()}


@pytest.fixture(scope="module")
def plotted(runs):
    """{name: (plots folder, exit code, stdout)} of ``mcrun plot RUN_DIR -o DIR``."""
    out = {}
    for name, run_dir in runs.items():
        folder = run_dir.parent / f"{name}-plots"
        code = main(["plot", str(run_dir), "-o", str(folder), "--dpi", str(DPI)])
        out[name] = folder, code
    return out


@pytest.fixture(scope="module")
def page(runs):
    """The HTML report of the sweep."""
    path = runs["sweep"].parent / "sweep-report.html"
    assert main(["report", str(runs["sweep"]), "-o", str(path), "--dpi", str(DPI)]) == 0
    return path.read_text(encoding="utf-8")


def expected_files(points, trajectories):
    names = ["summary", "finish"] if points > 1 else []
    for k in range(points):
        names += [f"point{k:02d}-positions", f"point{k:02d}-distances"]
        if trajectories:
            names.append(f"point{k:02d}-trajectories")
    return {f"{n}.png" for n in names}


def kind_of(name):
    stem = Path(name).stem
    return stem.split("-")[-1] if stem.startswith("point") else stem


def assert_drawn(rgb):
    """An image that shows something: grey levels that vary, dark ink (text, axes, curves)
    and more than a handful of distinct colours."""
    grey = rgb.mean(axis=2)
    assert grey.std() > 0.05
    assert (grey < 0.5).mean() > 0.005
    colours = np.unique((rgb.reshape(-1, 3) * 255).round().astype(np.uint8), axis=0)
    assert len(colours) > 50


# --- mcrun plot --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "points", "trajectories"),
    [("single", 1, True), ("sweep", 2, True), ("groups", 2, False)],
)
def test_plot_writes_one_png_per_plot(plotted, name, points, trajectories):
    folder, code = plotted[name]
    assert code == 0
    assert {p.name for p in folder.iterdir()} == expected_files(points, trajectories)
    # What --force may delete with a run: its pictures' names, and no other.
    assert all(output.PLOT_NAME.fullmatch(p.name) for p in folder.iterdir())


@pytest.mark.parametrize("name", ["single", "sweep", "groups"])
def test_every_png_has_its_size_and_is_not_blank(plotted, name):
    from matplotlib.image import imread

    folder, _ = plotted[name]
    for path in sorted(folder.iterdir()):
        image = imread(path)
        width_in, height_in = style.FIGURE_SIZES_IN[kind_of(path.name)]
        assert image.shape[:2] == (round(height_in * DPI), round(width_in * DPI)), path.name
        assert_drawn(image[..., :3])


def test_plot_defaults_to_a_plots_folder_in_the_run(runs, tmp_path, capsys):
    """No -o: RUN_DIR/plots; every file written is printed."""
    run_dir = tmp_path / "copy"
    run_dir.mkdir()
    for name in (output.SHOTS_FILE, output.SUMMARY_FILE):
        (run_dir / name).write_bytes((runs["groups"] / name).read_bytes())
    assert main(["plot", str(run_dir), "--dpi", "30"]) == 0
    printed = capsys.readouterr().out.split()
    written = {p.name for p in (run_dir / plots.PLOTS_FOLDER).iterdir()}
    assert written == expected_files(2, False)
    assert len([w for w in printed if w.endswith(".png")]) == len(written)


# --- what is drawn is what the run holds --------------------------------------------------------


def ok_shots(run_dir, point, columns):
    shots = pd.read_parquet(run_dir / output.SHOTS_FILE, columns=["point", "status", *columns])
    return shots[(shots["point"] == point) & (shots["status"] == 0)]


@pytest.mark.parametrize(("name", "point"), [("single", 0), ("sweep", 1)])
def test_histograms_count_every_ok_shot(runs, name, point):
    """The binned histograms equal numpy's over the whole column, and every ok shot is in a
    bin or counted beyond the axis."""
    run = run_view.open_run(runs[name])
    drawn = run_view.read_point_shots(run, point)
    shots = ok_shots(runs[name], point, [q for q, _ in run_view.DISTANCES])
    assert drawn.n_ok == len(shots) == run.summary.loc[point, "n_ok"]
    for q, _ in run_view.DISTANCES:
        counts, _ = np.histogram(shots[q].to_numpy(), bins=drawn.edges[q])
        np.testing.assert_array_equal(drawn.hist[q], counts)
        assert drawn.hist[q].sum() + drawn.outside[q] == len(shots)


def test_a_large_point_is_binned_and_a_small_one_drawn_shot_by_shot(runs):
    """Above SCATTER_MAX_SHOTS the positions are a 2-D histogram of every ok shot; at or below
    it, every position is kept, in the file's order."""
    single = run_view.read_point_shots(run_view.open_run(runs["single"]), 0)
    assert not single.scatter
    for key in ("landing", "final"):
        assert single.density[key].sum() + single.beyond[key] == single.n_ok == SINGLE_N
        assert single.positions(key).shape == (0, 2)
    sweep = run_view.read_point_shots(run_view.open_run(runs["sweep"]), 1)
    assert sweep.scatter
    shots = ok_shots(runs["sweep"], 1, ["final_x_m", "final_y_m"])
    np.testing.assert_array_equal(sweep.positions("final"), shots[["final_x_m", "final_y_m"]])


@pytest.mark.parametrize("name", ["single", "sweep"])
def test_ellipses_are_the_summarys(runs, name):
    """The final position's 68 % and 95 % ellipses computed from the shots as they are read
    equal summary.parquet's (the landing ellipses are computed the same way)."""
    run = run_view.open_run(runs[name])
    for row in run.summary.to_dict("records"):
        drawn = run_view.read_point_shots(run, row["point"])
        for level in stats.ELLIPSE_LEVELS:
            a, b, angle = drawn.ellipse("final", level)
            assert a == pytest.approx(row[f"ellipse{level}_semi_major_m"], rel=1e-9)
            assert b == pytest.approx(row[f"ellipse{level}_semi_minor_m"], rel=1e-9)
            assert angle == pytest.approx(row[f"ellipse{level}_angle_deg"], abs=1e-6)


def test_trajectories_are_the_first_complete_paths_of_the_point(runs):
    """The sample is the first K shots of the point in trajectories.parquet, each complete."""
    run = run_view.open_run(runs["sweep"])
    table = pd.read_parquet(runs["sweep"] / output.TRAJECTORIES_FILE)
    for point in (0, 1):
        paths = run_view.sample_trajectories(run, point, limit=5)
        rows = table[table["point"] == point]
        assert [s for s, *_ in paths] == list(dict.fromkeys(rows["shot"]))[:5]
        for shot, x, y, z, phase in paths:
            mine = rows[rows["shot"] == shot]
            np.testing.assert_array_equal(x, mine["x_m"])
            np.testing.assert_array_equal(y, mine["y_m"])
            np.testing.assert_array_equal(z, mine["z_m"])
            assert phase[0] == "flight" and phase[-1] != "flight"


def test_shots_are_read_a_row_group_and_the_drawn_columns_at_a_time(runs, monkeypatch):
    """Memory does not grow with N: each read asks for one row group of the point and only the
    columns the plots draw."""
    calls = []

    class Recording(pq.ParquetFile):
        def iter_batches(self, *args, **kwargs):
            calls.append((kwargs.get("row_groups"), tuple(kwargs.get("columns"))))
            return super().iter_batches(*args, **kwargs)

    monkeypatch.setattr(pq, "ParquetFile", Recording)
    run = run_view.open_run(runs["sweep"])
    drawn = run_view.read_point_shots(run, 1)
    assert drawn.n_ok == run.summary.loc[1, "n_ok"]
    metadata = pq.read_metadata(runs["sweep"] / output.SHOTS_FILE)
    # Small points share row groups (output.ROW_GROUP_ROWS): those that may hold point 1.
    of_point_1 = [
        g
        for g in range(metadata.num_row_groups)
        if metadata.row_group(g).column(0).statistics.min
        <= 1
        <= metadata.row_group(g).column(0).statistics.max
    ]
    assert of_point_1
    assert [groups for groups, _ in calls] == [[g] for g in of_point_1]
    assert {columns for _, columns in calls} == {run_view.SHOT_COLUMNS}


def test_the_sweep_is_laid_out_against_its_parameter():
    """A numeric sweep with a unit is an x axis with that unit; units of one kind are put in
    the first value's unit (5 m/s was drawn after 10 mph, as categories in the order given); a
    bare number beside numbers with units, and text values, are categories."""
    assert figures._numeric(["909.8 rad/s", "1124.6 rad/s"])[1] == "rad/s"
    np.testing.assert_array_equal(figures._numeric(["5 m/s", "10 m/s"])[0], [5.0, 10.0])
    np.testing.assert_array_equal(figures._numeric([1.5, 2])[0], [1.5, 2.0])
    values, unit = figures._numeric(["5 m/s", "10 mph"])
    assert unit == "m/s" and values[0] == 5.0 and values[1] == pytest.approx(4.4704, rel=1e-15)
    assert figures._numeric(["5", "10 mph"]) is None
    np.testing.assert_allclose(figures._numeric(["10 mph", "12 MPH"])[0], [10.0, 12.0], rtol=1e-15)
    assert figures._numeric(["10 mph", "12 MPH"])[1] == "mph"  # (the first value's unit)
    assert figures._numeric(["green", "firm_green"]) is None


def test_groups_and_sweeps_are_laid_out(runs):
    groups = run_view.open_run(runs["groups"])
    assert groups.explicit_target
    x_label, values, ticks, series = figures.sweep_layout(groups)
    assert (x_label, values, ticks, series) == ("group", None, ["gap wedge", "sand wedge"],
                                                [("", [0, 1])])  # fmt: skip
    sweep = run_view.open_run(runs["sweep"])
    assert sweep.sweep_keys == ["turf.preset"]
    assert not sweep.explicit_target
    assert figures.sweep_layout(sweep)[:3] == ("turf.preset", None, ["green", "firm_green"])


# --- mcrun report ------------------------------------------------------------------------------


def test_report_references_nothing_outside_itself(page):
    """Every src= and href= is a data: URI or a link to a section of the page; no script,
    stylesheet link, font or CSS url()."""
    targets = re.findall(r"""(?:src|href)\s*=\s*["']?([^"'\s>]*)""", page, flags=re.I)
    assert targets
    for target in targets:
        assert target.startswith(("data:image/png;base64,", "#")), target[:60]
    for word in ("<script", "<link", "<iframe", "@import", "url(", "http://", "https://"):
        assert word not in page.lower()
    sections = set(re.findall(r'id="([^"]+)"', page))
    for target in targets:
        if target.startswith("#"):
            assert target[1:] in sections


def test_report_embeds_every_plot_at_its_size(page, runs):
    run = run_view.open_run(runs["sweep"])
    images = re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', page)
    assert len(images) == len(expected_files(run.points, True))
    for data in images:
        png = base64.b64decode(data)
        assert png[:8] == b"\x89PNG\r\n\x1a\n"
        width, height = struct.unpack(">II", png[16:24])
        assert (width, height) in {
            (round(w * DPI), round(h * DPI)) for w, h in style.FIGURE_SIZES_IN.values()
        }


def test_report_holds_the_scenario_the_summary_and_the_provenance(page, runs):
    run = run_view.open_run(runs["sweep"])
    text = run.provenance["scenario_text"]
    assert f"<pre>{html.escape(text)}</pre>" in page
    assert html.escape(run.question) in page
    summary = pd.read_parquet(runs["sweep"] / output.SUMMARY_FILE)
    for point in (0, 1):
        for column in ("total_m_mean", "carry_m_p95", "run_m_mean", "ellipse95_semi_major_m"):
            assert f">{summary.loc[point, column]:.2f}<" in page, (point, column)
    assert "total, at rest (m)" in page and "area (m²)" in page  # units in the headers
    for key in ("seed", "n", "versions", "start_time_utc", "elapsed_s", "threads", "backend"):
        assert f'<td class="text">{key}</td>' in page
    assert f"seed {run.seed}" in page and f"{SWEEP_N:,} shots per point" in page


def _another_run_into(folder, runs):
    """Replace the run in ``folder`` by another, as ``mcrun run ... -o folder --force`` does."""
    shutil.rmtree(folder)
    shutil.copytree(runs["single"], folder)


def test_a_report_whose_run_was_replaced_while_drawn_writes_nothing(runs, tmp_path, capsys,
                                                                    monkeypatch):  # fmt: skip
    """``mcrun report R`` while ``mcrun run ... -o R --force`` replaced the run: the old run's
    page was written into the new run's folder, without a word. Now the run is read again
    before the page is written: one line, exit 2, no page."""
    folder = tmp_path / "run"
    shutil.copytree(runs["groups"], folder)
    drawn = report.report_html

    def replaced_meanwhile(run, *args):
        page = drawn(run, *args)
        _another_run_into(folder, runs)
        return page

    monkeypatch.setattr(report, "report_html", replaced_meanwhile)
    code = main(["report", str(folder), "--dpi", "30"])
    out, err = capsys.readouterr()
    assert (code, out) == (2, "") and err.count("\n") == 1
    assert "another run replaced the one the report was drawn from" in err
    assert not (folder / output.REPORT_FILE).exists()


def test_pictures_whose_run_was_replaced_while_drawn_say_so(runs, tmp_path, capsys,
                                                             monkeypatch):  # fmt: skip
    """``mcrun plot R`` while ``mcrun run ... -o R --force`` replaced the run: the pictures'
    folder went with the old run ("cannot write R/plots/...: No such file"). Now it says that
    another run replaced the one drawn: one line, exit 2, no picture."""
    folder = tmp_path / "run"
    shutil.copytree(runs["groups"], folder)
    drawn = plots.figures

    def replaced_meanwhile(*args, **kwargs):
        for k, figure in enumerate(drawn(*args, **kwargs)):
            if k == 1:
                _another_run_into(folder, runs)
            yield figure

    monkeypatch.setattr(plots, "figures", replaced_meanwhile)
    code = main(["plot", str(folder), "--dpi", "30"])
    out, err = capsys.readouterr()
    assert (code, out) == (2, "") and err.count("\n") == 1, err
    assert "another run replaced the one the pictures were drawn from" in err
    assert not (folder / output.PLOTS_FOLDER).exists()


def test_report_defaults_to_the_run_folder(runs, tmp_path, capsys):
    run_dir = tmp_path / "copy"
    run_dir.mkdir()
    for name in (output.SHOTS_FILE, output.SUMMARY_FILE):
        (run_dir / name).write_bytes((runs["groups"] / name).read_bytes())
    assert main(["report", str(run_dir), "--dpi", "30"]) == 0
    path = run_dir / report.REPORT_FILE
    assert capsys.readouterr().out.strip() == f"wrote {path}"
    assert "two-wedges" in path.read_text(encoding="utf-8")


# --- mistakes ------------------------------------------------------------------------------------


def one_line_error(capsys, code, *needles):
    out, err = capsys.readouterr()
    assert code == 2
    assert out == ""
    assert err.startswith("mcrun: error: ") and err.count("\n") == 1, err
    for needle in needles:
        assert needle in err, err


@pytest.mark.parametrize("command", ["plot", "report"])
def test_a_folder_that_is_not_a_run_is_one_line(runs, tmp_path, capsys, command):
    one_line_error(capsys, main([command, str(tmp_path / "nowhere")]), "no such run folder")
    one_line_error(capsys, main([command, str(tmp_path)]), "not an mcrun run folder")
    a_file = tmp_path / "file.txt"
    a_file.write_text("x")
    one_line_error(capsys, main([command, str(a_file)]), "is not a folder" if command == "report"
                   else "is a file but not one that mcrun replay wrote")  # fmt: skip
    partial = tmp_path / "partial"
    partial.mkdir()
    (partial / output.SUMMARY_FILE).write_bytes((runs["groups"] / output.SUMMARY_FILE).read_bytes())
    one_line_error(capsys, main([command, str(partial)]), "has no shots.parquet")
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / output.SHOTS_FILE).write_bytes(b"not parquet")
    (broken / output.SUMMARY_FILE).write_bytes(b"not parquet either")
    one_line_error(capsys, main([command, str(broken)]), "cannot read the run")
    (broken / output.SUMMARY_FILE).write_bytes((runs["groups"] / output.SUMMARY_FILE).read_bytes())
    says = f"cannot read the run in {broken}: {output.SHOTS_FILE}: "  # (which file: not said)
    one_line_error(capsys, main([command, str(broken)]), says)


def _damaged(source, folder, shots=None, trajectories=None):
    """A copy of the run folder ``source`` at ``folder``, its shots and trajectories replaced
    by the tables given."""
    shutil.copytree(source, folder)
    for name, table in ((output.SHOTS_FILE, shots), (output.TRAJECTORIES_FILE, trajectories)):
        if table is not None:
            pq.write_table(table, folder / name)
    return folder


@pytest.mark.parametrize("command", ["plot", "report"])
def test_a_run_folder_of_two_runs_or_damaged_columns_is_one_line(runs, tmp_path, capsys,
                                                                  command):  # fmt: skip
    """Shots of another run beside a summary, shots cut short, a column of text where numbers
    go or a trajectory column missing: each refused in one line naming the file, where they
    drew another run's shots under this one's title, or ended in a traceback."""
    single, groups = runs["single"], runs["groups"]

    def out(k):
        return str(tmp_path / (f"o{k}.html" if command == "report" else f"o{k}"))

    mixed = tmp_path / "mixed"
    shutil.copytree(single, mixed)
    shutil.copy(groups / output.SHOTS_FILE, mixed / output.SHOTS_FILE)
    one_line_error(
        capsys,
        main([command, str(mixed), "-o", out(1)]),
        "shots.parquet and summary.parquet are not of one run (scenario_name",
    )
    shots = pq.read_table(single / output.SHOTS_FILE)
    short = _damaged(single, tmp_path / "short", shots=shots.slice(0, 10))
    one_line_error(
        capsys,
        main([command, str(short), "-o", out(2)]),
        f"shots.parquet has 10 shots where summary.parquet counts {SINGLE_N:,}",
    )
    k = shots.schema.get_field_index("total_m")
    text = shots.set_column(k, "total_m", pa.array(shots["total_m"].to_numpy().astype(str)))
    strings = _damaged(single, tmp_path / "strings", shots=text)
    one_line_error(
        capsys,
        main([command, str(strings), "-o", out(3)]),
        "strings/shots.parquet: column total_m is string: allowed are numbers",
    )
    paths = pq.read_table(single / output.TRAJECTORIES_FILE)
    no_z = _damaged(single, tmp_path / "no_z", trajectories=paths.drop_columns(["z_m"]))
    one_line_error(
        capsys,
        main([command, str(no_z), "-o", out(4)]),
        "no_z/trajectories.parquet was not written by mcrun run: no column z_m",
    )
    later = _damaged(single, tmp_path / "later")
    table = pq.read_table(later / output.SUMMARY_FILE)
    metadata = {**table.schema.metadata, b"mcrun.format_version": b"7"}
    pq.write_table(table.replace_schema_metadata(metadata), later / output.SUMMARY_FILE)
    one_line_error(
        capsys,
        main([command, str(later), "-o", out(5)]),
        "later: format_version 7: this mcrun reads runs of format 1",
    )
    assert not any(Path(out(k)).exists() for k in range(1, 6))


def test_an_unwritable_output_is_one_line(runs, tmp_path, capsys):
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    code = main(["plot", str(runs["groups"]), "-o", str(blocker / "plots")])
    one_line_error(capsys, code, "cannot write to")
    code = main(["report", str(runs["groups"]), "-o", str(tmp_path)])
    one_line_error(capsys, code, "is a folder")
    code = main(["report", str(runs["groups"]), "-o", str(blocker / "r.html")])
    one_line_error(capsys, code, "-o:")
    code = main(["report", str(runs["groups"]), "-o", str(tmp_path / "r.pdf")])  # (was HTML)
    one_line_error(capsys, code, "r.pdf: the report is an HTML page: give a file ending in .html")
    assert not (tmp_path / "r.pdf").exists()


@pytest.mark.parametrize("command", ["plot", "report"])
def test_missing_matplotlib_is_one_line(runs, tmp_path, monkeypatch, capsys, command):
    import sys

    for name in ("matplotlib", "matplotlib.figure", "matplotlib.backends.backend_agg"):
        monkeypatch.setitem(sys.modules, name, None)
    code = main([command, str(runs["groups"]), "-o", str(tmp_path / "out")])
    one_line_error(capsys, code, f"mcrun {command} needs matplotlib", "mcrun[plot]")
    assert not (tmp_path / "out").exists()


def test_the_report_reads_the_question_as_the_scenario_does(tmp_path):
    """``[scenario] question`` comes before a ``# Question:`` line (a comment copied from
    another scenario above an edited key was the question everywhere), and the comment where
    there is no key, in the library's list, the loaded scenario and the report's title alike."""
    launch = "[launch]\nball_speed = 70\nlaunch_angle = 12\nspin = 300\n"
    for text, question in (
        ('# Question: from the comment?\n[scenario]\nquestion = "from the table?"\n' + launch,
         "from the table?"),
        ("# Question: from the comment?\n[scenario]\n" + launch, "from the comment?"),
        ('# Question: from the comment?\n[scenario]\nquestion = " "\n' + launch,
         "from the comment?"),
    ):  # fmt: skip
        path = tmp_path / "q.toml"
        path.write_text(text, encoding="utf-8")
        assert sc.list_library(tmp_path)[0][2] == question
        assert sc.load(path).question == question
        folder = reader.RunFolder(
            tmp_path, None, None, str(tmp_path), "file", pd.DataFrame(), {"scenario_text": text},
            [], False,
        )  # fmt: skip
        run = run_view.Run(folder, pd.DataFrame(), [])
        assert run.question == question


# --- written as a run is: all or nothing ----------------------------------------------------------


def test_ctrl_c_during_plot_leaves_no_picture(runs, tmp_path, capsys, monkeypatch):
    """Ctrl-C while the third picture is saved once left the first two: now the pictures are
    drawn under temporary names and renamed together at the end, so none is left (nor any
    temporary file, nor the folder it made), and the pictures of an earlier plot into the
    folder are kept as they were."""
    folder = tmp_path / "plots"
    saved = []
    png_bytes = style.png_bytes

    def third_interrupted(fig, dpi):
        saved.append(fig)
        if len(saved) == 3:
            raise KeyboardInterrupt
        return png_bytes(fig, dpi)

    monkeypatch.setattr(style, "png_bytes", third_interrupted)
    assert main(["plot", str(runs["groups"]), "-o", str(folder), "--dpi", "30"]) == 130
    assert capsys.readouterr().err == "mcrun: interrupted: nothing was written\n"
    assert not folder.exists()  # (nor the folder it made for them)
    monkeypatch.undo()
    assert main(["plot", str(runs["groups"]), "-o", str(folder), "--dpi", "30"]) == 0
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    assert set(before) == expected_files(2, False)
    saved.clear()
    monkeypatch.setattr(style, "png_bytes", third_interrupted)
    assert main(["plot", str(runs["groups"]), "-o", str(folder), "--dpi", "40"]) == 130
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before


def test_pictures_are_renamed_with_interrupts_deferred(tmp_path, monkeypatch, ctrl_c_raises):
    """Ctrl-C (here SIGINT raised by the second rename) waits until every picture is in place:
    the set is whole, and the interrupt follows."""
    import signal

    from matplotlib.figure import Figure

    renames = []
    replace = output.os.replace

    def interrupting_replace(source, destination):
        replace(source, destination)
        renames.append(destination)
        if len(renames) == 2:
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(output.os, "replace", interrupting_replace)
    paths = [tmp_path / f"{k}.png" for k in range(3)]
    with pytest.raises(style.WrittenThenInterrupted) as raised, style.Pictures() as pictures:
        for path in paths:
            pictures.add(path, Figure(figsize=(1, 1)), 10)
        pictures.commit()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["0.png", "1.png", "2.png"]
    assert raised.value.paths == paths


def test_a_run_whose_files_lost_their_provenance_says_so(runs, tmp_path, capsys):
    """A run rewritten by a tool that keeps no key-value metadata: the report said "mcrun ?"
    without a word; now a note on stderr and in the page. A question or versions of another
    type than mcrun writes (a list, a string) were a traceback."""
    copy = tmp_path / "groups"
    shutil.copytree(runs["groups"], copy)
    for name in (output.SHOTS_FILE, output.SUMMARY_FILE):
        table = pq.read_table(copy / name)
        pq.write_table(table.replace_schema_metadata({}), copy / name)
    page = tmp_path / "page.html"
    assert main(["report", str(copy), "-o", str(page), "--dpi", str(DPI)]) == 0
    err = capsys.readouterr().err
    assert err == (f"mcrun: note: {copy}: its files hold no mcrun provenance (rewritten by "
                   "another tool?): the scenario, seed and versions are unknown\n")  # fmt: skip
    text = page.read_text(encoding="utf-8")
    assert "no mcrun provenance in the files" in text and "mcrun ?" not in text
    assert output.question_of({"question": [1]}) == ""
    run = run_view.open_run(runs["groups"])
    run.folder.provenance = {**run.provenance, "versions": "v", "question": "why " * 100_000}
    assert "mcrun " not in report.report_html(run, dpi=DPI).split("Run folder")[0][-200:]
    fig = style.new_figure("positions", run, "positions")
    assert fig._suptitle.get_text().count("\n") == style.QUESTION_LINES + 1


def test_an_ok_shot_whose_position_is_not_finite_is_refused(runs, tmp_path, capsys):
    """A run writes finite values of its ok shots: an infinite final_y_m (a file altered) drew
    with numpy's warnings on stderr and exit 0; now one line, and no picture."""
    copy = tmp_path / "groups"
    shutil.copytree(runs["groups"], copy)
    table = pq.read_table(copy / output.SHOTS_FILE)
    y = table["final_y_m"].to_numpy().copy()
    y[3] = np.inf
    j = table.schema.get_field_index("final_y_m")
    pq.write_table(table.set_column(j, "final_y_m", pa.array(y)), copy / output.SHOTS_FILE)
    out = tmp_path / "plots"
    assert main(["plot", str(copy), "-o", str(out), "--dpi", str(DPI)]) == 2
    err = capsys.readouterr().err
    assert err == (f"mcrun: error: {copy}: point 0: an ok shot's final_y_m is not finite: not a "
                   "value a run writes (its file altered?)\n")  # fmt: skip
    assert not out.exists()  # (the folder it made was left empty)
    out.mkdir()
    assert main(["plot", str(copy), "-o", str(out), "--dpi", str(DPI)]) == 2
    assert out.is_dir() and not list(out.iterdir())  # (a folder of the user's is kept)
