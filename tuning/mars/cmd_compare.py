"""``lgw compare mars``: seed 000 Part 1's comparison table and figure (``compare``)."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.sim.mars.optimal import N_RANGE
from lgw.theory.errors import ParameterError
from lgw.tuning.io import (
    atomic_write_text,
    atomic_writer,
    check_out_dir,
    json_document,
    make_out_dir,
)
from lgw.tuning.mars.compare import TUNED_DEFAULT, format_table, run_comparison, tuned_sets
from lgw.tuning.mars.compare import figure as comparison_figure
from lgw.tuning.mars.gains_file import load_tuned
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import Integer, Number, choice, gains_option, out_dir_option

AMPLITUDE = Number(0, 1e6, lo_open=True, unit="m/s^2")


@click.command("mars")
@gains_option
@click.option("--tuned", "tuned_paths", multiple=True,
              type=click.Path(dir_okay=False, path_type=Path),
              help="tuned gains file from `lgw tune` (repeatable; default: the shipped "
                   "tuning/data/tuned_tf90_50kN.toml)")
@click.option("--dist-amplitude", "amplitude", type=AMPLITUDE, default=None,
              help="A in the disturbance a_p,i = A sin t, m/s^2 [default: 1, seed 000 Fig. 3; "
                   "(47) prints 20]")
@click.option("--amplitude", "amplitude_old", type=AMPLITUDE, default=None, hidden=True,
              help="deprecated name of --dist-amplitude")
@click.option("--drag", type=choice(("none", "physical", "printed")), default="none",
              show_default=True, help="plant drag model for every row (none: the SOCP's)")
@click.option("--n", "n", type=Integer(N_RANGE[0], N_RANGE[1], "SOCP time steps"), default=80,
              show_default=True, help="SOCP zero-order-hold steps")
@click.option("--json", "as_json", is_flag=True,
              help="print JSON instead of the table (schema: docs/json.md)")
@out_dir_option("compare.json and compare.png", dest="out_dir")
def command(gains_path: Path | None, tuned_paths: tuple[Path, ...],
            amplitude: float | None, amplitude_old: float | None, drag: str, n: int,
            as_json: bool, out_dir: Path | None) -> None:
    """Fuel, landing time and error, peak thrust, minimum altitude: optimal vs closed loops."""
    check_out_dir(out_dir)
    if amplitude_old is not None:
        if amplitude is not None:
            raise ParameterError("--amplitude", amplitude_old, "is the deprecated name of "
                                 "--dist-amplitude; give only --dist-amplitude")
        click.echo("warning: --amplitude is deprecated; use --dist-amplitude", err=True)
        amplitude = amplitude_old
    amplitude = 1.0 if amplitude is None else amplitude
    gains = resolve_gains(gains_path)
    for p in tuned_paths:  # validated before anything runs or is written
        load_tuned(p)
    tuned = tuned_sets(list(tuned_paths))
    try:
        name = "default gains" if gains_path is None else f"gains {gains_path.name}"
        report, trajs = run_comparison(gains, tuned, amplitude=amplitude, drag=drag, n=n,
                                       gains_name=name)
    except RuntimeError as exc:
        raise click.ClickException(str(exc)) from exc
    settings = {"dist_amplitude": amplitude, "drag": drag, "n": n,
                "tuned": [str(p) for p in tuned_paths] or [str(TUNED_DEFAULT)]}
    doc = {"command": "compare mars", **gains.to_dict(), "settings": settings,
           "tuned_gains": [{"label": lab, **tg.to_dict()} for lab, tg in tuned], **report}
    text = json_document(doc, indent=1)
    if out_dir is not None:
        make_out_dir(out_dir)
        with atomic_writer(out_dir / "compare.png", "wb") as f:
            comparison_figure(trajs, amplitude, f)
        atomic_write_text(out_dir / "compare.json", text + "\n")
    if as_json:
        click.echo(text)
        return
    click.echo(f"Seed 000 Part 1 comparison, Table I case, tf = {report['optimal_tf']:g} s for "
               f"the optimum, drag {drag!r}, disturbance a_p,i = {amplitude:g} sin t")
    click.echo(format_table(report))
    click.echo(report["note"])
    click.echo(report["why"])
    if out_dir is not None:
        click.echo(f"wrote {out_dir / 'compare.json'} and {out_dir / 'compare.png'}")
