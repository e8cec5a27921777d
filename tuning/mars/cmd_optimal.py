"""``lgw optimal mars``: the fuel-optimal (lossless-convexification SOCP) baseline of seed 000."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click
import numpy as np
from lgw.sim.mars.optimal import N_RANGE
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import ISP, M0, R0, THRUST_MAX_AXIS, V0
from lgw.tuning.io import atomic_write_text, check_out_dir, json_document, make_out_dir
from lgw.tuning.options import Integer, Number, choice, out_dir_option

PAPER_FUEL_OPTIMAL = 212.9067  # kg, seed 000 Part 1 (GPOPS, tf = 30 s)
REPLAYS = (("none", 0.0), ("sin", 1.0), ("sin", 20.0))  # Fig. 3 uses 1; (47) prints 20


def _sources(sol: Any) -> list[str]:
    st = sol.settings
    lim = ("|F_i| <= {:g} N per axis (seed 000 Part 3)" if st["limit"] == "axis"
           else "||F|| <= {:g} N (norm limit)").format(st["thrust_max_N"])
    low = ("none (seed 000 states no minimum thrust)" if st["thrust_min_N"] is None
           else f"||F|| >= {st['thrust_min_N']:g} N (--thrust-min)")
    return [
        f"thrust upper bound: {lim}",
        f"thrust lower bound: {low}",
        f"Isp = {st['isp_s']:g} s (Acikmese & Ploen 2007; seed 000 does not state it), "
        f"g_e = {st['g_e']} m/s^2 (seed 000 Table I), dry mass {st['m_dry_kg']:g} kg "
        "(Acikmese & Ploen 2007)",
        "initial state: seed 000 Table I (r0, v0, m0 = 1905 kg); target r = v = 0 at tf",
        "no drag: Martian drag (12) is not in the convex model (the replay can add it)",
        f"problem class: {st['case']}",
    ]


def _replays(sol: Any, drag: str) -> list[dict[str, Any]]:
    from lgw.sim.mars.optimal import replay

    out = []
    for dist, amp in REPLAYS:
        rep = replay(sol, dist, amplitude=amp, drag=drag)
        rep.pop("trajectory")
        out.append(rep)
    return out


@click.command("mars")
@click.option("--tf", type=Number(0, 1e5, lo_open=True, unit="s"), default=None,
              help="flight time, s [default: 30, seed 000 Part 1]")
@click.option("--min-tf", is_flag=True, help="find the shortest feasible flight time instead")
@click.option("--thrust-max", type=Number(0, 1e9, lo_open=True, unit="N"),
              default=THRUST_MAX_AXIS,
              show_default=True,
              help="thrust upper bound, N (per axis or on the norm, see --limit)")
@click.option("--limit", type=choice(("axis", "norm")), default="axis", show_default=True,
              help="axis: |F_i| <= thrust-max (seed 000 Part 3); norm: ||F|| <= thrust-max")
@click.option("--thrust-min", type=Number(0, 1e9, unit="N"), default=None,
              help="lower bound on ||F||, N (needs the lossless convexification) [default: "
                   "none, seed 000 states no minimum]")
@click.option("--n", "n", type=Integer(N_RANGE[0], N_RANGE[1], "ZOH steps"), default=80,
              show_default=True,
              help="number of zero-order-hold steps of the SOCP")
@click.option("--isp", type=Number(0, lo_open=True, unit="s"), default=ISP, show_default=True,
              help="specific impulse, s")
@click.option("--no-replay", is_flag=True, help="skip the open-loop replays")
@click.option("--drag", type=choice(("none", "physical", "printed")), default="none",
              show_default=True, help="drag model of the replay's plant (none: the SOCP's)")
@click.option("--json", "as_json", is_flag=True,
              help="print JSON instead of text (schema: docs/json.md)")
@out_dir_option("optimal.json and thrust.csv", dest="out_dir")
def command(tf: float | None, min_tf: bool, thrust_max: float, limit: str,
            thrust_min: float | None, n: int, isp: float, no_replay: bool, drag: str,
            as_json: bool,
            out_dir: Path | None) -> None:
    """Fuel-optimal descent (SOCP, Acikmese & Ploen 2007) and its open-loop replay."""
    check_out_dir(out_dir)
    from lgw.sim.mars.optimal import min_time, solve_fuel_optimal

    if min_tf and tf is not None:
        raise ParameterError("--tf", tf, "give either --tf SECONDS or --min-tf, not both")
    kw = dict(thrust_max=thrust_max, limit=limit, thrust_min=thrust_min, n=n, isp=isp)
    mt = None
    if min_tf:
        mt = min_time(R0, V0, M0, **kw)
        sol = mt.solution
    else:
        tf = 30.0 if tf is None else tf
        sol = solve_fuel_optimal(R0, V0, M0, tf, **kw)
        if not sol.feasible:
            if sol.status != "infeasible":
                raise click.ClickException(f"solver failed: status {sol.status}")
            lo = min_time(R0, V0, M0, **kw).tf_min
            raise ParameterError("--tf", tf, f"infeasible with these thrust bounds: must be >= "
                                 f"{lo:.3f} s (shortest feasible tf, from --min-tf)")
    reps = [] if no_replay else _replays(sol, drag)
    report: dict[str, Any] = {"command": "optimal mars", "plant": "mars",
                              "solution": sol.to_dict(arrays=True),
                              "sources": _sources(sol), "replays": reps,
                              "paper_fuel_optimal_kg": PAPER_FUEL_OPTIMAL}
    if mt is not None:
        report["min_tf"] = {"tf_min": mt.tf_min, "bracket": list(mt.bracket),
                            "iterations": mt.iterations}
    text = json_document(report, indent=1)
    if out_dir is not None:
        make_out_dir(out_dir)
        rows = ["t_start_s,t_end_s,Fx_N,Fy_N,Fz_N,norm_N"]
        for k in range(sol.n):
            f = sol.F[k]
            rows.append(f"{sol.t[k]:.6f},{sol.t[k + 1]:.6f},{f[0]:.3f},{f[1]:.3f},{f[2]:.3f},"
                        f"{np.linalg.norm(f):.3f}")
        atomic_write_text(out_dir / "thrust.csv", "\n".join(rows) + "\n")
        atomic_write_text(out_dir / "optimal.json", text + "\n")
    if as_json:
        click.echo(text)
        return
    _print_text(sol, mt, reps, out_dir)


def _print_text(sol: Any, mt: Any, reps: list[dict[str, Any]], out_dir: Path | None) -> None:
    e = click.echo
    e("Fuel-optimal powered descent, seed 000 Table I lander (SOCP, Acikmese & Ploen 2007;")
    e("Blackmore, Acikmese & Scharf 2010), cvxpy + Clarabel")
    for s in _sources(sol):
        e(f"  {s}")
    if mt is not None:
        lo, hi = mt.bracket
        e(f"shortest feasible tf: {mt.tf_min:.3f} s (bisection on feasibility, bracket "
          f"[{lo:.3f}, {hi:.3f}] s, {mt.iterations} solves)")
    e(f"tf = {sol.tf:g} s, N = {sol.n} ZOH steps, dt = {sol.dt:.4f} s; status {sol.status}; "
      f"solve time {sol.solve_time * 1e3:.1f} ms "
      f"({sol.settings['solves']} solves; Clarabel {sol.settings['clarabel_time_s'] * 1e3:.1f} ms)")
    e(f"fuel = {sol.fuel:.4f} kg (final mass {sol.m[-1]:.4f} kg); "
      f"seed 000's GPOPS figure: {PAPER_FUEL_OPTIMAL} kg")
    pk = sol.peak_thrust
    e(f"peak thrust per axis: x {pk[0]:.0f} N, y {pk[1]:.0f} N, z {pk[2]:.0f} N; "
      f"peak ||F|| {sol.peak_thrust_norm:.0f} N")
    tight = "tight (lossless)" if sol.tightness < 1e-5 else "NOT tight"
    e(f"convexification check: max(sigma - ||u||) / max(sigma) = {sol.tightness:.2e} "
      f"({sol.tightness_abs:.2e} m/s^2): the relaxation ||u|| <= sigma is {tight}")
    e("thrust profile (force held on each step; every step in --json / --out thrust.csv):")
    e(f"  {'t [s]':>7} {'Fx [N]':>9} {'Fy [N]':>9} {'Fz [N]':>9} {'|F| [N]':>9}")
    stride = max(1, sol.n // 10)
    for k in list(range(0, sol.n, stride)) + ([sol.n - 1] if (sol.n - 1) % stride else []):
        f = sol.F[k]
        e(f"  {sol.t[k]:7.2f} {f[0]:9.0f} {f[1]:9.0f} {f[2]:9.0f} {np.linalg.norm(f):9.0f}")
    if reps:
        e(f"open-loop replay in lgw.sim.mars.plant (force vs time, ZOH; drag {reps[0]['drag']!r}; "
          "engine off after tf):")
        for rep in reps:
            name = "none" if rep["disturbance"] == "none" else f"{rep['amplitude']:g} sin t"
            if rep["outcome"] == "landed":
                what = f"landed at tf = {rep['t_end']:.2f} s"
            elif rep["outcome"] == "crashed":
                what = f"crashed at t = {rep['contact_time']:.2f} s ({rep['phase']})"
            else:
                what = f"missed (airborne at t = {rep['t_end']:.1f} s)"
            e(f"  a_p = {name:>8}: {what}; min altitude while powered "
              f"{rep['min_altitude_powered']:.3f} m; at tf: miss {rep['miss_tf']:.3f} m, "
              f"speed {rep['speed_tf']:.3f} m/s; touchdown: miss {rep['miss_distance']:.3f} m, "
              f"speed {rep['touchdown_speed']:.3f} m/s")
        r0 = reps[0]
        if (r0["disturbance"] == "none" and r0["drag"] == "none"
                and not math.isnan(r0["node_error_r"])):
            e(f"cross-check (no disturbance): the replay ends {r0['node_error_r']:.2e} m / "
              f"{r0['node_error_v']:.2e} m/s from the SOCP's final state (tolerance 1e-3); "
              f"fuel used {r0['fuel_used']:.4f} kg vs SOCP {r0['fuel_predicted']:.4f} kg")
    if out_dir is not None:
        e(f"wrote {out_dir / 'optimal.json'} and {out_dir / 'thrust.csv'}")
