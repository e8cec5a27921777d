"""The compiled batched RK4 (``lgw.sim.lunar.batch.rk4_batch`` on ``lgw.sim.integrate``) against a
tight solve_ivp (DOP853, rtol = atol = 1e-9) and against the numpy RK4 of the same field
(``rk4_numpy``: same steps, so they agree to rounding: 1e-9 relative).

Stated tolerances (RK4 at dt = 0.05 s; the loop has saturations and the sign-like adaptive
term, so the observed order is below 4): position 1e-2 m, velocity 2e-2 m/s, quaternion 1e-3,
rate 5e-3 rad/s, virtual states 2e-2, d0e 1e-3; and halving dt must reduce the error."""

import numpy as np
import pytest
from lgw.sim.lunar.batch import rk4_batch, rk4_numpy, simulate, solve_ivp_case
from lgw.sim.lunar.closed_loop import RunOptions, field, initial_state, make_context
from lgw.sim.lunar.outcomes import OUTCOMES, case_record
from lgw.sim.lunar.reference import reference
from lgw.sim.lunar.scenario import section5_case
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar.cmd_simulate import random_cases
from scipy.integrate import solve_ivp

TOL = {"r": (slice(0, 1), 1e-2), "V": (slice(3, 6), 2e-2), "Q": (slice(12, 16), 1e-3),
       "w": (slice(16, 19), 5e-3), "lam": (slice(7, 11), 2e-2), "d0e": ([11, 25], 1e-3)}


def _errors(res, i, sol):
    e = np.abs(res.X[:, :, i] - sol.y.T)
    return {k: float(e[:, s].max()) for k, (s, _) in TOL.items()}


def test_section5_case_against_solve_ivp():
    # the old default step and filter (wn dt = 0.1), where the tolerances were set
    errs = []
    for dt in (0.05, 0.025):
        ctx, X0 = section5_case(opts=RunOptions(t_end=4.0, dt=dt, cmd_wn=2.0))
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
    assert res.flagged == [(1, 0.0, "below_surface")]
    assert [OUTCOMES[k] for k in res.cases["outcome"]] == ["completed", "below_surface"]
    assert np.all(np.isfinite(res.X))  # frozen at t = 0, not dropped, no NaN


def test_surface_contact_is_located_inside_the_step():
    # 200 m above the surface, falling at 100 m/s: contact near t = 2 s, located between nodes
    g = paper_gains()
    ref = reference()
    ctx = make_context(ref, [g], RunOptions(t_end=5.0, dt=0.05, cmd_wn=2.0))
    X0 = initial_state(ref, np.array([-15_000.0 + 200.0]), np.array([[0.0], [0.0], [0.0]]),
                       np.array([[1.0], [0], [0], [0]]), np.zeros((3, 1)), [g])
    X0[5] = 100.0  # w: r' = -w
    res = simulate(ctx, X0, record=False)
    assert res.flagged and res.flagged[0][2] == "crashed"
    t_c = res.flagged[0][1]
    ev = lambda t, x: x[0] - P.R_MOON  # noqa: E731
    ev.terminal = True
    s = solve_ivp(lambda t, x: field(t, x[:, None], ctx)[:, 0], (0, 5.0), X0[:, 0],
                  method="DOP853", rtol=1e-10, atol=1e-10, events=ev)
    # located on the Hermite interpolant (O(h^4)), not at the next node (0.05 s grid)
    assert abs(t_c - s.t_events[0][0]) < 1e-4, (t_c, s.t_events[0])
    # the case ends at the crossing: on the surface, with the impact speed of the reference
    rec = case_record(res.cases, 0)
    assert abs(res.cases["y_end"][0, 0] - P.R_MOON) < 1e-6
    want = np.linalg.norm(s.y_events[0][0][3:6])
    assert abs(rec["impact_speed_mps"] - want) < 1e-4 * want, (rec, want)
    assert 90.0 < rec["impact_vertical_speed_mps"] <= rec["impact_speed_mps"]  # w: downward


@pytest.mark.parametrize("case", ["section5", "random"])
def test_compiled_against_numpy_rk4(case):
    g = paper_gains()
    ref = reference()
    opts = RunOptions(t_end=3.0, dt=0.05, cmd_wn=2.0)  # 60 steps: rounding stays below 1e-9
    if case == "section5":
        ctx, X0 = section5_case(opts=opts)
    else:
        n = 4
        dh, dv, Q0 = random_cases(n, seed=11)
        ctx = make_context(ref, [g] * n, opts)
        X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, n)), [g] * n)
    a = rk4_batch(ctx, X0, record_every=6)
    b = rk4_numpy(ctx, X0, record_every=6)
    np.testing.assert_array_equal(a.t, b.t)
    scale = np.maximum(np.abs(b.X).max(axis=(0, 2), keepdims=True), 1.0)
    assert np.max(np.abs(a.X - b.X) / scale) < 1e-9
    for k in ("eh", "ev", "thrust", "thrust_cmd", "torque", "torque_cmd", "d_orbit", "eq", "ew",
              "z2o", "z2a", "V2o_part", "V2a_part", "B0du_o", "B0du_a", "d0e_orbit",
              "d0e_attitude", "Vlam_o", "Vlam_a"):
        s = max(float(np.max(np.abs(b.out[k]))), 1.0)
        assert np.max(np.abs(np.asarray(a.out[k], float) - np.asarray(b.out[k], float))) / s \
            < 1e-9, k
    np.testing.assert_array_equal(a.out["orbit_saturated"], b.out["orbit_saturated"])


def test_per_case_results_match_the_records():
    ctx, X0 = section5_case(opts=RunOptions(t_end=6.0))
    res = rk4_batch(ctx, X0, record_every=1)
    c = res.cases
    o = res.out
    assert c["peak_thrust"][0] == pytest.approx(np.max(o["thrust"][:-1, 0]), rel=1e-12)
    assert c["peak_torque"][0] == pytest.approx(np.max(np.abs(o["torque"][:-1, :, 0])),
                                                rel=1e-12)
    sat = o["torque_saturated"][:-1, 0]
    assert c["time_saturated_torque"][0] == pytest.approx(np.sum(sat) * res.dt, abs=1e-9)
    assert c["V2a_part_max"][0] == pytest.approx(np.max(o["V2a_part"][:-1, 0]), rel=1e-12)
    assert c["outcome"][0] == 0 and c["t_outcome"][0] == pytest.approx(6.0)


@pytest.mark.slow
def test_section5_first_20s_against_solve_ivp_converges():
    # Over 20 s the saturations make the loop sensitive: measured errors at dt = 0.05 / 0.025 /
    # 0.0125 s were r 0.51 / 0.036 / 0.0017 m and V 0.19 / 0.12 / 0.0068 m/s, with the old
    # command filter (wn = 2 rad/s; the default wn = 30 needs dt <= ~1/80 s for RK4).
    errs = []
    sol = None
    for dt in (0.05, 0.0125):
        ctx, X0 = section5_case(opts=RunOptions(t_end=20.0, dt=dt, cmd_wn=2.0))
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


def test_stage_peaks_equal_the_numpy_trial_states():
    """peak_thrust_stages / peak_thrust_cmd_stages: the max over every rhs evaluation of the
    accepted steps (RK4's trial states and the new node), >= the node peaks.  Independent
    route: from the kernel's recorded nodes, the RK4 trial states computed with the numpy
    field (``closed_loop.field``) and its thrust outputs there.  Unsaturated (T_max = 1e9 N:
    saturated, the thrust is T_max at every node and stage alike), the thrust grows to the
    end, so the stages (the last step's reach t_end) ask for more than any left node."""
    ctx, X0 = section5_case(opts=RunOptions(t_end=3.0, thrust_max=1e9, dt=0.05, cmd_wn=2.0))
    res = rk4_batch(ctx, X0, record_every=1)
    c = res.cases
    assert c["peak_thrust_stages"][0] > 1.01 * c["peak_thrust"][0]
    assert c["peak_thrust_cmd_stages"][0] > 1.01 * c["peak_thrust_cmd"][0]
    h = res.dt
    pk, pkc = 0.0, 0.0
    for k in range(len(res.t) - 1):
        t, X = res.t[k], res.X[k]
        k1 = field(t, X, ctx)
        x2 = X + h / 2 * k1
        k2 = field(t + h / 2, x2, ctx)
        x3 = X + h / 2 * k2
        k3 = field(t + h / 2, x3, ctx)
        x4 = X + h * k3
        for tt, xx in ((t, X), (t + h / 2, x2), (t + h / 2, x3), (t + h, x4),
                       (res.t[k + 1], res.X[k + 1])):
            out = field(tt, xx, ctx, outputs=True)[1]
            pk = max(pk, float(out["thrust"][0]))
            pkc = max(pkc, float(out["thrust_cmd"][0]))
    assert c["peak_thrust_stages"][0] == pytest.approx(pk, rel=1e-9)
    assert c["peak_thrust_cmd_stages"][0] == pytest.approx(pkc, rel=1e-9)
