"""The general system (5) of seed 001 in its orbit-instance form, flown with the generated law
(7), (8), (11) under a disturbance of known constant norm: where the hypotheses of (13) hold
exactly, so that V2 (12) with D = ||d|| must not increase and (18)-(21) must bound the measured
L2 norms (``tests/lunar/test_properties.py``).

    x1' = a_h x2 (x1 = e_h scalar),  x2' = d(t) + B0 u,  B0 = -I/m (m constant),
    d(t) = D [cos(w t), sin(w t), 0]  (||d|| = D for all t),
    u = clip(u_c, -u_max, u_max) per axis (du = u - u_c; u_max = inf: no saturation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from lgw.sim.lunar import laws


@dataclass(frozen=True)
class GeneralCase:
    m: float = 5000.0  # kg
    D: float = 0.5  # m/s^2, ||d||
    w: float = 0.7  # rad/s
    u_max: float = np.inf  # N per axis
    D_assumed: float | None = None  # the D in V2 (12); None: the true ||d|| (hypothesis holds)


def rhs(t, X, g, case: GeneralCase, outputs=False):
    """X = [x1, x2 (3), lambda1, lambda2 (3), d0e] (9, N)."""
    x1, x2, l1, l2, d0e = X[0], X[1:4], X[4], X[5:8], X[8]
    m = np.full_like(x1, case.m)
    uc, z2, nz, v2p = laws.orbit_command(x1, x2, l1, l2, d0e, m, g)
    u = np.clip(uc, -case.u_max, case.u_max)
    du = u - uc
    d = case.D * np.array([np.cos(case.w * t), np.sin(case.w * t), 0.0])[:, None]
    B0du = -du / case.m
    F1 = g["K1"][2, 2]
    Xd = np.concatenate([(-x2[2])[None], d + (-u / case.m),
                         (-F1 * l1 - l2[2])[None],
                         -np.einsum("ijn,jn->in", g["F2"], l2) + np.array([0 * l1, 0 * l1, l1])
                         + B0du, (g["q"] * nz)[None]])
    if not outputs:
        return Xd
    Da = case.D if case.D_assumed is None else case.D_assumed
    V2 = v2p + (d0e - Da) ** 2 / (2 * g["q"])
    return Xd, {"V2": V2, "z1": x1 - l1, "z2": z2, "B0du": B0du, "l1": l1, "l2": l2,
                "x1": x1, "x2": x2, "d0e": d0e, "nz": nz}


def fly(X0, g, case: GeneralCase, t_end: float, dt: float):
    """RK4 of all cases; returns t (K,) and the outputs at each step."""
    n = int(round(t_end / dt))
    X = X0.copy()
    ts, outs = [], []
    for k in range(n + 1):
        t = k * dt
        _, o = rhs(t, X, g, case, outputs=True)
        ts.append(t)
        outs.append(o)
        if k == n:
            break
        k1 = rhs(t, X, g, case)
        k2 = rhs(t + dt / 2, X + dt / 2 * k1, g, case)
        k3 = rhs(t + dt / 2, X + dt / 2 * k2, g, case)
        k4 = rhs(t + dt, X + dt * k3, g, case)
        X = X + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return np.array(ts), {k: np.array([o[k] for o in outs]) for k in outs[0]}
