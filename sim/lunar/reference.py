"""The reference descent of seed 001 (3)-(4): linear-tangent steering on the simplified model,
solved as a boundary-value problem from Section 5's boundary conditions.

Simplified model (seed 001, text above (4)): (1) without the small terms -v^2 tan(phi)/r,
u w/r, u v tan(phi)/r, v w/r, keeping the centrifugal -(u^2 + v^2)/r and the gravity mu/r^2 of
(1f) (they are of the size of the thrust acceleration here), constant thrust T_d and the mass
flow (1g):

    r' = -w,  u' = Tx/m,  v' = Ty/m,  w' = -(u^2 + v^2)/r + mu/r^2 + Tz/m,  m' = -T_d/(Isp g0)

with (2) and the steering (3): tan(psi_B) = a1, tan(alpha_B) = a2 t + a3.  Unknowns a1, a2, a3
and the time of flight t_f; boundary conditions: r(0) = R + h0, V(0) = V0, m(0) = m0 and
r(t_f) = R + h_f, V(t_f) = 0 (four terminal conditions for four unknowns).  The paper's closed
form (4) is a polynomial approximation of this solution; the workbench uses the BVP solution
itself (scipy ``solve_bvp``, dense cubic output) as the reference.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
from lgw.theory.lunar import parameters as P
from scipy.integrate import solve_bvp, solve_ivp
from scipy.optimize import fsolve


def simplified_rhs(t, y, a1, a2, a3, T=P.T_NOMINAL):
    """The simplified model above, y = [r, u, v, w, m] (arrays broadcast)."""
    r, u, v, w, m = y
    psi = np.arctan(a1)
    alpha = np.arctan(a2 * t + a3)
    Tx = -T * np.cos(alpha) * np.cos(psi)
    Ty = -T * np.cos(alpha) * np.sin(psi)
    Tz = -T * np.sin(alpha)
    return np.array([-w, Tx / m, Ty / m, -(u * u + v * v) / r + P.MU_MOON / r ** 2 + Tz / m,
                     -T / (P.ISP * P.G0) * np.ones_like(r)])


@dataclass(frozen=True)
class Reference:
    a1: float
    a2: float  # 1/s
    a3: float
    tf: float  # s
    sol: object  # solve_bvp's dense solution in tau = t / tf
    bvp_max_residual: float
    shooting: dict  # the single-shooting solution used as the initial guess (cross-check)
    # the same dense solution as piecewise-cubic coefficients of [r, u, v, w, m] in tau (SI
    # units): breakpoints (M + 1,), coefficients (4, M, 5), highest power first (scipy PPoly),
    # for the compiled simulator (lgw.sim.lunar.kernel), which evaluates it exactly as ``sol``
    spline: tuple = ()

    def state(self, t) -> np.ndarray:
        """[r, u, v, w, m] at times t (s), clipped to [0, tf]; shape (5, *t.shape)."""
        tau = np.clip(np.asarray(t, dtype=float) / self.tf, 0.0, 1.0)
        return self.sol(tau.ravel()).reshape((5, *np.shape(tau)))

    def angles(self, t):
        """(alpha_Bd, psi_Bd, alpha_Bd', alpha_Bd'') of the steering (3) at t (rad, 1/s...)."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, self.tf)
        s = self.a2 * t + self.a3
        alpha = np.arctan(s)
        ad = self.a2 / (1 + s * s)
        add = -2 * self.a2 ** 2 * s / (1 + s * s) ** 2
        return alpha, np.full_like(alpha, np.arctan(self.a1)), ad, add

    def to_dict(self) -> dict:
        return {"a1": self.a1, "a2_per_s": self.a2, "a3": self.a3, "tf_s": self.tf,
                "psi_B_deg": float(np.degrees(np.arctan(self.a1))),
                "alpha_B0_deg": float(np.degrees(np.arctan(self.a3))),
                "alpha_Bf_deg": float(np.degrees(np.arctan(self.a2 * self.tf + self.a3))),
                "final_mass_kg": float(self.state(self.tf)[4]),
                "bvp_max_residual": self.bvp_max_residual,
                "shooting_a2_a3_tf": [self.shooting[k] for k in ("a2", "a3", "tf")]}


@cache
def reference(tol: float = 1e-6) -> Reference:
    """Solve the BVP (cached).  Initial guess: a straight-line deceleration."""
    y0 = np.array([P.R_MOON + P.H0, *P.V0, P.M0])
    rf = P.R_MOON + P.HF

    # Scaled unknowns for solve_bvp: y = [r - R, u, v, w, m] / SCALE (km, km/s, t).
    SCALE = np.array([1e3, 1e3, 1e3, 1e3, 1e3])[:, None]
    off = np.array([P.R_MOON, 0, 0, 0, 0])[:, None]

    def f(tau, ys, p):
        a1, a2, a3, tf = p
        return tf * simplified_rhs(tau * tf, ys * SCALE + off, a1, a2, a3) / SCALE

    def bc(ya, yb, p):
        ya = ya * SCALE[:, 0] + off[:, 0]
        yb = yb * SCALE[:, 0] + off[:, 0]
        return np.array([*((ya - y0) / SCALE[:, 0]), (yb[0] - rf) / 1e3, yb[1] / 1e3,
                         yb[2] / 1e3, yb[3] / 1e3])

    # Initial guess from single shooting (fsolve on a2, a3, tf with a1 = v0/u0, which the
    # simplified model keeps exactly: v/u is constant when psi is), then the BVP proper.
    a1 = P.V0[1] / P.V0[0]

    def shoot(x):
        s = solve_ivp(lambda t, y: simplified_rhs(t, y, a1, x[0], x[1]), (0.0, x[2]), y0,
                      rtol=1e-10, atol=1e-8)
        y = s.y[:, -1]
        return [y[1] / 100.0, y[3] / 10.0, (y[0] - rf) / 1000.0]

    a2, a3, tf0 = fsolve(shoot, [0.0, 0.05, 300.0], xtol=1e-12)
    tau = np.linspace(0.0, 1.0, 81)
    guess = solve_ivp(lambda t, y: simplified_rhs(t, y, a1, a2, a3), (0.0, tf0), y0,
                      t_eval=tau * tf0, rtol=1e-10, atol=1e-8).y
    res = solve_bvp(f, bc, tau, (guess - off) / SCALE, p=np.array([a1, a2, a3, tf0]), tol=tol,
                    max_nodes=20000)
    if not res.success:
        raise RuntimeError(f"reference BVP did not converge: {res.message}")
    a1, a2, a3, tf = (float(x) for x in res.p)
    scaled = res.sol

    def sol(tau):
        return scaled(tau) * SCALE + off

    c = scaled.c * SCALE[:, 0]  # (4, M, 5)
    c[-1] += off[:, 0]  # the constant terms carry the offset
    return Reference(a1, a2, a3, tf, sol, float(np.max(res.rms_residuals)),
                     {"a2": float(a2), "a3": float(a3), "tf": float(tf0)},
                     (np.array(scaled.x, float), np.ascontiguousarray(c)))


def open_loop_full_model(ref: Reference) -> dict:
    """Fly the full model (1) (all terms, latitude phi0) open loop with the reference's steering
    and thrust; the miss at t_f tells how far the simplified model is from (1)."""
    from lgw.sim.lunar.plant import translational_rhs

    y0 = np.array([P.R_MOON + P.H0, P.PHI0, P.LON0, *P.V0, P.M0])

    def rhs(t, y):
        alpha, psi, _, _ = ref.angles(t)
        n = np.array([np.cos(alpha) * np.cos(psi), np.cos(alpha) * np.sin(psi), np.sin(alpha)])
        return translational_rhs(y[:, None], -P.T_NOMINAL * n[:, None],
                                 np.array([P.T_NOMINAL]))[:, 0]

    sol = solve_ivp(rhs, (0.0, ref.tf), y0, rtol=1e-10, atol=1e-8, dense_output=True)
    t = np.linspace(0.0, ref.tf, 2001)
    y = sol.sol(t)
    rs = ref.state(t)
    dh = (y[0] - rs[0])
    dV = y[3:6] - rs[1:4]
    return {"height_miss_final_m": float(dh[-1]), "velocity_miss_final_m_s": dV[:, -1].tolist(),
            "max_height_dev_m": float(np.max(np.abs(dh))),
            "max_speed_dev_m_s": float(np.max(np.linalg.norm(dV, axis=0)))}
