"""The fuzzy blend (20)-(22): the reaching condition holds exactly where the theory says
(k >= Fbar max(1, N/M)), and fails (found counterexample) where it does not."""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st
from lgw.theory.eros.claims import fuzzy_vdot, fuzzy_vdot_fd


def _vdot(F, s, dist, k, N, M):
    """V' = (1 - a) F s - b k |s| (claim fuzzy-condition), floats."""
    a, b = math.exp(-N * dist), 1 - math.exp(-M * dist)
    return (1 - a) * F * s - b * k * abs(s)


@given(N=st.floats(0.05, 20), M=st.floats(0.05, 20), Fbar=st.floats(0.01, 10),
       frac=st.floats(-1, 1), s=st.floats(-10, 10).filter(lambda x: abs(x) > 1e-6),
       dist=st.floats(1e-6, 100), margin=st.floats(1.0001, 3))
def test_reaching_holds_where_theory_says(N, M, Fbar, frac, s, dist, margin):
    k = margin * Fbar * max(1.0, N / M)
    assert _vdot(frac * Fbar, s, dist, k, N, M) < 0


@given(N=st.floats(0.05, 20), M=st.floats(0.05, 20), Fbar=st.floats(0.01, 10),
       shrink=st.floats(0.05, 0.95))
def test_counterexample_below_the_condition(N, M, Fbar, shrink):
    """k = shrink Fbar max(1, N/M): a state with |F| = Fbar and V' > 0 exists (near D -> 0
    if N > M, at large D otherwise)."""
    k = shrink * Fbar * max(1.0, N / M)
    found = any(_vdot(Fbar, 1.0, d, k, N, M) > 0 for d in (1e-8, 1e-6, 1e-4, 1e-2, 1, 10, 1e3))
    assert found


def test_witness_state_two_routes():
    st_ = {"e": 0.1, "ed": 2.0, "f": 0.0, "D": 0.0, "xdd": 0.0, "d": 1.6, "alpha": 1.0,
           "beta": 1.0, "r": 0.6, "k": 2.0, "N": 5.0, "M": 5.0}
    v1, v2 = fuzzy_vdot(st_), fuzzy_vdot_fd(st_)
    assert v1 > 0 and abs(v1 - v2) < 1e-5 * abs(v1)
    st_["k"] = 20.0  # dominating gain: the condition holds again
    assert fuzzy_vdot(st_) < 0
