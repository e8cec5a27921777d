"""Fuel-optimal descent of seed 000's Table I lander (SOCP, Acikmese & Ploen 2007; lossless
convexification) and its open-loop replay in the plant.

The flight time is --tf (default 30 s, seed 000 Part 1) or, with --min-tf, the shortest
feasible one.  A flight time outside the feasible interval is refused with that interval: too
short, the thrust limit cannot stop the lander; too long, the propellant runs out.  The
document carries ``gains: null``: the optimum flies no gain set.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim.mars.optimal import N_RANGE
from lgw.sim.mars.parameters import DRAG_MODELS
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import G_EARTH, ISP, M0, M_DRY, R0, THRUST_MAX_AXIS, V0
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Integer, Number, choice
from lgw.tuning.spec import Options, option
from lgw.tuning.system import Job, Outcome

PAPER_FUEL_OPTIMAL = 212.9067  # kg, seed 000 Part 1 (GPOPS, tf = 30 s)
REPLAYS = (("none", 0.0), ("sin", 1.0), ("sin", 20.0))  # Fig. 3 uses 1; (47) prints 20
TF_DEFAULT = 30.0  # s, seed 000 Part 1
TF_MAX = 1e5  # s


@dataclass(frozen=True)
class Options(Options):
    tf: float | None = option("--tf", Number(0, TF_MAX, lo_open=True, unit="s"), None,
                              f"flight time, s [default: {TF_DEFAULT:g}, seed 000 Part 1]; not "
                              "with --min-tf", probe=40.0)
    min_tf: bool = option("--min-tf", None, False, "find the shortest feasible flight time "
                          "instead (bisection on feasibility)", is_flag=True)
    thrust_max: float = V.thrust_max(THRUST_MAX_AXIS, "per axis or on the norm (--limit)")
    limit: str = option("--limit", choice(("axis", "norm")), "axis",
                        "axis: |F_i| <= thrust-max (seed 000 Part 3); norm: ||F|| <= "
                        "thrust-max")
    thrust_min: float | None = option("--thrust-min", Number(0, 1e9, unit="N"), None,
                                      "lower bound on ||F||, N (lossless convexification): "
                                      "below the largest ||F|| the limit allows, and low "
                                      "enough that it alone does not burn the propellant "
                                      "within tf [default: none, seed 000 states no minimum]",
                                      probe=5000.0)
    n: int = option("--n", Integer(N_RANGE[0], N_RANGE[1], "ZOH steps"), 80,
                    "number of zero-order-hold steps of the SOCP", probe=40)
    isp: float = V.isp(ISP)
    replay: bool = option("--replay", None, True, "fly the optimal force profile open loop in "
                          "the plant (no disturbance, 1 sin t, 20 sin t)", secondary="--no-replay")
    drag: str = option("--drag", choice(DRAG_MODELS), "none", "drag model of the replay's "
                       "plant (none: the SOCP's; only with --replay)")
    json: bool = V.json_flag()
    out: Path | None = V.out_dir("optimal.json (the --json document) and thrust.csv")

    def check(self) -> None:
        super().check()
        self.refuse_unless(not self.min_tf, "tf", "give either --tf SECONDS or --min-tf, not "
                           "both")
        self.refuse_unless(self.replay, "drag", "only applies with --replay (the SOCP has no "
                           "drag)")
        if self.thrust_min is not None:
            rho_max = self.thrust_max * (math.sqrt(3.0) if self.limit == "axis" else 1.0)
            what = "sqrt(3) x --thrust-max (the axis limit)" if self.limit == "axis" else \
                "--thrust-max (the norm limit)"
            if not self.thrust_min < rho_max:
                raise ParameterError("--thrust-min", self.thrust_min, f"must be in [0, "
                                     f"{rho_max:.6g}) N: below the largest ||F||, {what}")
            if not self.min_tf:
                tf = TF_DEFAULT if self.tf is None else self.tf
                burn_max = (M0 - M_DRY) * self.isp * G_EARTH / tf
                if not self.thrust_min < burn_max:
                    raise ParameterError("--thrust-min", self.thrust_min, f"must be < "
                                         f"{burn_max:.6g} N at tf = {tf:g} s: a larger minimum "
                                         f"thrust alone burns more than the {M0 - M_DRY:g} kg "
                                         "of propellant (m0 - m_dry) before tf")


@dataclass(frozen=True)
class OptimalJob(Job):
    tf: float | None  # None: the shortest feasible
    socp: dict[str, Any]  # keywords of lgw.sim.mars.optimal.solve_fuel_optimal
    replay: bool
    drag: str

    def run(self, progress: Any) -> Outcome:
        from lgw.sim.mars.optimal import solve_fuel_optimal

        mt = None
        if self.tf is None:
            progress.stage("shortest feasible flight time (bisection on feasibility)")
            mt = _min_time(self.socp)
            sol = mt.solution
        else:
            progress.stage(f"fuel-optimal SOCP, tf = {self.tf:g} s")
            sol = solve_fuel_optimal(R0, V0, M0, self.tf, **self.socp)
            if not sol.feasible:
                progress.stage("feasible flight times (bisection on feasibility)")
                _refuse_tf(self.tf, sol, self.socp)
        reps = []
        if self.replay:
            progress.stage("open-loop replays in the plant")
            reps = _replays(sol, self.drag)
        doc: dict[str, Any] = {"plant": "mars",
                               "solution": sol.to_dict(arrays=True), "sources": _sources(sol),
                               "replays": reps, "paper_fuel_optimal_kg": PAPER_FUEL_OPTIMAL}
        if mt is not None:
            doc["min_tf"] = {"tf_min": mt.tf_min, "bracket": list(mt.bracket),
                             "iterations": mt.iterations}
        return Outcome(doc, render=lambda con: _render(con, sol, mt, reps),
                       files={"optimal.json": DOCUMENT, "thrust.csv": thrust_csv(sol)})


def _min_time(socp: dict[str, Any]) -> Any:
    from lgw.sim.mars.optimal import min_time

    try:
        return min_time(R0, V0, M0, **socp)
    except ParameterError as e:  # no feasible tf at all: the engine is to blame
        raise ParameterError("--thrust-max/--thrust-min/--isp",
                             [socp["thrust_max"], socp["thrust_min"], socp["isp"]],
                             f"admit no feasible flight time from Table I ({e.valid}): "
                             "raise --thrust-max or --isp, or lower --thrust-min") from None


def _refuse_tf(tf: float, sol: Any, socp: dict[str, Any]) -> None:
    """Raise the named error for an infeasible --tf, with the feasible interval."""
    from lgw.sim.mars.optimal import max_time

    if sol.status != "infeasible":
        raise ParameterError("--tf", tf, f"the conic solver failed on this problem (status "
                             f"{sol.status}); try another --n or --tf")
    mt = _min_time(socp)
    if tf < mt.tf_min:
        raise ParameterError("--tf", tf, f"infeasible with these thrust bounds: must be >= "
                             f"{mt.tf_min:.3f} s (shortest feasible tf, from --min-tf)")
    longest = max_time(R0, V0, M0, mt.tf_min, tf, **socp)
    raise ParameterError("--tf", tf, f"infeasible: must be <= {longest:.3f} s (the longest "
                         f"feasible flight time: beyond it the {M0 - M_DRY:g} kg of propellant "
                         f"run out; the shortest is {mt.tf_min:.3f} s)")


def plan(opts: Options, system: Any) -> OptimalJob:
    socp = dict(thrust_max=opts.thrust_max, limit=opts.limit,
                thrust_min=opts.thrust_min or None, n=opts.n, isp=opts.isp)
    tf = None if opts.min_tf else (TF_DEFAULT if opts.tf is None else opts.tf)
    return OptimalJob(tf, socp, opts.replay, opts.drag if opts.replay else "none")


def thrust_csv(sol: Any) -> str:
    """The force held on each step: t_start_s, t_end_s, Fx_N, Fy_N, Fz_N, norm_N."""
    rows = ["t_start_s,t_end_s,Fx_N,Fy_N,Fz_N,norm_N"]
    for k in range(sol.n):
        f = sol.F[k]
        rows.append(f"{sol.t[k]:.6f},{sol.t[k + 1]:.6f},{f[0]:.3f},{f[1]:.3f},{f[2]:.3f},"
                    f"{np.linalg.norm(f):.3f}")
    return "\n".join(rows) + "\n"


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


def _render(con: Any, sol: Any, mt: Any, reps: list[dict[str, Any]]) -> None:
    def e(s: str) -> None:
        con.print(s, markup=False, highlight=False)

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
