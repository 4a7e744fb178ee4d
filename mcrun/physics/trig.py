"""The arctangent, sine and cosine the kernel needs, as branch-free polynomials.

The bounce runs in loops over many shots at once; the C library's atan2, sin and cos are calls
the compiler cannot vectorise, these are plain arithmetic it can (and cheaper calls where they
are not vectorised: the launch). Rational and polynomial approximations of Cephes (S. L.
Moshier, "Methods and programs for mathematical functions", 1989; atan.c and sin.c), accurate
to about 1e-16 relative: the angles of the bounce lie in [0, pi/2]; ``sincos`` reduces any
angle of magnitude below about 1e9 rad to [-pi/4, pi/4] first.
"""

import math

from numba import njit

_ATAN_P = (
    -8.750608600031904122785e-1,
    -1.615753718733365076637e1,
    -7.500855792314704667340e1,
    -1.228866684490136173410e2,
    -6.485021904942025371773e1,
)
_ATAN_Q = (
    2.485846490142306297962e1,
    1.650270098316988542046e2,
    4.328810604912902668951e2,
    4.853903996359136964868e2,
    1.945506571482613964425e2,
)
_SIN = (
    1.58962301576546568060e-10,
    -2.50507477628578072866e-8,
    2.75573136213857245213e-6,
    -1.98412698295895385996e-4,
    8.33333333332211858878e-3,
    -1.66666666666666307295e-1,
)
_COS = (
    -1.13585365213876817300e-11,
    2.08757008419747316778e-9,
    -2.75573141792967388112e-7,
    2.48015872888517045348e-5,
    -1.38888888888730564116e-3,
    4.16666666666665929218e-2,
)


@njit(cache=True, error_model="numpy", inline="always")
def atan2_first_quadrant(y, x):
    """atan2(y, x) for y >= 0, x >= 0 (not both zero), in [0, pi/2]."""
    small = min(x, y)
    big = max(x, y)
    # atan(a) of a = small / big in [0, 1]. Cephes: above a = 0.66, atan(a) = pi/4 +
    # atan((a - 1) / (a + 1)), here (small - big) / (small + big): one division either way.
    reduced = small > 0.66 * big
    u = (small - big if reduced else small) / (small + big if reduced else big)
    z = u * u
    p = (((_ATAN_P[0] * z + _ATAN_P[1]) * z + _ATAN_P[2]) * z + _ATAN_P[3]) * z + _ATAN_P[4]
    q = ((((z + _ATAN_Q[0]) * z + _ATAN_Q[1]) * z + _ATAN_Q[2]) * z + _ATAN_Q[3]) * z + _ATAN_Q[4]
    angle = u + u * z * p / q
    if reduced:
        angle += 0.25 * math.pi
    return 0.5 * math.pi - angle if y > x else angle


@njit(cache=True, error_model="numpy", inline="always")
def sincos_first_quadrant(theta):
    """(sin theta, cos theta) for theta in [0, pi/2]."""
    # Cephes: the polynomials hold on [0, pi/4]; above, swap sine and cosine of pi/2 - theta.
    upper = theta > 0.25 * math.pi
    s, c = _sincos_reduced(0.5 * math.pi - theta if upper else theta)
    return (c, s) if upper else (s, c)


@njit(cache=True, error_model="numpy", inline="always")
def _sincos_reduced(r):
    """(sin r, cos r) for |r| <= pi/4: Cephes' polynomials."""
    z = r * r
    s = r + r * z * (
        ((((_SIN[0] * z + _SIN[1]) * z + _SIN[2]) * z + _SIN[3]) * z + _SIN[4]) * z + _SIN[5]
    )
    c = (
        1.0
        - 0.5 * z
        + z
        * z
        * (((((_COS[0] * z + _COS[1]) * z + _COS[2]) * z + _COS[3]) * z + _COS[4]) * z + _COS[5])
    )
    return s, c


# Cephes sin.c: pi/4 in three parts (Cody-Waite), and 4/pi.
_PI4_PARTS = (7.85398125648498535156e-1, 3.77489470793079817668e-8, 2.69515142907905952645e-15)
_FOUR_OVER_PI = 1.27323954473516268615


@njit(cache=True, error_model="numpy", inline="always")
def sincos(x):
    """(sin x, cos x) for |x| below about 1e9."""
    a = abs(x)
    j = int(a * _FOUR_OVER_PI)  # the octant; made even, a = j pi/4 + r with |r| <= pi/4
    j += j & 1
    y = float(j)
    s, c = _sincos_reduced(((a - y * _PI4_PARTS[0]) - y * _PI4_PARTS[1]) - y * _PI4_PARTS[2])
    # Quarter turns q = j / 2 (mod 4): (sin, cos)(q pi/2 + r) = (s, c), (c, -s), (-s, -c), (-c, s).
    q = j & 6
    swap = (q == 2) | (q == 6)
    sine = c if swap else s
    cosine = s if swap else c
    sine = -sine if q >= 4 else sine
    cosine = -cosine if (q == 2) | (q == 4) else cosine
    return (-sine if x < 0.0 else sine), cosine
