"""Nothing moved: the golden file (``golden_cases.py``), written before the package was
restructured, against the current tree: every library scenario's shots and summary at a fixed
seed, and one-shot outcomes and trajectories over every model, wind profile, turf, slope and
club delivery.

On any CPU, what is exact everywhere (statuses, zones, counts) is compared exactly and every
float at the tolerance that ``tolerance.py`` derives from the float error that can reach it.
``pytest --bit-for-bit`` compares everything bit for bit (but for the summary's linear algebra,
below), for a refactoring on the machine that wrote the file."""

import json
import re

import golden_cases as golden
import numpy as np
import pandas as pd
import pytest
from tolerance import assert_frames_close, assert_outcomes_close

pytestmark = pytest.mark.golden

# Summary columns computed by linear algebra (the covariance and its ellipses, the regression
# of the drivers, the correlations), whose last bits depend on the BLAS kernel of the CPU
# (OPENBLAS_CORETYPE=Haswell moves them by up to 3.4e-12 relative): bit for bit, compared to
# 1e-9 relative.
BLAS_COLUMNS = re.compile(r"_corr_|_r2$|_share_|_src_|^cov_|^ellipse")


@pytest.fixture
def bit_for_bit(request):
    return request.config.getoption("--bit-for-bit")


@pytest.mark.parametrize("name", golden.library_scenarios())
def test_library_scenario_unchanged(name, tmp_path, bit_for_bit):
    shots, summary = golden.run_scenario(name, tmp_path / name)
    expected = pd.read_parquet(golden.GOLDEN / f"{name}.shots.parquet")
    # The one change on purpose since the golden file: the statuses of a shot on a hole
    # (penalty_area, out_of_bounds, off_map) joined status_name's dictionary. Its values are
    # compared as they read.
    for frame in (shots, expected):
        frame["status_name"] = frame["status_name"].astype(str)
    expected_summary = pd.read_parquet(golden.GOLDEN / f"{name}.summary.parquet")
    if not bit_for_bit:
        assert_frames_close(shots, expected, f"{name} shots: ")
        assert_frames_close(summary, expected_summary, f"{name} summary: ")
        return
    pd.testing.assert_frame_equal(shots, expected, check_exact=True)
    blas = [c for c in expected_summary.columns if BLAS_COLUMNS.search(c)]
    others = expected_summary.drop(columns=blas)
    pd.testing.assert_frame_equal(summary.drop(columns=blas), others, check_exact=True)
    pd.testing.assert_frame_equal(summary[blas], expected_summary[blas], check_exact=False,
                                  rtol=1e-9)  # fmt: skip


def test_every_library_scenario_has_a_golden_file():
    assert {p.name.split(".")[0] for p in golden.GOLDEN.glob("*.shots.parquet")} == set(
        golden.library_scenarios()
    )


def test_shots_unchanged(bit_for_bit):
    expected = json.loads((golden.GOLDEN / "shots.json").read_text())
    trajectories = pd.read_parquet(golden.GOLDEN / "trajectories.parquet")
    cases = golden.shot_cases()
    assert set(cases) == set(expected)
    for name, (argv, keep) in cases.items():
        outcome, trajectory = golden.run_shot(argv, keep)
        if bit_for_bit:
            assert outcome == expected[name], name
        else:
            assert_outcomes_close(outcome, expected[name], f"{name}: ")
        if keep:
            kept = trajectories[trajectories["case"] == name].drop(columns="case")
            kept = kept.reset_index(drop=True)
            if bit_for_bit:
                pd.testing.assert_frame_equal(trajectory, kept, check_exact=True, obj=name)
            else:
                assert_frames_close(trajectory, kept, f"{name} trajectory: ")


def test_the_tolerance_takes_float_error_and_catches_a_change():
    """What the default comparison lets through on another CPU, and what it still catches: a
    longitude one ulp off and a run 1e-9 of its scale off pass; a run 1e-6 of its scale off, a
    status or a zone changed, or a NaN where a number was, fail."""
    expected = pd.read_parquet(golden.GOLDEN / "drive-real-ground.shots.parquet")
    near = expected.copy()
    near["final_lon_deg"] = np.nextafter(near["final_lon_deg"], 180.0)
    near["run_m"] = near["run_m"] + 1e-9 * near["run_m"].abs().max()
    assert_frames_close(near, expected)
    changes = {
        "run_m": lambda f: f["run_m"] + 1e-6 * f["run_m"].abs().max(),
        "final_lon_deg": lambda f: f["final_lon_deg"] + 1e-6,  # about 8 cm
        "status": lambda f: f["status"].where(f.index != 3, 1).astype(f["status"].dtype),
        "finish_zone": lambda f: f["finish_zone"].where(f.index != 3, "water"),
        "carry_m": lambda f: f["carry_m"].where(f.index != 3, np.nan),
    }
    for column, change in changes.items():
        moved = expected.copy()
        moved[column] = change(moved)
        with pytest.raises(AssertionError):
            assert_frames_close(moved, expected)
