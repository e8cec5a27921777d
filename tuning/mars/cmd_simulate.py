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

import math
from pathlib import Path
from typing import Any

import click
import numpy as np
from lgw.sim.mars.batch import ARRAY_FIELDS, LIMITS, METHODS, BatchResult, simulate_batch
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
    DT_DEFAULT,
    EPS_DEFAULT,
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
from lgw.tuning.io import atomic_write_text, check_out_dir, console, json_document, make_out_dir
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import (
    SCHEDULER_TIMEOUT,
    Integer,
    Number,
    check_scheduler,
    choice,
    gains_option,
    out_dir_option,
    seed_option,
)
from rich.console import Console
from rich.table import Table

FIG6_S1X = (-8000.0, -6000.0, -4000.0, -2000.0, -1000.0)  # m, seed 000 Fig. 6
PER_CASE_ROWS = 50  # rows of the per-case table printed to the terminal (all go to --json/--out)
DISPERSIONS = ("table2", "table3")
MAX_CASES = 100_000_000  # --cases: a campaign beyond this does not fit the per-case arrays
A_MAX_PAPER = 20.0  # m/s^2, seed 000 (47): the default disturbance amplitude
MAX_RK4_STEPS = 10**8  # per case: t_max/dt beyond this would run for hours (a mistyped --dt)


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


def case_flags(res: BatchResult) -> np.ndarray:
    """True for the cases the per-case table lists first: not landed, non-finite, below ground,
    out of propellant or stopped at the step limit."""
    return (~res.landed | res.nonfinite | res.ground_contact | res.fuel_exhausted
            | res.step_limit)


def shown_cases(res: BatchResult, rows: int = PER_CASE_ROWS) -> np.ndarray:
    """Indices of the cases the table shows: flagged cases first (in case order), then the worst
    landed ones (latest landing first), ``rows`` in all."""
    flagged = np.flatnonzero(case_flags(res))
    rest = np.flatnonzero(~case_flags(res))
    lt = np.where(np.isfinite(res.landing_time[rest]), res.landing_time[rest], np.inf)
    rest = rest[np.argsort(-lt, kind="stable")]
    return np.concatenate([flagged, rest])[:rows].astype(np.int64)


def select_cases(res: BatchResult, idx: np.ndarray) -> list[dict[str, Any]]:
    """``case_records`` of the cases ``idx`` only (their case numbers kept)."""
    kw = {k: getattr(res, k)[idx] for k in ARRAY_FIELDS}
    sub = BatchResult(eps=res.eps, dt=res.dt, r0=res.r0[idx], v0=res.v0[idx], m0=res.m0[idx],
                      info=res.info, **kw)
    recs = case_records(sub)
    for rec, i in zip(recs, idx, strict=True):
        rec["case"] = int(i)
    return recs


def _print_cases(recs: list[dict[str, Any]], total: int, flagged: int,
                 console: Console) -> None:
    t = Table(title=f"per case: {len(recs)} of {total} shown, flagged cases first ({flagged} "
                    "flagged), then the latest landings (peak thrust after the limit; t_s2: "
                    "first time |s2_i| <= eps per axis, - if not before the case ended)")
    for c in ("case", "landed", "t_land s", "|r| m", "fuel kg", "peak x/y/z kN", "t_sat s",
              "t_s2 x/y/z s", "flags"):
        t.add_column(c, justify="right")
    for rec in recs:
        rl = rec["r_land"]
        flags = " ".join(f for f, on in (("NONFINITE", rec["nonfinite"]),
                                         ("GROUND", rec["ground_contact"]),
                                         ("DRY", rec["fuel_exhausted"] and not rec["landed"]),
                                         ("STEPLIMIT", rec["step_limit"]),
                                         ("NOT-LANDED", not rec["landed"]))
                         if on)
        peak = "/".join(_fmt(None if p is None else p / 1e3, ".1f") for p in rec["peak_thrust"])
        t.add_row(str(rec["case"]), "yes" if rec["landed"] else "NO",
                  _fmt(rec["landing_time"], ".2f"),
                  _fmt(math.hypot(*rl) if None not in rl else None, ".3f"),
                  _fmt(rec["fuel"], ".1f"), peak, _fmt(rec["time_saturated"], ".2f"),
                  "/".join(_fmt(x, ".2f") for x in rec["t_s2"]), flags)
    console.print(t)
    if total > len(recs):
        console.print(f"{total - len(recs)} more cases not shown (all {total} in --json and "
                      "--out cases.json / cases.csv)")


def settings_used(res: BatchResult, opts: dict[str, Any], *, method: str, reference: bool,
                  dispersion: str | None, initial_states: Path | None, cases: int
                  ) -> dict[str, Any]:
    """The settings that shaped the results, as flown: the simulator's own record
    (``res.info``), completed from the options where the reference mode records less, and no
    disturbance amplitude without a disturbance."""
    from lgw.sim.mars.disturbances import amplitude_array

    st = dict(res.info)
    st.setdefault("dist_amplitude", amplitude_array(opts["dist_amplitude"]).tolist())
    for k in ("isp", "t_max", "seed"):
        st.setdefault(k, opts[k])
    st.setdefault("land_tol", list(opts["land_tol"]))
    st.setdefault("guidance_drag", opts["guidance_drag"] or opts["drag"])
    if st.get("disturbance") == "none":
        st["dist_amplitude"] = None
    st.update(method="reference" if reference else method,
              dt=None if reference else res.dt, eps=res.eps, cases=cases,
              dispersion=dispersion,
              initial_states=None if initial_states is None else str(initial_states))
    return st


@click.command("mars")
@gains_option
@click.option("--law", type=choice(list(LAWS)), default="corrected", show_default=True,
              help="guidance law (corrected: seed 000 (25) with the workbench's correction)")
@click.option("--dispersion", type=choice(DISPERSIONS), default=None,
              help="table2: seed 000 Table II, normal about Table I (300 cases); table3: the "
                   "Table III box (50 cases, 50 kN per axis) [default: the single Table I case]")
@click.option("--initial-states", "initial_states", default=None,
              type=click.Path(dir_okay=False, path_type=Path),
              help="CSV of initial states, header rx, ry, rz, vx, vy, vz, m (m, m/s, kg; UTF-8)")
@click.option("--cases", type=Integer(1, MAX_CASES, "cases"), default=None,
              help="number of dispersed cases [default: 300 for table2, 50 for table3]")
@seed_option("seed of the dispersion and of random disturbances")
@click.option("--disturbance", type=choice(DISTURBANCES), default="none", show_default=True,
              help="lumped disturbance a_p: none, sin (A sin t, seed 000 (47)), random "
                   "(sum of sines), worst (-A sgn s2)")
@click.option("--dist-amplitude", "dist_amplitude", type=Number(0, 1e6, unit="m/s^2"),
              default=None,
              help=f"disturbance amplitude A, m/s^2 [default: {A_MAX_PAPER:g}, seed 000 (47)]; "
                   "needs --disturbance")
@click.option("--thrust-max", type=Number(0, lo_open=True, unit="N"), default=None,
              help="thrust limit, N [default: none; 50000 with --dispersion table3]")
@click.option("--limit", type=choice(LIMITS), default="axis", show_default=True,
              help="axis: |F_i| <= thrust-max; norm: ||F|| <= thrust-max")
@click.option("--drag", type=choice(DRAG_MODELS), default="physical", show_default=True,
              help="drag model of the plant")
@click.option("--guidance-drag", type=choice(DRAG_MODELS), default=None,
              help="drag model the law cancels [default: the plant's --drag]")
@click.option("--isp", type=Number(0, lo_open=True, unit="s"), default=ISP, show_default=True,
              help="specific impulse, s")
@click.option("--m-dry", "m_dry", type=Number(0, lo_open=True, unit="kg"), default=M_DRY,
              show_default=True,
              help="dry mass, kg: a case whose mass reaches it is out of propellant")
@click.option("--dt", type=Number(0, lo_open=True, unit="s"), default=None,
              help=f"RK4 step, s [default: {DT_DEFAULT}]; dopri5: the first step")
@click.option("--method", type=choice(METHODS), default="rk4", show_default=True,
              help="rk4 (fixed step) | dopri5 (adaptive Dormand-Prince 5(4), for landing "
                   "statistics; peaks and saturation time are sampled at its steps)")
@click.option("--rtol", type=Number(0, lo_open=True), default=DOPRI_RTOL, show_default=True,
              help="dopri5 relative tolerance (>= 1e-13)")
@click.option("--atol", type=Number(0, lo_open=True), default=DOPRI_ATOL, show_default=True,
              help="dopri5 absolute tolerance (m, m/s, kg)")
@click.option("--max-step", type=Number(0, lo_open=True, unit="s"), default=DOPRI_MAX_STEP,
              show_default=True, help="dopri5 largest step, s")
@click.option("--eps", type=Number(0, lo_open=True, unit="m or m/s"), default=None,
              help=f"sliding band for t_s1 (m) / t_s2 (m/s) [default: {EPS_DEFAULT}]")
@click.option("--t-max", type=Number(0, 1e7, lo_open=True, unit="s"), default=T_MAX_DEFAULT,
              show_default=True, help="simulation horizon, s")
@click.option("--land-r", type=Number(0, lo_open=True, unit="m"), default=LAND_POS_TOL,
              show_default=True, help="landed when |r| <= this (m) ...")
@click.option("--land-v", type=Number(0, lo_open=True, unit="m/s"), default=LAND_VEL_TOL,
              show_default=True, help="... and |v| <= this (m/s)")
@click.option("--reference", is_flag=True,
              help="tight solve_ivp (LSODA) per case instead of the batch integrator")
@click.option("--workers", type=Integer(1, 1024, "dask workers"), default=None,
              help="run on a dask LocalCluster with N single-threaded workers [default: "
                   "in-process]; not with --scheduler")
@click.option("--scheduler", default=None,
              help="address of a running dask scheduler (tcp://host:port), checked before any "
                   "work; not with --workers")
@click.option("--scheduler-timeout", type=Number(0, 600, lo_open=True, unit="s"),
              default=SCHEDULER_TIMEOUT, show_default=True,
              help="seconds to wait for --scheduler to answer")
@click.option("--fig6", is_flag=True, help="seed 000 Fig. 6 fixed-time experiment")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (schema: docs/json.md)")
@out_dir_option("summary.json, cases.json, cases.csv (--fig6: fig6.json)")
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
            workers: int | None, scheduler: str | None, scheduler_timeout: float, fig6: bool,
            as_json: bool, out: Path | None, plot_dir: Path | None) -> None:
    """Simulate seed 000's closed loop (corrected law by default) and summarize the landings."""
    check_out_dir(out)
    check_out_dir(plot_dir, "--plot")
    gains = resolve_gains(gains_path)
    if dist_amplitude is not None and disturbance == "none":
        raise ParameterError("--dist-amplitude", dist_amplitude, "needs --disturbance sin, "
                             "random or worst (with --disturbance none there is no amplitude)")
    if workers is not None and scheduler is not None:
        raise ParameterError("--workers", workers, "cannot be combined with --scheduler (the "
                             "scheduler's cluster decides the workers); give one of them")
    if scheduler is not None and not fig6:
        check_scheduler(scheduler, scheduler_timeout)  # fail fast, before any state is drawn
    con = console()
    if fig6:
        res6 = globals()["fig6"](gains, law=law, dt=dt, eps=eps, drag=drag)
        doc = {"command": "simulate mars --fig6", **gains.to_dict(), **res6}
        text = json_document(doc, indent=1)
        if out is not None:
            atomic_write_text(make_out_dir(out) / "fig6.json", text + "\n")
        if as_json:
            click.echo(text)
        else:
            _print_fig6(res6, con)
        if plot_dir is not None:
            _plot_fig6(res6, plot_dir, as_json)
        return
    if dispersion is not None and initial_states is not None:
        raise ParameterError("--dispersion", dispersion, "cannot be combined with "
                             "--initial-states; give one of them")
    if dispersion is not None:
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
    opts: dict[str, Any] = dict(law=law, disturbance=disturbance, dist_amplitude=dist_amplitude,
                                thrust_limit=thrust_max, limit=limit, dt=dt, t_max=t_max,
                                eps=eps, seed=seed, drag=drag, isp=isp, m_dry=m_dry,
                                land_tol=(land_r, land_v), guidance_drag=guidance_drag)
    if method != "rk4":
        if reference:
            raise ParameterError("--method", method, "cannot be combined with --reference "
                                 "(the reference is solve_ivp LSODA)")
        opts.update(method=method, rtol=rtol, atol=atol, max_step=max_step)
    if method == "rk4" and not reference:
        steps = t_max / (DT_DEFAULT if dt is None else dt)
        if steps > MAX_RK4_STEPS:
            name, val = ("--t-max", t_max) if dt is None else ("--dt", dt)
            raise ParameterError(name, val, f"gives t_max/dt = {steps:.3g} RK4 steps per case "
                                 f"(dt = {DT_DEFAULT if dt is None else dt} s); at most "
                                 f"{MAX_RK4_STEPS:.0e} (raise --dt or lower --t-max)")
    if reference and (workers is not None or scheduler is not None):
        raise ParameterError("--reference", True, "runs in-process; it cannot be combined "
                             "with --workers or --scheduler")
    progress = len(r0) > 1000 and not as_json
    if reference:
        from lgw.sim.mars.reference import simulate_reference
        res = simulate_reference(r0, v0, m0, gains, progress=len(r0) > 1 and not as_json,
                                 **opts)
    elif workers is not None or scheduler is not None:
        res = run_campaign(r0, v0, m0, gains, executor="dask", workers=workers,
                           scheduler=scheduler, progress=progress, **opts)
    else:
        res = run_campaign(r0, v0, m0, gains, progress=progress, **opts)
    summ = summarize(res)
    summ["settings"] = settings_used(res, opts, method=method, reference=reference,
                                     dispersion=dispersion, initial_states=initial_states,
                                     cases=len(r0))
    head = {"command": "simulate mars", **gains.to_dict()}
    # the table shows PER_CASE_ROWS cases: a million records only when they are written
    recs = case_records(res) if (as_json or out is not None) else None
    if out is not None:
        _write(make_out_dir(out), head, summ, recs)
    if as_json:
        click.echo(json_document({**head, "summary": summ, "cases": recs}))
    else:
        _print_summary(summ, con)
        _print_cases(select_cases(res, shown_cases(res)), len(res),
                     int(case_flags(res).sum()), con)
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


CSV_COLS = ["case", "landed", "landing_time", "fuel", "time_saturated", "min_altitude",
            "ground_contact", "nonfinite", "fuel_exhausted", "step_limit", "steps", "eps"]
CSV_VEC = ["r0", "v0", "r_land", "v_land", "peak_thrust", "t_s1", "t_s2"]


def _write(out: Path, head: dict[str, Any], summ: dict[str, Any],
           recs: list[dict[str, Any]]) -> None:
    """summary.json, cases.json and cases.csv, each written atomically."""
    atomic_write_text(out / "summary.json", json_document({**head, **summ}, indent=1) + "\n")
    atomic_write_text(out / "cases.json", json_document({**head, "cases": recs}) + "\n")
    header = CSV_COLS[:1] + ["m0"] + [f"{k}_{ax}" for k in CSV_VEC for ax in "xyz"] \
        + CSV_COLS[1:]
    lines = [",".join(header)]
    for r in recs:
        vals = [r["case"], r["m0"]] + [x for k in CSV_VEC for x in r[k]] \
            + [r[c] for c in CSV_COLS[1:]]
        lines.append(",".join("" if x is None else str(x) for x in vals))
    atomic_write_text(out / "cases.csv", "\n".join(lines) + "\n")
