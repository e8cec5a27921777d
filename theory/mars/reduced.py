"""The per-axis closed loop of seed 000 reduced to (r, v) with exact cancellation of g and a_m.

Used by the claims to exhibit counterexamples that need a trajectory (e.g. the printed law (25)
not bringing s2 to 0 within (26)).  Integrated with LSODA at tight tolerances; this is a
stand-alone check inside ``theory`` (which must not import ``sim``), not the campaign simulator.
"""

from __future__ import annotations

import numpy as np
from lgw.theory.mars.mss import law_numeric, s2_drift_numeric, surfaces_numeric
from lgw.theory.symbolic import np_sig
from scipy.integrate import solve_ivp

GAIN_ORDER = ("beta1", "beta2", "alpha1", "alpha2", "q1", "q2", "g1", "g2")
# right-hand-side evaluations one reference integration may use (~50 at each of the 2000
# max_step steps; a few seconds of Python)
RHS_BUDGET = 100_000


def trajectory(law: str, gains: dict[str, float], r0: float, v0: float, t_end: float,
               n_out: int = 4001, a_p=None) -> dict[str, np.ndarray]:
    """(t, r, v, s1, s2) on a uniform grid; a_p(t, r, v) optional disturbance."""
    f = law_numeric(law)
    args = [gains[k] for k in GAIN_ORDER]

    calls = [0]

    def rhs(t, y):
        calls[0] += 1
        if calls[0] > RHS_BUDGET:  # LSODA crawls, it does not fail, when gains make it stiff
            raise RuntimeError(f"reference integration stopped after {RHS_BUDGET} right-hand "
                               f"side evaluations at t = {t:.6g} s (the closed loop is too "
                               "stiff for these gains at rtol 1e-10)")
        acc = f(y[0], y[1], 0.0, 0.0, *args)  # grav and a_m cancel exactly: pass 0 for both
        return [y[1], acc + (a_p(t, y[0], y[1]) if a_p else 0.0)]

    ts = np.linspace(0.0, t_end, n_out)
    sol = solve_ivp(rhs, (0.0, t_end), [r0, v0], method="LSODA", t_eval=ts, rtol=1e-10,
                    atol=1e-10, max_step=t_end / 2000)
    if not sol.success:
        raise RuntimeError(f"reference integration failed: {sol.message}")
    s1f, s2f = surfaces_numeric()
    b = (gains["beta1"], gains["beta2"], gains["q1"], gains["q2"])
    return {"t": sol.t, "r": sol.y[0], "v": sol.y[1], "s1": s1f(sol.y[0], sol.y[1], *b),
            "s2": s2f(sol.y[0], sol.y[1], *b)}


def surface_trajectory(law: str, gains: dict[str, float], s1_0: float, s2_0: float,
                       t_end: float, n_out: int = 4001) -> dict[str, np.ndarray]:
    """The per-axis closed loop without disturbance, in surface coordinates (s1, s2):
        s1' = s2 - beta1 sig(s1,q1) - beta2 sig(s1,q2)                       (41)
        s2' = -alpha1 sig(s2,g1) - alpha2 sig(s2,g2) + e(s1, s2)
    with the drift e computed from the law's own closed loop
    (``lgw.theory.mars.mss.s2_drift_numeric``): 0 for the corrected law (claim V2dot-corrected)
    and (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s2 for the printed law (claim s2dot-24).

    Honest numerics at the non-Lipschitz zeros: phase 1 integrates (s1, w2), w2 = sig(s2, 1-g1),
    which reaches 0 transversally (w2' -> -(1-g1) alpha1 sgn s2), with a terminal event there;
    s2 = 0 is invariant (e vanishes with s2), so phase 2 integrates w1 = sig(s1, 1-q1) alone,
    again to a transversal event; after it the state is at the origin for good.  An adaptive
    solver in the raw variables crawls through the chatter around those zeros instead."""
    g = gains
    b1, b2, q1, q2 = g["beta1"], g["beta2"], g["q1"], g["q2"]
    a1, a2, g1, g2 = g["alpha1"], g["alpha2"], g["g1"], g["g2"]
    ts = np.linspace(0.0, t_end, n_out)
    s1 = np.zeros(n_out)
    s2 = np.zeros(n_out)

    # The sign of s2 (then s1) is frozen at its initial value within a phase, so the right side
    # is smooth through the event (the power (g2-g1)/(1-g1) > 1) and root finding is reliable.
    sgn2 = float(np.sign(s2_0))
    sgn1 = 1.0
    drift = s2_drift_numeric(law)
    gargs = tuple(float(g[k]) for k in GAIN_ORDER)

    def phase1(t, y):
        x1, w2 = y
        z2 = sgn2 * abs(w2) ** (1 / (1 - g1))
        d1 = z2 - b1 * np_sig(x1, q1) - b2 * np_sig(x1, q2)
        dw = (1 - g1) * (-a1 * sgn2 - a2 * sgn2 * abs(z2) ** (g2 - g1))
        if drift is not None and z2 != 0.0:  # w2' gets (1-g1)|s2|^(-g1) e(s1, s2)
            dw += (1 - g1) * abs(z2) ** (-g1) * drift(x1, z2, *gargs)
        return [d1, dw]

    def phase2(t, y):
        z1 = abs(y[0]) ** (1 / (1 - q1))
        return [(1 - q1) * sgn1 * (-b1 - b2 * z1 ** (q2 - q1))]

    def hit(i):
        def ev(t, y):
            return y[i]
        ev.terminal = True
        return ev

    # Values below the solvers' absolute tolerance are zero for this reference.
    floor = 1e-12 * (1.0 + abs(s1_0) + abs(s2_0))
    s1_0 = 0.0 if abs(s1_0) < floor else s1_0
    s2_0 = 0.0 if abs(s2_0) < floor else s2_0
    t0, x1 = 0.0, s1_0
    if s2_0 != 0.0:
        sol = solve_ivp(phase1, (0.0, t_end), [s1_0, np_sig(s2_0, 1 - g1)], method="LSODA",
                        dense_output=True, rtol=1e-11, atol=1e-12, max_step=t_end / 500,
                        events=hit(1))
        if sol.status < 0:
            raise RuntimeError(f"reference integration failed: {sol.message}")
        t0 = float(sol.t[-1])
        m = ts <= t0
        if m.any():
            y = sol.sol(ts[m])
            s1[m], s2[m] = y[0], np_sig(y[1], 1 / (1 - g1))
        x1 = float(sol.y[0, -1])
    if t0 < t_end and x1 != 0.0:
        sgn1 = float(np.sign(x1))
        sol = solve_ivp(phase2, (t0, t_end), [np_sig(x1, 1 - q1)], method="LSODA",
                        dense_output=True, rtol=1e-11, atol=1e-14, max_step=t_end / 500,
                        events=hit(0))
        if sol.status < 0:
            raise RuntimeError(f"reference integration failed: {sol.message}")
        m = (ts >= t0) & (ts <= sol.t[-1])
        if m.any():
            s1[m] = np_sig(sol.sol(ts[m])[0], 1 / (1 - q1))
    v = s2 - b1 * np_sig(s1, q1) - b2 * np_sig(s1, q2)
    return {"t": ts, "s1": s1, "s2": s2, "r": s1, "v": v}
