"""Design of seed 001's loop for a target tracking error and a thrust limit, with the failure:
what the paper leaves open (the orbit gains, the command-filter bandwidth, the thrust
redundancy), the certificate that says how each promise is known, and the checks a verifier
re-runs on a tuned file (``check_certificate``).

The design, step by step (docs/lunar.md, "Tuning"):

1. Thrust redundancy (closed form, exact).  After the failure (26) the engine delivers T_a of
   the command, so holding the nominal thrust T_d needs a command T_d / T_a; the limit must
   cover it: T_max T_a >= T_d (checked in exact rationals over the envelope's smallest T_a).
   Without a given limit the tuner sizes T_max = (1 + THRUST_MARGIN) T_d / T_a,min, rounded
   up to 100 N; with one, a limit below T_d / T_a,min is infeasible.
2. Orbit gains (closed form, a design estimate).  Under the persistent failure the command
   and the delivered thrust differ by du = (T_a - 1) T_d / T_a along the thrust, so the filter
   (11) settles at lambda2 = F2^-1 B0 du, lambda1 = -lambda2_z / K1_zz (f1 = a_h): the loop
   tracks lambda, not 0, and the final errors are that offset.  With b = (1 - T_a) T_d /
   (T_a m_f) (m_f the reference's final mass) the offset at t_f is |F2^-1 b n| (n the thrust
   direction at t_f); F2 = f I with f = |b| / (TRANSIENT_SHARE ev_max) keeps it within half
   the velocity target, and K1_zz = max(paper, b_z / (f TRANSIENT_SHARE eh_max)) the height
   offset within half the height target.  The other half is left to the transient.
3. Command-filter bandwidth (simulation).  ``select_bandwidth`` flies the envelope's nominal
   case (coupled pointing, with the failure) for every wn of ``WN_GRID`` at dt and dt / 2; a
   point is robust when the case completes at both steps and both scores max(|e_h|/eh_max,
   |e_v|/ev_max) are at most max(1, BAND_SCORE x the best score); the widest run of
   consecutive robust points is the band, and wn is its grid point nearest the band's
   geometric centre.  (Not "agree to 1 %": the coupled loop's final errors move by up to
   ~10 % between dt and dt/2 when the torque saturates for long; what must not move is whether
   the target is met.)  Why no closed form: with the torque limit of (28) the
   attitude loop cannot follow the commanded thrust direction of a saturated orbit loop
   (docs/lunar.md, "The command filter"); the sweep shows where the outcome is insensitive.
4. Acceptance (simulation, sampled).  A fresh campaign over the envelope (coupled, with the
   failure drawn as the envelope says): every case must complete, meet both targets, and
   command no more than T_max after the failure; its first cases are re-flown at dt / 2 and
   must complete and meet the targets there too (their largest relative difference is
   recorded).
   Candidates (``candidates``) are tried in order; none accepted: infeasible (exit 3).

The certificate ([certificate] of the tuned TOML) names every promise with its evidence word:
"proven" only for what is proven over the envelope (the redundancy inequality in exact
arithmetic; the hypotheses of (13) and (18) on the gains; the (18) constants against the true
L2 gains of the orbit filter by python-control's linfnorm), "sampled" with sample size and
best margin for what only simulation supports (the tracking targets, no saturation after the
failure, the bandwidth's robustness).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

import numpy as np
from lgw.sim.lunar import parameters as SP
from lgw.sim.lunar.campaign import SECTION5, Envelope
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.theory.errors import ParameterError
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import Gains, from_dict

THRUST_MARGIN = 0.05  # sized T_max above T_d / T_a,min (transients of the feedback): chosen
TRANSIENT_SHARE = 0.5  # share of each target the steady failure offset may use: chosen
BAND_SCORE = 2.0  # robust points score within this factor of the best robust score: chosen
WN_GRID = (1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 20.0, 25.0, 30.0,
           35.0, 40.0, 45.0, 50.0)  # rad/s
SCALES = (1.0, 2.0, 0.5, 4.0)  # candidate multipliers of the closed-form F2 (step 2)
EVIDENCE = ("proven", "sampled", "design estimate")
DEFAULT_TARGETS = (10.0, 2.0)  # m, m/s: the "tracking is maintained" tolerances of the
# Section 5 claim (lgw.sim.lunar.scenario.TRACK_H_TOL, TRACK_V_TOL)


@dataclass(frozen=True)
class Request:
    """What the design must meet: |e_h(t_f)| <= eh_max (m), |e_v(t_f)| <= ev_max (m/s) over the
    envelope with its failure, the thrust limit ``thrust_max`` (N; None: size it), acceptance
    ``cases`` (plus the envelope's nominal case), ``seed``, RK4 step ``dt`` (s); ``pointing``:
    whose flights the promises are about: "ideal" (the thrust along the command: the paper's
    orbit loop (22) with u_o as its input) or "coupled" (through the attitude loop and the
    command filter; with an ideal-pointing design the coupled campaign is flown and reported,
    not promised)."""

    eh_max: float = DEFAULT_TARGETS[0]
    ev_max: float = DEFAULT_TARGETS[1]
    thrust_max: float | None = None
    envelope: Envelope = SECTION5
    cases: int = 24
    seed: int = 0
    dt: float = SP.DT_CAMPAIGN
    wn_grid: tuple[float, ...] = WN_GRID
    pointing: str = "ideal"

    def __post_init__(self) -> None:
        for name, lo, hi in (("eh_max", 0.0, 1e5), ("ev_max", 0.0, 1e4), ("dt", 0.0, 0.1)):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and lo < v <= hi):
                raise ParameterError(name, v, f"must lie in ({lo:g}, {hi:g}]")
        if self.pointing not in ("ideal", "coupled"):
            raise ParameterError("pointing", self.pointing, "ideal or coupled")
        if self.thrust_max is not None and not (math.isfinite(self.thrust_max)
                                                and self.thrust_max > 0):
            raise ParameterError("thrust_max", self.thrust_max, "must be a finite number > 0")


# --- step 1: the redundancy -------------------------------------------------------------

def redundancy(ta_min: float, thrust_max: float | None = None) -> dict[str, Any]:
    """The thrust needed after the failure and the limit used (step 1 of the module
    docstring): ``required_N`` = T_d / T_a,min; ``thrust_max_N`` the given or sized limit;
    ``margin_N`` = T_max T_a,min - T_d, computed in exact rationals (``proven``: the sign of an
    exact number), ``sized``: whether the tuner chose T_max."""
    td, ta = Fraction(str(P.T_NOMINAL)), Fraction(str(ta_min))
    required = td / ta
    sized = thrust_max is None
    if sized:
        tm = Fraction(math.ceil(float(required * Fraction(str(1 + THRUST_MARGIN))) / 100) * 100)
    else:
        tm = Fraction(str(thrust_max))
    margin = tm * ta - td
    return {"required_N": float(required), "thrust_max_N": float(tm), "margin_N": float(margin),
            "ta_min": ta_min, "nominal_N": P.T_NOMINAL, "sized": sized,
            "holds": margin >= 0, "evidence": "proven",
            "how": "T_max T_a,min - T_d in exact rational arithmetic (fractions.Fraction)"}


# --- step 2: the gains ------------------------------------------------------------------

def failure_offset(F2_diag: np.ndarray, k1zz: float, ta: float) -> dict[str, Any]:
    """The quasi-steady tracking offset at t_f under the persistent failure (step 2): the
    filter (11) with the constant input B0 du, du = (T_a - 1) T_d / T_a along the reference
    thrust direction at t_f and m = the reference's final mass.  A design estimate (it assumes
    the command unsaturated and the transient over), not a bound."""
    from lgw.sim.lunar.reference import reference

    ref = reference()
    alpha, psi, _, _ = ref.angles(ref.tf)
    n = np.array([np.cos(alpha) * np.cos(psi), np.cos(alpha) * np.sin(psi), np.sin(alpha)])
    m_f = float(ref.state(ref.tf)[4])
    b = (1 - ta) / ta * P.T_NOMINAL / m_f * n  # |B0 du|, m/s^2
    lam2 = b / np.asarray(F2_diag, float)
    eh = abs(lam2[2]) / k1zz
    return {"b_m_s2": b.tolist(), "ev_m_s": float(np.linalg.norm(lam2)), "eh_m": float(eh),
            "m_final_kg": m_f, "evidence": "design estimate"}


def closed_form_gains(req: Request, scale: float = 1.0) -> Gains:
    """Orbit gains of step 2 (times ``scale`` on F2), the paper's attitude gains and its f3,
    q, d0e(0) (f3 kept below f2bar)."""
    ta = req.envelope.ta[0]
    b = failure_offset(np.ones(3), 1.0, ta)["b_m_s2"]
    bn = float(np.linalg.norm(b))
    f = max(scale * bn / (TRANSIENT_SHARE * req.ev_max), 0.6)  # f2bar > 1/2 (7), (17b)
    k1 = max(float(P.ORBIT_GAINS["K1"][2]), abs(b[2]) / (f * TRANSIENT_SHARE * req.eh_max))
    orbit = {**P.ORBIT_GAINS, "K1": [k1] * 3, "F2": [f] * 3,
             "f3": min(float(P.ORBIT_GAINS["f3"]), 0.5 * f)}
    return from_dict({"orbit": orbit, "attitude": dict(P.ATTITUDE_GAINS)})


def candidates(req: Request) -> list[Gains]:
    """The gain sets tried in order: the closed form of step 2 scaled by ``SCALES``."""
    return [closed_form_gains(req, s) for s in SCALES]


# --- step 3: the command-filter bandwidth -------------------------------------------------

@dataclass(frozen=True)
class SweepPoint:
    """One bandwidth of the sweep: the nominal case at dt and dt / 2."""

    wn: float
    eh: float
    ev: float
    eh_fine: float
    ev_fine: float
    outcome: str
    outcome_fine: str
    torque_saturation_end_s: float
    orbit_saturated_after_failure_s: float
    score: float
    score_fine: float
    converged: bool

    def to_dict(self) -> dict[str, Any]:
        from lgw.sim.lunar.outcomes import json_safe

        return json_safe(dict(self.__dict__))


@dataclass(frozen=True)
class Bandwidth:
    """The sweep and the choice: ``wn`` (None: no robust point), ``band`` (lo, hi) rad/s."""

    points: tuple[SweepPoint, ...]
    wn: float | None
    band: tuple[float, float] | None
    best_score: float | None
    robust: tuple[float, ...] = ()

    COLUMNS = ("wn rad/s", "e_h(t_f) m", "|e_v(t_f)| m/s", "outcome", "torque sat ends s",
               "sat after failure s", "dt/2 agrees", "robust")

    def rows(self, fmt: Callable[[Any], str]) -> tuple[tuple[str, ...], ...]:
        """The sweep as table rows (``COLUMNS``, numbers by ``fmt``: the report's or the
        terminal's): what the rule judged at each point."""
        return tuple((fmt(p.wn), fmt(p.eh), fmt(p.ev), p.outcome, fmt(p.torque_saturation_end_s),
                      fmt(p.orbit_saturated_after_failure_s), "yes" if p.converged else "no",
                      "yes" if p.wn in self.robust else "no") for p in self.points)

    def to_dict(self) -> dict[str, Any]:
        return {"wn_rad_s": self.wn, "band_rad_s": list(self.band) if self.band else None,
                "robust_rad_s": list(self.robust), "best_score": self.best_score,
                "rule": "widest run of consecutive robust grid points (completed at dt and "
                        "dt/2, both scores max(|e_h|/eh_max, |e_v|/ev_max) <= max(1, "
                        f"{BAND_SCORE:g} x the best), orbit thrust never saturated after the "
                        "failure); wn = its grid point nearest the band's "
                        "geometric centre",
                "points": [p.to_dict() for p in self.points]}


def _nominal_state(env: Envelope) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The envelope's nominal case: the Section 5 initial errors."""
    return np.full(1, P.DH0), P.DV0[:, None].copy(), P.Q0[:, None].copy()


def sweep_bandwidth(gains: Gains, opts: RunOptions, grid: tuple[float, ...], eh_max: float,
                    ev_max: float, env: Envelope = SECTION5, progress: Any = None
                    ) -> tuple[SweepPoint, ...]:
    """Fly the nominal case (coupled pointing, the failure at the envelope's nominal time and
    level) for each wn of ``grid`` at opts.dt and opts.dt / 2."""
    from lgw.sim.lunar import convergence as CV
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.closed_loop import initial_state, make_context
    from lgw.sim.lunar.outcomes import OUTCOMES
    from lgw.sim.lunar.reference import reference
    from lgw.sim.lunar.scenario import case_numbers

    ref = reference()
    dh, dv, Q0 = _nominal_state(env)
    fail = (np.array([0.5 * sum(env.ta)]),
            np.array([ref.tf * 0.5 * sum(env.t_fail_fraction)]))
    pts = []
    for k, wn in enumerate(grid):
        row = []
        for dt in (opts.dt, opts.dt / 2):
            o = replace(opts, cmd_wn=float(wn), dt=dt, thrust_pointing="coupled")
            ctx = make_context(ref, [gains], o)
            X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, 1)), [gains])
            c = simulate(ctx, X0, record=False, failures=fail).cases
            row.append(case_numbers(c, ctx))
        a, b = row
        conv = CV.compare(a, b, opts.dt, opts.dt / 2, a["outcome"], b["outcome"],
                          {q: CV.QUOTED[q] for q in ("eh_final_m", "ev_final_norm_m_s")})
        def score(n: dict) -> float:
            if n["outcome"] != OUTCOMES[0]:
                return math.inf
            return max(abs(n["eh_final_m"]) / eh_max, n["ev_final_norm_m_s"] / ev_max)

        pts.append(SweepPoint(float(wn), a["eh_final_m"], a["ev_final_norm_m_s"],
                              b["eh_final_m"], b["ev_final_norm_m_s"], a["outcome"],
                              b["outcome"], a["torque_saturation_end_s"],
                              a["orbit_saturated_after_failure_s"], score(a), score(b),
                              bool(a["outcome"] == OUTCOMES[0] and conv.converged)))
        if progress is not None:
            progress.advance(k + 1, len(grid))
    return tuple(pts)


def choose_bandwidth(points: tuple[SweepPoint, ...]) -> Bandwidth:
    """The band and wn from a sweep (rule of step 3): a point is robust when the case
    completes at dt and at dt/2, both scores are at most S = max(1, BAND_SCORE x the best
    score of the sweep) (S = 1: the target met at both steps whenever any point meets it)
    and the orbit thrust is never saturated after the failure (seed 001's Section 5 claims
    the remaining thrust suffices: a filter that makes the vehicle lean on the limit after
    the failure fails the paper's premise however small its final errors); the band is the
    widest run of consecutive robust points (ties: the better best score), wn its point
    nearest the band's geometric centre."""
    done = [p for p in points if math.isfinite(p.score)]
    if not done:
        return Bandwidth(points, None, None, None)
    best = min(p.score for p in done)
    cap = max(1.0, BAND_SCORE * best)
    ok = [p.outcome == p.outcome_fine == "completed" and p.score <= cap
          and p.score_fine <= cap and p.orbit_saturated_after_failure_s == 0.0
          for p in points]
    if not any(ok):
        return Bandwidth(points, None, None, best)
    runs: list[list[int]] = []
    for i, good in enumerate(ok):
        if good and runs and runs[-1][-1] == i - 1:
            runs[-1].append(i)
        elif good:
            runs.append([i])
    widest = max(runs, key=lambda r: (len(r), -min(points[i].score for i in r)))
    lo, hi = points[widest[0]].wn, points[widest[-1]].wn
    centre = math.sqrt(lo * hi)
    pick = min(widest, key=lambda i: abs(math.log(points[i].wn / centre)))
    return Bandwidth(points, points[pick].wn, (lo, hi), best,
                     tuple(p.wn for p, g in zip(points, ok, strict=True) if g))


def select_bandwidth(gains: Gains, opts: RunOptions | None = None,
                     grid: tuple[float, ...] | None = None,
                     targets: tuple[float, float] = DEFAULT_TARGETS,
                     env: Envelope = SECTION5, progress: Any = None) -> Bandwidth:
    """Step 3: sweep and choose.  For the paper's gains on Section 5 this gives
    ``lgw.sim.lunar.parameters.CMD_WN`` (tests/lunar/test_design.py, slow)."""
    pts = sweep_bandwidth(gains, opts or RunOptions(), WN_GRID if grid is None else grid,
                          *targets, env, progress)
    return choose_bandwidth(pts)


# --- step 4: acceptance -----------------------------------------------------------------

def acceptance(gains: Gains, opts: RunOptions, req: Request, seed: int,
               cases: int | None = None, progress: Any = None) -> dict[str, Any]:
    """A fresh campaign over the envelope with the design (coupled, the failure as the
    envelope draws it), plus the nominal case; the sampled evidence of the certificate."""
    from lgw.sim.lunar import campaign as CP
    from lgw.sim.lunar.outcomes import OUTCOMES
    from lgw.sim.lunar.reference import reference

    n = req.cases if cases is None else cases
    d = CP.draw(n, seed, reference().tf, opts, req.envelope, "all")
    dh, dv, Q0 = _nominal_state(req.envelope)
    env = req.envelope
    nominal = CP.Draw(dh, dv, Q0, np.zeros((3, 1)), np.array([0.5 * sum(env.ta)]),
                      np.array([reference().tf * 0.5 * sum(env.t_fail_fraction)]))
    d = CP.Draw(*(np.concatenate([a, b], axis=-1) for a, b in
                  zip((nominal.dh, nominal.dv, nominal.Q0, nominal.w0, nominal.ta,
                       nominal.t_fail), (d.dh, d.dv, d.Q0, d.w0, d.ta, d.t_fail), strict=True)))
    nums, codes = CP.fly(gains, opts, d, progress)
    k = min(len(d), CP.CHECK_CASES)
    fnums, fcodes = CP.fly(gains, replace(opts, dt=opts.dt / 2), d.take(slice(0, k)))
    done = codes == OUTCOMES.index("completed")
    eh = np.abs(nums["eh_final_m"])
    ev = nums["ev_final_norm_m_s"]
    pk = np.where(np.isnan(nums["thrust_cmd_max_after_failure_N"]), 0.0,
                  nums["thrust_cmd_max_after_failure_N"])
    rel = [abs(nums[q][i] - fnums[q][i]) / max(abs(fnums[q][i]), fl)
           for i in range(k) for q, fl in (("eh_final_m", 0.01), ("ev_final_norm_m_s", 0.01))]
    fine_meets = bool(np.all(fcodes == OUTCOMES.index("completed"))
                      and np.all(np.abs(fnums["eh_final_m"]) <= req.eh_max)
                      and np.all(fnums["ev_final_norm_m_s"] <= req.ev_max))
    conv_outcome = bool(np.all(codes[:k] == fcodes))

    def worst(x: np.ndarray, bound: float) -> float | None:
        """(bound - max x)/bound over the completed cases (None: none completed)."""
        return float(np.min((bound - x) / bound)) if len(x) else None

    def top(x: np.ndarray) -> float | None:
        return float(np.max(x)) if len(x) else None

    return {"cases": int(len(d)), "seed": seed, "completed": int(done.sum()),
            "outcomes": {o: int(np.sum(codes == j)) for j, o in enumerate(OUTCOMES)},
            "eh_final_max_m": top(eh[done]), "ev_final_max_m_s": top(ev[done]),
            "eh_margin": worst(eh[done], req.eh_max),
            "ev_margin": worst(ev[done], req.ev_max),
            "thrust_cmd_after_failure_max_N": float(np.max(pk)),
            "thrust_margin": worst(pk, opts.thrust_max),
            "orbit_saturated_after_failure_max_s": float(np.nanmax(
                nums["orbit_saturated_after_failure_s"])),
            "torque_saturation_end_max_s": float(np.nanmax(nums["torque_saturation_end_s"])),
            "refined_cases": k, "refined_meets": bool(fine_meets and conv_outcome),
            "refined_max_difference": float(max(rel)) if rel else 0.0, "dt": opts.dt}


def accepted(acc: dict[str, Any]) -> tuple[bool, str]:
    """Whether an acceptance campaign meets every promise, and if not, why."""
    why = []
    if acc["completed"] < acc["cases"]:
        bad = {k: v for k, v in acc["outcomes"].items() if v and k != "completed"}
        why.append(f"{acc['cases'] - acc['completed']} of {acc['cases']} cases did not "
                   f"complete ({bad})")
    if acc["eh_margin"] is not None and acc["eh_margin"] < 0:
        why.append(f"|e_h(t_f)| reached {acc['eh_final_max_m']:.4g} m")
    if acc["ev_margin"] is not None and acc["ev_margin"] < 0:
        why.append(f"|e_v(t_f)| reached {acc['ev_final_max_m_s']:.4g} m/s")
    if acc["thrust_margin"] < 0:
        why.append(f"the command after the failure reached "
                   f"{acc['thrust_cmd_after_failure_max_N']:.6g} N")
    if not acc["refined_meets"]:
        why.append("the first cases re-flown at dt/2 do not all complete and meet the targets")
    return not why, "; ".join(why)


# --- the whole design -------------------------------------------------------------------

@dataclass
class TuneResult:
    feasible: bool
    reason: str = ""
    gains: Gains | None = None
    redundancy: dict = field(default_factory=dict)
    bandwidth: Bandwidth | None = None
    acceptance: dict = field(default_factory=dict)
    offset: dict = field(default_factory=dict)
    tried: list = field(default_factory=list)
    coupled: dict = field(default_factory=dict)  # the campaign under coupled pointing


def tune(req: Request, progress: Any = None) -> TuneResult:
    """Steps 1-4 of the module docstring."""
    red = redundancy(req.envelope.ta[0], req.thrust_max)
    if not red["holds"]:
        return TuneResult(False, f"the thrust limit {red['thrust_max_N']:.6g} N is below the "
                          f"demand after the failure: T_d / T_a,min = {P.T_NOMINAL:g} / "
                          f"{req.envelope.ta[0]:g} = {red['required_N']:.6g} N (T_max T_a,min "
                          f"- T_d = {red['margin_N']:.6g} N < 0, exact); give --thrust-max "
                          f">= {red['required_N']:.6g} or omit it to size it", redundancy=red)
    base = RunOptions(dt=req.dt, thrust_max=red["thrust_max_N"])
    tried = []
    for scale, g in zip(SCALES, candidates(req), strict=True):
        f2 = np.diag(g.orbit.F2)
        if progress is not None:
            progress.stage(f"candidate F2 = {f2[0]:.4g} I, K1_zz = {g.orbit.K1[2, 2]:.4g}: "
                           "command-filter sweep (coupled, nominal case)")
        bw = select_bandwidth(g, base, req.wn_grid, (req.eh_max, req.ev_max), req.envelope,
                              progress)
        entry: dict[str, Any] = {"scale": scale, "F2": f2.tolist(),
                                 "K1_zz": float(g.orbit.K1[2, 2]), "wn": bw.wn,
                                 "band": bw.band}
        meets = bw.wn is not None and bw.best_score is not None and bw.best_score <= 1
        if req.pointing == "coupled" and not meets:
            entry["rejected"] = ("no bandwidth of the sweep meets the target on the nominal "
                                 "case" if bw.wn is not None else
                                 "no robust point in the sweep")
            tried.append(entry)
            continue
        wn = bw.wn if bw.wn is not None else SP.CMD_WN
        opts = replace(base, cmd_wn=wn, thrust_pointing=req.pointing)
        if progress is not None:
            progress.stage(f"acceptance campaign ({req.cases} + 1 cases, {req.pointing} "
                           f"pointing, wn = {wn:g})")
        acc = acceptance(g, opts, req, req.seed + 1000, progress=progress)
        ok, why = accepted(acc)
        entry["acceptance"] = {k: acc[k] for k in ("cases", "completed", "eh_final_max_m",
                                                   "ev_final_max_m_s")}
        if not ok:
            entry["rejected"] = why
            tried.append(entry)
            continue
        coupled = acc
        if req.pointing == "ideal":
            if progress is not None:
                progress.stage("the same campaign under coupled pointing (reported, not "
                               "promised)")
            coupled = acceptance(g, replace(opts, thrust_pointing="coupled"), req,
                                 req.seed + 1000, progress=progress)
        tried.append(entry)
        design = Gains(g.orbit, g.attitude, extra={
            "command_filter": {"wn": float(wn)},
            "vehicle": {"thrust_max": red["thrust_max_N"]}})
        res = TuneResult(True, "", design, red, bw, acc,
                         failure_offset(f2, float(g.orbit.K1[2, 2]), req.envelope.ta[0]),
                         tried)
        res.coupled = coupled
        return res
    return TuneResult(False, "no candidate gain set was accepted: " + "; ".join(
        f"F2 = {t['F2'][0]:.4g} I: {t['rejected']}" for t in tried), redundancy=red,
        tried=tried)


# --- the certificate ----------------------------------------------------------------------

def hypotheses(g: Gains) -> dict[str, Any]:
    """The hypotheses (13), (17b), (18) need, checked exactly on the gains (orbit loop: F1 =
    K1_zz > 0, f2bar > 1/2, 0 < f3 < f2bar, q > 0, d0e(0) >= 0)."""
    o = g.orbit
    checks = {"F1 = K1_zz > 0": float(o.K1[2, 2]) > 0, "f2bar > 1/2": o.f2bar > 0.5,
              "0 < f3 < f2bar": 0 < o.f3 < o.f2bar, "q > 0": o.q > 0,
              "d0e(0) >= 0": o.d0e0 >= 0}
    return {"holds": all(checks.values()), "checks": checks, "evidence": "proven",
            "how": "the inequalities evaluated on the gains (eigenvalues by numpy eigvalsh)"}


def l2_gains(g: Gains) -> dict[str, Any]:
    """(18) for the orbit loop: the constants 1/sqrt(2 f1bar), 1/sqrt(2 f2bar - 1) against the
    true L2 gains of the LTI filter (11) (python-control linfnorm, SLICOT AB13DD; cross-checked
    by a frequency sweep in ``lgw.theory.lunar.bounds.hinf_gains``)."""
    from lgw.theory.lunar.bounds import orbit_bounds

    b = orbit_bounds(g.orbit)
    h = b.hinf
    ok1 = h["lambda1_hinf"] <= b.lambda1_gain * (1 + 1e-9)
    ok2 = h["lambda2_hinf"] <= b.lambda2_gain * (1 + 1e-9)
    return {"lambda1_gain_18a": b.lambda1_gain, "lambda1_hinf": h["lambda1_hinf"],
            "lambda2_gain_18b": b.lambda2_gain, "lambda2_hinf": h["lambda2_hinf"],
            "holds": bool(ok1 and ok2), "evidence": "proven",
            "how": "closed form (18) with its hypotheses checked; the true H-infinity norm "
                   "of the LTI orbit filter by python-control linfnorm is below it"}


def certificate(res: TuneResult, req: Request, command: str = "") -> dict[str, Any]:
    """The [certificate] table of a feasible design (flat keys, TOML-ready)."""
    g = res.gains
    assert g is not None and res.bandwidth is not None
    red, acc, bw = res.redundancy, res.acceptance, res.bandwidth
    wn = float(g.extra["command_filter"]["wn"])  # flown: the band's choice, else the default
    hyp, l2 = hypotheses(g), l2_gains(g)
    env = req.envelope
    return {
        "command": command, "system": "lunar", "law": "seed 001 (7)-(11), orbit and attitude",
        "envelope": env.name, "envelope_dh_m": list(env.dh),
        "envelope_dv_half_width_m_s": list(env.dv), "envelope_attitude_deg": env.att_deg,
        "envelope_attitude_axis": env.att_axis,
        "envelope_t_fail_fraction": list(env.t_fail_fraction), "envelope_ta": list(env.ta),
        "eh_max_m": req.eh_max, "ev_max_m_s": req.ev_max, "dt_s": req.dt,
        # step 1
        "thrust_max_N": red["thrust_max_N"], "thrust_sized": red["sized"],
        "thrust_required_N": red["required_N"], "redundancy_margin_N": red["margin_N"],
        "redundancy_evidence": "proven: T_max T_a,min - T_d >= 0 in exact rational arithmetic",
        # hypotheses and (18)
        "hypotheses_evidence": "proven: " + ", ".join(hyp["checks"]) + " checked on the gains",
        "lambda1_gain_18a": l2["lambda1_gain_18a"], "lambda1_hinf": l2["lambda1_hinf"],
        "lambda2_gain_18b": l2["lambda2_gain_18b"], "lambda2_hinf": l2["lambda2_hinf"],
        "l2_gain_evidence": "proven: " + l2["how"],
        # step 2
        "offset_ev_estimate_m_s": res.offset["ev_m_s"], "offset_eh_estimate_m": res.offset["eh_m"],
        "offset_evidence": "design estimate, not a bound: the quasi-steady filter (11) under "
                           "the persistent failure",
        # step 3
        "cmd_wn_rad_s": wn,
        "cmd_band_rad_s": list(bw.band or ()),
        "cmd_wn_evidence": f"sampled: {len(bw.points)} bandwidths x 2 steps on the nominal "
                           + ("case; the widest robust band's centre" if bw.wn is not None else
                              "case, none robust: the default wn of the paper's gains (ideal "
                              "pointing promised; the coupled run reported, not promised)"),
        # step 4 (the promises, for the flights of ``pointing``)
        "pointing": req.pointing,
        "tracking_evidence": f"sampled: {acc['cases']} cases (seed {acc['seed']}, "
                             f"{req.pointing} pointing), best margin "
                             f"{min(acc['eh_margin'], acc['ev_margin']):.4g}",
        "acceptance_cases": acc["cases"], "acceptance_seed": acc["seed"],
        "eh_final_max_m": acc["eh_final_max_m"], "ev_final_max_m_s": acc["ev_final_max_m_s"],
        "eh_margin": acc["eh_margin"], "ev_margin": acc["ev_margin"],
        "no_saturation_after_failure_evidence": f"sampled: {acc['cases']} cases, best margin "
                                                f"{acc['thrust_margin']:.4g}",
        "thrust_cmd_after_failure_max_N": acc["thrust_cmd_after_failure_max_N"],
        "thrust_margin": acc["thrust_margin"],
        "refined_cases": acc["refined_cases"], "refined_meets": acc["refined_meets"],
        "refined_max_difference": acc["refined_max_difference"],
        "torque_saturation_end_max_s": acc["torque_saturation_end_max_s"],
        # coupled pointing (reported; promised only when pointing = "coupled")
        "coupled_cases": res.coupled.get("cases", 0),
        "coupled_completed": res.coupled.get("completed", 0),
        "coupled_eh_final_max_m": res.coupled.get("eh_final_max_m"),
        "coupled_ev_final_max_m_s": res.coupled.get("ev_final_max_m_s"),
        "coupled_evidence": (f"sampled: the same {res.coupled.get('cases', 0)} cases under "
                             f"coupled pointing at wn = {wn}: "
                             f"{res.coupled.get('completed', 0)} completed; "
                             + ("promised" if req.pointing == "coupled" else
                                "reported, not promised")),
    }


# --- the verifier's checks of a tuned file --------------------------------------------------

CERT_NUMBERS = ("eh_max_m", "ev_max_m_s", "thrust_max_N", "dt_s", "cmd_wn_rad_s",
                "lambda1_gain_18a", "lambda2_gain_18b")
CERT_LISTS = ("envelope_dh_m", "envelope_dv_half_width_m_s", "envelope_t_fail_fraction",
              "envelope_ta")


def certificate_request(g: Gains) -> Request:
    """The request a tuned file's [certificate] records, validated by name (a string, a list,
    nan or a missing key is a named error, exit 2)."""
    cert = g.extra.get("certificate")
    if cert is None:
        raise ParameterError("certificate", None, "the gains file has no [certificate] table "
                             "(only files written by lgw tune lunar have one)")
    for k in CERT_NUMBERS:
        v = cert.get(k)
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) \
                or v <= 0:
            raise ParameterError(f"certificate.{k}", v, "must be a finite number > 0")
    for k in CERT_LISTS:
        v = cert.get(k)
        if not (isinstance(v, list) and all(isinstance(x, int | float) and not
                                             isinstance(x, bool) and math.isfinite(x)
                                             for x in v)):
            raise ParameterError(f"certificate.{k}", v, "must be a list of finite numbers")
    if len(cert["envelope_dv_half_width_m_s"]) != 3:
        raise ParameterError("certificate.envelope_dv_half_width_m_s",
                             cert["envelope_dv_half_width_m_s"], "three half-widths, m/s")
    att = cert.get("envelope_attitude_deg")
    if isinstance(att, bool) or not isinstance(att, int | float) or not math.isfinite(att):
        raise ParameterError("certificate.envelope_attitude_deg", att, "must be a finite number")
    axis = cert.get("envelope_attitude_axis", "random")
    if axis not in ("random", "x"):
        raise ParameterError("certificate.envelope_attitude_axis", axis, "random or x")
    env = Envelope(tuple(cert["envelope_t_fail_fraction"]), tuple(cert["envelope_ta"]),
                   tuple(cert["envelope_dh_m"]), tuple(cert["envelope_dv_half_width_m_s"]),
                   float(att), str(cert.get("envelope", "file")), axis)
    pointing = cert.get("pointing", "ideal")
    if pointing not in ("ideal", "coupled"):
        raise ParameterError("certificate.pointing", pointing, "ideal or coupled")
    return Request(cert["eh_max_m"], cert["ev_max_m_s"], cert["thrust_max_N"], env,
                   dt=cert["dt_s"], pointing=pointing)


@dataclass(frozen=True)
class CertificateCheck:
    """One promise of a certificate re-checked: ``observed`` against ``bound``, ``margin`` =
    (bound - observed)/bound (< 0 violates), the evidence word of the promise and of the
    re-check, and a ``reproduce`` command."""

    promise: str
    evidence: str
    observed: float
    bound: float
    margin: float
    holds: bool
    detail: str
    reproduce: str = ""

    def to_dict(self) -> dict[str, Any]:
        from lgw.sim.lunar.outcomes import json_safe

        return json_safe(dict(self.__dict__))


def check_certificate(g: Gains, cases: int = 16, seed: int = 12345,
                      progress: Any = None, sampled: bool = True) -> list[CertificateCheck]:
    """Re-check every promise of a tuned file's [certificate] (for ``lgw verify lunar``):
    the proven ones are recomputed from the file's gains (the redundancy in exact arithmetic,
    the hypotheses, the (18) constants against linfnorm); the sampled ones are re-flown on a
    fresh campaign of ``cases`` cases (``seed``) over the certificate's envelope with the
    file's command filter and thrust limit.  A promise the file's numbers contradict (e.g. a
    stated T_max below the demand) fails with the observed value.  ``sampled=False``: the
    proven promises only (no flight)."""
    req = certificate_request(g)
    cert = g.extra["certificate"]
    out: list[CertificateCheck] = []
    tm = float(cert["thrust_max_N"])
    red = redundancy(req.envelope.ta[0], tm)
    out.append(CertificateCheck(
        "thrust redundancy T_max T_a,min >= T_d", "proven", P.T_NOMINAL,
        tm * req.envelope.ta[0], red["margin_N"] / (tm * req.envelope.ta[0]),
        bool(red["holds"]), f"T_max = {tm:g} N, T_a,min = {req.envelope.ta[0]:g}, T_d = "
        f"{P.T_NOMINAL:g} N: margin {red['margin_N']:.6g} N (exact)"))
    hyp = hypotheses(g)
    out.append(CertificateCheck("hypotheses of (13), (17b), (18) on the orbit gains", "proven",
                                0.0, 0.0, 0.0 if hyp["holds"] else -1.0, bool(hyp["holds"]),
                                ", ".join(f"{k}: {v}" for k, v in hyp["checks"].items())))
    l2 = l2_gains(g)
    for lam, key in (("lambda1", "lambda1_gain_18a"), ("lambda2", "lambda2_gain_18b")):
        stated = float(cert[key])
        true = l2[f"{lam}_hinf"]
        out.append(CertificateCheck(
            f"L2 gain B0 du -> {lam} <= {key}", "proven", true, stated,
            (stated - true) / stated, bool(true <= stated * (1 + 1e-9)),
            f"stated {stated:.6g}, (18) recomputed {l2[key]:.6g}, linfnorm {true:.6g}"))
    if not sampled:
        return out
    opts = RunOptions(dt=req.dt, thrust_max=tm, cmd_wn=float(cert["cmd_wn_rad_s"]),
                      thrust_pointing=req.pointing)
    acc = acceptance(g, opts, req, seed, cases=cases, progress=progress)
    repro = (f"lgw simulate lunar --gains FILE --cases {cases} --seed {seed} --envelope "
             "certificate (the check adds the envelope's nominal case as its case 0)")
    done = acc["completed"] == acc["cases"]
    out.append(CertificateCheck(
        "every case of the envelope completes", "sampled", acc["cases"] - acc["completed"], 0,
        0.0 if done else -1.0, bool(done), f"outcomes {acc['outcomes']}", repro))
    for promise, obs, bound in (("|e_h(t_f)| <= eh_max", acc["eh_final_max_m"], req.eh_max),
                                ("|e_v(t_f)| <= ev_max", acc["ev_final_max_m_s"], req.ev_max),
                                ("commanded thrust after the failure <= T_max",
                                 acc["thrust_cmd_after_failure_max_N"], tm)):
        obs = math.inf if obs is None or not done else obs  # a crash meets no target
        m = (bound - obs) / bound
        out.append(CertificateCheck(promise, "sampled", obs, bound, m, bool(m >= 0),
                                    f"fresh campaign of {acc['cases']} cases (seed {seed}), "
                                    f"{req.pointing} pointing, dt = {req.dt:g} s", repro))
    return out


__all__ = ["Request", "TuneResult", "tune", "certificate", "check_certificate",
           "certificate_request", "select_bandwidth", "redundancy", "failure_offset"]
