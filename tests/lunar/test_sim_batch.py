"""The batched RK4 stand-in against a tight solve_ivp (DOP853, rtol = atol = 1e-9).

Stated tolerances (RK4 at dt = 0.05 s; the loop has saturations and the sign-like adaptive
term, so the observed order is below 4): position 1e-2 m, velocity 2e-2 m/s, quaternion 1e-3,
rate 5e-3 rad/s, virtual states 2e-2, d0e 1e-3; and halving dt must reduce the error."""

import numpy as np
import pytest
from lgw.sim.lunar.batch import rk4_batch, solve_ivp_case
from lgw.sim.lunar.closed_loop import RunOptions, initial_state, make_context
from lgw.sim.lunar.reference import reference
from lgw.sim.lunar.scenario import section5_case
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar.cmd_simulate import random_cases

TOL = {"r": (slice(0, 1), 1e-2), "V": (slice(3, 6), 2e-2), "Q": (slice(12, 16), 1e-3),
       "w": (slice(16, 19), 5e-3), "lam": (slice(7, 11), 2e-2), "d0e": ([11, 25], 1e-3)}


def _errors(res, i, sol):
    e = np.abs(res.X[:, :, i] - sol.y.T)
    return {k: float(e[:, s].max()) for k, (s, _) in TOL.items()}


def test_section5_case_against_solve_ivp():
    errs = []
    for dt in (0.05, 0.025):
        ctx, X0 = section5_case(opts=RunOptions(t_end=4.0, dt=dt))
        res = rk4_batch(ctx, X0, record_every=int(round(0.5 / dt)))
        sol = solve_ivp_case(ctx, X0[:, 0], res.t, rtol=1e-9, atol=1e-9)
        errs.append(_errors(res, 0, sol))
    for k, (_, tol) in TOL.items():
        assert errs[0][k] <= tol, (k, errs[0][k])
        assert errs[1][k] <= errs[0][k] + 1e-12, k  # converges with the step


def test_random_cases_against_solve_ivp():
    n = 3
    g = paper_gains()
    dh, dv, Q0 = random_cases(n, seed=7)
    ref = reference()
    opts = RunOptions(t_end=2.0)
    ctx = make_context(ref, [g] * n, opts)
    X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, n)), [g] * n)
    res = rk4_batch(ctx, X0, record_every=10)
    for i in range(n):
        ci = make_context(ref, [g], opts)
        sol = solve_ivp_case(ci, X0[:, i], res.t, rtol=1e-9, atol=1e-9)
        e = _errors(res, i, sol)
        for k, (_, tol) in TOL.items():
            assert e[k] <= tol, (i, k, e[k])


def test_case_below_the_surface_is_flagged_not_dropped():
    g = paper_gains()
    ref = reference()
    ctx = make_context(ref, [g] * 2, RunOptions(t_end=0.2))
    X0 = initial_state(ref, np.array([0.0, -15_100.0]), np.zeros((3, 2)),
                       np.tile(np.array([[1.0], [0], [0], [0]]), (1, 2)), np.zeros((3, 2)),
                       [g] * 2)
    res = rk4_batch(ctx, X0)
    assert res.n_cases == 2
    assert [f[0] for f in res.flagged] == [1]
    assert res.flagged[0][2] == "r below the lunar surface"


@pytest.mark.slow
def test_section5_first_20s_against_solve_ivp_converges():
    # Over 20 s the saturations make the loop sensitive: measured errors at dt = 0.05 / 0.025 /
    # 0.0125 s were r 0.51 / 0.036 / 0.0017 m and V 0.19 / 0.12 / 0.0068 m/s.
    errs = []
    sol = None
    for dt in (0.05, 0.0125):
        ctx, X0 = section5_case(opts=RunOptions(t_end=20.0, dt=dt))
        res = rk4_batch(ctx, X0, record_every=int(round(1.0 / dt)))
        if sol is None:
            sol = solve_ivp_case(ctx, X0[:, 0], res.t, rtol=1e-9, atol=1e-9)
        errs.append(_errors(res, 0, sol))
    assert errs[0]["r"] < 1.0 and errs[0]["V"] < 0.5
    assert errs[1]["r"] < 0.01 and errs[1]["V"] < 0.02
    assert errs[1]["r"] < errs[0]["r"] and errs[1]["V"] < errs[0]["V"]


@pytest.mark.slow
def test_section5_scenario_claims_have_computed_verdicts():
    from lgw.sim.lunar.scenario import scenario_claims

    claims = scenario_claims()
    assert [c.id for c in claims] == ["s5-no-saturation", "s5-d0e", "s5-tracking"]
    assert all(c.scope == "scenario" for c in claims)
    # T_max T_a = 23.8 kN < T_d = 24 kN: exact, whatever the simulation
    assert claims[0].steps[0].status == "refuted"
