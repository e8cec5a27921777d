"""Derive and check every claim of seed 002 for a gain set and write the report (--out:
Markdown, LaTeX, HTML, claims.json and the figures) and/or print the claims as JSON (--json).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.reporting import ReportJob, ReportOptions, ReportParts, plan_report
from lgw.tuning.spec import option


@dataclass(frozen=True)
class Options(ReportOptions, claim="settling-ftsm",
              sim="the scenario and a campaign: the paper's simulation claims and the figures "
                  "(the six variants' tracking errors, control and chattering; the campaign's "
                  "reaching and tracked times), and the whole descent to touchdown"):
    descent: bool = option("--descent", None, True, "with --sim: the whole descent from Table "
                           "1's start to touchdown (six variants, with and without navigation "
                           "errors; about a minute), its figures and claim gravity-scope",
                           secondary="--no-descent")
    cases: int = V.cases(100, "Monte Carlo cases for the simulation claims")
    seed: int = V.seed(1, "seed of the campaign")

    NEEDS_SIM = (("cases", "the campaign is the simulation"),
                 ("seed", "the campaign is the simulation"),
                 ("descent", "the descent is one of the simulations"))


@dataclass(frozen=True)
class Inputs:
    gains: Any
    sim: bool
    cases: int
    seed: int
    descent: bool = True


def parts(inp: Inputs, progress: Any) -> ReportParts:
    from lgw.theory.eros.claims import all_claims
    from lgw.theory.eros.report import axis_bounds, coverage_rows, report_spec
    from lgw.tuning.eros import report_sections as RS

    g = inp.gains
    progress.stage("deriving and judging every claim of seed 002")
    claims = list(all_claims(g))  # every gain-set claim judged for these gains
    sections = [RS.settling_section(), RS.cubic_section(), RS.gravity_section()]
    if inp.sim:
        from lgw.sim.eros.batch import SimOptions
        from lgw.sim.eros.campaign import monte_carlo, scenario, table
        from lgw.tuning.eros.scenario import claims as scenario_claims

        progress.stage(f"the scenario and a {inp.cases}-case campaign, six variants; the "
                       "paper's simulation statements over the gain box and the campaign")
        base = SimOptions()
        scen = scenario(g, base)
        mc = monte_carlo(g, inp.cases, inp.seed, base)
        claims += scenario_claims(g, base, scen, mc)
        sections += RS.table2_sections(scen, table(mc[1]), inp.cases)
        progress.stage("figures")
        sections.append(RS.figures_section(g, base, mc, inp.cases, inp.seed))
    if inp.sim and inp.descent:
        progress.stage("the whole descent to touchdown, six variants")
        from lgw.theory.eros.claims import gravity_scope_claim

        claims.append(gravity_scope_claim())
        sections += RS.descent_sections()
    return ReportParts(claims, report_spec(g, axis_bounds(g)), sections, coverage_rows())


def plan(opts: Options, system: Any) -> ReportJob:
    from lgw.tuning.eros.gainset import resolve

    g = resolve(opts.gains)  # validated before anything is written
    if opts.sim:
        from lgw.theory.eros import parameters as P
        from lgw.tuning.eros.cmd_simulate import case_bytes
        from lgw.tuning.io import check_memory

        check_memory("--cases", opts.cases, case_bytes(P.T_SCENARIO, P.DT_SAMPLE))
    return plan_report("lgw.tuning.eros.cmd_report:parts",
                       Inputs(g, opts.sim, opts.cases, opts.seed, opts.descent), opts)
