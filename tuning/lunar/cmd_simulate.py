"""Fly seed 001's closed loop: the Section 5 case (h error 100 m, V error [2, 3, 5] m/s,
Q0 = [sqrt .8, sqrt .2, 0, 0], the failure (26) at t_f/2 to 70 %) with every quoted number
checked against the same run at dt/4 (flagged when they differ by more than 1 %), or, with
--cases N, a Monte Carlo campaign over the failure time and level and the initial state
(--envelope, --dispersion), cases streamed to --json / --out, statistics over the completed
cases (every other outcome counted apart), the first cases re-flown at dt/2.  A tuned file
(--gains, from lgw tune lunar) also sets the command filter and T_max it was designed for.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Number, choice
from lgw.tuning.spec import option
from lgw.tuning.system import Job, Outcome

ENVELOPE_CHOICES = ("campaign", "section5", "certificate")
DISPERSIONS = ("all", "states", "failure")  # lgw.sim.lunar.campaign.DISPERSIONS
WN_DT_MAX = 2.5  # RK4 on the filter's poles (|lambda| = wn, damping 0.9): |lambda dt| <= 2.5
MAX_STEPS = 10**8  # per case: beyond this a run would take hours (a mistyped --dt)
T_END_MAX = 400.0  # s, above the reference's t_f (~276 s): the default horizon, for the estimate


def random_cases(n: int, seed: int):
    """N random initial errors (height U(-200, 200) m, velocity U(-5, 5) m/s per axis, attitude
    up to 60 deg about a random axis): dh (N,), dv (3, N), Q0 (4, N); the cases of the tests
    and benchmarks (the command's campaigns draw with ``lgw.sim.lunar.campaign``)."""
    rng = np.random.default_rng(seed)
    dh = rng.uniform(-200, 200, n)
    dv = rng.uniform(-5, 5, (3, n))
    axis = rng.normal(size=(3, n))
    axis /= np.linalg.norm(axis, axis=0)
    ang = rng.uniform(0, np.radians(60), n)
    Q0 = np.vstack([np.cos(ang / 2), np.sin(ang / 2) * axis])
    return dh, dv, Q0


@dataclass(frozen=True)
class Options(V.Outputs, gains=" (a tuned file also sets --cmd-wn and --thrust-max)",
              out="summary.json (the --json document; a campaign's cases streamed) and "
                  "section5.png",
              plot="figures of case 0: tracking errors, thrust around the failure with T_max, "
                   "d0e against ||d||, V2 and Vlambda"):
    cases: int | None = V.cases(None, "Monte Carlo cases over --envelope [default: the "
                                "Section 5 case]")
    seed: int = V.seed(0, "seed of the campaign")
    envelope: str = option("--envelope", choice(ENVELOPE_CHOICES), "campaign",
                           "campaign: failure at 25-75 % of t_f to 60-80 % thrust, height "
                           "error +-200 m, velocity +-10 m/s per axis, attitude up to 60 deg; "
                           "section5: the paper's failure, errors within the box of its case; "
                           "certificate: the envelope of the --gains file's [certificate] "
                           "(only with --cases)")
    dispersion: str = option("--dispersion", choice(DISPERSIONS), "all",
                             "what a campaign draws: all, states (the failure fixed by "
                             "--failure/--t-fail/--ta) or failure (the Section 5 initial "
                             "errors)")
    pointing: str | None = option("--pointing", choice(("coupled", "ideal")), None,
                                  "thrust along the simulated body axis (coupled), or along "
                                  "the command (ideal: the orbit loop alone) [default: the "
                                  "--gains file's design pointing, else coupled]",
                                  probe="ideal")
    failure: str = option("--failure", choice(("atan", "step", "none")), "atan",
                          "thrust failure: (26) as printed, a step to T_a, or none")
    t_fail: float | None = option("--t-fail", Number(0, 1e5, unit="s"), None,
                                  "failure time, s [default: t_f/2]", probe=20.0)
    ta: float | None = option("--ta", Number(0, 1, lo_open=True, unit="fraction"), None,
                              "thrust fraction left after the failure, T_a of (26) "
                              "[default: the paper's]", probe=0.8)
    sat_reading: str = option("--sat-reading", choice(("commanded", "nominal")), "commanded",
                              "the T of (24): the commanded or the nominal thrust")
    cmd_wn: float | None = option("--cmd-wn", Number(0, 1e3, lo_open=True, unit="rad/s"), None,
                                  "natural frequency of the desired-attitude command filter, "
                                  "rad/s [default: the --gains file's, else "
                                  "lgw.sim.lunar.parameters.CMD_WN]", probe=3.0)
    thrust_max: float | None = V.thrust_max(None, "engine thrust limit T_max of (24) "
                                            "[default: the --gains file's, else the paper's]")
    dt: float | None = V.dt(None, 0.1, "RK4 step [default: lgw.sim.lunar.parameters.DT "
                            "(1/640 s), campaigns DT_CAMPAIGN (1/320 s): chosen by "
                            "convergence]", probe=0.02)
    t_max: float | None = V.t_max(None, "end time", hi=1e5)

    def check(self) -> None:
        super().check()
        r = self.refuse_unless
        campaign = self.cases is not None
        r(campaign, "seed", "only applies with --cases (the Section 5 case draws nothing)")
        r(campaign, "envelope", "only applies with --cases")
        r(campaign, "dispersion", "only applies with --cases")
        r(self.failure != "none", "t_fail", "does not apply with --failure none")
        r(self.failure != "none", "ta", "does not apply with --failure none")
        drawn = campaign and self.dispersion in ("all", "failure")
        r(not drawn, "t_fail", "the campaign draws the failure time (--dispersion states "
          "fixes it)")
        r(not drawn, "ta", "the campaign draws T_a (--dispersion states fixes it)")
        r(not (drawn and self.failure == "none"), "failure", "--failure none leaves nothing "
          "to draw with --dispersion all/failure (use --dispersion states)")
        if self.dt is not None:
            t_end = self.t_max if self.t_max is not None else T_END_MAX
            if t_end / self.dt > MAX_STEPS:
                from lgw.theory.errors import ParameterError

                raise ParameterError("--dt", self.dt, f"gives {t_end / self.dt:.3g} RK4 steps "
                                     f"per case; at most {MAX_STEPS:.0e} (raise --dt or lower "
                                     "--t-max)")


@dataclass(frozen=True)
class SimulateJob(Job):
    """The Section 5 case, flown with its convergence check."""

    gains: Any
    run_options: Any  # lgw.sim.lunar.closed_loop.RunOptions
    want_figures: bool
    want_overview: bool

    def run(self, progress: Any) -> Outcome:
        from lgw.sim.lunar.outcomes import case_record, json_safe
        from lgw.sim.lunar.reference import reference
        from lgw.sim.lunar.scenario import fly_section5

        ref = reference()
        opts = self.run_options
        progress.stage(f"flying the Section 5 case (RK4, dt = {opts.dt:g} s) and again at "
                       "dt/4 (the convergence check)")
        f = fly_section5(self.gains, opts)
        res, ctx = f.res, f.ctx
        s = json_safe({**f.summary.numbers, **case_record(res.cases, 0)})
        conv = f.convergence
        figures, files = [], {"summary.json": DOCUMENT}
        if self.want_figures:
            progress.stage("figures")
            from lgw.tuning.lunar.figures import report_figures

            figures = report_figures(res, ctx, what=f"Section 5 case, {opts.thrust_pointing} "
                                     "pointing, the command's gains")
        if self.want_overview:
            from lgw.tuning.lunar.figures import section5_png

            files["section5.png"] = section5_png(res)
        doc = {"options": json_safe(dict(opts.__dict__)), "reference": ref.to_dict(),
               "outcomes": {s["outcome"]: 1}, "cases": [s],
               "convergence": conv.to_dict()}
        return Outcome(doc, render=lambda con: _render(con, ref, opts, [s], {s["outcome"]: 1},
                                                       conv),
                       files=files, figures=figures, flags=conv.flags("Section 5"))


@dataclass(frozen=True)
class CampaignJob(Job):
    """A Monte Carlo campaign (``lgw.sim.lunar.campaign``)."""

    gains: Any
    run_options: Any
    cases: int
    seed: int
    envelope: Any  # lgw.sim.lunar.campaign.Envelope
    dispersion: str
    want_figures: bool

    def run(self, progress: Any) -> Outcome:
        from lgw.sim.lunar import campaign as CP
        from lgw.sim.lunar.outcomes import OUTCOMES, json_safe
        from lgw.tuning.io import Stream
        from lgw.tuning.stats import finite_stats

        opts = self.run_options
        progress.stage(f"flying {self.cases} cases over the {self.envelope.name} envelope "
                       f"(RK4, dt = {opts.dt:g} s), the first {min(self.cases, CP.CHECK_CASES)}"
                       " again at dt/2")
        res = CP.run(self.gains, opts, self.cases, self.seed, self.envelope, self.dispersion,
                     progress)
        include = np.isin(res.outcome, [OUTCOMES.index(o) for o in CP.COUNTED])
        stats = {k: {**finite_stats(res.numbers[k], include), "unit": CP.UNITS[k]}
                 for k in CP.NUMBERS}
        outcomes = {o: int(np.sum(res.outcome == j)) for j, o in enumerate(OUTCOMES)}
        conv = [c.to_dict() for c in res.convergence]
        flags = [line for i, c in enumerate(res.convergence)
                 for line in c.flags(f"campaign case {i}")]
        head = {"options": json_safe(dict(opts.__dict__)), "envelope": self.envelope.to_dict(),
                "dispersion": self.dispersion, "seed": self.seed, "cases_n": self.cases,
                "outcomes": outcomes, "counted": list(CP.COUNTED), "statistics": stats,
                "convergence": {"refined_cases": len(conv), "converged": not flags,
                                "cases": conv}}
        figures = []
        if self.want_figures:
            progress.stage("figures of case 0")
            figures = _case0_figures(self.gains, opts, res)
        # summary.json is the --json document itself (with its lgw_version, command, gains
        # head); the cases are re-generated for each of the two writes
        doc = {**head, "cases": Stream(items=lambda: CP.iter_case_records(res))}
        files = {"summary.json": DOCUMENT}
        return Outcome(doc, render=lambda con: _render_campaign(con, head), files=files,
                       figures=figures, flags=flags)


def _case0_figures(gains: Any, opts: Any, res: Any) -> list:
    from dataclasses import replace

    from lgw.sim.lunar.batch import rk4_batch
    from lgw.sim.lunar.closed_loop import initial_state, make_context
    from lgw.sim.lunar.reference import reference
    from lgw.tuning.lunar.figures import report_figures

    d = res.draw.take(slice(0, 1))
    o = replace(opts, t_fail=float(d.t_fail[0]), Ta=float(d.ta[0]))
    ref = reference()
    ctx = make_context(ref, [gains], o)
    X0 = initial_state(ref, d.dh, d.dv, d.Q0, d.w0, [gains])
    r = rk4_batch(ctx, X0, record_every=max(1, int(round(0.1 / o.dt))))
    return report_figures(r, ctx, what=f"case 0 of {len(res)} campaign cases, "
                          f"{o.thrust_pointing} pointing")


def _render(con: Any, ref: Any, opts: Any, sums: list[dict[str, Any]],
            outcomes: dict[str, int], conv: Any) -> None:
    from lgw.tuning.tables import fmt, result_table

    con.print(f"reference: t_f = {ref.tf:.3f} s, a1 = {ref.a1:.6g}, a2 = {ref.a2:.6g} 1/s, "
              f"a3 = {ref.a3:.6g}; RK4 dt = {opts.dt:g} s, pointing {opts.thrust_pointing}, "
              f"command filter wn = {opts.cmd_wn:g} rad/s, T_max = {opts.thrust_max:g} N",
              markup=False)
    rows = [(str(i), fmt(s["eh_final_m"]), fmt(s["ev_final_norm_m_s"]),
             fmt(s["max_abs_eh_m"]), fmt(s["orbit_saturated_s"]),
             fmt(s["orbit_saturated_after_failure_s"]), fmt(s["torque_saturated_initial_s"]),
             fmt(s["torque_saturation_end_s"]),
             f"{fmt(s['d0e_orbit_final'])}/{fmt(s['d0e_attitude_final'])}",
             f"{s['outcome']} at {fmt(s['t_outcome_s'])} s")
            for i, s in enumerate(sums)]
    result_table(con, "seed 001: the Section 5 case",
                 ("case", "e_h(t_f) m", "|e_v(t_f)| m/s", "max|e_h| m", "orbit sat s",
                  "sat after failure s", "torque sat from 0 s", "torque sat ends s",
                  "d0e orbit/att", "outcome"), rows)
    crow = [(c.name, f"{c.value:.6g}", f"{c.refined:.6g}", f"{100 * c.difference:.3g} %",
             "yes" if c.converged else "NO") for c in conv.checks]
    result_table(con, f"convergence: dt = {conv.dt:g} s against dt/4 = {conv.refined_dt:g} s "
                 "(1 % or the floor)", ("number", "dt", "dt/4", "difference", "converged"),
                 crow)
    for line in conv.record.notes():
        con.print(line, markup=False)  # the line every system prints


def _render_campaign(con: Any, head: dict[str, Any]) -> None:
    from lgw.tuning.tables import fmt, result_table

    st = head["statistics"]
    rows = [(k, st[k]["unit"], str(st[k]["n"]), fmt(st[k]["min"]), fmt(st[k]["mean"]),
             fmt(st[k]["max"])) for k in st]
    result_table(con, f"seed 001 campaign: {head['cases_n']} cases over the "
                 f"{head['envelope']['name']} envelope, statistics over the completed cases",
                 ("number", "unit", "n", "min", "mean", "max"), rows)
    con.print("outcomes: " + ", ".join(f"{k} {v}" for k, v in head["outcomes"].items()),
              markup=False)
    c = head["convergence"]
    con.print(f"convergence: the first {c['refined_cases']} cases re-flown at dt/2: "
              + ("converged (1 %)" if c["converged"] else "NOT converged (see warnings)"),
              markup=False)


def check_filter_step(run: Any, wn_given: bool) -> None:
    """RK4 is stable on the command filter's poles only for wn dt <= WN_DT_MAX: a named error
    (--cmd-wn if given, else --dt) before any work."""
    from lgw.theory.errors import ParameterError

    if run.cmd_wn * run.dt > WN_DT_MAX:
        name, val = ("--cmd-wn", run.cmd_wn) if wn_given else ("--dt", run.dt)
        raise ParameterError(name, val, f"gives wn dt = {run.cmd_wn * run.dt:.3g} with wn = "
                             f"{run.cmd_wn:g} rad/s, dt = {run.dt:g} s: RK4 is stable on the "
                             f"command filter only for wn dt <= {WN_DT_MAX:g}")


def plan(opts: Options, system: Any) -> Job:
    from dataclasses import replace

    from lgw.sim.lunar import campaign as CP
    from lgw.sim.lunar.closed_loop import RunOptions
    from lgw.theory.errors import ParameterError
    from lgw.tuning.lunar.gainset import resolve, run_defaults

    g = resolve(opts.gains)
    pointing = opts.pointing or str(g.extra.get("certificate", {}).get("pointing", "coupled"))
    if pointing not in ("coupled", "ideal"):
        raise ParameterError("--gains", pointing, "its certificate.pointing must be coupled or "
                             "ideal")
    run = RunOptions(sat_reading=opts.sat_reading, failure=opts.failure, t_fail=opts.t_fail,
                     thrust_pointing=pointing)
    from lgw.sim.lunar import parameters as SP

    changes = run_defaults(g)
    if opts.cases is not None:
        changes["dt"] = SP.DT_CAMPAIGN
    changes.update({k: v for k, v in (("dt", opts.dt), ("t_end", opts.t_max), ("Ta", opts.ta),
                                      ("cmd_wn", opts.cmd_wn),
                                      ("thrust_max", opts.thrust_max)) if v is not None})
    run = replace(run, **changes)
    check_filter_step(run, opts.cmd_wn is not None)
    if opts.cases is None:
        return SimulateJob(g, run, opts.plot is not None, opts.out is not None)
    from lgw.tuning.io import check_memory

    check_memory("--cases", opts.cases, CP.BYTES_PER_CASE, "the campaign's per-case draw and "
                 "numbers")
    if opts.envelope == "certificate":
        from lgw.tuning.lunar.design import certificate_request

        if opts.gains is None:
            raise ParameterError("--envelope", "certificate", "needs --gains with a "
                                 "[certificate] table (a file from lgw tune lunar)")
        env = certificate_request(g).envelope
    else:
        env = CP.ENVELOPES[opts.envelope]
    return CampaignJob(g, run, opts.cases, opts.seed, env, opts.dispersion,
                       opts.plot is not None)
