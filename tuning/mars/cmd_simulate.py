"""``lgw simulate mars``: fly seed 000's closed loop, one case or a campaign.

    lgw simulate mars [--gains FILE] [--law corrected|printed|super-twisting]
        [--dispersion table2|table3 | --initial-states FILE] [--cases N] [--seed S]
        [--disturbance none|sin|random|worst] [--dist-amplitude A]
        [--thrust-max N --limit axis|norm] [--drag physical|printed|none]
        [--guidance-drag physical|printed|none] [--isp S] [--land-r M --land-v MPS]
        [--dt S] [--eps E] [--t-max S] [--reference] [--workers N | --scheduler ADDRESS]
        [--json] [--out DIR]
    lgw simulate mars --fig6        the fixed-time experiment of seed 000 Fig. 6

Without --dispersion / --initial-states: the single Table I case.  --dispersion table3 flies
with the paper's Part 3 limit (50 kN per axis) unless --thrust-max is given.  Every result
reports the integrator step dt and the band eps used for the t_s1 / t_s2 times.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import click
import numpy as np
from lgw.sim.mars.batch import METHODS, simulate_batch
from lgw.sim.mars.campaign import (
    case_records,
    read_states_csv,
    run_campaign,
    summarize,
    table1_state,
    table2_states,
    table3_states,
)
from lgw.sim.mars.disturbances import DISTURBANCES
from lgw.sim.mars.laws import LAWS
from lgw.sim.mars.parameters import (
    DOPRI_ATOL,
    DOPRI_MAX_STEP,
    DOPRI_RTOL,
    DRAG_MODELS,
    T_MAX_DEFAULT,
)
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import (
    ISP,
    LAND_POS_TOL,
    LAND_VEL_TOL,
    M0,
    M_DRY,
    R0,
    THRUST_MAX_AXIS,
    V0,
)
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import gains_option
from rich.console import Console
from rich.table import Table

FIG6_S1X = (-8000.0, -6000.0, -4000.0, -2000.0, -1000.0)  # m, seed 000 Fig. 6
PER_CASE_ROWS = 50  # rows of the per-case table printed to the terminal (all go to --json/--out)


def _choice(name: str, value: str, valid: tuple[str, ...] | list[str]) -> str:
    if value not in valid:
        raise ParameterError(name, value, f"must be one of {', '.join(valid)}")
    return value


def fig6(gains: Gains, *, law: str = "corrected", dt: float | None = None,
         eps: float | None = None, t_max: float = 100.0, drag: str = "physical"
         ) -> dict[str, Any]:
    """Seed 000 Fig. 6: from s1x(0) = -8000 ... -1000 m (other states Table I), the first time
    |s1x| and |s2x| enter the eps band, beside the bounds of ``lgw.theory.mars.bounds``."""
    n = len(FIG6_S1X)
    r0 = np.tile(R0, (n, 1))
    r0[:, 0] = FIG6_S1X
    res = simulate_batch(r0, np.tile(V0, (n, 1)), np.full(n, M0), gains, law=law, dt=dt,
                         eps=eps, t_max=t_max, drag=drag, stop="t_max")
    b = axis_bounds(gains)["x"]
    rows = [{"s1x0": float(s), "t_s2x": float(res.t_s2[i, 0]), "t_s1x": float(res.t_s1[i, 0]),
             "landing_time": float(res.landing_time[i])} for i, s in enumerate(FIG6_S1X)]
    return {"law": law, "eps": res.eps, "dt": res.dt, "t_max": t_max, "rows": rows,
            "bounds_x": {k: b[k] for k in ("T2_exact", "T1_exact", "landing_time_bound",
                                           "T2_polyakov", "T1_polyakov")}}


def _fmt(x: float | None, spec: str = ".3f") -> str:
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, spec)


def _print_fig6(out: dict[str, Any], console: Console) -> None:
    b = out["bounds_x"]
    t = Table(title=f"seed 000 Fig. 6, x axis ({out['law']} law; eps = {out['eps']}, "
                    f"dt = {out['dt']} s)")
    for c in ("s1x(0) m", "t_s2x s", "T2_exact s", "t_s1x s", "T2+T1 bound s",
              "landing time s"):
        t.add_column(c, justify="right")
    for r in out["rows"]:
        t.add_row(_fmt(r["s1x0"], ".0f"), _fmt(r["t_s2x"]), _fmt(b["T2_exact"]),
                  _fmt(r["t_s1x"]), _fmt(b["landing_time_bound"]), _fmt(r["landing_time"]))
    console.print(t)
    console.print("bounds (lgw.theory.mars.bounds.axis_bounds, x): "
                  f"T2_exact {b['T2_exact']:.3f} s, "
                  f"T1_exact {b['T1_exact']:.3f} s, sound landing bound T2+T1 "
                  f"{b['landing_time_bound']:.3f} s; Polyakov (18) {b['T1_polyakov']:.3f} s, "
                  f"(26) {b['T2_polyakov']:.3f} s.  t_s1x counts from t = 0 (s1 first enters "
                  f"|s1x| <= eps), so compare it with T2 + T1.")


def _print_summary(summ: dict[str, Any], console: Console) -> None:
    t = Table(title=f"{summ['cases']} cases: {summ['landed']} landed, {summ['nonfinite']} "
                    f"non-finite, {summ['ground_contact']} ground contacts, "
                    f"{summ['fuel_exhausted']} out of propellant (m_dry {summ['m_dry']:g} kg)"
                    + (f", {summ['step_limit']} stopped at the dopri5 step limit"
                       if summ["step_limit"] else "")
                    + f" (eps = {summ['eps']}; {summ['settings']['integrator']})")
    for c in ("quantity (landed cases)", "min", "median", "max"):
        t.add_column(c, justify="right")
    rows = [("landing error |r| m", summ["landing_error_m"]),
            ("landing speed |v| m/s", summ["landing_speed_mps"]),
            ("landing time s", summ["landing_time_s"]), ("fuel kg", summ["fuel_kg"])]
    rows += [(f"peak thrust {ax} N", summ["peak_thrust_N"][ax]) for ax in "xyz"]
    rows.append(("time saturated s", summ["time_saturated_s"]))
    rows.append(("min altitude m (all cases)", summ["min_altitude_m"]))
    for name, st in rows:
        t.add_row(name, _fmt(st["min"], ".4g"), _fmt(st["median"], ".4g"), _fmt(st["max"], ".4g"))
    console.print(t)
    for c in summ.get("nonfinite_cases", []):
        console.print(f"[red]NON-FINITE[/red] case {c['case']}: r0 = {c['r0']}, v0 = {c['v0']}, "
                      f"m0 = {c['m0']}, stopped at t = {c['t_end']} s")


def _print_cases(recs: list[dict[str, Any]], console: Console) -> None:
    t = Table(title="per case (peak thrust after the limit; t_s2: last axis to enter the band)")
    for c in ("case", "landed", "t_land s", "|r| m", "fuel kg", "peak x/y/z kN", "t_sat s",
              "t_s2 s", "flags"):
        t.add_column(c, justify="right")
    for rec in recs[:PER_CASE_ROWS]:
        rl = rec["r_land"]
        ts2 = [x for x in rec["t_s2"] if x is not None]
        flags = " ".join(f for f, on in (("NONFINITE", rec["nonfinite"]),
                                         ("GROUND", rec["ground_contact"]),
                                         ("DRY", rec["fuel_exhausted"] and not rec["landed"]),
                                         ("STEPLIMIT", rec["step_limit"]))
                         if on)
        peak = "/".join(_fmt(None if p is None else p / 1e3, ".1f") for p in rec["peak_thrust"])
        t.add_row(str(rec["case"]), "yes" if rec["landed"] else "NO",
                  _fmt(rec["landing_time"], ".2f"),
                  _fmt(math.hypot(*rl) if None not in rl else None, ".3f"),
                  _fmt(rec["fuel"], ".1f"), peak, _fmt(rec["time_saturated"], ".2f"),
                  _fmt(max(ts2) if len(ts2) == 3 else None, ".2f"), flags)
    console.print(t)
    if len(recs) > PER_CASE_ROWS:
        console.print(f"... {len(recs) - PER_CASE_ROWS} more cases (all in --json / --out)")


@click.command("mars")
@gains_option
@click.option("--law", default="corrected", show_default=True,
              help=f"guidance law: {', '.join(LAWS)}")
@click.option("--dispersion", default=None, help="table2 (300 normal cases) | table3 (50 cases)")
@click.option("--initial-states", "initial_states", default=None,
              type=click.Path(dir_okay=False, path_type=Path),
              help="CSV with columns rx, ry, rz, vx, vy, vz, m")
@click.option("--cases", type=int, default=None, help="number of dispersed cases")
@click.option("--seed", type=int, default=0, show_default=True)
@click.option("--disturbance", default="none", show_default=True,
              help=f"{' | '.join(DISTURBANCES)}")
@click.option("--dist-amplitude", type=float, default=None,
              help="disturbance amplitude a_max, m/s^2 (default 20, seed 000 (47))")
@click.option("--thrust-max", type=float, default=None, help="thrust limit, N")
@click.option("--limit", default="axis", show_default=True, help="axis | norm")
@click.option("--drag", default="physical", show_default=True, help=" | ".join(DRAG_MODELS))
@click.option("--guidance-drag", default=None,
              help="drag model the law cancels (default: the plant's --drag)")
@click.option("--isp", type=float, default=ISP, show_default=True, help="specific impulse, s")
@click.option("--m-dry", "m_dry", type=float, default=M_DRY, show_default=True,
              help="dry mass, kg: a case whose mass reaches it is out of propellant")
@click.option("--dt", type=float, default=None,
              help="RK4 step, s (default 0.05); dopri5: the first step")
@click.option("--method", default="rk4", show_default=True,
              help="rk4 (fixed step) | dopri5 (adaptive Dormand-Prince 5(4), for landing "
                   "statistics; peaks and saturation time are sampled at its steps)")
@click.option("--rtol", type=float, default=DOPRI_RTOL, show_default=True,
              help="dopri5 relative tolerance")
@click.option("--atol", type=float, default=DOPRI_ATOL, show_default=True,
              help="dopri5 absolute tolerance")
@click.option("--max-step", type=float, default=DOPRI_MAX_STEP, show_default=True,
              help="dopri5 largest step, s")
@click.option("--eps", type=float, default=None, help="sliding band for t_s1/t_s2 (default 0.05)")
@click.option("--t-max", type=float, default=T_MAX_DEFAULT, show_default=True)
@click.option("--land-r", type=float, default=LAND_POS_TOL, show_default=True,
              help="landed when |r| <= this (m) ...")
@click.option("--land-v", type=float, default=LAND_VEL_TOL, show_default=True,
              help="... and |v| <= this (m/s)")
@click.option("--reference", is_flag=True, help="tight solve_ivp per case instead of RK4")
@click.option("--workers", type=int, default=None, help="dask LocalCluster with N workers")
@click.option("--scheduler", default=None, help="address of a dask scheduler")
@click.option("--fig6", is_flag=True, help="seed 000 Fig. 6 fixed-time experiment")
@click.option("--json", "as_json", is_flag=True, help="print one JSON object")
@click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="write summary.json, cases.json, cases.csv to DIR")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write figures (PNG) to DIR: one case: thrust against time "
                                 "with the limit, s1-s2 phase portrait; a campaign: also the "
                                 "trajectory overlays (first 300 cases re-flown with RK4) and "
                                 "the final positions/velocities of every case; --fig6: "
                                 "settling against s1x(0) beside the bounds")
def command(gains_path: Path | None, law: str, dispersion: str | None,
            initial_states: Path | None, cases: int | None, seed: int, disturbance: str,
            dist_amplitude: float | None, thrust_max: float | None, limit: str, drag: str,
            guidance_drag: str | None, isp: float, m_dry: float, dt: float | None,
            method: str, rtol: float, atol: float, max_step: float, eps: float | None,
            t_max: float, land_r: float, land_v: float, reference: bool,
            workers: int | None, scheduler: str | None, fig6: bool, as_json: bool,
            out: Path | None, plot_dir: Path | None) -> None:
    """Simulate seed 000's closed loop (corrected law by default) and summarize the landings."""
    gains = resolve_gains(gains_path)
    _choice("--law", law, list(LAWS))
    _choice("--disturbance", disturbance, DISTURBANCES)
    _choice("--limit", limit, ("axis", "norm"))
    _choice("--method", method, METHODS)
    _choice("--drag", drag, DRAG_MODELS)
    if guidance_drag is not None:
        _choice("--guidance-drag", guidance_drag, DRAG_MODELS)
    console = Console()
    if fig6:
        res6 = globals()["fig6"](gains, law=law, dt=dt, eps=eps, drag=drag)
        if as_json:
            click.echo(json.dumps(res6, indent=1))
        else:
            _print_fig6(res6, console)
        if out is not None:
            out.mkdir(parents=True, exist_ok=True)
            (out / "fig6.json").write_text(json.dumps(res6, indent=1))
        if plot_dir is not None:
            _plot_fig6(res6, plot_dir, as_json)
        return
    if dispersion is not None and initial_states is not None:
        raise ParameterError("--dispersion", dispersion, "cannot be combined with "
                             "--initial-states; give one of them")
    if dispersion is not None:
        _choice("--dispersion", dispersion, ("table2", "table3"))
        n = cases if cases is not None else (300 if dispersion == "table2" else 50)
        r0, v0, m0 = (table2_states if dispersion == "table2" else table3_states)(n, seed)
        if dispersion == "table3" and thrust_max is None:
            thrust_max = THRUST_MAX_AXIS  # seed 000 Part 3
    elif initial_states is not None:
        if cases is not None:
            raise ParameterError("--cases", cases, "only applies with --dispersion")
        r0, v0, m0 = read_states_csv(initial_states)
    else:
        if cases is not None:
            raise ParameterError("--cases", cases, "only applies with --dispersion "
                                 "(without it the single Table I case is flown)")
        r0, v0, m0 = table1_state()
    if thrust_max is not None and not (math.isfinite(thrust_max) and thrust_max > 0):
        raise ParameterError("--thrust-max", thrust_max, "must be a finite number > 0 (N)")
    opts: dict[str, Any] = dict(law=law, disturbance=disturbance, dist_amplitude=dist_amplitude,
                                thrust_limit=thrust_max, limit=limit, dt=dt, t_max=t_max,
                                eps=eps, seed=seed, drag=drag, isp=isp, m_dry=m_dry,
                                land_tol=(land_r, land_v), guidance_drag=guidance_drag)
    if method != "rk4":
        if reference:
            raise ParameterError("--method", method, "cannot be combined with --reference "
                                 "(the reference is solve_ivp LSODA)")
        opts.update(method=method, rtol=rtol, atol=atol, max_step=max_step)
    progress = len(r0) > 1000 and not as_json
    if reference:
        from lgw.sim.mars.reference import simulate_reference
        res = simulate_reference(r0, v0, m0, gains, progress=len(r0) > 1, **opts)
    elif workers is not None or scheduler is not None:
        res = run_campaign(r0, v0, m0, gains, executor="dask", workers=workers,
                           scheduler=scheduler, progress=progress, **opts)
    else:
        res = run_campaign(r0, v0, m0, gains, progress=progress, **opts)
    summ = summarize(res)
    # the table shows PER_CASE_ROWS cases: a million records only when they are written
    recs = case_records(res, None if (as_json or out is not None) else PER_CASE_ROWS)
    if as_json:
        click.echo(json.dumps({"summary": summ, "cases": recs}))
    else:
        _print_summary(summ, console)
        _print_cases(recs, console)
    if out is not None:
        _write(out, summ, recs)
    if plot_dir is not None:
        _plot(gains, res, opts, (r0, v0, m0), plot_dir, as_json)


def _plot(gains: Gains, res: Any, opts: dict[str, Any], states: tuple, plot_dir: Path,
          quiet: bool) -> None:
    from lgw.tuning.mars.figures import simulation_figures, write

    paths = write(simulation_figures(gains, res, opts, states), plot_dir)
    if not quiet:
        click.echo("wrote " + ", ".join(str(p) for p in paths))


def _plot_fig6(res6: dict[str, Any], plot_dir: Path, quiet: bool) -> None:
    from lgw.tuning.figures import save_png
    from lgw.tuning.mars.figures import settling_figure

    path = save_png(settling_figure(res6, "Seed 000 Fig. 6: settling against s1x(0)"),
                    plot_dir / "settling_fig6.png")
    if not quiet:
        click.echo(f"wrote {path}")


def _write(out: Path, summ: dict[str, Any], recs: list[dict[str, Any]]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    (out / "summary.json").write_text(json.dumps(summ, indent=1))
    (out / "cases.json").write_text(json.dumps(recs))
    cols = ["case", "landed", "landing_time", "fuel", "time_saturated", "min_altitude",
            "ground_contact", "nonfinite", "fuel_exhausted", "step_limit", "steps", "eps"]
    vec = ["r0", "v0", "r_land", "v_land", "peak_thrust", "t_s1", "t_s2"]
    header = cols[:1] + ["m0"] + [f"{k}_{ax}" for k in vec for ax in "xyz"] + cols[1:]
    lines = [",".join(header)]
    for r in recs:
        vals = [r["case"], r["m0"]] + [x for k in vec for x in r[k]] + [r[c] for c in cols[1:]]
        lines.append(",".join("" if x is None else str(x) for x in vals))
    (out / "cases.csv").write_text("\n".join(lines) + "\n")
