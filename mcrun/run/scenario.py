"""Scenarios: what a Monte Carlo run samples, read from a TOML file and validated.

A scenario file names every input of a shot (the ball launch or the club delivery, the turf,
the weather, the models), each a constant or a distribution, and may hold several groups (a bag
of clubs) and a grid sweep over any parameter. ``load`` reads it into plain objects: a
``Scenario`` with one ``Point`` per group and sweep combination, each point holding the fully
resolved parameter specs (defaults filled in, SI) that ``mcrun.run.sampling`` draws from.

Every mistake a user can make in a file ends in a ``ScenarioError`` whose message is one line
naming the file, the key path and what is allowed, e.g.
``scenarios/x.toml: launch.spin.sd: must be >= 0, got -5 rad/s``.

Sections and their keys (``PARAMETERS``): ``[scenario]`` name, question, description, shots,
seed, target, block_size; ``[launch]`` ball_speed, launch_angle, spin, azimuth, spin_axis,
correlation, or file (a launch monitor's CSV or Parquet: resampled, with jitter, or fitted as a
correlated normal with ``sample = "normal"``); ``[club]``
speed, mass (default 0.200 kg), loft, azimuth, spin_axis, correlation (instead of the ball
launch); ``[turf]`` preset, mu, softness, restitution, rho_g or stimp, critical_height, slope,
fall_line; ``[weather]`` wind_speed, wind_direction (towards which it blows: 0 tailwind, 90 deg
left to right), wind_profile, wind_reference_height, wind_profile_parameter, temperature,
altitude or pressure, humidity; ``[models]`` aero, bounce, cd_scale, cl_scale, dt;
``[[group]]`` name, target and dotted overrides (``launch.spin = ...``); ``[sweep]``
"section.key" = [values]. Defaults are those of ``mcrun.quantities`` (as for
``mcrun.api.simulate``), and the turf preset's.

Units: values may carry a unit (``"167 mph"``), or the key may (``ball_speed_mph = 167``); bare
values are SI, except angles (degrees) and temperatures (Celsius), as in ``mcrun.units``.

Distributions (``dist``): constant (a bare value, or ``{dist = "constant", value = ...}``),
normal (mean, sd), truncnormal (mean, sd, low, high), uniform (low, high), triangular (low,
mode, high), lognormal (median, sigma; sigma is the sd of the log, dimensionless). Ranges: a
constant, a normal's mean, a lognormal's median and the bounds of a truncnormal, uniform or
triangular must lie in the quantity's documented range (``mcrun.quantities``, whose table
``PARAMETERS`` is read from). A normal or lognormal draw may still fall outside it; the sampler
then makes that shot's kernel input invalid, so the kernel returns status ``invalid_input`` for
it (bound a quantity with a truncnormal to avoid that).
"""

import itertools
import math
import numbers
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcrun.hole.errors import HoleError
from mcrun.hole.hole import hole_from_table
from mcrun.physics.constants import DEG
from mcrun.quantities import BOUNCE_MODELS, QUANTITIES, SECTIONS, InputError, default_of
from mcrun.run.monitors import FILE_COLUMNS, check_file, read_session
from mcrun.run.monitors import NAMES as MONITOR_FORMATS
from mcrun.units import (
    KINDS,
    UnitError,
    foreign_digits,
    from_column_name,
    parse_quantity,
    shown,
    to_unit,
)

__all__ = [
    "BOUNCE_MODELS",
    "DEFAULT_BLOCK_SIZE",
    "DISTRIBUTIONS",
    "ENV_LIBRARY",
    "FILE_COLUMNS",
    "PARAMETERS",
    "Correlation",
    "Dist",
    "Param",
    "Point",
    "Resample",
    "Scenario",
    "ScenarioError",
    "find",
    "library_folder",
    "list_library",
    "load",
    "question_of",
]


class ScenarioError(InputError):
    """A scenario cannot be used; the message is one line: file, key path, what is allowed."""


DEFAULT_BLOCK_SIZE = 4096
MAX_BLOCK_SIZE = 1 << 20
ENV_LIBRARY = "MCRUN_SCENARIOS"

# A truncnormal whose interval lies further than this many sd from its mean is refused: its
# probability mass underflows.
_TRUNCNORMAL_MAX_Z = 30.0


@dataclass(frozen=True)
class Param:
    """One parameter of a section: its kind (a ``mcrun.units`` kind, "number" for a
    dimensionless value, "choice" for a name), SI limits, and whether it may be sampled."""

    kind: str
    limits: tuple[float, float] | None = None
    choices: tuple[str, ...] = ()
    constant_only: bool = False


PARAMETERS: dict[str, dict[str, Param]] = {
    section: {
        path.partition(".")[2]: Param(q.kind, q.limits, q.choices, q.constant_only)
        for q in QUANTITIES
        for path in q.paths
        if path.partition(".")[0] == section
    }
    for section in SECTIONS
}
"""Section -> parameter name -> Param. Every sampled quantity of a scenario is one of these."""

# Keys of a section that are not quantities.
_SPECIAL = {
    "launch": ("correlation", "file", "jitter", "club", "format", "sample"),
    "club": ("correlation",),
}
_SECTIONS = tuple(PARAMETERS)
_TOP_KEYS = ("scenario", *_SECTIONS, "group", "sweep", "hole")
_SCENARIO_KEYS = ("name", "question", "description", "shots", "seed", "target", "block_size")
_GROUP_KEYS = ("name", "target", *_SECTIONS)
_BALL = ("ball_speed", "launch_angle", "spin")
_CLUB = ("speed", "loft")
_OPTIONAL_LAUNCH = ("azimuth", "spin_axis")

DISTRIBUTIONS = {
    # dist: its keys, in the order of Dist.args; "sd"-like keys are spreads (no unit offset).
    "constant": ("value",),
    "normal": ("mean", "sd"),
    "truncnormal": ("mean", "sd", "low", "high"),
    "uniform": ("low", "high"),
    "triangular": ("low", "mode", "high"),
    "lognormal": ("median", "sigma"),
}
_SPREADS = ("sd",)
_DIMENSIONLESS = ("sigma",)

# --- the objects ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Dist:
    """A quantity's distribution, SI. ``args`` follow ``DISTRIBUTIONS[dist]``."""

    kind: str
    dist: str
    args: tuple[float, ...]

    @property
    def is_constant(self):
        """True for a constant, and for a normal with sd 0 or a lognormal with sigma 0."""
        return self.dist == "constant" or (
            self.dist in ("normal", "lognormal") and self.args[1] == 0.0
        )

    @property
    def value(self):
        """The value of a constant (the mean or median when the spread is 0)."""
        if not self.is_constant:
            raise ValueError(f"a {self.dist} distribution has no single value")
        return self.args[0]

    @property
    def center(self):
        """A typical value: the constant, mean, median or mode (for defaults and checks)."""
        if self.dist in ("constant", "normal", "truncnormal", "lognormal"):
            return self.args[0]
        if self.dist == "uniform":
            return 0.5 * (self.args[0] + self.args[1])
        return self.args[1]

    def describe(self):
        """The distribution in the kind's bare unit, e.g. ``normal(mean=167 mph...)``."""
        unit = _bare_unit(self.kind)
        parts = []
        for key, value in zip(DISTRIBUTIONS[self.dist], self.args, strict=True):
            if key in _DIMENSIONLESS or self.kind in ("number", "choice"):
                parts.append(f"{key}={value:g}")
            elif key in _SPREADS:
                parts.append(f"{key}={_spread_in(value, self.kind):g}{unit}")
            else:
                parts.append(f"{key}={_in_unit(value, self.kind):g}{unit}")
        return f"{self.dist}({', '.join(parts)})"


@dataclass(frozen=True)
class Correlation:
    """Jointly normal quantities of one section: their names, the correlation matrix and a
    lower-triangular factor F with F F^T = matrix (``semidefinite_cholesky``), so that F z has
    that correlation for standard normal z."""

    names: tuple[str, ...]
    matrix: np.ndarray
    factor: np.ndarray

    def __eq__(self, other):
        return (
            isinstance(other, Correlation)
            and self.names == other.names
            and np.array_equal(self.matrix, other.matrix)
            and np.array_equal(self.factor, other.factor)
        )

    __hash__ = None


# How ``launch.file`` draws the launches: the measured shots themselves, or a fitted normal.
FILE_SAMPLING = ("resample", "normal")

# The name and the SI -> factor of each launch quantity in a fit's table (the sampled columns).
FIT_COLUMNS = {
    "ball_speed": ("ball_speed_mps", 1.0),
    "launch_angle": ("launch_angle_deg", 1.0 / DEG),
    "azimuth": ("azimuth_deg", 1.0 / DEG),
    "spin": ("spin_radps", 1.0),
    "spin_axis": ("spin_axis_deg", 1.0 / DEG),
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
    to the shots and drawn from instead (``sample = "normal"``)."""

    path: Path
    columns: dict
    n_rows: int
    jitter: dict = field(default_factory=dict)
    rows: np.ndarray | None = None
    fit: NormalFit | None = None
    club: str | None = None

    def __eq__(self, other):
        return (
            isinstance(other, Resample)
            and (self.path, self.n_rows, self.jitter) == (other.path, other.n_rows, other.jitter)
            and self.columns.keys() == other.columns.keys()
            and all(np.array_equal(v, other.columns[k]) for k, v in self.columns.items())
            and np.array_equal(self.source_rows, other.source_rows)
            and (self.fit, self.club) == (other.fit, other.club)
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


@dataclass(frozen=True)
class Point:
    """One group x sweep combination of a scenario.

    ``params`` maps key paths to resolved specs: ``Dist`` for quantities (SI), ``str`` for
    choices (``turf.preset``, ``weather.wind_profile``, ``models.aero``, ``models.bounce``),
    ``Correlation`` at ``launch.correlation`` or ``club.correlation`` and ``Resample`` at
    ``launch.file``. The launch is given by ``launch.*`` (ball) or ``club.*`` (club delivery);
    with a file, quantities it holds are not in ``params``. Turf fields not given come from the
    preset; ``turf.stimp`` replaces ``turf.rho_g``; ``weather.altitude`` replaces
    ``weather.pressure``.
    """

    index: int
    label: str
    group: str
    sweep: dict
    params: dict
    target_m: tuple[float, float] | None

    @property
    def mode(self):
        """How the launch is given: "ball", "club" or "file"."""
        if "launch.file" in self.params:
            return "file"
        return "club" if "club.speed" in self.params else "ball"


@dataclass(frozen=True)
class Scenario:
    """A validated scenario: the file, its text, defaults for a run, and its points."""

    path: Path
    text: str
    name: str
    question: str
    shots: int
    seed: int
    block_size: int
    points: list
    # The hole the shots are played on (``mcrun.hole.hole.Hole``), None on a plane, and the
    # azimuth (rad, + right) of its aim point from the tee: the shots' azimuths are about it.
    hole: object = None
    aim_rad: float | None = None


# --- the library ---------------------------------------------------------------------------


def library_folder():
    """The folder of the scenario library.

    ``$MCRUN_SCENARIOS`` when set (an explicit choice wins), else the ``scenarios/`` folder
    shipped beside the package (the repository root for a source checkout or an editable
    install). Raises ScenarioError if neither is a folder.
    """
    env = os.environ.get(ENV_LIBRARY)
    if env:
        folder = Path(env)
        if not folder.is_dir():
            raise ScenarioError(f"{ENV_LIBRARY}={env}: not a folder of scenario files")
        return folder
    folder = Path(__file__).resolve().parents[2] / "scenarios"
    if folder.is_dir():
        return folder
    raise ScenarioError(
        f"no scenario library found: {folder} does not exist; set {ENV_LIBRARY} to the folder "
        "that holds the *.toml scenarios"
    )


_QUESTION = re.compile(r"^#\s*Question:\s*(.*?)\s*$")


def question_of(text):
    """The question the scenario ``text`` answers: its first ``# Question:`` comment line,
    else ``[scenario] question``, else "" (the library's list, ``load`` and the report's title
    all read it here)."""
    for line in text.splitlines():
        match = _QUESTION.match(line.strip())
        if match:
            return match[1]
    try:
        question = tomllib.loads(text).get("scenario", {}).get("question", "")
    except (tomllib.TOMLDecodeError, AttributeError):
        return ""
    return question if isinstance(question, str) else ""


def list_library(folder=None):
    """[(name, path, question)] of the ``*.toml`` files of ``folder`` (default: the library),
    sorted by name. The name is the file's stem; the question its ``# Question:`` line."""
    folder = library_folder() if folder is None else Path(folder)
    entries = []
    for path in sorted(folder.glob("*.toml")):
        try:
            text = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            text = ""
        entries.append((path.stem, path, question_of(text)))
    return entries


def find(name_or_path):
    """The path of a scenario: a file that exists, or the name of a library scenario
    (``"pga-driver"`` or ``"pga-driver.toml"``). ScenarioError if neither."""
    path = Path(name_or_path)
    if path.is_file():
        return path
    if path.parent == Path(".") and path.suffix in ("", ".toml"):
        try:
            folder = library_folder()
        except ScenarioError:
            folder = None
        if folder is not None:
            candidate = folder / (path.stem + ".toml")
            if candidate.is_file():
                return candidate
    if path.exists():
        raise ScenarioError(f"{name_or_path}: not a file")
    raise ScenarioError(
        f"{name_or_path}: no such file, nor a scenario of the library (mcrun scenarios lists it)"
    )


# --- values with units ---------------------------------------------------------------------


def _bare_unit(kind):
    if kind in ("number", "choice"):
        return ""
    unit = KINDS[kind][0]
    return "" if unit == "fraction" else " " + unit


def _in_unit(value_si, kind):
    """An SI value in the kind's bare unit (deg, C, ...), for messages."""
    if kind in ("number", "choice"):
        return value_si
    return to_unit(value_si, kind, KINDS[kind][0])


def _spread_in(value_si, kind):
    """An SI difference (an sd) in the kind's bare unit: the scale only, no offset."""
    if kind in ("number", "choice"):
        return value_si
    return value_si / KINDS[kind][1][KINDS[kind][0]][0]


def _shown(value):
    return shown(value, 60)


_LEADING_NUMBER = re.compile(r"^\s*[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")


@dataclass
class _Context:
    """Where a value comes from, for messages: the file and a key path."""

    file: str

    def error(self, where, what):
        return ScenarioError(f"{self.file}: {where}: {what}")


@dataclass(frozen=True)
class _Leaf:
    """A raw value of a parameter as written: the value, where it was written, and the unit
    its key carried (``spin_rpm`` -> "rpm"), or None."""

    value: object
    where: str
    key_unit: str | None = None


def _number(value):
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _read(ctx, where, value, kind, key_unit, spread=False):
    """One value of a quantity (a number or a string with an optional unit) in SI."""
    if kind == "number" or key_unit is not None and kind != "choice":
        if isinstance(value, str):
            foreign = foreign_digits(value)
            if foreign is not None:
                raise ctx.error(where, f"cannot read {_shown(value)}: {foreign}")
            try:
                value = float(value)
            except ValueError:
                if kind == "number":
                    raise ctx.error(
                        where, f"must be a number (dimensionless), got {_shown(value)}"
                    ) from None
                raise ctx.error(
                    where,
                    f"the key gives the unit ({key_unit}): give a bare number, got {_shown(value)}",
                ) from None
        if not _number(value):
            raise ctx.error(where, f"must be a number, got {_shown(value)}")
        if not math.isfinite(value):
            raise ctx.error(where, f"must be finite, got {value}")
        if kind == "number":
            return float(value)
        value = f"{float(value)!r} {key_unit}"
    if not (isinstance(value, str) or _number(value)):
        raise ctx.error(
            where,
            f"must be a number or a string with a unit ({', '.join(KINDS[kind][1])}), "
            f"got {_shown(value)}",
        )
    try:
        si = parse_quantity(value, kind)
        if spread:
            zero = _LEADING_NUMBER.sub("0", value, count=1) if isinstance(value, str) else 0.0
            si -= parse_quantity(zero, kind)
    except UnitError as err:
        raise ctx.error(where, str(err)) from None
    return si


def _fmt(value_si, kind, spread=False):
    """An SI value in the kind's bare unit, e.g. "-5 rad/s", "12 deg"."""
    if kind == "number":
        return f"{value_si:g}"
    number = _spread_in(value_si, kind) if spread else _in_unit(value_si, kind)
    return f"{number:g}{_bare_unit(kind)}"


def _check_in(ctx, where, value_si, param, what="must be"):
    lo, hi = param.limits
    if not lo <= value_si <= hi:
        raise ctx.error(
            where,
            f"{what} within [{_fmt(lo, param.kind)}, {_fmt(hi, param.kind)}], "
            f"got {_fmt(value_si, param.kind)}",
        )


def _dist(ctx, leaf, param):
    """A Dist from a raw value (constant or distribution table), validated against param."""
    value, where = leaf.value, leaf.where
    kind = param.kind
    if not isinstance(value, dict):
        if isinstance(value, list):
            raise ctx.error(
                where,
                "must be a value or a distribution table {dist = ...}, got a list "
                "(sweep a parameter in [sweep])",
            )
        si = _read(ctx, where, value, kind, leaf.key_unit)
        _check_in(ctx, where, si, param)
        return Dist(kind, "constant", (si,))
    if "dist" not in value:
        raise ctx.error(f"{where}.dist", f"missing; choose one of {', '.join(DISTRIBUTIONS)}")
    name = value["dist"]
    if name not in DISTRIBUTIONS:
        raise ctx.error(
            f"{where}.dist",
            f"unknown distribution {_shown(name)}; choose one of {', '.join(DISTRIBUTIONS)}",
        )
    keys = DISTRIBUTIONS[name]
    for key in value:
        if key != "dist" and key not in keys:
            raise ctx.error(
                f"{where}.{key}",
                f"unknown key for a {name} distribution; allowed: dist, {', '.join(keys)}",
            )
    args = []
    for key in keys:
        if key not in value:
            raise ctx.error(
                f"{where}.{key}", f"missing: a {name} distribution needs {', '.join(keys)}"
            )
        if key in _DIMENSIONLESS:
            args.append(_read(ctx, f"{where}.{key}", value[key], "number", None))
        else:
            args.append(
                _read(ctx, f"{where}.{key}", value[key], kind, leaf.key_unit, key in _SPREADS)
            )
    if param.constant_only and name != "constant":
        raise ctx.error(where, f"must be a constant, not a {name} distribution")
    if name == "constant":
        _check_in(ctx, f"{where}.value", args[0], param)
    elif name in ("normal", "truncnormal"):
        mean, sd = args[:2]
        if sd < 0.0:
            raise ctx.error(f"{where}.sd", f"must be >= 0, got {_fmt(sd, kind, spread=True)}")
        if name == "normal":
            _check_in(ctx, f"{where}.mean", mean, param)
        else:
            low, high = args[2:]
            if sd == 0.0:
                raise ctx.error(f"{where}.sd", "must be > 0 for a truncnormal, got 0")
            if not low < high:
                raise ctx.error(
                    f"{where}.low",
                    f"must be < high ({_fmt(high, kind)}), got {_fmt(low, kind)}",
                )
            _check_in(ctx, f"{where}.low", low, param)
            _check_in(ctx, f"{where}.high", high, param)
            if (low - mean) / sd > _TRUNCNORMAL_MAX_Z or (high - mean) / sd < -_TRUNCNORMAL_MAX_Z:
                raise ctx.error(
                    where,
                    f"[low, high] must come within {_TRUNCNORMAL_MAX_Z:g} sd of the mean",
                )
    elif name in ("uniform", "triangular"):
        low, high = args[0], args[-1]
        if not low < high:
            raise ctx.error(
                f"{where}.low", f"must be < high ({_fmt(high, kind)}), got {_fmt(low, kind)}"
            )
        _check_in(ctx, f"{where}.low", low, param)
        _check_in(ctx, f"{where}.high", high, param)
        if name == "triangular" and not low <= args[1] <= high:
            raise ctx.error(
                f"{where}.mode",
                f"must be within [low, high] = [{_fmt(low, kind)}, {_fmt(high, kind)}], "
                f"got {_fmt(args[1], kind)}",
            )
    else:  # lognormal
        median, sigma = args
        if not median > 0.0:
            raise ctx.error(f"{where}.median", f"must be > 0, got {_fmt(median, kind)}")
        if sigma < 0.0:
            raise ctx.error(f"{where}.sigma", f"must be >= 0, got {sigma:g}")
        _check_in(ctx, f"{where}.median", median, param)
    return Dist(kind, name, tuple(args))


def _choice(ctx, leaf, param):
    if not isinstance(leaf.value, str) or leaf.value not in param.choices:
        raise ctx.error(
            leaf.where,
            f"must be one of {', '.join(param.choices)}, got {_shown(leaf.value)}",
        )
    return leaf.value


# --- reading the file into leaves ------------------------------------------------------------


def _table(ctx, where, value):
    if not isinstance(value, dict):
        raise ctx.error(where, f"must be a table, got {_shown(value)}")
    return value


def _canonical(ctx, section, key, where):
    """(parameter name, key unit) of a key of a section; units may be in the name."""
    names = PARAMETERS[section]
    if key in names or key in _SPECIAL.get(section, ()):
        return key, None
    found = from_column_name(key)
    if found is not None and found[0] in names:
        base, kind, unit = found
        if names[base].kind != kind:
            expected = names[base].kind
            allowed = (
                f"units of a {expected}: {', '.join(KINDS[expected][1])}"
                if expected in KINDS
                else "no unit (dimensionless)"
                if expected == "number"
                else "no unit"
            )
            raise ctx.error(where, f"{unit} is a {kind} unit, but {base} takes {allowed}")
        return base, unit
    allowed = ", ".join((*names, *_SPECIAL.get(section, ())))
    raise ctx.error(
        where,
        f"unknown key; allowed: {allowed} (a unit may end the name, e.g. ball_speed_mph)",
    )


def _section_leaves(ctx, section, table, prefix):
    """{parameter: _Leaf} of one section table; ``prefix`` is where it sits in the file."""
    table = _table(ctx, prefix.rstrip("."), table)
    leaves = {}
    for key, value in table.items():
        where = f"{prefix}{key}"
        name, unit = _canonical(ctx, section, key, where)
        if name in leaves:
            raise ctx.error(
                where, f"{section}.{name} is given twice ({leaves[name].where} and {where})"
            )
        leaves[name] = _Leaf(value, where, unit)
    return leaves


def _target(ctx, where, value):
    if not isinstance(value, list) or len(value) != 2:
        raise ctx.error(
            where, f'must be a pair [x, y] of lengths, e.g. ["251 m", "0 m"], got {_shown(value)}'
        )
    return tuple(_read(ctx, f"{where}[{k}]", v, "length", None) for k, v in enumerate(value))


def _flatten_sweep(ctx, table, prefix=""):
    """{key path: list} of a [sweep] table; accepts "launch.spin" = [...] and nested tables."""
    out = {}
    for key, value in table.items():
        path = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten_sweep(ctx, value, path + "."))
        else:
            out[path] = value
    return out


def _sweep_leaves(ctx, table):
    """[(section, name, key path as written, [leaf per value])] of the [sweep] table."""
    entries = []
    seen = {}
    for path, values in _flatten_sweep(ctx, _table(ctx, "sweep", table)).items():
        where = f'sweep."{path}"'
        section, _, key = path.partition(".")
        if section not in _SECTIONS or not key or "." in key:
            raise ctx.error(
                where,
                "a sweep key is a parameter path section.name with section one of "
                f'{", ".join(_SECTIONS)} (e.g. "launch.spin")',
            )
        name, unit = _canonical(ctx, section, key, where)
        if (section, name) in seen:
            raise ctx.error(where, f"{section}.{name} is swept twice (also {seen[section, name]})")
        seen[section, name] = where
        if not isinstance(values, list) or not values:
            raise ctx.error(where, f"must be a non-empty list of values, got {_shown(values)}")
        leaves = [_Leaf(v, f"{where}[{k}]", unit) for k, v in enumerate(values)]
        entries.append((section, name, path, leaves))
    return entries


def _written(value):
    """A sweep value as written, for labels."""
    if isinstance(value, str):
        return value
    if isinstance(value, dict):
        inner = ", ".join(f"{k}={_written(v)}" for k, v in value.items() if k != "dist")
        return f"{value.get('dist', '')}({inner})"
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


# --- resolving a point -------------------------------------------------------------------------


def _correlation(ctx, leaf, section, dists, leaves, context=""):
    """A Correlation from ``{names = [...], matrix = [[...]]}``, checked against the point."""
    where = leaf.where
    table = _table(ctx, where, leaf.value)
    for key in table:
        if key not in ("names", "matrix"):
            raise ctx.error(f"{where}.{key}", "unknown key; allowed: names, matrix")
    names = table.get("names")
    if not isinstance(names, list) or len(names) < 2 or not all(isinstance(n, str) for n in names):
        raise ctx.error(
            f"{where}.names", f"must be a list of at least two quantity names, got {_shown(names)}"
        )
    if len(set(names)) != len(names):
        raise ctx.error(f"{where}.names", f"must not repeat a name, got {names}")
    quantities = tuple(PARAMETERS[section])
    for name in names:
        if name not in quantities:
            raise ctx.error(
                f"{where}.names", f"unknown quantity {name!r}; allowed: {', '.join(quantities)}"
            )
        dist = dists.get(name)
        if dist is None or dist.dist != "normal":
            if name not in leaves:
                got = "not given"
            elif leaves[name].where == f"{section}.{name}":
                got = f"a {dist.dist}"
            else:
                got = f"a {dist.dist}, at {leaves[name].where}"
            raise ctx.error(
                f"{where}.names",
                f"{name} must be a normal distribution to be correlated ({section}.{name} is "
                f"{got}){context}",
            )
    k = len(names)
    rows = table.get("matrix")
    if (
        not isinstance(rows, list)
        or len(rows) != k
        or not all(isinstance(r, list) and len(r) == k for r in rows)
        or not all(_number(x) and math.isfinite(x) for r in rows for x in r)
    ):
        raise ctx.error(
            f"{where}.matrix", f"must be a {k} x {k} list of lists of numbers, got {_shown(rows)}"
        )
    matrix = np.array(rows, dtype=float)
    if not np.all(np.diag(matrix) == 1.0):
        raise ctx.error(
            f"{where}.matrix", f"must have 1 on the diagonal, got {np.diag(matrix).tolist()}"
        )
    if np.max(np.abs(matrix - matrix.T)) > 1e-12:
        raise ctx.error(f"{where}.matrix", "must be symmetric")
    if np.max(np.abs(matrix)) > 1.0:
        raise ctx.error(f"{where}.matrix", "entries must be within [-1, 1]")
    smallest = np.linalg.eigvalsh(matrix)[0]
    if smallest < -PSD_TOLERANCE * k:
        raise ctx.error(
            f"{where}.matrix",
            f"must be positive semi-definite, its smallest eigenvalue is {smallest:.3g}",
        )
    factor = semidefinite_cholesky(matrix)
    matrix.setflags(write=False)
    factor = np.ascontiguousarray(factor)
    factor.setflags(write=False)
    return Correlation(tuple(names), matrix, factor)


# Pivots of the Cholesky factor below this, relative to the matrix's scale (its largest
# eigenvalue is at most k for a k x k correlation matrix), are zero: a rank-deficient matrix
# whose rounding leaves a pivot of 1e-17 instead of 0 must not give its factor a column of
# 3e-9. Eigenvalues down to -PSD_TOLERANCE * k are rounding too.
PSD_TOLERANCE = 1e-10


def semidefinite_cholesky(matrix):
    """Lower-triangular F with F F^T = ``matrix``, for a positive semi-definite matrix.

    The Cholesky algorithm in plain Python (k is a handful of launch quantities), where a pivot
    below PSD_TOLERANCE * k is zero and so is the rest of its column: for a semi-definite matrix
    that column is zero in exact arithmetic. No LAPACK, so the factor, and the samples drawn
    with it, do not depend on which BLAS kernel the machine runs.
    """
    k = matrix.shape[0]
    factor = np.zeros((k, k))
    for j in range(k):
        pivot = matrix[j, j] - sum(factor[j, m] * factor[j, m] for m in range(j))
        if pivot <= PSD_TOLERANCE * k:
            continue
        factor[j, j] = math.sqrt(pivot)
        # Times the reciprocal, as LAPACK's dpotrf scales a column: the same factor, to the
        # bit, for the library's matrices.
        scale = 1.0 / factor[j, j]
        for i in range(j + 1, k):
            dot = sum(factor[i, m] * factor[j, m] for m in range(j))
            factor[i, j] = (matrix[i, j] - dot) * scale
    return factor


_FILE_CACHE: dict = {}


def _read_shots(ctx, where, path, club=None, format=None):
    """({quantity: SI array}, rows) of the launches of a launch-monitor file (mcrun's columns or
    a device's export, ``mcrun.run.monitors``) and their rows in the file (0-based); only the
    shots of ``club`` when given."""
    key = (str(path.resolve()), path.stat().st_mtime_ns, club, format)
    if key in _FILE_CACHE:
        return _FILE_CACHE[key]
    try:
        session = read_session(path, format)
    except InputError as err:
        raise ctx.error(where, str(err)) from None
    rows = np.arange(len(session.frame))
    if club is not None:
        if session.club is None:
            raise ctx.error(where, f"{path}: a club is asked for but the file has no club column")
        rows = np.flatnonzero([c.casefold() == club.casefold() for c in session.club])
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
            raise ctx.error(
                where,
                f"{path}: column {column!r} row {r + 1}: not a number "
                f"({_shown(raw)}); every row must be complete",
            )
        lo, hi = param.limits
        outside = np.flatnonzero((si < lo) | (si > hi))
        if outside.size:
            r = outside[0]
            raise ctx.error(
                where,
                f"{path}: column {column!r} row {rows[r] + 1}: "
                f"{to_unit(si[r], param.kind, unit):g} {unit} is outside the "
                f"allowed range [{_fmt(lo, param.kind)}, {_fmt(hi, param.kind)}]",
            )
        si.setflags(write=False)
        columns[quantity] = si
    rows = rows.astype(np.int64)
    rows.setflags(write=False)
    _FILE_CACHE[key] = columns, rows
    return columns, rows


def _resample(
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
                raise ctx.error(option.where, f"must be {allowed}, got {_shown(option.value)}")
            if known is not None and option.value not in known:
                raise ctx.error(option.where, f"must be {allowed}, got {_shown(option.value)}")
            choices[name] = option.value.strip()
    normal = choices.get("sample") == "normal"
    if normal and jitter_leaf is not None:
        raise ctx.error(
            jitter_leaf.where,
            'not allowed with launch.sample = "normal": the fitted normal has the shots\' spread',
        )
    if not isinstance(leaf.value, str) or not leaf.value:
        raise ctx.error(where, f"must be a path to a CSV or Parquet file, got {_shown(leaf.value)}")
    path = Path(leaf.value)
    if not path.is_absolute():
        path = scenario_dir / path
    try:
        check_file(path)  # before _read_shots looks at its time stamp
    except InputError as err:
        raise ctx.error(where, str(err)) from None
    columns, rows = _read_shots(ctx, where, path, choices.get("club"), choices.get("format"))
    jitter = {}
    if jitter_leaf is not None:
        table = _table(ctx, jitter_leaf.where, jitter_leaf.value)
        for key, value in table.items():
            jwhere = f"{jitter_leaf.where}.{key}"
            name, unit = _canonical(ctx, "launch", key, jwhere)
            if name not in FILE_COLUMNS:
                raise ctx.error(jwhere, f"unknown key; allowed: {', '.join(FILE_COLUMNS)}")
            if name in jitter:
                raise ctx.error(jwhere, f"jitter of {name} is given twice")
            param = PARAMETERS["launch"][name]
            sd = _read(ctx, jwhere, value, param.kind, unit, spread=True)
            if sd < 0.0:
                raise ctx.error(jwhere, f"must be >= 0, got {_fmt(sd, param.kind, spread=True)}")
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
    return Resample(path, dict(columns), n_rows, jitter, rows, fit, choices.get("club"))


def launch_fits(points):
    """The normal fits of the points' launch files, each once, JSON-able: the ``points`` (their
    indices) that draw from it, the ``file``, the ``club`` (or None) and ``NormalFit.as_dict``.
    What a run prints when it starts and records beside its scenario."""
    fits = []
    for point in points:
        spec = point.params.get("launch.file")
        if spec is None or spec.fit is None:
            continue
        entry = {"file": str(spec.path), "club": spec.club, **spec.fit.as_dict()}
        same = next((f for f in fits if {**f, "points": None} == {**entry, "points": None}), None)
        if same is None:
            fits.append({"points": [point.index], **entry})
        else:
            same["points"].append(point.index)
    return fits


def _resolve(ctx, sections, scenario_dir, context):
    """The params of one point from its merged {section: {name: _Leaf}}."""
    params = {}
    launch = sections.get("launch", {})
    club = sections.get("club", {})

    def quantity(section, name):
        leaf = sections.get(section, {}).get(name)
        param = PARAMETERS[section][name]
        if leaf is None:
            default = default_of(f"{section}.{name}", params)
            if default is None:
                return None
            dist = Dist(param.kind, "constant", (float(default),))
        elif param.kind == "choice":
            return _choice(ctx, leaf, param)
        else:
            dist = _dist(ctx, leaf, param)
        params[f"{section}.{name}"] = dist
        return dist

    def choice(section, name):
        leaf = sections.get(section, {}).get(name)
        if leaf is None:
            value = default_of(f"{section}.{name}", params)
        else:
            value = _choice(ctx, leaf, PARAMETERS[section][name])
        params[f"{section}.{name}"] = value
        return value

    # Launch: ball, club or file.
    if launch and club:
        first = next(iter(club.values())).where
        raise ctx.error(
            first,
            f"give the ball launch [launch] or the club delivery [club], not both{context}",
        )
    if club:
        missing = [n for n in _CLUB if n not in club]
        if missing:
            raise ctx.error(
                f"club.{missing[0]}", f"missing: a club delivery needs speed and loft{context}"
            )
        dists = {}
        for name in PARAMETERS["club"]:
            dists[name] = quantity("club", name)
        if "correlation" in club:
            params["club.correlation"] = _correlation(
                ctx, club["correlation"], "club", dists, club, context
            )
    elif "file" in launch:
        for name in _BALL:
            if name in launch:
                raise ctx.error(
                    launch[name].where,
                    f"not allowed with launch.file, which gives {name}{context}",
                )
        if "correlation" in launch:
            raise ctx.error(
                launch["correlation"].where,
                f"not allowed with launch.file: the measured shots keep their own correlation"
                f"{context}",
            )
        resample = _resample(
            ctx,
            launch["file"],
            launch.get("jitter"),
            scenario_dir,
            launch.get("club"),
            launch.get("format"),
            launch.get("sample"),
        )
        params["launch.file"] = resample
        for name in _OPTIONAL_LAUNCH:
            if name in resample.columns:
                if name in launch:
                    raise ctx.error(
                        launch[name].where,
                        f"not allowed: the file {resample.path.name} gives {name}{context}",
                    )
            else:
                if name in launch and name in resample.jitter:
                    raise ctx.error(
                        launch[name].where,
                        f"{name} is given here and jittered in launch.jitter: give one{context}",
                    )
                if name not in resample.jitter:
                    quantity("launch", name)
    else:
        for key in ("jitter", "club", "format", "sample"):
            if key in launch:
                raise ctx.error(launch[key].where, f"only allowed with launch.file{context}")
        if not launch:
            raise ctx.error(
                "launch",
                "missing: give [launch] with ball_speed, launch_angle and spin, [launch] with "
                f"file = a launch-monitor CSV or Parquet, or [club] with speed and loft{context}",
            )
        missing = [n for n in _BALL if n not in launch]
        if missing:
            raise ctx.error(
                f"launch.{missing[0]}",
                f"missing: a ball launch needs ball_speed, launch_angle and spin (or give launch."
                f"file, or [club]){context}",
            )
        dists = {name: quantity("launch", name) for name in PARAMETERS["launch"]}
        if "correlation" in launch:
            params["launch.correlation"] = _correlation(
                ctx, launch["correlation"], "launch", dists, launch, context
            )

    # The conditions: every quantity of the turf, the weather and the models, given or its
    # default (``mcrun.quantities``: a turf field's is the preset's); a Stimp reading replaces
    # rho_g, an altitude the pressure. The checks across quantities come where they did.
    turf = sections.get("turf", {})
    weather = sections.get("weather", {})

    def check_turf():
        if "rho_g" in turf and "stimp" in turf:
            raise ctx.error(
                turf["stimp"].where, f"give turf.rho_g or turf.stimp, not both{context}"
            )

    def check_profile():
        profile = params["weather.wind_profile"]
        reference = params["weather.wind_reference_height"].value
        parameter = params["weather.wind_profile_parameter"].value
        if "wind_profile_parameter" in weather:
            where = weather["wind_profile_parameter"].where
            if profile == "log" and not 0.0 < parameter < reference:
                raise ctx.error(
                    where,
                    "the log profile's roughness length (m) must be > 0 and below the reference "
                    f"height ({reference:g} m), got {parameter:g}{context}",
                )
            if profile == "power" and not 0.0 <= parameter <= 1.0:
                raise ctx.error(
                    where, f"the power profile's exponent must be within [0, 1], got {parameter:g}"
                )
        elif profile == "log" and not parameter < reference:
            raise ctx.error(
                weather["wind_reference_height"].where,
                f"must be above the log profile's roughness length ({parameter:g} m){context}",
            )

    def check_air():
        if "altitude" in weather and "pressure" in weather:
            raise ctx.error(
                weather["pressure"].where,
                f"give weather.altitude or weather.pressure, not both{context}",
            )

    before = {"turf.mu": check_turf, "weather.temperature": check_profile}
    before["weather.altitude"] = check_air
    replaced = {"turf.rho_g": "stimp" in turf, "weather.pressure": "altitude" in weather}
    for section in ("turf", "weather", "models"):
        for name, param in PARAMETERS[section].items():
            path = f"{section}.{name}"
            if path in before:
                before[path]()
            if param.kind == "choice":
                choice(section, name)
            elif not replaced.get(path, False):
                quantity(section, name)
    return params


# --- loading ---------------------------------------------------------------------------------


def _integer(ctx, where, value, low, high=None):
    if (
        not isinstance(value, int)
        or isinstance(value, bool)
        or value < low
        or (high is not None and value > high)
    ):
        bound = f">= {low}" if high is None else f"within [{low}, {high}]"
        raise ctx.error(where, f"must be an integer {bound}, got {_shown(value)}")
    return value


def load(path):
    """Read and validate a scenario file (or a library scenario's name) into a Scenario.

    Raises
    ------
    ScenarioError
        With one line naming the file, the key path and what is allowed.
    """
    path = find(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise ScenarioError(f"{path}: cannot read the file: {err}") from None
    return loads(text, path)


def loads(text, path):
    """A Scenario from its TOML ``text``, as if read from ``path`` (which names it in errors
    and against which a resampled shots file is found): how a worker of a distributed run, or
    a rerun from a run's provenance, gets the scenario without the file."""
    path = Path(path)
    ctx = _Context(str(path))
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ScenarioError(f"{path}: not valid TOML: {err}") from None
    for key in data:
        if key not in _TOP_KEYS:
            raise ctx.error(key, f"unknown key; allowed: {', '.join(_TOP_KEYS)}")

    head = _table(ctx, "scenario", data.get("scenario", {}))
    for key in head:
        if key not in _SCENARIO_KEYS:
            raise ctx.error(f"scenario.{key}", f"unknown key; allowed: {', '.join(_SCENARIO_KEYS)}")
    for key in ("name", "question", "description"):
        if key in head and not isinstance(head[key], str):
            raise ctx.error(f"scenario.{key}", f"must be a string, got {_shown(head[key])}")
    name = head.get("name", path.stem)
    question = question_of(text)
    shots = _integer(ctx, "scenario.shots", head.get("shots", 100_000), 1)
    seed = _integer(ctx, "scenario.seed", head.get("seed", 0), 0)
    block_size = _integer(
        ctx, "scenario.block_size", head.get("block_size", DEFAULT_BLOCK_SIZE), 1, MAX_BLOCK_SIZE
    )
    target = _target(ctx, "scenario.target", head["target"]) if "target" in head else None
    hole, aim_rad = _hole(ctx, data, path) if "hole" in data else (None, None)
    if hole is not None and target is None:
        target = tuple(float(v) for v in hole.pin_xy)

    base = {s: _section_leaves(ctx, s, data[s], f"{s}.") for s in _SECTIONS if s in data}

    groups = data.get("group")
    if groups is None:
        groups = []
        group_list = [("", {}, target, "")]
    else:
        if not isinstance(groups, list) or not all(isinstance(g, dict) for g in groups):
            raise ctx.error("group", "must be an array of tables ([[group]] with a name each)")
        group_list = []
        names = set()
        for k, table in enumerate(groups):
            where = f"group[{k}]"
            for key in table:
                if key not in _GROUP_KEYS:
                    raise ctx.error(
                        f"{where}.{key}", f"unknown key; allowed: {', '.join(_GROUP_KEYS)}"
                    )
            gname = table.get("name")
            if not isinstance(gname, str) or not gname.strip():
                got = "" if gname is None else f", got {_shown(gname)}"
                raise ctx.error(f"{where}.name", f"missing: every group needs a name{got}")
            if gname in names:
                raise ctx.error(f"{where}.name", f"group name {gname!r} is used twice")
            names.add(gname)
            overrides = {
                s: _section_leaves(ctx, s, table[s], f"{where}.{s}.")
                for s in _SECTIONS
                if s in table
            }
            gtarget = target
            if "target" in table:
                gtarget = _target(ctx, f"{where}.target", table["target"])
            group_list.append((gname, overrides, gtarget, where))

    sweep = _sweep_leaves(ctx, data["sweep"]) if "sweep" in data else []
    combos = list(itertools.product(*(leaves for _, _, _, leaves in sweep))) if sweep else [()]

    points = []
    single = len(group_list) * len(combos) == 1
    for gname, overrides, gtarget, _ in group_list:
        for combo in combos:
            sections = {s: dict(base.get(s, {})) for s in _SECTIONS}
            for s, leaves in overrides.items():
                sections[s].update(leaves)
            values = {}
            for (section, pname, written, _), leaf in zip(sweep, combo, strict=True):
                sections[section][pname] = leaf
                values[written] = leaf.value
            sweep_label = ", ".join(f"{k}={_written(v)}" for k, v in values.items())
            label = " | ".join(p for p in (gname, sweep_label) if p)
            context = "" if single else f" (point {label!r})"
            sections = {s: v for s, v in sections.items() if v}
            params = _resolve(ctx, sections, path.parent, context)
            points.append(Point(len(points), label, gname, values, params, gtarget))
    return Scenario(path, text, name, question, shots, seed, block_size, points, hole, aim_rad)


def _hole(ctx, data, path):
    """The scenario's ``[hole]`` (``hole.hole_from_table``) and the azimuth of its ``aim``
    ([x, y] m in the hole's frame; default the pin). On a hole the turf is the zones': a
    ``[turf]`` table anywhere is refused."""
    table = dict(_table(ctx, "hole", data["hole"]))
    aim = table.pop("aim", None)
    folder = path.parent.resolve()
    if "file" in table:
        # A hole file, its keys (paths relative to its folder) under those given here.
        hole_path = folder / str(table.pop("file"))
        try:
            with hole_path.open("rb") as f:
                given = tomllib.load(f)
        except (OSError, tomllib.TOMLDecodeError) as err:
            raise ctx.error("hole.file", f"cannot read {hole_path}: {err}") from None
        given = given["hole"] if isinstance(given.get("hole"), dict) else given
        table = {**given, **table}
        folder = hole_path.parent
    places = ["turf"] if "turf" in data else []
    groups = data.get("group")
    for k, group in enumerate(groups if isinstance(groups, list) else []):
        if isinstance(group, dict) and "turf" in group:
            places.append(f"group[{k}].turf")
    sweep = data.get("sweep")
    if isinstance(sweep, dict) and "turf" in sweep:
        places.append("sweep.turf")
    if places:
        raise ctx.error(places[0], "on a hole each zone has its turf: set it in [hole.turf.KIND]")
    hole = _cached_hole(
        tuple(sorted((k, repr(v)) for k, v in table.items())), table, folder, f"{path} [hole]"
    )
    if aim is None:
        aim = hole.pin_xy
    if (
        not isinstance(aim, list | tuple)
        or len(aim) != 2
        or not all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in aim)
        or not math.isfinite(aim[0] + aim[1])
        or aim[0] <= 0.0
    ):
        raise ctx.error("hole.aim", f"must be [x_m, y_m] ahead of the tee (x > 0), got {aim!r}")
    return hole, math.atan2(float(aim[1]), float(aim[0]))


_HOLES = {}


def _cached_hole(key, table, folder, source):
    """``hole.hole_from_table``, once per table and folder in a process (a Dask worker reads
    the scenario for every chunk)."""
    key = (key, str(folder))
    if key not in _HOLES:
        try:
            _HOLES[key] = hole_from_table(table, folder, source)
        except HoleError as err:
            raise ScenarioError(str(err)) from None
    return _HOLES[key]
