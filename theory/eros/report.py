"""Seed 002's report frame for the shared renderer (``lgw.theory.report``): title, gain rows,
warnings, bound labels, references and the coverage table; the renderer takes the evidence
claims directly."""

from __future__ import annotations

from collections.abc import Sequence

from lgw.theory import report as R
from lgw.theory.eros import bounds as B
from lgw.theory.eros import parameters as P
from lgw.theory.eros.coverage import COVERAGE
from lgw.theory.eros.gains import Gains
from lgw.theory.evidence import Claim
from lgw.theory.report import ReportSpec, Section, fmt

REFERENCES = (
    "Seed 002: M. Azadmanesh, J. Roshanian, M. Hassanalian, A fuzzy fast terminal approach for "
    "tracking a probe around an asteroid, J. Aerospace Sci. Tech. (2023), "
    "doi:10.22034/jast.2022.362213.1131 (the paper under review; equation numbers refer to it).",
    "X. Yu, M. Zhihong, Fast terminal sliding-mode control design for nonlinear dynamical "
    "systems, IEEE TCAS-I 49(2), 2002 (the settling time (7), with exponent q/p).",
    "R. A. Werner, D. J. Scheeres, Exterior gravitation of a polyhedron..., Celest. Mech. Dyn. "
    "Astr. 65, 1997 (the polyhedral gravity).",
    "D. K. Yeomans et al., Radio science results during the NEAR-Shoemaker spacecraft "
    "rendezvous with Eros, Science 289, 2000 (mass, density, volume).",
    "J. K. Miller et al., Determination of shape, gravity, and rotational state of asteroid "
    "433 Eros, Icarus 155, 2002 (GM, spin rate).",
    "H. K. Khalil, Nonlinear Systems, 3rd ed., 2002 (comparison lemma 3.4).",
)

BOUND_LABELS = (
    ("s0", "s(0) of (6)", "m/s"), ("t_reach", "reaching time abs(s0)/(k - dbar)", "s"),
    ("e_max_reaching", "abs(e) bound during reaching", "m"),
    ("t_slide", "sliding settling time (6), derived", "s"),
    ("t_total", "reaching + sliding bound", "s"),
    ("ts_tsm", "(5) derived t_s", "s"), ("ts_tsm_printed", "(5) as printed", "s"),
    ("ts_ftsm", "(7) derived t_s", "s"), ("ts_ftsm_printed", "(7) as printed", "s"),
    ("t_pd", "PD surface: time to abs(e) <= TRACK_TOL", "s"),
)


def axis_bounds(g: Gains, e0=P.SCENARIO_OFFSET, ed0=P.SCENARIO_VOFFSET,
                dbar: float = 0.0) -> dict[str, dict[str, float]]:
    """Every bound per axis for initial errors e0, ed0 (the CLI, the report, the tuner)."""
    out = {}
    for i, ax in enumerate(("x", "y", "z")):
        b = B.axis_time_bound(float(e0[i]), float(ed0[i]), g, dbar)
        b["ts_tsm"] = float(B.ts_tsm(e0[i], g.beta, g.r))
        b["ts_tsm_printed"] = float(B.ts_tsm_printed(e0[i], g.beta, g.p, g.q))
        b["ts_ftsm"] = float(B.ts_ftsm(e0[i], g.alpha, g.beta, g.r))
        b["ts_ftsm_printed"] = float(B.ts_ftsm_printed(e0[i], g.alpha, g.beta, g.p, g.q))
        b["t_pd"] = float(B.t_pd(e0[i], g.lam, P.TRACK_TOL))
        out[ax] = b
    return out


def gain_warnings(g: Gains) -> list[str]:
    out = []
    if g.r < 0.5:
        out.append(f"p/q = {g.p}/{g.q} < 1/2: e'|e|^(p/q-1) is unbounded even on the sliding "
                   "surface (claim singular-term)")
    if g.N > g.M:
        out.append(f"N = {g.N} > M = {g.M}: the fuzzy reaching condition needs k >= |F| N/M")
    return out


def report_spec(g: Gains, bounds: dict[str, dict[str, float]]) -> ReportSpec:
    rows = tuple((k, fmt(v)) for k, v in g.to_dict()["gains"].items())
    note = ("Bounds for the scenario's initial error (e0 = SCENARIO_OFFSET, e0' = 0), known D, "
            "continuous-time control; the printed (5) and (7) are negative (claims settling-*).")
    return ReportSpec("Seed 002 (433 Eros, fuzzy FTSMC)", rows, tuple(gain_warnings(g)),
                      BOUND_LABELS, ("x", "y", "z"), bounds, REFERENCES, note)


def coverage_rows() -> list[R.CoverageRow]:
    """The coverage table of ``lgw.theory.eros.coverage`` as the shared renderer's rows."""
    return [R.CoverageRow.of(item, what, ids, note) for item, what, ids, note in COVERAGE]


def render_documents(claims: Sequence[Claim], spec: ReportSpec,
                     sections: Sequence[Section] = ()) -> dict[str, str]:
    """report.md / .tex / .html and claims.json (``lgw.theory.report.claims_json``, as for
    every system), with the coverage table of ``lgw.theory.eros.coverage``."""
    cov = coverage_rows()
    fns = (("report.md", R.render_markdown), ("report.tex", R.render_latex),
           ("report.html", R.render_html))
    docs = {n: f(list(claims), spec, sections, coverage=cov) for n, f in fns}
    docs["claims.json"] = R.claims_json(claims)
    return docs
