"""Seed 002's claims: every verdict computed, every refutation carries a confirmed witness, and
the coverage table names only existing claims."""

from __future__ import annotations

import pytest
from lgw.theory.eros.claims import all_claims
from lgw.theory.eros.coverage import COVERAGE
from lgw.theory.evidence import VERDICTS

SCENARIO_IDS = {"tracked-times", "fastest-sign", "fastest-tanh", "abs-error-sign",
                "abs-error-tanh", "chatter-fuzzy", "chatter-tanh"}


def test_claims_have_computed_verdicts_and_witnesses():
    claims = all_claims()
    ids = [c.id for c in claims]
    assert len(ids) == len(set(ids))
    for c in claims:
        assert c.verdict in VERDICTS
        assert c.steps, c.id
        if c.verdict == "refuted":
            w = c.counterexample
            assert w is not None and w.confirmed, c.id
        c.to_dict()  # serialisable


def test_coverage_names_existing_claims():
    known = {c.id for c in all_claims()} | SCENARIO_IDS
    for item, _what, ids, note in COVERAGE:
        assert ids or note.startswith("not checkable, because"), item
        for n in ids:
            assert n in known, (item, n)
    # every claim is covered somewhere
    covered = {n for _i, _w, ids, _n in COVERAGE for n in ids}
    assert known <= covered, known - covered


def test_gain_set_claims_judge_the_gains_in_use():
    """The fuzzy and sampled-tanh witnesses and numbers come from the gains passed, not the
    defaults: k = 1.6 gives k dt/phi = 0.32 at the paper's dt, a witness state built for
    k = 1.6, N = 1, and its own limit-cycle sampling time."""
    from lgw.theory.eros.claims import fuzzy_vdot, fuzzy_vdot_fd
    from lgw.theory.eros.gains import default_gains

    g = default_gains().replace(k=1.6, N=1.0)
    c = {x.id: x for x in all_claims(g)}
    d = {x.id: x for x in all_claims()}
    assert c["sampled-tanh"].numbers["k_dt_over_phi"] == pytest.approx(0.32)
    assert "0.32" in c["sampled-tanh"].derived and "0.4" not in c["sampled-tanh"].derived
    assert c["sampled-tanh-limit"].numbers["dt_limit_cycle"] == pytest.approx(4 * 0.05 / 1.6)
    w = c["fuzzy-reaching"].counterexample
    assert w.confirmed and w["k"] == 1.6 and w["N"] == 1.0
    assert fuzzy_vdot(dict(w.point)) > 0 and fuzzy_vdot_fd(dict(w.point)) > 0
    for cid, x in c.items():
        if x.scope == "gain-set":
            assert x.numbers != d[cid].numbers, cid


def test_statements_are_the_paper_s_or_the_workbench_s():
    claims = {c.id: c for c in all_claims()}
    for cid in ("settling-ode", "fuzzy-condition", "sampled-tanh-limit", "pd-smc",
                "singular-term"):
        assert claims[cid].statement == "workbench", cid
    assert claims["sampled-tanh"].statement == "paper"
    assert claims["settling-ode"].verdict == "checked"
    ev = claims["settling-ode"].steps[0].evidence
    assert ev.best_margin >= 0 and claims["settling-ode"].numbers["worst_relative_error"] < 1e-7


class _Quiet:
    def stage(self, *_a, **_k) -> None:
        pass


def test_two_gain_sets_through_the_report_change_every_gain_set_claim():
    from lgw.theory.eros.gains import default_gains
    from lgw.tuning.eros.cmd_report import Inputs, parts

    def claims(g):
        return {c.id: c for c in parts(Inputs(g, False, 0, 1), _Quiet()).claims}
    a = claims(default_gains())
    b = claims(default_gains().replace(k=4.0, N=1.0, M=2.0, alpha=0.5, phi=0.08))
    scoped = [cid for cid, c in a.items() if c.scope == "gain-set"]
    assert len(scoped) >= 5
    for cid in scoped:
        assert a[cid].numbers != b[cid].numbers, cid


def test_scenario_claims_are_judged_over_a_gain_box_and_a_campaign():
    """The paper's simulation statements: reproduced at gains found by search (checked, the
    campaign re-flown by the independent route), or not reproducible within the box
    (unproven with its best margin); never refuted (seed 002 states no gains)."""
    from lgw.sim.eros.batch import SimOptions
    from lgw.sim.eros.campaign import monte_carlo, scenario
    from lgw.theory.eros.gains import default_gains
    from lgw.tuning.eros import scenario as S

    g, base = default_gains(), SimOptions(t_final=8.0)
    mc = monte_carlo(g, 4, 1, base)
    budget = S.Budget(lhs=2, cases=2, scan=False, confirm=1)
    claims = S.claims(g, base, scenario(g, base), mc, budget)
    assert {c.id for c in claims} == SCENARIO_IDS
    for c in claims:
        ev = c.steps[0].evidence
        assert c.scope == "scenario" and c.verdict in ("checked", "unproven"), c.id
        assert "gains (box B)" in ev.domain and "campaign" in ev.domain
        assert c.numbers["reproduced"] == (c.verdict == "checked")
        if c.verdict == "checked":
            assert ev.best_margin >= 0 and ev.best_point["recheck_margin"] >= 0
            assert c.derived.startswith("reproduced at")
            G = S.gains_at(g, {k: v for k, v in c.numbers["gains"].items()
                               if k not in ("p", "q")}).replace(p=c.numbers["gains"]["p"],
                                                                q=c.numbers["gains"]["q"])
            # a fresh flight of the campaign at G reproduces the margin
            st = next(s for s in S.statements(base.dt) if s.id == c.id)
            r = S.fly(G, base, S.Campaign(*mc[0]))
            assert float(st.margin(r).min()) == pytest.approx(ev.best_point["fast_margin"])
        else:
            assert c.derived.startswith("not reproducible within box B")
