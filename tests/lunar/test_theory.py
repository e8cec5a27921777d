"""Seed 001 derivation checks: V2' against (13), hypotheses, instances, computed verdicts."""

import sympy as sp
from lgw.theory.evidence import VERDICTS, Claim
from lgw.theory.lunar import derivation as D
from lgw.theory.lunar import law as L
from lgw.theory.lunar.claims import theory_claims


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


def test_verdicts_are_computed_and_as_derived():
    claims = {c.id: c for c in theory_claims()}
    assert len(claims) == len(theory_claims())  # unique ids
    for c in claims.values():
        assert isinstance(c, Claim) and c.verdict in VERDICTS
    assert claims["V2dot"].verdict == "proved-given"
    assert claims["smooth-7"].verdict == "refuted"  # (7) is discontinuous at z2 = 0
    assert claims["LaSalle-14"].verdict == "unproven"
    assert claims["L2-19-20"].verdict == "unproven"  # printed (19b) not implied by (13)
    assert claims["attitude-27b"].verdict == "refuted"  # sign of S(e_w) L w_d in n_do
    assert claims["attitude-27a"].verdict == "proved"
    assert claims["sat-24"].verdict == "proved"


def test_smooth_claim_witness_is_confirmed():
    w = D.smooth_claim().counterexample
    assert w is not None and w.confirmed


def test_l2_claim_numbers_orbit_bound_and_true_gain():
    n = D.l2_claim().numbers["orbit"]
    assert abs(n["lambda1_gain_18a"] - 1 / (2 * 0.1) ** 0.5) < 1e-12
    assert n["lambda1_hinf"] <= n["lambda1_gain_18a"]
    assert abs(n["lambda2_hinf"] - n["lambda2_sweep"]) < 1e-6
