"""hole.shapes: the analytic ground shapes' heights, their exact gradients and the validation of
their parameters."""

import math

import numpy as np
import pytest

from mcrun.ground import plane
from mcrun.hole.shapes import SHAPES, ShapeError, check_shape, shape_gradient, shape_height
from mcrun.physics.turf import Turf

RNG = np.random.default_rng(12)
X = RNG.uniform(100.0, 200.0, 400)
Y = RNG.uniform(-30.0, 30.0, 400)

CASES = [
    ("plane", {}),
    ("tilted_plane", {"slope_deg": 3.0, "fall_line_deg": 30.0}),
    ("tilted_plane", {"slope_deg": 40.0, "fall_line_deg": -135.0}),
    ("two_tier", {"front_m": -0.2, "back_m": 0.7, "step_x_m": 150.0, "step_width_m": 4.0}),
    ("bowl", {"centre_x_m": 140.0, "centre_y_m": 5.0, "radius_m": 30.0, "bottom_m": -1.0}),
    ("ridge", {"crest_x_m": 160.0, "height_m": 1.5, "half_width_m": 8.0, "angle_deg": 20.0}),
    ("back_to_front", {}),
    ("back_to_front", {"front_x_m": 135.0, "back_x_m": 175.0, "slope_pct": 3.0, "blend_m": 5.0}),
    ("crown", {}),
    ("crown", {"centre_x_m": 145.0, "centre_y_m": -4.0, "height_m": -0.7, "radius_m": 25.0}),
]


@pytest.mark.parametrize("kind,params", CASES)
def test_gradient_is_the_central_difference_of_the_height(kind, params):
    # Central differences of step h err by h^2/6 z''' (~1e-9 m/m here for h = 1e-4 m) plus the
    # rounding of heights of ~300 m over 2h: 1e-7 m/m covers both.
    h = 1e-4
    gx, gy = shape_gradient(kind, params, X, Y)
    fx = (shape_height(kind, params, X + h, Y) - shape_height(kind, params, X - h, Y)) / (2 * h)
    fy = (shape_height(kind, params, X, Y + h) - shape_height(kind, params, X, Y - h)) / (2 * h)
    np.testing.assert_allclose(gx, fx, rtol=0, atol=1e-7)
    np.testing.assert_allclose(gy, fy, rtol=0, atol=1e-7)


def test_plane_is_flat():
    assert np.all(shape_height("plane", {}, X, Y) == 0.0)
    gx, gy = shape_gradient("plane", None, X, Y)
    assert np.all(gx == 0.0) and np.all(gy == 0.0)


@pytest.mark.parametrize("slope_deg,fall_deg", [(2.0, 0.0), (3.0, 30.0), (10.0, -120.0)])
def test_tilted_plane_has_the_normal_of_the_scenario_slope(slope_deg, fall_deg):
    p = {"slope_deg": slope_deg, "fall_line_deg": fall_deg}
    # The ground's normal in the core's frame (y LEFT) for this slope and fall line; the hole
    # frame has y to the RIGHT, so its y component changes sign.
    turf = Turf(*([0.0] * len(Turf._fields)))
    g = plane(math.radians(slope_deg), math.radians(fall_deg), turf)
    n = np.array([g.nx, -g.ny, g.nz])
    # Every pair of points of the surface differs by a vector normal to n (to rounding).
    z = shape_height("tilted_plane", p, X, Y)
    chords = np.stack([X - X[0], Y - Y[0], z - z[0]], axis=1)
    assert np.max(np.abs(chords @ n)) < 1e-12 * np.max(np.abs(chords))
    assert shape_height("tilted_plane", p, 0.0, 0.0) == 0.0
    # The ground falls by tan(slope) per metre along the fall line and is level across it.
    a = math.radians(fall_deg)
    gx, gy = shape_gradient("tilted_plane", p, X, Y)
    along = gx * math.cos(a) + gy * math.sin(a)
    across = -gx * math.sin(a) + gy * math.cos(a)
    np.testing.assert_allclose(along, -math.tan(math.radians(slope_deg)), rtol=1e-15, atol=0)
    np.testing.assert_allclose(across, 0.0, rtol=0, atol=1e-16)


def test_a_fall_line_to_the_right_lowers_the_right():
    z = shape_height("tilted_plane", {"slope_deg": 5.0, "fall_line_deg": 90.0}, 0.0, [-10, 10])
    np.testing.assert_allclose(z, [10 * math.tan(math.radians(5)), -10 * math.tan(math.radians(5))])


def test_two_tier_heights_and_step():
    p = {"front_m": 0.1, "back_m": 0.9, "step_x_m": 150.0, "step_width_m": 4.0}
    x = np.array([100.0, 147.9, 148.0, 150.0, 152.0, 152.1, 200.0])
    z = shape_height("two_tier", p, x, 3.0)
    assert z[0] == z[1] == z[2] == 0.1  # the front tier, up to the foot of the step
    assert z[4] == z[5] == z[6] == 0.9  # the back tier from its top
    assert z[3] == pytest.approx(0.5, abs=1e-15)  # halfway up at the middle
    gx, gy = shape_gradient("two_tier", p, x, 3.0)
    assert gx[3] == pytest.approx(math.pi / 2 * 0.8 / 4.0, rel=1e-15)  # steepest at the middle
    assert gx[0] == gx[6] == 0.0 and np.all(gy == 0.0)
    # The slope is continuous at the foot and top of the step: it tends to 0 there.
    near = shape_gradient("two_tier", p, np.array([148.0 + 1e-6, 152.0 - 1e-6]), 0.0)[0]
    assert np.all(np.abs(near) < 1e-6)


def test_bowl_is_lowest_at_its_centre_with_its_curvature():
    p = {"centre_x_m": 140.0, "centre_y_m": 5.0, "radius_m": 30.0, "bottom_m": -1.0}
    z = shape_height("bowl", p, X, Y)
    assert shape_height("bowl", p, 140.0, 5.0) == -1.0
    assert np.all(z > -1.0)
    gx, gy = shape_gradient("bowl", p, 140.0, 5.0)
    assert gx == 0.0 and gy == 0.0
    # z'' = 1/R: 10 m from the bottom the bowl has risen 10^2 / (2 * 30) m.
    assert shape_height("bowl", p, 150.0, 5.0) == pytest.approx(-1.0 + 100 / 60, rel=1e-15)


def test_ridge_crest_and_feet():
    p = {"crest_x_m": 160.0, "height_m": 1.5, "half_width_m": 8.0, "angle_deg": 0.0}
    z = shape_height("ridge", p, np.array([140.0, 152.0, 156.0, 160.0, 168.0, 190.0]), 7.0)
    np.testing.assert_allclose(z, [0.0, 0.0, 0.75, 1.5, 0.0, 0.0], rtol=0, atol=1e-15)
    gx, gy = shape_gradient("ridge", p, np.array([156.0, 160.0]), 7.0)
    assert gx[0] == pytest.approx(1.5 * math.pi / 16, rel=1e-14) and gx[1] == 0.0
    assert np.all(gy == 0.0)
    # Turned by 30 degrees, the crest is the line (x - 160) cos 30 + y sin 30 = 0.
    turned = dict(p, angle_deg=30.0)
    t = np.linspace(-20, 20, 9)
    on_crest_x = 160.0 - t * math.sin(math.radians(30.0))
    on_crest_y = t * math.cos(math.radians(30.0))
    np.testing.assert_allclose(shape_height("ridge", turned, on_crest_x, on_crest_y), 1.5)


def test_back_to_front_heights_and_slopes():
    p = {"front_x_m": 140.0, "back_x_m": 170.0, "slope_pct": 2.0, "blend_m": 2.0}
    s, w = 2.0 / 100, 2.0
    # The sharp ramp would rise s (back - front); each half-cosine blend gives up s w / 2 of it.
    rise = s * (170.0 - 140.0 - w)
    x = np.array([100.0, 139.9, 140.0, 141.0, 142.0, 155.0, 169.0, 170.0, 170.1, 200.0])
    z = shape_height("back_to_front", p, x, -4.0)
    gx, gy = shape_gradient("back_to_front", p, x, -4.0)
    assert z[0] == z[1] == z[2] == 0.0  # flat, at the tee's height, up to the front
    assert z[7] == z[8] == z[9] == pytest.approx(rise, rel=1e-14)  # flat from the back on
    assert gx[0] == gx[2] == gx[7] == gx[9] == 0.0 and np.all(gy == 0.0)
    # Halfway up the first blend the slope is s/2, the height s/2 (t - (w/pi) sin(pi t / w)).
    assert gx[3] == pytest.approx(s / 2, rel=1e-15)
    assert z[3] == pytest.approx(s / 2 * (1.0 - w / math.pi), rel=1e-14)
    # Between the blends the slope is exactly slope_pct / 100, the height s (x - front - w/2).
    assert gx[4] == gx[5] == s
    assert z[4] == pytest.approx(s * w / 2, rel=1e-14)
    assert z[5] == pytest.approx(s * (155.0 - 140.0 - w / 2), rel=1e-14)
    # The top blend mirrors the foot's: z(back - d) = rise - z(front + d).
    assert z[6] == pytest.approx(rise - z[3], rel=1e-14)
    assert gx[6] == pytest.approx(gx[3], rel=1e-14)
    # C1 across the four joins: every 1 cm from 139 to 171 m the gradient is the central
    # difference of the height. Here z'' = s h is continuous and |z'''| <= s (pi/w)^2 / 2, so
    # the difference errs by at most d^2/6 |z'''| = 4e-11 plus rounding (~1e-12): 1e-9 m/m.
    xs = np.linspace(139.0, 171.0, 3201)
    d = 1e-4
    up = shape_height("back_to_front", p, xs + d, 0.0)
    down = shape_height("back_to_front", p, xs - d, 0.0)
    fd = (up - down) / (2 * d)
    np.testing.assert_allclose(shape_gradient("back_to_front", p, xs, 0.0)[0], fd, atol=1e-9)
    # The slope tends to 0 at the foot and the top, and to s at the ends of the blends.
    near = shape_gradient("back_to_front", p, np.array([140 + 1e-6, 170 - 1e-6, 142 - 1e-6]), 0)
    assert np.all(np.abs(near[0][:2]) < 1e-12) and abs(near[0][2] - s) < 1e-12
    assert np.all(np.diff(shape_height("back_to_front", p, xs, 0.0)) >= 0.0)  # never falls


def test_crown_top_rim_and_steepest_slope():
    p = {"centre_x_m": 150.0, "centre_y_m": -3.0, "height_m": 0.5, "radius_m": 12.0}
    assert shape_height("crown", p, 150.0, -3.0) == 0.5
    gx, gy = shape_gradient("crown", p, 150.0, -3.0)
    assert gx == 0.0 and gy == 0.0  # level on the top
    # Zero height and slope on the rim (r = R) and beyond.
    rim_x = np.array([162.0, 138.0, 150.0, 150.0, 170.0, 100.0])
    rim_y = np.array([-3.0, -3.0, 9.0, -15.0, -3.0, 20.0])
    assert np.all(shape_height("crown", p, rim_x, rim_y) == 0.0)
    gx, gy = shape_gradient("crown", p, rim_x, rim_y)
    assert np.all(gx == 0.0) and np.all(gy == 0.0)
    # At r = R/2 the height is height cos^2(pi/4) = height/2 and the ground falls away from the
    # top at its steepest, height pi / (2R) per metre (here along x, and along (3, 4) / 5).
    assert shape_height("crown", p, 156.0, -3.0) == pytest.approx(0.25, rel=1e-14)
    gx, gy = shape_gradient("crown", p, 156.0, -3.0)
    assert gx == pytest.approx(-0.5 * math.pi / 24.0, rel=1e-14) and gy == 0.0
    gx, gy = shape_gradient("crown", p, 150.0 + 3.6, -3.0 + 4.8)
    want = -0.5 * math.pi / 24.0 * np.array([0.6, 0.8])
    np.testing.assert_allclose([gx, gy], want, rtol=1e-14, atol=0)
    # A negative height is a hollow of the same profile.
    hollow = shape_height("crown", dict(p, height_m=-0.5), X, Y)
    np.testing.assert_array_equal(hollow, -shape_height("crown", p, X, Y))


def test_defaults_and_shapes_listing():
    for kind, spec in SHAPES.items():
        assert set(check_shape(kind)) == set(spec["params"])
        for name, param in spec["params"].items():
            lo_ok = param.default > param.min if param.min_open else param.default >= param.min
            assert lo_ok and param.default <= param.max, (kind, name)
    assert check_shape("bowl", {"radius_m": 10})["radius_m"] == 10.0


@pytest.mark.parametrize(
    "kind,params,expected",
    [
        ("cone", {}, "unknown ground shape 'cone': allowed are plane, tilted_plane"),
        ("bowl", {"depth_m": 1.0}, "ground shape 'bowl' has no parameter 'depth_m'"),
        ("plane", {"slope_deg": 1.0}, "its parameters are none"),
        ("tilted_plane", {"slope_deg": 50.0}, "tilted_plane.slope_deg = 50: allowed is a number"),
        ("tilted_plane", {"slope_deg": "2"}, "tilted_plane.slope_deg = '2': allowed is a number"),
        ("two_tier", {"step_width_m": 0.0}, "two_tier.step_width_m = 0: allowed is a number in (0"),
        ("bowl", {"radius_m": float("nan")}, "bowl.radius_m = nan"),
        ("ridge", {"height_m": True}, "ridge.height_m = True"),
        ("back_to_front", {"slope_pct": 12.0}, "back_to_front.slope_pct = 12: allowed is a"),
        ("back_to_front", {"blend_m": 0.0}, "back_to_front.blend_m = 0: allowed is a number in (0"),
        (
            "back_to_front",
            {"front_x_m": 140.0, "back_x_m": 144.0},
            "back_to_front.back_x_m = 144: allowed is more than front_x_m + 2 blend_m = 140 + 2",
        ),
        ("back_to_front", {"back_x_m": 120.0}, "back_to_front.back_x_m = 120: allowed is more"),
        ("crown", {"radius_m": 0.0}, "crown.radius_m = 0: allowed is a number in (0, 200] m"),
        ("crown", {"height_m": 6.0}, "crown.height_m = 6: allowed is a number in [-5, 5] m"),
    ],
)
def test_bad_parameters_say_so_in_one_line(kind, params, expected):
    with pytest.raises(ShapeError) as err:
        shape_height(kind, params, 0.0, 0.0)
    message = str(err.value)
    assert expected in message and "\n" not in message
