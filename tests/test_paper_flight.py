"""Penner (2002) section 3: the four landings the paper computes from its launches.

Flown with the ``penner2002`` aerodynamic model in Penner's air (1.204 kg/m^3). Tolerances of
targets.md: 5 % on the landing speed, 2.5 deg on the landing angle (from the vertical), 2 % on
the landing spin.
"""

import pytest

from mcrun.api import simulate

PENNER_AIR = {"aero_model": "penner2002", "air_density_kgpm3": 1.204}

# launch (speed m/s, angle above horizontal deg, backspin rad/s) -> landing (speed m/s,
# angle from the vertical deg, backspin rad/s)
FLIGHTS = {
    "driver 35 m/s": ((48.8, 10.7, 253.0), (26.8, 68.0, 224.0)),
    "driver 55 m/s": ((74.3, 10.7, 397.0), (26.2, 46.2, 315.0)),
    "1-iron": ((56.6, 13.8, 372.0), (24.7, 51.9, 313.0)),
    "9-iron": ((42.5, 35.4, 915.0), (23.8, 34.0, 809.0)),
}


@pytest.mark.parametrize("name", FLIGHTS)
def test_landing(name):
    """Landing speed, angle and spin of the paper's shot."""
    (speed, angle, spin), (land_speed, land_angle, land_spin) = FLIGHTS[name]
    out = simulate(
        ball_speed_mps=speed, launch_angle_deg=angle, spin_radps=spin, **PENNER_AIR
    ).outcome
    assert out["status"] == 0
    assert out["landing_speed_mps"] == pytest.approx(land_speed, rel=0.05)
    assert out["landing_angle_deg"] == pytest.approx(land_angle, abs=2.5)
    assert out["landing_spin_radps"] == pytest.approx(land_spin, rel=0.02)


def test_landing_speed_nearly_constant_for_drives():
    """Section 3.1: "the landing speed of the golf ball was approximately constant" while the
    impact angle "varied greatly" (68.0 to 46.2 deg, 21.8 deg apart; 2 x 2.5 deg tolerance):
    harder drives land steeper."""
    outs = [
        simulate(ball_speed_mps=s, launch_angle_deg=10.7, spin_radps=w, **PENNER_AIR).outcome
        for s, w in ((48.8, 253.0), (74.3, 397.0))
    ]
    assert outs[1]["landing_speed_mps"] == pytest.approx(outs[0]["landing_speed_mps"], rel=0.05)
    spread = outs[0]["landing_angle_deg"] - outs[1]["landing_angle_deg"]
    assert spread == pytest.approx(68.0 - 46.2, abs=5.0)
