"""``lgw verify mars``: a property campaign for seed 000's proven bounds (``verify``)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click
from lgw.theory.errors import ParameterError
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.mars.verify import CLAIMS, exit_code, run_campaign
from lgw.tuning.options import gains_option
from rich.console import Console
from rich.progress import Progress
from rich.table import Table


def _parse_scale(items: tuple[str, ...]) -> dict[str, float]:
    out = {}
    for it in items:
        name, _, val = it.partition("=")
        if name not in CLAIMS:
            raise ParameterError("--scale-bound", it, f"CLAIM=FACTOR, CLAIM in {', '.join(CLAIMS)}")
        try:
            out[name] = float(val)
        except ValueError:
            raise ParameterError("--scale-bound", it, "FACTOR must be a number") from None
    return out


@click.command("mars")
@gains_option
@click.option("--examples", default=32, show_default=True, help="random initial states")
@click.option("--seed", default=0, show_default=True, help="SeedSequence seed of the states")
@click.option("--batch", default=16, show_default=True, help="states per simulate_batch call")
@click.option("--dt", default=0.05, show_default=True, help="RK4 step (s)")
@click.option("--eps", default=0.05, show_default=True, help="sliding band (m, m/s)")
@click.option("--scale-bound", "scale", multiple=True, hidden=True,
              help="CLAIM=FACTOR: multiply a bound (self-test of the checker)")
@click.option("--json", "as_json", is_flag=True, help="print one JSON object")
def command(gains_path: Path | None, examples: int, seed: int, batch: int,
            dt: float, eps: float, scale: tuple[str, ...], as_json: bool) -> None:
    """Check seed 000's proven bounds on random initial states (corrected law).

    Per claim: the bound, the worst observed time, the margin, the closest case (its initial
    state and seed reproduce it) and a verdict.  Exit code 1 when a proven bound is violated.
    """
    g = resolve_gains(gains_path)
    for name, x in (("dt", dt), ("eps", eps)):
        if not x > 0:
            raise ParameterError(name, x, "must be > 0")
    sc = _parse_scale(scale)
    if as_json:
        results = run_campaign(g, examples, seed, dt=dt, eps=eps, scale=sc, batch=batch)
    else:
        with Progress(transient=True) as prog:
            task = prog.add_task("flying cases", total=examples)
            results = run_campaign(g, examples, seed, dt=dt, eps=eps, scale=sc, batch=batch,
                                   progress=lambda done, _t: prog.update(task, completed=done))
    code = exit_code(results)
    if as_json:
        click.echo(json.dumps({"examples": examples, "seed": seed, "dt": dt, "eps": eps,
                               "claims": [r.to_dict() for r in results], "exit_code": code},
                              indent=2, default=float))
    else:
        t = Table(title=f"lgw verify mars: {examples} states, seed {seed}, dt {dt}, eps {eps}")
        for col in ("claim", "eq.", "bound s", "worst s", "obs/bound", "margin s",
                    "skipped", "verdict"):
            t.add_column(col)
        for r in results:
            color = "green" if r.verdict == "holds" else "red"
            t.add_row(r.claim, r.equation, f"{r.bound:.4g}", f"{r.worst:.4g}",
                      f"{r.ratio:.3g}", f"{r.margin:.4g}",
                      f"{r.n_nonfinite}+{r.n_unresolved}/{r.n_cases}",
                      f"[{color}]{r.verdict}[/]")
        con = Console()
        con.print(t)
        con.print("skipped = nonfinite (simulator) + unresolved (a step over the s1 = 0 "
                  "singularity of the command) / cases; obs/bound > 1 is a violation")
        for r in results:
            c = r.closest
            if c:
                con.print(f"{r.claim}: closest case {c['case']} axis {c['axis']} "
                          f"({c['disturbance']}), seed {c['seed']}, r0 = {c['r0']}, "
                          f"v0 = {c['v0']}")
    sys.exit(code)
