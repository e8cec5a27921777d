"""Seed 000's report: what the shared renderer (``lgw.theory.report``) puts around the claims.

The claims are ``lgw.theory.mars.claims.all_claims(gains)`` and the coverage table is
``lgw.theory.mars.coverage.coverage()``; both are passed to the renderer by the CLI."""

from __future__ import annotations

from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import AXES
from lgw.theory.report import ReportSpec, fmt

PAPER_TITLE = ("Mars Powered Descent Phase Guidance Design Based on Fixed-time Stabilization "
               "Technique (seed 000)")

REFERENCES = (
    "Seed 000: Mars powered-descent phase guidance design based on fixed-time stabilization "
    "technique (the paper under review; equation numbers refer to it).",
    "A. Polyakov, Nonlinear feedback design for fixed-time stabilization of linear control "
    "systems, IEEE TAC 57(8), 2012 (the bound (3)).",
    "R. Aldana-Lopez, D. Gomez-Gutierrez, E. Jimenez-Rodriguez, J. D. Sanchez-Torres, "
    "M. Defoort, Enhancing the settling time estimation of a class of fixed-time stable "
    "systems, IJRNC 29(12), 2019 (the least upper bound T*).",
    "B. Acikmese, S. R. Ploen, Convex programming approach to powered descent guidance for "
    "Mars landing, JGCD 30(5), 2007 (the Table I lander, Isp = 225 s, dry mass).",
    "H. K. Khalil, Nonlinear Systems, 3rd ed., Prentice Hall, 2002 (comparison lemma, Lemma "
    "3.4; positive invariance, Sec. 4.8): cited by the claims' proofs.",
    "W. Rudin, Principles of Mathematical Analysis, 3rd ed., McGraw-Hill, 1976 (monotonicity "
    "of the integral, Thm 6.12; Taylor's theorem, Thm 5.15): cited by the claims' proofs.",
)

BOUND_LABELS = [
    ("T1_polyakov", "(18) T1, Polyakov", "s"), ("T1_exact", "T1*, exact", "s"),
    ("T2_polyakov", "(26) T2, Polyakov", "s"), ("T2_exact", "T2*, exact", "s"),
    ("T_whole_paper", "paper: max{T1, T2}", "s"),
    ("landing_time_bound", "landing bound T1* + T2* (no disturbance)", "s"),
    ("landing_time_bound_polyakov", "landing bound (18) + (26)", "s"),
    ("s2_bound", "(39) |s2| neighbourhood", "m/s"), ("T2_practical", "(40) time to (39)", "s"),
    ("T2_practical_exact", "time to (39), exact", "s"),
    ("s1_bound", "(31) |r| neighbourhood", "m"), ("T1_practical", "(45) time to (31)", "s"),
    ("T1_practical_exact", "time to (31), exact", "s"),
    ("T3_paper", "(32) as printed", "s"), ("v_bound", "|v| inside both neighbourhoods", "m/s"),
    ("landing_time_bound_disturbed", "landing bound under disturbance (40*)+(45*)", "s"),
]


def gain_warnings(g: Gains) -> list[str]:
    """Notes on a gain set that is valid for the bounds but risky for a law."""
    out = []
    if g.q1 < 0.5:
        out.append(f"q1 = {g.q1} < 1/2: the term |s1|^(2 q1 - 1) of the printed law (25) is "
                   "unbounded at s1 = 0; the bounds hold, the printed law's command does not "
                   "stay bounded.")
    elif g.q1 == 0.5:
        out.append("q1 = 1/2: the term |s1|^(2 q1 - 1) sgn(s1) of (25) is the discontinuous "
                   "sgn(s1).")
    return out


def _gain_rows(g: Gains) -> list[tuple[str, str]]:
    d = g.to_dict()
    rows = [(k, ", ".join(fmt(x) for x in val) if isinstance(val, list) else fmt(val))
            for k, val in d["gains"].items()]
    if "disturbance" in d:
        rows += [(k, fmt(val)) for k, val in d["disturbance"].items()]
    return rows



BOUNDS_NOTE = ("The landing-time bounds are the workbench's own: sound for the corrected law; "
               "the printed law (25) has no proven bound (see claims V2dot-printed, T2-printed).")


def report_spec(g: Gains, bounds: dict[str, dict[str, float]]) -> ReportSpec:
    """Seed 000's frame of the report for gain set ``g`` and its ``bounds`` (axis_bounds)."""
    return ReportSpec("Seed 000", tuple(_gain_rows(g)), tuple(gain_warnings(g)),
                      tuple(BOUND_LABELS), tuple(AXES), bounds, REFERENCES, BOUNDS_NOTE,
                      paper_title=PAPER_TITLE)


def citation() -> str:
    """The references behind seed 000's bounds and claims, for users to cite."""
    return "\n".join(REFERENCES)
