"""Seed 001 derivation checks: V2' against (13), hypotheses, instances, computed verdicts; the
paper's statements judged as printed beside the workbench's corrections; the gains in use."""

import numpy as np
import pytest
import sympy as sp
from lgw.theory.evidence import VERDICTS, Claim
from lgw.theory.lunar import derivation as D
from lgw.theory.lunar import hypotheses as H
from lgw.theory.lunar import l2 as L2
from lgw.theory.lunar import law as L
from lgw.theory.lunar import scalar_run as SR
from lgw.theory.lunar.claims import theory_claims
from lgw.theory.lunar.comparison import integrate_comparison
from lgw.theory.lunar.gains import LoopGains, from_dict, paper_gains


def test_v2dot_residual_is_zero_for_every_instance():
    for S in D.systems():
        r = sp.simplify(sp.together(D.v2dot_residual(S)))
        assert r == 0, S.name


def test_v2dot_check_can_fail_when_the_law_drops_its_adaptive_term():
    # Without Phi in (7) the derivation must leave a remainder: the check discriminates.
    S = L.scalar_system()
    S.__dict__["Phi"] = sp.zeros(1, 1)  # override the cached property for this instance
    r = sp.simplify(sp.together(D.v2dot_residual(S)))
    assert r != 0


def test_underactuated_remainder_is_the_projection_term():
    c = D.rank_claim()
    assert c.verdict == "proved"
    assert "I - B0 B0^+ (n2=2, m=1)" in c.numbers


EXPECTED = {
    # the paper's statements as printed
    "V2dot": "refuted", "B0-rank": "proved", "smooth-7": "refuted", "LaSalle-14": "unproven",
    "Vlambda-16-17": "proved-given", "L2-18": "proved-given", "L2-19-20": "refuted",
    "transient-21": "refuted", "orbit-22-23": "proved", "sat-24": "refuted",
    "failure-26": "refuted", "attitude-27a": "proved", "attitude-27b": "refuted",
    "attitude-F1": "refuted",
    # the workbench's own statements (corrections and cross-checks)
    "V2dot-bound": "proved-given", "L2-18-hinf": "checked", "L2-19-20-derived": "proved-given",
    "transient-21-derived": "proved-given", "sat-24-commanded": "proved",
    "failure-26-model": "proved", "attitude-F1-bound": "proved",
}


def test_verdicts_are_computed_and_as_derived():
    claims = {c.id: c for c in theory_claims()}
    assert len(claims) == len(theory_claims())  # unique ids
    for c in claims.values():
        assert isinstance(c, Claim) and c.verdict in VERDICTS
    assert {k: c.verdict for k, c in claims.items()} == EXPECTED


def test_paper_and_workbench_statements_are_split():
    """Each correction names an existing paper claim; every refuted paper claim carries a
    confirmed witness; the four mixed claims of the old report are split."""
    claims = {c.id: c for c in theory_claims()}
    for c in claims.values():
        if c.corrects is not None:
            assert c.statement == "workbench" and claims[c.corrects].statement == "paper", c.id
        if c.verdict == "refuted":
            w = c.counterexample
            assert w is not None and w.confirmed, c.id
    fixes = {c.corrects: c.id for c in claims.values() if c.corrects}
    for paper in ("V2dot", "attitude-F1", "sat-24", "failure-26", "L2-19-20", "transient-21"):
        assert claims[paper].statement == "paper" and paper in fixes, paper
        assert claims[paper].verdict == "refuted"
        assert claims[fixes[paper]].verdict in ("proved", "proved-given")
    assert not any(c.remarks and any(s.status == "refuted" for s in c.remarks)
                   for c in claims.values()), "a refutation hidden in remarks"


def test_f1_singular_at_eq0_zero_is_an_exact_strict_witness():
    w = {c.id: c for c in theory_claims()}["attitude-F1"].counterexample
    assert w.strict and w.margin == 0.0 and w.rechecked_margin == 0.0 and w.confirmed
    assert w["e_Q"] == "[0, 1, 0, 0]"


def test_v2dot_witness_comes_from_the_law():
    w = D.v2dot_claim().counterexample
    assert w.confirmed and w["Ddot"] == "1" and w["d_0e"] == "0"
    # the same point, with D' = 0 (constant bound): the printed (13) holds there
    So = D.systems()[1]
    margin = So.norm_subs(D._rhs_13(So) - So.V2dot_z)
    pt = {**D._orbit_point(So), So.Ddot: 0}
    assert float(margin.subs(pt)) >= 0


def test_scalar_witness_of_19_20_exceeds_the_printed_and_keeps_the_derived_bounds():
    c = L2.z_l2_claim()
    w = c.counterexample
    assert w.confirmed and w.rechecked_margin < -0.5  # observed at least 1.5 x the printed bound
    o = c.numbers["witness"]
    assert o["Z1"] <= o["(19a) derived"] and o["Z2"] <= o["(19b) derived"]
    assert max(o["ratio (19a) observed/printed"], o["ratio (19b) observed/printed"]) > 1.5
    # the independent route reproduces the run
    sg = SR.scalar_gains(paper_gains().orbit)
    assert SR.margin_19(sg, w.point, True, "reference") == pytest.approx(
        w.rechecked_margin, rel=1e-9)


def test_comparison_integration_gives_the_printed_18_and_not_the_printed_19b():
    f1, f2, f3, v0 = sp.symbols("f1 f2 f3 v0", real=True)
    I = integrate_comparison({"z1": f1, "z2": f2 - f3}, {}, v0, "(13)")
    assert I.check.status == "proved"
    assert all(p.status == "proved" for p in I.proofs.values())
    assert sp.simplify(I.bounds["z2"] - v0 / (f2 - f3)) == 0
    assert sp.simplify(I.bounds["z2"] - v0 / f2) != 0  # the printed (19b) is not what it gives
    with pytest.raises(ValueError, match="constant"):  # signs are stated, never assumed
        integrate_comparison({"z1": sp.Symbol("a", positive=True)}, {}, v0, "assumed")


def test_gain_hypotheses_are_checked_on_the_gains_not_declared():
    g = paper_gains()
    bad = LoopGains(g.orbit.K1, g.orbit.F2, 1.5, 0.0, 0.01)  # f3 > f2bar (loader bypassed)
    Q = H.quantities("orbit", bad)
    assert H.f2bar_minus_f3(Q).status == "unproven"
    assert H.f2bar_minus_f3(H.quantities("orbit", g.orbit)).status == "proved"
    nondiag = LoopGains(np.eye(3), np.array([[1.0, 0.3, 0], [0.3, 2.0, 0.1], [0, 0.1, 0.7]]),
                        0.69, 0.0, 0.01)  # lambda_min(F2) = 0.6902 > f3 = 0.69, barely
    Qn = H.quantities("attitude", nondiag)
    assert float(Qn.f2bar) == pytest.approx(np.linalg.eigvalsh(nondiag.F2).min(), rel=1e-12)
    assert H.f2bar_minus_f3(Qn).status == "proved"
    assert H.f2bar_minus_f3(H.quantities("attitude", LoopGains(
        np.eye(3), nondiag.F2, 0.6905, 0.0, 0.01))).status == "unproven"


def test_gain_set_claims_judge_the_gains_in_use():
    g2 = from_dict({"orbit": {"K1": [0.2, 0.2, 0.4], "F2": [2.0, 2.0, 8.0], "f3": 0.5,
                              "d0e0": 0.0, "q": 0.05}})
    a = {c.id: c for c in theory_claims()}
    b = {c.id: c for c in theory_claims(g2)}
    n = b["L2-18"].numbers["orbit"]
    assert n["lambda1_gain_18a"] == pytest.approx(1 / (2 * 0.4) ** 0.5)
    assert n["lambda2_gain_18b"] == pytest.approx(1 / (2 * 2.0 - 1) ** 0.5)
    assert n["lambda1_hinf"] <= n["lambda1_gain_18a"]
    assert abs(n["lambda2_hinf"] - n["lambda2_sweep"]) < 1e-6
    assert a["L2-18"].numbers["orbit"]["lambda1_gain_18a"] == pytest.approx(1 / 0.2 ** 0.5)
    for cid in ("L2-18", "L2-18-hinf", "L2-19-20-derived"):
        assert a[cid].numbers != b[cid].numbers, cid
