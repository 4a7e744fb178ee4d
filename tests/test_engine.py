"""The Monte Carlo run end to end (mcrun.run.local, mcrun.results.output, mcrun.results.stats over
the sampler and the batch kernel): determinism, the prefix property, the summary against pandas on
shots.parquet, provenance, atomic writes, the command line's errors, and Penner (2002) Fig. 4 at
zero dispersion against the single-shot API.

Runs are small (a few thousand shots) with a small sampler block, so that chunks cross block
boundaries. Statistics use ddof = 1 (pandas' default) and pandas' default linear-interpolation
percentiles; they must agree with pandas to 1e-9 relative.
"""

import json
import math
import os
import shutil
from datetime import datetime
from pathlib import Path

import numba
import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from mcrun.api import simulate
from mcrun.cli import main
from mcrun.engine import batch
from mcrun.engine.schema import HOLE_FIELDS, PLANE_FIELDS
from mcrun.results import output, stats
from mcrun.run import local as run
from mcrun.run import plan
from mcrun.status import INVALID_INPUT, OK

REL = 1e-9

# Two groups (one whose spin sometimes draws negative: those shots end invalid_input) times a
# sweep over the friction: four points.
DRIVE = """\
# Question: how far does a dispersed drive go, and what drives the dispersion?
[scenario]
name = "engine-test"
shots = 1000
seed = 2019
block_size = 256
target = ["280 m", "1 yd"]

[launch]
ball_speed = { dist = "normal", mean = "167 mph", sd = "1.5 mph" }
launch_angle = { dist = "normal", mean = "10.9 deg", sd = "0.8 deg" }
spin = { dist = "normal", mean = "2686 rpm", sd = "250 rpm" }
spin_axis = { dist = "normal", mean = "0 deg", sd = "3 deg" }
azimuth = { dist = "uniform", low = "-2 deg", high = "2 deg" }
correlation = { names = ["ball_speed", "spin"], matrix = [[1.0, -0.3], [-0.3, 1.0]] }

[turf]
preset = "fairway"

[weather]
temperature = { dist = "normal", mean = "20 C", sd = "4 C" }

[[group]]
name = "driver"

[[group]]
name = "wild"
launch.spin = { dist = "normal", mean = "300 rad/s", sd = "200 rad/s" }

[sweep]
"turf.mu" = [0.4, 0.25]
"""

N = 1200


def write(folder, text, name="scenario.toml"):
    path = Path(folder) / name
    path.write_text(text, encoding="utf-8")
    return path


def assert_same_content(a, b):
    """Two Parquet files hold the same columns and values, bit for bit (NaN included)."""
    ta, tb = pq.read_table(a), pq.read_table(b)
    assert ta.schema.remove_metadata() == tb.schema.remove_metadata()
    assert ta.num_rows == tb.num_rows
    for name in ta.column_names:
        x = ta.column(name).combine_chunks()
        y = tb.column(name).combine_chunks()
        if pa.types.is_floating(x.type):
            np.testing.assert_array_equal(
                x.to_numpy().view(np.uint64), y.to_numpy().view(np.uint64), err_msg=name
            )
        else:
            assert x.to_pylist() == y.to_pylist(), name


def listing(folder):
    """Every path under ``folder`` (hidden ones included), with file sizes and mtimes."""
    entries = set()
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            p = Path(root) / name
            st = p.stat()
            entries.add((str(p.relative_to(folder)), p.is_dir(), st.st_size, st.st_mtime_ns))
    return entries


@pytest.fixture(scope="module")
def drive(tmp_path_factory):
    """One run of DRIVE (n = 1200 per point, chunks of 500, trajectories every 400th shot)."""
    folder = tmp_path_factory.mktemp("drive")
    path = write(folder, DRIVE)
    result = run.run_scenario(
        path, n=N, out_dir=folder / "run", chunk_size=500, trajectories_every=400, progress=False
    )
    return path, result


# --- determinism -------------------------------------------------------------------------------


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs 2 threads")
@pytest.mark.determinism
def test_same_shots_on_1_and_2_threads_and_any_chunk_size(drive, tmp_path):
    """Same seed, same shots bit for bit: 2 threads with chunks of 500 (the fixture) against 1
    thread with chunks of 317 and 2 threads with one chunk per point; trajectories too."""
    path, reference = drive
    for threads, chunk in ((1, 317), (2, N)):
        other = run.run_scenario(
            path,
            n=N,
            out_dir=tmp_path / f"t{threads}-c{chunk}",
            threads=threads,
            chunk_size=chunk,
            trajectories_every=400,
            progress=False,
        )
        assert other.threads == threads
        assert_same_content(other.shots_path, reference.shots_path)
        assert_same_content(other.trajectories_path, reference.trajectories_path)
        # The summary merges its sums in another order: equal to rounding.
        pd.testing.assert_frame_equal(other.summary(), reference.summary(), rtol=1e-12)
    assert numba.get_num_threads() == numba.config.NUMBA_NUM_THREADS  # restored


def test_prefix_property(drive, tmp_path):
    """The first 700 shots of every point of the 1200-shot run are a 700-shot run."""
    path, reference = drive
    short = run.run_scenario(path, n=700, out_dir=tmp_path / "short", progress=False)
    long_ = reference.shots()
    prefix = long_[long_["shot"] < 700].reset_index(drop=True)
    pd.testing.assert_frame_equal(short.shots(), prefix, check_exact=True)


# --- the summary against pandas ----------------------------------------------------------------


def pandas_summary(shots, point, target=None):
    """The summary of one point computed directly with pandas on shots.parquet's rows."""
    rows = shots[shots["point"] == point]
    ok = rows[rows["status"] == OK]
    want = {"n_shots": len(rows), "n_ok": len(ok)}
    want["n_invalid_input"] = int((rows["status"] == INVALID_INPUT).sum())
    for name in stats.QUANTITIES:
        want[f"{name}_mean"] = ok[name].mean()
        want[f"{name}_std"] = ok[name].std(ddof=1)
        for p in stats.PERCENTILES:
            want[f"{name}_p{p:02d}"] = ok[name].quantile(p / 100.0)
    cov = ok[["final_x_m", "final_y_m"]].cov(ddof=1).to_numpy()
    want["cov_xx_m2"], want["cov_xy_m2"], want["cov_yy_m2"] = cov[0, 0], cov[0, 1], cov[1, 1]
    eig = np.linalg.eigvalsh(cov)
    for level in stats.ELLIPSE_LEVELS:
        k = math.sqrt(-2.0 * math.log(1.0 - level / 100.0))
        want[f"ellipse{level}_semi_major_m"] = k * math.sqrt(eig[1])
        want[f"ellipse{level}_semi_minor_m"] = k * math.sqrt(eig[0])
        want[f"ellipse{level}_area_m2"] = math.pi * k * k * math.sqrt(np.linalg.det(cov))
    tx, ty = target if target else (ok["final_x_m"].mean(), ok["final_y_m"].mean())
    distance = np.hypot(ok["final_x_m"] - tx, ok["final_y_m"] - ty)
    want["target_x_m"], want["target_y_m"] = tx, ty
    want["distance_mean_m"] = distance.mean()
    want["distance_r50_m"] = distance.quantile(0.50)
    want["distance_r95_m"] = distance.quantile(0.95)
    # Standardised regression coefficients: least squares on standardised sampled inputs.
    inputs = ["ball_speed_mps", "launch_angle_deg", "azimuth_deg", "spin_radps"]
    inputs += ["spin_axis_deg", "temperature_c"]
    xs = (ok[inputs] - ok[inputs].mean()) / ok[inputs].std(ddof=1)
    for y in stats.DRIVEN:
        ys = (ok[y] - ok[y].mean()) / ok[y].std(ddof=1)
        coef, *_ = np.linalg.lstsq(xs.to_numpy(), ys.to_numpy(), rcond=None)
        residual = ys.to_numpy() - xs.to_numpy() @ coef
        want[f"{y}_r2"] = 1.0 - residual @ residual / (ys @ ys)
        for name, c in zip(inputs, coef, strict=True):
            want[f"{y}_src_{name}"] = c
            want[f"{y}_share_{name}"] = c * c
    return want


def assert_summary_matches(summary, shots):
    for point in summary["point"]:
        got = summary[summary["point"] == point].iloc[0]
        want = pandas_summary(shots, point, target=(280.0, 0.9144))
        for key, value in want.items():
            assert got[key] == pytest.approx(value, rel=REL, abs=1e-12), (point, key)


def test_summary_equals_pandas_on_shots_parquet(drive):
    _, result = drive
    summary = result.summary()
    shots = result.shots()
    assert list(summary["label"]) == [
        "driver | turf.mu=0.4",
        "driver | turf.mu=0.25",
        "wild | turf.mu=0.4",
        "wild | turf.mu=0.25",
    ]
    assert list(summary["turf.mu"]) == [0.4, 0.25, 0.4, 0.25]
    # The wild group's negative spins end invalid_input and are left out of the statistics.
    assert (summary["n_invalid_input"][2:] > 0).all()
    assert (summary["n_ok"] + summary["n_failed"] == N).all()
    assert_summary_matches(summary, shots)


def test_summary_percentiles_by_histogram_select(drive, tmp_path):
    """With a memory budget of 100 values per column the percentiles come from the
    histogram-then-select path; they still equal pandas'."""
    path, reference = drive
    small = run.run_scenario(
        path, n=N, out_dir=tmp_path / "small", budget_bytes=800, progress=False
    )
    assert_summary_matches(small.summary(), reference.shots())


IMPACT = """\
# Question: what at impact drives the run of a 6-iron on the paper's green?
[scenario]
name = "impact"
seed = 6

[launch]
ball_speed = { dist = "normal", mean = "50 m/s", sd = "2 m/s" }
launch_angle = { dist = "uniform", low = "12 deg", high = "22 deg" }
spin = { dist = "normal", mean = "600 rad/s", sd = "60 rad/s" }

[turf]
preset = "green"
"""


def test_impact_angle_drives_the_run(tmp_path):
    """Penner (2002) section 3: the run is governed mainly by the impact angle. With the launch
    angle, speed and spin sampled, the landing angle must be the landing quantity that explains
    the largest share of the run's variance alone (its squared correlation with run_m), and
    that share must equal pandas' correlation squared."""
    result = run.run_scenario(
        write(tmp_path, IMPACT), n=1500, out_dir=tmp_path / "impact", progress=False
    )
    row = result.summary().iloc[0]
    shares = {name: row[f"run_m_share_{name}"] for name in stats.LANDING_DRIVERS}
    assert max(shares, key=shares.get) == "landing_angle_deg"
    assert shares["landing_angle_deg"] > 0.5
    ok = result.shots().query("status == 0")
    for name in stats.LANDING_DRIVERS:
        r = ok["run_m"].corr(ok[name])
        assert row[f"run_m_corr_{name}"] == pytest.approx(r, rel=REL)
        assert row[f"run_m_share_{name}"] == pytest.approx(r * r, rel=REL)


# --- provenance and reproducibility ------------------------------------------------------------


def test_metadata_round_trips_and_reproduces_the_run(drive, tmp_path):
    path, result = drive
    text = path.read_text(encoding="utf-8")
    for file, kind in (
        (result.shots_path, "shots"),
        (result.summary_path, "summary"),
        (result.trajectories_path, "trajectories"),
    ):
        meta = output.read_provenance(file)
        assert meta["file"] == kind
        assert meta["scenario_text"] == text
        assert meta["scenario_path"] == str(path)
        assert meta["scenario_name"] == "engine-test"
        assert meta["seed"] == 2019 and meta["n"] == N
        assert meta["points"] == list(result.summary()["label"])
        assert meta["groups"] == ["driver", "driver", "wild", "wild"]
        assert meta["versions"] == output.versions()
        assert meta["models"] == {
            "aero": ["trackman2019_lyu"],
            "bounce": ["penner2002"],
            "wind_profile": ["uniform"],
        }
        assert meta["chunk_size"] == 500 and meta["trajectories_every"] == 400
        assert meta["threads"] == numba.config.NUMBA_NUM_THREADS
        assert meta["backend"] == "local" and meta["block_size"] == 256
        assert datetime.fromisoformat(meta["start_time_utc"]).utcoffset().total_seconds() == 0
        assert 0.0 < meta["elapsed_s"] < 600.0
        if kind == "summary":
            assert meta["ddof"] == 1 and "linear" in meta["percentile_method"]
    # Reproduce from the metadata alone: its scenario text, seed and N.
    meta = output.read_provenance(result.shots_path)
    again = run.run_scenario(
        write(tmp_path, meta["scenario_text"]),
        n=meta["n"],
        seed=meta["seed"],
        out_dir=tmp_path / "again",
        progress=False,
    )
    assert_same_content(again.shots_path, result.shots_path)


def test_shots_parquet_layout(drive):
    """Columns named with units, small chunks sharing a row group, LZ4 where it gains (a
    sampled input and an outcome uncompressed), status and status_name."""
    _, result = drive
    f = pq.ParquetFile(result.shots_path)
    assert f.num_row_groups == 1  # 4 points x 1200 shots, under output.ROW_GROUP_ROWS
    columns = [f.metadata.row_group(0).column(k) for k in range(f.metadata.num_columns)]
    codecs = {c.path_in_schema: c.compression for c in columns}
    assert codecs["point"] == codecs["mu"] == "LZ4"  # LZ4_RAW: pyarrow names both so
    assert codecs["temperature_c"] == codecs["carry_m"] == "UNCOMPRESSED"
    schema = f.schema_arrow
    assert schema.names[:4] == ["point", "group", "label", "shot"]
    assert set(PLANE_FIELDS) <= set(schema.names)
    assert not set(HOLE_FIELDS) & set(schema.names)  # a run on a plane leaves them out
    assert schema.field("status").type == pa.int8()
    assert schema.field("bounces").type == pa.int32()
    shots = result.shots()
    assert set(shots["status_name"].unique()) <= {"ok", "invalid_input"}
    bad = shots[shots["status"] == INVALID_INPUT]
    assert (bad["status_name"] == "invalid_input").all() and bad["bounces"].isna().all()
    assert (shots.groupby("point")["shot"].agg(list) == [list(range(N))] * 4).all()
    traj = result.trajectories()
    assert set(traj["shot"]) == {0, 400, 800}
    assert list(traj.columns) == ["point", "shot", "t_s", "x_m", "y_m", "z_m", "phase"]


def test_columns_that_lz4_does_not_shrink_are_written_uncompressed():
    """output.column_compression: random float64 gain nothing from LZ4 (none); a constant, a
    count and text do (LZ4); an empty table keeps LZ4."""
    rng = np.random.default_rng(1)
    n = 10_000
    table = pa.table({
        "sampled": rng.normal(size=n), "constant": np.full(n, 20.0),
        "shot": np.arange(n, dtype=np.int64), "noise": rng.integers(0, 2**62, n),
        "name": pa.array(["ok"] * n).dictionary_encode(),
    })  # fmt: skip
    assert output.column_compression(table) == {
        "sampled": "none", "constant": "lz4", "shot": "lz4", "noise": "none", "name": "lz4"
    }  # fmt: skip
    assert set(output.column_compression(table.slice(0, 0)).values()) == {"lz4"}
    # A column sliced from the middle of its buffer is judged on its own values.
    mixed = pa.table({"x": np.concatenate([np.zeros(n), rng.normal(size=n)])})
    assert output.column_compression(mixed.slice(n))["x"] == "none"
    assert output.column_compression(mixed.slice(0, n))["x"] == "lz4"


def test_a_shots_writer_without_shots_writes_the_schema_and_an_aborted_one_nothing(tmp_path):
    """The writer opens shots.parquet on its first row group (whose values choose the codecs):
    closed before any, it still writes the file, its schema and no row; aborted, nothing, even
    when closed after."""

    def writer(name):
        return output.ShotsWriter(tmp_path / name, ["ball_speed_mps"], ["g"], ["p"], {})

    empty = writer("empty.parquet")
    empty.close()
    empty.close()
    assert pq.read_table(tmp_path / "empty.parquet").num_rows == 0
    aborted = writer("aborted.parquet")
    aborted.abort()
    aborted.close()
    assert not (tmp_path / "aborted.parquet").exists()


def test_run_dataframes(drive):
    path, result = drive
    shots, summary = run.run_dataframes(path, n=300)
    assert len(shots) == 4 * 300 and len(summary) == 4
    expected = result.shots()
    pd.testing.assert_frame_equal(
        shots, expected[expected["shot"] < 300].reset_index(drop=True), check_exact=True
    )


# --- Penner (2002) Fig. 4 as a scenario --------------------------------------------------------

FIG4 = """\
# Question: Penner (2002) Fig. 4: drives at club-head speeds of 35, 45 and 55 m/s.
[scenario]
name = "penner-fig4"
shots = 3

[club]
speed = "35 m/s"
mass = "0.200 kg"
loft = "13.3 deg"

[turf]
preset = "green"

[weather]   # Penner's air: 20 C, sea level, dry: 1.2041 kg/m^3
temperature = "20 C"
pressure = "101325 Pa"
humidity = 0

[models]
aero = "penner2002"

[sweep]
"club.speed" = ["35 m/s", "45 m/s", "55 m/s"]
"""


LIBRARY = Path(__file__).resolve().parent.parent / "scenarios"


@pytest.mark.parametrize(
    "source, air",
    [
        ("above", {"pressure_pa": 101325.0}),
        ("penner-fig4-drives.toml", {"altitude_m": 0.0}),
    ],
)
def test_penner_fig4_scenario_equals_single_shots(tmp_path, source, air):
    """At zero dispersion every shot of a point is the single-shot API's result, bit for bit
    (the launch angle, computed through radians and back, to 1e-12), trajectory included;
    for FIG4 above and for the library's copy of the study.
    The paper's first bounces: 2.82 m at 35 m/s and 1.17 m at 55 m/s (ours 2.82, 1.16; 2 %)."""
    if source == "above":
        path = write(tmp_path, FIG4)
    else:
        path = LIBRARY / source
        if not path.is_file():
            pytest.skip(f"{path} is not in the library")
    result = run.run_scenario(
        path, n=3, out_dir=tmp_path / "fig4", trajectories_every=1, progress=False
    )
    shots = result.shots()
    traj = result.trajectories()
    first_bounce = {}
    for point, speed in enumerate((35.0, 45.0, 55.0)):
        single = simulate(
            club_speed_mps=speed,
            club_mass_kg=0.200,
            loft_deg=13.3,
            turf="green",
            aero_model="penner2002",
            temperature_c=20.0,
            relative_humidity=0.0,
            trajectory=True,
            **air,
        )
        assert single.status == OK
        rows = shots[shots["point"] == point]
        assert len(rows) == 3
        for _, row in rows.iterrows():
            for name in PLANE_FIELDS:
                if name == "launch_angle_deg":
                    assert row[name] == pytest.approx(single.outcome[name], rel=1e-12)
                else:
                    assert row[name] == single.outcome[name], name
            path = traj[(traj["point"] == point) & (traj["shot"] == row["shot"])]
            want = single.trajectory
            for column in ("t_s", "x_m", "y_m", "z_m"):
                np.testing.assert_array_equal(path[column].to_numpy(), want[column].to_numpy())
            assert list(path["phase"].astype(str)) == list(want["phase"].astype(str))
        first_bounce[speed] = single.outcome["first_bounce_height_m"]
        assert rows["air_density_kgpm3"].iloc[0] == pytest.approx(1.204, abs=5e-4)
    assert first_bounce[35.0] == pytest.approx(2.82, rel=0.02)
    assert first_bounce[55.0] == pytest.approx(1.17, rel=0.02)
    summary = result.summary()
    assert (summary["total_m_std"] < 1e-9).all()  # zero dispersion, to rounding
    assert list(summary["run_m_mean"]) == sorted(summary["run_m_mean"], reverse=True)


# --- atomic writes, interrupts and errors ------------------------------------------------------


def cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_run_prints_summary_and_paths(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, DRIVE)
    code, out, err = cli(capsys, "run", "scenario.toml", "-n", "300", "--quiet")
    assert code == 0, err
    default = Path("runs") / "engine-test-2019"  # runs/<scenario name>-<seed>
    assert (default / "shots.parquet").is_file() and (default / "summary.parquet").is_file()
    assert str(default / "shots.parquet") in out
    assert "driver | turf.mu=0.4" in out and "variance of total_m from" in out
    assert err == ""
    # --force replaces the run, and leaves no temporary folder behind.
    code, out, err = cli(capsys, "run", "scenario.toml", "-n", "200", "--force", "--json")
    assert code == 0, err
    printed = json.loads(out)
    assert printed["n"] == 200 and len(printed["summary"]) == 4
    assert printed["files"] == [str(default / "shots.parquet"), str(default / "summary.parquet")]
    assert output.read_provenance(default / "shots.parquet")["n"] == 200
    assert sorted(p.name for p in (tmp_path / "runs").iterdir()) == ["engine-test-2019"]


def test_the_summary_says_where_correlated_inputs_shares_overlap(tmp_path):
    """pga-driver's ball speed, launch angle and spin are correlated: their shares of total_m's
    variance (coefficients squared) do not add up to its R^2, and the printed summary says so;
    the lateral position's inputs (spin axis, azimuth) are independent: theirs do, unremarked."""
    from mcrun.cli.run import OVERLAP_NOTE, SHARES_APART, format_summary

    result = run.run_scenario(LIBRARY / "pga-driver.toml", n=4000, out_dir=tmp_path / "r",
                              progress=False)  # fmt: skip
    row = pd.read_parquet(result.out_dir / "summary.parquet").iloc[0]
    apart = {}
    for y in ("total_m", "final_y_m"):
        shares = [v for k, v in row.items() if k.startswith(f"{y}_share_") and np.isfinite(v)]
        apart[y] = abs(sum(shares) - row[f"{y}_r2"])
    assert apart["total_m"] > 2 * SHARES_APART and apart["final_y_m"] < SHARES_APART
    lines = format_summary(pd.read_parquet(result.out_dir / "summary.parquet")).splitlines()
    total = next(line for line in lines if "variance of total_m" in line)
    lateral = next(line for line in lines if "variance of final_y_m" in line)
    assert total.endswith(f"{OVERLAP_NOTE})") and lateral.endswith(")")
    assert OVERLAP_NOTE not in lateral


def test_cli_validate_and_scenarios(tmp_path, capsys):
    path = write(tmp_path, DRIVE)
    code, out, err = cli(capsys, "validate", str(path))
    assert code == 0, err
    assert "4 point(s)" in out and "wild | turf.mu=0.25" in out and "spin_radps" in out
    code, out, err = cli(capsys, "scenarios", "--dir", str(tmp_path))
    assert code == 0, err
    assert out.split(None, 1) == [
        "scenario",
        "how far does a dispersed drive go, and what drives the dispersion?\n",
    ]


def test_scenarios_marks_a_file_that_does_not_load(tmp_path, capsys):
    """``mcrun scenarios --dir``: a file that does not load is listed with why (what ``mcrun
    validate`` would say), in the table and in --json; the others as they are."""
    write(tmp_path, DRIVE)
    write(tmp_path, DRIVE.replace('sd = "250 rpm"', 'sd = "-5 rpm"'), "bad.toml")
    code, out, err = cli(capsys, "scenarios", "--dir", str(tmp_path))
    assert code == 0, err
    lines = out.splitlines()
    question = "how far does a dispersed drive go, and what drives the dispersion?"
    assert lines[0] == f"bad       {question}" and lines[2] == f"scenario  {question}"
    assert lines[1].startswith(f"          does not load: {tmp_path / 'bad.toml'}: ")
    assert lines[1].endswith("launch.spin.sd: must be >= 0, got -5 rpm (-0.523599 rad/s)")
    assert len(lines) == 3
    code, out, err = cli(capsys, "scenarios", "--dir", str(tmp_path), "--json")
    listed = {entry["name"]: entry["error"] for entry in json.loads(out)}
    assert listed["scenario"] is None and listed["bad"] == lines[1].split(": ", 1)[1]
    code, out, err = cli(capsys, "validate", str(tmp_path / "bad.toml"))
    assert code == 2 and err == f"mcrun: error: {listed['bad']}\n"
    # A question over two lines (refused) is listed on one: its line break printed raw before.
    (tmp_path / "bad.toml").unlink()
    two = DRIVE.replace("[scenario]\n", '[scenario]\nquestion = """two\nlines"""\n', 1)
    write(tmp_path, two.replace("# Question:", "# About:"), "two.toml")
    code, out, err = cli(capsys, "scenarios", "--dir", str(tmp_path))
    assert out.splitlines()[1] == "two       two lines"


def bad_cases(tmp_path):
    """(argv, what the message must mention) for every user error of run/validate."""
    good = write(tmp_path, DRIVE)
    bad_sd = write(tmp_path, DRIVE.replace('sd = "250 rpm"', 'sd = "-5 rpm"'), "bad.toml")
    existing = tmp_path / "existing"  # an earlier run's files, as far as --force looks
    existing.mkdir()
    earlier = pa.table({"point": [0]}).replace_schema_metadata({"mcrun.seed": "1"})
    pq.write_table(earlier, existing / "summary.parquet")
    (existing / "plots").mkdir()
    with_notes = tmp_path / "with-notes"  # the same with a file of the user's, kept
    shutil.copytree(existing, with_notes)
    (with_notes / "notes.txt").write_text("mine")
    not_mcrun = tmp_path / "not-mcrun"  # a summary.parquet that mcrun did not write
    not_mcrun.mkdir()
    (not_mcrun / "summary.parquet").write_bytes(b"an earlier run")
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    a_file = tmp_path / "a_file"
    a_file.write_text("not a folder")
    return [
        (["run", str(tmp_path / "missing.toml")], "missing.toml"),
        (["run", str(bad_sd)], "launch.spin.sd"),
        (["run", str(good), "-n", "0"], "-n (n) must be an integer >= 1"),
        (["run", str(good), "-n", "many"], "-n (n) must be an integer"),
        (["run", str(good), "--seed", "-1"], "seed"),
        (["run", str(good), "--threads", "0"], "threads"),
        (["run", str(good), "--threads", "100000"], "threads"),
        # (said "up to 2**63 - 1", where this machine has a few)
        (["run", str(good), "--threads", "1e400"], "--threads (threads) must be within [1, "),
        (["run", str(good), "--chunk-size", "0"], "--chunk-size (chunk_size) must be"),
        (["run", str(good), "--trajectories", "0"], "--trajectories (trajectories_every) must"),
        (["run", str(good), "-o", str(existing)], "--force"),
        (["run", str(good), "-o", str(other)], "holds 'notes.txt', which no run writes"),
        (["run", str(good), "-o", str(with_notes), "--force"], "holds 'notes.txt', which no"),
        (["run", str(good), "-o", str(not_mcrun), "--force"], "not an mcrun run folder (no"),
        (["run", str(good), "-o", str(a_file)], "not a folder"),
        (["run", str(good), "-o", ""], "-o: empty: give a value"),  # (".")
        (["run", str(good), "-o", str(a_file / "run")], "cannot write"),
        # A URL with the local executor: a traceback (a path named file:, or a bucket).
        (
            ["run", str(good), "-o", f"file://{tmp_path}/url-run"],
            "is a URL: the local executor writes to a folder's path",
        ),
        (["validate", str(bad_sd)], "must be >= 0"),
        (["validate", str(tmp_path / "missing.toml")], "missing.toml"),
    ]


def test_every_bad_input_exits_2_with_one_line_and_writes_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cases = bad_cases(tmp_path)
    before = listing(tmp_path)
    for argv, needle in cases:
        code, out, err = cli(capsys, *argv)
        assert code == 2, argv
        assert out == "", argv
        assert err.count("\n") == 1 and err.startswith("mcrun: error: "), (argv, err)
        assert needle in err, (argv, err)
        assert listing(tmp_path) == before, argv


def test_force_replaces_a_run_with_its_pictures_and_nothing_of_the_user_s(tmp_path, capsys):
    """--force replaces a run folder whole, the pictures mcrun wrote into it included; a folder
    that also holds a file no run writes is refused, and nothing in it is touched."""
    path = write(tmp_path, DRIVE)
    out = tmp_path / "run"
    assert cli(capsys, "run", str(path), "-n", "20", "-o", str(out), "--quiet")[0] == 0
    (out / output.PLOTS_FOLDER).mkdir()
    (out / output.PLOTS_FOLDER / "point00-positions.png").write_bytes(b"png")
    (out / output.REPORT_FILE).write_text("<html>")
    # a report being written meanwhile (it was "holds '.report.html.partial-...', which no run
    # writes"): the run's own, replaced with it
    (out / ".report.html.partial-host-123-0123abcd").write_text("<ht")
    assert cli(capsys, "run", str(path), "-n", "30", "-o", str(out), "--force", "--quiet")[0] == 0
    assert sorted(p.name for p in out.iterdir()) == [output.SHOTS_FILE, output.SUMMARY_FILE]
    assert len(pd.read_parquet(out / output.SHOTS_FILE)) == 4 * 30
    (out / "notes.txt").write_text("mine")
    before = listing(tmp_path)
    code, _, err = cli(capsys, "run", str(path), "-n", "20", "-o", str(out), "--force")
    assert code == 2 and "holds 'notes.txt', which no run writes" in err
    assert listing(tmp_path) == before
    # A file of the user's in plots/ (plots/ is a run's own name: it was deleted with it).
    (out / "notes.txt").unlink()
    (out / output.PLOTS_FOLDER).mkdir()
    (out / output.PLOTS_FOLDER / "point00-hole.png").write_bytes(b"png")
    (out / output.PLOTS_FOLDER / "my-annotated.png").write_bytes(b"mine")
    before = listing(tmp_path)
    code, _, err = cli(capsys, "run", str(path), "-n", "20", "-o", str(out), "--force")
    assert code == 2 and "holds 'plots/my-annotated.png', which no run writes" in err
    assert listing(tmp_path) == before


def interrupt_on_second_chunk(monkeypatch):
    """Make the second batch call from now on raise KeyboardInterrupt, as Ctrl-C would."""
    real = batch.simulate_batch
    calls = []

    def flaky(inputs, out=None, **kwargs):
        calls.append(len(inputs))
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(inputs, out, **kwargs)

    monkeypatch.setattr(plan, "simulate_batch", flaky)  # (where a run's chunks are flown)
    return calls


def test_ctrl_c_leaves_nothing(tmp_path, capsys, monkeypatch):
    """Ctrl-C in the middle of a run (raised from the batch call of the second chunk): the API
    re-raises, the command line exits 130 with one line; no file or folder is left behind,
    not even the runs/ folder it created. The chunks run as tasks on the threads: those the
    other threads already hold finish, and none is taken after."""
    monkeypatch.chdir(tmp_path)
    path = write(tmp_path, DRIVE)
    before = listing(tmp_path)
    calls = interrupt_on_second_chunk(monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        run.run_scenario(path, n=600, chunk_size=300, trajectories_every=10, progress=False)
    assert 2 <= len(calls) <= 1 + numba.get_num_threads()
    assert listing(tmp_path) == before
    interrupt_on_second_chunk(monkeypatch)
    code, out, err = cli(capsys, "run", str(path), "-n", "600", "--chunk-size", "300")
    assert code == 130 and out == ""
    # The run's plan, then one line saying it was interrupted.
    assert err.startswith("mcrun: 4 points x 600 shots") and err.count("\n") == 2
    assert err.splitlines()[-1].startswith("mcrun: interrupted")
    assert listing(tmp_path) == before


def test_ctrl_c_during_force_keeps_the_earlier_run(tmp_path, monkeypatch):
    """--force replaces an earlier run only once the new one is complete."""
    path = write(tmp_path, DRIVE)
    run.run_scenario(path, n=100, out_dir=tmp_path / "run", progress=False)
    before = listing(tmp_path)
    interrupt_on_second_chunk(monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        run.run_scenario(path, n=600, chunk_size=300, out_dir=tmp_path / "run", force=True)
    assert listing(tmp_path) == before


def test_failure_while_summarising_leaves_nothing(tmp_path, monkeypatch):
    """A failure after shots.parquet is complete (here in the summary) removes it too."""
    path = write(tmp_path, DRIVE)
    before = listing(tmp_path)

    def broken(*args, **kwargs):
        raise RuntimeError("summary failed")

    monkeypatch.setattr(stats, "summarise", broken)
    with pytest.raises(RuntimeError, match="summary failed"):
        run.run_scenario(path, n=100, out_dir=tmp_path / "runs" / "x", progress=False)
    assert listing(tmp_path) == before


def test_a_ball_that_never_stops_is_stopped_at_the_roll_s_bounds():
    """The roll is bounded (``status.MAX_ROLL_TIME_S``, ``MAX_ROLL_DISTANCE_M``): a ball that
    slides without friction (mu 0) was let slide 240 s on the level, one step of 120 s past
    the first, and 36 km down a slope of 45 deg (the sliding phase checked the time only).
    Now its last step ends at the bound; a ball that stops is stopped as before (the golden
    file's)."""
    from mcrun.physics.turf import PRESETS
    from mcrun.status import MAX_ROLL_DISTANCE_M, MAX_ROLL_TIME_S, NOT_STOPPED

    frictionless = PRESETS["fairway"]._replace(mu=0.0, rho_g=0.0)
    for slope in (0.0, 45.0):
        shot = simulate(ball_speed_mps=60.0, launch_angle_deg=12.0, spin_radps=300.0,
                        turf=frictionless, slope_deg=slope, trajectory=True)  # fmt: skip
        assert shot.outcome["status"] == NOT_STOPPED
        roll = shot.trajectory[shot.trajectory["phase"] == "roll"]
        assert roll["t_s"].iloc[-1] - roll["t_s"].iloc[0] <= MAX_ROLL_TIME_S
        far = math.hypot(roll["x_m"].iloc[-1] - roll["x_m"].iloc[0],
                         roll["y_m"].iloc[-1] - roll["y_m"].iloc[0])  # fmt: skip
        assert far <= MAX_ROLL_DISTANCE_M
    assert shot.outcome["total_time_s"] < MAX_ROLL_TIME_S  # (1,000 m down the slope first)
