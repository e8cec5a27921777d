"""Seed 001's report frame for the shared renderer ``lgw.theory.report``.

The shared renderer takes the evidence claims directly; this module gives it seed 001's
title, gain rows, bound labels, references and coverage table.
"""

from __future__ import annotations

from typing import Any

from lgw.theory.lunar.coverage import COVERAGE
from lgw.theory.lunar.gains import Gains
from lgw.theory.report import CoverageRow, ReportSpec, fmt

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


def coverage_rows() -> tuple[CoverageRow, ...]:
    """The coverage table of seed 001 (``lgw.theory.lunar.coverage.COVERAGE``) as the shared
    renderer's rows: every numbered item with its claims, or why it is not checkable."""
    return tuple(CoverageRow.of(item, "item", ids, note) for item, ids, note in COVERAGE)


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
