"""Penner (2002) section 3 (club model of Penner 2001): every launch the paper quotes, to 1 %.

Drives: club-head mass 0.200 kg, dynamic loft 13.3 deg, 35 and 55 m/s. Irons: 0.250 kg at
40 m/s, loft 17 deg (1-iron) and 46 deg (9-iron). Launch angles above the horizontal.
"""

import math

import pytest

from mcrun.api import simulate
from mcrun.physics.launch import launch_from_club

REL = 0.01

# (club speed m/s, club mass kg, loft deg) -> (ball speed m/s, launch angle deg, spin rad/s)
LAUNCHES = {
    "driver 35 m/s": ((35.0, 0.200, 13.3), (48.8, 10.7, 253.0)),
    "driver 55 m/s": ((55.0, 0.200, 13.3), (74.3, 10.7, 397.0)),
    "1-iron": ((40.0, 0.250, 17.0), (56.6, 13.8, 372.0)),
    "9-iron": ((40.0, 0.250, 46.0), (42.5, 35.4, 915.0)),
}


@pytest.mark.parametrize("name", LAUNCHES)
def test_launch_from_club(name):
    """The club-ball collision gives the paper's ball speed, launch angle and backspin."""
    (club_speed, club_mass, loft), (speed, angle, spin) = LAUNCHES[name]
    got_speed, got_angle, got_spin = launch_from_club(club_speed, club_mass, math.radians(loft))
    assert got_speed == pytest.approx(speed, rel=REL)
    assert math.degrees(got_angle) == pytest.approx(angle, rel=REL)
    assert got_spin == pytest.approx(spin, rel=REL)


@pytest.mark.parametrize("name", LAUNCHES)
def test_launch_through_the_api(name):
    """``simulate(club_speed_mps=..., club_mass_kg=..., loft_deg=...)`` reports the same launch
    in its outcome."""
    (club_speed, club_mass, loft), (speed, angle, spin) = LAUNCHES[name]
    out = simulate(club_speed_mps=club_speed, club_mass_kg=club_mass, loft_deg=loft).outcome
    assert out["launch_speed_mps"] == pytest.approx(speed, rel=REL)
    assert out["launch_angle_deg"] == pytest.approx(angle, rel=REL)
    assert out["launch_spin_radps"] == pytest.approx(spin, rel=REL)


def test_driver_launch_angle_nearly_constant():
    """Drives from 35 to 55 m/s leave "at a relatively constant launch angle of approximately
    10.7 deg" (section 3.1): within 1 % of 10.7 deg all the way."""
    for club_speed in (35.0, 40.0, 45.0, 50.0, 55.0):
        _, angle, _ = launch_from_club(club_speed, 0.200, math.radians(13.3))
        assert math.degrees(angle) == pytest.approx(10.7, rel=REL)
