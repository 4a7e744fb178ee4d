"""A value of a scenario file as written, read and checked: a number with its unit, a
distribution table, a choice; and the file's tables read into leaves (a value and where it was
written), sections, targets and sweeps."""

import math
import re
from dataclasses import dataclass

from mcrun.run.scenario.specs import (
    DIMENSIONLESS,
    DISTRIBUTIONS,
    PARAMETERS,
    SPREADS,
    Dist,
    ScenarioError,
    bare_unit,
    in_bare_unit,
    spread_in_bare_unit,
)
from mcrun.units import (
    KINDS,
    UNIT_SUFFIXES,
    UnitError,
    article,
    canonical_unit,
    column_suffix,
    foreign_digits,
    from_column_name,
    is_number,
    meant_quoted,
    parse_quantity,
    quoted_hint,
    shown,
)

# A truncnormal whose interval lies further than this many sd from its mean is refused: its
# probability mass underflows.
_TRUNCNORMAL_MAX_Z = 30.0

# Keys of a section that are not quantities.
_SPECIAL = {
    "launch": ("correlation", "file", "jitter", "club", "format", "sample"),
    "club": ("correlation",),
}
SECTION_NAMES = tuple(PARAMETERS)


def short(value):
    return shown(value, 60)


_LEADING_NUMBER = re.compile(r"^\s*[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")


@dataclass
class Context:
    """Where a value comes from, for messages: the file and a key path."""

    file: str

    def error(self, where, what):
        return ScenarioError(f"{self.file}: {where}: {what}")


@dataclass(frozen=True)
class Leaf:
    """A raw value of a parameter as written: the value, where it was written, and the unit
    its key carried (``spin_rpm`` -> "rpm"), or None."""

    value: object
    where: str
    key_unit: str | None = None


def read_value(ctx, where, value, kind, key_unit, spread=False):
    """One value of a quantity (a number or a string with an optional unit) in SI."""
    if kind == "number" or key_unit is not None and kind != "choice":
        if isinstance(value, str):
            foreign = foreign_digits(value)
            if foreign is not None:
                raise ctx.error(where, f"cannot read {short(value)}: {foreign}")
            try:
                value = float(value)
            except ValueError:
                if kind == "number":
                    raise ctx.error(
                        where, f"must be a number (dimensionless), got {short(value)}"
                    ) from None
                raise ctx.error(
                    where,
                    f"the key gives the unit ({key_unit}): give a bare number, got {short(value)}",
                ) from None
        if not is_number(value):
            raise ctx.error(where, f"must be a number, got {short(value)}")
        if not math.isfinite(value):
            raise ctx.error(where, f"must be finite, got {value}")
        if kind == "number":
            return float(value)
        value = f"{float(value)!r} {key_unit}"
    if not (isinstance(value, str) or is_number(value)):
        raise ctx.error(
            where,
            f"must be a number or a string with a unit ({', '.join(KINDS[kind][1])}), "
            f"got {short(value)}",
        )
    try:
        si = parse_quantity(value, kind)
        if spread:
            zero = _LEADING_NUMBER.sub("0", value, count=1) if isinstance(value, str) else 0.0
            si -= parse_quantity(zero, kind)
    except UnitError as err:
        raise ctx.error(where, str(err)) from None
    return si


def fmt(value_si, kind, spread=False):
    """An SI value in the kind's bare unit, e.g. "-5 rad/s", "12 deg"."""
    if kind == "number":
        return f"{value_si:g}"
    number = spread_in_bare_unit(value_si, kind) if spread else in_bare_unit(value_si, kind)
    return f"{number:g}{bare_unit(kind)}"


def as_given(raw, key_unit, value_si, kind, spread=False):
    """``value_si`` for a message: in the kind's bare unit, after the value as written where it
    was written in another unit (``-5 rpm (-0.523599 rad/s)``), so that a user finds it."""
    bare = fmt(value_si, kind, spread)
    if key_unit is not None:  # a bare number, in the key's unit (``spin_rpm = 2686``)
        written = f"{float(raw):g} {key_unit}"
    elif isinstance(raw, str) and _unit_written(raw):
        written = " ".join(raw.split())  # a number and its unit
    else:  # a number in the bare unit
        return bare
    return bare if written == bare else f"{written} ({bare})"


def _check_in(ctx, where, value_si, param, what="must be", shown=None, bare=False, table=""):
    """ScenarioError unless ``value_si`` is within ``param``'s limits; the message gives it as
    ``shown`` (default: in the bare unit). ``bare``: the value was a bare number (a humidity of
    50 then says how to write 50 %, a spin of 2686 how to write 2686 rpm); ``table``: the
    parameter's path where the value is one of a distribution's table (the advice is then for
    every value of it: a unit on each, or in the key)."""
    lo, hi = param.limits
    if not lo <= value_si <= hi:
        typed = f"{value_si:.15g}"
        if bare and param.kind == "fraction" and hi == 1.0 and 1.0 < value_si <= 100.0:
            quoted = ("%",)
            hint = f' (a share: for {typed} %, write "{typed} %")'
        else:
            quoted = meant_quoted(value_si, param.kind, lo, hi) if bare else ()
            hint = quoted_hint(typed, param.kind, quoted, lambda t, unit: f'"{t} {unit}"')
        if table and quoted:
            suffix = column_suffix(param.kind, quoted[0])
            key = f", or the key one: {table}_{suffix} = {{...}}" * bool(suffix)
            hint = (f" (a bare number is {_bare_word(param.kind)}: in {quoted[0]}, give every "
                    f'value of the table its unit ("{typed} {quoted[0]}"){key})')  # fmt: skip
        rounded = fmt(value_si, param.kind)
        got = shown or rounded
        if rounded in (fmt(lo, param.kind), fmt(hi, param.kind)):  # ("got 120 m/s", of 120.0000001)
            precise = f"{in_bare_unit(value_si, param.kind):.15g}{bare_unit(param.kind)}"
            got = got.replace(rounded, precise)
        raise ctx.error(
            where, f"{what} within [{fmt(lo, param.kind)}, {fmt(hi, param.kind)}], got {got}{hint}"
        )


def _unit_written(value):
    """The text after a value's leading number ("mph" of "167 mph"; "" of a bare number)."""
    return _LEADING_NUMBER.sub("", str(value), count=1).strip()


def _bare_word(kind):
    """What a bare number of ``kind`` is read as, for advice: "rad/s", "a share"."""
    return "a share" if kind == "fraction" else KINDS[kind][0]


def _mixed_units(ctx, where, values, kind, keys=None):
    """The first of ``values`` (each a raw value, or a ``keys`` entry's) written without a unit
    beside one written in a unit other than ``kind``'s bare one, and that one: (index, index),
    or None. A bare 0 is 0 in any unit of a kind without an offset (not a temperature), and
    a spread's (``keys`` in ``SPREADS``) in any."""
    keys = list(range(len(values))) if keys is None else keys
    offset = any(o for _, o in KINDS[kind][1].values())  # (0 C is no 0 F)

    bare, given = [], []
    for k, value in zip(keys, values, strict=True):
        if k in DIMENSIONLESS or isinstance(value, dict | list):
            continue
        if _is_bare(value, None):
            zero = read_value(ctx, where, value, "number", None) == 0.0
            if not zero or (offset and k not in SPREADS):
                bare.append(k)
        elif canonical_unit(kind, _unit_written(value)) != KINDS[kind][0]:
            given.append(k)
    return (bare[0], given[0]) if bare and given else None


def _is_bare(value, key_unit):
    """Whether a value was written as a bare number, in no unit (none in its key either)."""
    if key_unit is not None:
        return False
    return is_number(value) or (isinstance(value, str) and not _unit_written(value))


def _refuse_bare(ctx, where, value, leaf, param):
    """ScenarioError where ``param`` wants its unit given (``Quantity.bare_refused``) and
    ``value`` is a bare number under a key that names no unit (``stimp = 6``, meant in feet as
    Stimp readings are quoted, was 6 m: 19.7 ft)."""
    if param.bare_refused and _is_bare(value, leaf.key_unit):
        raise ctx.error(where, f"{short(value)}: {param.bare_refused}")


def _refuse_mixed_units(ctx, where, table, keys, leaf, param, path=None):
    """ScenarioError where some values of a distribution's table carry a unit other than the
    bare one and some carry none (``mean = "167 mph", sd = 1``: the sd was 1 m/s, 2.2 mph); a
    dimensionless key (``sigma``) aside, and ``mean = "10.9 deg", sd = 1`` (both degrees)."""
    if param.kind in ("number", "choice") or leaf.key_unit is not None:
        return
    mixed = _mixed_units(ctx, where, [table[k] for k in keys], param.kind, keys)
    if mixed is not None:
        bare, given = mixed
        unit = _unit_written(table[given])
        suffix = column_suffix(param.kind, unit)
        key = f", or the key one: {path}_{suffix} = {{...}}" * bool(suffix and path)
        raise ctx.error(
            where,
            f"{bare} without a unit beside {given} with one ({short(unit)}): give every value "
            f"its unit{key}; a bare number here is {_bare_word(param.kind)}",
        )


def read_dist(ctx, leaf, param, path=None):
    """A Dist from a raw value (constant or distribution table), validated against param;
    ``path`` (``"launch.spin"``) names the parameter in advice on a key's unit."""
    value, where = leaf.value, leaf.where
    kind = param.kind
    if not isinstance(value, dict):
        if isinstance(value, list):
            raise ctx.error(
                where,
                "must be a value or a distribution table {dist = ...}, got a list "
                "(sweep a parameter in [sweep])",
            )
        _refuse_bare(ctx, where, value, leaf, param)
        si = read_value(ctx, where, value, kind, leaf.key_unit)
        _check_in(ctx, where, si, param, shown=as_given(value, leaf.key_unit, si, kind),
                  bare=_is_bare(value, leaf.key_unit))  # fmt: skip
        return Dist(kind, "constant", (si,))
    if "dist" not in value:
        raise ctx.error(f"{where}.dist", f"missing; choose one of {', '.join(DISTRIBUTIONS)}")
    name = value["dist"]
    if not isinstance(name, str) or name not in DISTRIBUTIONS:  # (a list: unhashable)
        raise ctx.error(
            f"{where}.dist",
            f"unknown distribution {short(name)}; choose one of {', '.join(DISTRIBUTIONS)}",
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
        if key in DIMENSIONLESS:
            args.append(read_value(ctx, f"{where}.{key}", value[key], "number", None))
        else:
            _refuse_bare(ctx, f"{where}.{key}", value[key], leaf, param)
            args.append(
                read_value(ctx, f"{where}.{key}", value[key], kind, leaf.key_unit, key in SPREADS)
            )
    _refuse_mixed_units(ctx, where, value, keys, leaf, param, path)
    if param.constant_only and name != "constant":
        raise ctx.error(where, f"must be a constant, not a {name} distribution")

    def given(key, spread=False):  # the value of ``key`` as written, for a message
        return as_given(value[key], leaf.key_unit, args[keys.index(key)], kind, spread)

    def check_in(key):
        _check_in(ctx, f"{where}.{key}", args[keys.index(key)], param, shown=given(key),
                  bare=_is_bare(value[key], leaf.key_unit), table=path or "")  # fmt: skip

    if name == "constant":
        check_in("value")
    elif name in ("normal", "truncnormal"):
        mean, sd = args[:2]
        if sd < 0.0:
            raise ctx.error(f"{where}.sd", f"must be >= 0, got {given('sd', spread=True)}")
        if name == "normal":
            check_in("mean")
            lo, hi = param.limits
            if sd > hi - lo:  # (a humidity's sd of 5, meant as 5 %: most draws invalid_input)
                raise ctx.error(
                    f"{where}.sd",
                    f"{given('sd', spread=True)} is wider than the whole allowed range "
                    f"[{fmt(lo, kind)}, {fmt(hi, kind)}]: most draws would fall outside it",
                )
        else:
            low, high = args[2:]
            if sd == 0.0:
                raise ctx.error(f"{where}.sd", "must be > 0 for a truncnormal, got 0")
            if not low < high:
                raise ctx.error(
                    f"{where}.low", f"must be < high = {given('high')}, got {given('low')}"
                )
            check_in("low")
            check_in("high")
            if (low - mean) / sd > _TRUNCNORMAL_MAX_Z or (high - mean) / sd < -_TRUNCNORMAL_MAX_Z:
                raise ctx.error(
                    where,
                    f"[low, high] must come within {_TRUNCNORMAL_MAX_Z:g} sd of the mean",
                )
    elif name in ("uniform", "triangular"):
        low, high = args[0], args[-1]
        if not low < high:
            raise ctx.error(f"{where}.low", f"must be < high = {given('high')}, got {given('low')}")
        check_in("low")
        check_in("high")
        if name == "triangular" and not low <= args[1] <= high:
            raise ctx.error(
                f"{where}.mode",
                f"must be within [low, high] = [{given('low')}, {given('high')}], "
                f"got {given('mode')}",
            )
    else:  # lognormal
        median, sigma = args
        if kind == "temperature":  # (its log is of kelvin: sigma 0.05 of -5 C spread 13.5 C)
            raise ctx.error(where, "a temperature cannot be lognormal (it would spread in "
                            "kelvin whatever unit it is written in): use a normal or "
                            "truncnormal")  # fmt: skip
        if not median > 0.0:
            raise ctx.error(f"{where}.median", f"must be > 0, got {given('median')}")
        if sigma < 0.0:
            raise ctx.error(f"{where}.sigma", f"must be >= 0, got {sigma:g}")
        check_in("median")
    return Dist(kind, name, tuple(args))


def read_choice(ctx, leaf, param):
    if not isinstance(leaf.value, str) or leaf.value not in param.choices:
        raise ctx.error(
            leaf.where,
            f"must be one of {', '.join(param.choices)}, got {short(leaf.value)}",
        )
    return leaf.value


# --- reading the file into leaves ------------------------------------------------------------


def as_table(ctx, where, value):
    if not isinstance(value, dict):
        raise ctx.error(where, f"must be a table, got {short(value)}")
    return value


def key_name(ctx, section, key, where, only=None):
    """(parameter name, key unit) of a key of a section; units may be in the name. ``only``:
    the parameters allowed there (default every one of the section, and its special keys)."""
    names = PARAMETERS[section]
    special = _SPECIAL.get(section, ())
    if only is not None:
        names, special = {k: v for k, v in names.items() if k in only}, ()
    if key in names or key in special:
        return key, None
    found = from_column_name(key)
    if found is not None and found[0] in names:
        base, kind, unit = found
        if names[base].kind != kind:
            expected = names[base].kind
            allowed = (
                f"units of {article(expected)} {expected}: {', '.join(KINDS[expected][1])}"
                if expected in KINDS
                else "no unit (dimensionless)"
                if expected == "number"
                else "no unit"
            )
            raise ctx.error(
                where, f"{unit} is {article(kind)} {kind} unit, but {base} takes {allowed}"
            )
        return base, unit
    allowed = ", ".join((*names, *special))
    raise ctx.error(
        where,
        f"unknown key; allowed: {allowed} (a unit may end the name, e.g. ball_speed_mph; the "
        f"units: {', '.join(UNIT_SUFFIXES)})",
    )


def section_leaves(ctx, section, table, prefix):
    """{parameter: Leaf} of one section table; ``prefix`` is where it sits in the file."""
    table = as_table(ctx, prefix.rstrip("."), table)
    leaves = {}
    for key, value in table.items():
        where = f"{prefix}{key}"
        name, unit = key_name(ctx, section, key, where)
        if name in leaves:
            raise ctx.error(
                where, f"{section}.{name} is given twice ({leaves[name].where} and {where})"
            )
        leaves[name] = Leaf(value, where, unit)
    return leaves


# How far from the start a target may be, along or across the line (m): past any shot.
TARGET_LIMIT_M = 2000.0


def read_target(ctx, where, value):
    if not isinstance(value, list) or len(value) != 2:
        raise ctx.error(
            where, f'must be a pair [x, y] of lengths, e.g. ["251 m", "0 m"], got {short(value)}'
        )
    mixed = _mixed_units(ctx, where, value, "length")
    if mixed is not None:  # (as a vector's components: parse_vector)
        raise ctx.error(
            f"{where}[{mixed[0]}]",
            f"{short(value[mixed[0]])} without a unit beside {short(value[mixed[1]])}: give both "
            "their unit, or neither (m)",
        )
    target = tuple(read_value(ctx, f"{where}[{k}]", v, "length", None) for k, v in enumerate(value))
    for k, v in enumerate(target):
        if abs(v) > TARGET_LIMIT_M:
            raise ctx.error(
                f"{where}[{k}]",
                f"{v:g} m: allowed: -{TARGET_LIMIT_M:g} m to {TARGET_LIMIT_M:g} m from the tee",
            )
    return target


def _flatten_sweep(ctx, table, prefix=""):
    """{key path: list} of a [sweep] table; accepts "launch.spin" = [...] and nested tables."""
    out = {}
    for key, value in table.items():
        path = f"{prefix}{key}"
        leaves = _flatten_sweep(ctx, value, path + ".") if isinstance(value, dict) else {
            path: value}  # fmt: skip
        for leaf, values in leaves.items():
            if leaf in out:  # ("launch.spin" quoted and spin in [sweep.launch])
                raise ctx.error(f'sweep."{leaf}"', f"{leaf} is swept twice")
            out[leaf] = values
    return out


def sweep_leaves(ctx, table):
    """[(section, name, key path as written, [leaf per value])] of the [sweep] table."""
    entries = []
    seen = {}
    for path, values in _flatten_sweep(ctx, as_table(ctx, "sweep", table)).items():
        where = f'sweep."{path}"'
        section, _, key = path.partition(".")
        if section not in SECTION_NAMES or not key or "." in key:
            raise ctx.error(
                where,
                "a sweep key is a parameter path section.name with section one of "
                f'{", ".join(SECTION_NAMES)} (e.g. "launch.spin")',
            )
        name, unit = key_name(ctx, section, key, where)
        if (section, name) in seen:
            raise ctx.error(where, f"{section}.{name} is swept twice (also {seen[section, name]})")
        seen[section, name] = where
        if not isinstance(values, list) or not values:
            raise ctx.error(where, f"must be a non-empty list of values, got {short(values)}")
        twice = next((k for k, v in enumerate(values) if v in values[:k]), None)
        if twice is not None:
            raise ctx.error(f"{where}[{twice}]", f"{short(values[twice])} is swept twice: "
                            "give each value once")  # fmt: skip
        kind = PARAMETERS[section][name].kind
        mixed = (
            None if unit or kind in ("number", "choice") else _mixed_units(ctx, where, values, kind)
        )
        if mixed is not None:
            raise ctx.error(
                f"{where}[{mixed[0]}]",
                f"{short(values[mixed[0]])} without a unit beside {short(values[mixed[1]])}: give "
                f"every value its unit; a bare number here is {_bare_word(kind)}",
            )
        leaves = [Leaf(v, f"{where}[{k}]", unit) for k, v in enumerate(values)]
        entries.append((section, name, path, leaves))
    return entries


def as_written(value):
    """A sweep value as written, for labels (its spaces one each: a line break or a tab in
    "2686\rrpm", read as a space, was carried into the point's label and its output)."""
    if isinstance(value, str):
        return " ".join(value.split())
    if isinstance(value, dict):
        inner = ", ".join(f"{k}={as_written(v)}" for k, v in value.items() if k != "dist")
        return f"{value.get('dist', '')}({inner})"
    if isinstance(value, float):  # (six digits, else as many as tell it apart: 0.1000001)
        return f"{value:g}" if float(f"{value:g}") == value else repr(value)
    return str(value)
