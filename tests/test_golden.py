"""Nothing moved: the golden file (``golden_cases.py``), written before the package was
restructured, against the current tree, bit for bit: every library scenario's shots and summary
at a fixed seed, and one-shot outcomes and trajectories over every model, wind profile, turf,
slope and club delivery."""

import json

import golden_cases as golden
import pandas as pd
import pytest


@pytest.mark.parametrize("name", golden.library_scenarios())
def test_library_scenario_unchanged(name, tmp_path):
    shots, summary = golden.run_scenario(name, tmp_path / name)
    pd.testing.assert_frame_equal(
        shots, pd.read_parquet(golden.GOLDEN / f"{name}.shots.parquet"), check_exact=True
    )
    pd.testing.assert_frame_equal(
        summary, pd.read_parquet(golden.GOLDEN / f"{name}.summary.parquet"), check_exact=True
    )


def test_every_library_scenario_has_a_golden_file():
    assert {p.name.split(".")[0] for p in golden.GOLDEN.glob("*.shots.parquet")} == set(
        golden.library_scenarios()
    )


def test_shots_unchanged():
    expected = json.loads((golden.GOLDEN / "shots.json").read_text())
    trajectories = pd.read_parquet(golden.GOLDEN / "trajectories.parquet")
    cases = golden.shot_cases()
    assert set(cases) == set(expected)
    for name, (argv, keep) in cases.items():
        outcome, trajectory = golden.run_shot(argv, keep)
        assert outcome == expected[name], name
        if keep:
            kept = trajectories[trajectories["case"] == name].drop(columns="case")
            pd.testing.assert_frame_equal(
                trajectory, kept.reset_index(drop=True), check_exact=True, obj=name
            )
