"""``lgw report mars``: the derivation report (Markdown, LaTeX, HTML)."""

from __future__ import annotations

from pathlib import Path

import click

from theory.mars_bounds import axis_bounds
from theory.mars_claims import all_claims
from theory.report import render_html, render_latex, render_markdown
from tuning.options import gains_option, plant_argument, resolve_gains


@click.command("report")
@plant_argument
@gains_option
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              required=True, help="directory to write report.md, report.tex, report.html")
def command(plant: str, gains_path: Path | None, out_dir: Path) -> None:
    """Derive and check every claim of seed 000 and write the report for a gain set."""
    g = resolve_gains(gains_path)  # validated before anything is written
    bounds = axis_bounds(g)
    claims = all_claims()
    docs = {"report.md": render_markdown(claims, g, bounds),
            "report.tex": render_latex(claims, g, bounds),
            "report.html": render_html(claims, g, bounds)}
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, text in docs.items():
        (out_dir / name).write_text(text)
    counts: dict[str, int] = {}
    for c in claims:
        counts[c.verdict] = counts.get(c.verdict, 0) + 1
    click.echo(f"wrote {', '.join(str(out_dir / n) for n in docs)}")
    click.echo("verdicts: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
