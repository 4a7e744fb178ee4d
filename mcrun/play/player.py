"""The player: a bag of clubs (each a launch distribution, as a scenario's group), the
wedge's part-power shots, how a lie changes a launch, and a putter.

A player file is a scenario file without a ``[hole]``: its ``[[group]]``s are the clubs, each
with its launch (presets, correlated normals, or fitted from a launch-monitor session:
``[launch] file`` with a club filter), its weather and models; ``pga-tour-bag`` (the library's)
is the Tour player. The shortest club of the bag (its last group: the wedge) is also hit at
part power (``PART_POWERS``): its ball speed and spin scaled by the power, its launch angle
kept, an ESTIMATE of a pitch's launch.

How a lie changes a launch (``LIE_LAUNCH``, ESTIMATES a user can override): from the rough a
"flyer" (grass between the face and the ball: less spin, a little less speed); from a bunker
less speed and spin (sand taken with the ball); a recovery shot (under trees) is a punch, at
much less speed. Fairway and tee shots are the launch as sampled.
"""

import dataclasses
from dataclasses import dataclass

from mcrun.quantities import InputError
from mcrun.run import scenario as sc
from mcrun.run.scenario.hole_table import Play

__all__ = ["LIE_LAUNCH", "PART_POWERS", "Player", "PlayerError", "load_player", "on_hole"]

# (ball speed factor, spin factor) by the lie the ball is struck from. ESTIMATES: a flyer from
# the rough carries 20-50 % less spin (the grass between face and ball); a fairway bunker
# shot loses about a tenth of its speed; a recovery is a punch back into play.
LIE_LAUNCH = {
    "tee": (1.0, 1.0),
    "fairway": (1.0, 1.0),
    "rough": (0.97, 0.65),
    "sand": (0.90, 0.80),
    "recovery": (0.60, 0.80),
}
# The wedge at part power: ball speed and spin times each of these.
PART_POWERS = (0.85, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2)


class PlayerError(InputError):
    """A player that cannot be used; one line."""


@dataclass(frozen=True)
class Player:
    """A bag: ``scenario`` (a plane scenario whose points are the clubs), the clubs' names,
    the putter (a name of ``mcrun.putting.PUTTERS``) and where it was read."""

    name: str
    scenario: object
    clubs: tuple
    putter: str
    source: str


def load_player(spec, putter="tour"):
    """The Player of a player file or a library scenario's name (``pga-tour-bag``)."""
    scenario = sc.load(spec)
    if scenario.hole is not None:
        raise PlayerError(
            f"{scenario.path}: a player is a bag of clubs ([[group]]s) without a [hole]: the "
            "hole is given apart (mcrun play PLAYER HOLE)"
        )
    clubs = tuple(p.label or p.group or f"club {p.index}" for p in scenario.points)
    if len(set(clubs)) != len(clubs):
        raise PlayerError(f"{scenario.path}: each club (group) needs a name of its own")
    return Player(scenario.name, scenario, clubs, putter, str(scenario.path))


def on_hole(player, hole):
    """The player's scenario played on ``hole``: every club struck from the tee at the pin
    (the solver moves the start and the aim of each shot)."""
    play = Play((0.0, 0.0), tuple(hole.pin_xy))
    points = [dataclasses.replace(p, play=play) for p in player.scenario.points]
    return dataclasses.replace(player.scenario, hole=hole, play=play, points=points)
