"""The bounded cascade law: generated code = SymPy, finite everywhere, claims' verdicts,
and simulated landings inside the proven bounds."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.laws import LEAD_ARGS, numba_law, numpy_law
from lgw.theory.errors import ParameterError
from lgw.theory.mars import bounded as B
from lgw.theory.mars.bounded_claims import TABLE3_AXES, all_claims, fly_axis
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import G_MARS, M0
from lgw.tuning.mars.design_bounded import axis_certificate, drag_force_coef

RNG = np.random.default_rng(17)
NAME = B.NAME


def _gains(bg: B.BoundedGains):
    return replace(default_gains(), extra={"bounded": bg.to_dict()})


def _random_bg() -> B.BoundedGains:
    return B.bounded_gains_from_dict({
        "c1": float(10 ** RNG.uniform(-0.5, 1)), "delta": float(10 ** RNG.uniform(0, 3)),
        "c2": float(10 ** RNG.uniform(-9, -3)), "k1": float(10 ** RNG.uniform(-1, 1)),
        "k2": float(10 ** RNG.uniform(-5, -1)), "p2": float(RNG.uniform(1.05, 3)),
        "e1": float(RNG.uniform(0.05, 0.95)), "e2": float(RNG.uniform(1.05, 3))})


@pytest.mark.parametrize("bg", [B.default_bounded(), _random_bg(), _random_bg()])
def test_generated_equals_symbolic(bg):
    """numba and numpy code vs the SymPy expression at exact rational points, r = 0 included."""
    expr = B.law_bounded()
    args = LEAD_ARGS + B.PARAMS
    f_nb, f_np = numba_law(NAME), numpy_law(NAME)
    P = bg.params()
    for k in range(12):
        i = k % 3
        r = 0.0 if k < 3 else float(RNG.choice([-1, 1]) * 10 ** RNG.uniform(-3, 3.5))
        v = float(RNG.uniform(-150, 150))
        grav, am = float(G_MARS[i]), float(RNG.uniform(-0.5, 0.5))
        m = float(RNG.uniform(1500, 2000))
        subs = dict(zip(args, [sp.Float(x, 30) for x in (r, v, grav, am, m, *P[i])], strict=True))
        want = float(sp.N(expr.subs(subs), 30))
        got = f_nb(r, v, grav, am, m, P, i)
        assert got == pytest.approx(want, rel=1e-10, abs=1e-10)
        rr = np.zeros((1, 3)); vv = np.zeros((1, 3))  # noqa: E702
        rr[0, i], vv[0, i] = r, v
        a = f_np(rr, vv, G_MARS, np.full((1, 3), am), np.array([m]), P)
        assert a[0, i] == pytest.approx(want, rel=1e-10, abs=1e-10)


def test_finite_everywhere_on_a_box():
    """Finite command on a grid of r, v including r = 0 with v != 0 (the corrected law is +-inf
    there) and r = v = 0, for the default and random gains."""
    f = numba_law(NAME)
    for bg in (B.default_bounded(), _random_bg()):
        P = bg.params()
        for r in np.r_[np.linspace(-3000, 3000, 41), 0.0, 1e-300, -1e-12]:
            for v in np.r_[np.linspace(-200, 200, 21), 0.0]:
                for i in range(3):
                    assert np.isfinite(f(r, v, G_MARS[i], 0.0, M0, P, i))
    # and the corrected law is not (so this test would see the singularity)
    Pc = np.column_stack([default_gains().beta1, default_gains().beta2, default_gains().alpha1,
                          default_gains().alpha2] + [np.full(3, 0.6)] * 4)
    assert not np.isfinite(numba_law("corrected")(0.0, -50.0, 0.0, 0.0, M0, Pc, 0))


def test_command_continuous_at_r0():
    """|a(r) - a(0)| -> 0 as r -> 0 at fixed v != 0 (where the corrected law blows up)."""
    f, bg = numba_law(NAME), B.default_bounded()
    P = bg.params()
    a0 = f(0.0, -80.0, 0.0, 0.0, M0, P, 1)
    gaps = [abs(f(h, -80.0, 0.0, 0.0, M0, P, 1) - a0) for h in (1e-2, 1e-4, 1e-6)]
    assert gaps[0] > gaps[1] > gaps[2] and gaps[2] < 1e-4


def test_bad_gains_are_parameter_errors():
    d = dict(B.DEFAULT_BOUNDED)
    for key, bad in (("e1", 1.2), ("e2", 0.9), ("p2", 1.0), ("c1", -1.0), ("delta", [1, 2])):
        with pytest.raises(ParameterError):
            B.bounded_gains_from_dict({**d, key: bad})
    with pytest.raises(ParameterError):
        B.bounded_gains_from_dict({**d, "zeta": 1.0})


def test_claims_have_verdicts():
    from lgw.theory.mars.bounded_claims import gain_set_claims
    got = {c.id: c.verdict for c in [*all_claims(), *gain_set_claims()]}
    assert got["bounded-derivative"] == "proved"
    assert got["bounded-command-finite"] == "proved"
    assert got["bounded-psi-monotone"] == "proved"
    assert got["bounded-slide-time"] == "proved"
    assert got["bounded-fixed-time"] == "proved-given"
    assert got["bounded-invariants"] == "proved-given"  # flights and quadrature: searches
    assert got["bounded-sat-invariance"] == "proved"
    for c in all_claims():
        for s in c.steps:
            if s.evidence.kind == "search":
                assert s.evidence.best_margin >= 0


def test_slide_primitive_matches_quadrature():
    """Closed-form sliding time vs adaptive quadrature of 1/(c1 phi) (independent route)."""
    from scipy.integrate import quad
    bg = B.default_bounded()
    for i, (x0, x1) in enumerate(((1500.0, 0.1), (20.0, 0.01), (2400.0, 1.0))):
        q, _ = quad(lambda x, i=i: np.sqrt(bg.delta[i] + x) / (bg.c1[i] * x), x1, x0,
                    limit=200)
        assert float(B.slide_time(x0, x1, bg, i)) == pytest.approx(q, rel=1e-9)


def test_bounds_hold_on_solve_ivp_corners():
    """The box bounds against the independent two-phase solve_ivp at the corners of Table III,
    overshooting states (r_y = 0, v_y = -100) included."""
    bg = B.default_bounded()
    for i, box in enumerate(TABLE3_AXES):
        d = B.axis_box_bounds(bg, i, box)
        for r0 in (box.r_lo, box.r_hi):
            for v0 in (box.v_lo, box.v_hi):
                o = fly_axis(bg, i, r0, v0, t_max=d["T_land"] + 5)
                assert o["u"] <= d["u_b"] and o["t_land"] <= d["T_land"]
                assert o["r"] <= d["R_b"] * (1 + 1e-9) and o["v"] <= d["V_b"] * (1 + 1e-9)


STATE = st.tuples(*(st.floats(0.0, 1.0) for _ in range(6)))


@pytest.mark.slow  # compiles and flies the bounded kernel, ~1.5 min cold in CI
@settings(max_examples=8)
@given(st.lists(STATE, min_size=8, max_size=8))
def test_simulated_landing_within_proven_bound(us):
    """simulate_batch with the bounded law (50 kN per axis) from Table III states: no saturation,
    lands, landing time <= the proven per-axis bound, peak thrust <= the proven thrust bound."""
    bg = B.default_bounded()
    u = np.array(us)
    lo = np.array([[b.r_lo for b in TABLE3_AXES], [b.v_lo for b in TABLE3_AXES]])
    hi = np.array([[b.r_hi for b in TABLE3_AXES], [b.v_hi for b in TABLE3_AXES]])
    r0 = lo[0] + u[:, :3] * (hi[0] - lo[0])
    v0 = lo[1] + u[:, 3:] * (hi[1] - lo[1])
    boxes = [(np.r_[lo[0], lo[1], M0], np.r_[hi[0], hi[1], M0])]
    cert = [axis_certificate(bg, i, boxes, M0) for i in range(3)]
    res = simulate_batch(r0, v0, np.full(len(r0), M0), _gains(bg), law=NAME,
                         thrust_limit=50_000.0, t_max=max(c["T_land"] for c in cert) + 5)
    assert res.landed.all() and not res.nonfinite.any()
    assert np.all(res.time_saturated == 0)
    assert np.all(res.landing_time <= max(c["T_land"] for c in cert))
    for i in range(3):
        assert np.all(res.peak_thrust[:, i] <= cert[i]["F_b"])
    assert drag_force_coef().shape == (3,)


def test_disturbed_landing_within_practical_bound():
    """With |a_p,i| <= a_max (seed 000 (47)-type sinusoid, amplitude a_max) the cases land
    inside the practical bound: |s| enters s_nb, the landing set is unchanged (rho <= 0.1 m)."""
    bg, a_max = B.default_bounded(), 0.3
    r0 = np.array([[b.r_lo for b in TABLE3_AXES], [b.r_hi for b in TABLE3_AXES]])
    v0 = np.array([[b.v_lo for b in TABLE3_AXES], [b.v_hi for b in TABLE3_AXES]])
    T = [B.axis_box_bounds(bg, i, b, a_max=a_max)["T_land"] for i, b in enumerate(TABLE3_AXES)]
    T0 = [B.axis_box_bounds(bg, i, b)["T_land"] for i, b in enumerate(TABLE3_AXES)]
    assert all(t > t0 for t, t0 in zip(T, T0, strict=True))  # the practical bound is slower
    res = simulate_batch(r0, v0, np.full(2, M0), _gains(bg), law=NAME, disturbance="sin",
                         dist_amplitude=a_max, thrust_limit=50_000.0, t_max=max(T) + 5)
    assert res.landed.all() and np.all(res.landing_time <= max(T))
    with pytest.raises(ParameterError):  # a disturbance whose neighbourhood leaves the set
        B.axis_box_bounds(bg, 0, TABLE3_AXES[0], a_max=3.0)
