"""The player: a bag of clubs (each a launch distribution, as a scenario's group), the
wedge's part-power shots, how a lie changes a launch, and a putter.

A player file is a scenario file without a ``[hole]``: its ``[[group]]``s are the clubs, each
with its launch (presets, correlated normals, or fitted from a launch-monitor session:
``[launch] file`` with a club filter), its weather and models; ``pga-tour-bag`` (the library's)
is the Tour player. The shortest club of the bag (its last group: the wedge) is also hit at
part power (``PART_POWERS``), an ESTIMATE of a pitch's launch: ball speed times the power p,
spin times sqrt(p), launch angle raised by (1 - p) ``PITCH_LOFT_DEG`` (a pitch is played with
the face open: a Tour 50-yd pitch launches near 30 deg with 6,000-7,000 rpm, against the
full wedge's 24 deg and 9,300 rpm).

How a lie changes a launch (``LIE_LAUNCH``, ESTIMATES a user can override; ``lie_launch``):
from the rough a "flyer" (grass between the face and the ball: less spin, a little less speed)
and a wider pattern (the ball speed's, azimuth's and spin axis's deviations from their means
times a factor); from a bunker less speed and spin (sand taken with the ball) and a wider
pattern; a recovery shot (under trees) is a punch, at much less speed. Fairway and tee shots
are the launch as sampled. The rough's factor is calibrated for the Tour bag's clubs
(``TOUR_ROUGH``: the Tour's proximity from the rough over that from the fairway) and for the
wedge's pitches of under ``calibration.SHORT_GAME_YD`` (``PITCH_ROUGH``: the Table 9 cost of
the rough around the green); a bag of its own takes ``LIE_LAUNCH``'s for its full clubs.

The driver (a club named "Driver") is struck from the tee only (``tee_only``): its launch is a
teed ball's, and off the ground the Tour plays a fairway wood.
"""

import dataclasses
import math
import unicodedata
from dataclasses import dataclass

import numpy as np

from mcrun.engine.schema import COLUMN
from mcrun.putting.putter import PUTTERS
from mcrun.quantities import InputError
from mcrun.run import sampling
from mcrun.run import scenario as sc
from mcrun.run.scenario.hole_table import Play
from mcrun.strokes.baseline import LIES
from mcrun.units import is_number, path_of, shown

__all__ = [
    "LIE_LAUNCH",
    "PART_POWERS",
    "PITCH_LOFT_DEG",
    "BOGEY_SPREAD",
    "PITCH_ROUGH",
    "SCRATCH_SPREAD",
    "TOUR_GROUND",
    "TOUR_ROUGH",
    "TOUR_SPREAD",
    "Player",
    "PlayerError",
    "SPREAD_COLUMNS",
    "check_dispersion",
    "club_shots",
    "lie_launch",
    "load_player",
    "on_hole",
    "spread_inputs",
    "tee_only",
]

# The launch values a club's spread scales about their means.
SPREAD_COLUMNS = ("ball_speed_mps", "launch_angle_rad", "spin_radps", "spin_axis_rad",
                  "azimuth_rad")  # fmt: skip
# (ball speed factor, spin factor, spread factor) by the lie the ball is struck from.
# ESTIMATES: a flyer from the rough carries 20-50 % less spin (the grass between face and
# ball) and scatters more; a fairway bunker shot loses about a tenth of its speed; a recovery
# is a punch back into play.
LIE_LAUNCH = {
    "tee": (1.0, 1.0, 1.0),
    "fairway": (1.0, 1.0, 1.0),
    "rough": (0.97, 0.65, 1.6),
    "sand": (0.90, 0.80, 1.6),
    "recovery": (0.60, 0.80, 2.0),
}
# The wedge at part power p: ball speed times p, spin times sqrt(p), launch angle plus
# (1 - p) PITCH_LOFT_DEG.
PART_POWERS = tuple(round(1.0 - 0.05 * k, 2) for k in range(1, 17))  # 0.95 .. 0.2
PITCH_LOFT_DEG = 16.0
# CALIBRATED (``mcrun.play.calibration.calibrate``, 4,000 shots a club; tests/test_play.py):
# the Tour bag's spread per club, Driver .. PW, to the Tour's approach proximity (to over 200 yd)
# and fairways.
TOUR_BAG = "pga-tour-bag"
TOUR_SPREAD = (1.654, 1.877, 1.929, 1.719, 2.004, 1.939, 1.798, 1.699, 1.624, 1.678, 2.101, 2.29)
# CALIBRATED (``mcrun.play.calibration``, 4,000 shots; tests/test_play.py), Driver .. PW: the
# factor on the Tour bag's spread off the ground (``calibrate_ground``: the woods calibrated off
# the tee, to Table 9 on the plane); the rough's pattern factor per club (``calibrate_rough``:
# the Tour's proximity from the rough over that from the fairway; the driver, struck from the
# tee only, keeps LIE_LAUNCH's), and per part power of the wedge, ``PART_POWERS``' order (under
# ``SHORT_GAME_YD``: Table 9's cost of the rough; the others as the full clubs).
TOUR_GROUND = (1.0, 1.441, 1.042) + (1.0,) * 9
TOUR_ROUGH = (1.6, 1.643, 2.057, 2.165, 2.086, 1.986, 2.005, 1.924, 1.785, 1.588, 1.421, 1.402)
PITCH_ROUGH = (1.433, 1.437, 1.451, 1.477, 1.514, 1.567, 1.636, 1.719, 1.814, 1.914, 2.33, 2.29,
               2.172, 2.061, 1.915, 1.962)  # fmt: skip
# The presets: (the bag, its ball speed factor, its spread per club, its putter). Scratch and
# bogey are the USGA Course Rating's model players (a scratch player drives 250 yd and reaches
# 470 yd in two; a bogey player drives 200 yd and reaches 370 yd in two): the Tour bag's ball
# speeds times 0.8875 and 0.7698 (the driver's mean total on the level, at their spreads, 248
# and 200 yd, their 3-woods 224 and 174 yd). Their spreads CALIBRATED as the Tour's
# (``calibration.calibrate`` with ``calibration.AMATEUR_TARGETS``, four steps, 4,000 shots a
# club; tests/test_play.py): approach proximity 1.28 and 3.09 times the Tour's (fitted to the
# amateurs' scores), fairways 50 % and 43 % (the amateurs reference). Their putters:
# ``putting.PUTTERS``'s scratch and 15-handicap (the nearest preset to a bogey player's,
# ESTIMATES). Off the ground and from the rough they take the Tour bag's factors (ESTIMATES for
# them).
SCRATCH_SPREAD = (2.555, 3.08, 2.993, 2.238, 2.512, 2.412, 2.199, 2.021, 2.024, 2.174, 2.655, 2.906)
BOGEY_SPREAD = (4.095, 5.38, 5.249, 4.609, 4.679, 4.765, 4.867, 4.939, 4.964, 5.138, 5.758, 6.154)
# The women's model players (a scratch woman drives 210 yd and reaches 400 yd in two; a bogey
# woman, Handicap Index about 24, 150 and 280): the Tour bag's ball speeds times 0.7765 and
# 0.628 (drives of 211 and 151 yd on the level at their spreads, 3-woods of 190 and 129). No
# shot pattern of women amateurs is in our references: each plays as the man of her model
# (scratch, bogey) would at her distances, an ESTIMATE: her approach clubs CALIBRATED as his
# (``calibration.calibrate`` with his ``AMATEUR_TARGETS`` at her ball speed: the same ratio
# to the Tour's proximity at the distance she hits them), her woods at his spreads (the same
# angular dispersion: she hits more fairways than he does, her drives being shorter); his
# putter.
WOMEN = {"scratch-woman": "scratch", "bogey-woman": "bogey"}  # each woman's man, as above
SCRATCH_WOMAN_SPREAD = (2.555, 3.08, 2.993, 2.065, 2.269, 2.149, 2.04, 2.057, 2.086, 2.2, 2.63,
                        2.919)  # fmt: skip
BOGEY_WOMAN_SPREAD = (4.095, 5.38, 5.249, 4.465, 4.433, 4.551, 4.704, 4.842, 4.895, 5.053, 5.567,
                      6.069)  # fmt: skip
PLAYERS = {
    "tour": (TOUR_BAG, 1.0, TOUR_SPREAD, "tour"),
    "scratch": (TOUR_BAG, 0.8875, SCRATCH_SPREAD, "scratch"),
    "bogey": (TOUR_BAG, 0.7698, BOGEY_SPREAD, "15-handicap"),
    "scratch-woman": (TOUR_BAG, 0.7765, SCRATCH_WOMAN_SPREAD, "scratch"),
    "bogey-woman": (TOUR_BAG, 0.628, BOGEY_WOMAN_SPREAD, "15-handicap"),
}
# The clubs struck from the tee only, by name (case aside).
TEE_ONLY = ("driver",)


# A club's dispersion: its first DISPERSION_SHOTS shots must differ in some launch value; the
# keys that give those values, by how the club's launch is given (``Point.mode``).
DISPERSION_SHOTS = 64
UNFLOWN_SHARE = 0.1  # of a club's first shots that cannot be flown: more, and it is refused
# The least spread: a tenth of the file's dispersion (1e-9 was a player without dispersion in
# all but name, 75 % birdies, which a bag without dispersion is refused for).
MIN_SPREAD = 0.1
DISPERSION_KEYS = {
    "ball": "launch.ball_speed, launch.launch_angle, launch.spin, launch.spin_axis and "
    "launch.azimuth are all constant",
    "club": "club.speed, club.loft, club.spin_axis and club.azimuth are all constant",
    "file": "every shot of its launch.file is the same",
}


class PlayerError(InputError):
    """A player that cannot be used; one line."""


@dataclass(frozen=True)
class Player:
    """A bag: ``scenario`` (a plane scenario whose points are the clubs), the clubs' names,
    each club's ``spread`` (the factor on its launch's deviations from their means:
    ``mcrun.play.calibration``), the putter (a name of ``mcrun.putting.PUTTERS``) and where it
    was read."""

    name: str
    scenario: object
    clubs: tuple
    spread: tuple
    putter: str
    source: str
    speed: tuple = ()  # each club's ball speed times this (empty: 1)
    rough: tuple = ()  # each club's pattern factor from the rough (empty: LIE_LAUNCH's)
    ground: tuple = ()  # each club's spread off the ground over its spread (empty: 1)

    def __post_init__(self):
        """PlayerError for a bag that cannot be played (one built by hand, or replaced: a NaN
        factor or a tuple of another length was an IndexError deep in the solve)."""
        where = f"player {self.name!r} ({self.source})"
        if not (isinstance(self.clubs, tuple) and self.clubs
                and all(isinstance(c, str) for c in self.clubs)):  # fmt: skip
            raise PlayerError(f"{where}: clubs {shown(self.clubs)}: allowed: a tuple of names")
        n = len(self.clubs)
        for field, least, most, empty in (("spread", MIN_SPREAD, 10.0, False),
                                          ("speed", 0.1, 10.0, True),
                                          ("rough", 0.1, 10.0, True),
                                          ("ground", 0.1, 10.0, True)):  # fmt: skip
            value = getattr(self, field)
            if not (isinstance(value, tuple) and (len(value) == n or (empty and not value))
                    and all(is_number(v) and least <= v <= most for v in value)):  # fmt: skip
                allowed = f"{n} factors in [{least:g}, {most:g}], one per club"
                raise PlayerError(f"{where}: {field} {shown(value)}: allowed: "
                                  f"{allowed}{' (or none)' if empty else ''}")  # fmt: skip
        if not isinstance(self.putter, str) or self.putter not in PUTTERS:
            raise PlayerError(f"{where}: putter {shown(self.putter)}: allowed: "
                              f"{', '.join(PUTTERS)}")  # fmt: skip

    def speed_of(self, club):
        """The ball speed factor of ``club`` (an index)."""
        return self.speed[club] if self.speed else 1.0

    def ground_of(self, club):
        """The factor on ``club``'s spread (an index) struck from any lie but the tee."""
        return self.ground[club] if self.ground else 1.0

    def rough_of(self, club, power=1.0):
        """The rough's pattern factor of ``club`` (an index) at ``power``: the wedge's part
        powers ``PITCH_ROUGH``'s, a full club its own (``rough``) or ``LIE_LAUNCH``'s."""
        if power != 1.0:
            return PITCH_ROUGH[PART_POWERS.index(power)]
        return self.rough[club] if self.rough else LIE_LAUNCH["rough"][2]


def spread_inputs(inputs, factor):
    """``inputs`` with each ``SPREAD_COLUMNS`` deviation from its mean times ``factor``."""
    out = np.asfortranarray(inputs.copy())
    for name in SPREAD_COLUMNS:
        j = COLUMN[name]
        centre = out[:, j].mean()
        out[:, j] = centre + (out[:, j] - centre) * factor
    return out


def club_shots(scenario, club, n, power, spread, speed=1.0):
    """The kernel inputs of the first n shots of ``club`` (an index of the player's
    ``scenario``) at its ``spread`` (``spread_inputs``), ball speed times ``speed``, at
    ``power`` (``PART_POWERS``: ball speed times it, spin times its root, launch angle raised
    by (1 - power) ``PITCH_LOFT_DEG``)."""
    inputs, _ = sampling.sample(scenario, scenario.points[club], 0, n)
    inputs = spread_inputs(inputs, spread)
    inputs[:, COLUMN["ball_speed_mps"]] *= speed
    inputs[:, COLUMN["ball_speed_mps"]] *= power
    inputs[:, COLUMN["spin_radps"]] *= math.sqrt(power)
    inputs[:, COLUMN["launch_angle_rad"]] += (1.0 - power) * math.radians(PITCH_LOFT_DEG)
    return inputs


def tee_only(club_name):
    """Whether the club named ``club_name`` is struck from the tee only (``TEE_ONLY``)."""
    return club_name.strip().lower() in TEE_ONLY


def lie_launch(batch, rows_lie, n, rough=None):
    """``batch`` (starts x n shots, start-major) struck from lies ``rows_lie`` (codes of
    ``LIES``), in place: speed and spin scaled, the spread of speed, azimuth and spin axis about
    their means widened (``LIE_LAUNCH``; from the rough by ``rough`` where given)."""
    factors = np.array([LIE_LAUNCH.get(LIES[k], (1.0, 1.0, 1.0)) for k in rows_lie])
    if rough is not None:
        factors[np.asarray(rows_lie) == LIES.index("rough"), 2] = rough
    m = len(rows_lie)
    for name, f in (("ball_speed_mps", factors[:, 0]), ("spin_radps", factors[:, 1])):
        batch[:, COLUMN[name]].reshape(m, n)[:] *= f[:, None]
    for name in ("ball_speed_mps", "azimuth_rad", "spin_axis_rad"):
        view = batch[:, COLUMN[name]].reshape(m, n)
        centre = view.mean(axis=1, keepdims=True)
        view[:] = centre + (view - centre) * factors[:, 2, None]


def load_player(spec, putter=None, spread=None, straight=False):
    """The Player of a preset (``PLAYERS``: tour, scratch, bogey, scratch-woman,
    bogey-woman), a player file or a library
    scenario's name (``pga-tour-bag``: the Tour player, its spreads ``TOUR_SPREAD``);
    ``putter``: a name of ``putting.PUTTERS`` (default the preset's, else the Tour's);
    ``spread``: one factor for every club, or a tuple (default 1, the file's own dispersion).
    A club whose every shot is the same (no dispersion: ``check_dispersion``) is refused
    (PlayerError), unless ``straight`` (a bag of straight shots, for tests from first
    principles: a model player has a dispersion)."""
    what = f"a preset ({', '.join(PLAYERS)}), a player file or a library scenario's name"
    path_of(spec, "player", what, PlayerError)
    if str(spec) in PLAYERS:
        name = str(spec)
        bag, speed, preset, own_putter = PLAYERS[name]
        putter = own_putter if putter is None else putter
        player = load_player(bag, putter, preset if spread is None else spread, straight)
        return Player(name, player.scenario, player.clubs, player.spread, putter,
                      player.source, (speed,) * len(player.clubs), player.rough,
                      player.ground)  # fmt: skip
    if not isinstance(straight, bool | np.bool_):  # ("no" was true)
        raise PlayerError(f"straight {shown(straight)}: allowed: True or False")
    putter = "tour" if putter is None else putter
    if not isinstance(putter, str) or putter not in PUTTERS:  # (a list: a TypeError)
        raise PlayerError(f"putter {putter!r}: allowed: {', '.join(PUTTERS)}")
    try:
        sc.find(spec)
    except sc.ScenarioError as err:  # (a preset's name mistyped was told of scenarios alone)
        raise PlayerError(f"{err}; a player is {what}") from None
    scenario = sc.load(spec)
    if scenario.hole is not None:
        raise PlayerError(
            f"{scenario.path}: a player is a bag of clubs ([[group]]s) without a [hole]: the "
            "hole is given apart (mcrun play PLAYER HOLE)"
        )
    swept = next((p.sweep for p in scenario.points if p.sweep), None)
    if swept:
        raise PlayerError(
            f"{scenario.path}: a [sweep] ({', '.join(swept)}): a player is a bag of clubs "
            "([[group]]s), each played as it is; allowed: no [sweep] (sweep a study with mcrun "
            "run)"
        )
    clubs = tuple(p.label or p.group or f"club {p.index}" for p in scenario.points)
    # (Control characters in a club's name are refused where the file is read, as a group's.)
    # Names that print the same (one composed and one decomposed, a trailing space) are one.
    seen = {}
    for club in clubs:
        key = " ".join(unicodedata.normalize("NFC", club).split())
        if key in seen:
            raise PlayerError(f"{scenario.path}: clubs {seen[key]!r} and {club!r} print the "
                              "same: each club (group) needs a name of its own")  # fmt: skip
        seen[key] = club
    given = spread
    if spread is None:
        spread = TOUR_SPREAD if scenario.name == TOUR_BAG else (1.0,) * len(clubs)
    elif is_number(spread):
        spread = (float(spread),) * len(clubs)
    elif isinstance(spread, list | tuple | np.ndarray) and all(is_number(v) for v in spread):
        spread = tuple(float(v) for v in spread)
    else:
        spread = ()  # (refused below, named as given)
    if len(spread) != len(clubs) or not all(MIN_SPREAD <= v <= 10.0 for v in spread):
        raise PlayerError(f"{scenario.path}: spread {shown(given)}: allowed: one factor in "
                          f"[{MIN_SPREAD:g}, 10] or one per club ({len(clubs)})")  # fmt: skip
    if not straight:
        check_dispersion(scenario, clubs, spread)
    tour = scenario.name == TOUR_BAG
    return Player(scenario.name, scenario, clubs, spread, putter, str(scenario.path),
                  rough=TOUR_ROUGH if tour else (), ground=TOUR_GROUND if tour else ())  # fmt: skip


def check_dispersion(scenario, clubs, spread=None):
    """PlayerError (one line naming the file, the club and its launch's keys) for a club of
    the player's ``scenario`` whose first ``DISPERSION_SHOTS`` shots are all the same in every
    launch value its spread scales (``SPREAD_COLUMNS``: ball speed, launch angle, spin, spin
    axis, azimuth): a bag without dispersion hits every shot exactly where it is aimed, and its
    solution (holes in one from wherever a pin is in reach) is no player's. And for a club
    more than ``UNFLOWN_SHARE`` of whose first shots cannot be flown (a ball speed not above 0
    or a backspin below 0: a spread too wide for its mean), whose values would be infinite.
    ``spread``: each club's factor on its dispersion (``spread_inputs``), as it is played (a
    factor of 10 left a tenth of some clubs' shots unflown, which the solve dropped)."""
    columns = [COLUMN[name] for name in SPREAD_COLUMNS]
    speed, spin = COLUMN["ball_speed_mps"], COLUMN["spin_radps"]
    spread = (1.0,) * len(clubs) if spread is None else spread
    for point, club, factor in zip(scenario.points, clubs, spread, strict=True):
        inputs, _ = sampling.sample(scenario, point, 0, DISPERSION_SHOTS)
        inputs = spread_inputs(inputs, factor)
        unflown = int(np.count_nonzero(~((inputs[:, speed] > 0.0) & (inputs[:, spin] >= 0.0))))
        if unflown > UNFLOWN_SHARE * DISPERSION_SHOTS:
            at = "" if factor == 1.0 else f" at a spread of {factor:g}"
            raise PlayerError(
                f"{scenario.path}: club {club!r}: {unflown} of its first {DISPERSION_SHOTS} "
                f"shots{at} cannot be flown (a ball speed not above 0 or a spin below 0): "
                "allowed is a launch whose spread leaves its shots flying (a smaller sd)"
            )
        values = inputs[:, columns]
        if np.all(values == values[0]):
            raise PlayerError(
                f"{scenario.path}: club {club!r}: every shot is the same "
                f"({DISPERSION_KEYS[point.mode]}): a player needs a dispersion: allowed is a "
                "launch with at least one of them a distribution with a spread (sd > 0), e.g. "
                '{ dist = "normal", mean = "0 deg", sd = "1.5 deg" } for its azimuth'
            )


def on_hole(player, hole):
    """The player's scenario played on ``hole``: every club struck from the tee at the pin
    (the solver moves the start and the aim of each shot)."""
    play = Play((0.0, 0.0), tuple(hole.pin_xy))
    points = [dataclasses.replace(p, play=play) for p in player.scenario.points]
    return dataclasses.replace(player.scenario, hole=hole, play=play, points=points)
