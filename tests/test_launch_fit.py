"""A scenario's ``launch.file`` fitted as a correlated normal (``sample = "normal"``): the fit is
the file's sample moments, its draws have them within statistical tolerances, the draws are a
pure function of the scenario and the seed whatever the chunks; the fit is printed; and, with a
club filter, a resampled shot's ``source_row`` is its row in the file."""

import hashlib
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from mcrun.cli import main
from mcrun.cli.run import fit_lines
from mcrun.physics.constants import DEG
from mcrun.results.output import read_provenance
from mcrun.run import sampling
from mcrun.run import scenario as sc
from mcrun.run.plan import with_seed

MPH, RPM = 0.44704, 2.0 * math.pi / 60.0
N_SAMPLES = 20_000


def session(path, n=60, seed=5):
    """A session in mcrun's own columns: n 7-irons with correlated speed, launch and spin,
    and a driver every fourth row; returns the file's rows of the 7-irons (0-based)."""
    rng = np.random.default_rng(seed)
    sd = np.array([1.5, 1.0, 300.0])
    corr = np.array([[1.0, 0.3, -0.5], [0.3, 1.0, 0.2], [-0.5, 0.2, 1.0]])
    x = rng.multivariate_normal([120.0, 16.3, 7000.0], corr * np.outer(sd, sd), n)
    rows, irons = [], []
    for k in range(n):
        irons.append(len(rows))
        rows.append(
            {
                "club": "7 Iron",
                "ball_speed_mph": x[k, 0],
                "launch_deg": x[k, 1],
                "spin_rpm": x[k, 2],
                "spin_axis_deg": rng.normal(1.0, 3.0),
                "azimuth_deg": rng.normal(0.0, 2.0),
            }
        )
        if k % 4 == 0:
            rows.append(
                {
                    "club": "Driver",
                    "ball_speed_mph": 167.0 + k / 10,
                    "launch_deg": 10.9,
                    "spin_rpm": 2686.0,
                    "spin_axis_deg": 0.0,
                    "azimuth_deg": 0.0,
                }
            )
    frame = pd.DataFrame(rows)
    frame.to_csv(path, index=False)
    return frame, np.array(irons)


def scenario(tmp_path, extra='sample = "normal"\n', club="7 iron", name="s.toml"):
    frame, irons = session(tmp_path / "session.csv")
    text = f'[scenario]\nseed = 3\n[launch]\nfile = "session.csv"\nclub = "{club}"\n{extra}'
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path, frame, irons


def si_columns(frame, rows):
    """The file's launches of ``rows`` in SI, in the fit's order."""
    part = frame.iloc[rows]
    return {
        "ball_speed": part["ball_speed_mph"].to_numpy() * MPH,
        "launch_angle": part["launch_deg"].to_numpy() * DEG,
        "azimuth": part["azimuth_deg"].to_numpy() * DEG,
        "spin": part["spin_rpm"].to_numpy() * RPM,
        "spin_axis": part["spin_axis_deg"].to_numpy() * DEG,
    }


def test_the_fit_is_the_files_sample_moments_of_the_club(tmp_path):
    path, frame, irons = scenario(tmp_path)
    spec = sc.load(path).points[0].params["launch.file"]
    fit = spec.fit
    assert spec.sample == "normal" and fit.shots == len(irons) == 60
    assert fit.names == ("ball_speed", "launch_angle", "azimuth", "spin", "spin_axis")
    data = np.column_stack(list(si_columns(frame, irons).values()))
    # Means and the covariance (n - 1) reproduce NumPy's to rounding (rel 1e-12).
    np.testing.assert_allclose(fit.mean, data.mean(axis=0), rtol=1e-12)
    np.testing.assert_allclose(fit.covariance, np.cov(data, rowvar=False), rtol=1e-11, atol=0)
    np.testing.assert_allclose(fit.sd, data.std(axis=0, ddof=1), rtol=1e-12)
    np.testing.assert_allclose(fit.correlation, np.corrcoef(data, rowvar=False), atol=1e-12)
    np.testing.assert_allclose(fit.factor @ fit.factor.T, fit.correlation, atol=1e-12)
    assert np.array_equal(fit.factor, np.tril(fit.factor))
    # In the units of the sampled columns, and JSON-able, as a run records it.
    table = sc.launch_fits(sc.load(path).points)
    assert json.loads(json.dumps(table)) == table
    (entry,) = table
    assert entry["points"] == [0] and entry["club"] == "7 iron" and entry["shots"] == 60
    assert entry["names"][:2] == ["ball_speed_mps", "launch_angle_deg"]
    assert entry["mean"][1] == pytest.approx(frame["launch_deg"].iloc[irons].mean(), rel=1e-12)
    assert entry["sd"][3] == pytest.approx(
        frame["spin_rpm"].iloc[irons].std() * RPM, rel=1e-12
    )  # spin_radps


def test_draws_have_the_fits_moments_at_20000(tmp_path):
    """Tolerances at n = 20,000: 4 standard errors. A mean within 4 sd / sqrt(n) (2.8 % of an
    sd); an sd within 4 / sqrt(2 n) relative (2.0 %); a correlation within 4 (1 - rho^2) /
    sqrt(n) (at most 0.028)."""
    path, _, _ = scenario(tmp_path)
    loaded = sc.load(path)
    point = loaded.points[0]
    fit = point.params["launch.file"].fit.as_dict()
    _, sampled = sampling.sample(loaded, point, 0, N_SAMPLES)
    draws = np.column_stack([sampled[name] for name in fit["names"]])
    mean, sd = np.array(fit["mean"]), np.array(fit["sd"])
    corr = np.array(fit["correlation"])
    n = N_SAMPLES
    assert np.all(np.abs(draws.mean(axis=0) - mean) < 4.0 * sd / math.sqrt(n))
    assert np.all(np.abs(draws.std(axis=0, ddof=1) / sd - 1.0) < 4.0 / math.sqrt(2.0 * n))
    # Off the diagonal (on it both are 1, np.corrcoef's to the last bit of its BLAS kernel).
    off = ~np.eye(len(corr), dtype=bool)
    error = np.abs(np.corrcoef(draws, rowvar=False) - corr)[off]
    assert np.all(error <= (4.0 * (1 - corr**2) / math.sqrt(n))[off])
    assert np.all(np.diag(corr) == 1.0)
    assert "source_row" not in sampled  # not resampled: no row of the file


def test_draws_are_a_function_of_scenario_and_seed_whatever_the_chunks(tmp_path):
    path, _, _ = scenario(tmp_path)
    loaded = sc.load(path)
    point = loaded.points[0]
    whole_inputs, whole = sampling.sample(loaded, point, 0, 10_000)
    parts = [sampling.sample(loaded, point, a, b) for a, b in ((0, 3), (3, 4097), (4097, 10_000))]
    np.testing.assert_array_equal(np.concatenate([p[0] for p in parts]), whole_inputs)
    for name, values in whole.items():
        np.testing.assert_array_equal(np.concatenate([p[1][name] for p in parts]), values)
    again = sampling.sample(sc.load(path), sc.load(path).points[0], 0, 10_000)[0]
    np.testing.assert_array_equal(again, whole_inputs)  # loaded again: the same fit, bit for bit
    other = with_seed(loaded, 4)
    seeded = sampling.sample(other, other.points[0], 0, 100)[0]
    assert not np.array_equal(seeded, whole_inputs[:100])


def test_the_fit_is_printed_by_validate_and_when_a_run_starts(tmp_path, capsys):
    path, _, _ = scenario(tmp_path)
    loaded = sc.load(path)
    lines = fit_lines(loaded)
    assert lines[0] == (
        f"point(s) 0: launch.file fitted as a correlated normal to 60 shots of club '7 iron' of "
        f"{tmp_path / 'session.csv'}:"
    )
    fit = loaded.points[0].params["launch.file"].fit.as_dict()
    speed = lines[2].split()
    assert speed[0] == "ball_speed_mps"
    assert float(speed[1]) == pytest.approx(fit["mean"][0], abs=5e-4)
    assert float(speed[2]) == pytest.approx(fit["sd"][0], abs=5e-4)
    assert [float(v) for v in speed[3:]] == pytest.approx(fit["correlation"][0], abs=5e-4)
    assert main(["validate", str(path)]) == 0
    out, _ = capsys.readouterr()
    assert out.rstrip().endswith("\n".join(lines))
    code = main(["run", str(path), "-n", "50", "-o", str(tmp_path / "run")])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert "\n".join(lines) in err
    shots = pd.read_parquet(tmp_path / "run" / "shots.parquet")
    assert "source_row" not in shots and len(shots) == 50
    # The run records the file's digest beside its scenario, which names the file alone.
    digest = hashlib.sha256((tmp_path / "session.csv").read_bytes()).hexdigest()
    for name in ("shots", "summary"):
        recorded = read_provenance(tmp_path / "run" / f"{name}.parquet")["launch_files"]
        assert recorded == [{"file": str(tmp_path / "session.csv"), "sha256": digest,
                             "club": "7 iron", "points": [0]}]  # fmt: skip


def test_a_club_filters_source_row_is_the_files_row(tmp_path):
    path, frame, _ = scenario(tmp_path, extra="", club="Driver")
    loaded = sc.load(path)
    spec = loaded.points[0].params["launch.file"]
    drivers = np.flatnonzero(frame["club"].to_numpy() == "Driver")
    np.testing.assert_array_equal(spec.rows, drivers)
    _, sampled = sampling.sample(loaded, loaded.points[0], 0, 2000)
    rows = sampled["source_row"]
    assert set(rows) == set(drivers)  # every driver drawn, nothing else
    np.testing.assert_allclose(
        sampled["ball_speed_mps"], frame["ball_speed_mph"].to_numpy()[rows] * MPH, rtol=1e-12
    )


@pytest.mark.parametrize(
    ("extra", "club", "needle"),
    [
        ('sample = "lognormal"\n', "7 iron", "launch.sample: must be one of resample, normal, got"),
        ("sample = 3\n", "7 iron", "launch.sample: must be one of resample, normal, got 3"),
        (
            'sample = "normal"\njitter = { spin = "50 rpm" }\n',
            "7 iron",
            'launch.jitter: not allowed with launch.sample = "normal"',
        ),
        ('sample = "normal"\n', "Driver", "a normal fit needs at least 2 shots"),
    ],
)
def test_bad_sample_keys_are_one_line(tmp_path, capsys, extra, club, needle):
    frame, _ = session(tmp_path / "session.csv")
    if club == "Driver":  # one driver only
        frame[(frame["club"] != "Driver") | (frame.index == 1)].to_csv(
            tmp_path / "session.csv", index=False
        )
    path = tmp_path / "s.toml"
    path.write_text(f'[launch]\nfile = "session.csv"\nclub = "{club}"\n{extra}', encoding="utf-8")
    with pytest.raises(sc.ScenarioError) as info:
        sc.load(path)
    assert str(info.value).startswith(f"{path}: ") and needle in str(info.value)
    assert main(["validate", str(path)]) == 2
    _, err = capsys.readouterr()
    assert err.startswith("mcrun: error: ") and err.count("\n") == 1 and needle in err


def test_sample_is_only_allowed_with_a_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(
        '[launch]\nball_speed = "70 m/s"\nlaunch_angle = 12\nspin = 300\nsample = "normal"\n',
        encoding="utf-8",
    )
    with pytest.raises(sc.ScenarioError, match=r"launch.sample: only allowed with launch.file"):
        sc.load(path)


def test_an_exports_summary_rows_and_cut_last_row_are_not_resampled(tmp_path, capsys):
    """A TrackMan export as it comes, with its Average and Std. Dev. rows and a last row the
    file ends inside (the reader's reasons): a scenario's launch file skips them, so its
    source rows are the shots' rows only; a shot with a cell that cannot be read is refused
    with its reason in one line."""
    trackman = (Path(__file__).parent / "data" / "monitors" / "trackman.csv").read_text("utf-8")
    lines = trackman.splitlines()
    shots = [line for line in lines[2:] if line.strip()]
    average = "Average," + shots[0].split(",", 1)[1]
    text = "\n".join([*lines[:2], *shots, average, shots[0][:40]])
    (tmp_path / "export.csv").write_text(text, encoding="utf-8")
    path = tmp_path / "s.toml"
    path.write_text('[scenario]\nseed = 3\n[launch]\nfile = "export.csv"\n', encoding="utf-8")
    scenario = sc.load(path)
    _, sampled = sampling.sample(scenario, scenario.points[0], 0, 200)
    assert set(sampled["source_row"]) <= set(range(len(shots)))
    assert len(set(sampled["source_row"])) == len(shots)
    (tmp_path / "export.csv").write_text("\n".join([*lines[:2], average]), encoding="utf-8")
    assert main(["validate", str(path)]) == 2  # no shot: its summary row alone
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "no shot" in err and "summary" in err, err
    bad = trackman.replace("120.0,1.38", "--,1.38", 1)
    (tmp_path / "export.csv").write_text(bad, encoding="utf-8")
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "row 1" in err and "--" in err, err
