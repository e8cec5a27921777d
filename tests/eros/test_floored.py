"""The floored FTSMC's proven bounds (lgw.theory.eros.floored) against the loop flown, and the
tuner that certifies a control limit by proof (lgw.tuning.eros.design).

The bounds are for the continuous-time law; the checks fly the loop sampled at 1 ms (close to
continuous time) and the paper's 0.01 s.  The command bound is attained: from e(0) = 0 with
e'(0) = v_max the command at t = 0 is (up to the drift term) the bound itself, so a bound that
were too small fails here; a bound without the floor does not exist (it grows as e_floor ->
0)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from lgw.sim.eros.batch import SimOptions, metrics, simulate
from lgw.theory.eros import floored as FL
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import default_gains

TUNED = default_gains().replace(alpha=0.05, beta=1.0, k=1.6, lam=0.05, e_floor=0.01)
OLD = default_gains().replace(alpha=0.25, beta=1.0, k=1.6, lam=0.25)  # e_floor 1e-4


def _fly(g, e0, ed0, dt, t_final=12.0, disturbance="known"):
    rng = np.random.default_rng(0)
    opts = SimOptions(law="ftsmc", switch="sign", t_final=t_final, dt=dt,
                      disturbance=disturbance)
    return metrics(simulate(e0, ed0, g, opts, rng.uniform(0, 2 * np.pi, len(e0))))


def _states(n, e_max, v_max, seed=1):
    rng = np.random.default_rng(seed)
    e0 = rng.uniform(-e_max, e_max, (n, 3))
    ed0 = rng.uniform(-v_max, v_max, (n, 3))
    # the corners and the states where the command bound is attained (e0 = 0, |e0'| = v_max)
    e0[:4] = [[0, 0, 0], [0, 0, 0], [e_max] * 3, [-e_max] * 3]
    ed0[:4] = [[v_max] * 3, [-v_max] * 3, [v_max] * 3, [-v_max] * 3]
    return e0, ed0


@pytest.mark.parametrize("g", [TUNED, OLD], ids=["e_floor 1 cm", "e_floor 0.1 mm"])
def test_command_bound_holds_on_the_flown_loop_and_is_attained(g):
    b = FL.envelope_bound(g, 10.0, 0.5, known_amp=P.DIST_AMP)
    e0, ed0 = _states(48, 10.0, 0.5)
    m = _fly(g, e0, ed0, dt=1e-3)
    peak = float(np.max(m["u_peak"]))
    assert peak <= b["u"], (peak, b["u"])
    # the bound is attained at t = 0 from e0 = 0, e0' = v_max (all but the drift term)
    assert float(np.max(m["u_peak"][:2])) >= b["u"] - b["drift"] - 1e-6
    # and the paper's sampling (0.01 s): the same, the 13.7 m/s^2 of the old design included
    m10 = _fly(g, e0, ed0, dt=P.DT_SAMPLE)
    assert float(np.max(m10["u_peak"])) <= b["u"]


def test_old_design_needs_its_proven_13_7_m_s2_from_e0_zero():
    """lgw tune eros --ts 10 --u-max 4 certified |u_i| <= 4 by sampling; from e(0) = 0,
    e'(0) = 0.5 m/s its command is 13.7 m/s^2 at t = 0, which the proof gives."""
    b = FL.envelope_bound(OLD, 10.0, 0.5, known_amp=P.DIST_AMP)
    assert 13.6 < b["u"] < 13.8
    m = _fly(OLD, np.zeros((1, 3)), np.full((1, 3), 0.5), dt=P.DT_SAMPLE, t_final=1.0)
    assert float(np.max(m["u_peak"])) > 13.5


def test_tracking_time_bound_holds_on_the_flown_loop():
    g = TUNED
    e0, ed0 = _states(48, 10.0, 0.5, seed=2)
    b = FL.envelope_bound(g, 10.0, 0.5, known_amp=P.DIST_AMP)
    m = _fly(g, e0, ed0, dt=1e-3)
    t = np.asarray(m["t_track"], float)
    assert np.all(np.isfinite(t)) and float(np.max(t)) <= b["t_total"] + 1e-3
    # per state, each axis within its own bound
    for i in range(len(e0)):
        for a in range(3):
            bd = FL.axis_bound(e0[i, a], ed0[i, a], g, screen=True)
            assert t[i, a] <= bd.t_total + 1e-3, (e0[i, a], ed0[i, a], t[i, a], bd.t_total)


def test_paper_reaching_bound_fails_with_a_floor_and_the_floored_one_holds():
    """From e0 = 0, e0' = 0.09 m/s the paper's |s0|/k = 0.05625 s is too short for the law
    flown with a 1 cm floor; s_reach_time accounts for the floor."""
    g = TUNED
    ed = 0.09
    m = _fly(g, np.zeros((1, 3)), np.full((1, 3), ed), dt=1e-4, t_final=0.3)
    observed = float(np.max(m["t_reach"]))
    assert observed > ed / g.k + 2e-3  # the unfloored bound is violated
    assert observed <= FL.s_reach_time(0.0, ed, g) + 1e-4


def test_no_bound_without_the_floor():
    """The command bound grows like e_floor^(p/q - 1): without the floor there is none."""
    us = [FL.envelope_bound(TUNED.replace(e_floor=ef), 10.0, 0.5, screen=True)["ed_g"]
          for ef in (1e-2, 1e-4, 1e-6, 1e-8)]
    r = TUNED.p / TUNED.q
    # each factor 100 off the floor multiplies the bound by 100^(1 - p/q) (6.3 for 3/5)
    for a, b in zip(us[1:], us[2:], strict=False):
        assert b / a == pytest.approx(100 ** (1 - r), rel=0.02)
    assert us[-1] == pytest.approx(0.5 * (TUNED.alpha + TUNED.beta * r * 1e-8 ** (r - 1)),
                                   rel=1e-9)


def test_arb_and_float_screen_agree_and_arb_is_an_upper_bound():
    for g in (TUNED, OLD, TUNED.replace(p=5, q=7, alpha=0.5)):
        a = FL.envelope_bound(g, 10.0, 0.5, known_amp=P.DIST_AMP)
        f = FL.envelope_bound(g, 10.0, 0.5, known_amp=P.DIST_AMP, screen=True)
        for k in ("t_total", "u", "E", "V"):
            assert a[k] >= f[k] * (1 - 1e-12) and a[k] == pytest.approx(f[k], rel=1e-9), k


def test_drift_bound_covers_the_drift_near_the_reference():
    """The drift term: rotating terms, two-point gravity, the cancelled disturbance and the
    reference acceleration, evaluated at random times and offsets within E, V."""
    from lgw.sim.eros.plant import gravity, rotating_terms
    from lgw.theory.eros.reference import coefficients, evaluate

    E, V = 12.0, 5.0
    d = FL.drift_bound(E, V, P.DIST_AMP)
    rng = np.random.default_rng(3)
    t = rng.uniform(0, P.T_LAND, 4000)
    pos, vel, acc = evaluate(coefficients(), t)
    x = pos.T + rng.uniform(-E, E, (len(t), 3))
    v = vel.T + rng.uniform(-V, V, (len(t), 3))
    f = rotating_terms(x, v) + gravity(x, "two-point")
    worst = np.max(np.abs(f) + P.DIST_AMP + np.abs(acc.T))
    assert worst <= d["drift"] and worst > 0.5 * d["drift"]


def test_hypotheses_are_checked():
    assert FL.hypotheses(TUNED) == {"k > d": True, "h(tol) > delta": True}
    assert not FL.hypotheses(TUNED, dm=2.0)["k > d"]
    big = TUNED.replace(e_floor=1.0, alpha=0.01)  # the floor's band exceeds the tolerance
    assert not FL.hypotheses(big)["h(tol) > delta"]
    assert math.isinf(FL.axis_bound(10.0, 0.5, big).t_total)


def test_tuner_certifies_the_control_limit_by_proof():
    """lgw tune eros --ts 10 --thrust-max 600: a design whose |u_i| <= 4 m/s^2 is proven over
    the whole envelope (the floor designed), re-proven in Arb, and flown."""
    from lgw.tuning.eros.design import Request, certificate, tune

    req = Request(ts=10.0, u_max=4.0, design_cases=40, fresh_cases=30)
    res = tune(req)
    assert "gains" in res, res.get("infeasible")
    cert = certificate(res, req, 600.0, 150.0)
    assert cert["u_max_evidence"].startswith("proven") and cert["bound_u"] <= 4.0
    assert cert["bound_evidence"].startswith("proven") and cert["bound_t_total"] <= 10.0
    b = FL.envelope_bound(res["gains"], 10.0, 0.5, known_amp=P.DIST_AMP)
    assert b["u"] <= cert["bound_u"] and b["t_total"] <= cert["bound_t_total"]
    assert cert["validation_peak"] <= 4.0


def test_tuner_says_infeasible_with_the_closest_proof():
    from lgw.tuning.eros.design import Request, tune

    res = tune(Request(ts=10.0, u_max=0.2, design_cases=4, fresh_cases=4))
    assert "infeasible" in res and "--u-limit sampled" in res["infeasible"] or \
        "no grid point" in res["infeasible"]
