"""Evidence kinds and provers: each status comes from the data, and each prover can say no."""

from __future__ import annotations

import math

import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st
from lgw.theory.evidence import (
    Cited,
    Claim,
    FromClaim,
    Identity,
    Search,
    Step,
    Unproven,
    Witness,
    combine,
)
from lgw.theory.provers import (
    arb_enclosure,
    identity_at,
    prove_arb,
    prove_identity,
    prove_nonneg,
    prove_z3,
    refute_nonneg_at,
    run_search,
    search_step,
)

x, y, A = sp.symbols("x y A", real=True)
p = sp.Symbol("p", positive=True)


def test_identity_proves_and_refutes():
    assert prove_identity(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1, "pythagoras").status == "proved"
    s = prove_identity(sp.sin(x) ** 2 - sp.cos(x) ** 2 + 1, "false")
    assert s.status == "refuted" and s.witness.confirmed
    s = identity_at(x**2 - x, {x: 2}, "x^2 = x")
    assert s.status == "refuted" and s.witness.margin == pytest.approx(-2.0)
    # a printed number within its rounding is not a refutation
    assert identity_at(sp.Rational(30821, 1000) - sp.Rational(308217, 10000), {}, "rounded",
                       tolerance=1e-3).status == "unproven"


def test_sympy_none_is_unproven():
    s = prove_nonneg(sp.sin(p) + sp.Rational(1, 2), "SymPy cannot decide")
    assert s.evidence.answer is None and s.status == "unproven"
    assert prove_nonneg(p**2, "p^2 >= 0").status == "proved"
    s = refute_nonneg_at(x - 1, {x: 0}, "x >= 1")
    assert s.status == "refuted" and s.witness["x"] == "0"


def test_z3_proves_and_gives_models():
    ok = prove_z3(sp.Le(x * y, A * sp.Abs(x)), [sp.Le(y, A), sp.Ge(y, -A)], "|xy| <= A|x|")
    assert ok.status == "proved" and ok.evidence.answer == "unsat" and ok.evidence.certificate
    bad = prove_z3(sp.Le(x * y, A * x), [sp.Le(y, A), sp.Ge(y, -A)], "xy <= Ax")
    assert bad.status == "refuted"
    w = bad.witness
    pt = {sp.Symbol(k, real=True): sp.Rational(v) for k, v in w.point.items()}
    assert (x * y - A * x).subs(pt) > 0  # the model violates the goal, exactly


@given(lo=st.floats(0.1, 5), width=st.floats(0, 3))
def test_arb_encloses_the_true_range(lo, width):
    """Independent route: the true range of p^2 - 2p on [lo, lo + w] (closed form)."""
    hi = lo + width
    elo, ehi = arb_enclosure(p**2 - 2 * p, {p: (lo, hi)}, splits=3)
    f = lambda t: t * t - 2 * t  # noqa: E731
    tmin = f(min(max(1.0, lo), hi))
    tmax = max(f(lo), f(hi))
    assert elo <= tmin + 1e-12 and ehi >= tmax - 1e-12


def test_arb_proves_on_a_box_and_keeps_it():
    s = prove_arb(sp.gamma(p) - sp.Rational(4, 5), {p: (0.5, 3.0)}, "Gamma > 0.8", splits=5)
    assert s.status == "proved" and s.evidence.box == {"p": (0.5, 3.0)}
    # Gamma has its minimum 0.8856 near 1.46: 0.9 fails, and a box is not a witness point
    s = prove_arb(sp.gamma(p) - sp.Rational(9, 10), {p: (0.5, 3.0)}, "Gamma > 0.9", splits=5)
    assert s.status == "unproven" and s.witness is None
    s = prove_arb(1 - p, {p: (2.0, 2.0)}, "p <= 1", recheck=lambda pt: 1 - pt["p"])
    assert s.status == "refuted" and s.witness.rechecked_margin == -1.0


def test_search_is_checked_or_refuted_never_proved():
    pts = [{"x": float(i)} for i in range(10)]
    s = search_step("x <= 20", lambda pt: 20 - pt["x"], pts, domain={"x": [0, 9]}, method="grid")
    assert s.status == "checked" and s.evidence.best_margin == 11 and s.evidence.evaluations == 10
    s = search_step("x <= 5", lambda pt: 5 - pt["x"], pts, domain={"x": [0, 9]}, method="grid",
                    recheck=lambda pt: 5 - pt["x"], recheck_method="same, exact")
    assert s.status == "refuted" and s.witness["x"] == 9.0
    # without an independent re-check a negative margin does not refute, and it is not
    # "checked" either: a best margin below the tolerance is unproven
    s = search_step("x <= 5", lambda pt: 5 - pt["x"], pts, domain={"x": [0, 9]}, method="grid")
    assert s.status == "unproven"
    ev = s.evidence
    assert Step("tol", Search(ev.domain, ev.method, ev.evaluations, -1e-7, ev.best_point,
                              tolerance=1e-6)).status == "checked"
    assert Step("tol", Search(ev.domain, ev.method, ev.evaluations, -8.4e-6, ev.best_point,
                              tolerance=1e-6)).status == "unproven"
    assert run_search(lambda pt: -pt["x"], pts).best_point == {"x": 9.0}


def test_cited_and_combine():
    hyp = prove_nonneg(p, "p > 0", strict=True)
    c = Step("lemma", Cited("Khalil, Lemma 3.4", "comparison", (hyp,)))
    assert c.status == "cited"
    weak = Step("lemma", Cited("ref", "r", (Step("gap", Unproven("no proof")),)))
    assert weak.status == "unproven"
    cl = Claim("x", "(0)", "t", "p", "d", [hyp, c])
    assert cl.verdict == "proved-given" and cl.references == ["Khalil, Lemma 3.4"]
    chk = search_step("s", lambda pt: 1.0, [{"a": 1}], domain={"a": 1}, method="m")
    assert combine([hyp, c, chk]) == "checked"


def test_a_claim_used_as_a_lemma_carries_its_verdict_and_a_refuted_one_is_unproven():
    proved = Claim("a", "(1)", "t", "p", "d", [prove_nonneg(p, "p > 0", strict=True)])
    gap = Claim("b", "(2)", "t", "p", "d", [Step("gap", Unproven("no proof"))])
    assert Step("uses a", FromClaim(proved)).status == "proved"
    assert Step("uses b", FromClaim(gap)).status == "unproven"
    wrong = Claim("c", "(3)", "t", "p", "d", [search_step(
        "x <= 5", lambda pt: 5 - pt["x"], [{"x": 9.0}], domain={"x": [0, 9]}, method="grid",
        recheck=lambda pt: 5 - pt["x"], recheck_method="exact")])
    assert wrong.verdict == "refuted"
    lemma = Step("Theorem 1", Cited("paper, Theorem 1", "fixed time",
                                    (Step("Theorem 1 holds", FromClaim(wrong)),)))
    assert lemma.status == "unproven"  # citing a refuted result proves nothing
    fix = Claim("c-fixed", "(3)", "t", "p", "d", [proved.steps[0]], statement="workbench",
                corrects="c")
    assert fix.to_dict()["corrects"] == "c" and fix.to_dict()["statement"] == "workbench"
    assert combine([]) == "unproven"


def test_witness_needs_both_margins():
    assert not Witness({"x": 1}, -1.0, "m").confirmed
    assert not Witness({"x": 1}, -1.0, "m", 0.5, "r").confirmed
    assert Witness({"x": 1}, -1.0, "m", -0.5, "r").confirmed
    w = Witness({"x": 1}, -1.0, "m", -0.5, "r")
    assert Search({"x": 1}, "m", 1, -1.0, {"x": 1}, counter=w).status == "refuted"
    assert Identity(sp.Integer(1), "m").status == "unproven"
    assert math.isfinite(w.to_dict()["margin"])


def test_searches_refute_a_claim_but_never_weaken_its_proof():
    """Falsification searches of a claim's statement: a confirmed counterexample refutes
    whatever the proof steps say; a search that finds nothing leaves a proof as it is and
    makes an undecided claim checked (and one below its tolerance leaves it unproven)."""
    proof = prove_nonneg(p, "p > 0", strict=True)
    gap = Step("gap", Unproven("no proof"))
    clear = search_step("x <= 10", lambda pt: 10 - pt["x"], [{"x": 9.0}],
                        domain={"x": [0, 9]}, method="grid", budget="one point")
    below = search_step("x <= 8.99", lambda pt: 8.99 - pt["x"], [{"x": 9.0}],
                        domain={"x": [0, 9]}, method="grid")  # not re-checked: unproven
    wrong = search_step("x <= 5", lambda pt: 5 - pt["x"], [{"x": 9.0}], domain={"x": [0, 9]},
                        method="grid", recheck=lambda pt: 5 - pt["x"], recheck_method="exact")
    assert (clear.status, below.status, wrong.status) == ("checked", "unproven", "refuted")
    assert clear.evidence.budget == "one point" and "one point" in clear.evidence.summary()
    assert Claim("a", "(1)", "t", "p", "d", [proof], searches=[clear]).verdict == "proved"
    assert Claim("a", "(1)", "t", "p", "d", [proof], searches=[below]).verdict == "proved"
    c = Claim("a", "(1)", "t", "p", "d", [proof], searches=[clear, wrong])
    assert c.verdict == "refuted" and c.counterexample.point == {"x": 9.0}
    assert Claim("a", "(1)", "t", "p", "d", [gap], searches=[clear]).verdict == "checked"
    assert Claim("a", "(1)", "t", "p", "d", [], searches=[clear]).verdict == "checked"
    assert Claim("a", "(1)", "t", "p", "d", [gap], searches=[below]).verdict == "unproven"
    assert Claim("a", "(1)", "t", "p", "d", []).verdict == "unproven"
    assert c.to_dict()["searches"][1]["status"] == "refuted"


def test_a_proved_given_lemma_carries_its_references():
    hyp = prove_nonneg(p, "p > 0", strict=True)
    lemma = Claim("l", "(1)", "t", "p", "d",
                  [Step("cmp", Cited("Khalil, Lemma 3.4", "comparison", (hyp,)))])
    user = Claim("u", "(2)", "t", "p", "d", [Step("uses l", FromClaim(lemma))])
    assert user.verdict == "proved-given" and user.references == ["Khalil, Lemma 3.4"]
    assert user.verdict_text() == "proved, given Khalil, Lemma 3.4"


def test_the_witness_sampler_stays_inside_the_hypotheses():
    """A residual that vanishes only for q > 1 is not refuted by a point with q > 1: the
    sampler draws inside the stated ranges (a hypothesis 0 < q < 1 here)."""
    import random

    from lgw.theory.provers import _rational_point, identity_evidence

    q = sp.Symbol("q", positive=True)
    rng = random.Random(0)
    for _ in range(200):
        pt = _rational_point([q, x], rng, {q: (0.0, 1.0)})
        assert 0 < pt[q] < 1 and pt[x] != 0
    ev = identity_evidence(sp.Max(q - 1, 0) * x, ranges={q: (0.0, 1.0)}, simplified=x * 0 + 1)
    assert ev.status == "unproven" and ev.point_witness is None
    ev2 = identity_evidence(sp.Max(q - 1, 0) * x, ranges={q: (1.0, 3.0)}, simplified=x * 0 + 1)
    assert ev2.status == "refuted" and float(sp.Rational(ev2.point_witness["q"])) > 1
