"""Air: density from temperature, pressure (or altitude) and humidity; kinematic viscosity.

All functions accept floats or NumPy arrays (the Monte Carlo engine samples weather per shot).
"""

import numpy as np

from mcrun.physics.constants import STANDARD_HUMIDITY, STANDARD_PRESSURE_PA, STANDARD_TEMPERATURE_K

R_DRY_J_PER_KG_K = 287.058
R_VAPOUR_J_PER_KG_K = 461.495


def saturation_vapour_pressure_pa(temperature_k):
    """Saturation vapour pressure over water, Magnus-Tetens form (Alduchov and Eskridge 1996)."""
    t_c = np.asarray(temperature_k, dtype=float) - 273.15
    return 610.94 * np.exp(17.625 * t_c / (t_c + 243.04))


def pressure_at_altitude_pa(altitude_m):
    """Pressure of the ICAO standard atmosphere at a geometric altitude (troposphere, < 11 km)."""
    return (
        STANDARD_PRESSURE_PA * (1.0 - 2.25577e-5 * np.asarray(altitude_m, dtype=float)) ** 5.25588
    )


def air_density_kgpm3(
    temperature_k=STANDARD_TEMPERATURE_K,
    pressure_pa=STANDARD_PRESSURE_PA,
    relative_humidity=STANDARD_HUMIDITY,
):
    """Density of moist air: ideal gas for the dry air plus the water vapour (Dalton's law).

    20 C, 101325 Pa and dry air give 1.2041 kg/m^3, the density Penner flew his balls in.
    """
    t = np.asarray(temperature_k, dtype=float)
    p_vapour = np.asarray(relative_humidity, dtype=float) * saturation_vapour_pressure_pa(t)
    rho = (pressure_pa - p_vapour) / (R_DRY_J_PER_KG_K * t) + p_vapour / (R_VAPOUR_J_PER_KG_K * t)
    return float(rho) if np.ndim(rho) == 0 else rho


def dynamic_viscosity_pas(temperature_k=STANDARD_TEMPERATURE_K):
    """Dynamic viscosity of air, Sutherland's law (1.81e-5 Pa s at 20 C)."""
    t = np.asarray(temperature_k, dtype=float)
    mu = 1.716e-5 * (t / 273.15) ** 1.5 * (273.15 + 110.4) / (t + 110.4)
    return float(mu) if np.ndim(mu) == 0 else mu


def kinematic_viscosity_m2ps(temperature_k, density_kgpm3):
    """Kinematic viscosity nu = mu / rho, for the Reynolds number Re = |v| 2r / nu."""
    return dynamic_viscosity_pas(temperature_k) / density_kgpm3
