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
``[hole]`` the hole (``hole.hole``'s keys), ``start`` ([x, y] m in its frame; default the tee)
and ``aim`` (default the pin); ``[[group]]`` name, target, ``hole.start`` and ``hole.aim`` (a
group struck from elsewhere on the hole, aimed at the pin unless it says) and dotted overrides
(``launch.spin = ...``); ``[sweep]``
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

The package, one idea a module: ``specs`` (what a read scenario holds: ``PARAMETERS``, read from
the table of quantities ``mcrun.quantities``, ``Dist``, ``Point``, ``Scenario``), ``values`` (a
value as written, read and checked, and the file's tables read into leaves), ``correlation``,
``launch_file`` (a launch monitor's shots resampled, or the normal fitted to them), ``library``,
``hole_table`` (``[hole]``) and ``reader`` (``load``, ``loads``: the file, each point resolved).
Every name other modules use is imported from here.
"""

from mcrun.quantities import BOUNCE_MODELS
from mcrun.run.monitors import FILE_COLUMNS
from mcrun.run.scenario.correlation import PSD_TOLERANCE, semidefinite_cholesky
from mcrun.run.scenario.launch_file import (
    FILE_SAMPLING,
    FIT_COLUMNS,
    NormalFit,
    Resample,
    describe_fit,
    fit_normal,
    launch_files,
    launch_fits,
)
from mcrun.run.scenario.library import ENV_LIBRARY, find, library_folder, list_library, question_of
from mcrun.run.scenario.reader import load, loads
from mcrun.run.scenario.specs import (
    DEFAULT_BLOCK_SIZE,
    DISTRIBUTIONS,
    MAX_BLOCK_SIZE,
    PARAMETERS,
    Correlation,
    Dist,
    Param,
    Point,
    Scenario,
    ScenarioError,
)

__all__ = [
    "BOUNCE_MODELS",
    "DEFAULT_BLOCK_SIZE",
    "DISTRIBUTIONS",
    "ENV_LIBRARY",
    "FILE_COLUMNS",
    "FILE_SAMPLING",
    "FIT_COLUMNS",
    "MAX_BLOCK_SIZE",
    "PARAMETERS",
    "PSD_TOLERANCE",
    "Correlation",
    "Dist",
    "NormalFit",
    "Param",
    "Point",
    "Resample",
    "Scenario",
    "ScenarioError",
    "describe_fit",
    "find",
    "fit_normal",
    "launch_files",
    "launch_fits",
    "library_folder",
    "list_library",
    "load",
    "loads",
    "question_of",
    "semidefinite_cholesky",
]
