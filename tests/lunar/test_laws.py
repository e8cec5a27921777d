"""The generated law (lambdify) agrees with the SymPy expressions it was generated from."""

import numpy as np
import sympy as sp
from lgw.sim.lunar import laws
from lgw.theory.lunar import law as L


def _pt(rng, syms, lo=-1.0, hi=1.0):
    return {s: float(rng.uniform(lo, hi)) for s in syms}


def test_orbit_generated_equals_symbolic():
    S = L.orbit_system(full=True)
    rng = np.random.default_rng(3)
    m = sp.Symbol("m", positive=True)
    for _ in range(5):
        K1 = np.diag(rng.uniform(0.05, 1, 3)) + 0.01 * rng.normal(size=(3, 3))
        F2 = np.diag(rng.uniform(0.6, 5, 3))
        vals = {S.x1[0]: rng.uniform(-50, 50), m: rng.uniform(3000, 6000),
                S.d0e: rng.uniform(0, 1), S.f3: 0.2,
                **_pt(rng, list(S.x2) + list(S.lam2), -5, 5), S.lam1[0]: rng.uniform(-5, 5)}
        vals.update(dict(zip(S.K1, K1.ravel(), strict=True)))
        vals.update(dict(zip(S.F2, F2.ravel(), strict=True)))
        z2 = np.array([float(e.subs(vals)) for e in S.z2])
        vals[S.nz] = float(np.linalg.norm(z2))
        sym = np.array([float(e.subs(vals)) for e in S.uc])
        g = {"K1": K1[:, :, None], "F2": F2[:, :, None], "f3": np.array([0.2])}
        uc, z2g, nz, _ = laws.orbit_command(np.array([vals[S.x1[0]]]),
                                            np.array([[vals[s]] for s in S.x2]),
                                            np.array([vals[S.lam1[0]]]),
                                            np.array([[vals[s]] for s in S.lam2]),
                                            np.array([vals[S.d0e]]), np.array([vals[m]]), g)
        np.testing.assert_allclose(uc[:, 0], sym, rtol=1e-10, atol=1e-8)
        np.testing.assert_allclose(z2g[:, 0], z2, rtol=1e-12, atol=1e-12)


def test_attitude_generated_equals_symbolic():
    S = L.attitude_system()
    rng = np.random.default_rng(4)
    eq0s = sp.Symbol("e_q0", real=True)
    for _ in range(5):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        K1 = np.diag(rng.uniform(0.5, 2, 3))
        F2 = np.diag(rng.uniform(0.6, 6, 3))
        J = np.array([2865.0, 1826.0, 1826.0])
        vals = {eq0s: q[0], **dict(zip(S.x1, q[1:], strict=True)), S.d0e: 0.01, S.f3: 0.1,
                **_pt(rng, list(S.x2) + list(S.lam1) + list(S.lam2) + list(S.f2), -0.1, 0.1)}
        vals.update(dict(zip(S.K1, K1.ravel(), strict=True)))
        vals.update(dict(zip(S.F2, F2.ravel(), strict=True)))
        Jsym = sp.symbols("J_1:4", positive=True)
        vals.update(dict(zip(Jsym, J, strict=True)))
        z2 = np.array([float(e.subs(vals)) for e in S.z2])
        vals[S.nz] = float(np.linalg.norm(z2))
        sym = np.array([float(e.subs(vals)) for e in S.uc])
        g = {"K1": K1[:, :, None], "F2": F2[:, :, None], "f3": np.array([0.1])}

        def col(ss, vals=vals):
            return np.array([[vals[s]] for s in ss])

        M, _, _, _ = laws.attitude_command(np.array([q[0]]), col(S.x1), col(S.x2), col(S.lam1),
                                           col(S.lam2), np.array([0.01]), col(S.f2),
                                           J[:, None], g)
        np.testing.assert_allclose(M[:, 0], sym, rtol=1e-9, atol=1e-9)


def test_adaptive_term_is_zero_at_z2_zero():
    # at z2 = 0 exactly the generated law sets the (undefined) adaptive term to 0
    g = {"K1": np.diag([0.1] * 3)[:, :, None], "F2": np.diag([1.0, 1, 20])[:, :, None],
         "f3": np.array([0.25])}
    z = np.zeros(1)
    uc, _, nz, _ = laws.orbit_command(z, np.zeros((3, 1)), z, np.zeros((3, 1)), np.ones(1),
                                      np.full(1, 5000.0), g)
    assert nz[0] == 0 and np.all(np.isfinite(uc)) and np.all(uc == 0)
