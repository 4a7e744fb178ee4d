"""The flight alone, as it is usually written: the baselines mcrun's kernel is measured against.

Three implementations of the same 3D flight (physics.md, "Flight"; no wind, which the
benchmark scenario has none of), each returning the carry (m, along the target line) of every
shot:

- ``solve_ivp_carry``: scipy's ``solve_ivp`` per shot, RK45 at its default tolerances, a NumPy
  right-hand side and a terminal ground event: what most people write first;
- ``numpy_carry``: every shot at once, vectorised classical RK4 at a fixed step, a mask for the
  shots that have landed;
- ``numba_carry``: a plain ``@njit`` RK4 loop, one shot per ``prange`` iteration.

The aerodynamic coefficients are a quadratic row of ``mcrun.physics.aero.QUADRATIC_COEFFICIENTS``
(``trackman2019`` for the benchmarks): C_D = a0 + a1 S + a2 S^2, C_L = b0 + b1 S + b2 S^2,
S = r w / |v| clipped at s_max. The RK4 baselines locate the landing by linear interpolation of
z inside the last step (0.1 mm at dt = 10 ms, where the path bends over a radius of ~80 m).

``FlightSet.from_inputs`` takes the shots from rows of the kernel's inputs
(``mcrun.engine.schema.INPUT_FIELDS``), so that every implementation flies exactly the same shots.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit, prange
from scipy.integrate import solve_ivp

from mcrun.engine.schema import COLUMN
from mcrun.physics.aero import MODELS, QUADRATIC_COEFFICIENTS

R = 0.021335  # ball radius (m)
M = 0.04593  # ball mass (kg)
G = 9.80665
AREA = math.pi * R * R
SPIN_DECAY = 2.0e-5  # dw/dt = -SPIN_DECAY |v| / r w
DT_S = 0.01
MAX_TIME_S = 60.0


class FlightSet(NamedTuple):
    """N shots in structure-of-arrays form, core frame (x target, y LEFT, z up)."""

    v0: np.ndarray  # (N, 3) launch velocity, m/s
    axis: np.ndarray  # (N, 3) unit spin axis
    spin: np.ndarray  # (N,) rad/s
    k: np.ndarray  # (N,) rho A / (2 m), 1/m
    cd_scale: np.ndarray  # (N,)
    cl_scale: np.ndarray  # (N,)
    coefficients: np.ndarray  # (7,) a0, a1, a2, b0, b1, b2, s_max

    @classmethod
    def from_inputs(cls, inputs, model="trackman2019"):
        """The flights of the rows of ``inputs`` (n, N_INPUT), which must have no wind."""
        col = {name: inputs[:, k] for name, k in COLUMN.items()}
        if np.any(col["wind_x_mps"] != 0.0) or np.any(col["wind_right_mps"] != 0.0):
            raise ValueError("the baselines fly without wind")
        elevation = col["launch_angle_rad"]
        azimuth = col["azimuth_rad"]
        tilt = col["spin_axis_rad"]
        v_hat = np.stack(
            [
                np.cos(elevation) * np.cos(azimuth),
                -np.cos(elevation) * np.sin(azimuth),
                np.sin(elevation),
            ],
            axis=1,
        )
        # Backspin about v x z, tilted about v by the spin axis (positive curves right).
        b = np.cross(v_hat, [0.0, 0.0, 1.0])
        b /= np.linalg.norm(b, axis=1)[:, None]
        up = np.cross(b, v_hat)
        axis = np.cos(tilt)[:, None] * b - np.sin(tilt)[:, None] * up
        return cls(
            v0=col["ball_speed_mps"][:, None] * v_hat,
            axis=np.ascontiguousarray(axis),
            spin=np.ascontiguousarray(col["spin_radps"]),
            k=0.5 * col["air_density_kgpm3"] * AREA / M,
            cd_scale=np.ascontiguousarray(col["cd_scale"]),
            cl_scale=np.ascontiguousarray(col["cl_scale"]),
            coefficients=QUADRATIC_COEFFICIENTS[MODELS[model]][:7].copy(),
        )

    def __len__(self):
        return self.spin.shape[0]

    def take(self, index):
        """The shots ``index`` (a slice or an index array) as a new FlightSet."""
        return FlightSet(
            self.v0[index],
            self.axis[index],
            self.spin[index],
            self.k[index],
            self.cd_scale[index],
            self.cl_scale[index],
            self.coefficients,
        )


# --- scipy solve_ivp, one shot at a time -----------------------------------------------------


def _solve_ivp_one(v0, axis, spin, k, cd_scale, cl_scale, coefficients, rtol, atol):
    a0, a1, a2, b0, b1, b2, s_max = coefficients

    def rhs(t, s):
        v = s[3:6]
        speed = np.linalg.norm(v)
        ratio = min(R * s[6] / speed, s_max)
        cd = cd_scale * (a0 + a1 * ratio + a2 * ratio**2)
        cl = cl_scale * (b0 + b1 * ratio + b2 * ratio**2)
        lift = np.cross(axis, v)
        a = -k * cd * speed * v + k * cl * speed**2 * lift / np.linalg.norm(lift)
        a[2] -= G
        return np.concatenate([v, a, [-SPIN_DECAY * speed / R * s[6]]])

    def ground(t, s):
        return s[2]

    ground.terminal = True
    ground.direction = -1.0
    y0 = np.concatenate([[0.0, 0.0, 0.0], v0, [spin]])
    sol = solve_ivp(rhs, (0.0, MAX_TIME_S), y0, rtol=rtol, atol=atol, events=ground)
    return sol.y_events[0][0][0] if sol.status == 1 else np.nan


def solve_ivp_carry(shots, rtol=1e-3, atol=1e-6):
    """Carry of each shot by ``solve_ivp`` with RK45 (scipy's default tolerances, unless given)."""
    return np.array(
        [
            _solve_ivp_one(
                shots.v0[i],
                shots.axis[i],
                shots.spin[i],
                shots.k[i],
                shots.cd_scale[i],
                shots.cl_scale[i],
                shots.coefficients,
                rtol,
                atol,
            )
            for i in range(len(shots))
        ]
    )


# --- NumPy, all shots at once ----------------------------------------------------------------


def _numpy_derivatives(vx, vy, vz, w, shots):
    a0, a1, a2, b0, b1, b2, s_max = shots.coefficients
    ax, ay, az = shots.axis.T
    speed = np.sqrt(vx * vx + vy * vy + vz * vz)
    ratio = np.minimum(R * w / speed, s_max)
    cd = shots.cd_scale * (a0 + ratio * (a1 + ratio * a2))
    cl = shots.cl_scale * (b0 + ratio * (b1 + ratio * b2))
    lx = ay * vz - az * vy
    ly = az * vx - ax * vz
    lz = ax * vy - ay * vx
    drag = shots.k * cd * speed
    lift = shots.k * cl * speed * speed / np.sqrt(lx * lx + ly * ly + lz * lz)
    return (
        -drag * vx + lift * lx,
        -drag * vy + lift * ly,
        -drag * vz + lift * lz - G,
        -SPIN_DECAY / R * speed * w,
    )


def numpy_carry(shots, dt=DT_S):
    """Carry of every shot by vectorised RK4 at step ``dt``; landed shots are masked out."""
    n = len(shots)
    x = np.zeros(n)
    y = np.zeros(n)
    z = np.zeros(n)
    vx, vy, vz = (np.array(c) for c in shots.v0.T)
    w = shots.spin.copy()
    carry = np.full(n, np.nan)
    flying = np.ones(n, dtype=bool)
    h = 0.5 * dt
    t = 0.0
    while flying.any() and t < MAX_TIME_S:
        a1x, a1y, a1z, s1 = _numpy_derivatives(vx, vy, vz, w, shots)
        v2x, v2y, v2z = vx + h * a1x, vy + h * a1y, vz + h * a1z
        a2x, a2y, a2z, s2 = _numpy_derivatives(v2x, v2y, v2z, w + h * s1, shots)
        v3x, v3y, v3z = vx + h * a2x, vy + h * a2y, vz + h * a2z
        a3x, a3y, a3z, s3 = _numpy_derivatives(v3x, v3y, v3z, w + h * s2, shots)
        v4x, v4y, v4z = vx + dt * a3x, vy + dt * a3y, vz + dt * a3z
        a4x, a4y, a4z, s4 = _numpy_derivatives(v4x, v4y, v4z, w + dt * s3, shots)
        c = dt / 6.0
        x1 = x + c * (vx + 2.0 * v2x + 2.0 * v3x + v4x)
        z1 = z + c * (vz + 2.0 * v2z + 2.0 * v3z + v4z)
        landed = flying & (z1 < 0.0)
        fraction = z[landed] / (z[landed] - z1[landed])
        carry[landed] = x[landed] + fraction * (x1[landed] - x[landed])
        flying &= ~landed
        # Shots on the ground keep their last state.
        x = np.where(flying, x1, x)
        y = np.where(flying, y + c * (vy + 2.0 * v2y + 2.0 * v3y + v4y), y)
        z = np.where(flying, z1, z)
        vx = np.where(flying, vx + c * (a1x + 2.0 * a2x + 2.0 * a3x + a4x), vx)
        vy = np.where(flying, vy + c * (a1y + 2.0 * a2y + 2.0 * a3y + a4y), vy)
        vz = np.where(flying, vz + c * (a1z + 2.0 * a2z + 2.0 * a3z + a4z), vz)
        w = np.where(flying, w + c * (s1 + 2.0 * s2 + 2.0 * s3 + s4), w)
        t += dt
    return carry


# --- Numba, one shot per prange iteration ----------------------------------------------------


@njit(cache=True)
def _derivatives(vx, vy, vz, w, ax, ay, az, k, cd_scale, cl_scale, c):
    speed = math.sqrt(vx * vx + vy * vy + vz * vz)
    ratio = min(R * w / speed, c[6])
    cd = cd_scale * (c[0] + ratio * (c[1] + ratio * c[2]))
    cl = cl_scale * (c[3] + ratio * (c[4] + ratio * c[5]))
    lx = ay * vz - az * vy
    ly = az * vx - ax * vz
    lz = ax * vy - ay * vx
    drag = k * cd * speed
    lift = k * cl * speed * speed / math.sqrt(lx * lx + ly * ly + lz * lz)
    return (
        -drag * vx + lift * lx,
        -drag * vy + lift * ly,
        -drag * vz + lift * lz - G,
        -SPIN_DECAY / R * speed * w,
    )


@njit(cache=True)
def _numba_one(v0, axis, w, k, cd_scale, cl_scale, c, dt):
    ax, ay, az = axis[0], axis[1], axis[2]
    x = 0.0
    y = 0.0
    z = 0.0
    vx, vy, vz = v0[0], v0[1], v0[2]
    h = 0.5 * dt
    t = 0.0
    while t < MAX_TIME_S:
        a1x, a1y, a1z, s1 = _derivatives(vx, vy, vz, w, ax, ay, az, k, cd_scale, cl_scale, c)
        v2x, v2y, v2z = vx + h * a1x, vy + h * a1y, vz + h * a1z
        a2x, a2y, a2z, s2 = _derivatives(
            v2x, v2y, v2z, w + h * s1, ax, ay, az, k, cd_scale, cl_scale, c
        )
        v3x, v3y, v3z = vx + h * a2x, vy + h * a2y, vz + h * a2z
        a3x, a3y, a3z, s3 = _derivatives(
            v3x, v3y, v3z, w + h * s2, ax, ay, az, k, cd_scale, cl_scale, c
        )
        v4x, v4y, v4z = vx + dt * a3x, vy + dt * a3y, vz + dt * a3z
        a4x, a4y, a4z, s4 = _derivatives(
            v4x, v4y, v4z, w + dt * s3, ax, ay, az, k, cd_scale, cl_scale, c
        )
        q = dt / 6.0
        x1 = x + q * (vx + 2.0 * v2x + 2.0 * v3x + v4x)
        z1 = z + q * (vz + 2.0 * v2z + 2.0 * v3z + v4z)
        if z1 < 0.0:
            return x + z / (z - z1) * (x1 - x)
        x = x1
        y += q * (vy + 2.0 * v2y + 2.0 * v3y + v4y)
        z = z1
        vx += q * (a1x + 2.0 * a2x + 2.0 * a3x + a4x)
        vy += q * (a1y + 2.0 * a2y + 2.0 * a3y + a4y)
        vz += q * (a1z + 2.0 * a2z + 2.0 * a3z + a4z)
        w += q * (s1 + 2.0 * s2 + 2.0 * s3 + s4)
        t += dt
    return math.nan


@njit(parallel=True, cache=True)
def _numba_all(v0, axis, spin, k, cd_scale, cl_scale, c, dt, carry):
    for i in prange(spin.shape[0]):
        carry[i] = _numba_one(v0[i], axis[i], spin[i], k[i], cd_scale[i], cl_scale[i], c, dt)


def numba_carry(shots, dt=DT_S):
    """Carry of every shot by an njit RK4 loop at step ``dt``, one shot per prange iteration."""
    carry = np.empty(len(shots))
    _numba_all(
        shots.v0,
        shots.axis,
        shots.spin,
        shots.k,
        shots.cd_scale,
        shots.cl_scale,
        shots.coefficients,
        dt,
        carry,
    )
    return carry
