"""One reader for every run folder (mcrun.results.reader): a local run's shots.parquet and a Dask
run's dataset of parts open alike, with the same summary, columns, shots, trajectories and
per-point batches; ``mcrun plot`` and ``mcrun report`` work on a Dask run and draw what they draw
of the same local run; a folder that is not a complete run is one line, exit code 2.

One scenario of two groups (a hive-partitioned dataset), run by both executors with the same
seed and chunk size (so bit for bit the same shots), small and once per module; the Dask run
on a LocalCluster of one worker.
"""

from pathlib import Path

import numpy as np
import pandas as pd
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
