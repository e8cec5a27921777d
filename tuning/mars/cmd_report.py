"""``lgw report mars``: the derivation report (Markdown, LaTeX, HTML) and the claims as JSON."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import click
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.claims import all_claims
from lgw.theory.mars.coverage import coverage
from lgw.theory.mars.report import report_spec
from lgw.theory.report import (
    Figure,
    Section,
    claims_json,
    render_html,
    render_latex,
    render_markdown,
    verdict_counts,
)
from lgw.tuning.io import atomic_write_text, atomic_writer, check_out_dir, make_out_dir
from lgw.tuning.mars.gains_file import load_tuned
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import gains_option

FIGURES_NOTE = ("Made by lgw.tuning.mars.figures from the simulator (RK4 at its default step) "
                "and the bounds of lgw.theory.mars.bounds; each caption states what was flown.  "
                "The same figures come from `lgw simulate mars ... --plot DIR`.")


@click.command("mars")
@gains_option
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="directory to write report.md, report.tex, report.html and "
                                 "claims.json (needed unless --json)")
@click.option("--json", "as_json", is_flag=True,
              help="print the claims as one JSON object (id, equations, paper and derived "
                   "statements, scope, verdict, steps with their evidence, witness)")
@click.option("--compare/--no-compare", "with_compare", default=True, show_default=True,
              help="include seed 000 Part 1's simulated comparison (lgw compare, ~20 s) and "
                   "its figure compare.png (only with --out)")
@click.option("--figures/--no-figures", "with_figures", default=None,
              help="include the figures (Monte Carlo overlays and dispersions of Figs. 7-8 "
                   "from a 300-case Table II campaign, settling against s1x(0) beside the "
                   "bounds as Fig. 6, thrust against time, s1-s2 phase portraits; ~10 s), "
                   "embedded in report.html and written beside the report (only with --out; "
                   "default: as --compare, so --no-compare gives the theory-only report)")
@click.option("--tuned", "tuned_paths", multiple=True,
              type=click.Path(dir_okay=False, path_type=Path),
              help="tuned gains file(s) for the comparison (default: the shipped one)")
def command(gains_path: Path | None, out_dir: Path | None, as_json: bool, with_compare: bool,
            with_figures: bool | None, tuned_paths: tuple[Path, ...]) -> None:
    """Derive and check every claim of seed 000, the general ones and those judged for the gain
    set, and write the report (--out) and/or print the claims as JSON (--json)."""
    if out_dir is None and not as_json:
        raise ParameterError("--out", None, "give --out DIR, --json, or both")
    check_out_dir(out_dir)  # before any work
    g = resolve_gains(gains_path)  # validated before anything is written
    for p in tuned_paths:
        load_tuned(p)
    claims = all_claims(g)
    text = claims_json(claims)
    images: list[Figure] = []
    if out_dir is not None:
        sections = []
        if with_compare:
            from lgw.tuning.mars.compare import (
                figure_png,
                report_section,
                run_comparison,
                tuned_sets,
            )

            tuned = tuned_sets(list(tuned_paths))
            name = "default gains" if gains_path is None else f"gains {gains_path.name}"
            comparison, trajs = run_comparison(g, tuned, gains_name=name)
            fig = Figure("compare.png", "Seed 000 Part 1: altitude, horizontal distance and "
                         "max_i |F_i| against time, per method, without and with the "
                         "disturbance", figure_png(trajs, comparison["thrust_max_axis"]))
            images.append(fig)
            sections.append(dataclasses.replace(report_section(comparison, None),
                                                figures=(fig,)))
        if with_compare if with_figures is None else with_figures:
            from lgw.tuning.mars.figures import report_figures

            figs = report_figures(g)
            images += figs
            sections.append(Section("Figures", (FIGURES_NOTE,), (), (), figures=tuple(figs)))
        spec = report_spec(g, axis_bounds(g))
        cov = coverage()
        docs = {"report.md": render_markdown(claims, spec, sections, coverage=cov),
                "report.tex": render_latex(claims, spec, sections, coverage=cov),
                "report.html": render_html(claims, spec, sections, coverage=cov),
                "claims.json": text}
        make_out_dir(out_dir)
        for name, doc in docs.items():
            atomic_write_text(out_dir / name, doc)
        for fig in images:
            with atomic_writer(out_dir / fig.file, "wb") as f:
                f.write(fig.png)
    if as_json:
        click.echo(text, nl=False)
        return
    written = [str(out_dir / n) for n in docs] + [str(out_dir / f.file) for f in images]
    click.echo(f"wrote {', '.join(written)}")
    click.echo("verdicts: " + ", ".join(f"{k} {v}" for k, v in verdict_counts(claims).items()))
