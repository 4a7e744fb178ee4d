"""The TOML reader: a scenario file into a ``Scenario``, every point resolved (its
quantities given or their defaults, the launch by ball, club or file)."""

import itertools
import math
import tomllib
from pathlib import Path

from mcrun.quantities import InputError, default_of, wind_profile_problem
from mcrun.run.scenario.correlation import read_correlation
from mcrun.run.scenario.hole_table import GROUP_KEYS, read_hole, read_play
from mcrun.run.scenario.launch_file import read_launch_file
from mcrun.run.scenario.library import find, question_of
from mcrun.run.scenario.specs import (
    DEFAULT_BLOCK_SIZE,
    MAX_BLOCK_SIZE,
    PARAMETERS,
    Dist,
    Point,
    Scenario,
    ScenarioError,
)
from mcrun.run.scenario.values import (
    SECTION_NAMES,
    Context,
    as_table,
    as_written,
    read_choice,
    read_dist,
    read_target,
    section_leaves,
    short,
    sweep_leaves,
)
from mcrun.units import control_free

_TOP_KEYS = ("scenario", *SECTION_NAMES, "group", "sweep", "hole")
# A scenario's name is its default run folder's (``runs/<name>-<seed>``), with room for the seed.
MAX_NAME_BYTES = 200
# The points a scenario may have (its groups times its sweep's combinations): each is read and
# checked as it is built (a hundred thousand take some 20 s and 0.9 GB).
MAX_POINTS = 100_000
_SCENARIO_KEYS = ("name", "question", "description", "shots", "seed", "target", "block_size")
_GROUP_KEYS = ("name", "target", "hole", *SECTION_NAMES)
_BALL = ("ball_speed", "launch_angle", "spin")
_CLUB = ("speed", "loft")
_OPTIONAL_LAUNCH = ("azimuth", "spin_axis")


def _resolve(ctx, sections, scenario_dir, context):
    """The params of one point from its merged {section: {name: Leaf}}."""
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
            return read_choice(ctx, leaf, param)
        else:
            dist = read_dist(ctx, leaf, param, f"{section}.{name}")
        params[f"{section}.{name}"] = dist
        return dist

    def choice(section, name):
        leaf = sections.get(section, {}).get(name)
        if leaf is None:
            value = default_of(f"{section}.{name}", params)
        else:
            value = read_choice(ctx, leaf, PARAMETERS[section][name])
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
            params["club.correlation"] = read_correlation(
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
        resample = read_launch_file(
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
            params["launch.correlation"] = read_correlation(
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
        problem = wind_profile_problem(profile, reference, parameter)
        if problem is not None:
            key = next((k for k in ("wind_profile_parameter", "wind_reference_height",
                                    "wind_profile") if k in weather), None)  # fmt: skip
            if key is None:
                raise InputError(problem)  # (a default profile is never refused)
            raise ctx.error(weather[key].where, f"{problem}{context}")

    def check_air():
        if "altitude" in weather and "pressure" in weather:
            raise ctx.error(
                weather["pressure"].where,
                f"give weather.altitude or weather.pressure, not both{context}",
            )

    # The checks across quantities, each where the file's sections come to it.
    after = {"turf.preset": check_turf, "weather.wind_profile_parameter": check_profile}
    before = {"weather.altitude": check_air}
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
            if path in after:
                after[path]()
    return params


# --- loading ---------------------------------------------------------------------------------


def _integer(ctx, where, value, low, high=None):
    if (
        not isinstance(value, int)
        or isinstance(value, bool)
        or value < low
        or (high is not None and value > high)
    ):
        top = "2**63 - 1" if high == 2**63 - 1 else high
        bound = f">= {low}" if high is None else f"within [{low}, {top}]"
        raise ctx.error(where, f"must be an integer {bound}, got {short(value)}")
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
        text = path.read_text(encoding="utf-8-sig")  # (a byte-order mark, as Notepad saves)
    except (OSError, UnicodeDecodeError) as err:
        raise ScenarioError(f"{path}: cannot read the file: {err}") from None
    return loads(text, path)


def loads(text, path):
    """A Scenario from its TOML ``text``, as if read from ``path`` (which names it in errors
    and against which a resampled shots file is found): how a worker of a distributed run, or
    a rerun from a run's provenance, gets the scenario without the file."""
    path = Path(path)
    ctx = Context(str(path))
    try:
        data = tomllib.loads(text)
    except ValueError as err:  # (TOMLDecodeError, or an integer of over 4,300 digits)
        raise ScenarioError(f"{path}: not valid TOML: {err}") from None
    for key in data:
        if key not in _TOP_KEYS:
            raise ctx.error(key, f"unknown key; allowed: {', '.join(_TOP_KEYS)}")

    head = as_table(ctx, "scenario", data.get("scenario", {}))
    for key in head:
        if key not in _SCENARIO_KEYS:
            raise ctx.error(f"scenario.{key}", f"unknown key; allowed: {', '.join(_SCENARIO_KEYS)}")
    for key in ("name", "question", "description"):
        if key in head and not isinstance(head[key], str):
            raise ctx.error(f"scenario.{key}", f"must be a string, got {short(head[key])}")
        # Printed by validate, run and scenarios: an escape sequence would reach the terminal
        # (a window's title set, the screen cleared); a description may have lines and tabs.
        plain = "".join(c for c in head.get(key, "") if key != "description" or c not in "\n\t")
        if control_free(plain) != plain:
            raise ctx.error(f"scenario.{key}", f"{short(head[key])}: allowed: text without "
                            "control characters (an escape sequence, a line break)")  # fmt: skip
    name = head.get("name", path.stem)
    if "name" in head and (
        not name.strip() or name.startswith(".") or any(c in name for c in "/\\\0")
        or len(name.encode("utf-8")) > MAX_NAME_BYTES
    ):  # fmt: skip
        raise ctx.error(
            "scenario.name",
            f"{short(name)}: allowed is a name a run's folder can take (runs/<name>-<seed>): "
            f"not blank, no / or \\, not starting with '.', at most {MAX_NAME_BYTES} bytes",
        )
    question = question_of(text)
    # (an int64, as the options: beyond it a run said "--seed (seed) must be...", untyped)
    shots = _integer(ctx, "scenario.shots", head.get("shots", 100_000), 1, 2**63 - 1)
    seed = _integer(ctx, "scenario.seed", head.get("seed", 0), 0, 2**63 - 1)
    block_size = _integer(
        ctx, "scenario.block_size", head.get("block_size", DEFAULT_BLOCK_SIZE), 1, MAX_BLOCK_SIZE
    )
    target = read_target(ctx, "scenario.target", head["target"]) if "target" in head else None
    hole, play = read_hole(ctx, data, path) if "hole" in data else (None, None)
    if hole is not None and target is None:
        target = tuple(float(v) for v in hole.pin_xy)

    base = {s: section_leaves(ctx, s, data[s], f"{s}.") for s in SECTION_NAMES if s in data}

    groups = data.get("group")
    if groups is None:
        groups = []
        group_list = [("", {}, target, play)]
    else:
        if not isinstance(groups, list) or not all(isinstance(g, dict) for g in groups):
            raise ctx.error("group", "must be an array of tables ([[group]] with a name each)")
        group_list = []
        names = set()
        for k, table in enumerate(groups):
            where = f"group[{k}]"
            for key in table:
                if key not in _GROUP_KEYS:
                    # "launch.spin" quoted is one key of that name (as [sweep] writes it)
                    dotted = key.partition(".")[0] in SECTION_NAMES
                    hint = f" (write {key} unquoted: a dotted key)" if dotted else ""
                    raise ctx.error(
                        f"{where}.{key}", f"unknown key; allowed: {', '.join(_GROUP_KEYS)}{hint}"
                    )
            gname = table.get("name")
            if not isinstance(gname, str) or not gname.strip():
                got = "" if gname is None else f", got {short(gname)}"
                raise ctx.error(f"{where}.name", f"missing: every group needs a name{got}")
            if control_free(gname) != gname:
                raise ctx.error(f"{where}.name", f"{short(gname)}: allowed: text without control "
                                "characters (an escape sequence, a line break)")  # fmt: skip
            if gname in names:
                raise ctx.error(f"{where}.name", f"group name {gname!r} is used twice")
            names.add(gname)
            overrides = {
                s: section_leaves(ctx, s, table[s], f"{where}.{s}.")
                for s in SECTION_NAMES
                if s in table
            }
            gplay = play
            if "hole" in table:
                gplay = _group_play(ctx, f"{where}.hole", table["hole"], hole, play)
            gtarget = target
            if "target" in table:
                gtarget = read_target(ctx, f"{where}.target", table["target"])
            group_list.append((gname, overrides, gtarget, gplay))

    sweep = sweep_leaves(ctx, data["sweep"]) if "sweep" in data else []
    combinations = math.prod(len(leaves) for _, _, _, leaves in sweep)
    if len(group_list) * combinations > MAX_POINTS:  # counted before a point is built
        each = f" ({len(group_list)} groups x {combinations:,} of the sweep)" if groups else ""
        raise ctx.error("sweep" if sweep else "group", f"{len(group_list) * combinations:,} "
                        f"points{each}: allowed are at most {MAX_POINTS:,}")  # fmt: skip
    combos = list(itertools.product(*(leaves for _, _, _, leaves in sweep))) if sweep else [()]
    _check_swept_over(ctx, sweep, [base, *(overrides for _, overrides, _, _ in group_list)])

    points = []
    single = len(group_list) * len(combos) == 1
    for gname, overrides, gtarget, gplay in group_list:
        for combo in combos:
            sections = {s: dict(base.get(s, {})) for s in SECTION_NAMES}
            for s, leaves in overrides.items():
                sections[s].update(leaves)
            values = {}
            for (section, pname, written, _), leaf in zip(sweep, combo, strict=True):
                sections[section][pname] = leaf
                values[written] = leaf.value
            sweep_label = ", ".join(f"{k}={as_written(v)}" for k, v in values.items())
            label = " | ".join(p for p in (gname, sweep_label) if p)
            context = "" if single else f" (point {label!r})"
            sections = {s: v for s, v in sections.items() if v}
            params = _resolve(ctx, sections, path.parent, context)
            points.append(Point(len(points), label, gname, values, params, gtarget, gplay))
    return Scenario(path, text, name, question, shots, seed, block_size, points, hole, play)


def _check_swept_over(ctx, sweep, tables):
    """Each value that a swept value takes the place of, in the base or a group (``tables``:
    their {section: {name: Leaf}}), read and checked as if it were used: ``temperature = "500
    K"`` under a sweep of the temperature validated."""
    for section, name, _, _ in sweep:
        param = PARAMETERS.get(section, {}).get(name)
        for table in tables:
            leaf = table.get(section, {}).get(name)
            if param is None or leaf is None:
                continue
            if param.kind == "choice":
                read_choice(ctx, leaf, param)
            else:
                read_dist(ctx, leaf, param, f"{section}.{name}")


def _group_play(ctx, where, given, hole, play):
    """A group's ``hole`` table: where its shots start and their aim (``hole_table.Play``)."""
    if hole is None:
        raise ctx.error(where, "a group's start and aim are on a hole: the scenario has no [hole]")
    given = as_table(ctx, where, given)
    for key in given:
        if key not in GROUP_KEYS:
            raise ctx.error(f"{where}.{key}", f"unknown key; allowed: {', '.join(GROUP_KEYS)}")
    return read_play(ctx, where, given, hole, play)
