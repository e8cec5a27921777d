"""Derive and check every claim of seed 001 for a gain set and write the report (--out:
Markdown, LaTeX, HTML, claims.json and the figures) and/or print the claims as JSON (--json).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning.reporting import ReportJob, ReportOptions, ReportParts, plan_report


@dataclass(frozen=True)
class Options(ReportOptions, claim="attitude-F1",
              sim="the Section 5 case (coupled and ideal pointing, each checked at dt/4) for "
                  "the scenario claims, the measured L2 norms and the figures (tracking "
                  "errors, thrust around the failure, d0e against ||d||, V2 and Vlambda), and "
                  "the command filter's bandwidth swept (~2-5 min)"):
    """--gains, --json, --out, --sim/--no-sim and --claim: seed 001's report has no other
    option."""


@dataclass(frozen=True)
class Inputs:
    gains: Any
    scenario: bool
    run: Any  # lgw.sim.lunar.closed_loop.RunOptions: the gains file's filter and T_max


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
        progress.stage("the Section 5 case, coupled and ideal pointing, each at dt and dt/4; "
                       "the command filter's bandwidth swept")
        scenario, secs, measured = run_scenario(g, inp.run)
        sections.extend(secs)
    sections.append(tuning_section(g))
    progress.stage("deriving and judging every claim of seed 001")
    # every gain-set claim judged for these gains; the reference (3)-(4) and Section 5 after
    claims = all_claims(g, [reference_claim(), *scenario])
    bounds, note = bounds_table(g, measured, g)  # the Section 5 run flies these gains
    return ReportParts(claims, report_spec(g, bounds, note), sections, coverage_rows())


def plan(opts: Options, system: Any) -> ReportJob:
    from dataclasses import replace

    from lgw.sim.lunar.closed_loop import RunOptions
    from lgw.tuning.lunar.gainset import resolve, run_defaults

    g = resolve(opts.gains)  # validated before anything is written
    run = replace(RunOptions(), **run_defaults(g))
    return plan_report("lgw.tuning.lunar.cmd_report:parts", Inputs(g, opts.sim, run), opts)


def tuning_section(g):
    """The design behind the gain set: a tuned file's [certificate] promises with their
    evidence words, or, for other gains, what ``lgw tune lunar`` designs."""
    from lgw.theory.report import Section

    cert = g.extra.get("certificate")
    if cert is None:
        return Section("Tuning: lgw tune lunar", (
            "These gains carry no [certificate].  `lgw tune lunar --out FILE` designs what the "
            "paper leaves open for a target tracking error and the thrust limit with the "
            "failure: the orbit gains (from the quasi-steady offset the filter (11) keeps "
            "under the persistent failure), the command filter's bandwidth (the robust band "
            "of the sweep above) and the thrust redundancy T_max >= T_d / T_a (exact); the "
            "certificate says proven only for what is proven and sampled, with sample size "
            "and best margin, for the rest (docs/lunar.md).",), (), ())
    rows = tuple((k, str(v)) for k, v in cert.items())
    return Section("Tuning: the certificate of these gains", (
        "The [certificate] table of the gains file as lgw tune lunar wrote it; every promise "
        "names its evidence (proven, sampled with sample size and best margin, or a design "
        "estimate).  `lgw verify lunar --gains FILE` re-checks it "
        "(lgw.tuning.lunar.design.check_certificate).",), ("key", "value"), rows)
