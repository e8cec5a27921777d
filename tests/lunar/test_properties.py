"""Property tests of seed 001's bounds on the general system (5) (orbit-instance form) flown
with the generated law, where the hypotheses of (13) hold exactly (||d(t)|| = D constant):

- V2 (12) does not increase (13) at the steps where ||z2|| is outside the chattering band
  3 dt (d0e + D) of the fixed-step sign-like term of (7) (claim smooth-7: inside it the
  discretised law does raise V2, by O((dt (d0e + D))^2) per step; the band is the measured
  exception, stated, not hidden);
- the L2 norms of lambda1, lambda2 on [0, T] obey (18) against the measured ||B0 du||;
- ||z1||^2, ||z2||^2 obey the derived (19) (V2(0) with its d0e term, f2bar - f3bar);
- ||x1|| obeys (21a).
Integrals by the trapezoidal rule on the RK4 grid; tolerances: 1e-6 V2(0) per step for V2,
relative 2e-3 for the integral bounds."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from lgw.sim.lunar.closed_loop import gain_arrays
from lgw.sim.lunar.general import GeneralCase, fly
from lgw.theory.lunar.gains import make_loop
from lgw.tuning.lunar.verify import margins

T_END, DT = 5.0, 0.02


@st.composite
def cases(draw):
    k = draw(st.floats(0.05, 1.0))
    F2 = [draw(st.floats(0.6, 5.0)) for _ in range(3)]
    f3 = draw(st.floats(0.05, 0.95)) * min(F2)
    q = draw(st.floats(0.005, 1.0))
    g = make_loop("orbit", {"K1": [k, k, k], "F2": F2, "f3": f3, "d0e0": 0.0, "q": q})
    x0 = np.array([draw(st.floats(-100, 100))] + [draw(st.floats(-5, 5)) for _ in range(3)])
    umax = draw(st.sampled_from([np.inf, 500.0, 2000.0]))
    D = draw(st.floats(0.0, 1.0))
    return g, x0, GeneralCase(D=D, u_max=umax)


def _fly(g, x0, case):
    X0 = np.zeros((9, 1))
    X0[0:4, 0] = x0
    X0[8, 0] = g.d0e0
    return fly(X0, gain_arrays([g]), case, T_END, DT)


@given(cases())
def test_v2_nonincreasing_and_l2_bounds(c):
    g, x0, case = c
    t, o = _fly(g, x0, case)
    m = margins(t, o, g, case, float(x0[0]), DT)
    tol = 2e-3  # trapezoidal integrals on the RK4 grid
    assert m["V2_step_outside_band"] >= -1e-6, m
    for k in ("(18a)", "(18b)", "(19a)", "(19b) derived", "(21a)"):
        assert m[k] >= -tol, (k, m)


def test_v2_rises_inside_the_chattering_band():
    # the measured exception: zero initial error, ||d|| = D = 1; d0e climbs to D, z2 chatters
    g = make_loop("orbit", {"K1": [1.0] * 3, "F2": [1.0] * 3, "f3": 0.5, "d0e0": 0.0, "q": 1.0})
    t, o = _fly(g, np.zeros(4), GeneralCase(D=1.0))
    dV = np.diff(o["V2"][:, 0])
    inside = o["nz"][:-1, 0] <= 3 * DT * (o["d0e"][:-1, 0] + 1.0)
    assert np.max(dV[inside]) > 0 and np.max(dV[~inside], initial=-1.0) <= 1e-9


def test_v2_increases_when_the_bound_on_d_is_wrong():
    # The hypothesis ||d|| <= D matters: with V2 built on D = 0 while ||d|| = 1, V2 rises.
    g = make_loop("orbit", {"K1": [0.1] * 3, "F2": [1.0, 1.0, 1.0], "f3": 0.25, "d0e0": 0.0,
                            "q": 0.01})
    t, o = _fly(g, np.array([0.0, 0.0, 0.0, 0.0]), GeneralCase(D=1.0, D_assumed=0.0))
    assert np.max(np.diff(o["V2"][:, 0])) > 0


def test_v2_nonincreasing_check_can_fail():
    # Break the law for a moment (wrong sign of the remainder's f3): V2 must be caught rising.
    g = make_loop("orbit", {"K1": [0.1] * 3, "F2": [1.0, 1.0, 1.0], "f3": 0.25, "d0e0": 0.0,
                            "q": 0.01})
    ga = gain_arrays([g])
    ga["F2"] = -ga["F2"]  # an unstable "law"
    X0 = np.zeros((9, 1))
    X0[0:4, 0] = [10.0, 1.0, 1.0, 1.0]
    t, o = fly(X0, ga, GeneralCase(D=0.1), 2.0, DT)
    assert np.max(np.diff(o["V2"][:, 0])) > 0


def test_l2_margins_can_fail():
    # Hide du from the check (as if the filter were driven by nothing): (18) must be violated.
    g = make_loop("orbit", {"K1": [0.1] * 3, "F2": [1.0, 1.0, 1.0], "f3": 0.25, "d0e0": 0.0,
                            "q": 0.01})
    case = GeneralCase(D=0.2, u_max=500.0)
    t, o = _fly(g, np.array([50.0, 3.0, -2.0, 4.0]), case)
    assert margins(t, o, g, case, 50.0, DT)["(18a)"] >= 0
    o["B0du"] = 0.1 * o["B0du"]
    assert margins(t, o, g, case, 50.0, DT)["(18a)"] < 0
