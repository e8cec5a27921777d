"""``lgw compare mars``: seed 000 Part 1's comparison table and figure (``compare``)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click
from lgw.theory.errors import ParameterError
from lgw.tuning.mars.compare import figure as comparison_figure
from lgw.tuning.mars.compare import format_table, run_comparison, tuned_sets
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import gains_option


@click.command("mars")
@gains_option
@click.option("--tuned", "tuned_paths", multiple=True,
              type=click.Path(dir_okay=False, path_type=Path),
              help="tuned gains file from `lgw tune` (repeatable; default: the shipped "
                   "tuning/data/tuned_tf90_50kN.toml)")
@click.option("--amplitude", type=float, default=1.0, show_default=True,
              help="A in a_p,i = A sin t (1: seed 000 Fig. 3; 20: (47))")
@click.option("--drag", type=click.Choice(("none", "physical", "printed")), default="none",
              show_default=True, help="plant drag model for every row (none: the SOCP's)")
@click.option("--n", "n", type=int, default=80, show_default=True, help="SOCP steps")
@click.option("--json", "as_json", is_flag=True, help="print JSON instead of the table")
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="write compare.json and compare.png here")
def command(gains_path: Path | None, tuned_paths: tuple[Path, ...],
            amplitude: float, drag: str, n: int, as_json: bool, out_dir: Path | None) -> None:
    """Fuel, landing time and error, peak thrust, minimum altitude: optimal vs closed loops."""
    if not (math.isfinite(amplitude) and amplitude > 0.0):
        raise ParameterError("--amplitude", amplitude, "must be a finite number > 0 m/s^2")
    if n < 10:
        raise ParameterError("--n", n, "must be an integer >= 10 (SOCP time steps)")
    gains = resolve_gains(gains_path)
    tuned = tuned_sets(list(tuned_paths))  # validated before anything runs or is written
    try:
        name = "default gains" if gains_path is None else f"gains {gains_path.name}"
        report, trajs = run_comparison(gains, tuned, amplitude=amplitude, drag=drag, n=n,
                                       gains_name=name)
    except RuntimeError as exc:
        raise click.ClickException(str(exc)) from exc
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
        (out_dir / "compare.json").write_text(json.dumps(report, indent=1))
        comparison_figure(trajs, amplitude, out_dir / "compare.png")
    if as_json:
        click.echo(json.dumps(report, indent=1))
        return
    click.echo(f"Seed 000 Part 1 comparison, Table I case, tf = {report['optimal_tf']:g} s for "
               f"the optimum, drag {drag!r}, disturbance a_p,i = {amplitude:g} sin t")
    click.echo(format_table(report))
    click.echo(report["note"])
    click.echo(report["why"])
    if out_dir is not None:
        click.echo(f"wrote {out_dir / 'compare.json'} and {out_dir / 'compare.png'}")
