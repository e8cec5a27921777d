"""``lgw tune mars``: design gains whose proven landing-time bound meets tf and whose simulated
peak thrust over an initial-state envelope stays under the limit (issue 5;
``lgw.tuning.mars.design``).

Exit codes: 0 feasible (file written); 2 invalid input (``lgw.theory.errors.ParameterError``);
3 infeasible request (reason and the nearest feasible tf printed, nothing written).
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import click
import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import AXES, THETA1_PAPER, THETA2_PAPER
from lgw.tuning.io import check_out_file, json_document
from lgw.tuning.mars.design import (
    BOUNDS,
    LIMITS,
    OBJECTIVES,
    Envelope,
    Request,
    envelope_from_name,
    nearest_feasible_tf,
    tune,
)
from lgw.tuning.mars.gains_file import certificate, write_gains
from lgw.tuning.options import Number, choice, seed_option

EXIT_INFEASIBLE = 3
# Upper ends of the request, on the scale of a Mars powered descent (km, minutes, kN), so that the
# geometric program and the simulated check stay well scaled: larger values are typing errors.
TF_MAX = 1e4  # s
THRUST_CAP = 1e9  # N


def _fmt_state(x: np.ndarray) -> str:
    return (f"r0 = {np.round(x[:3], 1).tolist()} m, v0 = {np.round(x[3:6], 1).tolist()} m/s, "
            f"m0 = {x[6]:.0f} kg")


def whole_box_note(env: Envelope, forced_fraction: float, thrust_max: float,
                   limit: str) -> str | None:
    """Why no gain set certifies the whole box (None when nothing in it forbids it)."""
    why = []
    x = env.singular_state()
    if x is not None:
        why.append(f"it contains states with r_i = 0, v_i != 0 (e.g. {_fmt_state(x)}), where "
                   "the command is infinite at t = 0")
    if forced_fraction > 0.0:
        why.append(f"{100 * forced_fraction:.1f} % of it cannot stop short of the target on "
                   f"some axis within {thrust_max:g} N ({limit}), so every law crosses r_i = 0 "
                   "with v_i != 0, where the command is infinite")
    if not why:
        return None
    return ("no gain set certifies the whole box: " + "; ".join(why) + " (the corrected law's "
            "-beta1 q1 |s1|^(q1-1) v, claim bounded-command-corrected in lgw report); the "
            "keep-out removes those states")


@click.command("mars")
@click.option("--tf", type=Number(0, TF_MAX, lo_open=True, unit="s"), required=True,
              help="required landing-time bound, s")
@click.option("--thrust-max", type=Number(0, THRUST_CAP, lo_open=True, unit="N"), required=True,
              help="thrust limit, N (per axis or on the norm, see --limit)")
@click.option("--limit", type=choice(LIMITS), default="axis", show_default=True,
              help="axis: |F_i| <= thrust-max; norm: ||F|| <= thrust-max")
@click.option("--envelope", "envelope", default="table3+table2", show_default=True,
              help="initial states to cover: table3+table2 | table3 | table2 | a CSV file of "
                   "states (rx, ry, rz, vx, vy, vz, m; m, m/s, kg)")
@click.option("--a-max", type=Number(0, 1e3, lo_open=True, unit="m/s^2"), default=None,
              help="disturbance bound |a_p,i|, m/s^2 [default: no disturbance; needs "
                   "--neighborhood]")
@click.option("--neighborhood", type=Number(0, 1e6, lo_open=True, unit="m"), default=None,
              help="required landing neighbourhood (31) under --a-max, m [default: none]")
@click.option("--theta1", type=Number(0, 1, lo_open=True, hi_open=True), default=THETA1_PAPER,
              show_default=True, help="Theorem 4 splitting constant of s2 (39), in (0, 1)")
@click.option("--theta2", type=Number(0, 1, lo_open=True, hi_open=True), default=THETA2_PAPER,
              show_default=True, help="Theorem 4 splitting constant of s1 (31), in (0, 1)")
@click.option("--bound", type=choice(BOUNDS), default="exact", show_default=True,
              help="landing-time bound to meet: exact (T1* + T2*) or polyakov ((18) + (26))")
@click.option("--objective", type=choice(OBJECTIVES), default="peak-thrust", show_default=True,
              help="what the gains minimize over the envelope")
@click.option("--keep-out", type=Number(0, 1e5, unit="m"), default=50.0, show_default=True,
              help="d_keep: states closer than this to the target on an axis are not covered, m")
@click.option("--brake-fraction", type=Number(0, 1, lo_open=True), default=0.5,
              show_default=True,
              help="kappa in (0, 1]: states that must brake harder than kappa x the available "
                   "deceleration to stop short of the target are not covered")
@seed_option("seed of the worst-case search")
@click.option("--fast", is_flag=True, help="smaller exponent grid and worst-case search")
@click.option("--no-suggest", is_flag=True, help="do not search the nearest feasible tf")
@click.option("--json", "as_json", is_flag=True,
              help="print the certificate as JSON (schema: docs/json.md)")
@click.option("--law", type=choice(("corrected", "bounded", "bounded-sat")), default="corrected",
              show_default=True,
              help="law to tune: corrected (seed 000 with exact cancellation), bounded "
                   "(issue 17: proven command bound, no keep-out) or bounded-sat (bounded "
                   "with the cancellation saturated at psi(|r|) + w0)")
@click.option("--out", type=click.Path(path_type=Path), required=True,
              help="the gains TOML file to write (one file, with a [certificate] table); its "
                   "folder must exist; checked before any work, written atomically")
def command(tf: float, thrust_max: float, limit: str, envelope: str,
            a_max: float | None, neighborhood: float | None, theta1: float, theta2: float,
            bound: str, objective: str, keep_out: float, brake_fraction: float, seed: int,
            fast: bool, no_suggest: bool, as_json: bool, law: str, out: Path) -> None:
    """Tune the corrected law's gains for a landing-time bound TF and a thrust limit."""
    check_out_file(out)
    if law in ("bounded", "bounded-sat"):
        from lgw.tuning.mars.design_bounded import run_cli
        sys.exit(run_cli(tf, thrust_max, limit, envelope, seed, no_suggest, as_json, out,
                         command="lgw tune mars " + " ".join(sys.argv[3:]), law=law))
    req = Request(tf=tf, thrust_max=thrust_max, limit=limit, bound=bound, objective=objective,
                  a_max=a_max, neighborhood=neighborhood, theta1=theta1, theta2=theta2)
    req.check()
    try:
        env = envelope_from_name(envelope, keep_out=keep_out, brake_fraction=brake_fraction)
    except ParameterError as e:  # a CSV envelope is read by the --initial-states loader
        if not e.name.startswith("--initial-states"):
            raise
        raise ParameterError(e.name.replace("--initial-states", "--envelope"), e.value,
                             e.valid) from None
    res = tune(req, env, seed=seed, fast=fast)
    cmd = "lgw tune mars " + " ".join(sys.argv[3:] if len(sys.argv) > 3 else [])
    note = whole_box_note(env, res.forced_fraction, req.thrust_max, req.limit)
    if not res.feasible:
        click.echo(f"infeasible: {res.reason}", err=True)
        if note:
            click.echo(f"note: {note}", err=True)
        if not no_suggest:
            start = replace(req, tf=max(req.tf, res.tf_min_envelope))
            tf_ok, r_ok = nearest_feasible_tf(start, env, seed=seed)
            if tf_ok is None:
                click.echo("no tf up to 600 s is feasible at this thrust limit: raise "
                           "--thrust-max or shrink the envelope", err=True)
            else:
                ev = r_ok.evaluation
                click.echo(f"nearest feasible tf: {tf_ok:g} s (worst simulated peak "
                           f"{ev.worst_value:.0f} N at {_fmt_state(ev.worst_state)}); "
                           f"rerun with --tf {tf_ok:g}", err=True)
        click.echo("nothing written", err=True)
        sys.exit(EXIT_INFEASIBLE)
    cert = certificate(res, req, env, command=cmd)
    header = (f"lgw tune mars: tf = {tf:g} s, thrust_max = {thrust_max:g} N ({limit}), "
              f"bound = {bound}, envelope = {env.name}")
    write_gains(out, res.gains, cert, header=header)
    if as_json:
        click.echo(json_document({"command": "tune mars", **res.gains.to_dict(),
                                  "out": str(out), "certificate": cert}, indent=1))
        return
    ev = res.evaluation
    b = cert["bounds"]
    key = "landing_time_bound" if bound == "exact" else "landing_time_bound_polyakov"
    click.echo(f"wrote {out}")
    click.echo(f"exponents q1 = {res.gains.q1:.4g}, q2 = {res.gains.q2:.4g}, "
               f"g1 = {res.gains.g1:.4g}, g2 = {res.gains.g2:.4g}; solver {cert['solver']} "
               f"({cert['solver_status']})")
    for i, ax in enumerate(AXES):
        click.echo(f"  {ax}: beta1 {res.gains.beta1[i]:.4g} beta2 {res.gains.beta2[i]:.4g} "
                   f"alpha1 {res.gains.alpha1[i]:.4g} alpha2 {res.gains.alpha2[i]:.4g}  "
                   f"bound ({bound}) {b[ax][key]:.2f} s")
    click.echo(f"worst simulated peak thrust {ev.worst_value:.0f} N "
               f"({100 * ev.worst_value / thrust_max:.1f} % of the limit) at "
               f"{_fmt_state(ev.worst_state)}; {res.search_counts['total']} states, "
               f"{ev.saturated} saturated, all landed: {ev.all_landed}, "
               f"latest landing {ev.max_landing_time:.2f} s")
    click.echo(f"fuel over the envelope: max {ev.fuel_max:.1f} kg, mean {ev.fuel_mean:.1f} kg")
    click.echo(f"envelope {env.name}: {100 * res.excluded_fraction:.1f} % of the box is in the "
               f"keep-out (not covered); {100 * res.forced_fraction:.1f} % cannot be stopped "
               f"short of the target by any law within the limit")
    if note:
        click.echo(f"note: {note}")
    click.echo(f"tuned in {res.elapsed:.1f} s")
