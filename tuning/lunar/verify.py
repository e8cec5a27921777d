"""Seed 001's property campaign on the general system (5) (orbit-instance form, ||d|| = D
constant, saturation per axis): measured behaviour against (13), (18), (19), (21a).

``margins`` is the one check used by ``lgw verify lunar`` and tests/lunar/test_properties.py.
Margins are relative (bound - observed) / bound; negative violates.  The chattering band of
the sign-like term of (7) (claim smooth-7) is excluded from the step-wise V2 check and stated.
"""

from __future__ import annotations

import numpy as np
from lgw.sim.lunar.batch import l2_norm
from lgw.sim.lunar.closed_loop import gain_arrays
from lgw.sim.lunar.general import GeneralCase, fly
from lgw.theory.lunar.bounds import lambda_gain_bounds, transient_bounds, v2_initial, z_l2_bounds
from lgw.theory.lunar.gains import LoopGains, make_loop

BAND = 3.0  # chattering band: ||z2|| <= BAND dt (d0e + D)


def margins(t: np.ndarray, o: dict, g: LoopGains, case: GeneralCase, x1_0: float,
            dt: float, i: int = 0) -> dict[str, float]:
    V2 = o["V2"][:, i]
    band = BAND * dt * (o["d0e"][:-1, i] + case.D)
    outside = o["nz"][:-1, i] > band
    dV = np.diff(V2)
    f1b, f2b = float(g.K1[2, 2]), g.f2bar
    w = float(l2_norm(t, o["B0du"][..., i:i + 1])[0])
    c1, c2 = lambda_gain_bounds(f1b, f2b)
    v20 = v2_initial(np.array([x1_0]), o["z2"][0, :, i], g.d0e0, case.D, g.q)
    b1, b2 = z_l2_bounds(v20, f1b, f2b, g.f3)
    _, b2p = z_l2_bounds(v20, f1b, f2b, g.f3, printed=True)
    x1b, _ = transient_bounds(v20, w, f1b, f2b, g.f3, float(np.linalg.norm(g.K1[:, 2])))

    def rel(bound, obs):
        return (bound - obs) / bound if bound > 0 else (0.0 if obs <= 0 else -np.inf)

    n = lambda k: float(l2_norm(t, o[k][..., i:i + 1])[0])  # noqa: E731
    return {
        "V2_step_outside_band": float(-np.max(dV[outside], initial=-np.inf) / V2[0])
        if V2[0] > 0 else 0.0,
        "V2_max_rise_inside_band": float(np.max(dV[~outside], initial=0.0) / V2[0])
        if V2[0] > 0 else 0.0,
        "(18a)": rel(c1 * w, n("l1")) if w > 0 else -n("l1"),
        "(18b)": rel(c2 * w, n("l2")) if w > 0 else -n("l2"),
        "(19a)": rel(b1, n("z1") ** 2), "(19b) derived": rel(b2, n("z2") ** 2),
        "(19b) printed": rel(b2p, n("z2") ** 2), "(21a)": rel(x1b, n("x1")),
    }


def random_loop_gains(rng: np.random.Generator) -> LoopGains:
    k = rng.uniform(0.05, 1.0)
    F2 = rng.uniform(0.6, 5.0, 3)
    return make_loop("orbit", {"K1": [k, k, k], "F2": F2.tolist(),
                               "f3": float(rng.uniform(0.05, 0.95) * F2.min()), "d0e0": 0.0,
                               "q": float(rng.uniform(0.005, 1.0))})


def campaign(n: int, seed: int, t_end: float = 5.0, dt: float = 0.02,
             u_max: float = 2000.0, D: float = 0.5) -> list[dict]:
    """n random cases (gains and initial errors), flown together; margins per case."""
    rng = np.random.default_rng(seed)
    gs = [random_loop_gains(rng) for _ in range(n)]
    X0 = np.zeros((9, n))
    X0[0] = rng.uniform(-100, 100, n)
    X0[1:4] = rng.uniform(-5, 5, (3, n))
    case = GeneralCase(D=D, u_max=u_max)
    t, o = fly(X0, gain_arrays(gs), case, t_end, dt)
    return [margins(t, o, gs[i], case, float(X0[0, i]), dt, i) for i in range(n)]
