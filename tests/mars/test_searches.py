"""Seed 000's full-domain searches (lgw.theory.mars.searches): the fast and the independent
routes agree, the engine re-finds from scratch the counterexamples the report gives by hand,
and the steps are exposed per claim id."""

from __future__ import annotations

import math

import numpy as np
import pytest
from lgw.theory.evidence import Search, Step
from lgw.theory.falsify import Budget, falsify
from lgw.theory.mars import bounds as B
from lgw.theory.mars import searches as S

DEFAULT = {"beta1": 2.8, "beta2": 4e-4, "alpha1": 0.5, "alpha2": 2e-5, "q1": 0.6, "q2": 1.5,
           "g1": 0.7, "g2": 1.9}
QUICK = Budget(popsize=6, maxiter=10, local_evals=40, seed=0)


@pytest.mark.parametrize("s0", [1e-3, 1.0, 1e4, 1e9])
def test_quadrature_matches_incomplete_beta(s0):
    a, b, p, g = 0.2, 0.01, 0.9, 1.5
    t = float(B.reaching_time(np.array([s0]), a, b, p, g)[0])
    assert S.quad_time(0.0, s0, a, b, p, g) == pytest.approx(t, rel=1e-9)


@pytest.mark.parametrize("s1_0,s2_0", [(1e3, 1e6), (-50.0, 3.0), (0.5, -1e4)])
def test_landing_fast_route_matches_reference(s1_0, s2_0):
    """ln|s2|-domain integration + closed forms vs the time-domain LSODA reference: within the
    reference's grid step (it reports the node after the landing)."""
    p = {**DEFAULT, "s1_0": s1_0, "s2_0": s2_0}
    fast = S.landing_time_fast(p)
    ref = S.landing_time_reference(p)
    h = 1.05 * S._sum_star(p) / 40000
    assert fast - 2 * h <= ref <= fast + 2 * h
    assert fast >= float(B.reaching_time(np.array([s2_0]), 0.5, 2e-5, 0.7, 1.9)[0])


def test_engine_refinds_paper_landing_max_counterexample():
    """Without being told where: a gain set and state landing later than max{T1 (18), T2 (26)}
    (the old search, alpha = beta and g = q over 12 cases, found none)."""
    s = falsify(S.problems()["landing-time"][1], QUICK)
    assert s.status == "refuted", s.best_margin
    w = s.witness
    p = w.point
    assert S.landing_time_fast(p) > max(S.bound(p, "T1_polyakov"), S.bound(p, "T2_polyakov"))
    assert w.rechecked_margin < 0
    # and the sound sum is not violated there
    assert S.landing_time_fast(p) <= S.bound(p, "landing_time_bound")


@pytest.mark.slow
def test_engine_refinds_printed_law_T2_counterexample():
    """Claim T2-printed's counterexample (the report's: Fig. 6 case, by hand) re-found from
    scratch over the full box: s2 not at 0 by (26) under the printed law (25), re-checked by
    the SymPy law in (r, v) with LSODA (~45 s)."""
    s = falsify(S.problems()["T2-printed"][1], QUICK)
    assert s.status == "refuted"
    assert s.witness.margin < 0 and s.witness.rechecked_margin < 0


def test_underflowing_bands_are_not_counterexamples():
    """q1, g1 near 0 make the (31) band underflow to 0: excluded as undecidable in float64."""
    p = {**DEFAULT, "q1": 0.1, "g1": 0.03, "alpha1": 50.0, "a_max": 0.02, "theta1": 0.3,
         "theta2": 0.2}
    assert B.axis_bounds(S.gains_of(p))["x"]["s1_bound"] == 0.0
    assert not S.representable(p) and not S.resolvable(p)


def test_full_domain_steps_are_keyed_by_claim_id(monkeypatch):
    tiny = Budget(popsize=2, maxiter=1, local_evals=0, seed=0)
    monkeypatch.setattr(S, "run", lambda sid, budget=tiny: Search(
        domain={}, method="stub for keys", evaluations=1, best_margin=math.inf,
        best_point={}))
    steps = S.full_domain_steps(tiny)
    assert set(steps) == set(S.PAPER_SEARCH)
    assert all(isinstance(v, Step) for v in steps.values())
    ids = {cid for cid, _ in S.problems().values()}
    assert set(steps) <= ids


def test_box_is_the_full_valid_range():
    dims = {d.name: d for d in S.GAIN_DIMS + S.DIST_DIMS + S.STATE_DIMS}
    assert dims["q1"].lo <= 0.02 and dims["q1"].hi >= 0.98
    assert dims["q2"].lo <= 1.02 and dims["q2"].hi >= 4.0
    assert dims["theta1"].lo <= 0.02 and dims["theta1"].hi >= 0.98
    assert dims["s2_0"].scale == "signed-log" and dims["s2_0"].hi >= 1e9
