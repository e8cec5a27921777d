"""Closed-form settling-time bounds against independent quadrature and ODE solves."""

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from lgw.theory import settling
from lgw.theory import settling_proofs as SP
from lgw.theory.errors import ParameterError
from scipy import integrate

pos = st.floats(1e-3, 1e3)
p_st = st.floats(0.05, 0.95)
g_st = st.floats(1.05, 4.0)


def quad_T(a, b, p, g, k=1.0, v0=math.inf):
    """Independent route: adaptive quadrature of int_0^v0 dV/(aV^p + bV^g)^k in x = ln V,
    where the integrand e^x (a e^(px) + b e^(gx))^-k decays exponentially at both ends; split at
    the crossover of the two terms."""
    xc = math.log(a / b) / (g - p)

    def f(x):
        # factor out the dominant term to avoid overflow
        lead = math.log(a) + p * x if x < xc else math.log(b) + g * x
        rest = math.log1p(math.exp(-abs((math.log(a) + p * x) - (math.log(b) + g * x))))
        return math.exp(x - k * (lead + rest))

    xe = math.log(v0) if v0 < math.inf else math.inf
    i1, _ = integrate.quad(f, -math.inf, min(xc, xe), limit=500, epsabs=0, epsrel=1e-12)
    i2 = 0.0
    if xe > xc:
        i2, _ = integrate.quad(f, xc, xe, limit=500, epsabs=0, epsrel=1e-12)
    return i1 + i2


@given(a=pos, b=pos, p=p_st, g=g_st)
def test_exact_bound_matches_quadrature(a, b, p, g):
    assert settling.exact_bound(a, b, p, g) == pytest.approx(quad_T(a, b, p, g), rel=1e-6)


@given(a=pos, b=pos, p=st.floats(0.05, 0.9), g=g_st, k=st.floats(0.6, 1.5))
def test_exact_bound_general_k(a, b, p, g, k):
    if not (p * k < 0.97 and g * k > 1.03):
        return
    assert settling.exact_bound(a, b, p, g, k) == pytest.approx(quad_T(a, b, p, g, k), rel=1e-5)


@given(a=pos, b=pos, p=p_st, g=g_st, k=st.floats(0.6, 1.5))
def test_exact_below_polyakov(a, b, p, g, k):
    if not (p * k < 1 and g * k > 1):
        return
    pol = settling.polyakov_bound(a, b, p, g, k)
    assert settling.exact_bound(a, b, p, g, k) <= pol * (1 + 1e-12)


@given(a=pos, b=pos, p=p_st, g=g_st, v0=st.floats(1e-6, 1e6))
def test_settling_time_matches_quadrature(a, b, p, g, v0):
    assert settling.settling_time(v0, a, b, p, g) == pytest.approx(
        quad_T(a, b, p, g, v0=v0), rel=1e-6, abs=1e-12)


@given(a=pos, b=pos, p=p_st, g=g_st)
def test_settling_time_tends_to_exact(a, b, p, g):
    assert settling.settling_time(np.inf, a, b, p, g) == pytest.approx(
        settling.exact_bound(a, b, p, g), rel=1e-12)


@given(b1=st.floats(0.05, 5), b2=st.floats(1e-3, 1), q1=st.floats(0.2, 0.95),
       q2=st.floats(1.05, 2.5), s0=st.floats(1e-2, 1e4))
def test_reaching_time_against_ode(b1, b2, q1, q2, s0):
    """T(s0) for the reaching law (16) against an ODE solve.  |s|' = -b1|s|^q1 - b2|s|^q2 is not
    Lipschitz at 0, so the solve uses w = |s|^(1-q1), for which w' = -(1-q1)(b1 + b2 w^c),
    c = (q2-q1)/(1-q1): smooth, and w crosses 0 transversally, so the event time is sharp."""
    T = float(settling.settling_time(s0, b1, b2, q1, q2))
    c = (q2 - q1) / (1 - q1)

    def rhs(t, y):
        return [-(1 - q1) * (b1 + b2 * max(y[0], 0.0) ** c)]

    hit = lambda t, y: y[0]  # noqa: E731
    hit.terminal = True
    sol = integrate.solve_ivp(rhs, (0, 2 * T + 1), [s0 ** (1 - q1)], events=hit, rtol=1e-12,
                              atol=1e-14, method="LSODA")
    assert sol.t_events[0].size == 1
    assert sol.t_events[0][0] == pytest.approx(T, rel=1e-7, abs=1e-9)


@given(a=pos, p=st.floats(0.05, 0.95), v0=st.floats(1e-3, 1e3))
def test_lemma1_matches_quadrature(a, p, v0):
    q, _ = integrate.quad(lambda V: 1.0 / (a * V**p), 0, v0, limit=200, epsabs=0, epsrel=1e-11)
    assert float(settling.lemma1_bound(a, p, v0)) == pytest.approx(q, rel=1e-7)


def test_numeric_matches_symbolic_forms():
    """The numeric functions implement the expressions the proofs are about."""
    rng = np.random.default_rng(3)
    a, b, k = sp.symbols("a b k", positive=True)
    p, g = sp.symbols("p g", positive=True)
    pol = sp.lambdify((a, b, p, g, k), SP.polyakov_expr(a, b, p, g, k))
    ex = sp.lambdify((a, b, p, g, k), SP.exact_expr(a, b, p, g, k), modules="scipy")
    for _ in range(50):
        av, bv = 10 ** rng.uniform(-2, 2, 2)
        pv, gv, kv = rng.uniform(0.1, 0.9), rng.uniform(1.2, 3), rng.uniform(0.9, 1.1)
        assert settling.polyakov_bound(av, bv, pv, gv, kv) == pytest.approx(pol(av, bv, pv, gv, kv))
        assert settling.exact_bound(av, bv, pv, gv, kv) == pytest.approx(ex(av, bv, pv, gv, kv))


@pytest.mark.parametrize("kw", [dict(p=1.2), dict(g=0.9), dict(a=-1.0), dict(b=0.0),
                                dict(k=0.0)])
def test_bad_parameters_raise(kw):
    args = dict(a=1.0, b=1.0, p=0.5, g=2.0, k=1.0) | kw
    with pytest.raises(ParameterError) as e:
        settling.exact_bound(**args)
    assert next(iter(kw)) in str(e.value)


def test_practical_neighborhood_definition():
    """(5): at the neighbourhood boundary the decrease condition (9) holds with equality in the
    active term."""
    a, b, p, g, k, th, eta = 2.0, 0.5, 0.6, 1.5, 1.0, 0.3, 0.7
    Vn = float(settling.practical_neighborhood(a, b, p, g, k, th, eta))
    active = min((a * Vn**p) ** k, (b * Vn**g) ** k, key=lambda x: abs(x - eta / (1 - th**k)))
    assert active == pytest.approx(eta / (1 - th**k))
    assert (a * Vn**p + b * Vn**g) ** k >= eta / (1 - th**k)
