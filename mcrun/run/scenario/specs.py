"""What a scenario holds once read: its points' parameter specs (``Param``, ``PARAMETERS``,
read from the table of quantities), the distributions (``Dist``), a correlation, a point and the
scenario, and the error a scenario raises."""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mcrun.quantities import QUANTITIES, SECTIONS, InputError
from mcrun.units import (
    KINDS,
    to_unit,
)


class ScenarioError(InputError):
    """A scenario cannot be used; the message is one line: file, key path, what is allowed."""


DEFAULT_BLOCK_SIZE = 4096
MAX_BLOCK_SIZE = 1 << 20


@dataclass(frozen=True)
class Param:
    """One parameter of a section: its kind (a ``mcrun.units`` kind, "number" for a
    dimensionless value, "choice" for a name), SI limits, whether it may be sampled, and why a
    bare number is refused ("" where it is read in the kind's bare unit)."""

    kind: str
    limits: tuple[float, float] | None = None
    choices: tuple[str, ...] = ()
    constant_only: bool = False
    bare_refused: str = ""


PARAMETERS: dict[str, dict[str, Param]] = {
    section: {
        path.partition(".")[2]: Param(q.kind, q.limits, q.choices, q.constant_only, q.bare_refused)
        for q in QUANTITIES
        for path in q.paths
        if path.partition(".")[0] == section
    }
    for section in SECTIONS
}
"""Section -> parameter name -> Param. Every sampled quantity of a scenario is one of these."""

DISTRIBUTIONS = {
    # dist: its keys, in the order of Dist.args; "sd"-like keys are spreads (no unit offset).
    "constant": ("value",),
    "normal": ("mean", "sd"),
    "truncnormal": ("mean", "sd", "low", "high"),
    "uniform": ("low", "high"),
    "triangular": ("low", "mode", "high"),
    "lognormal": ("median", "sigma"),
}
SPREADS = ("sd",)
DIMENSIONLESS = ("sigma",)


def bare_unit(kind):
    if kind in ("number", "choice"):
        return ""
    unit = KINDS[kind][0]
    return "" if unit == "fraction" else " " + unit


def in_bare_unit(value_si, kind):
    """An SI value in the kind's bare unit (deg, C, ...), for messages."""
    if kind in ("number", "choice"):
        return value_si
    return to_unit(value_si, kind, KINDS[kind][0])


def spread_in_bare_unit(value_si, kind):
    """An SI difference (an sd) in the kind's bare unit: the scale only, no offset."""
    if kind in ("number", "choice"):
        return value_si
    return value_si / KINDS[kind][1][KINDS[kind][0]][0]


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
        unit = bare_unit(self.kind)
        parts = []
        for key, value in zip(DISTRIBUTIONS[self.dist], self.args, strict=True):
            if key in DIMENSIONLESS or self.kind in ("number", "choice"):
                parts.append(f"{key}={value:g}")
            elif key in SPREADS:
                parts.append(f"{key}={spread_in_bare_unit(value, self.kind):g}{unit}")
            else:
                parts.append(f"{key}={in_bare_unit(value, self.kind):g}{unit}")
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
    # On a hole, where its shots are struck and aimed (``hole_table.Play``); None on a plane.
    play: object = None

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
    # The hole the shots are played on (``mcrun.hole.hole.Hole``), None on a plane, and its
    # ``[hole]`` table's start and aim (``hole_table.Play``; each point has its own).
    hole: object = None
    play: object = None

    @property
    def aim_rad(self):
        """The bearing (rad, + right) of the ``[hole]`` table's aim from its start, None on a
        plane."""
        return None if self.play is None else self.play.aim_rad
