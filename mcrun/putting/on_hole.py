"""The expected-putts map of a hole's green, as the hole's scores ask for it: built once per
green, pin, putter and settings, kept in memory and in a cache folder.

``map_of_hole(hole)`` is None where the hole values a ball on its green by the baseline's table
(``[hole] putting = "table"``, the default), else the ``GreenMap`` of its green
(``putting = "physics"``). The cache folder is ``$MCRUN_CACHE_DIR/greens`` (default
``~/.cache/mcrun/greens``); a map is stored under a hash of everything it depends on (the
green's heights and nodes, the pin, the speed and drift, the putter's parameters, the read, n,
seed, resolution and the map's code version ``MAP_VERSION``), so that an edit of any of them
builds a new map: a putter of the same name with other errors builds one too, and putters of
other names with the same parameters share one. A folder that cannot be written is skipped:
the map is then built in each process. A file there that cannot be read as a map (truncated,
emptied, damaged) is built again and replaced, with a warning on stderr.
"""

import contextlib
import dataclasses
import hashlib
import os
import sys
import weakref
import zipfile
from pathlib import Path

import numpy as np

from mcrun.putting.green import green_of_hole
from mcrun.putting.green_map import POLAR_ANGLES, POLAR_RADII_M, GreenMap, expected_putts_map
from mcrun.putting.putter import PUTTERS
from mcrun.putting.warmup import compile_announced

__all__ = ["MAP_VERSION", "cache_folder", "check_putting", "map_of_hole", "putting_of"]

# Raise when the map's numbers change for the same inputs. 2: the packaged baseline became the
# full Table 9 (a putt that leaves the green is a chip valued by its fairway rows). 3: the read's
# error, the green's drift, the pace at the hole, sweeps until settled.
MAP_VERSION = 3
_MEMORY = {}
_OF_HOLE = {}  # (id(hole), putter) -> (a weak reference to it, its settings, its map's key)
_ARRAYS = ("expected_putts", "expected_putts_se", "p_one_putt", "p_three_putt", "read_aim_deg",
           "read_pace_m", "polar_expected", "polar_p_one", "polar_p_three")  # fmt: skip


def putting_of(hole, putter=None):
    """The putting settings of ``hole`` putted by ``putter`` (a name of ``PUTTERS``; None: the
    hole's own): the hole's, with that putter; where the hole values its green by the table (the
    Tour's putts) and the putter is not the Tour's, its green's map (``model = "physics"``)."""
    spec = dict(hole.putting)
    if putter is not None and putter != spec["putter"]:
        spec["putter"] = putter
        if spec["model"] == "table" and putter != "tour":
            spec["model"] = "physics"
    return spec


def check_putting(hole, green=True, putter=None):
    """``hole``, whose ``[hole.putting] putter`` (or ``putter``) is one of ``PUTTERS`` and,
    where its green is valued by its map (``putting_of``) and ``green``, whose green can be
    putted on (``putting.green.green_of_hole``: its speed a green's, somewhere a ball can rest);
    GreenError (a HoleError: one line) otherwise."""
    from mcrun.putting.green import GreenError

    spec = putting_of(hole, putter)
    name = spec["putter"]
    if name not in PUTTERS:
        raise GreenError(f"{hole.source}: 'putting.putter' = {name!r}: choose {', '.join(PUTTERS)}")
    if green and spec["model"] == "physics":
        _green(hole, spec)
    return hole


def _green(hole, spec):
    return green_of_hole(hole, spec["cell_m"], spec["elevation"], spec["elevation_crs"],
                         drift_mm_per_m=spec["drift_mm_per_m"])  # fmt: skip


def cache_folder():
    root = os.environ.get("MCRUN_CACHE_DIR")
    base = Path(root) if root else Path.home() / ".cache" / "mcrun"
    return base / "greens"


def _key(green, spec):
    h = hashlib.sha256()
    h.update(green.key())
    putter = dataclasses.astuple(PUTTERS[spec["putter"]])[1:]  # its parameters, not its name
    h.update(repr((MAP_VERSION, putter, spec["read"], spec["n"], spec["seed"],
                   spec["resolution_m"])).encode())  # fmt: skip
    return h.hexdigest()[:32]


def map_of_hole(hole, progress=None, putter=None):
    """The GreenMap of ``hole``'s green under its ``putting`` settings putted by ``putter``
    (``putting_of``); None under the table."""
    spec = putting_of(hole, putter)
    if spec["model"] != "physics":
        return None
    # The hole asked before (every chunk of a run asks): its map, without building its green.
    known = _OF_HOLE.get((id(hole), spec["putter"]))
    if known is not None and known[0]() is hole and known[1] == spec and known[2] in _MEMORY:
        return _MEMORY[known[2]]
    green = _green(hole, spec)
    key = _key(green, spec)
    _OF_HOLE[(id(hole), spec["putter"])] = (weakref.ref(hole), dict(spec), key)
    if key in _MEMORY:
        return _MEMORY[key]
    path = cache_folder() / f"{key}.npz"
    found = _cached_map(path, green, spec)
    if found is None:
        compile_announced(("map",), lambda line: print(line, file=sys.stderr, flush=True))
        if progress is None:
            print(f"mcrun: computing the expected-putts map of {green.source}'s green "
                  f"({green.area_m2():.0f} m^2 at {spec['resolution_m']:g} m, "
                  f"{spec['n']} putts a read, {spec['read']} read) ...", file=sys.stderr,
                  flush=True)  # fmt: skip
        found = expected_putts_map(green, spec["putter"], spec["n"], spec["seed"],
                                   spec["resolution_m"], progress=progress,
                                   read=spec["read"])  # fmt: skip
        tmp = path.with_suffix(f".{os.getpid()}.tmp.npz")
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            np.savez(tmp, x0_m=found.x0_m, y0_m=found.y0_m, sweep_change=found.sweep_change,
                     elapsed_s=found.elapsed_s, sweeps=found.sweeps,
                     **{name: getattr(found, name) for name in _ARRAYS})  # fmt: skip
            os.replace(tmp, path)
        except OSError as err:  # (a full disk left the part written, and every run built it)
            with contextlib.suppress(OSError):
                tmp.unlink()
            if not isinstance(err, PermissionError | NotADirectoryError | FileNotFoundError):
                why = " ".join(str(err.strerror or err).split())
                print(f"mcrun: warning: the expected-putts map cannot be cached in "
                      f"{path.parent} ({why}): it is built again by each run",
                      file=sys.stderr, flush=True)  # fmt: skip
    _MEMORY[key] = found
    return found


def _cached_map(path, green, spec):
    """The GreenMap stored at ``path``; None where there is none, and where the file cannot be
    read as one (truncated, emptied, damaged: zip's checksums catch a changed byte), which is
    said on stderr: the map is then built again and the file replaced."""
    try:
        with np.load(path) as data:
            arrays = {name: np.asarray(data[name], dtype=float) for name in _ARRAYS}
            scalars = {name: float(data[name])
                       for name in ("x0_m", "y0_m", "sweep_change", "elapsed_s",
                                    "sweeps")}  # fmt: skip
    except (FileNotFoundError, NotADirectoryError, PermissionError):
        return None  # none, or a folder that cannot be read: skipped as one not written
    except (OSError, EOFError, KeyError, ValueError, TypeError, NotImplementedError,
            zipfile.BadZipFile) as err:  # fmt: skip
        _damaged(path, err)
        return None
    polar = (len(POLAR_RADII_M), POLAR_ANGLES)
    grids = {arrays[name].shape for name in _ARRAYS if not name.startswith("polar_")}
    polars = {arrays[name].shape for name in _ARRAYS if name.startswith("polar_")}
    if len(grids) != 1 or len(next(iter(grids))) != 2 or polars != {polar}:
        _damaged(path, "its arrays' shapes disagree")
        return None
    return GreenMap(
        green=green, x0_m=scalars["x0_m"], y0_m=scalars["y0_m"],
        resolution_m=float(spec["resolution_m"]), **arrays, putter=PUTTERS[spec["putter"]],
        n=spec["n"], seed=spec["seed"], sweep_change=scalars["sweep_change"],
        elapsed_s=scalars["elapsed_s"], sweeps=int(scalars["sweeps"]),
    )  # fmt: skip


def _damaged(path, why):
    why = " ".join(str(why).split()) or type(why).__name__
    print(f"mcrun: warning: the expected-putts map cached in {path} cannot be read ({why}): "
          "building it again", file=sys.stderr, flush=True)  # fmt: skip
