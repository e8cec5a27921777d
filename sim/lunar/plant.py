"""Seed 001's plant and actuators, batched over cases (arrays with the case index last).

Translational dynamics (1) in polar form with the mass flow (1g); thrust vector (2) from the
attitude; attitude dynamics (27) written as Euler's equation for the inertial rate (the paper's
C_r, n_r form, claim attitude-27b), scalar-first quaternion kinematics; thrust saturation (24),
failure (26), torque saturation (28), the disturbance torque of Section 5.
"""

from __future__ import annotations

import numpy as np
from lgw.theory.lunar import parameters as P

# --- quaternions (scalar first, Hamilton product), arrays of shape (4, N) -----------------


def qmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    a0, av = a[0], a[1:]
    b0, bv = b[0], b[1:]
    return np.concatenate([(a0 * b0 - np.sum(av * bv, axis=0))[None],
                           a0 * bv + b0 * av + cross(av, bv)], axis=0)


def qconj(a: np.ndarray) -> np.ndarray:
    return np.concatenate([a[:1], -a[1:]], axis=0)


def dcm(q: np.ndarray) -> np.ndarray:
    """L(q), shape (3, 3, N): coordinates in the from-frame to the to-frame, v_to = L v_from
    (the same formula as ``lgw.theory.lunar.quaternion.dcm``)."""
    q0, v = q[0], q[1:]
    n = q0 * q0 - np.sum(v * v, axis=0)
    L = 2.0 * v[:, None, :] * v[None, :, :]
    for i in range(3):
        L[i, i] += n
    S = skew(v)
    return L - 2.0 * q0 * S


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for (3, N) arrays (faster than np.cross for small N)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


def skew(a: np.ndarray) -> np.ndarray:
    z = np.zeros_like(a[0])
    return np.array([[z, -a[2], a[1]], [a[2], z, -a[0]], [-a[1], a[0], z]])


def matvec(M: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.einsum("ijn,jn->in", M, v)


def quat_from_yaw_pitch(psi: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Q from F_H to F_B for a 3-2-1 (yaw psi, pitch theta, roll 0) rotation."""
    cy, sy, cp, sp_ = np.cos(psi / 2), np.sin(psi / 2), np.cos(theta / 2), np.sin(theta / 2)
    return np.array([cy * cp, -sy * sp_, cy * sp_, sy * cp])


def thrust_axis(Q: np.ndarray) -> np.ndarray:
    """The unit vector n in F_H with thrust = -T n (2): the body x axis, n = L_BH^T e_x.

    With psi_B the yaw and theta = -alpha_B the pitch of a 3-2-1 sequence, n = [cos a cos psi,
    cos a sin psi, sin a] as (2) needs: alpha_B is the elevation of the thrust-reversal axis."""
    return dcm(Q)[0]


# --- translational dynamics (1) -------------------------------------------------------------


def translational_rhs(y: np.ndarray, F: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Seed 001 (1a)-(1g); y = [r, phi, lon, u, v, w, m] (7, N), F = [Tx, Ty, Tz] (N) in F_H,
    T = |F| (N) for the mass flow."""
    r, phi, _, u, v, w, m = y
    tp = np.tan(phi)
    return np.array([-w, u / r, v / (r * np.cos(phi)),
                     -v * v / r * tp + u * w / r + F[0] / m,
                     u * v / r * tp + v * w / r + F[1] / m,
                     -(u * u + v * v) / r + P.MU_MOON / r ** 2 + F[2] / m,
                     -T / (P.ISP * P.G0)])


def omega_hp(y: np.ndarray, ydot: np.ndarray | None = None):
    """omega_HP^H = [lon' cos(phi), -phi', -lon' sin(phi)] = [v/r, -u/r, -v tan(phi)/r] and, given
    y', its time derivative (rad/s, rad/s^2)."""
    r, phi, _, u, v, _, _ = y
    w_hp = np.array([v / r, -u / r, -v * np.tan(phi) / r])
    if ydot is None:
        return w_hp, None
    rd, phid, _, ud, vd = ydot[:5]
    sec2 = 1.0 / np.cos(phi) ** 2
    dw = np.array([vd / r - v * rd / r ** 2, -ud / r + u * rd / r ** 2,
                   -(vd * np.tan(phi) + v * sec2 * phid) / r + v * np.tan(phi) * rd / r ** 2])
    return w_hp, dw


def attitude_rates(Q, w, J, a, adot_part, M):
    """Q' = Q (x) [0, w]/2 and w' from Euler's equation for Omega = w + a (a = L_BH w_HP):
    J Omega' = -Omega x J Omega + M, Omega' = w' + L_BH w_HP' - S(w) a  (claim attitude-27b).
    ``adot_part`` is L_BH w_HP'; J is (3, N)."""
    Om = w + a
    JOm = J * Om
    wdot = (-cross(Om, JOm) + M) / J - adot_part + cross(w, a)
    Qdot = 0.5 * qmul(Q, np.concatenate([np.zeros_like(w[:1]), w], axis=0))
    return Qdot, wdot


# --- actuators --------------------------------------------------------------------------


SAT_READINGS = ("commanded", "nominal")
FAILURES = ("atan", "step", "none")


def saturate_thrust(uco: np.ndarray, unorm: np.ndarray, Tmax: float,
                    reading: str = "commanded") -> np.ndarray:
    """Seed 001 (24).  reading "commanded": T := |u_co + u_norm| (the commanded thrust
    magnitude), so that the saturated total thrust has magnitude T_max (claim sat-24);
    reading "nominal": T := T_d = |u_norm| (the printed symbol read as the nominal thrust; it
    does not limit the thrust, kept for comparison)."""
    tot = uco + unorm
    mag = np.linalg.norm(tot, axis=0)
    T = mag if reading == "commanded" else np.linalg.norm(unorm, axis=0)
    over = mag >= Tmax
    return np.where(over, tot * Tmax / np.where(T > 0, T, 1.0) - unorm, uco)


def failure_factor(t: float, tf: float, kind: str = "atan", Ta: float = P.T_A,
                   t_fail: float | None = None) -> float:
    """Thrust fraction of seed 001 (26) ("atan", as printed: (1+Ta)/2 (1 - (2/pi) (1-Ta)/(1+Ta)
    atan(2t - tf)) with t in seconds), a step to Ta at t_fail (default tf/2), or none."""
    if kind == "none":
        return 1.0
    if kind == "step":
        return 1.0 if t <= (tf / 2 if t_fail is None else t_fail) else Ta
    tc = tf if t_fail is None else 2.0 * t_fail
    return (1 + Ta) / 2 * (1 - 2 / np.pi * (1 - Ta) / (1 + Ta) * np.arctan(2 * t - tc))


def saturate_torque(Mc: np.ndarray, Mmax: float = P.M_MAX) -> np.ndarray:
    """Seed 001 (28): per axis, sign(Mc) Mmax when |Mc| >= Mmax."""
    return np.clip(Mc, -Mmax, Mmax)


def disturbance_torque(t: float, amp: float = P.DIST_TORQUE_AMP) -> np.ndarray:
    """d_M = amp [cos t, sin t, cos 2t] N m (seed 001 Section 5), shape (3, 1)."""
    return amp * np.array([[np.cos(t)], [np.sin(t)], [np.cos(2 * t)]])
