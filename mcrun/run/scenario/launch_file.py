"""A launch monitor's file as a scenario's launches (``launch.file``): the shots resampled
(with jitter), or the correlated normal fitted to them (``sample = "normal"``)."""

import hashlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcrun.quantities import InputError, column_and_factor
from mcrun.run.monitors import FILE_COLUMNS, check_file, read_session
from mcrun.run.monitors import NAMES as MONITOR_FORMATS
from mcrun.run.monitors.read import not_a_shot
from mcrun.run.scenario.correlation import semidefinite_cholesky
from mcrun.run.scenario.specs import PARAMETERS
from mcrun.run.scenario.values import as_table, fmt, key_name, read_value, short
from mcrun.units import (
    to_unit,
)

# How ``launch.file`` draws the launches: the measured shots themselves, or a fitted normal.
FILE_SAMPLING = ("resample", "normal")

# The name and the SI -> factor of each launch quantity in a fit's table (the sampled columns).
FIT_COLUMNS = {
    q: column_and_factor(f"launch.{q}")
    for q in ("ball_speed", "launch_angle", "azimuth", "spin", "spin_axis")
}


@dataclass(frozen=True)
class NormalFit:
    """The correlated normal fitted to measured launches: per quantity (``names``, the order of
    ``FIT_COLUMNS`` among those the file gives) the sample mean and standard deviation (n - 1),
    SI; their sample correlation matrix (1 on the diagonal, 0 off it for a quantity that does
    not vary) and its lower-triangular factor (``semidefinite_cholesky``). Drawn as
    mean + sd * (factor z) for standard normal z, which has the sample covariance."""

    names: tuple[str, ...]
    mean: np.ndarray
    sd: np.ndarray
    correlation: np.ndarray
    factor: np.ndarray
    shots: int

    def __eq__(self, other):
        return (
            isinstance(other, NormalFit)
            and (self.names, self.shots) == (other.names, other.shots)
            and all(
                np.array_equal(getattr(self, k), getattr(other, k))
                for k in ("mean", "sd", "correlation", "factor")
            )
        )

    __hash__ = None

    @property
    def covariance(self):
        """The fitted covariance matrix, SI: the sample covariance of the shots (n - 1)."""
        return self.correlation * np.outer(self.sd, self.sd)

    def as_dict(self):
        """The fit in the units of the sampled columns (m/s, deg, rad/s), JSON-able."""
        factors = np.array([FIT_COLUMNS[q][1] for q in self.names])
        return {
            "shots": self.shots,
            "names": [FIT_COLUMNS[q][0] for q in self.names],
            "mean": [float(v) for v in self.mean * factors],
            "sd": [float(v) for v in self.sd * factors],
            "correlation": [[float(v) for v in row] for row in self.correlation],
        }

    def describe(self):
        """The fit as a few lines of text: per quantity its mean, sd and correlations."""
        return describe_fit(self.as_dict())


def describe_fit(fit):
    """A fit of ``NormalFit.as_dict`` (or ``launch_fits``) as lines of text: per quantity its
    mean, sd and its row of the correlation matrix."""
    width = max(len(n) for n in fit["names"])
    lines = [f"  {'':<{width}}  {'mean':>9}  {'sd':>8}  correlation"]
    for k, name in enumerate(fit["names"]):
        row = "  ".join(f"{v:+.3f}" for v in fit["correlation"][k])
        lines.append(f"  {name:<{width}}  {fit['mean'][k]:9.3f}  {fit['sd'][k]:8.3f}  {row}")
    return "\n".join(lines)


def fit_normal(columns):
    """The ``NormalFit`` of {quantity: SI array} (two shots or more). Sums are NumPy's pairwise
    sums of elementwise products (no BLAS), so the fit, and the draws made with it, are the same
    on every machine."""
    names = tuple(q for q in FIT_COLUMNS if q in columns)
    data = [np.asarray(columns[q], dtype=float) for q in names]
    n = data[0].size
    mean = np.array([x.mean() for x in data])
    centred = [x - m for x, m in zip(data, mean, strict=True)]
    k = len(names)
    covariance = np.empty((k, k))
    for i in range(k):
        for j in range(i, k):
            covariance[i, j] = covariance[j, i] = (centred[i] * centred[j]).sum() / (n - 1)
    sd = np.sqrt(np.diag(covariance))
    correlation = np.eye(k)
    for i in range(k):
        for j in range(k):
            if i != j and sd[i] > 0.0 and sd[j] > 0.0:
                correlation[i, j] = min(max(covariance[i, j] / (sd[i] * sd[j]), -1.0), 1.0)
    factor = semidefinite_cholesky(correlation)
    return NormalFit(names, mean, sd, correlation, factor, n)


@dataclass(frozen=True)
class Resample:
    """Shots measured by a launch monitor: the file, its columns in SI (quantity -> array, one
    value per shot kept), ``rows`` (each shot's row in the file, 0-based, as ``mcrun replay``
    numbers them; with a club filter, only that club's) and either the normal jitter sd added
    per quantity to shots resampled with replacement, or ``fit``, the correlated normal fitted
    to the shots and drawn from instead (``sample = "normal"``); ``sha256``: the file's, as
    read."""

    path: Path
    columns: dict
    n_rows: int
    jitter: dict = field(default_factory=dict)
    rows: np.ndarray | None = None
    fit: NormalFit | None = None
    club: str | None = None
    sha256: str = ""

    def __eq__(self, other):
        return (
            isinstance(other, Resample)
            and (self.path, self.n_rows, self.jitter) == (other.path, other.n_rows, other.jitter)
            and self.columns.keys() == other.columns.keys()
            and all(np.array_equal(v, other.columns[k]) for k, v in self.columns.items())
            and np.array_equal(self.source_rows, other.source_rows)
            and (self.fit, self.club, self.sha256) == (other.fit, other.club, other.sha256)
        )

    __hash__ = None

    @property
    def sample(self):
        """How the launches are drawn: "resample" or "normal" (``FILE_SAMPLING``)."""
        return "resample" if self.fit is None else "normal"

    @property
    def source_rows(self):
        """Each kept shot's row in the file (0-based): ``rows``, or every row when not given."""
        return np.arange(self.n_rows) if self.rows is None else self.rows


_FILE_CACHE: dict = {}


def _read_shots(ctx, where, path, club=None, format=None):
    """({quantity: SI array}, rows, sha256) of the launches of a launch-monitor file (mcrun's
    columns or a device's export, ``mcrun.run.monitors``), their rows in the file (0-based) and
    the file's SHA-256 (hex), which a run records; only the shots of ``club`` when given."""
    key = (str(path.resolve()), path.stat().st_mtime_ns, club, format)
    if key in _FILE_CACHE:
        return _FILE_CACHE[key]
    try:
        session = read_session(path, format)
        digest = _sha256(path)
    except InputError as err:
        raise ctx.error(where, str(err)) from None
    rows = np.arange(len(session.frame))
    skipped = not_a_shot(session.reasons)
    if skipped is not None:
        rows = rows[~skipped]  # an export's summary rows, a last row cut short
        if rows.size == 0:
            raise ctx.error(where, f"{path}: no shot: {session.reasons[0]}")
    if club is not None:
        if session.club is None:
            raise ctx.error(where, f"{path}: a club is asked for but the file has no club column")
        rows = rows[[session.club[r].casefold() == club.casefold() for r in rows]]
        if rows.size == 0:
            clubs = ", ".join(sorted(set(session.club) - {""})) or "none"
            raise ctx.error(where, f"{path}: no shot of club {club!r}; its clubs: {clubs}")
    columns = {}
    for quantity, values in session.launch.items():
        column, unit = session.sources[quantity], session.units[quantity]
        param = PARAMETERS["launch"][quantity]
        si = values[rows]
        bad = np.flatnonzero(~np.isfinite(si))
        if bad.size:
            r = rows[bad[0]]
            raw = session.frame[column].iloc[r] if column in session.frame else float("nan")
            why = session.reasons[r] if session.reasons is not None else ""
            raise ctx.error(
                where,
                f"{path}: column {column!r} row {r + 1}: not a number "
                f"({short(why or raw)}); every row must be complete",
            )
        lo, hi = param.limits
        outside = np.flatnonzero((si < lo) | (si > hi))
        if outside.size:
            r = outside[0]
            raise ctx.error(
                where,
                f"{path}: column {column!r} row {rows[r] + 1}: "
                f"{to_unit(si[r], param.kind, unit):g} {unit} is outside the "
                f"allowed range [{fmt(lo, param.kind)}, {fmt(hi, param.kind)}]",
            )
        si.setflags(write=False)
        columns[quantity] = si
    rows = rows.astype(np.int64)
    rows.setflags(write=False)
    _FILE_CACHE[key] = columns, rows, digest
    return columns, rows, digest


def _sha256(path):
    """The SHA-256 (hex) of the file at ``path``, read in blocks; InputError where it cannot be
    read."""
    h = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
    except OSError as err:
        raise InputError(f"{path}: cannot read: {err.strerror or err}") from None
    return h.hexdigest()


def read_launch_file(
    ctx, leaf, jitter_leaf, scenario_dir, club_leaf=None, format_leaf=None, sample_leaf=None
):
    where = leaf.where
    choices = {}
    for name, option, allowed, known in (
        ("club", club_leaf, "a club name as the file writes it", None),
        ("format", format_leaf, f"one of {', '.join(MONITOR_FORMATS)}", MONITOR_FORMATS),
        ("sample", sample_leaf, f"one of {', '.join(FILE_SAMPLING)}", FILE_SAMPLING),
    ):
        if option is not None:
            if not isinstance(option.value, str) or not option.value.strip():
                raise ctx.error(option.where, f"must be {allowed}, got {short(option.value)}")
            if known is not None and option.value not in known:
                raise ctx.error(option.where, f"must be {allowed}, got {short(option.value)}")
            choices[name] = option.value.strip()
    normal = choices.get("sample") == "normal"
    if normal and jitter_leaf is not None:
        raise ctx.error(
            jitter_leaf.where,
            'not allowed with launch.sample = "normal": the fitted normal has the shots\' spread',
        )
    if not isinstance(leaf.value, str) or not leaf.value:
        raise ctx.error(where, f"must be a path to a CSV or Parquet file, got {short(leaf.value)}")
    path = Path(leaf.value)
    if not path.is_absolute():
        path = scenario_dir / path
    try:
        check_file(path)  # before _read_shots looks at its time stamp
    except InputError as err:
        raise ctx.error(where, str(err)) from None
    columns, rows, digest = _read_shots(
        ctx, where, path, choices.get("club"), choices.get("format")
    )
    jitter = {}
    if jitter_leaf is not None:
        table = as_table(ctx, jitter_leaf.where, jitter_leaf.value)
        for key, value in table.items():
            jwhere = f"{jitter_leaf.where}.{key}"
            name, unit = key_name(ctx, "launch", key, jwhere, only=FILE_COLUMNS)
            if name in jitter:
                raise ctx.error(jwhere, f"jitter of {name} is given twice")
            param = PARAMETERS["launch"][name]
            sd = read_value(ctx, jwhere, value, param.kind, unit, spread=True)
            if sd < 0.0:
                raise ctx.error(jwhere, f"must be >= 0, got {fmt(sd, param.kind, spread=True)}")
            jitter[name] = sd
    n_rows = len(next(iter(columns.values())))
    fit = None
    if normal:
        if n_rows < 2:
            which = f" of club {choices['club']!r}" if "club" in choices else ""
            raise ctx.error(
                sample_leaf.where,
                f"a normal fit needs at least 2 shots; {path} has {n_rows}{which}",
            )
        fit = fit_normal(columns)
    return Resample(path, dict(columns), n_rows, jitter, rows, fit, choices.get("club"), digest)


def _per_entry(points, entry_of):
    """[(entry, [indices of the points that give it])] of ``entry_of(spec)`` for each point's
    launch file, each distinct entry once, in the order first given (None: left out)."""
    entries = []
    for point in points:
        spec = point.params.get("launch.file")
        entry = None if spec is None else entry_of(spec)
        if entry is None:
            continue
        same = next((indices for known, indices in entries if known == entry), None)
        if same is None:
            entries.append((entry, [point.index]))
        else:
            same.append(point.index)
    return entries


def launch_files(points):
    """The launch files the points draw from, each once, JSON-able: the ``file``, its
    ``sha256`` (as read), its ``club`` (or None) and the ``points`` (their indices) that draw
    from it; what a run records beside its scenario, which names the file alone (another file
    under its name would draw other shots)."""
    return [
        {**entry, "points": indices}
        for entry, indices in _per_entry(
            points, lambda spec: {"file": str(spec.path), "sha256": spec.sha256, "club": spec.club}
        )
    ]


def launch_fits(points):
    """The normal fits of the points' launch files, each once, JSON-able: the ``points`` (their
    indices) that draw from it, the ``file``, the ``club`` (or None) and ``NormalFit.as_dict``.
    What a run prints when it starts and records beside its scenario."""

    def fit_of(spec):
        if spec.fit is None:
            return None
        return {"file": str(spec.path), "club": spec.club, **spec.fit.as_dict()}

    return [{"points": indices, **entry} for entry, indices in _per_entry(points, fit_of)]
