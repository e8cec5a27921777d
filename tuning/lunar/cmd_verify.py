"""``lgw verify lunar``: seed 001's bounds (13), (18), (19), (21a) on random cases of the general
system (5), per claim: checked and excluded counts, the worst relative margin and a verdict.

Exit codes: 0 every claim holds (on at least --min-cases checked cases); 1 a claim is violated
(a witness re-checked at half the step is printed); 4 inconclusive (fewer than --min-cases
checked cases, e.g. excluded because nothing could be checked on them, or a violation that the
re-check did not confirm).
"""

from __future__ import annotations

import json
import sys

import click
from lgw.theory.errors import ParameterError
from lgw.tuning.options import SEED, Integer, Number


def _parse_scale(items: tuple[str, ...]) -> dict[str, float]:
    from lgw.tuning.lunar.verify import SCALABLE

    out = {}
    for it in items:
        name, _, val = it.rpartition("=")
        if name not in SCALABLE:
            raise ParameterError("--scale", it, f"CLAIM=FACTOR with CLAIM in {list(SCALABLE)}")
        try:
            f = float(val)
        except ValueError:
            raise ParameterError("--scale", it, "FACTOR must be a number > 0") from None
        if not f > 0:
            raise ParameterError("--scale", it, "FACTOR must be a number > 0")
        out[name] = f
    return out


@click.command("lunar")
@click.option("--cases", type=Integer(1, 10**6, "cases"), default=64, show_default=True,
              help="random initial errors and gains flown")
@click.option("--seed", type=SEED, default=0, show_default=True,
              help="random seed (numpy SeedSequence); integer in [0, 2^64 - 1]")
@click.option("--t-end", type=Number(0, 1e4, lo_open=True, unit="s"), default=5.0,
              show_default=True, help="flight time per case (s)")
@click.option("--dt", type=Number(0, 1, lo_open=True, unit="s"), default=0.02,
              show_default=True, help="RK4 step (s)")
@click.option("--u-max", type=Number(0, lo_open=True, unit="N; inf: none"), default=2000.0,
              show_default=True, help="per-axis saturation of u (N; inf: none)")
@click.option("--min-cases", type=Integer(1, 10**6, "cases"), default=None,
              help="checked cases a claim needs to hold [default: 30]")
@click.option("--scale", multiple=True, metavar="CLAIM=FACTOR",
              help="multiply a bound (self-test of the checker), e.g. '(19a)=0.5' "
                   "[default: none]")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (strict, with lgw_version)")
def command(cases: int, seed: int, t_end: float, dt: float, u_max: float,
            min_cases: int | None, scale: tuple[str, ...], as_json: bool) -> None:
    """V2 (13), (18), (19), (21a) against measured runs: per claim checked / excluded cases,
    worst relative margin (< 0 violates), result; exit 1 on a violation, 4 if inconclusive."""
    from lgw.tuning.lunar.verify import MIN_CASES

    if not 1 <= cases <= 100_000:
        raise ParameterError("--cases", cases, "must lie in [1, 100000]")
    if not 0 < t_end <= 600:
        raise ParameterError("--t-end", t_end, "must lie in (0, 600] s")
    if not 0 < dt <= 0.1:
        raise ParameterError("--dt", dt, "must lie in (0, 0.1] s")
    if not u_max > 0:
        raise ParameterError("--u-max", u_max, "must be > 0 N")
    min_cases = MIN_CASES if min_cases is None else min_cases
    if min_cases < 1:
        raise ParameterError("--min-cases", min_cases, "must be an integer >= 1")
    sc = _parse_scale(scale)
    from lgw.sim.lunar.outcomes import json_safe
    from lgw.tuning.lunar.verify import exit_code, verify

    rows = verify(cases, seed, t_end, dt=dt, u_max=u_max, min_cases=min_cases, scale=sc)
    code = exit_code(rows)
    if as_json:
        click.echo(json.dumps(json_safe({"cases": cases, "seed": seed, "t_end": t_end, "dt": dt,
                                         "u_max": u_max, "min_cases": min_cases,
                                         "claims": rows, "exit_code": code}), indent=2,
                              allow_nan=False))
    else:
        click.echo(f"lgw verify lunar: {cases} random cases (seed {seed}), {t_end} s, dt {dt} s,"
                   f" u_max = {u_max} N, ||d|| = 0.5; holds needs >= {min_cases} checked")
        click.echo(f"  {'claim':22s} {'checked':>8s} {'excluded':>8s} {'violations':>10s} "
                   f"{'worst margin':>13s}  result")
        for r in rows:
            wm = "-" if r["worst_margin"] is None else f"{r['worst_margin']:.4g}"
            click.echo(f"  {r['claim']:22s} {r['checked']:8d} {r['excluded']:8d} "
                       f"{r['violations']:10d} {wm:>13s}  {r['result']}")
        for r in rows:
            for why, k in r["excluded_reasons"].items():
                click.echo(f"  {r['claim']}: {k} excluded: {why}")
            if r["witness"]:
                w = r["witness"]
                click.echo(f"  {r['claim']}: witness {json.dumps(json_safe(w['point']))}, margin"
                           f" {w['margin']:.4g}, re-checked {w['rechecked_margin']:.4g} "
                           f"({w['recheck_method']})")
            elif r["result"] == "inconclusive":
                why = (f"only {r['checked']} checked < {min_cases}" if r["checked"] < min_cases
                       else "a violation the re-check at dt/2 did not confirm")
                click.echo(f"  {r['claim']}: inconclusive: {why}")
    sys.exit(code)
