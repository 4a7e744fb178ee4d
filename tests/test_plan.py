"""The size of a run: a sweep's cost per point does not grow with its number of points, the
plan ``mcrun run`` states before it starts (points, shots, time, Parquet size), and the refusal
of a run that would not fit on the disk (exit code 2, nothing written) unless
``--ignore-disk-space``.

The cost is counted, not timed: the calls of ``sampling.sampled_columns`` (which looks at every
point) and the openings of shots.parquet (each reads the footer, which lists every row group of
the run) must not grow with the number of points.
"""

import os
import shutil
from collections import namedtuple
from pathlib import Path

import pandas as pd
import pyarrow.parquet as pq
import pytest

from mcrun.cli import main
from mcrun.cli.run import describe
from mcrun.results import output
from mcrun.run import local as run
from mcrun.run import plan as run_plan
from mcrun.run import sampling, scenario

SWEEP = """\
[scenario]
name = "plan-test"
shots = 3
seed = 11
block_size = 64

[launch]
ball_speed = {{ dist = "normal", mean = "42.5 m/s", sd = "1 m/s" }}
launch_angle = "35.4 deg"
spin = "900 rad/s"

[turf]
preset = "green"

[sweep]
"turf.mu" = [{mus}]
"launch.spin" = [{spins}]
"""


def sweep(folder, k):
    """A k x k sweep scenario file: k^2 points."""
    mus = ", ".join(f"{0.3 + 0.01 * i:.2f}" for i in range(k))
    spins = ", ".join(f'"{500 + 50 * i} rad/s"' for i in range(k))
    path = Path(folder) / f"sweep{k}.toml"
    path.write_text(SWEEP.format(mus=mus, spins=spins), encoding="utf-8")
    return path


def listing(folder):
    return sorted(str(p.relative_to(folder)) for p in Path(folder).rglob("*"))


def costs(tmp_path, monkeypatch, k):
    """(calls of sampled_columns, openings of a Parquet file) of validate and run of a k x k
    sweep."""
    calls = {"columns": 0, "opened": 0}
    real_columns = sampling.sampled_columns

    def counted_columns(s):
        calls["columns"] += 1
        return real_columns(s)

    class CountedParquetFile(pq.ParquetFile):
        def __init__(self, *args, **kwargs):
            calls["opened"] += 1
            super().__init__(*args, **kwargs)

    monkeypatch.setattr(sampling, "sampled_columns", counted_columns)
    monkeypatch.setattr(pq, "ParquetFile", CountedParquetFile)
    path = sweep(tmp_path, k)
    loaded = scenario.load(path)
    assert len(loaded.points) == k * k
    describe(loaded)
    result = run.run_scenario(loaded, out_dir=tmp_path / f"run{k}", progress=False)
    assert len(result.summary()) == k * k
    monkeypatch.undo()
    return calls


def test_a_sweeps_cost_per_point_does_not_grow_with_its_points(tmp_path, monkeypatch):
    small = costs(tmp_path, monkeypatch, 2)
    large = costs(tmp_path, monkeypatch, 6)
    # Once per run (or per validate), whatever the number of points: not once per point.
    assert large == small
    assert small["columns"] <= 3 and small["opened"] <= 3


def test_plan_counts_points_shots_time_and_size(tmp_path):
    loaded = scenario.load(sweep(tmp_path, 3))
    plan = run_plan.plan(loaded, 10)
    assert (len(plan.points), plan.n, plan.shots) == (9, 10, 90)
    assert plan.seconds > 0 and plan.bytes > 90 * 100
    with_paths = run_plan.plan(loaded, 10, trajectories_every=1)
    assert with_paths.bytes > plan.bytes
    line = run_plan.plan(loaded, 1_000_000).line()
    assert line.startswith("mcrun: 9 points x 1,000,000 shots = 9,000,000 shots; about 23 s ")
    assert "s of simulation" in line and "of Parquet" in line


def test_plan_counts_the_samples_its_chunks_draw(tmp_path):
    """Each chunk draws the whole blocks it touches: 40 chunks of one shot in blocks of
    1,048,576 draw 40 blocks (12 s on a loaded machine, where the plan said "under 0.1 s");
    the default chunks and blocks draw what they fly."""
    assert run_plan.drawn_samples(40, 1, 1 << 20) == 40 << 20
    # 100 chunks, 157 blocks: of their 156 boundaries, every 25th (1,600 shots) is a chunk's
    assert run_plan.drawn_samples(10_000, 100, 64) == 64 * (100 + 156 - 156 // 25)
    assert run_plan.drawn_samples(1 << 20, run_plan.DEFAULT_CHUNK_SIZE, 4096) == 1 << 20
    path = tmp_path / "blocks.toml"
    path.write_text('[scenario]\nname = "blocks"\nblock_size = 1048576\n[launch]\n'
                    'ball_speed = "40 m/s"\nlaunch_angle = "30 deg"\nspin = "900 rad/s"\n',
                    encoding="utf-8")  # fmt: skip
    loaded = scenario.load(path)
    assert run_plan.plan(loaded, 40, chunk_size=1).seconds == pytest.approx(
        40 / run_plan.SHOTS_PER_S + run_plan.SECONDS_PER_POINT
        + ((40 << 20) - 4096) * run_plan.SECONDS_PER_DRAWN_SAMPLE
    )  # fmt: skip
    assert run_plan.plan(loaded, 40, chunk_size=1).line().split("; ")[1].startswith("about 6.3 s")


def test_plan_size_is_an_upper_bound_of_what_a_run_writes(tmp_path):
    loaded = scenario.load(sweep(tmp_path, 2))
    for n, every in ((3, None), (700, 50)):
        out = tmp_path / f"run-{n}"
        run.run_scenario(loaded, n=n, out_dir=out, trajectories_every=every, progress=False)
        written = sum(f.stat().st_size for f in out.iterdir())
        estimate = run_plan.plan(loaded, n, trajectories_every=every).bytes
        # Conservative, but not absurdly so.
        assert written <= estimate <= 6 * written, (n, written, estimate)


def test_cli_run_states_its_plan_first(tmp_path, capsys):
    path = sweep(tmp_path, 2)
    code = main(["run", str(path), "-n", "5", "-o", str(tmp_path / "run")])
    out, err = capsys.readouterr()
    assert code == 0, err
    first = err.splitlines()[0]
    assert first.startswith("mcrun: 4 points x 5 shots = 20 shots; under 0.1 s of "), err


Usage = namedtuple("Usage", "total used free")


def test_a_run_that_does_not_fit_is_refused_and_writes_nothing(tmp_path, capsys, monkeypatch):
    path = sweep(tmp_path, 2)
    asked = []

    def tiny(where):
        asked.append(Path(where))
        return Usage(10**9, 10**9 - 500, 500)

    monkeypatch.setattr(shutil, "disk_usage", tiny)
    out_dir = tmp_path / "deep" / "er" / "run"
    before = listing(tmp_path)
    code = main(["run", str(path), "-n", "1e10", "-o", str(out_dir)])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("mcrun: error: "), err
    assert "500 B free" in err and "--ignore-disk-space" in err and "TB" in err, err
    assert listing(tmp_path) == before
    assert asked == [tmp_path]  # the nearest folder that exists
    # The Python API refuses the same way.
    with pytest.raises(run.InputError, match="free"):
        run.run_scenario(path, n=10, out_dir=out_dir, progress=False)
    assert listing(tmp_path) == before


def test_ignore_disk_space_goes_ahead(tmp_path, capsys, monkeypatch):
    path = sweep(tmp_path, 2)
    monkeypatch.setattr(shutil, "disk_usage", lambda where: Usage(10**9, 10**9 - 1000, 1000))
    out_dir = tmp_path / "run"
    code = main(["run", str(path), "-n", "4", "-o", str(out_dir), "--ignore-disk-space"])
    _, err = capsys.readouterr()
    assert code == 0, err
    assert (out_dir / "shots.parquet").is_file()
    assert len(pq.read_table(out_dir / "shots.parquet")) == 16


def test_ignore_disk_space_is_in_the_help(capsys):
    assert main(["run", "--help"]) == 0
    out, _ = capsys.readouterr()
    assert "--ignore-disk-space" in out


def test_an_absurd_n_allocates_nothing_before_it_is_refused(tmp_path, capsys, monkeypatch):
    # 1e15 shots per point: a list of its chunks alone would take terabytes.
    path = sweep(tmp_path, 2)
    code = main(["run", str(path), "-n", "1e15", "-o", str(tmp_path / "run")])
    _, err = capsys.readouterr()
    assert code == 2 and "free" in err, err
    assert not os.path.exists(tmp_path / "run")


def test_small_points_share_row_groups_and_nothing_else_changes(tmp_path, monkeypatch):
    """A sweep of small points writes one row group for all of them, not one a point (each
    cost 3.5 ms and 18 kB): the shots and the summary are the same, to the bit, as with a row
    group per chunk."""
    path = sweep(tmp_path, 4)
    shared = run.run_scenario(path, n=300, chunk_size=128, out_dir=tmp_path / "a", progress=False)
    monkeypatch.setattr(output, "ROW_GROUP_ROWS", 1)
    apart = run.run_scenario(path, n=300, chunk_size=128, out_dir=tmp_path / "b", progress=False)
    assert pq.ParquetFile(shared.shots_path).num_row_groups == 1
    assert pq.ParquetFile(apart.shots_path).num_row_groups == 16 * 3
    pd.testing.assert_frame_equal(shared.shots(), apart.shots(), check_exact=True)
    pd.testing.assert_frame_equal(shared.summary(), apart.summary(), check_exact=True)


def test_dense_trajectories_take_smaller_chunks_unless_a_size_is_chosen():
    """A chunk's paths are held until written (``--trajectories 1`` of 20,000 shots, one chunk,
    held 3.6 GB): where the chunk size is the default, a chunk traces at most
    ``MAX_PATHS_PER_CHUNK`` paths; a size the user chose is kept. (The shots do not depend on
    it: tests/test_engine.py.)"""
    most = run_plan.MAX_PATHS_PER_CHUNK
    assert run_plan.plan("pga-driver", n=1000, trajectories_every=1).chunk_size == most
    assert run_plan.plan("pga-driver", n=1000, trajectories_every=3).chunk_size == 3 * most
    assert run_plan.plan("pga-driver", n=1000, trajectories_every=1000).chunk_size == (
        run_plan.DEFAULT_CHUNK_SIZE
    )
    assert run_plan.plan("pga-driver", n=1000).chunk_size == run_plan.DEFAULT_CHUNK_SIZE
    assert (
        run_plan.plan("pga-driver", n=1000, chunk_size=700, trajectories_every=1).chunk_size == 700
    )
