"""``lgw verify eros``: seed 002's proven per-axis reaching and reaching + sliding times for a
gain set, never passing on missing evidence (``lgw.tuning.eros.verify``).  Exit 0 holds,
1 violated, 4 inconclusive, 2 bad input."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import click
from lgw.theory.errors import ParameterError
from lgw.tuning.eros.options import resolve_gains
from lgw.tuning.eros.verify import CLAIMS, MIN_CASES, PROFILES
from lgw.tuning.io import check_out_dir, console, json_document
from lgw.tuning.options import SEED, Integer, choice, gains_option
from lgw.tuning.verify_common import print_claim_details


def parse_scale(items: tuple[str, ...], claims, name: str = "--scale-bound") -> dict[str, float]:
    """CLAIM=FACTOR items (a finite factor > 0) into a dict; a named error otherwise."""
    out = {}
    for it in items:
        claim, _, val = it.rpartition("=")
        if claim not in claims:
            raise ParameterError(name, it, f"CLAIM=FACTOR, CLAIM in {', '.join(claims)}")
        try:
            f = float(val)
        except ValueError:
            raise ParameterError(name, it, "FACTOR must be a number > 0") from None
        if not (math.isfinite(f) and f > 0):
            raise ParameterError(name, it, "FACTOR must be a finite number > 0")
        out[claim] = f
    return out


def _fmt(x: float, spec: str = ".4g") -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


@click.command("eros")
@gains_option
@click.option("--profile", type=choice(PROFILES), default="ci", show_default=True,
              help="ci: 8 Hypothesis examples (batches of 1..16 states) per disturbance mode; "
                   "thorough: 60")
@click.option("--seed", type=SEED, default=0, show_default=True,
              help="derandomised run with this seed (Hypothesis); integer in [0, 2^64 - 1]")
@click.option("--random", "random_", is_flag=True, help="a random run (ignores --seed)")
@click.option("--examples", type=Integer(1, 100_000, "examples"), default=None,
              help="Hypothesis examples per disturbance mode [default: the profile's]")
@click.option("--min-cases", type=Integer(1, 10**7, "cases"), default=MIN_CASES,
              show_default=True, help="checked simulated cases a claim needs for 'holds'")
@click.option("--database", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Hypothesis example database folder: replays earlier failures first and "
                   "saves new ones; makes the run random (Hypothesis uses no database in a "
                   "seeded run) [default: none]")
@click.option("--scale-bound", "scale", multiple=True, metavar="CLAIM=FACTOR",
              help="multiply a claim's bound (self-test of the checker: < 1 shrinks it) "
                   "[default: none]")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write verify_eros.png (observed against bound, one point "
                                 "per checked case and axis) to DIR [default: none]")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (strict, with lgw_version; docs/json.md)")
def command(gains_path: Path | None, profile: str, seed: int, random_: bool,
            examples: int | None, min_cases: int, database: Path | None,
            scale: tuple[str, ...], plot_dir: Path | None, as_json: bool) -> None:
    """Check seed 002's proven per-axis times (FTSMC, sign switching, sampled at 0.01 s).

    Per claim Hypothesis-driven simulations of the sampled-data loop against the case's own
    bound; the verdict is holds (>= --min-cases checked cases, no violation), violated (exit 1,
    shrunk witness and a ready-to-paste reproduction) or inconclusive (exit 4).
    """
    check_out_dir(plot_dir, "--plot")  # before any work
    g = resolve_gains(gains_path)
    sc = parse_scale(scale, CLAIMS)
    from lgw.tuning.eros.verify import VerifyOptions, exit_code, plot_panels, run_verify

    opts = VerifyOptions(profile=profile, seed=None if random_ else seed, database=database,
                         min_cases=min_cases, examples=examples, scale=sc)
    results = run_verify(g, opts)
    code = exit_code(results)
    if plot_dir is not None:
        from lgw.tuning.figures import write_verify_plot

        path = write_verify_plot(plot_dir, "eros", plot_panels(results),
                                 f"lgw verify eros: profile {profile}, seed {opts.seed}")
        if not as_json:
            click.echo(f"wrote {path}", err=True)
    if as_json:
        click.echo(json_document({"command": "verify eros", **g.to_dict(), "profile": profile,
                                  "seed": opts.seed, "min_cases": min_cases, "scale": sc,
                                  "dt": 0.01, "claims": [r.to_dict() for r in results],
                                  "exit_code": code}, indent=2))
        sys.exit(code)
    from rich.table import Table

    t = Table(title=f"lgw verify eros: FTSMC (sign), profile {profile}, seed {opts.seed}, "
                    f"dt 0.01 s")
    for col in ("claim", "eq.", "checked/cases", "fraction", "DOP853", "excluded",
                "worst (obs-dt)/bound", "verdict"):
        t.add_column(col)
    for r in results:
        color = {"holds": "green", "violated": "red"}.get(r.verdict, "yellow")
        frac = r.n_checked / r.n_cases if r.n_cases else 0.0
        t.add_row(r.claim, r.equation, f"{r.n_checked}/{r.n_cases}", f"{frac:.3f}",
                  str(r.n_reference), str(r.n_excluded), _fmt(r.ratio, ".4g"),
                  f"[{color}]{r.verdict}[/]")
    out = console()
    out.print(t)
    out.print("checked = simulated cases judged (DOP853: of them, carried by the reference "
              "route after RK4 could not); excluded: no integrator carried them or they touched "
              "the body; worst = the largest (observed - one sample)/bound, > 1 violates")
    print_claim_details(out, results)
    sys.exit(code)
