"""Seed 000's numbers checked for convergence (``lgw.sim.convergence``), and RK4 outcomes
refined until they do not depend on the step.

``check(res, fly)``: the cases of a run (all, or ``CHECK_CASES`` evenly spread ones of a larger
campaign) flown again finer (RK4 at dt/2, dopri5 at rtol/10 and atol/10, the reference at a
tenth of its tolerances on a few cases), every number ``QUOTED`` compared within its
tolerance.  ``refine(res, half, fly)``: RK4 cases whose outcome changes at dt/2 flown at dt/4,
dt/8, ... until two successive steps agree; they replace the run's cases, marked by the step
they were flown at (``info["refined"]``, the case records' ``refined_dt``).

``flier(r0, v0, m0, gains, sim)`` builds ``fly(idx, changes)``: cases ``idx`` of a run with
``simulate_batch`` keywords ``sim`` flown with ``changes`` (the same per-case disturbance: the
campaign's random draws are taken by case number, not position).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from lgw.sim.convergence import (
    CHECK_CASES,
    ConvergenceRecord,
    Refinement,
    Tol,
    check_indices,
    compare_cases,
    refine_outcomes,
    refinement,
)
from lgw.sim.mars.batch import ARRAY_FIELDS, BatchResult, simulate_batch
from lgw.sim.results import OUTCOMES

# The numbers ``lgw simulate mars`` prints per case (its table and summary), with their
# tolerance: 1 % or the quantity's resolution (1 ms, 1 mm, 1 mm/s, 10 g of propellant, 1 N,
# 10 ms of saturation)
QUOTED = {
    "outcome_time": Tol(atol=1e-3), "landing_time": Tol(atol=1e-3), "fuel": Tol(atol=0.01),
    "landing_error": Tol(atol=1e-3), "landing_speed": Tol(atol=1e-3),
    # time saturated: the tables print it to 0.01 s; a short saturated burst is located to a
    # few ms by the linear margin between nodes (0.243 against 0.239 s at dt/2, Table III)
    "peak_thrust": Tol(atol=1.0), "time_saturated": Tol(atol=0.01),
    "min_altitude": Tol(atol=1e-3), "impact_speed": Tol(atol=1e-3),
    "t_s2": Tol(atol=1e-3),
}
REF_CHECK_CASES = 4  # the reference (seconds per case) is checked on at most this many
REF_TIGHTEN = 10.0

Fly = Callable[[np.ndarray, dict[str, Any]], BatchResult]


def flier(r0: np.ndarray, v0: np.ndarray, m0: np.ndarray, gains: Any, sim: dict[str, Any],
          reference: bool = False) -> Fly:
    """fly(idx, changes): cases idx flown with the keywords ``sim`` updated by ``changes``."""
    from lgw.sim.mars.disturbances import make_disturbance

    kw = dict(sim)
    kind = kw.get("disturbance", "none")
    full = make_disturbance(kind, len(r0), amplitude=kw.get("dist_amplitude"),
                            seed=kw.get("seed", 0))

    def fly(idx: np.ndarray, changes: dict[str, Any]) -> BatchResult:
        idx = np.asarray(idx, np.int64)
        spec = full.take(idx)
        args = {**kw, **changes}
        if reference:
            from lgw.sim.mars.reference import simulate_reference
            return simulate_reference(r0[idx], v0[idx], m0[idx], gains, dist_spec=spec,
                                      **args)
        return simulate_batch(r0[idx], v0[idx], m0[idx], gains, dist_spec=spec, **args)

    return fly


def records(res: BatchResult, idx: np.ndarray | None = None) -> list[dict[str, Any]]:
    """The quoted numbers of the cases ``idx`` (default all) of a run, one dict per case."""
    code, t = res.outcomes()
    idx = np.arange(len(res)) if idx is None else np.asarray(idx, np.int64)
    lerr = np.linalg.norm(res.r_land, axis=1)
    lspd = np.linalg.norm(res.v_land, axis=1)
    imp = res.impact_speed
    return [{"outcome": OUTCOMES[code[i]], "outcome_time": t[i],
             "landing_time": res.landing_time[i], "fuel": res.fuel[i],
             "landing_error": lerr[i], "landing_speed": lspd[i],
             "peak_thrust": res.peak_thrust[i], "time_saturated": res.time_saturated[i],
             "min_altitude": res.min_altitude[i], "impact_speed": imp[i],
             "t_s2": res.t_s2[i]} for i in idx]


def describe(res: BatchResult, changes: dict[str, Any] | None = None) -> str:
    """One line naming a run's integrator (with ``changes`` applied)."""
    ch = changes or {}
    integ = res.info.get("integrator", "")
    if integ.startswith("RK4"):
        return f"RK4 dt = {ch.get('dt', res.dt):g} s"
    if integ.startswith("Dormand"):
        rtol = ch.get("rtol")
        return ("dopri5" if rtol is None else
                f"dopri5 rtol = {rtol:g}, atol = {ch.get('atol'):g}")
    return integ.split(" max_step")[0] if not ch else \
        f"solve_ivp rtol = {ch.get('rtol'):g}, atol = {ch.get('atol'):g}"


def check(res: BatchResult, fly: Fly, *, method: str, rtol: float | None = None,
          atol: float | None = None, limit: int = CHECK_CASES
          ) -> tuple[ConvergenceRecord, BatchResult, np.ndarray]:
    """The convergence record of run ``res`` (method "rk4", "dopri5" or "reference"), the finer
    run and the indices of the cases it flew."""
    if method == "reference":
        from lgw.sim.mars.reference import REF_ATOL, REF_RTOL

        how = "tolerance tightened"
        changes = {"rtol": (rtol or REF_RTOL) / REF_TIGHTEN,
                   "atol": (atol or REF_ATOL) / REF_TIGHTEN}
        limit = min(limit, REF_CHECK_CASES)
        base = describe(res, {"rtol": rtol or REF_RTOL, "atol": atol or REF_ATOL})
    else:
        how, changes = refinement(method, dt=res.dt, rtol=rtol, atol=atol)
        base = describe(res, {"rtol": rtol, "atol": atol} if method == "dopri5" else None)
    idx = check_indices(len(res), limit)
    fine = fly(idx, changes)
    rec = compare_cases(records(res, idx), records(fine), QUOTED, how=how, base_label=base,
                        check_label=describe(res, changes), cases=idx.tolist(),
                        total=len(res))
    return rec, fine, idx


def refine(res: BatchResult, half: BatchResult, idx: np.ndarray, fly: Fly,
           record: ConvergenceRecord | None = None) -> tuple[BatchResult, Refinement]:
    """RK4 run ``res`` with the cases ``idx`` whose outcome differs in ``half`` (the same cases
    at dt/2) re-flown until their outcome settles (``lgw.sim.convergence.refine_outcomes``);
    those cases are replaced by their finest flight and ``info["refined_dt"]`` maps each to its
    step.  ``record`` (the check that found them) gets the refinement and the check of the
    refined flights (each flown again at half its step, every quoted number compared)."""
    idx = np.asarray(idx, np.int64)
    code = res.outcomes()[0][idx]
    code_half = half.outcomes()[0]

    def fly_at(cases: np.ndarray, h: float) -> tuple[np.ndarray, BatchResult]:
        r = fly(cases, {"dt": h})
        return r.outcomes()[0], r

    ref = refine_outcomes(fly_at, code, code_half, res.dt)
    res.info["refined"] = ref.to_dict()
    if not len(ref.cases):
        return res, ref
    # the cases' dt/2 flights, then each later flight over them
    cases = idx[ref.cases]
    final = _take(half, ref.cases)
    for pending, _h, r in ref.results:
        final = final.with_rows(pending, r)
    out = res.with_rows(cases, final)
    out.info.pop("replaced", None)
    out.info["refined"] = {**ref.to_dict(), "cases": cases[:50].tolist()}
    out.info["refined_dt"] = dict(zip(cases.tolist(), ref.dt.tolist(), strict=True))
    if record is not None:
        base, finer, order = [], [], []
        for h in np.unique(ref.dt):
            pos = np.flatnonzero(ref.dt == h)
            chk = fly(cases[pos], {"dt": h / 2})
            base += records(final, pos)
            finer += records(chk)
            order += cases[pos].tolist()
        sub = compare_cases(base, finer, QUOTED, how="step halving",
                            base_label="RK4 at each refined case's step",
                            check_label="half that step", cases=order, total=len(cases))
        settled = {int(c): (float(h) if ok else None)
                   for c, h, ok in zip(cases, ref.dt, ref.settled, strict=True)}
        record.with_refinement(settled, sub)
    return out, ref


def _take(res: BatchResult, idx: np.ndarray) -> BatchResult:
    kw = {k: getattr(res, k)[idx] for k in ARRAY_FIELDS}
    return BatchResult(eps=res.eps, dt=res.dt, r0=res.r0[idx], v0=res.v0[idx],
                       m0=res.m0[idx], info=dict(res.info), **kw)


