"""A scenario's ``[hole]`` table: the hole it is played on, and the aim."""

import math
import numbers

from mcrun.hole.errors import HoleError
from mcrun.hole.hole import hole_from_table, read_hole_file
from mcrun.run.scenario.specs import ScenarioError
from mcrun.run.scenario.values import as_table


def read_hole(ctx, data, path):
    """The scenario's ``[hole]`` (``hole.hole_from_table``) and the azimuth of its ``aim``
    ([x, y] m in the hole's frame; default the pin). On a hole the turf is the zones': a
    ``[turf]`` table anywhere is refused."""
    table = dict(as_table(ctx, "hole", data["hole"]))
    aim = table.pop("aim", None)
    folder = path.parent.resolve()
    if "file" in table:
        # A hole file, its keys (paths relative to its folder) under those given here.
        hole_path = folder / str(table.pop("file"))
        try:
            given, _ = read_hole_file(hole_path)
        except HoleError as err:
            why = (
                str(err).removeprefix(f"{hole_path}: ").removeprefix("cannot read the hole file: ")
            )
            raise ctx.error("hole.file", f"cannot read {hole_path}: {why}") from None
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
