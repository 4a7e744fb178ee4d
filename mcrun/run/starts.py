"""Shots from many start points of a hole in one batch, at the kernel's rate.

``play_from`` flies one point of a scenario (a club: its sampled launch, spin and weather) from
each of many places on its hole: the same ``n`` sampled shots from every start (common random
numbers, as the aim search uses, so that two starts differ by where they are, not by their
draws), each struck on the ground there and aimed from there at the pin (or at an aim point
given). The kernel reads every shot's start from its inputs (``start_x_m``, ``start_y_m``), so
a batch mixes starts freely: there is no per-start call, plan or scoring pass. The starts are
cut into chunks of ``chunk_starts`` (the shots of a chunk are one kernel batch, start-major),
which bounds the memory whatever the number of starts; each chunk is scored in one pass
(``results.on_hole.scores`` with one start per shot: its lie and distance to the pin) and
reduced to per-start means.

The result (``StartsResult``) holds, per start: its lie and expected strokes (the Tour's
table), the mean expected strokes after the shot and the strokes gained with their standard
errors, and the shares that finished on the green, in a penalty area, out of bounds or off the
map and that failed; with ``keep_shots``, every shot's outcomes too (start-major: the shots of
start k are rows k n .. (k + 1) n - 1), for a solver that looks up where each shot stopped.

An argument that cannot be used is refused before anything is flown, in one line naming it
and what is allowed (``InputError``, a ValueError): a start that is not a point in play, an
``n`` under 2, a ``point`` that is not an index of the scenario's, an aim that is not a point;
for ``starts_grid``, a spacing that is not a positive number of metres (or gives more than
``MAX_GRID_NODES`` places), a ``within_m`` that is not (min, max) with 0 <= min <= max, a zone
that is not a zone kind. A grid none of whose places fits is empty, and ``play_from`` refuses
it.

The chunks are the tasks of the executor (``mcrun.executor``): on this process's threads, a
chunk on each, or on Dask (``client``). Each samples the same shots (they depend only on the
scenario, its seed and the shot index) and scores its starts, and its results go back to its
place in start order: bit for bit the same result whatever the threads or the workers.
"""

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN
from mcrun.executor import Executor
from mcrun.hole.zones import PENALTY_ZONES, ZONE_KINDS
from mcrun.putting.on_hole import map_of_hole
from mcrun.quantities import InputError
from mcrun.results import on_hole
from mcrun.run import plan, sampling
from mcrun.run.scenario import Scenario
from mcrun.strokes import start_of, tour_baseline
from mcrun.strokes.baseline import Baseline
from mcrun.strokes.expected import FAILED
from mcrun.units import float_or_nan, shown

AZIMUTH = COLUMN["azimuth_rad"]
START_X = COLUMN["start_x_m"]
START_Y = COLUMN["start_y_m"]
# Starts per batch of the kernel: 256 starts of 200 shots are 51,200 shots, a batch as long
# as a run's chunk, whose inputs and outcomes take 20 MB.
DEFAULT_CHUNK_STARTS = 256
# The most nodes of a grid of starts (``starts_grid``): 10 million places take 160 MB, and
# their shots far more; a finer grid is a mistake (a spacing of 1 mm).
MAX_GRID_NODES = 10_000_000
# The per-start columns of ``StartsResult.frame``, after x_m, y_m and lie.
SHARES = ("green", "penalty_area", "out_of_bounds", "off_map", "failed")


@dataclass
class StartsResult:
    """Shots of one club from many starts: per start (arrays of m), and with ``keep_shots``
    every shot's outcomes ((m n, N_OUTCOME), start-major)."""

    starts_xy_m: np.ndarray  # (m, 2), the hole's frame
    n: int  # shots per start
    lie: np.ndarray  # the start's lie (``strokes.LIES``)
    expected_strokes_start: np.ndarray
    expected_strokes_after_mean: np.ndarray
    expected_strokes_after_se: np.ndarray
    strokes_gained_mean: np.ndarray
    strokes_gained_se: np.ndarray
    shares: dict  # SHARES -> (m,) share of the start's shots
    outcomes: np.ndarray | None = None

    def frame(self):
        """One row per start: x_m, y_m, lie, the expected strokes and the shares."""
        columns = {
            "x_m": self.starts_xy_m[:, 0],
            "y_m": self.starts_xy_m[:, 1],
            "lie": pd.Categorical(self.lie),
            "expected_strokes_start": self.expected_strokes_start,
            "expected_strokes_after_mean": self.expected_strokes_after_mean,
            "expected_strokes_after_se": self.expected_strokes_after_se,
            "strokes_gained_mean": self.strokes_gained_mean,
            "strokes_gained_se": self.strokes_gained_se,
        }
        columns.update({f"p_{name}": self.shares[name] for name in SHARES})
        return pd.DataFrame(columns)


def check_starts(hole, starts_xy_m, where="starts_xy_m"):
    """``starts_xy_m`` as an (m, 2) float array of places in play on ``hole``; InputError (one
    line: the first bad start, its index and why) otherwise."""
    try:
        given = np.asarray(starts_xy_m)
        if given.dtype.kind not in "iuf":  # (bools were the point (1, 0), text read as numbers)
            raise TypeError
        starts = given.astype(float)
    except (TypeError, ValueError):
        raise InputError(
            f"{where}: cannot read {shown(starts_xy_m)} as points: allowed is an (m, 2) array "
            "of [x_m, y_m] (numbers of metres in the hole's frame)"
        ) from None
    if starts.ndim != 2 or starts.shape[1] != 2:
        raise InputError(f"{where}: must be (m, 2) points [x_m, y_m], got shape {starts.shape}")
    if len(starts) == 0:
        raise InputError(f"{where}: no starts: give at least one [x_m, y_m] place in play")
    bad = ~np.isfinite(starts).all(axis=1)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise InputError(f"{where}[{k}]: {starts[k].tolist()} is not a finite point")
    playable = hole.in_play_at(starts[:, 0], starts[:, 1])
    if not playable.all():
        k = int(np.flatnonzero(~playable)[0])
        why = hole.why_not_playable(*starts[k])
        raise InputError(f"{where}[{k}]: {starts[k].tolist()} is {why}: a shot starts in play")
    return starts


def _metres(value, name, positive=False):
    """``value`` as a finite number of metres (> 0 where ``positive``); InputError naming
    ``name`` otherwise."""
    number = float_or_nan(value)  # (text is not a number: "12" was an aim at (1, 2))
    if not math.isfinite(number) or (positive and number <= 0.0):
        allowed = "a positive number of metres" if positive else "a finite number of metres"
        raise InputError(f"{name} {shown(value)}: allowed: {allowed}")
    return number


def _pair(value, name, allowed="a point (x_m, y_m) in the hole's frame"):
    """``value`` as two finite numbers of metres; InputError naming ``name`` and what is
    ``allowed`` otherwise."""
    try:
        if isinstance(value, str | bytes):
            raise TypeError  # (its characters were taken as the two numbers)
        a, b = value
        return _metres(a, name), _metres(b, name)
    except (TypeError, ValueError):  # (InputError is a ValueError)
        raise InputError(f"{name} {shown(value)}: allowed: {allowed}") from None


def tile(inputs, play, starts_xy_m, aim_xy_m):
    """The kernel's inputs of ``inputs`` (n shots sampled about ``play``'s aim) struck from
    each of ``starts_xy_m`` (m, 2), start-major ((m n, N_INPUT), Fortran order), each aimed
    from its start at ``aim_xy_m`` (its sampled azimuth about that line)."""
    n = inputs.shape[0]
    m = starts_xy_m.shape[0]
    out = np.empty((m * n, inputs.shape[1]), order="F")
    x0 = starts_xy_m[:, 0]
    y0 = starts_xy_m[:, 1]
    bearing = np.arctan2(aim_xy_m[1] - y0, aim_xy_m[0] - x0)
    for column in range(inputs.shape[1]):
        out[:, column].reshape(m, n)[:] = inputs[:, column]
    out[:, AZIMUTH].reshape(m, n)[:] += (bearing - play.aim_rad)[:, None]
    out[:, START_X].reshape(m, n)[:] = x0[:, None]
    out[:, START_Y].reshape(m, n)[:] = y0[:, None]
    return out


def flown_from(scenario, point_index, inputs, starts_xy_m, aim_xy_m, launch=None):
    """The kernel's outcomes ((m n, N_OUTCOME), start-major) of ``inputs`` (n shots sampled
    about the aim of the scenario's point ``point_index``) struck from each of ``starts_xy_m``
    (m, 2) at ``aim_xy_m`` on the scenario's hole (``plan.terrain_of``); ``launch(batch)``:
    changes the tiled inputs in place before they fly (a lie's, ``mcrun.play``)."""
    batch = tile(inputs, scenario.points[point_index].play, starts_xy_m, aim_xy_m)
    if launch is not None:
        launch(batch)
    return simulate_batch(batch, terrain=plan.terrain_of(scenario))


def _mean_se(values):
    """Per row of (m, n) values: the mean and standard error of the finite ones."""
    ok = np.isfinite(values)
    count = ok.sum(axis=1)
    v = np.where(ok, values, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = v.sum(axis=1) / count
        squares = np.where(ok, (values - mean[:, None]) ** 2, 0.0).sum(axis=1)
        se = np.sqrt(squares / (count - 1)) / np.sqrt(count)
    return np.where(count > 0, mean, np.nan), np.where(count > 1, se, np.nan)


def play_chunk(scenario, point_index, n, aim_xy_m, strokes, keep_shots, starts_xy_m):
    """The per-start results (a dict of arrays of len(starts_xy_m)) of one chunk of starts, and
    its shots' outcomes when ``keep_shots``: one kernel batch and one scoring pass (a task of
    the executor)."""
    point = scenario.points[point_index]
    hole = scenario.hole
    inputs, _ = sampling.sample(scenario, point, 0, n)
    out = flown_from(scenario, point_index, inputs, starts_xy_m, aim_xy_m)
    m = len(starts_xy_m)
    x0 = np.repeat(starts_xy_m[:, 0], n)
    y0 = np.repeat(starts_xy_m[:, 1], n)
    scored = on_hole.scores(hole, out, strokes, start_xy_m=(x0, y0))
    after = scored["expected_strokes_after"].to_numpy().reshape(m, n)
    gained = scored["strokes_gained"].to_numpy().reshape(m, n)
    outcome = scored["outcome"].cat.codes.to_numpy().reshape(m, n)
    code = {name: k for k, name in enumerate(scored["outcome"].cat.categories)}
    part = {}
    part["expected_strokes_after_mean"], part["expected_strokes_after_se"] = _mean_se(after)
    part["strokes_gained_mean"], part["strokes_gained_se"] = _mean_se(gained)
    for name, where in (
        ("green", outcome == code["green"]),
        ("penalty_area", np.isin(outcome, [code[z] for z in PENALTY_ZONES])),
        ("out_of_bounds", outcome == code["out_of_bounds"]),
        ("off_map", outcome == code["off_map"]),
        ("failed", outcome == code[FAILED]),
    ):
        part[f"p_{name}"] = where.mean(axis=1)
    return part, (out if keep_shots else None)


def play_from(
    scenario,
    starts_xy_m,
    n=200,
    point=0,
    aim_xy_m=None,
    baseline=None,
    lie_of_zone=None,
    chunk_starts=DEFAULT_CHUNK_STARTS,
    keep_shots=False,
    client=None,
    progress=None,
):
    """Fly the first ``n`` shots of ``point`` (an index of ``scenario.points``) from each of
    ``starts_xy_m`` ((m, 2) m in the hole's frame, places in play), each aimed at ``aim_xy_m``
    (default the pin); a ``StartsResult``. ``baseline``, ``lie_of_zone``: as
    ``strokes.score_shots``. ``client``: a ``dask.distributed.Client`` to run the chunks of
    ``chunk_starts`` starts on (bit for bit the local result). ``progress(done, total)``:
    called after each chunk, in starts."""
    if not isinstance(scenario, Scenario):  # (a library name or a path: an AttributeError)
        raise InputError(f"scenario {shown(scenario)}: allowed: a Scenario "
                         "(mcrun.run.scenario.load(name or path))")  # fmt: skip
    if not isinstance(keep_shots, bool | np.bool_):  # ("no" kept them)
        raise InputError(f"keep_shots {shown(keep_shots)}: allowed: True or False")
    if progress is not None and not callable(progress):  # (a TypeError after the first chunk)
        raise InputError(f"progress {shown(progress)}: allowed: a function (done, total)")
    if baseline is not None and not isinstance(baseline, Baseline):
        raise InputError(f"baseline {shown(baseline)}: allowed: a Baseline "
                         "(mcrun.strokes.load_baseline(path))")  # fmt: skip
    hole = scenario.hole
    if hole is None:
        raise InputError(f"{scenario.path}: shots from start points need a hole ([hole])")
    last = len(scenario.points) - 1
    if isinstance(point, bool) or not isinstance(point, int | np.integer) or not 0 <= point <= last:
        raise InputError(f"point must be an index of the scenario's points, 0-{last}, got "
                         f"{shown(point)}")  # fmt: skip
    n = plan.positive_int(n, "n", minimum=2)  # (a standard error needs two)
    chunk_starts = plan.positive_int(chunk_starts, "chunk_starts")
    starts = check_starts(hole, starts_xy_m)
    aim = tuple(hole.pin_xy) if aim_xy_m is None else _pair(aim_xy_m, "aim_xy_m")
    aim = tuple(float(v) for v in aim)
    strokes = {"baseline": baseline or tour_baseline(), "lie_of_zone": lie_of_zone,
               "putting": map_of_hole(hole)}  # fmt: skip
    cuts = list(range(0, len(starts), chunk_starts))
    chunks = [starts[c : c + chunk_starts] for c in cuts]
    executor = Executor(client=client)
    if executor.on_dask:
        from mcrun.run.distributed import warm_workers
        from mcrun.run.plan import kernels_of

        warm_workers(client, *kernels_of(scenario))  # each worker's compile said, not silent
        task, shared = _chunk_task, (scenario.text, str(scenario.path), scenario.seed)
    else:
        task, shared = play_chunk, (scenario,)
    parts = [None] * len(chunks)
    said = [0]

    def done(k, part):
        parts[k] = part
        said[0] += len(chunks[k])
        if progress is not None:
            progress(said[0], len(starts))

    executor.map(task, chunks, shared=(*shared, point, n, aim, strokes, keep_shots), done=done,
                 name="chunk of starts")  # fmt: skip
    lie, distance = start_of(hole, (starts[:, 0], starts[:, 1]))
    base = strokes["baseline"]
    merged = {key: np.concatenate([p[0][key] for p in parts]) for key in parts[0][0]}
    return StartsResult(
        starts_xy_m=starts,
        n=n,
        lie=lie,
        expected_strokes_start=base.expected(lie, distance),
        expected_strokes_after_mean=merged["expected_strokes_after_mean"],
        expected_strokes_after_se=merged["expected_strokes_after_se"],
        strokes_gained_mean=merged["strokes_gained_mean"],
        strokes_gained_se=merged["strokes_gained_se"],
        shares={name: merged[f"p_{name}"] for name in SHARES},
        outcomes=np.concatenate([p[1] for p in parts]) if keep_shots else None,
    )


def _chunk_task(text, path, seed, point, n, aim, strokes, keep_shots, chunk):
    """A chunk of starts on a Dask worker: ``play_chunk`` on the scenario rebuilt from its text
    (read once per worker)."""
    from mcrun.run.distributed import scenario_on_worker

    scenario = scenario_on_worker(text, path, seed)
    return play_chunk(scenario, point, n, aim, strokes, keep_shots, chunk)


def starts_grid(hole, spacing_m, within_m=None, zones=None):
    """Places in play on ``hole`` every ``spacing_m`` (a square grid in its frame), optionally
    only those ``within_m`` (min, max) m of the pin and in ``zones`` (zone kinds): (m, 2),
    empty where none is. InputError (a ValueError, one line naming the argument) for a spacing
    that is not a positive number of metres or gives more than ``MAX_GRID_NODES`` nodes, a
    ``within_m`` that is not 0 <= min <= max, or a zone that is not one of ``ZONE_KINDS``."""
    spacing = _metres(spacing_m, "spacing_m", positive=True)
    if within_m is not None:
        allowed = "(min, max) metres from the pin, 0 <= min <= max"
        lo, hi = _pair(within_m, "within_m", allowed)
        if not 0.0 <= lo <= hi:
            raise InputError(f"within_m {shown(within_m)}: allowed: {allowed}")
    if zones is not None:
        zones = [zones] if isinstance(zones, str) else list(zones)
        unknown = [z for z in zones if z not in ZONE_KINDS]
        if unknown:
            raise InputError(
                f"zones: {shown(unknown[0])} is not a zone kind; allowed: {', '.join(ZONE_KINDS)}"
            )
    t = hole.terrain()
    ny, nx = t.zone.shape
    width, height = (nx - 1) * t.cell_m, (ny - 1) * t.cell_m
    nodes = (math.floor(width / spacing) + 1) * (math.floor(height / spacing) + 1)
    if nodes > MAX_GRID_NODES:
        least = math.sqrt(width * height / MAX_GRID_NODES)
        raise InputError(
            f"spacing_m {spacing:g}: {nodes:,} places over the hole's map ({width:.0f} m x "
            f"{height:.0f} m), at most {MAX_GRID_NODES:,}: allowed here: a spacing of at least "
            f"about {least:.2g} m"
        )
    xs = np.arange(t.x0_m, t.x0_m + width + 1e-9, spacing)
    ys = np.arange(t.y0_m, t.y0_m + height + 1e-9, spacing)
    X, Y = (a.ravel() for a in np.meshgrid(xs, ys))
    keep = hole.in_play_at(X, Y)
    if within_m is not None:
        d = np.hypot(X - hole.pin_xy[0], Y - hole.pin_xy[1])
        keep &= (d >= lo) & (d <= hi)
    if zones is not None:
        codes = [ZONE_KINDS.index(z) for z in zones]
        keep &= np.isin(hole.zone_at(X, Y), codes)
    return np.column_stack([X[keep], Y[keep]])
