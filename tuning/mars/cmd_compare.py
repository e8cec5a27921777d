"""``lgw compare mars``: seed 000 Part 1's comparison table and figure (``compare``)."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.sim.mars.laws import LAWS
from lgw.sim.mars.optimal import N_RANGE
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import THRUST_MAX_AXIS
from lgw.tuning.io import (
    atomic_write_text,
    atomic_writer,
    check_out_dir,
    json_document,
    make_out_dir,
)
from lgw.tuning.mars.compare import (
    AMPLITUDES,
    TUNED_DEFAULT,
    cannot_fly,
    format_table,
    law_gain_sets,
    run_comparison,
    tuned_law,
    tuned_sets,
)
from lgw.tuning.mars.compare import figure as comparison_figure
from lgw.tuning.mars.gains_file import load_tuned
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import Integer, Number, choice, gains_option, out_dir_option

AMPLITUDE = Number(0, 1e6, lo_open=True, unit="m/s^2")
THRUST = Number(0, 1e7, lo_open=True, unit="N")


@click.command("mars")
@gains_option
@click.option("--tuned", "tuned_paths", multiple=True,
              type=click.Path(dir_okay=False, path_type=Path),
              help="tuned gains file from `lgw tune` (repeatable; flown with the law its "
                   "certificate names; default: the shipped tuning/data/tuned_tf90_50kN.toml)")
@click.option("--dist-amplitude", "amplitudes", type=AMPLITUDE, multiple=True,
              help="A in the disturbance a_p,i = A sin t, m/s^2 (repeatable: one disturbed run "
                   "per A) [default: 1 (seed 000 Fig. 3) and 20 (seed 000 (47))]")
@click.option("--amplitude", "amplitude_old", type=AMPLITUDE, default=None, hidden=True,
              help="deprecated name of --dist-amplitude")
@click.option("--thrust-max", "thrust_max", type=THRUST, default=THRUST_MAX_AXIS,
              show_default=True,
              help="per-axis thrust limit |F_i| <= N, newtons, for the SOCP and every closed "
                   "loop (seed 000 Part 3's 50 kN)")
@click.option("--law", "laws", type=choice(tuple(LAWS)), multiple=True,
              help="registered law to fly (repeatable) [default: every registered law]")
@click.option("--drag", type=choice(("none", "physical", "printed")), default="none",
              show_default=True, help="plant drag model for every row (none: the SOCP's)")
@click.option("--n", "n", type=Integer(N_RANGE[0], N_RANGE[1], "SOCP time steps"), default=80,
              show_default=True, help="SOCP zero-order-hold steps")
@click.option("--json", "as_json", is_flag=True,
              help="print JSON instead of the table (schema: docs/json.md)")
@out_dir_option("compare.json and compare.png", dest="out_dir")
def command(gains_path: Path | None, tuned_paths: tuple[Path, ...],
            amplitudes: tuple[float, ...], amplitude_old: float | None, thrust_max: float,
            laws: tuple[str, ...], drag: str, n: int, as_json: bool, out_dir: Path | None
            ) -> None:
    """Every registered law beside the fuel-optimal baseline on Table I: outcome, landing time,
    fuel, peak thrust per axis, time saturated, thrust after arrival, minimum altitude."""
    check_out_dir(out_dir)
    if amplitude_old is not None:
        if amplitudes:
            raise ParameterError("--amplitude", amplitude_old, "is the deprecated name of "
                                 "--dist-amplitude; give only --dist-amplitude")
        click.echo("warning: --amplitude is deprecated; use --dist-amplitude", err=True)
        amplitudes = (amplitude_old,)
    amplitudes = tuple(dict.fromkeys(amplitudes)) or AMPLITUDES
    gains = resolve_gains(gains_path)
    for p in tuned_paths:  # validated before anything runs or is written
        load_tuned(p)
    tuned = tuned_sets(list(tuned_paths))
    for p, (_, tg) in zip(tuned_paths, tuned, strict=False):  # a file no law would fly
        if tuned_law(tg) not in LAWS:
            raise ParameterError(f"--tuned {p} certificate.law", tuned_law(tg),
                                 f"must be a registered law: {', '.join(LAWS)}")
    law_list = list(dict.fromkeys(laws)) or list(LAWS)
    for law in law_list:  # each law's gains (e.g. a [bounded] table) checked before any run
        for _, g in law_gain_sets(law, gains, tuned, ""):
            cannot_fly(law, g)  # raises on bad input; other failures become a table row
    try:
        name = "default gains" if gains_path is None else f"gains {gains_path.name}"
        report, trajs = run_comparison(gains, tuned, amplitudes=amplitudes, drag=drag, n=n,
                                       gains_name=name, thrust_max=thrust_max, laws=law_list)
    except RuntimeError as exc:
        raise click.ClickException(str(exc)) from exc
    flown = [(p, lab, tg) for p, (lab, tg) in zip(list(tuned_paths) or [TUNED_DEFAULT], tuned,
                                                  strict=True) if tuned_law(tg) in law_list]
    settings = {"dist_amplitudes": list(amplitudes), "thrust_max_axis": thrust_max,
                "laws": law_list, "drag": drag, "n": n, "tuned": [str(p) for p, _, _ in flown]}
    doc = {"command": "compare mars", **gains.to_dict(), "settings": settings,
           "tuned_gains": [{"label": lab, **tg.to_dict()} for _, lab, tg in flown], **report}
    text = json_document(doc, indent=1)
    if out_dir is not None:
        make_out_dir(out_dir)
        with atomic_writer(out_dir / "compare.png", "wb") as f:
            comparison_figure(trajs, thrust_max, f)
        atomic_write_text(out_dir / "compare.json", text + "\n")
    if as_json:
        click.echo(text)
        return
    amps = ", ".join(f"{a:g} sin t" for a in amplitudes)
    click.echo(f"Seed 000 Part 1 comparison, Table I case, tf = {report['optimal_tf']:g} s for "
               f"the optimum, per-axis thrust limit {thrust_max:g} N, drag {drag!r}, "
               f"disturbance 0 or a_p,i = {amps}")
    click.echo(format_table(report))
    click.echo(report["note"])
    click.echo(report["why"])
    click.echo(report["convergence"].split("; UNCONVERGED")[0])
    for line in report["convergence_flags"]:  # unconverged numbers (lgw.sim.convergence)
        click.echo(f"warning: {line}")
    if out_dir is not None:
        click.echo(f"wrote {out_dir / 'compare.json'} and {out_dir / 'compare.png'}")
