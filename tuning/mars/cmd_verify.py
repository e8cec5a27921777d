"""``lgw verify mars``: seed 000's proven bounds for one gain set, never passing on missing
evidence (``lgw.tuning.mars.verify``).  Exit 0 holds, 1 violated, 4 inconclusive, 2 bad input."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import click
from lgw.theory.errors import ParameterError
from lgw.tuning.io import check_out_dir, console, json_document
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.mars.verify import (
    CLAIMS,
    MIN_CASES,
    PROFILES,
    VerifyOptions,
    certificate_scale,
    exit_code,
    run_verify,
)
from lgw.tuning.options import SEED, Integer, Number, choice, gains_option
from lgw.tuning.verify_common import print_claim_details
from rich.console import Console
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


def _fmt(x: float, spec: str = ".4g") -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


@click.command("mars")
@gains_option
@click.option("--profile", type=choice(PROFILES), default="ci", show_default=True,
              help="ci: 20 Hypothesis examples per claim group, small search budget; "
                   "thorough: 150 examples, a larger search")
@click.option("--seed", type=SEED, default=0, show_default=True,
              help="derandomised run with this seed (Hypothesis and the search); integer in "
                   "[0, 2^64 - 1]")
@click.option("--random", "random_", is_flag=True, help="a random run (ignores --seed)")
@click.option("--examples", type=Integer(1, 100_000, "examples"), default=None,
              help="Hypothesis examples per claim group [default: the profile's]")
@click.option("--min-cases", type=Integer(1, 10**7, "cases"), default=MIN_CASES,
              show_default=True, help="checked simulated cases a claim needs for 'holds'")
@click.option("--database", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Hypothesis example database folder: replays earlier failures first and "
                   "saves new ones; makes the run random (Hypothesis uses no database in a "
                   "seeded run) [default: none]")
@click.option("--dt", type=Number(0, 1, lo_open=True, unit="s"), default=0.05,
              show_default=True, help="RK4 step (s)")
@click.option("--eps", type=Number(0, lo_open=True, unit="m or m/s"), default=0.05,
              show_default=True, help="sliding band (m, m/s)")
@click.option("--scale-bound", "scale", multiple=True, hidden=True,
              help="CLAIM=FACTOR: multiply a bound (self-test of the checker)")
@click.option("--no-simulate", "no_sim", is_flag=True, hidden=True,
              help="search only (no simulation: every claim is then inconclusive or violated)")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write verify_mars.png (observed against bound, one point "
                                 "per checked simulated case and axis) to DIR [default: none]")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (schema: docs/json.md)")
def command(gains_path: Path | None, profile: str, seed: int, random_: bool,
            examples: int | None, min_cases: int, database: Path | None, dt: float, eps: float,
            scale: tuple[str, ...], no_sim: bool, plot_dir: Path | None, as_json: bool) -> None:
    """Check seed 000's proven bounds for a gain set (corrected law).

    Per claim: a falsification search on the exact reduced per-axis loop and Hypothesis-driven
    simulations; the verdict is holds (>= --min-cases checked cases, no violation), violated
    (exit 1, shrunk witness and a ready-to-paste reproduction) or inconclusive (exit 4).
    """
    check_out_dir(plot_dir, "--plot")  # before any work
    g = resolve_gains(gains_path)
    sc = {**certificate_scale(g), **_parse_scale(scale)}
    opts = VerifyOptions(profile=profile, seed=None if random_ else seed, database=database,
                         min_cases=min_cases, dt=dt, eps=eps, scale=sc, examples=examples,
                         simulate=not no_sim)
    con = Console(stderr=True)
    if as_json:
        results = run_verify(g, opts)
    else:
        with con.status("verifying") as st:
            results = run_verify(g, opts, progress=lambda s: st.update(s))
    code = exit_code(results)
    if plot_dir is not None:
        from lgw.tuning.figures import write_verify_plot
        from lgw.tuning.mars.verify import plot_panels

        path = write_verify_plot(plot_dir, "mars", plot_panels(results),
                                 f"lgw verify mars: profile {profile}, seed {opts.seed}, "
                                 f"dt {dt} s")
        if not as_json:
            con.print(f"wrote {path}")
    if as_json:
        click.echo(json_document({"command": "verify mars", **g.to_dict(), "profile": profile,
                                  "seed": opts.seed, "dt": dt, "eps": eps,
                                  "min_cases": min_cases, "scale": sc,
                                  "claims": [r.to_dict() for r in results],
                                  "exit_code": code}, indent=2))
        sys.exit(code)
    t = Table(title=f"lgw verify mars: profile {profile}, seed {opts.seed}, dt {dt}, eps {eps}")
    for col in ("claim", "eq.", "checked/cases", "dopri5", "excluded", "worst obs/bound",
                "search best margin", "verdict"):
        t.add_column(col)
    for r in results:
        color = {"holds": "green", "violated": "red"}.get(r.verdict, "yellow")
        best = min((s["best_margin"] for s in r.search), default=math.nan)
        t.add_row(r.claim, r.equation, f"{r.n_checked}/{r.n_cases}", str(r.n_adaptive),
                  str(r.n_excluded), _fmt(r.ratio, ".3g"), _fmt(best, ".3g"),
                  f"[{color}]{r.verdict}[/]")
    out = console()
    out.print(t)
    out.print("checked = simulated cases judged (dopri5: of them, carried by the adaptive path "
              "after RK4 could not); excluded: no integrator carried them; search best margin "
              "= least (bound - observed)/bound on the reduced loop, < 0 violates")
    print_claim_details(out, results, extra=lambda r: [
        f"{r.claim} search (axis {s['axis']}): {s['evaluations']} evaluations, "
        f"best margin {s['best_margin']:.4g}, {s['status']}" for s in r.search])
    sys.exit(code)
