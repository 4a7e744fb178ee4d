"""The kernel's branch-free arctangent, sine and cosine (mcrun.physics.trig) against the C library.

Cephes' approximations are accurate to about one unit in the last place; the tests allow two
(4.5e-16 absolute on values of magnitude at most 1, 4.5e-16 relative on the arctangent).
"""

import math

import numpy as np
import pytest

from mcrun.physics.trig import atan2_first_quadrant, sincos, sincos_first_quadrant

ULP2 = 4.5e-16


def test_atan2_first_quadrant_equals_atan2():
    rng = np.random.default_rng(1)
    ys = np.concatenate([rng.uniform(0.0, 50.0, 2000), [0.0, 1.0, 3.0, 1e-300]])
    xs = np.concatenate([rng.uniform(0.0, 50.0, 2000), [1.0, 0.0, 3.0, 1.0]])
    for y, x in zip(ys, xs, strict=True):
        want = math.atan2(y, x)
        assert atan2_first_quadrant(y, x) == pytest.approx(want, rel=ULP2, abs=1e-300)


def test_sincos_first_quadrant_equals_sin_cos():
    for theta in np.linspace(0.0, 0.5 * math.pi, 4001):
        s, c = sincos_first_quadrant(theta)
        assert abs(s - math.sin(theta)) <= ULP2
        assert abs(c - math.cos(theta)) <= ULP2


@pytest.mark.parametrize("span", [1.0, 10.0, 1e4])
def test_sincos_equals_sin_cos_on_every_quadrant(span):
    """Any sign and quadrant, and the multiples of pi/4 where the reduction switches."""
    rng = np.random.default_rng(2)
    xs = np.concatenate(
        [rng.uniform(-span, span, 4000), np.arange(-16, 17) * 0.25 * math.pi, [0.0, -0.0]]
    )
    for x in xs:
        s, c = sincos(x)
        assert abs(s - math.sin(x)) <= ULP2
        assert abs(c - math.cos(x)) <= ULP2
