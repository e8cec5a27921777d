"""Seed 001's report frame for the shared renderer ``lgw.theory.report``.

The shared renderer reads the attributes of the older ``lgw.theory.claims.Claim`` (a verdict
string, ``evidence`` text, steps with ``method`` and ``detail``).  ``render_view`` presents a
computed-verdict ``lgw.theory.evidence.Claim`` in that shape without changing its verdict;
drop it when the renderer takes evidence claims directly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.theory.evidence import Claim
from lgw.theory.lunar.coverage import COVERAGE
from lgw.theory.lunar.gains import Gains
from lgw.theory.report import ReportSpec, Section, fmt

REFERENCES = (
    "Seed 001: Adaptive backstepping for optimal descent with input saturation and failure "
    "(the paper under review; equation numbers refer to it).",
    "M. Krstic, I. Kanellakopoulos, P. Kokotovic, Nonlinear and Adaptive Control Design, "
    "Wiley 1995 (LaSalle-Yoshizawa, Thm A.8).",
    "A. S. Konopliv et al., The JPL lunar gravity field to spherical harmonic degree 660 from "
    "the GRAIL Primary Mission, JGR Planets 118, 2013 (GM of the Moon).",
    "B. A. Archinal et al., Report of the IAU Working Group on Cartographic Coordinates and "
    "Rotational Elements: 2015, Celest. Mech. Dyn. Astr. 130, 2018 (mean lunar radius).",
)

BOUND_LABELS = (
    ("f1bar", "f1bar = lambda_min(F1)", "1/s"), ("f2bar", "f2bar = lambda_min(F2)", "1/s"),
    ("lambda1_gain_18a", "(18a) 1/sqrt(2 f1bar)", "-"),
    ("lambda1_hinf", "true L2 gain B0du -> lambda1 (H-inf)", "-"),
    ("lambda2_gain_18b", "(18b) 1/sqrt(2 f2bar - 1)", "-"),
    ("lambda2_hinf", "true L2 gain B0du -> lambda2 (H-inf)", "-"),
    ("B0du_L2", "||B0 du|| on [0, t_f], Section 5 run", "-"),
    ("lambda1_L2", "||lambda1|| measured", "-"), ("lambda1_L2_bound", "(18a) bound", "-"),
    ("lambda2_L2", "||lambda2|| measured", "-"), ("lambda2_L2_bound", "(18b) bound", "-"),
)


@dataclass(frozen=True)
class _StepView:
    status: str
    statement: str
    method: str
    detail: str


@dataclass(frozen=True)
class ClaimView:
    id: str
    equations: str
    title: str
    paper: str
    derived: str
    law: str | None
    verdict: str
    evidence: str
    steps: tuple
    remarks: tuple
    counterexample: dict | None
    numbers: dict


def render_view(c: Claim) -> ClaimView:
    def sv(s):
        return _StepView(s.status, s.statement, s.evidence.kind, s.evidence.summary())

    ce = c.counterexample
    return ClaimView(c.id, c.equations, c.title, c.paper, c.derived, c.law, c.verdict,
                     c.verdict_text() + f"; scope {c.scope}", tuple(sv(s) for s in c.steps),
                     tuple(sv(s) for s in c.remarks), ce.to_dict() if ce else None,
                     dict(c.numbers))


def coverage_section(claims: list[Claim]) -> Section:
    verdicts = {c.id: c.verdict for c in claims}
    rows = []
    for item, ids, note in COVERAGE:
        judged = ", ".join(f"{i}: {verdicts.get(i, 'not run')}" for i in ids) if ids else \
            "not checkable"
        rows.append((item, judged, note))
    return Section("Coverage of seed 001", columns=("item", "claims: verdict", "note"),
                   rows=tuple(rows), paragraphs=("Every numbered equation, hypothesis, remark "
                                                 "and simulation statement.",))


def gain_rows(g: Gains) -> tuple[tuple[str, str], ...]:
    rows = []
    for loop in ("orbit", "attitude"):
        lg = getattr(g, loop)
        for k, v in lg.to_dict().items():
            rows.append((f"{loop}.{k}", fmt(v) if not isinstance(v, list) else str(v)))
    return tuple(rows)


def report_spec(g: Gains, bounds: dict[str, dict[str, Any]], note: str = "") -> ReportSpec:
    return ReportSpec("Seed 001 (lunar)", gain_rows(g), (), BOUND_LABELS, ("orbit", "attitude"),
                      bounds, REFERENCES, note)
