"""Physical constants of the ball, the air and the ground: one source of truth, in SI.

Ball: the USGA/R&A limits (diameter 42.67 mm, mass 45.93 g), treated as a uniform sphere as
Penner (2002) and Daish (1972) do.
"""

import math

BALL_RADIUS_M = 0.021335
BALL_MASS_KG = 0.04593
BALL_AREA_M2 = math.pi * BALL_RADIUS_M**2
# Uniform sphere, I = (2/5) m r^2 (Penner 2002, section 2).
BALL_INERTIA_FACTOR = 0.4

G_MPS2 = 9.80665

# Spin decay, Smits and Smith (1994) as used by Penner (2001): dw/dt = -k |v_rel| / r * w.
SPIN_DECAY_K = 2.0e-5

# Standard conditions. Penner flew his balls in air of 1.204 kg/m^3 (20 C, sea level, dry).
STANDARD_TEMPERATURE_K = 293.15
STANDARD_PRESSURE_PA = 101325.0
STANDARD_HUMIDITY = 0.5
# The height at which a wind speed is given unless said otherwise: a weather station's 10 m.
STANDARD_WIND_HEIGHT_M = 10.0

DEG = math.pi / 180.0
