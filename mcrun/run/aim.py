"""The best aim: where to aim each club of a scenario on its hole to leave the fewest expected
strokes (``mcrun.strokes``), found with common random numbers.

An aim is a start line: the bearing from the tee of an aim point, given as its offset (m, + to
the right) at the pin's distance from the line to the pin; how far the ball goes is the club's
(a scenario's groups are its clubs). Every aim of a club is flown with the same sampled shots,
the same swing turned by the aim (``sampling.sample``, its azimuths plus the bearing), so that
the difference between two aims is measured shot by shot: its standard error is that of the
paired differences, far smaller than either value's.

The search is coarse to fine: aims ``coarse_m`` apart over the region, then, around the best
so far, aims a third as far apart, until they are ``resolution_m`` apart; each round flies the
club's shots once per new aim.

The table of every aim flown (``table``) is written as a run's files are (``write_table``):
atomically, with the provenance of a run of the scenario (``plan.provenance``: the scenario,
seed, N, versions, and the geometry: the hole's frame, tee, pin, the scenario's aim, each
club's target and the hole's map, ``mcrun.results.geometry``) and the baseline it was scored
by.
"""

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numba
import numpy as np
import pandas as pd

from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN, FINAL_X, FINAL_Y, N_OUTCOME
from mcrun.quantities import InputError
from mcrun.results import on_hole, output
from mcrun.run import plan, sampling
from mcrun.run import scenario as scenario_module
from mcrun.strokes import start_of, tour_baseline

AZIMUTH = COLUMN["azimuth_rad"]
DEFAULT_HALF_WIDTH_M = 20.0
DEFAULT_COARSE_M = 5.0
DEFAULT_RESOLUTION_M = 1.0
TOUR_BASELINE = "PGA Tour (Broadie 2012)"
TABLE_SUFFIXES = (".parquet", ".pq")


class AimError(InputError):
    """An aim search that cannot run; the message is one line."""


@dataclass
class ClubAims:
    """The aims flown for one club (a point of the scenario) and what they leave."""

    club: str
    offsets_m: list = field(default_factory=list)  # aim offsets flown, m right at the pin
    expected: list = field(default_factory=list)  # mean expected strokes after the shot
    expected_se: list = field(default_factory=list)
    difference: list = field(default_factory=list)  # minus that of the reference aim
    difference_se: list = field(default_factory=list)  # paired standard error
    scores: dict = field(default_factory=dict)  # offset -> per-shot expected strokes after
    reference_m: float = 0.0  # the aim the differences are to (the pin, or the scenario's)

    @property
    def best(self):
        """Index of the aim with the fewest expected strokes."""
        return int(np.nanargmin(self.expected))


@dataclass
class AimSearch:
    """An aim search: each club's aims, the shots per aim, and how long it took."""

    scenario: object
    clubs: list
    n: int
    pin_distance_m: float
    expected_start: float  # expected strokes from the hole's start (the tee)
    seconds: float
    shots_flown: int

    def best(self):
        """(club, index) of the aim with the fewest expected strokes of all the clubs."""
        k = int(np.nanargmin([c.expected[c.best] for c in self.clubs]))
        return self.clubs[k], self.clubs[k].best


def load_scenario(scenario, seed=None):
    """The scenario of an aim search: a file or a library name (``scenario.find``), with
    ``seed`` (default its own); AimError when it has no hole."""
    loaded = scenario_module.load(scenario_module.find(scenario))
    if seed is not None:
        loaded = plan.with_seed(loaded, plan.positive_int(seed, "seed", minimum=0))
    if loaded.hole is None:
        raise AimError(f"{loaded.path}: an aim search needs a hole ([hole] in the scenario)")
    return loaded


def check_table_path(path, force=False, option="-o"):
    """``path`` as a Path where ``write_table`` may write, checked before the search: a
    .parquet file, not there yet unless ``force``; AimError (one line) otherwise."""
    destination = Path(path)
    if destination.suffix.lower() not in TABLE_SUFFIXES:
        raise AimError(f"{option} {path}: the output must be a .parquet file")
    if destination.exists() and not force:
        raise AimError(f"{option} {path}: already exists: use --force to replace it")
    return destination


def _bearing(offset_m, distance_m):
    """The bearing (rad, + right) of the aim point ``offset_m`` right of the line to the pin at
    ``distance_m`` from the tee."""
    return math.atan2(offset_m, distance_m)


def _scores(hole, inputs, azimuth, bearing, scenario_bearing, terrain, out, strokes):
    """Per-shot expected strokes after the shot of ``inputs`` aimed on ``bearing``."""
    inputs[:, AZIMUTH] = azimuth + (bearing - scenario_bearing)
    simulate_batch(inputs, out, terrain=terrain)
    return on_hole.scores(hole, out, strokes)["expected_strokes_after"].to_numpy()


def _summary(values, reference):
    ok = np.isfinite(values) & np.isfinite(reference)
    n = int(ok.sum())
    if n < 2:
        return math.nan, math.nan, math.nan, math.nan
    v = values[ok]
    d = v - reference[ok]
    se = float(v.std(ddof=1) / math.sqrt(n))
    return float(v.mean()), se, float(d.mean()), float(d.std(ddof=1) / math.sqrt(n))


def search(
    scenario,
    n=10_000,
    half_width_m=DEFAULT_HALF_WIDTH_M,
    centre_m=None,
    coarse_m=DEFAULT_COARSE_M,
    resolution_m=DEFAULT_RESOLUTION_M,
    offsets_m=None,
    baseline=None,
    lie_of_zone=None,
    progress=None,
):
    """The aim search of a scenario on a hole (``AimSearch``), ``n`` shots per club.

    The aims lie ``centre_m`` +/- ``half_width_m`` (m right of the line to the pin, at its
    distance; default centre: the scenario's aim), coarse to fine; ``offsets_m``: fly exactly
    these aims instead (no refinement). ``baseline``, ``lie_of_zone``: as
    ``strokes.score_shots``. ``progress(text)``: called after each round.
    """
    hole = scenario.hole
    if hole is None:
        raise AimError(f"{scenario.path}: an aim search needs a hole ([hole] in the scenario)")
    if not (0.0 < resolution_m <= coarse_m) or not half_width_m > 0.0:
        raise AimError(
            f"aims: need 0 < resolution ({resolution_m} m) <= coarse step ({coarse_m} m) and a "
            f"half width > 0 ({half_width_m} m)"
        )
    started = time.perf_counter()
    terrain = hole.terrain()
    pin_x, pin_y = hole.pin_xy
    distance = math.hypot(pin_x, pin_y)
    scenario_bearing = scenario.aim_rad
    if centre_m is None:
        centre_m = distance * math.tan(scenario_bearing)
    strokes = {"baseline": baseline or tour_baseline(), "lie_of_zone": lie_of_zone}
    clubs = []
    flown = 0
    for point in scenario.points:
        inputs, _ = sampling.sample(scenario, point, 0, n)
        azimuth = inputs[:, AZIMUTH].copy()
        out = np.empty((n, N_OUTCOME), order="F")
        aims = ClubAims(point.label or point.group or "shot", reference_m=centre_m)

        def fly(offset, aims=aims, inputs=inputs, azimuth=azimuth, out=out):
            if offset not in aims.scores:
                aims.scores[offset] = _scores(
                    hole, inputs, azimuth, _bearing(offset, distance), scenario_bearing,
                    terrain, out, strokes,
                )  # fmt: skip
            return aims.scores[offset]

        if offsets_m is not None:
            todo = [float(o) for o in offsets_m]
        else:
            todo = list(centre_m + np.arange(-half_width_m, half_width_m + 1e-9, coarse_m))
        reference = fly(round(centre_m, 9))
        step = coarse_m
        while True:
            for offset in todo:
                fly(round(offset, 9))
            if progress is not None:
                progress(f"{aims.club}: {len(aims.scores)} aims flown, {step:g} m apart")
            if offsets_m is not None or step <= resolution_m + 1e-9:
                break
            best = min(aims.scores, key=lambda o: np.nanmean(aims.scores[o]))
            step = max(step / 3.0, resolution_m)
            todo = [best + k * step for k in range(-3, 4)]
        for offset in sorted(aims.scores):
            mean, se, diff, diff_se = _summary(aims.scores[offset], reference)
            aims.offsets_m.append(offset)
            aims.expected.append(mean)
            aims.expected_se.append(se)
            aims.difference.append(diff)
            aims.difference_se.append(diff_se)
        flown += n * len(aims.scores)
        clubs.append(aims)
    lie, start_m = start_of(hole)
    expected_start = float(strokes["baseline"].expected(lie, start_m))
    return AimSearch(
        scenario, clubs, n, distance, expected_start, time.perf_counter() - started, flown
    )


def table(result):
    """Every aim flown, one row per club and aim: a dict of columns (units in the names)."""
    names = ("club", "aim_offset_m", "aim_bearing_deg", "expected_strokes_after",
             "expected_strokes_after_se", "difference_strokes", "difference_se",
             "strokes_gained")  # fmt: skip
    rows = {name: [] for name in names}
    for club in result.clubs:
        for k, offset in enumerate(club.offsets_m):
            rows["club"].append(club.club)
            rows["aim_offset_m"].append(offset)
            rows["aim_bearing_deg"].append(math.degrees(_bearing(offset, result.pin_distance_m)))
            rows["expected_strokes_after"].append(club.expected[k])
            rows["expected_strokes_after_se"].append(club.expected_se[k])
            rows["difference_strokes"].append(club.difference[k])
            rows["difference_se"].append(club.difference_se[k])
            rows["strokes_gained"].append(result.expected_start - 1.0 - club.expected[k])
    return rows


def write_table(result, path, baseline=None, force=False):
    """Write ``table(result)`` to ``path`` (Parquet) atomically, with the provenance of a run of
    its scenario (``plan.provenance``, its geometry and its hole's map included: the file
    describes itself) and ``baseline``, the name of the table the shots were scored by
    (default the Tour's); return the path."""
    the_plan = plan.plan(result.scenario, n=result.n)
    provenance = plan.provenance(
        the_plan,
        "local",
        output.versions(),
        numba.get_num_threads(),
        baseline=TOUR_BASELINE if baseline is None else str(baseline),
        seconds=round(result.seconds, 3),
        shots_flown=result.shots_flown,
    )
    with output.AtomicFile(path, force=force) as target:
        output.write_table(
            target.tmp, pd.DataFrame(table(result)), plan.file_metadata(provenance, "aim")
        )
        target.commit()
    return Path(path)


def patterns(result):
    """The finishes (x, y) of the best club's shots (``AimSearch.best``) at its best aim and at
    the reference aim, as the search flew them: {"best": (x, y), "reference": (x, y)}."""
    club, k = result.best()
    c = result.clubs.index(club)
    return {
        "best": finishes(result, c, club.offsets_m[k]),
        "reference": finishes(result, c, club.reference_m),
    }


def finishes(result, club, offset_m):
    """(x, y) finish positions (hole frame, m) of the shots of ``club`` (an index of
    ``result.clubs``) aimed ``offset_m`` right of the pin: its shots flown again, as the
    search flew them."""
    scenario = result.scenario
    point = scenario.points[club]
    inputs, _ = sampling.sample(scenario, point, 0, result.n)
    bearing = _bearing(offset_m, result.pin_distance_m)
    inputs[:, AZIMUTH] += bearing - scenario.aim_rad
    out = simulate_batch(inputs, terrain=scenario.hole.terrain())
    return out[:, FINAL_X], out[:, FINAL_Y]
