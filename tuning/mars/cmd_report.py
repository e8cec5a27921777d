"""Derive and check every claim of seed 000, the general ones and those judged for the gain
set, and write the report (--out: Markdown, LaTeX, HTML, claims.json and the figures) and/or
print the claims as JSON (--json)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.options import FILE
from lgw.tuning.reporting import ReportJob, ReportOptions, ReportParts
from lgw.tuning.spec import option

FIGURES_NOTE = ("Made by lgw.tuning.mars.figures from the simulator (RK4 at its default step) "
                "and the bounds of lgw.theory.mars.bounds; each caption states what was flown.  "
                "The same figures come from `lgw simulate mars ... --plot DIR`.")


@dataclass(frozen=True)
class Options(ReportOptions,
              sim="seed 000 Part 1's simulated comparison (lgw compare mars, ~20 s) and its "
                  "figure compare.png, and the claims on the paper's simulations: a search "
                  "over the gains of (25) it leaves open, each flown on Table I, II and III "
                  "(~1 min)"):
    figures: bool | None = option("--figures", None, None, "include the figures (Monte Carlo "
                                  "overlays and dispersions of Figs. 7-8 from a 300-case "
                                  "Table II campaign, settling against s1x(0) beside the "
                                  "bounds as Fig. 6, thrust against time, s1-s2 phase "
                                  "portraits; ~10 s) [default: as --sim]",
                                  secondary="--no-figures", probe=False)
    tuned: tuple = option("--tuned", FILE, (), "tuned gains file(s) for the comparison "
                          "[default: the shipped one]; repeatable", multiple=True,
                          probe=V.NO_PROBE)
    claim: tuple = option("--claim", None, (), "report only this claim (its id, e.g. "
                          "T2-printed; the findings give the command that reproduces each "
                          "refuted claim's witness); repeatable", multiple=True,
                          metavar="ID", probe=("T2-printed",))

    NEEDS_SIM = (("tuned", "the tuned sets fly in the comparison and in the search of the "
                  "paper's simulation claims"),)

    def check(self) -> None:
        super().check()
        self.refuse_unless(self.out is not None, "figures", "needs --out (figures are "
                           "written beside the report)")


@dataclass(frozen=True)
class Inputs:
    gains: Any
    gains_name: str
    compare: bool
    figures: bool
    tuned: tuple[Path, ...]
    gains_path: str = ""  # as given on the command line ("" for the built-in set)
    scenarios: bool = False  # fly the paper's scenarios for its simulation claims


def parts(inp: Inputs, progress: Any) -> ReportParts:
    from lgw.theory.mars.bounds import axis_bounds
    from lgw.theory.mars.claims import all_claims
    from lgw.theory.mars.coverage import coverage
    from lgw.theory.mars.report import report_spec
    from lgw.theory.sections import Figure, Section

    g = inp.gains
    sections = []
    record = None
    if inp.compare or inp.scenarios:
        progress.stage("Part 1 comparison (every law, RK4 and dopri5)")
        from lgw.tuning.mars.compare import figure_png, report_section, run_comparison, tuned_sets
        from lgw.tuning.mars.report_scenarios import scenario_record

        tuned = tuned_sets(list(inp.tuned))
        comparison, trajs = run_comparison(g, tuned, gains_name=inp.gains_name)
        if inp.compare:
            fig = Figure("compare.png", "Seed 000 Part 1: altitude, horizontal distance and "
                         "max_i |F_i| against time, per method, without and with the "
                         "disturbance", figure_png(trajs, comparison["thrust_max_axis"]))
            sections.append(dataclasses.replace(report_section(comparison, None),
                                                figures=(fig,)))
        progress.stage("the paper's simulation statements over the gains of (25) it leaves "
                       "open (Table I, II, III)")
        record = scenario_record(g, comparison, tuned)
    progress.stage("deriving and judging every claim of seed 000")
    claims = all_claims(g, comparison=record)
    if inp.figures:
        progress.stage("figures (Table II campaign, Fig. 6 sweep, phase portraits)")
        from lgw.tuning.mars.figures import report_figures

        figs = report_figures(g)
        sections.append(Section("Figures", (FIGURES_NOTE,), (), (), figures=tuple(figs)))
    return ReportParts(claims, report_spec(g, axis_bounds(g)), sections, coverage(),
                       reproduce=reproduce_commands(claims, inp.gains_path))


def reproduce_commands(claims: list[Any], gains_path: str) -> dict[str, str]:
    """claim id -> the command that recomputes that claim alone (its witness in the JSON):
    the claims on the paper's simulations need them (--sim), the others not (--no-sim)."""
    from lgw.theory.mars.scenario_claims import comparison_claims

    flown = {c.id for c in comparison_claims(None)}
    gains = f" --gains {gains_path}" if gains_path else ""
    return {c.id: f"lgw report mars{gains}{'' if c.id in flown else ' --no-sim'} "
                  f"--claim {c.id} --json" for c in claims}


def inputs(opts: Options) -> list[Path]:
    return list(opts.tuned)


def plan(opts: Options, system: Any) -> ReportJob:
    from lgw.tuning.mars.gains_file import load_tuned
    from lgw.tuning.mars.gainset import resolve

    g = resolve(opts.gains)  # validated before anything is written
    for p in opts.tuned:
        load_tuned(p)
    with_docs = opts.out is not None
    figures = opts.sim if opts.figures is None else opts.figures
    name = "default gains" if opts.gains is None else f"gains {opts.gains.name}"
    return ReportJob("lgw.tuning.mars.cmd_report:parts",
                     Inputs(g, name, with_docs and opts.sim, with_docs and figures,
                            tuple(opts.tuned), "" if opts.gains is None else str(opts.gains),
                            opts.sim), with_docs, only=tuple(opts.claim))
