"""A finished run folder opened for its pictures (``Run``, ``open_run``), and what the plots
read of one point: its ok shots binned or as dots (``PointShots``, ``read_point_shots``) and a
sample of its paths (``sample_trajectories``). How much is read, and how, is said in
``mcrun.report.plots``. What a run recorded is all a picture needs: the scenario, its
question, and its geometry and hole map (``mcrun.results.geometry``); nothing is rebuilt from
the scenario's files.

The axes' ranges come from summary.parquet's percentiles (``span``, ``position_limits``), so
that a point is read once, batch by batch, whatever its number of shots.
"""

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa

from mcrun import status as status_codes
from mcrun.quantities import InputError
from mcrun.results import output, reader, stats

# How the plots read a run (see ``mcrun.report.plots``).
SCATTER_MAX_SHOTS = 5000
TRAJECTORIES_PER_POINT = 100
BATCH_ROWS = 65536
HISTOGRAM_BINS = 61  # odd: a point whose shots are all alike falls in the middle bin
DENSITY_BINS = (50, 200)  # bins per axis of a density: sqrt(ok shots) / 2 within these
RANGE_PAD = 0.15  # share of the 1 %..99 % span added on each side of a histogram's axis
POSITION_PAD = 0.3  # the same for the top views of the positions
MIN_SPAN_M = 1.0  # the smallest span an axis shows (a point whose shots are all alike)

SHOT_COLUMNS = (
    "point",
    "status",
    "carry_m",
    "carry_lateral_m",
    "run_m",
    "total_m",
    "final_x_m",
    "final_y_m",
)
TRAJECTORY_COLUMNS = ("point", "shot", "x_m", "y_m", "z_m", "phase")
DISTANCES = (
    ("carry_m", "carry"),
    ("run_m", "run (landing to rest)"),
    ("total_m", "total (at rest)"),
)


class PlotError(InputError):
    """A run folder cannot be read or its pictures cannot be written; one line for the user."""


# --- the run folder ----------------------------------------------------------------------------


@dataclass
class Run:
    """A run folder opened for its pictures: the reader's ``RunFolder`` (either layout), its
    summary by point and the swept parameters (the summary's columns between label and
    n_shots)."""

    folder: reader.RunFolder
    summary: pd.DataFrame
    sweep_keys: list

    @property
    def geometry(self):
        """What the run recorded of its geometry (``RunFolder.geometry``), or None."""
        return self.folder.geometry

    def hole_map(self):
        """The map of the run's hole as it recorded it (``RunFolder.hole_map``), or None."""
        return self.folder.hole_map()

    @property
    def path(self):
        return self.folder.path

    @property
    def provenance(self):
        return self.folder.provenance

    @property
    def has_trajectories(self):
        return self.folder.has_trajectories

    @property
    def name(self):
        return self.provenance.get("scenario_name") or Path(str(self.path)).name

    @property
    def n(self):
        return self.provenance.get("n")

    @property
    def seed(self):
        return self.provenance.get("seed")

    @property
    def points(self):
        return len(self.summary)

    @property
    def question(self):
        return output.question_of(self.provenance)

    @property
    def explicit_target(self):
        """Whether the scenario names a target (else it is each point's mean final position)."""
        try:
            data = tomllib.loads(self.provenance.get("scenario_text") or "")
        except tomllib.TOMLDecodeError:
            return False
        groups = data.get("group", [])
        return "target" in data.get("scenario", {}) or any(
            isinstance(g, dict) and "target" in g for g in groups
        )

    def beside(self, name):
        """``name`` in the run folder: where its pictures go unless told (-o)."""
        if self.folder.url is not None:
            raise PlotError(f"{self.path} is a URL: give -o, a local file or folder to write")
        return Path(self.path) / name


def check_unchanged(run, run_dir, drawn):
    """PlotError where the run folder no longer holds the run that ``drawn`` ("the report
    was", "the pictures were") drawn from: a ``run --force`` replaced it meanwhile (the old
    run's report was written into the new run's folder without a word; its pictures failed
    with "No such file")."""
    try:
        now = reader.open_run(run_dir).provenance
    except reader.RunFolderError:
        now = {}
    if any(now.get(key) != run.provenance.get(key) for key in reader.RUN_KEYS):
        raise PlotError(f"{run_dir}: another run replaced the one {drawn} drawn from while "
                        "it was drawn: nothing was written; draw it again")  # fmt: skip


def open_run(run_dir):
    """Open a finished run folder of either layout (``reader.open_run``) and check that it
    holds what the plots draw."""
    folder = reader.open_run(run_dir)
    summary = folder.summary
    needed = (
        "point",
        "group",
        "label",
        "n_shots",
        "n_ok",
        "total_m_mean",
        "ellipse95_semi_major_m",
        "target_x_m",
    )
    missing = [c for c in needed if c not in summary.columns]
    if missing:
        raise PlotError(
            f"{folder.path}/{output.SUMMARY_FILE} was not written by mcrun run: no column "
            f"{missing[0]}"
        )
    missing = [c for c in SHOT_COLUMNS if c not in folder.shot_columns]
    if missing:
        raise PlotError(
            f"the shots of {folder.path} were not written by mcrun run: no column {missing[0]}"
        )
    _check_numbers(folder, output.SHOTS_FILE, SHOT_COLUMNS)
    if folder.has_trajectories:
        _check_numbers(folder, output.TRAJECTORIES_FILE, TRAJECTORY_COLUMNS)
    summary = summary.sort_values("point").reset_index(drop=True)
    columns = list(summary.columns)
    sweep_keys = columns[columns.index("label") + 1 : columns.index("n_shots")]
    return Run(folder, summary, sweep_keys)


def _check_numbers(folder, what, columns):
    """PlotError unless each of ``columns`` of the run's ``what`` (shots or trajectories) is
    there and holds numbers (a dictionary of names for ``phase``), as mcrun run writes them."""
    try:
        schema = folder.schema(what)
    except (OSError, pa.ArrowException) as err:
        raise PlotError(f"cannot read {folder.path}/{what}: {err}") from None
    for name in columns:
        if name not in schema.names:
            raise PlotError(f"{folder.path}/{what} was not written by mcrun run: no column {name}")
        kind = schema.field(name).type
        if name == "phase":  # the phases' names
            ok, allowed = pa.types.is_dictionary(kind), "names (a dictionary)"
        else:
            ok, allowed = pa.types.is_floating(kind) or pa.types.is_integer(kind), "numbers"
        if not ok:
            raise PlotError(f"{folder.path}/{what}: column {name} is {kind}: allowed are "
                            f"{allowed}, as mcrun run writes them")  # fmt: skip


# --- what is drawn of one point ----------------------------------------------------------------


def _finite(*values):
    return [float(v) for v in values if v is not None and math.isfinite(float(v))]


def span(values, pad=RANGE_PAD, min_span=MIN_SPAN_M):
    """(lo, hi) around the finite ``values``: their extent widened by ``pad`` on each side."""
    values = _finite(*values)
    if not values:
        return -min_span, min_span
    lo, hi = min(values), max(values)
    if hi - lo < min_span:
        middle = 0.5 * (lo + hi)
        lo, hi = middle - 0.5 * min_span, middle + 0.5 * min_span
    width = hi - lo
    return lo - pad * width, hi + pad * width


def ellipse_extent(a, b, angle_deg):
    """Half extents (along the target line, across it) of an ellipse of semi-axes a, b whose
    major axis is ``angle_deg`` from the target line."""
    if not all(math.isfinite(v) for v in (a, b, angle_deg)):
        return 0.0, 0.0
    t = math.radians(angle_deg)
    return (
        math.sqrt((a * math.cos(t)) ** 2 + (b * math.sin(t)) ** 2),
        math.sqrt((a * math.sin(t)) ** 2 + (b * math.cos(t)) ** 2),
    )


def position_limits(row):
    """((downrange lo, hi), (lateral lo, hi)) in m of a point's positions plot, from its
    summary row: the 1-99 % range of carry and total, of the landing and final lateral
    positions, the 95 % ellipse and the target."""
    dx, dy = ellipse_extent(
        row["ellipse95_semi_major_m"], row["ellipse95_semi_minor_m"], row["ellipse95_angle_deg"]
    )
    mx, my = row["final_x_m_mean"], row["final_y_m_mean"]
    x = [row.get(f"{q}_{p}") for q in ("carry_m", "total_m") for p in ("p01", "p99")]
    y = [row.get(f"{q}_{p}") for q in ("carry_lateral_m", "final_y_m") for p in ("p01", "p99")]
    x += [mx - dx, mx + dx, row["target_x_m"]]
    y += [my - dy, my + dy, row["target_y_m"]]
    return span(x, POSITION_PAD), span(y, POSITION_PAD)


class PointShots:
    """What the plots need of one point's ok shots, accumulated batch by batch.

    ``hist[q]`` counts of carry_m, run_m and total_m on ``edges[q]`` (``outside[q]``: shots
    beyond); ``density`` 2-D counts of the landing and final positions on ``position_edges``
    (downrange, lateral); ``dots`` every position when the point has at most ``scatter_max``
    ok shots; ``moments`` co-moments of the landing and final positions.
    """

    def __init__(self, row, scatter_max=SCATTER_MAX_SHOTS):
        self.n_ok = 0
        self.n_failed = 0
        self.edges = {}
        for name, _ in DISTANCES:
            lo, hi = span([row.get(f"{name}_p01"), row.get(f"{name}_p99")])
            self.edges[name] = np.linspace(lo, hi, HISTOGRAM_BINS + 1)
        self.hist = {name: np.zeros(HISTOGRAM_BINS, dtype=np.int64) for name, _ in DISTANCES}
        self.outside = dict.fromkeys(self.hist, 0)
        xlim, ylim = position_limits(row)
        bins = int(np.clip(round(math.sqrt(max(int(row["n_ok"]), 0)) / 2.0), *DENSITY_BINS))
        self.position_edges = (np.linspace(*xlim, bins + 1), np.linspace(*ylim, bins + 1))
        self.scatter = int(row["n_ok"]) <= scatter_max
        self.density = {k: np.zeros((bins, bins)) for k in ("landing", "final")}
        self.dots = {"landing": [], "final": []}
        self.beyond = {"landing": 0, "final": 0}  # ok shots outside the position bins
        self.moments = {"landing": stats.Comoments(2), "final": stats.Comoments(2)}

    def update(self, batch):
        ok = batch["status"] == status_codes.OK
        for name in SHOT_COLUMNS[2:]:  # (a run writes finite values of its ok shots)
            if not np.isfinite(batch[name][ok]).all():
                raise PlotError(f"an ok shot's {name} is not finite: not a value a run writes "
                                "(its file altered?)")  # fmt: skip
        self.n_failed += int((~ok).sum())
        self.n_ok += int(ok.sum())
        for name in self.hist:
            values = batch[name][ok]
            counts, _ = np.histogram(values, bins=self.edges[name])
            self.hist[name] += counts
            self.outside[name] += len(values) - int(counts.sum())
        positions = {
            "landing": (batch["carry_m"][ok], batch["carry_lateral_m"][ok]),
            "final": (batch["final_x_m"][ok], batch["final_y_m"][ok]),
        }
        (x0, *_, x1), (y0, *_, y1) = self.position_edges
        for key, (x, y) in positions.items():
            self.beyond[key] += int(np.count_nonzero((x < x0) | (x > x1) | (y < y0) | (y > y1)))
            self.moments[key].update(np.column_stack([x, y]))
            if self.scatter:
                self.dots[key].append(np.column_stack([x, y]))
            else:
                counts, _, _ = np.histogram2d(x, y, bins=self.position_edges)
                self.density[key] += counts

    def positions(self, key):
        """(n, 2) downrange and lateral positions (dots only)."""
        parts = self.dots[key]
        return np.concatenate(parts) if parts else np.empty((0, 2))

    def ellipse(self, key, level):
        """(semi-major, semi-minor, angle deg) of the ``level`` % ellipse, ``stats.ellipse``."""
        m = self.moments[key]
        if m.n < 2:
            return math.nan, math.nan, math.nan
        c = m.covariance()
        return stats.ellipse(c[0, 0], c[0, 1], c[1, 1], level)[:3]


def read_point_shots(run, point, scatter_max=SCATTER_MAX_SHOTS):
    """PointShots of ``point`` (one pass over its row groups, the plotted columns only)."""
    row = run.summary.loc[run.summary["point"] == point].iloc[0].to_dict()
    shots = PointShots(row, scatter_max)
    try:
        for batch in run.folder.shot_batches(point, SHOT_COLUMNS, BATCH_ROWS):
            shots.update(batch)
    except PlotError as err:
        raise PlotError(f"{run.path}: point {point}: {err}") from None
    return shots


def sample_trajectories(run, point, limit=TRAJECTORIES_PER_POINT):
    """The paths of the first ``limit`` shots of ``point`` in trajectories.parquet: a list of
    (shot, x, y, z, phase names) arrays, in the file's order (shot index)."""
    paths = {}
    done = False
    for batch in run.folder.trajectory_batches(point, TRAJECTORY_COLUMNS, BATCH_ROWS):
        shot = batch["shot"]
        _, first = np.unique(shot, return_index=True)
        keep = np.zeros(len(shot), dtype=bool)
        for start in np.sort(first):
            s = int(shot[start])
            if s not in paths:
                if len(paths) == limit:
                    done = True
                    break
                paths[s] = []
            keep |= shot == s
        for s in np.unique(shot[keep]):
            rows = shot == s
            paths[int(s)].append(
                np.column_stack([batch["x_m"][rows], batch["y_m"][rows], batch["z_m"][rows]])
            )
            paths[int(s)].append(batch["phase"][rows])
        if done:
            break
    out = []
    for s, parts in paths.items():
        xyz = np.concatenate(parts[0::2])
        phase = np.concatenate(parts[1::2])
        out.append((s, xyz[:, 0], xyz[:, 1], xyz[:, 2], phase))
    return out
