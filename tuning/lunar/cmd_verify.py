"""``lgw verify lunar``: the property campaign of seed 001 on the general system (5)."""

from __future__ import annotations

import json

import click
from lgw.theory.errors import ParameterError


@click.command("lunar")
@click.option("--cases", type=int, default=64, show_default=True)
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--t-end", type=float, default=5.0, show_default=True, help="s")
@click.option("--u-max", type=float, default=2000.0, show_default=True,
              help="per-axis saturation of u, N (inf: none)")
@click.option("--json", "as_json", is_flag=True)
def command(cases: int, seed: int, t_end: float, u_max: float, as_json: bool) -> None:
    """V2 (13), (18), (19), (21a) against the measured runs (relative margins; < 0 violates)."""
    if not 1 <= cases <= 100_000:
        raise ParameterError("--cases", cases, "must lie in [1, 100000]")
    if not 0 < t_end <= 600:
        raise ParameterError("--t-end", t_end, "must lie in (0, 600] s")
    if not u_max > 0:
        raise ParameterError("--u-max", u_max, "must be > 0 N")
    from lgw.tuning.lunar.verify import campaign

    rows = campaign(cases, seed, t_end, u_max=u_max)
    keys = list(rows[0])
    worst = {k: min(r[k] for r in rows) for k in keys if k != "V2_max_rise_inside_band"}
    worst["V2_max_rise_inside_band"] = max(r["V2_max_rise_inside_band"] for r in rows)
    viol = {k: sum(r[k] < 0 for r in rows) for k in keys if k != "V2_max_rise_inside_band"}
    if as_json:
        click.echo(json.dumps({"worst": worst, "violations": viol, "cases": cases,
                               "seed": seed}, indent=2))
        return
    click.echo(f"{cases} random cases (seed {seed}), {t_end} s, u_max = {u_max} N, ||d|| = 0.5")
    for k in keys:
        v = viol.get(k)
        click.echo(f"  {k:26s} worst {worst[k]: .4g}" + (f"  violations {v}" if v is not None
                                                         else "  (relative to V2(0), stated)"))
