"""The whole hole played as a given player: their own expected strokes from everywhere, and the
best club and aim there, by value iteration over mcrun's own shots (a Markov decision process,
as Stauffer and Guillot solve a hole from shot-location data; here every shot is flown on the
hole's ground).

The parts: the player (``player``: a bag, its spread, lies, part power; ``calibration``: the
Tour bag's spread), the states (``lattice``), the actions and their shots (``transitions``),
the values and the policy (``solve``), the score distribution (``episodes``), and the solve
checked and sized before it runs (``plan``: ``plan_play``; ``solve_planned`` runs its plan).
``play_hole`` is the entry point from Python; ``mcrun play`` plans every player it solves
before it solves any, says each plan, and prints the results.
"""

import math
import time
from dataclasses import dataclass

import numpy as np
import pandas as pd

from mcrun.play.episodes import MAX_STROKES, play_policy
from mcrun.play.lattice import DEFAULT_COARSE_M, DEFAULT_FINE_M, DEFAULT_FINE_WITHIN_M
from mcrun.play.plan import PlayPlan, plan_play
from mcrun.play.player import Player, PlayerError, load_player
from mcrun.play.solve import solve
from mcrun.play.transitions import AIMS, OVERSHOOT_M, fly
from mcrun.putting.on_hole import map_of_hole
from mcrun.strokes.baseline import LIES, tour_baseline

__all__ = [
    "DEFAULT_N",
    "PlayPlan",
    "PlayResult",
    "Player",
    "PlayerError",
    "load_player",
    "plan_play",
    "play_hole",
    "solve_planned",
]

DEFAULT_N = 100
DEFAULT_PLAYS = 4000
# The plays' mean against the solve's expected score (``PlayResult.gap_note``): a gap beyond
# both is noted.
GAP_SES = 4.0
GAP_STROKES = 0.1
SCORE_NAMES = ("eagle or better", "birdie", "par", "bogey", "double bogey or worse")


@dataclass
class PlayResult:
    """A solved hole (see ``play_hole``)."""

    player: Player
    hole: object
    lattice: object
    transitions: object
    solution: object
    fairway_solution: object
    scores: np.ndarray  # strokes of each play of the policy
    n: int
    seed: int
    seconds: float

    def action_name(self, row):
        """The action of transition row ``row``, in words ("7-iron at the pin 2 deg left")."""
        return self.transitions.actions[self.transitions.row_action[row]].name(self.player.clubs)

    @property
    def tee_value(self):
        return float(self.solution.values[0])

    @property
    def tee_se(self):
        return float(self.solution.q_se[self.solution.best_row[0]])

    def plays_gap(self):
        """(the plays' mean score less the expected score from the tee, its standard error):
        the solve values states on a lattice, each action's shots snapped to its nodes; the
        plays follow its policy shot by shot. Where the two disagree by more than
        ``GAP_SES`` standard errors and ``GAP_STROKES``, the lattice is too coarse for the
        hole (``gap_note``)."""
        scores = np.asarray(self.scores, dtype=float)
        se_plays = float(scores.std(ddof=1)) / math.sqrt(len(scores)) if len(scores) > 1 else 0.0
        return float(scores.mean()) - self.tee_value, math.hypot(self.tee_se, se_plays)

    def gap_note(self):
        """A line for a gap between the plays and the solve beyond chance, else None."""
        gap, se = self.plays_gap()
        if abs(gap) <= max(GAP_SES * se, GAP_STROKES):
            return None
        return (f"the plays' mean is {gap:+.3f} strokes from the expected score from the tee "
                f"(+- {se:.3f}): the lattice is too coarse for this hole to value it; a finer "
                "--coarse (and --fine) holds it closer")  # fmt: skip

    def tee_rows(self):
        """Every row of the tee (state 0): (row, name, Q, se), best first."""
        rows = np.flatnonzero(self.transitions.row_state == 0)
        out = [(int(r), self.action_name(r), float(self.solution.q[r]),
                float(self.solution.q_se[r])) for r in rows]  # fmt: skip
        return sorted(out, key=lambda row: row[2])

    def savings(self):
        """{policy: (its expected strokes from the tee, strokes saved by the solution)} for the
        simple policies: the driver aimed at the pin from the tee (then the best), and every
        shot at the centre of the fairway (the line aim where offered, else the pin)."""
        out = {}
        tr = self.transitions
        driver = [r for r, name, q, se in self.tee_rows()
                  if tr.actions[tr.row_action[r]].club == 0
                  and tr.actions[tr.row_action[r]].power == 1.0
                  and AIMS[tr.actions[tr.row_action[r]].aim] == ("pin", 0.0)]  # fmt: skip
        if driver:
            q = float(self.solution.q[driver[0]])
            out[f"{self.player.clubs[0]} at the pin"] = (q, q - self.tee_value)
        if self.fairway_solution is not None:
            v = float(self.fairway_solution.values[0])
            out["every shot at the fairway's centre"] = (v, v - self.tee_value)
        return out

    def score_shares(self):
        """{name: share} of the plays' scores against par (``SCORE_NAMES``); where the hole's
        par is not known, against the expected score from the tee rounded (see
        ``stroke_shares``)."""
        par = self.hole.par or round(self.tee_value)
        d = self.scores - par
        counts = (d <= -2, d == -1, d == 0, d == 1, d >= 2)
        return {name: float(c.mean()) for name, c in zip(SCORE_NAMES, counts, strict=True)}

    def second_shots(self):
        """{"for the green": share, "lay-up": share, "over": share} of the policy's plays
        (played again, the same plays as ``scores``) by their second stroke: with a club whose
        mean total on the level reaches within ``transitions.OVERSHOOT_M`` of the pin from
        where it was struck (the green is in reach: a lay-up aim is not offered), short of
        that (a lay-up), or none (holed out, or on the green, after one)."""
        second = np.empty(len(self.scores), dtype=np.int64)
        play_policy(self.lattice, self.transitions, self.solution, len(self.scores),
                    self.seed, second_rows=second)  # fmt: skip
        tr, lat = self.transitions, self.lattice
        played = second >= 0
        rows = second[played]
        total = np.array([tr.actions[a].total_m for a in tr.row_action[rows]])
        xy = lat.xy[tr.row_state[rows]]
        distance = np.hypot(xy[:, 0] - self.hole.pin_xy[0], xy[:, 1] - self.hole.pin_xy[1])
        going = total >= distance - OVERSHOOT_M
        n = len(second)
        return {"for the green": float(going.sum()) / n,
                "lay-up": float((~going).sum()) / n,
                "over": float((~played).sum()) / n}  # fmt: skip

    def stroke_shares(self):
        """{strokes: share} of the plays' scores, fewest first: the distribution without a
        par."""
        values, counts = np.unique(self.scores, return_counts=True)
        return {int(v): float(c) / len(self.scores) for v, c in zip(values, counts, strict=True)}

    def states_frame(self):
        """One row per state: x_m, y_m, lie, expected_strokes, its se, the best action."""
        s = self.solution
        tr = self.transitions
        best = s.best_row
        action = [tr.actions[tr.row_action[r]] if r >= 0 else None for r in best]
        return pd.DataFrame(
            {
                "x_m": self.lattice.xy[:, 0],
                "y_m": self.lattice.xy[:, 1],
                "lie": pd.Categorical([LIES[k] for k in self.lattice.lie], categories=LIES),
                "expected_strokes": s.values,
                "expected_strokes_se": np.where(best >= 0, s.q_se[np.maximum(best, 0)], np.nan),
                "club": [self.player.clubs[a.club] if a else None for a in action],
                "power": [a.power if a else math.nan for a in action],
                "aim": [
                    f"{AIMS[a.aim][0]} {AIMS[a.aim][1]:+g} deg" if a else None for a in action
                ],  # fmt: skip
                "baseline_strokes": tour_baseline().expected(
                    [LIES[k] for k in self.lattice.lie],
                    np.hypot(
                        self.lattice.xy[:, 0] - self.hole.pin_xy[0],
                        self.lattice.xy[:, 1] - self.hole.pin_xy[1],
                    ),
                ),  # fmt: skip
            }
        )

    def actions_frame(self):
        """One row per state and action: state, x_m, y_m, club, power, aim, expected_strokes
        (Q) and its se, best (the state's chosen action)."""
        tr, s = self.transitions, self.solution
        a = [tr.actions[k] for k in tr.row_action]
        return pd.DataFrame(
            {
                "state": tr.row_state,
                "x_m": self.lattice.xy[tr.row_state, 0],
                "y_m": self.lattice.xy[tr.row_state, 1],
                "club": pd.Categorical(
                    [self.player.clubs[x.club] for x in a], categories=self.player.clubs
                ),  # fmt: skip
                "power": [x.power for x in a],
                "aim": pd.Categorical([f"{AIMS[x.aim][0]} {AIMS[x.aim][1]:+g} deg" for x in a]),
                "expected_strokes": s.q,
                "expected_strokes_se": s.q_se,
                "best": s.best_row[tr.row_state] == np.arange(len(tr.row_state)),
            }
        )


def play_hole(player, hole, n=DEFAULT_N, seed=None, coarse_m=DEFAULT_COARSE_M,
              fine_m=DEFAULT_FINE_M, fine_within_m=DEFAULT_FINE_WITHIN_M, plays=DEFAULT_PLAYS,
              progress=None, client=None):  # fmt: skip
    """Solve ``hole`` (a ``mcrun.hole.Hole``) for ``player`` (a ``Player``): ``n`` shots of each
    action from each state (the player's scenario's first n, its seed or ``seed``), states every
    ``coarse_m`` and every ``fine_m`` within ``fine_within_m`` of the pin; the policy played
    ``plays`` times. A ball on the green is worth the player's putts: the map of the hole's
    green putted by the player's putter (``putting.on_hole.putting_of``), or the baseline's
    putts where the hole asks for the table and the player putts as the Tour does.
    ``client``: a Dask client whose workers fly the shots (the same solution, bit for bit).
    ``progress(k)``: called with the actions flown so far. What cannot be solved is refused
    before a shot is flown on the hole (``plan.plan_play``: PlayerError, one line)."""
    planned = plan_play(player, hole, n=n, seed=seed, coarse_m=coarse_m, fine_m=fine_m,
                        fine_within_m=fine_within_m, plays=plays)  # fmt: skip
    return solve_planned(planned, progress=progress, client=client)


def solve_planned(planned, progress=None, client=None):
    """The ``PlayResult`` of a ``PlayPlan`` (``plan.plan_play``): its actions flown, the values
    solved, the policy played."""
    started = time.perf_counter()
    player, hole, scenario, lat, n = (planned.player, planned.hole, planned.scenario,
                                      planned.lattice, planned.n)  # fmt: skip
    tr = fly(scenario, lat, n, player, putting=map_of_hole(hole, putter=player.putter),
             baseline=planned.baseline, progress=progress, client=client,
             planned=(planned.actions, planned.jobs))  # fmt: skip
    solution = solve(lat, tr)
    if solution.change > 1e-3 or not np.isfinite(solution.values[0]):
        worst = int(np.argmax(solution.values))
        raise PlayerError(
            f"{hole.source}: the values did not settle in {solution.sweeps} sweeps: from "
            f"({lat.xy[worst, 0]:.0f}, {lat.xy[worst, 1]:.0f}) m the player cannot hole out "
            "(no green around the pin, or every shot of the bag flies past it)"
        )
    # Every shot at the fairway's centre: each club's line aim where it has one from there
    # (it stops short of the pin), else its pin aim.
    option = np.array([(a.club, a.power) for a in tr.actions])
    key = tr.row_state * 1000 + np.unique(option, axis=0, return_inverse=True)[1].ravel()[
        tr.row_action]  # fmt: skip
    row_aim = np.array([tr.actions[a].aim for a in tr.row_action])
    line_rows = row_aim == AIMS.index(("line", 0.0))
    allowed = line_rows | ((row_aim == AIMS.index(("pin", 0.0))) & ~np.isin(key, key[line_rows]))
    fairway = solve(lat, tr, allowed=allowed, start_values=solution.values)
    scores = play_policy(lat, tr, solution, planned.plays, scenario.seed)
    return PlayResult(player, hole, lat, tr, solution, fairway, scores, n, scenario.seed,
                      planned.planned_s + time.perf_counter() - started)  # fmt: skip


__all__ += ["MAX_STROKES", "SCORE_NAMES"]
