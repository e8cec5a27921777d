"""``lgw report lunar``: the derivation report of seed 001 (Markdown, LaTeX, HTML)."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.tuning.io import atomic_write_text, check_out_dir, make_out_dir
from lgw.tuning.lunar.options import resolve_gains
from lgw.tuning.options import gains_option


@click.command("lunar")
@gains_option
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              required=True, help="directory to write report.md, report.tex, report.html")
@click.option("--scenario/--no-scenario", "with_scenario", default=True, show_default=True,
              help="fly the Section 5 case (coupled and ideal pointing, ~2-4 min) for the "
                   "scenario claims, the measured L2 norms and the figures (tracking errors, "
                   "thrust around the failure, d0e against ||d||, V2 and Vlambda), embedded "
                   "in report.html and written beside the report")
def command(gains_path: Path | None, out_dir: Path, with_scenario: bool) -> None:
    """Derive and check every claim of seed 001 and write the report."""
    check_out_dir(out_dir)  # before any work
    g = resolve_gains(gains_path)  # validated before anything is written
    from lgw.theory.lunar.claims import all_claims
    from lgw.theory.lunar.report import coverage_rows, report_spec
    from lgw.theory.report import claims_json, render_html, render_latex, render_markdown
    from lgw.tuning.lunar.figures import write
    from lgw.tuning.lunar.report_sections import bounds_table, reference_section, run_scenario

    sections, scenario, figs = [reference_section()], [], ()
    measured = None
    if with_scenario:
        scenario, sec, measured = run_scenario()
        sections.append(sec)
        figs = sec.figures  # embedded in report.html, written beside the report
    sections.append(_no_tuner_section(g))
    claims = all_claims(scenario)
    cov = coverage_rows()
    bounds, note = bounds_table(g, measured)
    spec = report_spec(g, bounds, note)
    docs = {"report.md": render_markdown(claims, spec, sections, coverage=cov),
            "report.tex": render_latex(claims, spec, sections, coverage=cov),
            "report.html": render_html(claims, spec, sections, coverage=cov),
            "claims.json": claims_json(claims)}
    make_out_dir(out_dir)
    for name, text in docs.items():
        atomic_write_text(out_dir / name, text)
    written = [str(p) for p in write(list(figs), out_dir)]
    counts: dict[str, int] = {}
    for c in claims:
        counts[c.verdict] = counts.get(c.verdict, 0) + 1
    click.echo(f"wrote {', '.join([str(out_dir / n) for n in docs] + written)}")
    click.echo("verdicts: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))


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

