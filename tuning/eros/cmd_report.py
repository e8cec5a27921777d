"""``lgw report eros``: the derivation report (Markdown, LaTeX, HTML) of seed 002."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.tuning.eros.options import resolve_gains
from lgw.tuning.options import SEED, Integer, gains_option


@click.command("eros")
@gains_option
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              required=True, help="directory to write report.md, report.tex, report.html")
@click.option("--sim/--no-sim", "with_sim", default=True, show_default=True,
              help="fly the scenario and a campaign, judge the paper's simulation claims and "
                   "make the figures (the six variants' tracking errors, control and "
                   "chattering; the campaign's reaching and tracked times), embedded in "
                   "report.html and written beside the report")
@click.option("--cases", type=Integer(1, 10**5, "cases"), default=100, show_default=True,
              help="Monte Carlo cases for the simulation claims")
@click.option("--seed", type=SEED, default=1, show_default=True,
              help="random seed of the campaign (numpy SeedSequence)")
def command(gains_path: Path | None, out_dir: Path, with_sim: bool, cases: int,
            seed: int) -> None:
    """Derive and check every claim of seed 002 and write the report for a gain set."""
    from lgw.theory.eros.claims import all_claims
    from lgw.theory.eros.report import axis_bounds, render_documents, report_spec
    from lgw.theory.errors import ParameterError
    from lgw.tuning.eros import report_sections as RS

    g = resolve_gains(gains_path)
    if cases < 1:
        raise ParameterError("--cases", cases, "must be >= 1")
    claims = list(all_claims())
    sections = [RS.settling_section(), RS.cubic_section(), RS.gravity_section()]
    if with_sim:
        from lgw.sim.eros.batch import SimOptions
        from lgw.sim.eros.campaign import monte_carlo, scenario, table
        from lgw.tuning.eros.scenario import claims as scenario_claims

        base = SimOptions()
        scen = scenario(g, base)
        mc = monte_carlo(g, cases, seed, base)
        claims += scenario_claims(g, base, scen, mc)
        sections += RS.table2_sections(scen, table(mc[1]), cases)
        sections.append(RS.figures_section(g, base, mc, cases, seed))
    docs = render_documents(claims, report_spec(g, axis_bounds(g)), sections)
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, text in docs.items():
        (out_dir / name).write_text(text)
    from lgw.tuning.eros.figures import write

    # the figures embedded in report.html, also written beside the report
    written = [str(p) for sec in sections for p in write(list(sec.figures), out_dir)]
    counts: dict[str, int] = {}
    for c in claims:
        counts[c.verdict] = counts.get(c.verdict, 0) + 1
    click.echo(f"wrote {', '.join([str(out_dir / n) for n in docs] + written)}")
    click.echo("verdicts: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
