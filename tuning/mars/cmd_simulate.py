"""Fly seed 000's closed loop: the single Table I case, a Monte Carlo campaign (Table II / III
dispersions) or the states of a CSV file; or the Fig. 6 fixed-time experiment (``--fig6``).

Without --dispersion / --initial-states: the single Table I case.  --dispersion table3 flies
with the paper's Part 3 limit (50 kN per axis) unless --thrust-max is given.  Every result
reports the integrator step dt and the band eps used for the t_s1 / t_s2 times.  Cases are
streamed: --json and --out write them chunk by chunk, in flat memory.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim.mars.parameters import (
    DOPRI_ATOL,
    DOPRI_MAX_STEP,
    DOPRI_RTOL,
    DRAG_MODELS,
    DT_DEFAULT,
    EPS_DEFAULT,
    LAW_NAMES,
    T_MAX_DEFAULT,
)
from lgw.theory.errors import ParameterError
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
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.io import Stream, available_memory, json_stream
from lgw.tuning.options import Number, choice
from lgw.tuning.spec import option
from lgw.tuning.system import Job, Outcome

FIG6_S1X = (-8000.0, -6000.0, -4000.0, -2000.0, -1000.0)  # m, seed 000 Fig. 6
PER_CASE_ROWS = 50  # rows of the per-case table printed to the terminal (all go to --json/--out)
DISPERSIONS = ("table2", "table3")
DISTURBANCES = ("none", "sin", "random", "worst")  # lgw.sim.mars.disturbances.DISTURBANCES
LIMITS = ("axis", "norm")
A_MAX_PAPER = 20.0  # m/s^2, seed 000 (47): the default disturbance amplitude
MAX_RK4_STEPS = 10**8  # per case: t_max/dt beyond this would run for hours (a mistyped --dt)
BYTES_PER_CASE = 2_000  # the batch result's arrays per case (estimate for the memory check)
MEMORY_FRACTION = 0.5  # a campaign may use at most this share of the available memory


@dataclass(frozen=True)
class Options(V.Outputs, V.Dask,
              out="summary.json, cases.json, cases.csv (--fig6: fig6.json)",
              plot="one case: thrust against time with the limit, s1-s2 phase portrait; a "
                   "campaign: also the trajectory overlays (first 300 cases re-flown with RK4) "
                   "and the final positions and velocities of every case; --fig6: settling "
                   "against s1x(0) beside the bounds"):
    law: str = option("--law", choice(LAW_NAMES), "corrected",
                      "guidance law (corrected: seed 000 (25) with the workbench's correction)")
    dispersion: str | None = option("--dispersion", choice(DISPERSIONS), None,
                                    "table2: seed 000 Table II, normal about Table I (300 "
                                    "cases); table3: the Table III box (50 cases, 50 kN per "
                                    "axis) [default: the single Table I case]")
    initial_states: Path | None = V.initial_states("rx, ry, rz, vx, vy, vz, m (m, m/s, kg)")
    cases: int | None = V.cases(None, "number of dispersed cases [default: 300 for table2, "
                                "50 for table3]")
    seed: int = V.seed(0, "seed of the dispersion and of random disturbances")
    disturbance: str = option("--disturbance", choice(DISTURBANCES), "none",
                              "lumped disturbance a_p: none, sin (A sin t, seed 000 (47)), "
                              "random (sum of sines), worst (-A sgn s2)")
    dist_amplitude: float | None = option("--dist-amplitude", Number(0, 1e6, unit="m/s^2"),
                                          None, f"disturbance amplitude A, m/s^2 [default: "
                                          f"{A_MAX_PAPER:g}, seed 000 (47)]; needs "
                                          "--disturbance", probe=5.0)
    thrust_max: float | None = V.thrust_max(None, "per axis (or on the norm, --limit norm) "
                                            "[default: none; 50000 with --dispersion table3]")
    limit: str = option("--limit", choice(LIMITS), "axis",
                        "axis: |F_i| <= thrust-max; norm: ||F|| <= thrust-max (needs "
                        "--thrust-max)")
    drag: str = option("--drag", choice(DRAG_MODELS), "physical", "drag model of the plant")
    guidance_drag: str | None = option("--guidance-drag", choice(DRAG_MODELS), None,
                                       "drag model the law cancels [default: the plant's "
                                       "--drag]", probe="none")
    isp: float = V.isp(ISP)
    m_dry: float = option("--m-dry", Number(0, 1e9, lo_open=True, unit="kg"), M_DRY,
                          "dry mass, kg: a case whose mass reaches it is out of propellant")
    dt: float | None = V.dt(None, 1.0, f"RK4 step [default: {DT_DEFAULT}]; dopri5: the first "
                            "step")
    method: str = V.method("rk4")
    rtol: float = V.rtol(DOPRI_RTOL)
    atol: float = V.atol(DOPRI_ATOL, "m, m/s, kg")
    max_step: float = option("--max-step", Number(0, 1e3, lo_open=True, unit="s"),
                             DOPRI_MAX_STEP, "dopri5 largest step, s (only with --method "
                             "dopri5)")
    eps: float | None = option("--eps", Number(0, 1e3, lo_open=True, unit="m or m/s"), None,
                               f"sliding band for t_s1 (m) / t_s2 (m/s) [default: "
                               f"{EPS_DEFAULT}]", probe=0.1)
    t_max: float = V.t_max(T_MAX_DEFAULT)
    land_r: float = option("--land-r", Number(0, 1e4, lo_open=True, unit="m"), LAND_POS_TOL,
                           "landed when |r| <= this (m) ...")
    land_v: float = option("--land-v", Number(0, 1e4, lo_open=True, unit="m/s"),
                           LAND_VEL_TOL, "... and |v| <= this (m/s)")
    reference: bool = option("--reference", None, False, "tight solve_ivp (LSODA) per case "
                             "instead of the batch integrator", is_flag=True)
    fig6: bool = option("--fig6", None, False, "seed 000 Fig. 6 fixed-time experiment (the "
                        "law, --dt, --eps, --drag and --t-max apply)", is_flag=True)

    def check(self) -> None:
        super().check()
        r = self.refuse_unless
        if self.fig6:
            for name in ("dispersion", "initial_states", "cases", "seed", "disturbance",
                         "dist_amplitude", "thrust_max", "limit", "guidance_drag", "isp",
                         "m_dry", "method", "rtol", "atol", "max_step", "land_r", "land_v",
                         "reference", "workers", "scheduler"):
                r(False, name, "does not apply with --fig6 (the experiment flies Table I "
                  "with only s1x(0) varied; the law, --dt, --eps, --drag and --t-max apply)")
        r(self.disturbance != "none", "dist_amplitude", "needs --disturbance sin, random or "
          "worst (with --disturbance none there is no amplitude)")
        r(self.dispersion is None, "initial_states", "cannot be combined with --dispersion; "
          "give one of them")
        r(self.dispersion is not None, "cases", "only applies with --dispersion (without it "
          "the single Table I case, or the states file, is flown)")
        r(self.thrust_max is not None or self.dispersion == "table3", "limit",
          "needs --thrust-max (there is no limit to apply)")
        for name in ("rtol", "atol", "max_step"):
            r(self.method == "dopri5", name, "only applies with --method dopri5")
        r(not self.reference, "method", "cannot be combined with --reference (the reference "
          "is solve_ivp LSODA)")
        r(not self.reference, "dt", "does not apply with --reference (solve_ivp chooses its "
          "steps)")
        r(not self.reference, "workers", "does not apply with --reference (it runs in-process)")
        r(not self.reference, "scheduler", "does not apply with --reference (it runs "
          "in-process)")
        r(self.dispersion is not None or self.disturbance == "random" or self.fig6, "seed",
          "only applies with --dispersion or --disturbance random (nothing else is drawn)")
        if self.method == "rk4" and not self.reference:
            step = DT_DEFAULT if self.dt is None else self.dt
            steps = self.t_max / step
            if steps > MAX_RK4_STEPS:
                name, val = ("--t-max", self.t_max) if self.dt is None else ("--dt", self.dt)
                raise ParameterError(name, val, f"gives t_max/dt = {steps:.3g} RK4 steps per "
                                     f"case (dt = {step} s); at most {MAX_RK4_STEPS:.0e} "
                                     "(raise --dt or lower --t-max)")


def inputs(opts: Options) -> list[Path]:
    return [p for p in (opts.initial_states,) if p is not None]


@dataclass(frozen=True)
class SimulateJob(Job):
    """The inputs of one ``lgw simulate mars`` run: gain set, initial states, the
    ``simulate_batch`` keywords, where it runs."""

    gains: Any
    states: tuple[np.ndarray, np.ndarray, np.ndarray]
    sim: dict[str, Any]
    reference: bool
    executor: dict[str, Any]
    described: dict[str, Any]  # dispersion, initial-states file, cases: for the settings record
    want_figures: bool

    def run(self, progress: Any) -> Outcome:
        from lgw.sim.mars import campaign

        r0, v0, m0 = self.states
        n = len(r0)
        progress.stage(f"flying {n} case{'s' if n > 1 else ''}"
                       + (" (reference solve_ivp)" if self.reference else ""))
        if self.reference:
            from lgw.sim.mars.reference import simulate_reference

            res = simulate_reference(r0, v0, m0, self.gains, progress=False, **self.sim)
        else:
            # local campaigns keep their per-case results on disk (flat memory)
            res = campaign.run_campaign(r0, v0, m0, self.gains, progress=progress.live,
                                        spill=not self.executor, **self.executor, **self.sim)
        # convergence measured, never assumed (lgw.sim.mars.converged): the cases (all, or an
        # even spread of a large campaign) flown again finer, every printed number compared;
        # RK4 cases whose outcome changes with the step are refined until it settles
        progress.stage("convergence check")
        from lgw.sim.mars import converged as CV

        method = "reference" if self.reference else self.sim.get("method", "rk4")
        fly = CV.flier(r0, v0, m0, self.gains, self.sim, reference=self.reference)
        conv, fine, idx = CV.check(res, fly, method=method, rtol=self.sim.get("rtol"),
                                   atol=self.sim.get("atol"))
        if method == "rk4" and conv.outcome_changed:
            res, _ = CV.refine(res, fine, idx, fly, conv)
        summ = campaign.summarize(res)
        summ["settings"] = settings_used(res, self.sim, reference=self.reference,
                                         **self.described)
        summ["convergence"] = conv.to_dict()

        def records() -> Any:
            return with_checks(campaign.iter_case_records(res), conv)

        def encoded() -> Any:  # the same records as JSON text, a chunk at a time
            return campaign.CaseJson(res, extra=lambda a, b: check_column(conv, a, b))

        cases = Stream(encoded=encoded())
        figures = []
        if self.want_figures:
            progress.stage("figures")
            from lgw.tuning.mars.figures import simulation_figures

            figures = simulation_figures(self.gains, res, self.sim, self.states)
        head = {"command": "simulate mars", **self.gains.to_dict()}
        files = {"summary.json": json_stream({**head, **summ}, indent=1),
                 "cases.json": json_stream({**head, "cases": Stream(encoded=encoded())}),
                 "cases.csv": Stream(write=lambda f: write_cases_csv(records(), f))}
        return Outcome({"summary": summ, "cases": cases},
                       render=lambda con: _render(res, summ, con, conv), files=files,
                       figures=figures, flags=conv.flags("simulate mars"))


@dataclass(frozen=True)
class Fig6Job(Job):
    gains: Any
    law: str
    dt: float | None
    eps: float | None
    t_max: float
    drag: str
    want_figures: bool

    def run(self, progress: Any) -> Outcome:
        progress.stage("seed 000 Fig. 6: five s1x(0), flown to t_max")
        res6 = fig6(self.gains, law=self.law, dt=self.dt, eps=self.eps, t_max=self.t_max,
                    drag=self.drag)
        # convergence (lgw.sim.convergence): the same five runs at dt/2, every printed time
        from lgw.sim.convergence import Tol, compare_cases

        half = fig6(self.gains, law=self.law, dt=res6["dt"] / 2, eps=self.eps,
                    t_max=self.t_max, drag=self.drag)
        conv = compare_cases(res6["rows"], half["rows"],
                             {k: Tol(atol=1e-3) for k in ("t_s2x", "t_s1x", "landing_time")},
                             how="step halving", outcome_key="s1x0",
                             base_label=f"RK4 dt = {res6['dt']:g} s",
                             check_label=f"RK4 dt = {res6['dt'] / 2:g} s")
        res6["convergence"] = conv.to_dict()
        figures = []
        if self.want_figures:
            from lgw.theory.sections import Figure
            from lgw.tuning.mars.figures import settling_figure

            figures = [Figure("settling_fig6.png", "settling against s1x(0)",
                              settling_figure(res6, "Seed 000 Fig. 6: settling against "
                                              "s1x(0)"))]
        def render(con: Any) -> None:
            _print_fig6(res6, con)
            for line in conv.notes():
                con.print(line, markup=False)

        return Outcome(dict(res6), render=render, files={"fig6.json": DOCUMENT},
                       figures=figures, flags=conv.flags("simulate mars --fig6"))


def plan(opts: Options, system: Any) -> Job:
    from lgw.tuning.mars.gainset import resolve
    from lgw.tuning.options import check_scheduler

    gains = resolve(opts.gains)
    if opts.fig6:
        return Fig6Job(gains, opts.law, opts.dt, opts.eps, opts.t_max, opts.drag,
                       opts.plot is not None)
    if opts.scheduler is not None:
        check_scheduler(opts.scheduler, opts.scheduler_timeout)  # before any state is drawn
    from lgw.sim.mars import campaign

    thrust_max = opts.thrust_max
    if opts.dispersion is not None:
        n = opts.cases if opts.cases is not None else (300 if opts.dispersion == "table2"
                                                       else 50)
        check_memory(n)
        draw = campaign.table2_states if opts.dispersion == "table2" else \
            campaign.table3_states
        states = draw(n, opts.seed)
        if opts.dispersion == "table3" and thrust_max is None:
            thrust_max = THRUST_MAX_AXIS  # seed 000 Part 3
    elif opts.initial_states is not None:
        states = campaign.read_states_csv(opts.initial_states)
        below = np.flatnonzero(states[0][:, 2] < 0)
        if below.size:  # the mission starts above the ground plane (lgw.sim.results)
            raise ParameterError(f"--initial-states row {below[0] + 2} column rz",
                                 float(states[0][below[0], 2]), "must be >= 0 m: the state "
                                 "starts below the ground (the landing site's plane z = 0)")
        check_memory(len(states[0]))
    else:
        states = campaign.table1_state()
    sim: dict[str, Any] = dict(law=opts.law, disturbance=opts.disturbance,
                               dist_amplitude=opts.dist_amplitude, thrust_limit=thrust_max,
                               limit=opts.limit, dt=opts.dt, t_max=opts.t_max, eps=opts.eps,
                               seed=opts.seed, drag=opts.drag, isp=opts.isp, m_dry=opts.m_dry,
                               land_tol=(opts.land_r, opts.land_v),
                               guidance_drag=opts.guidance_drag)
    if opts.method != "rk4":
        sim.update(method=opts.method, rtol=opts.rtol, atol=opts.atol, max_step=opts.max_step)
    if opts.reference:
        sim.pop("dt")
    executor: dict[str, Any] = {}
    if opts.workers is not None or opts.scheduler is not None:
        executor = dict(executor="dask", workers=opts.workers, scheduler=opts.scheduler)
    described = dict(method=opts.method, dispersion=opts.dispersion,
                     initial_states=opts.initial_states, cases=len(states[0]))
    return SimulateJob(gains, states, sim, opts.reference, executor, described,
                       opts.plot is not None)


def check_memory(n: int) -> None:
    """Refuse a campaign whose per-case arrays would not fit in memory (named error)."""
    need = n * BYTES_PER_CASE
    avail = available_memory()
    if avail is not None and need > MEMORY_FRACTION * avail:
        raise ParameterError("--cases", n, f"needs about {need / 2**30:.1f} GiB for the "
                             f"per-case results; this machine has {avail / 2**30:.1f} GiB "
                             "available (split the campaign, or use --scheduler)")


def fig6(gains: Any, *, law: str = "corrected", dt: float | None = None,
         eps: float | None = None, t_max: float = 100.0, drag: str = "physical"
         ) -> dict[str, Any]:
    """Seed 000 Fig. 6: from s1x(0) = -8000 ... -1000 m (other states Table I), the first time
    |s1x| and |s2x| enter the eps band, beside the bounds of ``lgw.theory.mars.bounds``."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.theory.mars.bounds import axis_bounds

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


def _print_fig6(out: dict[str, Any], con: Any) -> None:
    from lgw.tuning.tables import result_table

    b = out["bounds_x"]
    rows = [(_fmt(r["s1x0"], ".0f"), _fmt(r["t_s2x"]), _fmt(b["T2_exact"]), _fmt(r["t_s1x"]),
             _fmt(b["landing_time_bound"]), _fmt(r["landing_time"])) for r in out["rows"]]
    result_table(con, f"seed 000 Fig. 6, x axis ({out['law']} law; eps = {out['eps']}, "
                 f"dt = {out['dt']} s)", ("s1x(0) m", "t_s2x s", "T2_exact s", "t_s1x s",
                                          "T2+T1 bound s", "landing time s"), rows)
    con.print("bounds (lgw.theory.mars.bounds.axis_bounds, x): "
              f"T2_exact {b['T2_exact']:.3f} s, "
              f"T1_exact {b['T1_exact']:.3f} s, sound landing bound T2+T1 "
              f"{b['landing_time_bound']:.3f} s; Polyakov (18) {b['T1_polyakov']:.3f} s, "
              f"(26) {b['T2_polyakov']:.3f} s.  t_s1x counts from t = 0 (s1 first enters "
              f"|s1x| <= eps), so compare it with T2 + T1.", markup=False)


def _print_summary(summ: dict[str, Any], con: Any) -> None:
    from lgw.tuning.tables import result_table

    title = (f"{summ['cases']} cases: {summ['landed']} landed, {summ['crashed']} crashed, "
             f"{summ['nonfinite']} non-finite, {summ['ground_contact']} below r_z = 0 before "
             "the outcome, "
             f"{summ['fuel_exhausted']} out of propellant (m_dry {summ['m_dry']:g} kg)"
             + (f", {summ['step_limit']} stopped at the dopri5 step limit"
                if summ["step_limit"] else "")
             + f" (eps = {summ['eps']}; {summ['settings']['integrator']})")
    rows = [("landing error |r| m", summ["landing_error_m"]),
            ("landing speed |v| m/s", summ["landing_speed_mps"]),
            ("landing time s", summ["landing_time_s"]), ("fuel kg", summ["fuel_kg"])]
    rows += [(f"peak thrust {ax} N", summ["peak_thrust_N"][ax]) for ax in "xyz"]
    rows.append(("time saturated s", summ["time_saturated_s"]))
    rows.append(("min altitude m (all cases)", summ["min_altitude_m"]))
    if summ["crashed"]:
        rows.append(("impact speed m/s (crashed)", summ["impact_speed_mps"]))
        rows.append(("contact time s (crashed)", summ["contact_time_s"]))
    result_table(con, title, ("quantity (landed cases)", "cases", "min", "median", "max"),
                 [(name, str(st["n"]), _fmt(st["min"], ".4g"), _fmt(st["median"], ".4g"),
                   _fmt(st["max"], ".4g")) for name, st in rows])
    for c in summ.get("nonfinite_cases", []):
        con.print(f"NON-FINITE case {c['case']}: r0 = {c['r0']}, v0 = {c['v0']}, "
                  f"m0 = {c['m0']}, stopped at t = {c['t_end']} s", markup=False)


def case_flags(res: Any, conv: Any = None) -> np.ndarray:
    """True for the cases the per-case table lists first: not landed, non-finite, below ground,
    out of propellant, stopped at the step limit, or (with the convergence record ``conv``)
    unconverged or refined."""
    out = (~res.landed | res.nonfinite | res.ground_contact | res.fuel_exhausted
           | res.step_limit)
    if conv is not None:
        bad = [c for c, ok in conv.case_ok.items() if not ok] + list(conv.refined)
        out = out.copy()
        out[np.asarray(bad, np.int64)] = True
    return out


def shown_cases(res: Any, rows: int = PER_CASE_ROWS, conv: Any = None) -> np.ndarray:
    """Indices of the cases the table shows: flagged cases first (in case order), then the worst
    landed ones (latest landing first), ``rows`` in all."""
    flagged = np.flatnonzero(case_flags(res, conv))
    rest = np.flatnonzero(~case_flags(res, conv))
    lt = np.where(np.isfinite(res.landing_time[rest]), res.landing_time[rest], np.inf)
    rest = rest[np.argsort(-lt, kind="stable")]
    return np.concatenate([flagged, rest])[:rows].astype(np.int64)


def select_cases(res: Any, idx: np.ndarray) -> list[dict[str, Any]]:
    """``case_records`` of the cases ``idx`` only (their case numbers kept)."""
    from lgw.sim.mars.batch import ARRAY_FIELDS, BatchResult
    from lgw.sim.mars.campaign import case_records, take

    kw = {k: take(res, k, idx) for k in (*ARRAY_FIELDS, "r0", "v0", "m0")}
    sub = BatchResult(eps=res.eps, dt=res.dt, info=res.info, **kw)
    sub.info = {k: v for k, v in res.info.items() if k != "refined_dt"}
    recs = case_records(sub)
    refined = res.info.get("refined_dt", {})
    for rec, i in zip(recs, idx, strict=True):
        rec["case"] = int(i)
        rec["refined_dt"] = refined.get(int(i))
    return recs


def _print_cases(recs: list[dict[str, Any]], total: int, flagged: int, con: Any) -> None:
    from lgw.tuning.tables import result_table

    rows = []
    for rec in recs:
        rl = rec["r_land"]
        crash = (f"CRASHED at {_fmt(rec['contact_time'], '.3f')} s, "
                 f"{_fmt(rec['impact_speed'], '.3g')} m/s")
        flags = " ".join(f for f, on in (("NONFINITE", rec["nonfinite"]),
                                         (crash, rec.get("outcome") == "crashed"),
                                         ("BELOW-SURFACE", rec.get("below_surface", False)),
                                         ("GROUND", rec["ground_contact"]),
                                         ("DRY", rec["fuel_exhausted"] and not rec["landed"]),
                                         ("STEPLIMIT", rec["step_limit"]),
                                         ("NOT-LANDED", not rec["landed"]),
                                         ("UNCONVERGED", rec.get("converged") is False),
                                         (f"REFINED dt={rec.get('refined_dt')}",
                                          rec.get("refined_dt") is not None))
                         if on)
        peak = "/".join(_fmt(None if p is None else p / 1e3, ".1f") for p in rec["peak_thrust"])
        rows.append((str(rec["case"]), "yes" if rec["landed"] else "NO",
                     _fmt(rec["landing_time"], ".2f"),
                     _fmt(math.hypot(*rl) if None not in rl else None, ".3f"),
                     _fmt(rec["fuel"], ".1f"), peak, _fmt(rec["time_saturated"], ".2f"),
                     "/".join(_fmt(x, ".2f") for x in rec["t_s2"]), flags))
    result_table(con, f"per case: {len(recs)} of {total} shown, flagged cases first ({flagged} "
                 "flagged), then the latest landings (peak thrust after the limit; t_s2: "
                 "first time |s2_i| <= eps per axis, - if not before the case ended)",
                 ("case", "landed", "t_land s", "|r| m", "fuel kg", "peak x/y/z kN",
                  "t_sat s", "t_s2 x/y/z s", "flags"), rows)
    if total > len(recs):
        con.print(f"{total - len(recs)} more cases not shown (all {total} in --json and "
                  "--out cases.json / cases.csv)", markup=False)


def _render(res: Any, summ: dict[str, Any], con: Any, conv: Any = None) -> None:
    _print_summary(summ, con)
    recs = select_cases(res, shown_cases(res, conv=conv))
    if conv is not None:
        recs = list(with_checks(recs, conv))
    _print_cases(recs, len(res), int(case_flags(res, conv).sum()), con)
    if conv is not None:
        for line in conv.notes():
            con.print(line, markup=False)


def with_checks(records: Any, conv: Any) -> Any:
    """The case records with the convergence check's verdict per case (``converged``: True or
    False for a checked case, None for one the check did not fly)."""
    for rec in records:
        rec["converged"] = conv.case_ok.get(rec["case"])
        yield rec


def check_column(conv: Any, a: int, b: int) -> dict[str, list[bool | None]]:
    """``with_checks``' key for the cases a..b-1, as a column (``lgw.sim.mars.campaign.
    CaseJson``)."""
    return {"converged": [conv.case_ok.get(i) for i in range(a, b)]}


def settings_used(res: Any, sim: dict[str, Any], *, method: str, reference: bool,
                  dispersion: str | None, initial_states: Path | None, cases: int
                  ) -> dict[str, Any]:
    """The settings that shaped the results, as flown: the simulator's own record
    (``res.info``), completed from the options where the reference mode records less, and no
    disturbance amplitude without a disturbance."""
    from lgw.sim.mars.disturbances import amplitude_array

    st = dict(res.info)
    st.setdefault("dist_amplitude", amplitude_array(sim["dist_amplitude"]).tolist())
    for k in ("isp", "t_max", "seed"):
        st.setdefault(k, sim[k])
    st.setdefault("land_tol", list(sim["land_tol"]))
    st.setdefault("guidance_drag", sim["guidance_drag"] or sim["drag"])
    if st.get("disturbance") == "none":
        st["dist_amplitude"] = None
    st.update(method="reference" if reference else method,
              dt=None if reference else res.dt, eps=res.eps, cases=cases,
              dispersion=dispersion,
              initial_states=None if initial_states is None else str(initial_states))
    return st


CSV_COLS = ["case", "landed", "landing_time", "fuel", "time_saturated", "min_altitude",
            "ground_contact", "nonfinite", "fuel_exhausted", "step_limit", "steps", "eps",
            "outcome", "outcome_time", "contact_time", "impact_speed", "below_surface",
            "refined_dt", "converged"]
CSV_VEC = ["r0", "v0", "r_land", "v_land", "peak_thrust", "t_s1", "t_s2"]


def write_cases_csv(records: Any, f: Any) -> None:
    """cases.csv from the case records, one row at a time."""
    header = CSV_COLS[:1] + ["m0"] + [f"{k}_{ax}" for k in CSV_VEC for ax in "xyz"] \
        + CSV_COLS[1:]
    f.write(",".join(header) + "\n")
    for r in records:
        vals = [r["case"], r["m0"]] + [x for k in CSV_VEC for x in r[k]] \
            + [r[c] for c in CSV_COLS[1:]]
        f.write(",".join("" if x is None else str(x) for x in vals) + "\n")
