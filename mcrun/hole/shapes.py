"""Analytic ground shapes for studies and tests: the height of the ground (m, relative to the
tee) at points of the hole's frame, x (m) from the tee towards the pin and y (m) to the RIGHT of
that line, and its exact gradient.

- ``plane``: flat, height 0.
- ``tilted_plane``: the plane through the origin whose normal is that of ``ground.plane`` for a
  slope of ``slope_deg`` falling towards ``fall_line_deg`` (degrees from +x, positive to the
  right), the scenario's ``slope``/``fall_line``: z = -tan(slope) (x cos(fall) + y sin(fall)).
- ``two_tier``: a green of two flat tiers, ``front_m`` for x before the step and ``back_m``
  after it, joined across ``step_width_m`` centred on ``step_x_m`` by a half sine, whose slope is
  continuous (zero at both ends of the step, steepest at its middle: pi/2 (back - front) / width).
- ``bowl``: the paraboloid z = bottom + r^2 / (2 R), r the distance from the centre: a bowl of
  radius of curvature R at its bottom (a sphere of radius R to second order).
- ``ridge``: a crest of ``height_m`` whose profile across it is cos^2 over ``half_width_m`` on
  each side (zero height and slope at its feet, flat ground beyond), its crest line through
  (``crest_x_m``, 0); ``angle_deg`` turns the ridge's normal from +x towards the right (0: the
  crest lies across the line of play).
- ``back_to_front``: a green falling from back to front, on a ramp from ``front_x_m`` to
  ``back_x_m`` (L = back - front) rising by s = ``slope_pct`` / 100 per metre, flat before and
  after. Its slope is s h(u) - s h(u - L + w), u = x - front, w = ``blend_m``, with h a half
  cosine from 0 to 1 over [0, w]: h(t) = (1 - cos(pi t / w)) / 2. Both blends lie inside the
  ramp (back > front + 2 w), so the height is z = s (H(u) - H(u - L + w)), H(t) = 0 for t <= 0,
  (t - (w / pi) sin(pi t / w)) / 2 on [0, w], t - w/2 beyond: 0 up to the front, s (L - w)
  from the back on (each blend gives up s w / 2 of the rise of the sharp ramp), the slope s
  between the blends, C1 at the joins (its slope continuous).
- ``crown``: a dome (a turtle-back green) z = height cos^2(pi r / (2 R)) for r < R, 0 beyond, r
  the distance from (``centre_x_m``, ``centre_y_m``), R = ``radius_m``: zero height and slope at
  its rim, steepest at r = R/2 (falling height pi / (2 R) per metre).

``SHAPES`` lists each kind's parameters (default, unit, allowed range) so that a reader of
scenario files can validate them; ``check_shape`` does so.
"""

import math
from typing import NamedTuple

import numpy as np

from mcrun.errors import InputError


class ShapeError(InputError):
    """A shape or parameter that is not allowed; its message is one line."""


class ShapeParam(NamedTuple):
    default: float
    unit: str
    min: float
    max: float
    min_open: bool  # the minimum itself is not allowed
    doc: str


SHAPES = {
    "plane": {
        "doc": "flat ground at the tee's height",
        "params": {},
    },
    "tilted_plane": {
        "doc": "a plane through the tee falling towards the fall line",
        "params": {
            "slope_deg": ShapeParam(2.0, "deg", 0.0, 45.0, False, "angle of the slope"),
            "fall_line_deg": ShapeParam(
                0.0, "deg", -360.0, 360.0, False, "direction it falls to, from +x, + right"
            ),
        },
    },
    "two_tier": {
        "doc": "two flat tiers joined by a smooth step across the line",
        "params": {
            "front_m": ShapeParam(0.0, "m", -50.0, 50.0, False, "height of the front tier"),
            "back_m": ShapeParam(0.6, "m", -50.0, 50.0, False, "height of the back tier"),
            "step_x_m": ShapeParam(150.0, "m", -100.0, 1000.0, False, "middle of the step"),
            "step_width_m": ShapeParam(3.0, "m", 0.0, 100.0, True, "length of the step along x"),
        },
    },
    "bowl": {
        "doc": "a paraboloid bowl, z = bottom + r^2 / (2 R)",
        "params": {
            "centre_x_m": ShapeParam(150.0, "m", -100.0, 1000.0, False, "x of the bottom"),
            "centre_y_m": ShapeParam(0.0, "m", -500.0, 500.0, False, "y of the bottom"),
            "radius_m": ShapeParam(50.0, "m", 0.0, 1e6, True, "radius of curvature at the bottom"),
            "bottom_m": ShapeParam(0.0, "m", -50.0, 50.0, False, "height of the bottom"),
        },
    },
    "ridge": {
        "doc": "a smooth ridge (cos^2 profile) across the line",
        "params": {
            "crest_x_m": ShapeParam(150.0, "m", -100.0, 1000.0, False, "x of the crest on y = 0"),
            "height_m": ShapeParam(1.0, "m", -50.0, 50.0, False, "height of the crest"),
            "half_width_m": ShapeParam(5.0, "m", 0.0, 500.0, True, "crest to foot, across it"),
            "angle_deg": ShapeParam(
                0.0, "deg", -90.0, 90.0, False, "ridge's normal from +x, + right"
            ),
        },
    },
    "back_to_front": {
        "doc": "a green falling from back to front on a ramp with smooth joins",
        "params": {
            "front_x_m": ShapeParam(140.0, "m", -100.0, 1000.0, False, "x of the ramp's foot"),
            "back_x_m": ShapeParam(170.0, "m", -100.0, 1000.0, False, "x of the ramp's top"),
            "slope_pct": ShapeParam(2.0, "%", 0.0, 10.0, False, "slope of the ramp, up to +x"),
            "blend_m": ShapeParam(
                2.0, "m", 0.0, 100.0, True, "the slope's half-cosine rise at each end"
            ),
        },
    },
    "crown": {
        "doc": "a dome (turtle back), z = height cos^2(pi r / (2 R)) for r < R",
        "params": {
            "centre_x_m": ShapeParam(150.0, "m", -100.0, 1000.0, False, "x of the top"),
            "centre_y_m": ShapeParam(0.0, "m", -500.0, 500.0, False, "y of the top"),
            "height_m": ShapeParam(0.5, "m", -5.0, 5.0, False, "height of the top"),
            "radius_m": ShapeParam(12.0, "m", 0.0, 200.0, True, "radius of the rim"),
        },
    },
}


def _check_back_to_front(kind, p):
    front, back, w = p["front_x_m"], p["back_x_m"], p["blend_m"]
    if not back > front + 2.0 * w:
        raise ShapeError(
            f"{kind}.back_x_m = {back:g}: allowed is more than front_x_m + 2 blend_m"
            f" = {front:g} + 2 * {w:g} = {front + 2.0 * w:g} m"
        )


# Checks of a kind's parameters together, after each has been checked on its own.
_CONSISTENCY = {"back_to_front": _check_back_to_front}


def check_shape(kind, params=None):
    """The parameters of shape ``kind`` with defaults filled in, as floats; ShapeError (one line)
    naming the shape or parameter and what is allowed."""
    if kind not in SHAPES:
        raise ShapeError(f"unknown ground shape {kind!r}: allowed are {', '.join(SHAPES)}")
    spec = SHAPES[kind]["params"]
    params = dict(params or {})
    unknown = sorted(set(params) - set(spec))
    if unknown:
        allowed = ", ".join(spec) if spec else "none"
        raise ShapeError(
            f"ground shape {kind!r} has no parameter {unknown[0]!r}: its parameters are {allowed}"
        )
    out = {}
    for name, p in spec.items():
        value = params.get(name, p.default)
        lo = "(" if p.min_open else "["
        allowed = f"a number in {lo}{p.min:g}, {p.max:g}] {p.unit}"
        if isinstance(value, bool) or not isinstance(value, int | float | np.number):
            raise ShapeError(f"{kind}.{name} = {value!r}: allowed is {allowed}")
        value = float(value)
        too_low = value <= p.min if p.min_open else value < p.min
        if not math.isfinite(value) or too_low or value > p.max:
            raise ShapeError(f"{kind}.{name} = {value:g}: allowed is {allowed}")
        out[name] = value
    if kind in _CONSISTENCY:
        _CONSISTENCY[kind](kind, out)
    return out


def _xy(x_m, y_m):
    x = np.asarray(x_m, dtype=np.float64)
    y = np.asarray(y_m, dtype=np.float64)
    return np.broadcast_arrays(x, y)


def _step(u):
    """0 before the step (u < -1/2), 1 after it (u > 1/2), a half sine between; and d/du."""
    inside = np.abs(u) < 0.5
    s = np.where(u <= -0.5, 0.0, np.where(u >= 0.5, 1.0, 0.5 * (1.0 + np.sin(np.pi * u))))
    ds = np.where(inside, 0.5 * np.pi * np.cos(np.pi * u), 0.0)
    return s, ds


def _ridge_profile(d, a):
    """cos^2(pi d / (2a)) for |d| < a, 0 beyond; and d/dd."""
    inside = np.abs(d) < a
    c = np.cos(0.5 * np.pi * d / a)
    s = np.sin(0.5 * np.pi * d / a)
    return np.where(inside, c * c, 0.0), np.where(inside, -np.pi / a * c * s, 0.0)


def _blend(t, w):
    """h(t): 0 for t <= 0, (1 - cos(pi t / w)) / 2 on [0, w], 1 beyond; and its integral H(t)
    from 0: 0, (t - (w / pi) sin(pi t / w)) / 2, t - w / 2."""
    a = np.pi * t / w
    h = np.where(t <= 0.0, 0.0, np.where(t >= w, 1.0, 0.5 * (1.0 - np.cos(a))))
    big_h = np.where(
        t <= 0.0, 0.0, np.where(t >= w, t - 0.5 * w, 0.5 * (t - w / np.pi * np.sin(a)))
    )
    return h, big_h


def _evaluate(kind, params, x_m, y_m):
    p = check_shape(kind, params)
    x, y = _xy(x_m, y_m)
    zero = np.zeros(x.shape)
    if kind == "plane":
        return zero, zero, zero.copy()
    if kind == "tilted_plane":
        t = math.tan(math.radians(p["slope_deg"]))
        a = math.radians(p["fall_line_deg"])
        gx, gy = -t * math.cos(a), -t * math.sin(a)
        return gx * x + gy * y, zero + gx, zero + gy
    if kind == "two_tier":
        w = p["step_width_m"]
        rise = p["back_m"] - p["front_m"]
        s, ds = _step((x - p["step_x_m"]) / w)
        return p["front_m"] + rise * s, rise * ds / w, zero
    if kind == "bowl":
        dx, dy = x - p["centre_x_m"], y - p["centre_y_m"]
        r = p["radius_m"]
        return p["bottom_m"] + (dx * dx + dy * dy) / (2.0 * r), dx / r, dy / r
    if kind == "ridge":
        th = math.radians(p["angle_deg"])
        c, s = math.cos(th), math.sin(th)
        f, df = _ridge_profile((x - p["crest_x_m"]) * c + y * s, p["half_width_m"])
        h = p["height_m"]
        return h * f, h * df * c, h * df * s
    if kind == "back_to_front":
        slope = p["slope_pct"] / 100.0
        w = p["blend_m"]
        length = p["back_x_m"] - p["front_x_m"]
        top = length - w  # where the second blend starts, from the foot
        u = np.minimum(x - p["front_x_m"], length)  # the same height all along the top
        h_up, big_h_up = _blend(u, w)
        h_down, big_h_down = _blend(u - top, w)
        return slope * (big_h_up - big_h_down), slope * (h_up - h_down), zero
    # crown: dz/dr = -height pi / (2R) sin(pi r / R), and sin(pi r / R) / r = (pi / R) sinc(r / R)
    dx, dy = x - p["centre_x_m"], y - p["centre_y_m"]
    r_rim, h = p["radius_m"], p["height_m"]
    r = np.hypot(dx, dy)
    f, _ = _ridge_profile(r, r_rim)
    k = np.where(r < r_rim, -h * np.pi**2 / (2.0 * r_rim**2) * np.sinc(r / r_rim), 0.0)
    return h * f, k * dx, k * dy


def shape_height(kind, params, x_m, y_m):
    """Height (m, relative to the tee) of ground shape ``kind`` at (x_m, y_m) of the hole's
    frame (arrays broadcast)."""
    return _evaluate(kind, params, x_m, y_m)[0]


def shape_gradient(kind, params, x_m, y_m):
    """The exact gradient (dz/dx, dz/dy) of ground shape ``kind`` at (x_m, y_m), y to the right."""
    _, gx, gy = _evaluate(kind, params, x_m, y_m)
    return gx, gy
