"""A scenario's ``[hole]`` table: the hole it is played on, where its shots start and where they
are aimed (``Play``), which a group may change in its own ``hole`` table."""

import math
import numbers
from dataclasses import dataclass

import numpy as np

from mcrun.hole.errors import HoleError
from mcrun.hole.hole import hole_from_table, read_hole_file
from mcrun.hole.zones import ZONE_KINDS, pin_off_green
from mcrun.putting.on_hole import check_putting
from mcrun.run.scenario.specs import ScenarioError
from mcrun.run.scenario.values import as_table, short


@dataclass(frozen=True)
class Play:
    """Where a point's shots are struck on the hole and where they are aimed: ``start_m`` and
    ``aim_m`` ((x, y) m in the hole's frame), and ``aim_rad``, the bearing of the aim from the
    start (rad, + to the right of +x): the shots' azimuths are about it."""

    start_m: tuple[float, float]
    aim_m: tuple[float, float]

    @property
    def aim_rad(self):
        return math.atan2(self.aim_m[1] - self.start_m[1], self.aim_m[0] - self.start_m[0])


# The keys a group may give in its own ``hole`` table: where its shots start and their aim.
GROUP_KEYS = ("start", "aim")


def read_hole(ctx, data, path):
    """The scenario's ``[hole]`` (``hole.hole_from_table``) and its ``Play``: its ``start``
    ([x, y] m in the hole's frame; default the tee, [0, 0]) and ``aim`` (default the pin). On
    a hole the turf is the zones': a ``[turf]`` table anywhere is refused."""
    table = dict(as_table(ctx, "hole", data["hole"]))
    given = {key: table.pop(key) for key in GROUP_KEYS if key in table}
    folder = path.parent.resolve()
    if "file" in table:
        # A hole file, its keys (paths relative to its folder) under those given here.
        given_path = table.pop("file")
        if not isinstance(given_path, str):  # (5 was read as a file named 5)
            raise ctx.error("hole.file", f"must be a hole TOML file's path, got "
                            f"{short(given_path)}")  # fmt: skip
        if "\0" in given_path:
            raise ctx.error("hole.file", f"{short(given_path)}: a path cannot hold a NUL "
                            "character")  # fmt: skip
        if given_path.lower().endswith((".geojson", ".json")):
            raise ctx.error("hole.file", f"{short(given_path)} is a course map: give it as "
                            "[hole] map = \"FILE\" with hole = N, or hole.file a hole TOML "
                            "file")  # fmt: skip
        hole_path = folder / given_path
        try:
            given_file, _ = read_hole_file(hole_path)
        except HoleError as err:
            why = (
                str(err).removeprefix(f"{hole_path}: ").removeprefix("cannot read the hole file: ")
            )
            raise ctx.error("hole.file", f"cannot read {hole_path}: {why}") from None
        table = {**given_file, **table}
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
    tee = Play((0.0, 0.0), tuple(float(v) for v in hole.pin_xy))
    return hole, read_play(ctx, "hole", given, hole, tee)


def read_play(ctx, where, given, hole, default):
    """The ``Play`` of ``given`` (a table's ``start`` and ``aim``, at ``where``) on ``hole``:
    what it leaves out is ``default``'s, except that a new start aims at the pin by default.
    A start must be in play on the hole's map; an aim ahead of it (further from the tee)."""
    start = default.start_m
    if hole.map_source is not None and where == "hole":  # (a plain rectangle's pin is not)
        code = int(hole.zone_at(*(np.array([v]) for v in hole.pin_xy))[0])
        if ZONE_KINDS[code] != "green":
            px, py = hole.pin_xy
            raise ctx.error("hole", pin_off_green(ZONE_KINDS[code], px, py, hole.cell_m))
    if "start" in given:
        start = _pair(ctx, f"{where}.start", given["start"], "a point of the hole's map")
    # The default too: a tee in a penalty area or out of bounds scored every shot from it.
    why = hole.why_not_playable(*start)
    if why is not None:
        told = "" if "start" in given else " (the default start: give one in play)"
        raise ctx.error(
            f"{where}.start",
            f"{list(start)} is {why}{told}: a shot starts in play on the hole's map",
        )
    aim = default.aim_m if start == default.start_m else tuple(float(v) for v in hole.pin_xy)
    if "aim" in given:
        aim = _pair(ctx, f"{where}.aim", given["aim"], "a point ahead of the start (x > start)")
    if not aim[0] > start[0]:
        if "aim" not in given:  # (the pin, its default: the start is at it or beyond it)
            raise ctx.error(
                f"{where}.start",
                f"{list(start)} is not short of the pin {list(aim)}: a shot starts short of the "
                "pin it is aimed at",
            )
        ahead = "the tee (x > 0)" if start == (0.0, 0.0) else f"the start (x > {start[0]:g})"
        raise ctx.error(f"{where}.aim", f"must be [x_m, y_m] ahead of {ahead}, got {list(aim)!r}")
    return Play(start, aim)


def _pair(ctx, where, value, what):
    """[x_m, y_m] of finite numbers, as a tuple of floats."""
    if (
        not isinstance(value, list | tuple)
        or len(value) != 2
        or not all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in value)
        or not math.isfinite(value[0] + value[1])
    ):
        raise ctx.error(where, f"must be [x_m, y_m], {what}, got {value!r}")
    return (float(value[0]), float(value[1]))


_HOLES = {}


def _cached_hole(key, table, folder, source):
    """``hole.hole_from_table``, once per table and folder in a process (a Dask worker reads
    the scenario for every chunk)."""
    key = (key, str(folder))
    if key not in _HOLES:
        try:
            _HOLES[key] = check_putting(hole_from_table(table, folder, source))
        except HoleError as err:
            raise ScenarioError(str(err)) from None
    return _HOLES[key]
