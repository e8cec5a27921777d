"""``lgw verify lunar``: seed 001's bounds (13), (18), (19), (21a) for one gain set's orbit loop
on Hypothesis-drawn initial errors of the general system (5) (``lgw.tuning.lunar.verify``).

Exit codes: 0 every claim holds (on at least --min-cases checked cases); 1 a claim is violated
(the shrunk witness, re-checked at half the step, and a reproduction are printed); 4
inconclusive (fewer than --min-cases checked cases, e.g. excluded because nothing could be
checked on them, or a violation the re-check did not confirm); 2 bad input.
"""

from __future__ import annotations

import sys
from pathlib import Path

import click
from lgw.tuning.io import check_out_dir, console, json_document
from lgw.tuning.options import SEED, Integer, Number, choice, gains_option
from lgw.tuning.verify_common import print_claim_details

PROFILE_NAMES = ("ci", "thorough")


@click.command("lunar")
@gains_option
@click.option("--profile", type=choice(PROFILE_NAMES), default="ci", show_default=True,
              help="ci: 16 Hypothesis examples (batches of 1..8 initial errors); thorough: 120")
@click.option("--seed", type=SEED, default=0, show_default=True,
              help="derandomised run with this seed (Hypothesis); integer in [0, 2^64 - 1]")
@click.option("--random", "random_", is_flag=True, help="a random run (ignores --seed)")
@click.option("--examples", type=Integer(1, 100_000, "examples"), default=None,
              help="Hypothesis examples [default: the profile's]")
@click.option("--database", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Hypothesis example database folder: replays earlier failures first and "
                   "saves new ones; makes the run random (Hypothesis uses no database in a "
                   "seeded run) [default: none]")
@click.option("--t-end", type=Number(0, 600, lo_open=True, unit="s"), default=5.0,
              show_default=True, help="flight time per case (s)")
@click.option("--dt", type=Number(0, 0.1, lo_open=True, unit="s"), default=0.02,
              show_default=True, help="RK4 step (s)")
@click.option("--u-max", type=Number(0, lo_open=True, unit="N; inf: none"), default=2000.0,
              show_default=True, help="per-axis saturation of u (N; inf: none)")
@click.option("--min-cases", type=Integer(1, 10**6, "cases"), default=None,
              help="checked cases a claim needs to hold [default: 30]")
@click.option("--scale", multiple=True, metavar="CLAIM=FACTOR",
              help="multiply a bound (self-test of the checker), e.g. '(19a)=0.5' "
                   "[default: none]")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write verify_lunar.png (observed against bound, one point "
                                 "per checked case) to DIR [default: none]")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (strict, with lgw_version)")
def command(gains_path: Path | None, profile: str, seed: int, random_: bool,
            examples: int | None, database: Path | None, t_end: float, dt: float,
            u_max: float, min_cases: int | None, scale: tuple[str, ...], plot_dir: Path | None,
            as_json: bool) -> None:
    """V2 (13), (18), (19), (21a) against measured runs of the orbit loop of a gain set: per
    claim checked / excluded cases, worst relative margin (< 0 violates), verdict; exit 1 on a
    violation, 4 if inconclusive."""
    check_out_dir(plot_dir, "--plot")  # before any work
    from lgw.tuning.lunar.options import resolve_gains
    from lgw.tuning.lunar.verify import (
        MIN_CASES,
        VerifyOptions,
        plot_panels,
        result_exit_code,
        run_verify,
    )

    g = resolve_gains(gains_path).orbit
    sc = _parse_scale(scale)
    min_cases = MIN_CASES if min_cases is None else min_cases
    opts = VerifyOptions(profile=profile, seed=None if random_ else seed, database=database,
                         min_cases=min_cases, examples=examples, scale=sc, t_end=t_end, dt=dt,
                         u_max=u_max)
    results = run_verify(g, opts)
    code = result_exit_code(results)
    if plot_dir is not None:
        from lgw.tuning.figures import write_verify_plot

        path = write_verify_plot(plot_dir, "lunar", plot_panels(results),
                                 f"lgw verify lunar: orbit loop, profile {profile}, "
                                 f"seed {opts.seed}")
        if not as_json:
            click.echo(f"wrote {path}", err=True)
    if as_json:
        click.echo(json_document({"command": "verify lunar", "gains": {"orbit": g.to_dict()},
                                  "profile": profile, "seed": opts.seed, "t_end": t_end,
                                  "dt": dt, "u_max": u_max, "D": opts.D,
                                  "min_cases": min_cases, "scale": sc,
                                  "claims": [r.to_dict() for r in results],
                                  "exit_code": code}, indent=2))
        sys.exit(code)
    from rich.table import Table

    t = Table(title=f"lgw verify lunar: orbit loop, profile {profile}, seed {opts.seed}, "
                    f"{t_end} s, dt {dt} s, u_max = {u_max} N, ||d|| = {opts.D}")
    for col in ("claim", "eq.", "checked/cases", "fraction", "excluded", "worst margin",
                "verdict"):
        t.add_column(col)
    for r in results:
        color = {"holds": "green", "violated": "red"}.get(r.verdict, "yellow")
        frac = r.n_checked / r.n_cases if r.n_cases else 0.0
        wm = "-" if r.n_checked == 0 else f"{r.worst_margin:.4g}"
        t.add_row(r.claim, r.equation, f"{r.n_checked}/{r.n_cases}", f"{frac:.3f}",
                  str(r.n_excluded), wm, f"[{color}]{r.verdict}[/]")
    out = console()
    out.print(t)
    out.print(f"margin = (bound - observed)/bound, < 0 violates; holds needs >= {min_cases} "
              "checked cases; excluded: the margin is undefined for the case (reason below)")
    print_claim_details(out, results)
    sys.exit(code)


def _parse_scale(items: tuple[str, ...]) -> dict[str, float]:
    import math

    from lgw.theory.errors import ParameterError
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
        if not (math.isfinite(f) and f > 0):
            raise ParameterError("--scale", it, "FACTOR must be a finite number > 0")
        out[name] = f
    return out
