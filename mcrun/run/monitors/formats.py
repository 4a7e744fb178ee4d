"""The exports of launch monitors mcrun reads: for each, the header names that identify it, the
column of each quantity and the unit a column has when neither a unit row nor its name says.

Names are compared normalised (``key``): lower case, spaces collapsed, the unit in brackets or
parentheses taken off (``Ball Speed (mph)`` and ``Ball Speed(mph)`` are ``ball speed``). Every
direction is positive to the right, as in mcrun (``L``/``R`` in a value give its sign); the
quantities are those of ``native.KIND``.
"""

import re
from dataclasses import dataclass, field

# A unit holds no bracket: a name of many brackets is matched in linear time, not quadratic.
_UNIT_IN_NAME = re.compile(r"^(?P<name>.*?)\s*[\(\[](?P<unit>[^\(\)\[\]]*)[\)\]]\s*$")


def split_name(column):
    """(normalised name, unit written in the name or "") of a header name: ``"Ball Speed
    (mph)"`` -> ``("ball speed", "mph")``, ``"Side Spin (rpm L-/R+)"`` -> ``("side spin",
    "rpm")``, ``"Launch V"`` -> ``("launch v", "")``."""
    text = " ".join(str(column).replace("\ufeff", "").split())
    match = _UNIT_IN_NAME.match(text)
    if match is None:
        return text.lower(), ""
    words = match["unit"].split()
    if words and words[0].lower() == "sim":  # TrackMan's simulated columns: a name, not a unit
        return text.lower(), ""
    return match["name"].lower(), words[0] if words else ""


@dataclass(frozen=True)
class Format:
    """One export: ``name`` (for ``--format``), ``title`` (for people), ``signature`` (the
    normalised header names that all appear in it and together in no other format known
    before it), ``columns`` (quantity -> its possible normalised names, first found wins),
    ``units`` (quantity kind or quantity -> unit when the file does not say), ``club`` (the
    names of its club column), ``sentinels`` (values that mean "not measured") and
    ``source`` (where its units were checked: the vendor's documentation, a real export, an
    open-source reader of it)."""

    name: str
    title: str
    signature: tuple
    columns: dict
    units: dict
    club: tuple = ()
    sentinels: tuple = field(default=())
    source: str = ""


IMPERIAL = {"speed": "mph", "angle": "deg", "spin": "rpm", "length": "yd"}
METRIC = {"speed": "m/s", "angle": "deg", "spin": "rpm", "length": "m"}

_TRACKMAN_COLUMNS = {
    "ball_speed": ("ball speed",),
    "launch_angle": ("launch angle",),
    "azimuth": ("launch direction",),
    "spin": ("spin rate",),
    "spin_axis": ("spin axis",),
    "carry": ("carry flat - length",),
    "total": ("total", "est. total flat - length"),
    "apex": ("max height - height",),
    "descent_angle": ("carry flat - land. angle",),
    "carry_side": ("carry flat - side",),
    "total_side": ("side total", "est. total flat - side"),
}
_TRACKMAN_SIGNATURE = ("ball speed", "launch angle", "spin rate", "carry flat - length")

# Most specific first: a format's signature may be part of a later one's header.
FORMATS = (
    Format(
        "trackman-normalized",
        "TrackMan (Normalized)",
        (*_TRACKMAN_SIGNATURE, "est. total flat - length"),
        _TRACKMAN_COLUMNS,
        {**IMPERIAL, "apex": "ft"},
        club=("club",),
        source=(
            "the unit row of every TrackMan Performance Studio / TPS export ([mph], [yds], [ft] for"
            " heights)"
        ),
    ),
    Format(
        "trackman",
        "TrackMan",
        _TRACKMAN_SIGNATURE,
        _TRACKMAN_COLUMNS,
        {**IMPERIAL, "apex": "ft"},
        club=("club",),
        source=(
            "the unit row of every TrackMan Performance Studio / TPS export ([mph], [yds], [ft] for"
            " heights)"
        ),
    ),
    Format(
        "garmin-r10",
        "Garmin Approach R10",
        ("club type", "ball speed", "backspin", "sidespin", "carry deviation distance"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("launch angle",),
            "azimuth": ("launch direction",),
            "spin": ("spin rate",),
            "spin_axis": ("spin axis",),
            "back_spin": ("backspin",),
            "side_spin": ("sidespin",),
            "carry": ("carry distance",),
            "total": ("total distance",),
            "apex": ("apex height",),
            "carry_side": ("carry deviation distance",),
            "total_side": ("total deviation distance",),
        },
        IMPERIAL,
        club=("club type", "club name"),
        source=(
            "the unit row of the Garmin Golf app export ([km/h] and [m], or [mph] and [yd], as the "
            "app is set)"
        ),
    ),
    Format(
        "rapsodo-mlm2pro",
        "Rapsodo MLM2PRO",
        ("club type", "carry distance", "ball speed", "apex", "side carry", "spin rate"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("launch angle",),
            "azimuth": ("launch direction",),
            "spin": ("spin rate",),
            "spin_axis": ("spin axis",),
            "carry": ("carry distance",),
            "total": ("total distance",),
            "apex": ("apex",),
            "descent_angle": ("descent angle",),
            "carry_side": ("side carry",),
        },
        {**IMPERIAL, "apex": "ft"},
        club=("club type",),
        source=(
            "Rapsodo MLM2PRO app export: no unit row; yards, mph, degrees, rpm, and Apex in feet (a"
            " real export: its apex read as yards was 3x the flight's)"
        ),
    ),
    Format(
        "skytrak",
        "SkyTrak",
        ("shot number", "ball speed", "push/pull", "back spin", "side spin", "carry"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("launch angle",),
            "azimuth": ("push/pull",),
            "spin": ("total spin",),
            "back_spin": ("back spin",),
            "side_spin": ("side spin",),
            "carry": ("carry",),
            "total": ("total distance",),
            "apex": ("peak height",),
            "descent_angle": ("descent angle",),
            "carry_side": ("offline",),
        },
        IMPERIAL,
        club=("club name", "club type"),
        source="the units in the SkyTrak shot-history names (mph, yds, rpm; Peak Height in yds)",
    ),
    Format(
        "flightscope-mevo",
        "FlightScope Mevo",
        ("ball speed", "smash", "carry distance", "launch angle v", "spin", "height"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("launch angle v",),
            "spin": ("spin",),
            "carry": ("carry distance",),
            "apex": ("height",),
        },
        {**IMPERIAL, "apex": "ft"},
        club=("club",),
        source="the units in the Mevo names (mph, yds, rpm, Height in ft)",
    ),
    Format(
        "flightscope-mevo-plus",
        "FlightScope Mevo+ / FS Golf",
        ("launch v", "launch h", "spin axis", "carry", "lateral"),
        {
            "ball_speed": ("ball speed", "ball"),
            "launch_angle": ("launch v",),
            "azimuth": ("launch h",),
            "spin": ("spin", "spin rate"),
            "spin_axis": ("spin axis",),
            "carry": ("carry",),
            "total": ("total",),
            "apex": ("height",),
            "descent_angle": ("descent v",),
            "carry_side": ("lateral",),
        },
        {**IMPERIAL, "apex": "ft"},
        club=("club",),
        source=(
            "FS Golf app default (imperial): mph, yds, rpm, Height in ft; a unit in a name governs"
        ),
    ),
    Format(
        "foresight-fsx",
        "Foresight FSX",
        ("shot id", "ball speed", "azimuth", "back spin", "side spin", "offline"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("launch angle",),
            "azimuth": ("azimuth",),
            "spin": ("total spin",),
            "back_spin": ("back spin",),
            "side_spin": ("side spin",),
            "carry": ("carry",),
            "total": ("total distance",),
            "apex": ("peak height",),
            "descent_angle": ("descent angle",),
            "carry_side": ("offline",),
        },
        METRIC,
        club=("club",),
        sentinels=(16777215.0,),
        source="the units in the FSX LastShot names (m/s, m, rpm)",
    ),
    Format(
        "square-golf",
        "Square Golf",
        ("club", "index", "ball speed", "launch direction", "offline", "clubspeed"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("launch angle",),
            "azimuth": ("launch direction",),
            "spin": ("spin rate",),
            "spin_axis": ("spin axis",),
            "back_spin": ("back spin",),
            "side_spin": ("side spin",),
            "carry": ("carry",),
            "total": ("total",),
            "apex": ("apex",),
            "descent_angle": ("landing angle",),
            "carry_side": ("offline",),
        },
        IMPERIAL,
        club=("club",),
        source=(
            "the units in the Square Golf names (Ball Speed(mph), Apex(yd), Carry(yd)); angles in "
            "degrees, spin in rpm"
        ),
    ),
    Format(
        "awesome-golf",
        "Awesome Golf",
        ("club type", "ball speed", "vertical launch", "horizontal launch", "spin reading"),
        {
            "ball_speed": ("ball speed",),
            "launch_angle": ("vertical launch",),
            "azimuth": ("horizontal launch",),
            "spin": ("spin rate",),
            "spin_axis": ("spin axis",),
            "carry": ("carry distance",),
            "total": ("total distance",),
            "apex": ("peak height",),
            "descent_angle": ("descent angle",),
            "carry_side": ("carry lateral distance",),
            "total_side": ("total lateral distance",),
        },
        {**IMPERIAL, "apex": "ft"},
        club=("club type",),
        source="the unit row of the Awesome Golf export ([mph], [yd], [ft] for Peak Height)",
    ),
    Format(
        "gspro",
        "GSPro Open Connect (JSON lines)",
        ("balldata.speed", "balldata.vla"),
        {
            "ball_speed": ("balldata.speed",),
            "launch_angle": ("balldata.vla",),
            "azimuth": ("balldata.hla",),
            "spin": ("balldata.totalspin",),
            "spin_axis": ("balldata.spinaxis",),
            "back_spin": ("balldata.backspin",),
            "side_spin": ("balldata.sidespin",),
            "carry": ("balldata.carrydistance",),
        },
        IMPERIAL,  # the distances: by each message's "Units"
        source=(
            "GSPro Open Connect API v1: Speed in mph, HLA/VLA/SpinAxis in degrees, spins in rpm, "
            "CarryDistance in the message's Units (as connectors send it, e.g. the MLM2PRO-GSPro-"
            "Connector's gspro_connect.py)"
        ),
    ),
)

BY_NAME = {f.name: f for f in FORMATS}
NATIVE = "mcrun"
"""The name of mcrun's own columns (``ball_speed_mph``...) among the formats."""

NAMES = (*BY_NAME, NATIVE)


def detect(names):
    """The first format whose signature is among the normalised header ``names``, or None."""
    present = set(names)
    for fmt in FORMATS:
        if all(name in present for name in fmt.signature):
            return fmt
    return None


def known():
    """The formats, for a message: ``trackman (TrackMan), ...``."""
    return ", ".join(f.name for f in FORMATS) + f", {NATIVE} (columns named with their unit)"
