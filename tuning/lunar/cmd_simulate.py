"""Fly seed 001's closed loop: the Section 5 case (h error 100 m, V error [2, 3, 5] m/s,
Q0 = [sqrt .8, sqrt .2, 0, 0]) or, with --cases N, N random cases (height error U(-200, 200)
m, velocity error U(-5, 5) m/s per axis, attitude error up to 60 degrees about a random axis),
seeded; per case the final and largest errors, saturation times, adaptive estimates and the
case's outcome.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Number, choice
from lgw.tuning.spec import Options, option
from lgw.tuning.system import Job, Outcome

PRINTED_CASES = 20  # cases listed on the terminal (all in --json / --out)


def random_cases(n: int, seed: int):
    """N random initial errors (see the module docstring): dh (N,), dv (3, N), Q0 (4, N)."""
    rng = np.random.default_rng(seed)
    dh = rng.uniform(-200, 200, n)
    dv = rng.uniform(-5, 5, (3, n))
    axis = rng.normal(size=(3, n))
    axis /= np.linalg.norm(axis, axis=0)
    ang = rng.uniform(0, np.radians(60), n)
    Q0 = np.vstack([np.cos(ang / 2), np.sin(ang / 2) * axis])
    return dh, dv, Q0


def _defaults() -> dict[str, Any]:
    """The run defaults of lgw.sim.lunar.closed_loop.RunOptions (one place)."""
    from lgw.theory.lunar import parameters as P

    return {"dt": P.DT, "thrust_max": P.T_MAX, "ta": P.T_A}


@dataclass(frozen=True)
class Options(Options):
    gains: Path | None = V.gains()
    cases: int | None = V.cases(None, "random cases [default: the Section 5 case]")
    seed: int = V.seed(0, "seed of the random cases")
    pointing: str = option("--pointing", choice(("coupled", "ideal")), "coupled",
                           "thrust along the simulated body axis, or along the command (the "
                           "orbit loop alone)")
    failure: str = option("--failure", choice(("atan", "step", "none")), "atan",
                          "thrust failure: (26) as printed, a step to T_a, or none")
    t_fail: float | None = option("--t-fail", Number(0, 1e5, unit="s"), None,
                                  "failure time, s [default: t_f/2]", probe=20.0)
    ta: float | None = option("--ta", Number(0, 1, lo_open=True, unit="fraction"), None,
                              "thrust fraction left after the failure, T_a of (26) "
                              "[default: the paper's]", probe=0.8)
    sat_reading: str = option("--sat-reading", choice(("commanded", "nominal")), "commanded",
                              "the T of (24): the commanded or the nominal thrust")
    cmd_wn: float | None = option("--cmd-wn", Number(0, 50, lo_open=True, unit="rad/s"), None,
                                  "natural frequency of the desired-attitude command filter, "
                                  "rad/s [default: the documented choice]", probe=3.0)
    thrust_max: float | None = V.thrust_max(None, "engine thrust limit T_max of (24) "
                                            "[default: the paper's]")
    dt: float | None = V.dt(None, 0.1, "RK4 step (<= 0.1 s: RK4 stability with F2 = 20) "
                            "[default: the documented choice]")
    t_max: float | None = V.t_max(None, "end time", hi=1e5)
    json: bool = V.json_flag()
    out: Path | None = V.out_dir("summary.json (the --json document) and section5.png")
    plot: Path | None = V.plot_dir("figures of case 0: tracking errors, thrust around the "
                                   "failure with T_max, d0e against ||d||, V2 and Vlambda")

    def check(self) -> None:
        super().check()
        r = self.refuse_unless
        r(self.cases is not None, "seed", "only applies with --cases (the Section 5 case "
          "draws nothing)")
        r(self.failure != "none", "t_fail", "does not apply with --failure none")
        r(self.failure != "none", "ta", "does not apply with --failure none")


@dataclass(frozen=True)
class SimulateJob(Job):
    gains: Any
    run_options: Any  # lgw.sim.lunar.closed_loop.RunOptions
    states: tuple[np.ndarray, np.ndarray, np.ndarray]
    want_figures: bool
    want_overview: bool

    def run(self, progress: Any) -> Outcome:
        from lgw.sim.lunar import campaign
        from lgw.sim.lunar.outcomes import json_safe
        from lgw.sim.lunar.reference import reference
        from lgw.tuning.io import Stream

        ref = reference()
        n = len(self.states[0])
        opts = self.run_options
        progress.stage(f"flying {n} case{'s' if n > 1 else ''} (RK4, dt = {opts.dt} s)")
        # flown a chunk at a time, the records kept on disk (flat memory in the cases)
        camp = campaign.fly(ref, self.gains, opts, self.states,
                            record_every=max(1, int(round(0.1 / opts.dt))), keep=PRINTED_CASES)
        res, ctx = camp.first_run  # case 0, for the figures
        sums, outcomes = camp.first_records, camp.outcomes
        figures, files = [], {"summary.json": DOCUMENT}
        if self.want_figures:
            progress.stage("figures")
            from lgw.tuning.lunar.figures import report_figures

            what = ("Section 5 case" if n == 1 else f"case 0 of {n} random cases")
            figures = report_figures(res, ctx, what=f"{what}, {opts.thrust_pointing} pointing,"
                                     " the command's gains")
        if self.want_overview:
            from lgw.tuning.lunar.figures import section5_png

            files["section5.png"] = section5_png(res)
        doc = {"options": json_safe(dict(opts.__dict__)), "reference": ref.to_dict(),
               "outcomes": outcomes, "cases": Stream(encoded=camp)}
        return Outcome(doc, render=lambda con: _render(con, ref, opts, sums, outcomes, n),
                       files=files, figures=figures)


def _render(con: Any, ref: Any, opts: Any, sums: list[dict[str, Any]],
            outcomes: dict[str, int], n: int) -> None:
    from lgw.tuning.tables import fmt, result_table

    con.print(f"reference: t_f = {ref.tf:.3f} s, a1 = {ref.a1:.6g}, a2 = {ref.a2:.6g} 1/s, "
              f"a3 = {ref.a3:.6g}; RK4 dt = {opts.dt} s, pointing {opts.thrust_pointing}",
              markup=False)
    rows = [(str(i), fmt(s["eh_final_m"]), fmt(float(np.linalg.norm(s["ev_final_m_s"]))),
             fmt(s["max_abs_eh_m"]), fmt(s["orbit_saturated_s"]),
             fmt(s["orbit_saturated_after_failure_s"]), fmt(s["torque_saturated_s"]),
             f"{fmt(s['d0e_orbit_final'])}/{fmt(s['d0e_attitude_final'])}",
             f"{s['outcome']} at {fmt(s['t_outcome_s'])} s")
            for i, s in enumerate(sums[:PRINTED_CASES])]
    result_table(con, f"seed 001: {n} case(s)" + (
        f", the first {PRINTED_CASES} shown" if n > PRINTED_CASES else ""),
        ("case", "e_h(t_f) m", "|e_v(t_f)| m/s", "max|e_h| m", "orbit sat s",
         "sat after failure s", "torque sat s", "d0e orbit/att", "outcome"), rows)
    con.print("outcomes: " + ", ".join(f"{k} {v}" for k, v in outcomes.items()), markup=False)


def plan(opts: Options, system: Any) -> SimulateJob:
    from dataclasses import replace

    from lgw.sim.lunar.closed_loop import RunOptions
    from lgw.theory.lunar import parameters as P
    from lgw.tuning.lunar.gainset import resolve

    g = resolve(opts.gains)
    run = RunOptions(sat_reading=opts.sat_reading, failure=opts.failure, t_fail=opts.t_fail,
                     thrust_pointing=opts.pointing)
    changes = {k: v for k, v in (("dt", opts.dt), ("t_end", opts.t_max), ("Ta", opts.ta),
                                 ("cmd_wn", opts.cmd_wn), ("thrust_max", opts.thrust_max))
               if v is not None}
    run = replace(run, **changes)
    if opts.cases is None:
        states = (np.full(1, P.DH0), P.DV0[:, None], P.Q0[:, None])
    else:
        states = random_cases(opts.cases, opts.seed)
    return SimulateJob(g, run, states, opts.plot is not None, opts.out is not None)
