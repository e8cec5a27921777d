"""``lgw simulate lunar``: fly seed 001's closed loop (Section 5 case, or random cases).

    lgw simulate lunar [--gains FILE] [--cases N --seed S] [--pointing coupled|ideal]
        [--failure atan|step|none] [--t-fail S] [--ta T] [--sat-reading commanded|nominal]
        [--cmd-wn W] [--dt S] [--t-end S] [--json] [--out DIR]

Without --cases: the Section 5 case (h error 100 m, V error [2, 3, 5] m/s, Q0 = [sqrt .8,
sqrt .2, 0, 0]).  With --cases N: N random cases (height error U(-200, 200) m, velocity error
U(-5, 5) m/s per axis, attitude error up to 60 degrees about a random axis), seeded.
"""

from __future__ import annotations

import json
from pathlib import Path

import click
import numpy as np
from lgw.theory.errors import ParameterError
from lgw.tuning.lunar.options import resolve_gains
from lgw.tuning.options import SEED, Integer, Number, choice, gains_option


def random_cases(n: int, seed: int):
    rng = np.random.default_rng(seed)
    dh = rng.uniform(-200, 200, n)
    dv = rng.uniform(-5, 5, (3, n))
    axis = rng.normal(size=(3, n))
    axis /= np.linalg.norm(axis, axis=0)
    ang = rng.uniform(0, np.radians(60), n)
    Q0 = np.vstack([np.cos(ang / 2), np.sin(ang / 2) * axis])
    return dh, dv, Q0


@click.command("lunar")
@gains_option
@click.option("--cases", type=Integer(0, 10**6, "cases"), default=0, show_default=True,
              help="number of random cases (0: the Section 5 case)")
@click.option("--seed", type=SEED, default=0, show_default=True,
              help="random seed (numpy SeedSequence); integer in [0, 2^64 - 1]")
@click.option("--pointing", type=choice(("coupled", "ideal")), default="coupled",
              show_default=True, help="thrust along the simulated body axis, or along the "
              "command (orbit loop alone)")
@click.option("--failure", type=choice(("atan", "step", "none")), default="atan",
              show_default=True, help="(26) as printed, a step to 70%, or no failure")
@click.option("--t-fail", type=Number(0, unit="s"), default=None,
              help="failure time (s) [default: t_f/2]")
@click.option("--ta", type=Number(0, 1, unit="fraction"), default=0.7, show_default=True,
              help="thrust fraction left after the failure, T_a of (26)")
@click.option("--sat-reading", type=choice(("commanded", "nominal")),
              default="commanded", show_default=True, help="the T of (24)")
@click.option("--cmd-wn", type=Number(0, 1e3, lo_open=True, unit="rad/s"), default=2.0,
              show_default=True,
              help="natural frequency of the desired-attitude command filter, rad/s")
@click.option("--dt", type=Number(0, 1, lo_open=True, unit="s"), default=None,
              help="RK4 step (s) [default: 0.05]")
@click.option("--t-end", type=Number(0, 1e5, lo_open=True, unit="s"), default=None,
              help="end time (s) [default: t_f of the reference]")
@click.option("--json", "as_json", is_flag=True, help="print the per-case summaries as JSON")
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write summary.json and section5.png there")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write figures (PNG) of case 0 to DIR: tracking errors, "
                                 "thrust around the failure with T_max, d0e against ||d||, "
                                 "V2 and Vlambda")
def command(gains_path, cases, seed, pointing, failure, t_fail, ta, sat_reading, cmd_wn, dt,
            t_end, as_json, out_dir, plot_dir) -> None:
    """Fly seed 001's closed loop: errors, thrust, torque, d0e, saturation, flags."""
    from lgw.theory.lunar import parameters as P
    from lgw.tuning.io import check_out_dir

    check_out_dir(plot_dir, "--plot")  # before any work
    if cases < 0 or cases > 100_000:
        raise ParameterError("--cases", cases, "must lie in [0, 100000]")
    if dt is not None and not 0 < dt <= 0.1:
        raise ParameterError("--dt", dt, "must lie in (0, 0.1] s (RK4 stability with F2 = 20)")
    if not 0 < ta <= 1:
        raise ParameterError("--ta", ta, "must lie in (0, 1]")
    if not 0 < cmd_wn <= 50:
        raise ParameterError("--cmd-wn", cmd_wn, "must lie in (0, 50] rad/s")
    if t_end is not None and not t_end > 0:
        raise ParameterError("--t-end", t_end, "must be > 0 s")
    if t_fail is not None and not t_fail >= 0:
        raise ParameterError("--t-fail", t_fail, "must be >= 0 s")
    g = resolve_gains(gains_path)
    from lgw.sim.lunar.batch import rk4_batch
    from lgw.sim.lunar.closed_loop import RunOptions, initial_state, make_context
    from lgw.sim.lunar.reference import reference
    from lgw.sim.lunar.scenario import summarize

    opts = RunOptions(dt=dt or P.DT, t_end=t_end, sat_reading=sat_reading, failure=failure,
                      t_fail=t_fail, Ta=ta, thrust_pointing=pointing,
                      cmd_wn=cmd_wn)
    ref = reference()
    if cases == 0:
        n = 1
        dh, dv, Q0 = np.full(1, P.DH0), P.DV0[:, None], P.Q0[:, None]
    else:
        n = cases
        dh, dv, Q0 = random_cases(n, seed)
    ctx = make_context(ref, [g] * n, opts)
    X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, n)), [g] * n)
    res = rk4_batch(ctx, X0, record_every=max(1, int(round(0.1 / opts.dt))))
    from lgw.sim.lunar.outcomes import case_record, counts, json_safe

    sums = [json_safe({**summarize(res, ctx, i).numbers, **case_record(res.cases, i)})
            for i in range(n)]
    if plot_dir is not None:
        from lgw.tuning.lunar.figures import plot_run

        plot_run(res, ctx, plot_dir, quiet=as_json)
    if as_json:
        # strict JSON: undefined numbers (no saturation entry, ...) are null, never NaN
        click.echo(json.dumps(json_safe({"options": opts.__dict__, "reference": ref.to_dict(),
                                         "outcomes": counts(res.cases["outcome"]),
                                         "cases": sums}), indent=2, default=str,
                              allow_nan=False))
    else:
        click.echo(f"reference: t_f = {ref.tf:.3f} s, a1 = {ref.a1:.6g}, a2 = {ref.a2:.6g} 1/s, "
                   f"a3 = {ref.a3:.6g}; RK4 dt = {opts.dt} s, pointing {pointing}")
        for i, s in enumerate(sums[:20]):
            click.echo(f"case {i}: e_h(t_f) = {s['eh_final_m']:.4g} m, |e_v(t_f)| = "
                       f"{np.linalg.norm(s['ev_final_m_s']):.4g} m/s, max|e_h| = "
                       f"{s['max_abs_eh_m']:.4g} m, orbit saturated {s['orbit_saturated_s']:.4g}"
                       f" s ({s['orbit_saturated_after_failure_s']:.4g} s after the failure), "
                       f"torque saturated {s['torque_saturated_s']:.4g} s, d0e = "
                       f"{s['d0e_orbit_final']:.4g} / {s['d0e_attitude_final']:.4g}, "
                       f"outcome {s['outcome']} at {s['t_outcome_s']:.4g} s")
        click.echo(f"outcomes: {counts(res.cases['outcome'])}")
    if out_dir is not None:
        from lgw.tuning.lunar.figures import section5_figure

        out_dir.mkdir(parents=True, exist_ok=True)
        (out_dir / "summary.json").write_text(json.dumps({"cases": sums}, indent=2,
                                                         default=str, allow_nan=False))
        section5_figure(res, out_dir / "section5.png")
        click.echo(f"wrote {out_dir / 'summary.json'}, {out_dir / 'section5.png'}")
