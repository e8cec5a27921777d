"""The generated (numba) and numpy laws agree with theory's SymPy expressions (exact numbers)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from lgw.sim.mars.laws import (
    LAWS,
    get_law,
    law_args,
    numba_law,
    numba_law_s2,
    numpy_law,
    python_law,
    surface_params,
)
from lgw.theory.errors import ParameterError
from lgw.theory.mars import mss as mss
from lgw.theory.mars.gains import default_gains, gains_from_dict
from lgw.theory.mars.supertwisting import law_supertwisting

RNG = np.random.default_rng(2024)


def _points(n: int) -> np.ndarray:
    """Random (r, v, grav, a_m, m) away from r = 0 (where the laws are singular)."""
    r = RNG.choice([-1, 1], n) * 10 ** RNG.uniform(-3, 3.5, n)
    v = RNG.uniform(-200, 200, n)
    grav = RNG.choice([0.0, -3.7114], n)
    am = RNG.uniform(-0.5, 0.5, n)
    m = RNG.uniform(1400, 2000, n)
    return np.column_stack([r, v, grav, am, m])


def _gain_sets():
    yield default_gains()
    for _ in range(2):
        yield gains_from_dict({"gains": {
            "beta1": float(10 ** RNG.uniform(-1, 1)), "beta2": float(10 ** RNG.uniform(-5, -2)),
            "alpha1": float(10 ** RNG.uniform(-1, 1)), "alpha2": float(10 ** RNG.uniform(-6, -3)),
            "q1": float(RNG.uniform(0.5, 0.95)), "q2": float(RNG.uniform(1.1, 2)),
            "g1": float(RNG.uniform(0.3, 0.95)), "g2": float(RNG.uniform(1.1, 2))}})


@pytest.mark.parametrize("name", list(LAWS))
def test_generated_law_matches_symbolic(name: str) -> None:
    spec = get_law(name)
    expr = spec.expr()
    args = law_args(spec)
    nb = numba_law(name)
    nb2 = numba_law_s2(name)
    npf = numpy_law(name)
    s2_expr = mss.surface2()
    for g in _gain_sets():
        P = spec.param_values(g)
        SP = surface_params(g)
        for pt in _points(15):
            ax = int(RNG.integers(3))
            vals = [*pt, *P[ax]]
            exact = expr.subs({s: sp.Float(repr(float(x)), 40) for s, x in zip(args, vals,
                                                                               strict=True)})
            exact = float(sp.N(exact, 30))
            got_nb = nb(*pt, P, ax)
            got_py = python_law(name)(*vals)
            r3 = np.zeros(3)
            v3 = np.zeros(3)
            r3[ax], v3[ax] = pt[0], pt[1]
            g3 = np.full(3, pt[2])
            a3 = np.full(3, pt[3])
            with np.errstate(divide="ignore", invalid="ignore"):  # other axes sit at r = 0
                got_np = npf(r3, v3, g3, a3, pt[4], P)[ax]
            tol = 1e-10 * max(1.0, abs(exact))
            assert abs(got_nb - exact) <= tol, (name, vals, got_nb, exact)
            assert abs(got_py - exact) <= tol
            assert abs(got_np - exact) <= tol
            # the law with s2 (21) from the same generated code, as the simulator calls it
            a2, s2 = nb2(*pt, P, SP, ax)
            assert abs(a2 - exact) <= tol
            sym = (mss.r, mss.v, mss.beta1, mss.beta2, mss.q1, mss.q2)
            num = (pt[0], pt[1], *SP[ax])
            s2_exact = float(sp.N(s2_expr.subs({s: sp.Float(repr(float(x)), 40)
                                                for s, x in zip(sym, num, strict=True)}), 30))
            assert abs(s2 - s2_exact) <= 1e-10 * max(1.0, abs(s2_exact))


@pytest.mark.parametrize("name", list(LAWS))
def test_tiny_positions_use_the_exact_form(name: str) -> None:
    """Below lgw.sim.mars.laws.TINY the shared-power form (|r|^(q-1) = |r|^q / |r|) would overflow;
    the compiled law switches to the exact form there and stays accurate."""
    spec = get_law(name)
    P = spec.param_values(default_gains())
    args = law_args(spec)
    for r in (3e-310, -3e-310, 1e-299, -2e-290):
        vals = [r, -1e-3, -3.7114, 0.01, 1900.0, *P[2]]
        exact = spec.expr().subs({s: sp.Float(repr(float(x)), 40) for s, x in zip(args, vals,
                                                                                   strict=True)})
        exact = float(sp.N(exact, 30))
        got = numba_law(name)(*vals[:5], P, 2)
        assert np.isfinite(got) and abs(got - exact) <= 1e-10 * max(1.0, abs(exact)), (r, got)


def test_supertwisting_reading() -> None:
    """(46) as read: a = -(B1/2 |r|^(-1/2) v + B2 sgn r)/m - g."""
    r, v, grav, m = 4.0, 2.0, -3.7114, 1900.0
    B1, B2 = 1200.0, 5500.0
    expect = -(B1 / 2 * v / 2.0 + B2) / m - grav
    f = numba_law("super-twisting")
    P = np.array([[B1, B2]] * 3)
    assert f(r, v, grav, 0.0, m, P, 0) == pytest.approx(expect, rel=1e-14)
    assert "a_m" not in str(law_supertwisting())  # (46) does not cancel drag


def test_singular_point_is_not_smoothed() -> None:
    """The corrected law's |s1|^(q1-1) v is infinite at s1 = 0, v != 0 (numba and numpy)."""
    f = numba_law("corrected")
    P = get_law("corrected").param_values(default_gains())
    assert f(0.0, 2.0, -3.7, 0.0, 1900.0, P, 0) == -np.inf
    assert f(0.0, -2.0, -3.7, 0.0, 1900.0, P, 0) == np.inf
    with np.errstate(divide="ignore", invalid="ignore"):
        a = numpy_law("corrected")(np.zeros(3), np.array([2.0, -2.0, 0.0]), np.zeros(3),
                                   np.zeros(3), 1900.0, P)
    assert a[0] == -np.inf and a[1] == np.inf and a[2] == 0.0


@pytest.mark.parametrize("name", list(LAWS))
def test_axis_at_equilibrium_gets_the_limit(name: str) -> None:
    """At r = v = 0 exactly the singular term (|s1|^(q1-1) v, (46)'s |s|^(-1/2) s') is 0 along
    the solution (the axis stays at its equilibrium), so the command is the law with v = 0:
    -g - a_m for the sliding-mode laws, -g for (46); not 0 * inf = NaN."""
    P = get_law(name).param_values(default_gains())
    grav, am, m = -3.7114, 0.25, 1900.0
    expect = -grav - (0.0 if name == "super-twisting" else am)
    for v0 in (0.0, -0.0):
        assert numba_law(name)(0.0, v0, grav, am, m, P, 2) == pytest.approx(expect, rel=1e-15)
        with np.errstate(divide="ignore", invalid="ignore"):  # the 0 * inf it replaces
            a = numpy_law(name)(np.zeros((2, 3)), np.full((2, 3), v0), np.full(3, grav),
                                np.full((2, 3), am), np.full(2, m), P)
        np.testing.assert_allclose(a, expect, rtol=1e-15)
    # next to it the law is finite and continuous along the surface s2 = 0 (corrected law:
    # -g - a_m + beta1^2 q1 sig(r, 2 q1 - 1) + ..., -> -g - a_m as r -> 0, slowly: r^0.2)
    if name == "corrected":
        g = default_gains()
        r = 1e-30
        v = -(g.beta1[2] * r**g.q1 + g.beta2[2] * r**g.q2)
        assert abs(numba_law(name)(r, v, grav, am, m, P, 2) - expect) < 1e-5


def test_unknown_law() -> None:
    with pytest.raises(ParameterError, match="law"):
        get_law("bang-bang")


@pytest.mark.slow
def test_register_a_new_law() -> None:
    """The documented way to add a law: a PD law a = -g - a_m - k1 r - k2 v lands Table I."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.laws import LAWS, LawSpec, register_law
    from lgw.theory.mars import mss as mss
    from lgw.theory.mars.parameters import M0, R0, V0

    k1, k2 = sp.symbols("k1 k2", positive=True)
    register_law(LawSpec("pd-test", lambda: -mss.grav - mss.am - k1 * mss.r - k2 * mss.v,
                         (k1, k2), lambda g: np.tile([0.04, 0.4], (3, 1)), "PD (test)"))
    try:
        b = simulate_batch(R0[None], V0[None], [M0], default_gains(), law="pd-test",
                           land_tol=(1.0, 1.0))
        assert b.landed[0]
    finally:
        LAWS.pop("pd-test")


@pytest.mark.slow
def test_replacing_a_law_needs_no_cache_clearing() -> None:
    """register_law under an existing name: the generated code is keyed by the LawSpec (and on
    disk by the expression), so the next simulation runs the new law, not a stale kernel."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.laws import LAWS, LawSpec, register_law
    from lgw.theory.mars.parameters import M0, R0, V0

    k1, k2 = sp.symbols("k1 k2", positive=True)

    def pd(gain: float) -> LawSpec:
        return LawSpec("pd-swap", lambda: -mss.grav - mss.am - k1 * mss.r - k2 * mss.v,
                       (k1, k2), lambda g: np.tile([gain, 0.4], (3, 1)), "PD (test)")

    try:
        register_law(pd(0.04))
        a = simulate_batch(R0[None], V0[None], [M0], default_gains(), law="pd-swap",
                           land_tol=(1.0, 1.0))
        register_law(LawSpec("pd-swap", lambda: -mss.grav - mss.am - 1.2 * k1 * mss.r - k2 * mss.v,
                             (k1, k2), lambda g: np.tile([0.04, 0.4], (3, 1)), "PD, 1.2 k1 (test)"))
        b = simulate_batch(R0[None], V0[None], [M0], default_gains(), law="pd-swap",
                           land_tol=(1.0, 1.0))
        assert a.landed[0] and b.landed[0]
        assert a.landing_time[0] != b.landing_time[0]
        # the same expression and parameters again: the first kernel, the first numbers
        register_law(pd(0.04))
        c = simulate_batch(R0[None], V0[None], [M0], default_gains(), law="pd-swap",
                           land_tol=(1.0, 1.0))
        assert c.equal(a)
    finally:
        LAWS.pop("pd-swap")


def test_law_names_for_the_command_line_are_the_registered_laws():
    from lgw.sim.mars.laws import LAWS
    from lgw.sim.mars.parameters import LAW_NAMES

    assert tuple(LAWS) == LAW_NAMES
