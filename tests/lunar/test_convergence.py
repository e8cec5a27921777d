"""Seed 001's Section 5 numbers are converged at the default step: the default run against the
same run at dt/4 (every quoted number but the one documented exception), and against a tight
adaptive reference of the same loop (slow).  The check itself must catch a difference, and a
stopped case must not count as saturated after it stopped.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from lgw.sim.lunar import convergence as CV
from lgw.sim.lunar import parameters as SP
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.sim.lunar.scenario import fly_section5, section5_case, summarize

# the one quoted number of the coupled Section 5 run that does not converge to 1 % at any
# practical step (sim/lunar/parameters.py: the torque command chatters on the limit of (28))
KNOWN_UNCONVERGED = {"coupled": {"B0du_attitude_L2"}, "ideal": set()}


def test_the_check_flags_a_difference_above_one_percent():
    a = {"eh_final_m": -1.00, "ev_final_norm_m_s": 2.0}
    b = {"eh_final_m": -1.02, "ev_final_norm_m_s": 2.0}
    c = CV.compare(a, b, 0.01, 0.0025, "completed", "completed")
    assert not c.converged and [x.name for x in c.unconverged] == ["eh_final_m"]
    assert "eh_final_m" in c.flags()[0]
    ok = CV.compare(a, {**b, "eh_final_m": -1.005}, 0.01, 0.0025, "completed", "completed")
    assert ok.converged and ok.flags() == []


def test_the_check_uses_the_floor_for_numbers_near_zero():
    # 3 mm against 5 mm: 2 mm is more than 1 % of the 0.1 m floor (1 mm): not converged
    a, b = {"eh_final_m": 0.003}, {"eh_final_m": 0.005}
    assert not CV.compare(a, b, 1, 1, "completed", "completed").converged
    a, b = {"eh_final_m": 0.0003}, {"eh_final_m": 0.0008}  # 0.5 mm <= 1 mm
    assert CV.compare(a, b, 1, 1, "completed", "completed").converged


def test_a_different_outcome_is_not_converged():
    a = {"eh_final_m": -1.0}
    c = CV.compare(a, a, 0.01, 0.0025, "completed", "crashed")
    assert not c.converged and "outcome" in c.flags()[0]


@pytest.mark.parametrize("pointing", ["coupled", "ideal"])
def test_section5_default_run_agrees_with_dt_over_4(pointing):
    f = fly_section5(opts=RunOptions(thrust_pointing=pointing))
    conv = f.convergence
    assert conv.dt == SP.DT and math.isclose(conv.refined_dt, SP.DT / 4)
    assert conv.outcome == conv.refined_outcome == "completed"
    bad = {c.name for c in conv.unconverged}
    assert bad == KNOWN_UNCONVERGED[pointing], [c.to_dict() for c in conv.unconverged]
    # the headline numbers, to 1 %
    for key in ("eh_final_m", "ev_final_norm_m_s", "max_abs_eh_m", "orbit_saturated_s"):
        c = next(x for x in conv.checks if x.name == key)
        assert c.difference <= 0.01


def test_saturated_time_stops_with_the_case():
    """A case that hits the surface early must not count the frozen samples after it as
    saturated (the records are frozen at its last node)."""
    o = RunOptions(dt=SP.DT_CAMPAIGN, cmd_wn=0.25)  # the coupled loop crashes at this wn
    ctx, X0 = section5_case(opts=o)
    from lgw.sim.lunar.batch import rk4_batch

    res = rk4_batch(ctx, X0, record_every=32)
    s = summarize(res, ctx).numbers
    assert s["outcome"] == "crashed"
    assert s["orbit_saturated_s"] <= s["t_outcome_s"] + 1e-9
    assert s["torque_saturated_s"] <= s["t_outcome_s"] + 1e-9
    # the record-based count agrees with the kernel's per-step count once it stops at t_stop
    t = res.t
    flying = t < s["t_outcome_s"]
    dt_rec = np.minimum(np.diff(t, append=t[-1]), np.maximum(s["t_outcome_s"] - t, 0))
    rec = float(np.sum(dt_rec[res.out["orbit_saturated"][:, 0] & flying]))
    assert abs(rec - s["orbit_saturated_s"]) <= 0.2 + 0.02 * s["orbit_saturated_s"]


@pytest.mark.slow
@pytest.mark.parametrize("pointing", ["coupled", "ideal"])
def test_section5_against_solve_ivp(pointing):
    """The default RK4 run against scipy's solve_ivp (DOP853, rtol = atol = 1e-6) of the same
    compiled vector field over the whole run (~3.7 M evaluations, ~10 min: the adaptive step
    resolves every switch of the relay of (7) once the loop slides on z2 = 0)."""
    from lgw.sim.lunar.batch import simulate, solve_ivp_compiled
    from lgw.sim.lunar.scenario import case_numbers

    ctx, X0 = section5_case(opts=RunOptions(thrust_pointing=pointing))
    a = case_numbers(simulate(ctx, X0, record=False).cases, ctx)
    sol = solve_ivp_compiled(ctx, X0[:, 0], rtol=1e-6, atol=1e-6)
    assert sol.status == 0
    rs = ctx.ref.state(sol.t[-1])
    ref = {"eh_final_m": sol.y[0, -1] - rs[0],
           "ev_final_norm_m_s": float(np.linalg.norm(sol.y[3:6, -1] - rs[1:4]))}
    c = CV.compare(a, ref, SP.DT, 0.0, "completed", "completed",
                   {k: CV.QUOTED[k] for k in ref})
    assert c.converged, [x.to_dict() for x in c.checks]


def test_campaign_dt_is_a_documented_choice():
    assert SP.DT_CAMPAIGN == 2 * SP.DT
    assert RunOptions().dt == SP.DT and replace(RunOptions(), dt=SP.DT_CAMPAIGN).dt > 0
