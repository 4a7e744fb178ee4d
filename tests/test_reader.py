"""One reader for every run folder (mcrun.results.reader): a local run's shots.parquet and a Dask
run's dataset of parts open alike, with the same summary, columns, shots, trajectories and
per-point batches; ``mcrun plot`` and ``mcrun report`` work on a Dask run and draw what they draw
of the same local run; a folder that is not a complete run is one line, exit code 2.

One scenario of two groups (a hive-partitioned dataset), run by both executors with the same
seed and chunk size (so bit for bit the same shots), small and once per module; the Dask run
on a LocalCluster of one worker.
"""

import re
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.compute  # noqa: F401  (pa.compute)
import pyarrow.parquet as pq
import pytest

pytest.importorskip("dask.distributed")

from dask.distributed import Client  # noqa: E402

from mcrun.cli import main  # noqa: E402
from mcrun.results import output, reader  # noqa: E402
from mcrun.run import distributed, local  # noqa: E402

TWO_GROUPS = """\
[scenario]
name = "two-clubs"
shots = 900
seed = 3
block_size = 256
target = ["150 m", "0 m"]

[launch]
ball_speed = { dist = "normal", mean = "120 mph", sd = "1.5 mph" }
launch_angle = { dist = "normal", mean = "16 deg", sd = "1 deg" }
spin = { dist = "normal", mean = "7000 rpm", sd = "400 rpm" }

[turf]
preset = "fairway"

[[group]]
name = "7 iron"

[[group]]
name = "6 iron"
launch.ball_speed = { dist = "normal", mean = "126 mph", sd = "1.5 mph" }
"""
N = 900
CHUNK = 300  # three parts a point
EVERY = 97
DPI = 30


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """(local run folder, Dask run folder) of the same run."""
    folder = tmp_path_factory.mktemp("reader")
    path = folder / "two-clubs.toml"
    path.write_text(TWO_GROUPS, encoding="utf-8")
    kwargs = {"n": N, "chunk_size": CHUNK, "trajectories_every": EVERY, "progress": False}
    made = local.run_scenario(path, out_dir=folder / "local", **kwargs)
    cluster = distributed.local_cluster(1)
    try:
        with Client(cluster) as client:
            dask = distributed.run_scenario(path, out_dir=folder / "dask", client=client, **kwargs)
    finally:
        cluster.close()
    return made.out_dir, dask.out_dir


def test_both_layouts_open_alike(runs):
    """The same summary, columns, shots and trajectories, whatever the layout."""
    mine, theirs = (reader.open_run(folder) for folder in runs)
    assert (mine.layout, theirs.layout) == (reader.FILE_LAYOUT, reader.DATASET_LAYOUT)
    assert mine.has_trajectories and theirs.has_trajectories
    assert mine.shot_columns == theirs.shot_columns
    assert mine.shot_columns[:2] == ["point", "group"]
    pd.testing.assert_frame_equal(mine.summary, theirs.summary, check_exact=True)
    assert mine.provenance["backend"] == "local" and theirs.provenance["backend"] == "dask"
    # the same geometry recorded: a plane, each group's target (150 m, 0)
    assert mine.geometry == theirs.geometry and mine.geometry.surface == "plane"
    assert mine.geometry.targets_xy_m == ((150.0, 0.0), (150.0, 0.0))
    pd.testing.assert_frame_equal(mine.shots(), theirs.shots(), check_exact=True)
    columns = ["shot", "group", "carry_m"]
    pd.testing.assert_frame_equal(mine.shots(columns), theirs.shots(columns), check_exact=True)
    pd.testing.assert_frame_equal(mine.trajectories(), theirs.trajectories(), check_exact=True)


@pytest.mark.parametrize("kind", ["shot", "trajectory"])
def test_a_point_is_read_from_its_own_row_groups_or_parts_in_order(runs, kind):
    """A point's batches (the local file's row groups of the point, or the point's parts in
    chunk order) hold every row of the point, in the file's order, and only those."""
    columns = ["point", "shot", "carry_m"] if kind == "shot" else ["point", "shot", "x_m"]
    for point in (0, 1):
        got = []
        for folder in runs:
            read = getattr(reader.open_run(folder), f"{kind}_batches")
            batches = list(read(point, columns, 128))
            got.append({c: np.concatenate([b[c] for b in batches]) for c in columns})
        whole = reader.read_shots(runs[0]) if kind == "shot" else reader.read_trajectories(runs[0])
        whole = whole[whole["point"] == point]
        for values in got:
            for c in columns:
                np.testing.assert_array_equal(values[c], whole[c].to_numpy())
        if kind == "shot":
            assert len(got[0]["shot"]) == N


@pytest.mark.parametrize("kind", ["shot", "trajectory"])
def test_a_point_s_batches_take_the_columns_asked_and_refuse_the_rest(runs, kind):
    """Without ``point`` among the columns (a KeyError before), each batch holds the columns
    asked for and the point's rows only; a column the run does not hold (the trajectories
    dropped it without a word), one named twice, and a point that is not one of the run's
    (True read as point 1, 99 as none, 0.0 a KeyError) are refused in one line."""
    column = "carry_m" if kind == "shot" else "x_m"
    for folder in runs:
        run = reader.open_run(folder)
        read = getattr(run, f"{kind}_batches")
        batches = list(read(1, ["shot", column], 128))
        assert batches and all(list(b) == ["shot", column] for b in batches)
        whole = reader.read_shots(runs[0]) if kind == "shot" else reader.read_trajectories(runs[0])
        np.testing.assert_array_equal(
            np.concatenate([b[column] for b in batches]), whole[whole["point"] == 1][column]
        )
        every = list(read(0, None, 10**6))  # (the Dask run's group from its folders' names)
        assert every[0].keys() >= {"point", "shot", column}
        if kind == "shot":
            assert set(np.concatenate([b["group"] for b in every])) == {"7 iron"}
        for columns, says in ((["nope", "point"], "no column nope in the"),
                              (["shot", "shot"], "columns: shot given twice")):  # fmt: skip
            with pytest.raises(reader.RunFolderError, match=says):
                list(read(0, columns, 10))
        for point, says in ((True, "point True: allowed"), (0.0, "point 0.0: allowed"),
                            ("0", "point '0': allowed"), (2, "no point 2: it has 2")):  # fmt: skip
            with pytest.raises(reader.RunFolderError, match=says):
                list(read(point, ["shot"], 10))


def test_plot_and_report_read_a_dask_run(runs, tmp_path, capsys):
    """``mcrun plot`` and ``mcrun report`` on a Dask run folder: the plots of the same local
    run, byte for byte (the same shots drawn the same way), and the report."""
    pytest.importorskip("matplotlib")
    written = {}
    for name, folder in zip(("local", "dask"), runs, strict=True):
        out = tmp_path / name
        assert main(["plot", str(folder), "-o", str(out), "--dpi", str(DPI)]) == 0
        written[name] = {p.name: p.read_bytes() for p in out.iterdir()}
    assert "point01-trajectories.png" in written["dask"]
    assert written["dask"] == written["local"]
    page = tmp_path / "dask.html"
    assert main(["report", str(runs[1]), "-o", str(page), "--dpi", str(DPI)]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == f"wrote {page}"
    assert "two-clubs" in page.read_text(encoding="utf-8")


def test_an_incomplete_dask_run_is_one_line(runs, tmp_path, capsys):
    """A copy of the Dask run without its _SUCCESS marker is not a run: exit 2, one line."""
    copy = tmp_path / "copy"
    for source in Path(runs[1]).rglob("*"):
        target = copy / source.relative_to(runs[1])
        if source.is_dir():
            target.mkdir(parents=True, exist_ok=True)
        elif source.name != output.SUCCESS_FILE:
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(source.read_bytes())
    assert main(["plot", str(copy), "-o", str(tmp_path / "plots")]) == 2
    err = capsys.readouterr().err
    assert err == f"mcrun: error: {copy}: not a complete Dask run (no _SUCCESS)\n"
    with pytest.raises(reader.RunFolderError, match="not a complete Dask run"):
        reader.open_run(copy)


def _altered(runs, tmp_path, which, alter):
    """A copy of the local (0) or Dask (1) run, ``alter(copy)`` applied to it."""
    copy = tmp_path / "copy"
    shutil.copytree(runs[which], copy)
    alter(copy)
    return copy


def _part(copy, chunk):
    return next(copy.rglob(output.part_name(chunk)))


@pytest.mark.parametrize(
    ("alter", "says"),
    [
        (lambda c: _part(c, 4).unlink(), "shots/ has 1 of its 6 parts missing (part 4 the first)"),
        # A copy of a part beside it, as a file manager names it (read twice before).
        (lambda c: shutil.copy(_part(c, 4), _part(c, 4).with_name("part-00004 (1).parquet")),
         "part-00004 (1).parquet is not a part of the run (part-NNNNN.parquet)"),
        (lambda c: shutil.copy(_part(c, 4), _part(c, 0).parent),
         "part 4 twice: shots/group="),
        (lambda c: (_part(c, 2).parent / "notes.txt").write_text("mine"),
         "notes.txt is not a part of the run"),
    ],
)  # fmt: skip
def test_a_dask_run_with_a_part_missing_or_twice_is_refused(runs, tmp_path, alter, says):
    """Its shots were read without the missing part's, or with a copy's twice, and drawn
    without a word; the local layout counted its rows against the summary already."""
    copy = _altered(runs, tmp_path, 1, alter)
    with pytest.raises(reader.RunFolderError, match=re.escape(says)):
        reader.open_run(copy)


def _rewrite(path, change):
    table = pq.read_table(path)
    pq.write_table(change(table), path)


def _plus(table, k, column="point"):
    j = table.schema.get_field_index(column)
    return table.set_column(j, column, pa.compute.add(table[column], k))


@pytest.mark.parametrize(
    ("alter", "says"),
    [
        # Another run's trajectories (the same scenario, another seed), drawn as this run's.
        (lambda c: _rewrite(c / output.TRAJECTORIES_FILE, lambda t: t.replace_schema_metadata(
            {**t.schema.metadata, b"mcrun.seed": b"5"})),
         "trajectories.parquet and summary.parquet are not of one run (seed 5 against 3)"),
        (lambda c: _rewrite(c / output.TRAJECTORIES_FILE, lambda t: _plus(t, 3)),
         "trajectories.parquet holds points 3 to 4 where summary.parquet has 2"),
        # The paths of shots the run never flew, drawn as its sample.
        (lambda c: _rewrite(c / output.TRAJECTORIES_FILE, lambda t: _plus(t, 10**6, "shot")),
         "trajectories.parquet holds shots 1000000 to "),
        # Shots renumbered: every figure empty, its title the summary's, exit 0.
        (lambda c: _rewrite(c / output.SHOTS_FILE, lambda t: _plus(t, 7)),
         "shots.parquet holds points 7 to 8 where summary.parquet has 2"),
        (lambda c: _rewrite(c / output.SUMMARY_FILE, lambda t: t.set_column(
            t.schema.get_field_index("n_shots"), "n_shots", pa.array([900.0, float("nan")]))),
         "summary.parquet's n_shots holds a value that is not a count"),
        (lambda c: _rewrite(c / output.SUMMARY_FILE, lambda t: t.replace_schema_metadata(
            {**t.schema.metadata, b"mcrun.format_version": b'"1"'})),
         "format_version '1' is not a format's number (this mcrun writes 1)"),
    ],
)  # fmt: skip
def test_files_of_another_run_or_points_are_refused(runs, tmp_path, alter, says):
    copy = _altered(runs, tmp_path, 0, alter)
    with pytest.raises(reader.RunFolderError, match=re.escape(says)):
        reader.open_run(copy)


def test_the_reader_names_what_it_cannot_read(runs, tmp_path):
    """One-line RunFolderErrors where a TypeError, a KeyError, pandas' or pyarrow's (with the
    schema over many lines) came out."""
    local_run = reader.open_run(runs[0])
    for folder in (None, 5, b"run", "run\0"):
        with pytest.raises(reader.RunFolderError, match=r"^run folder .*: allowed: a folder's"):
            reader.open_run(folder)
    for run in (local_run, reader.open_run(runs[1])):
        with pytest.raises(reader.RunFolderError, match=r": no column nope in the shots$"):
            run.shots(["nope"])
    with pytest.raises(reader.RunFolderError, match=r"^columns 'carry_m': allowed: a list"):
        local_run.shots("carry_m")
    with pytest.raises(reader.RunFolderError, match=r": no column zzz in the shots$"):
        local_run.shot_batches(0, ["zzz"], 10)
    with pytest.raises(reader.RunFolderError, match=r"^batch_rows 0: allowed: a whole number"):
        list(local_run.shot_batches(0, ["carry_m"], 0))
    empty = _altered(runs, tmp_path, 1, lambda c: _part(c, 4).write_bytes(b""))
    with pytest.raises(reader.RunFolderError, match=r"^cannot read the shots of .*size is 0"):
        reader.open_run(empty).shots()
