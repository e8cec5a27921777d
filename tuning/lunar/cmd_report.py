"""Derive and check every claim of seed 001 for a gain set and write the report (--out:
Markdown, LaTeX, HTML, claims.json and the figures) and/or print the claims as JSON (--json).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.reporting import ReportJob, ReportOptions, ReportParts


@dataclass(frozen=True)
class Options(ReportOptions):
    sim: bool = V.sim_toggle(True, "the Section 5 case (coupled and ideal pointing, ~2-4 min) "
                             "for the scenario claims, the measured L2 norms and the figures "
                             "(tracking errors, thrust around the failure, d0e against ||d||, "
                             "V2 and Vlambda)")


@dataclass(frozen=True)
class Inputs:
    gains: Any
    scenario: bool


def parts(inp: Inputs, progress: Any) -> ReportParts:
    from lgw.theory.lunar.claims import all_claims
    from lgw.theory.lunar.report import coverage_rows, report_spec
    from lgw.tuning.lunar.report_sections import (
        bounds_table,
        reference_claim,
        reference_section,
        run_scenario,
    )

    g = inp.gains
    progress.stage("the reference trajectory (3)-(4)")
    sections, scenario, measured = [reference_section()], [], None
    if inp.scenario:
        progress.stage("the Section 5 case, coupled and ideal pointing")
        scenario, sec, measured = run_scenario()
        sections.append(sec)
    sections.append(_no_tuner_section(g))
    progress.stage("deriving and judging every claim of seed 001")
    # every gain-set claim judged for these gains; the reference (3)-(4) and Section 5 after
    claims = all_claims(g, [reference_claim(), *scenario])
    from lgw.theory.lunar.gains import paper_gains

    bounds, note = bounds_table(g, measured, paper_gains())  # the Section 5 run's gains
    return ReportParts(claims, report_spec(g, bounds, note), sections, coverage_rows())


def plan(opts: Options, system: Any) -> ReportJob:
    from lgw.tuning.lunar.gainset import resolve

    g = resolve(opts.gains)  # validated before anything is written
    return ReportJob("lgw.tuning.lunar.cmd_report:parts", Inputs(g, opts.sim),
                     opts.out is not None)


def _no_tuner_section(g):
    """Why ``lgw tune lunar`` is not offered (issue 15 asks the report to say so)."""
    import numpy as np
    from lgw.theory.lunar.parameters import M0, T_MAX, T_NOMINAL
    from lgw.theory.report import Section

    f2max = float(np.max(np.linalg.eigvalsh(np.asarray(g.orbit.F2, float))))
    ev = (T_MAX - T_NOMINAL) / (M0 * f2max)  # m/s: the error at which m F2 e_v uses the margin
    return Section("Why there is no lgw tune lunar", (
        "The natural tuning problem (gains that minimise the transient bound (21) with the orbit "
        "thrust never saturating before the failure) has no feasible point near the paper's "
        f"gains: the orbit command's feedback m F2 e_v uses the whole margin T_max - T_d = "
        f"{T_MAX - T_NOMINAL:.0f} N above the nominal thrust once |e_v| exceeds "
        f"(T_max - T_d) / (m0 lambda_max(F2)) = {ev:.3g} m/s with these gains (m0 = {M0:.0f} kg, "
        f"lambda_max(F2) = {f2max:.3g} 1/s), well below the paper's own initial velocity error "
        "[2, 3, 5] m/s.  A tuner needs a saturation-aware transient bound first; (21) assumes no "
        "saturation.",), (), ())

