"""Design gains whose proven landing-time bound meets --tf and whose command stays under the
thrust limit over an initial-state envelope, and write them with a [certificate].

--law corrected (default): seed 000's law with exact cancellation; geometric programming on the
proven bound, the peak thrust checked by a simulated worst-case search over the envelope
(states too close to the target are kept out, --keep-out / --brake-fraction).  --law bounded /
bounded-sat: the workbench's bounded cascades; time and thrust bounds proven over the envelope's
boxes, no keep-out.  Exit 0 feasible (file written); 3 infeasible (the reason and the nearest
feasible tf on stderr, nothing written).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import AXES, THETA1_PAPER, THETA2_PAPER
from lgw.tuning import vocabulary as V
from lgw.tuning.options import Number, choice
from lgw.tuning.spec import Options, option
from lgw.tuning.system import EXIT_INFEASIBLE, Job, Outcome

# Upper ends of the request, on the scale of a Mars powered descent (km, minutes, kN), so that the
# geometric program and the simulated check stay well scaled: larger values are typing errors.
TF_MAX = 1e4  # s
THRUST_CAP = 1e9  # N
LAWS = ("corrected", "bounded", "bounded-sat")
BOUNDS = ("exact", "polyakov")  # lgw.tuning.mars.design.BOUNDS
OBJECTIVES = ("peak-thrust", "fuel")  # lgw.tuning.mars.design.OBJECTIVES
CORRECTED_ONLY = ("a_max", "neighborhood", "theta1", "theta2", "bound", "objective", "keep_out",
                  "brake_fraction", "fast")


@dataclass(frozen=True)
class Options(Options):
    tf: float | None = option("--tf", Number(0, TF_MAX, lo_open=True, unit="s"), None,
                              "required landing-time bound, s [required]", probe=90.0)
    thrust_max: float | None = option("--thrust-max", Number(0, THRUST_CAP, lo_open=True,
                                                             unit="N"), None,
                                      "actuator limit, N: per axis or on the norm (--limit) "
                                      "[required]", probe=50_000.0)
    limit: str = option("--limit", choice(("axis", "norm")), "axis",
                        "axis: |F_i| <= thrust-max; norm: ||F|| <= thrust-max")
    law: str = option("--law", choice(LAWS), "corrected",
                      "law to tune: corrected (seed 000 with exact cancellation), bounded "
                      "(proven command bound, no keep-out) or bounded-sat (bounded with the "
                      "cancellation saturated at psi(|r|) + w0)")
    envelope: str = option("--envelope", None, "table3+table2",
                           "initial states to cover: table3+table2 | table3 | table2 | a CSV "
                           "file of states (rx, ry, rz, vx, vy, vz, m; m, m/s, kg; corrected "
                           "law only)", probe="table3")
    a_max: float | None = option("--a-max", Number(0, 1e3, lo_open=True, unit="m/s^2"), None,
                                 "disturbance bound |a_p,i|, m/s^2 [default: no disturbance; "
                                 "needs --neighborhood; corrected law]", probe=V.NO_PROBE)
    neighborhood: float | None = option("--neighborhood", Number(0, 1e6, lo_open=True,
                                                                 unit="m"), None,
                                        "required landing neighbourhood (31) under --a-max, m "
                                        "[corrected law]", probe=V.NO_PROBE)
    theta1: float = option("--theta1", Number(0, 1, lo_open=True, hi_open=True),
                           THETA1_PAPER, "Theorem 4 splitting constant of s2 (39), in (0, 1) "
                           "(with --a-max)", probe=V.NO_PROBE)
    theta2: float = option("--theta2", Number(0, 1, lo_open=True, hi_open=True),
                           THETA2_PAPER, "Theorem 4 splitting constant of s1 (31), in (0, 1) "
                           "(with --a-max)", probe=V.NO_PROBE)
    bound: str = option("--bound", choice(BOUNDS), "exact", "landing-time bound to meet: "
                        "exact (T1* + T2*) or polyakov ((18) + (26)) [corrected law]")
    objective: str = option("--objective", choice(OBJECTIVES), "peak-thrust",
                            "what the gains minimize over the envelope [corrected law]")
    keep_out: float = option("--keep-out", Number(0, 1e5, unit="m"), 50.0,
                             "d_keep: states closer than this to the target on an axis are not "
                             "covered, m [corrected law]")
    brake_fraction: float = option("--brake-fraction", Number(0, 1, lo_open=True), 0.5,
                                   "kappa in (0, 1]: states that must brake harder than kappa x "
                                   "the available deceleration to stop short of the target are "
                                   "not covered [corrected law]", probe=0.6)
    seed: int = V.seed(0, "seed of the worst-case search and the simulated check")
    fast: bool = option("--fast", None, False, "smaller exponent grid and worst-case search "
                        "[corrected law]", is_flag=True)
    no_suggest: bool = option("--no-suggest", None, False, "on an infeasible target, do not "
                              "search the nearest feasible tf", is_flag=True, probe=V.NO_PROBE)
    json: bool = V.json_flag()
    out: Path | None = V.out_file("the gains TOML with its [certificate] table", required=True)

    def check(self) -> None:
        super().check()
        for name, flag in (("tf", "--tf"), ("thrust_max", "--thrust-max"), ("out", "--out")):
            if getattr(self, name) is None:
                raise ParameterError(flag, None, "is required")
        for name in CORRECTED_ONLY:
            self.refuse_unless(self.law == "corrected", name, f"does not apply with --law "
                               f"{self.law} (its bounds are proven over boxes, with no "
                               "keep-out and no disturbance term)")
        if self.law != "corrected" and self.envelope not in ("table3", "table2",
                                                             "table3+table2"):
            raise ParameterError("--envelope", self.envelope, "must be table3, table2 or "
                                 f"table3+table2 with --law {self.law} (the bounds are over "
                                 "boxes)")
        self.refuse_unless(self.a_max is not None, "theta1", "only applies with --a-max")
        self.refuse_unless(self.a_max is not None, "theta2", "only applies with --a-max")
        if (self.a_max is None) != (self.neighborhood is None):
            raise ParameterError("--a-max" if self.a_max is None else "--neighborhood", None,
                                 "--a-max and --neighborhood go together")


def inputs(opts: Options) -> list[Path]:
    p = Path(opts.envelope)
    return [p] if opts.envelope not in ("table3", "table2", "table3+table2") else []


def command_line(opts: Options) -> str:
    """The ``lgw tune mars`` command that reproduces this run (recorded in the certificate)."""
    from dataclasses import fields

    from lgw.tuning.spec import opt_of

    parts = ["lgw tune mars"]
    for f in fields(opts):
        o = opt_of(f)
        if o is None or o.flag == "--json" or not opts.given(f.name):
            continue
        v = getattr(opts, f.name)
        parts.append(o.flag if o.is_flag else f"{o.flag} {v:g}" if isinstance(v, float)
                     else f"{o.flag} {v}")
    return " ".join(parts)


@dataclass(frozen=True)
class CorrectedTuneJob(Job):
    request: Any  # lgw.tuning.mars.design.Request
    envelope: Any  # lgw.tuning.mars.design.Envelope
    seed: int
    fast: bool
    suggest: bool
    command: str

    def run(self, progress: Any) -> Outcome:
        from dataclasses import replace

        from lgw.tuning.mars import design
        from lgw.tuning.mars.gains_file import certificate, gains_file_text

        req, env = self.request, self.envelope
        progress.stage(f"geometric program and worst-case search over {env.name}")
        res = design.tune(req, env, seed=self.seed, fast=self.fast)
        note = whole_box_note(env, res.forced_fraction, req.thrust_max, req.limit)
        if not res.feasible:
            err = [f"infeasible: {res.reason}"] + ([f"note: {note}"] if note else [])
            if self.suggest:
                progress.stage("searching the nearest feasible tf")
                start = replace(req, tf=max(req.tf, res.tf_min_envelope))
                tf_ok, r_ok = design.nearest_feasible_tf(start, env, seed=self.seed)
                if tf_ok is None:
                    err.append("no tf up to 600 s is feasible at this thrust limit: raise "
                               "--thrust-max or shrink the envelope")
                else:
                    ev = r_ok.evaluation
                    err.append(f"nearest feasible tf: {tf_ok:g} s (worst simulated peak "
                               f"{ev.worst_value:.0f} N at {_fmt_state(ev.worst_state)}); "
                               f"rerun with --tf {tf_ok:g}")
            err.append("nothing written")
            return Outcome({"feasible": False, "reason": res.reason}, exit_code=EXIT_INFEASIBLE,
                           stderr=err)
        cert = certificate(res, req, env, command=self.command)
        header = (f"lgw tune mars: tf = {req.tf:g} s, thrust_max = {req.thrust_max:g} N "
                  f"({req.limit}), bound = {req.bound}, envelope = {env.name}")
        text = gains_file_text(res.gains, cert, header)
        return Outcome({**res.gains.to_dict(), "feasible": True,
                        "tuned_gains": res.gains.to_dict(), "certificate": cert},
                       render=lambda con: _render_corrected(con, res, req, env, cert, note),
                       files={"gains.toml": text})


def _render_corrected(con: Any, res: Any, req: Any, env: Any, cert: dict[str, Any],
                      note: str | None) -> None:
    ev = res.evaluation
    b = cert["bounds"]
    key = "landing_time_bound" if req.bound == "exact" else "landing_time_bound_polyakov"
    p = lambda s: con.print(s, markup=False, highlight=False)  # noqa: E731
    p(f"exponents q1 = {res.gains.q1:.4g}, q2 = {res.gains.q2:.4g}, g1 = {res.gains.g1:.4g}, "
      f"g2 = {res.gains.g2:.4g}; solver {cert['solver']} ({cert['solver_status']})")
    for i, ax in enumerate(AXES):
        p(f"  {ax}: beta1 {res.gains.beta1[i]:.4g} beta2 {res.gains.beta2[i]:.4g} "
          f"alpha1 {res.gains.alpha1[i]:.4g} alpha2 {res.gains.alpha2[i]:.4g}  "
          f"bound ({req.bound}) {b[ax][key]:.2f} s (proven)")
    p(f"worst simulated peak thrust {ev.worst_value:.0f} N "
      f"({100 * ev.worst_value / req.thrust_max:.1f} % of the limit; sampled, not proven) at "
      f"{_fmt_state(ev.worst_state)}; {res.search_counts['total']} states, "
      f"{ev.saturated} saturated, all landed: {ev.all_landed}, "
      f"latest landing {ev.max_landing_time:.2f} s")
    p(f"fuel over the envelope: max {ev.fuel_max:.1f} kg, mean {ev.fuel_mean:.1f} kg")
    p(f"envelope {env.name}: {100 * res.excluded_fraction:.1f} % of the box is in the "
      f"keep-out (not covered); {100 * res.forced_fraction:.1f} % cannot be stopped "
      f"short of the target by any law within the limit")
    if note:
        p(f"note: {note}")
    p(f"tuned in {res.elapsed:.1f} s")


@dataclass(frozen=True)
class BoundedTuneJob(Job):
    request: Any  # lgw.tuning.mars.design_bounded.BoundedRequest
    envelope: Any
    law: str
    seed: int
    suggest: bool
    command: str

    def run(self, progress: Any) -> Outcome:
        import time

        from lgw.tuning.mars import design_bounded as DB
        from lgw.tuning.mars.gains_file import bounded_gains_file_text

        t0 = time.perf_counter()
        req, env, law, tf = self.request, self.envelope, self.law, self.request.tf
        progress.stage(f"designing the {law} law for {env.name} ({len(env.boxes)} boxes): "
                       f"thrust bound ({DB.BOUND_WORD}) <= {req.margin:g} x "
                       f"{req.thrust_max:g} N")

        def sim(bg: Any) -> dict[str, Any]:
            return DB.simulate_check(bg, req, env.boxes, env.m_max,
                                     t_max=max(1.5 * tf, tf + 20), seed=self.seed)

        res = DB.tune_bounded(req, env.boxes, env.m_max, progress=progress.stage,
                              simulate=sim, law=law)
        res.timings["total"] = time.perf_counter() - t0
        if not res.feasible:
            err = [f"infeasible: {res.reason}"]
            if res.gains is not None and np.isfinite(res.T_proven) and self.suggest:
                tf_ok = math.ceil(res.T_proven * 10) / 10
                err.append(f"nearest feasible tf: {tf_ok:g} s ({DB.BOUND_WORD}: the landing-time "
                           f"bound of the best gains found, with the thrust bound "
                           f"{res.F_proven:.0f} N); rerun with --tf {tf_ok:g}")
            err.append("nothing written")
            return Outcome({"feasible": False, "reason": res.reason}, exit_code=EXIT_INFEASIBLE,
                           stderr=err)
        cert = DB.certificate_bounded(res, req, env.name, self.command)
        header = (f"lgw tune mars --law {law}: tf = {tf:g} s, thrust_max = "
                  f"{req.thrust_max:g} N ({req.limit}), envelope = {env.name}")
        text = bounded_gains_file_text(res.gains, cert, header)
        return Outcome({"gains": {"law": law, **res.gains.to_dict()}, "feasible": True,
                        "certificate": DB._plain(cert)},
                       render=lambda con: _render_bounded(con, res, law),
                       files={"gains.toml": text})


def _render_bounded(con: Any, res: Any, law: str) -> None:
    from lgw.tuning.mars.design_bounded import BOUND_WORD

    p = lambda s: con.print(s, markup=False, highlight=False)  # noqa: E731
    if res.sim:
        s = res.sim
        p(f"simulated {s['states']} states: latest landing {s['max_landing_time']:.1f} s, "
          f"{s['saturated']} saturated, {s['below_ground']} below ground, peak "
          f"{s['peak_thrust']:.0f} N")
    p(f"e1 = {res.gains.e1:g}, e2 = {res.gains.e2:g}, p2 = {res.gains.p2:g}; time "
      f"{BOUND_WORD if res.time_proven else 'checked by simulation'}")
    for i, ax in enumerate(AXES):
        a = res.axes[ax]
        p(f"  {ax}: c1 {res.gains.c1[i]:.4g} delta {res.gains.delta[i]:.4g} "
          f"k1 {res.gains.k1[i]:.4g} k2 {res.gains.k2[i]:.4g}"
          + (f" w0 {res.gains.w0[i]:.4g}" if law == "bounded-sat" else "")
          + f"  T_land {a['T_land']:.1f} s, |F| <= {a['F_b']:.0f} N ({BOUND_WORD})")
    p(f"tuned in {res.timings['total']:.1f} s")


def plan(opts: Options, system: Any) -> Job:
    from lgw.tuning.mars.design import Request, envelope_from_name

    try:
        env = envelope_from_name(opts.envelope, keep_out=opts.keep_out,
                                 brake_fraction=opts.brake_fraction)
    except ParameterError as e:  # a CSV envelope is read by the --initial-states loader
        if not e.name.startswith("--initial-states"):
            raise
        raise ParameterError(e.name.replace("--initial-states", "--envelope"), e.value,
                             e.valid) from None
    cmd = command_line(opts)
    if opts.law != "corrected":
        from lgw.tuning.mars.design_bounded import BoundedRequest

        req = BoundedRequest(tf=opts.tf, thrust_max=opts.thrust_max, limit=opts.limit)
        req.check()
        return BoundedTuneJob(req, env, opts.law, opts.seed, not opts.no_suggest, cmd)
    req = Request(tf=opts.tf, thrust_max=opts.thrust_max, limit=opts.limit, bound=opts.bound,
                  objective=opts.objective, a_max=opts.a_max, neighborhood=opts.neighborhood,
                  theta1=opts.theta1, theta2=opts.theta2)
    req.check()
    return CorrectedTuneJob(req, env, opts.seed, opts.fast, not opts.no_suggest, cmd)


def _fmt_state(x: np.ndarray) -> str:
    return (f"r0 = {np.round(x[:3], 1).tolist()} m, v0 = {np.round(x[3:6], 1).tolist()} m/s, "
            f"m0 = {x[6]:.0f} kg")


def whole_box_note(env: Any, forced_fraction: float, thrust_max: float,
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


