"""``lgw report mars``: the derivation report (Markdown, LaTeX, HTML)."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.claims import all_claims
from lgw.theory.mars.report import report_spec
from lgw.theory.report import render_html, render_latex, render_markdown
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import gains_option


@click.command("mars")
@gains_option
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              required=True, help="directory to write report.md, report.tex, report.html")
@click.option("--compare/--no-compare", "with_compare", default=True, show_default=True,
              help="include seed 000 Part 1's simulated comparison (lgw compare, ~20 s) and "
                   "its figure compare.png")
@click.option("--tuned", "tuned_paths", multiple=True,
              type=click.Path(dir_okay=False, path_type=Path),
              help="tuned gains file(s) for the comparison (default: the shipped one)")
def command(gains_path: Path | None, out_dir: Path, with_compare: bool,
            tuned_paths: tuple[Path, ...]) -> None:
    """Derive and check every claim of seed 000 and write the report for a gain set."""
    g = resolve_gains(gains_path)  # validated before anything is written
    sections = []
    if with_compare:
        from lgw.tuning.mars.compare import figure, report_section, run_comparison, tuned_sets

        tuned = tuned_sets(list(tuned_paths))
        name = "default gains" if gains_path is None else f"gains {gains_path.name}"
        comparison, trajs = run_comparison(g, tuned, gains_name=name)
        out_dir.mkdir(parents=True, exist_ok=True)
        figure(trajs, comparison["amplitude"], out_dir / "compare.png")
        sections.append(report_section(comparison, "compare.png"))
    bounds = axis_bounds(g)
    claims = all_claims()
    spec = report_spec(g, bounds)
    docs = {"report.md": render_markdown(claims, spec, sections),
            "report.tex": render_latex(claims, spec, sections),
            "report.html": render_html(claims, spec, sections)}
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, text in docs.items():
        (out_dir / name).write_text(text)
    counts: dict[str, int] = {}
    for c in claims:
        counts[c.verdict] = counts.get(c.verdict, 0) + 1
    written = [str(out_dir / n) for n in docs] + ([str(out_dir / "compare.png")] if sections
                                                  else [])
    click.echo(f"wrote {', '.join(written)}")
    click.echo("verdicts: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
