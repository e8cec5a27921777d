"""Walk every claim of every system: each verdict is the combination of its steps, each step's
evidence is of the kind its status needs, and every refuted claim's witness reproduces.

Systems are found as ``lgw.theory.<system>.claims.all_claims`` (called with the system's
default gain set when it takes one, so the gain-set claims are walked too).
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import lgw.theory
import pytest
import sympy as sp
from lgw.theory.evidence import (
    Cited,
    Claim,
    Evidence,
    FromClaim,
    Identity,
    Inequality,
    Search,
    Step,
    Unproven,
    Witness,
    combine,
    verdict_of,
)

# with pytest-xdist (--dist loadgroup), on the worker that derives seed 000's claims once
pytestmark = pytest.mark.xdist_group("mars-claims")


def systems() -> list[str]:
    out = []
    for m in pkgutil.iter_modules(lgw.theory.__path__):
        if m.ispkg and importlib.util.find_spec(f"lgw.theory.{m.name}.claims") is not None:
            out.append(m.name)
    return sorted(out)


def claims_of(system: str) -> list[Claim]:
    mod = importlib.import_module(f"lgw.theory.{system}.claims")
    fn = mod.all_claims
    required = [p for p in inspect.signature(fn).parameters.values()
                if p.default is inspect.Parameter.empty]
    if required:  # claims judged for a gain set: the system's built-in gains
        gains_mod = importlib.import_module(f"lgw.theory.{system}.gains")
        return fn(gains_mod.default_gains())
    return fn()


def walk(steps):
    for s in steps:
        yield s
        if isinstance(s.evidence, Cited):
            yield from walk(s.evidence.hypotheses)


def evidence_supports(ev: Evidence, status: str) -> str | None:
    """None if ``ev`` is the kind of evidence ``status`` needs, else why not.  Judged from the
    evidence's data directly, not from its ``status`` property."""
    if isinstance(ev, FromClaim):  # a lemma's verdict carries over, never stronger
        want = {"proved": "proved", "proved-given": "cited", "checked": "checked"}.get(
            ev.claim.verdict, "unproven")
        return None if status == want else f"claim {ev.claim.id} ({ev.claim.verdict}) " \
                                           f"used as {status}"
    if status == "proved":
        if isinstance(ev, Identity):
            return None if sp.sympify(ev.residual) == 0 else "proved identity, nonzero residual"
        if isinstance(ev, Inequality):
            ok = {"z3": ev.answer == "unsat",
                  "arb": ev.lower is not None and (ev.lower > 0 or (not ev.strict
                                                                    and ev.lower >= 0)),
                  "sympy": ev.answer is True,
                  "sos": ev.answer == "feasible" and ev.certificate is not None}[ev.prover]
            if ev.prover == "arb" and not ev.box:
                return "an Arb proof without its box"
            if ev.prover == "z3" and not ev.certificate:
                return "a z3 proof without its query"
            return None if ok else f"proved inequality without a proving {ev.prover} answer"
        return f"proved by {ev.kind} evidence"
    if status == "checked":
        if not isinstance(ev, Search):
            return f"checked by {ev.kind} evidence"
        if not (ev.domain and ev.method and ev.evaluations >= 1 and ev.best_point is not None):
            return "a search without domain, method, budget or best point"
        return None
    if status == "refuted":
        w = ev.witness
        if not isinstance(w, Witness):
            return "refuted without a witness"
        # a strict claim (x > 0) is violated by an exact 0 as well (Witness.strict)
        neg = (lambda m: m <= 0) if getattr(w, "strict", False) else (lambda m: m < 0)
        if not (neg(w.margin) and w.rechecked_margin is not None and neg(w.rechecked_margin)
                and w.recheck_method):
            return "refuted by a witness not re-checked by an independent route"
        return None
    if status == "cited":
        if not isinstance(ev, Cited) or not ev.reference:
            return "cited without a reference"
        if not ev.hypotheses:
            return "cited without checked hypotheses"
        bad = [h.status for h in ev.hypotheses if h.status not in ("proved", "cited")]
        return f"cited with hypotheses {bad}" if bad else None
    if status == "unproven":
        if isinstance(ev, Unproven):
            return None if ev.reason else "an unproven gap without a reason"
        return None  # a prover that did not decide: always allowed to be weaker
    return f"unknown status {status}"


_WEAKEST_FIRST = ("refuted", "unproven", "checked", "cited", "proved")
_VERDICT_OF = {"refuted": "refuted", "unproven": "unproven", "checked": "checked",
               "cited": "proved-given", "proved": "proved"}


def expected_verdict(steps, searches=()) -> str:
    """The combination rule written again here (independent of evidence.combine): a
    conclusion that needs every step is as weak as its weakest step; no step, unproven.  A
    refuted falsification search refutes; searches that found nothing make an undecided
    proof (unproven, or no steps) checked, and never weaken a proof."""
    if any(s.status == "refuted" for s in searches):
        return "refuted"
    st = {s.status for s in steps}
    proof = "unproven"
    for s in _WEAKEST_FIRST:
        if s in st:
            proof = _VERDICT_OF[s]
            break
    if proof == "unproven" and searches:
        sst = {s.status for s in searches}
        if sst and sst <= {"checked", "proved", "cited"}:
            return "checked"
    return proof


def check_claim(c: Claim) -> list[str]:
    problems = []
    want = expected_verdict(c.steps, c.searches)
    if c.verdict != want or c.verdict != verdict_of(c.steps, c.searches):
        problems.append(f"verdict {c.verdict} is not the combination {want}")
    if not c.searches and c.verdict != combine(c.steps):
        problems.append("without searches the verdict must be the combination of the steps")
    if not c.steps and not c.searches:
        problems.append("no steps and no searches")
    for s in c.searches:
        if not isinstance(s.evidence, Search | Unproven):
            problems.append(f"search {s.statement[:60]!r} is {s.evidence.kind} evidence")
        elif isinstance(s.evidence, Search) and not (s.evidence.domain and s.evidence.budget):
            problems.append(f"search {s.statement[:60]!r} states no domain or budget")
    for s in walk(c.steps + c.remarks + c.searches):
        if not isinstance(s, Step):
            problems.append(f"not a Step: {s!r}")
            continue
        why = evidence_supports(s.evidence, s.status)
        if why:
            problems.append(f"step {s.statement[:60]!r}: {why}")
    if c.verdict == "refuted":
        w = c.counterexample
        if w is None or not w.confirmed:
            problems.append("refuted without a confirmed witness")
    return problems


def all_system_claims() -> list[tuple[str, Claim]]:
    return [(sys_, c) for sys_ in systems() for c in claims_of(sys_)]


@pytest.fixture(scope="module")
def every_claim():
    return all_system_claims()


def test_there_are_systems_and_claims(every_claim):
    assert "mars" in systems()
    assert len(every_claim) >= 30


def test_every_claim_walks(every_claim):
    bad = {f"{s}:{c.id}": p for s, c in every_claim if (p := check_claim(c))}
    assert not bad, bad


def test_refuted_witnesses_reproduce(every_claim):
    """Every refuted claim's witness reproduces: the claim rebuilt from scratch (caches
    cleared) gives the same witness, point and margins."""
    import lgw.theory.mars.bounded_claims as BC
    import lgw.theory.mars.claims as MC
    import lgw.theory.mars.mss as MM
    import lgw.theory.mars.searches as MS
    import lgw.theory.settling_proofs as SP

    before = {c.id: c.counterexample for _, c in every_claim if c.verdict == "refuted"}
    for mod in (MC, SP, BC, MM, MS):
        for name in dir(mod):
            f = getattr(mod, name)
            if hasattr(f, "cache_clear"):
                f.cache_clear()
    after = {c.id: c.counterexample for _, c in all_system_claims() if c.verdict == "refuted"}
    assert before.keys() == after.keys()
    for cid, w in before.items():
        w2 = after[cid]
        assert w2.point == w.point and w2.margin == pytest.approx(w.margin, rel=1e-9), cid
        assert w2.confirmed, cid


def _first(claims, pred):
    for c in claims:
        for s in walk(c.steps):
            if pred(s):
                return c, s
    raise AssertionError("no such step")


def test_walk_fails_when_a_status_is_unsupported(every_claim, monkeypatch):
    """Break one step for a moment: an Identity whose residual is made nonzero, an Arb proof
    whose enclosure is made negative, a z3 proof made "unknown", a search made to claim
    refutation without a re-check.  The walk must go red for each."""
    claims = [c for _, c in every_claim]
    c, s = _first(claims, lambda s: isinstance(s.evidence, Identity) and s.status == "proved")
    assert not check_claim(c)
    # the evidence claims "proved" (as a string-typed status would) while its residual is 1
    monkeypatch.setattr(type(s.evidence), "status", property(lambda self: "proved"))
    object.__setattr__(s.evidence, "residual", sp.Integer(1))
    assert any("nonzero residual" in p for p in check_claim(c))
    object.__setattr__(s.evidence, "residual", sp.Integer(0))
    monkeypatch.undo()
    assert not check_claim(c)

    c, s = _first(claims, lambda s: isinstance(s.evidence, Inequality)
                  and s.evidence.prover == "arb" and s.status == "proved")
    monkeypatch.setattr(Inequality, "status", property(lambda self: "proved"))
    lower = s.evidence.lower
    object.__setattr__(s.evidence, "lower", -1.0)
    assert any("proving arb" in p for p in check_claim(c))
    object.__setattr__(s.evidence, "lower", lower)
    monkeypatch.undo()

    c, s = _first(claims, lambda s: isinstance(s.evidence, Inequality)
                  and s.evidence.prover == "z3" and s.status == "proved")
    monkeypatch.setattr(Inequality, "status", property(lambda self: "proved"))
    object.__setattr__(s.evidence, "answer", "unknown")
    assert any("proving z3" in p for p in check_claim(c))
    object.__setattr__(s.evidence, "answer", "unsat")
    monkeypatch.undo()

    c, s = _first(claims, lambda s: isinstance(s.evidence, Search) and s.status == "refuted")
    w = s.evidence.counter
    method = w.recheck_method
    object.__setattr__(w, "recheck_method", "")
    assert any("independent route" in p for p in check_claim(c))
    object.__setattr__(w, "recheck_method", method)
    # a verdict that is not the combination of the steps
    monkeypatch.setattr(Claim, "verdict", property(lambda self: "proved"))
    assert any("not the combination" in p for p in check_claim(c))
