"""Seed 000's claims as ``lgw verify`` checks them (the shared machinery: ``lgw.tuning.verifying``).

Two kinds of evidence per claim:

* **simulation** (``judge``): batches of initial states flown by
  ``lgw.sim.mars.batch.simulate_batch`` (corrected law, no thrust limit, no drag: the plant of
  the bounds).  A case RK4 cannot carry (nonfinite, or a step over the s1 = 0 singularity of
  the command) is re-flown on the adaptive dopri5 path (max_step = dt) for the time claims;
  the band claims need a recorded trajectory, which dopri5 does not record, so such cases are
  excluded there, counted and shown.  The re-check of a violation (``fine``) flies the case
  alone at dt/2.
* **search** (``search``): the falsification engine (``lgw.theory.falsify``) on the exact
  reduced per-axis loop (``lgw.theory.mars.searches``) with the gain set fixed, minimising the
  margin over the initial states: over (r_i(0), v_i(0)) in each box of the envelope (s1 = r,
  s2 of (21)), or with ``--domain whole`` over the surfaces s1(0), s2(0) of either sign and
  magnitudes 1e-3 .. 1e9 (where the landing time approaches T2* + T1*).  A witness is shrunk
  and re-checked by a second integrator (tight LSODA or Radau) before it refutes.

Tolerances come from the integrator, never from a fudge factor: an event is located to within
one step dt (times), and an explicit RK4 step leaves a chattering floor on s2 of about
0.85 dt^1.5 m/s (docs/sim.md, ``benchmarks/bench_sim.py --floor``: 9.0e-3 m/s at dt = 0.05 s);
at the edge of a band one step can overshoot it by one step's increment of s2, so the band
tolerance of s2 is tol2 = S2_FLOOR_COEF dt^1.5 + inc(c), inc(c) = dt (alpha1 c^g1 + alpha2 c^g2
+ a_max) the most one step of s2' of (25) can move at |s2| = c, c = band + floor + inc(band +
floor) (where RK4's stages can be); that of s1 is the growth of the (31) band when its eta, the
s2 band, grows by tol2, plus the s1 floor (1.4e-4 m at dt = 0.05 s, fitted as 0.22 dt^2.46).

Note: the simulator's ``disturbance="worst"`` is a_p = -a_max sgn(s2), which helps s2 to 0; the
search uses a_p = +a_max sgn(s2), the disturbance that keeps |s2| largest (docs/verify.md).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
from lgw.sim.mars.batch import simulate_batch
from lgw.theory.errors import ParameterError
from lgw.theory.evidence import Search, Witness
from lgw.theory.falsify import Budget, Dim, Problem, falsify
from lgw.theory.mars import searches as S
from lgw.theory.mars.bounds import axis_bounds, landing_time_bound, neighborhood, reaching_time
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.mss import surfaces_numeric
from lgw.theory.mars.parameters import (
    M0,  # Table I mass (the bounds do not depend on it: the law divides it out)
)
from lgw.theory.symbolic import np_sig
from lgw.tuning.mars.cmd_verify import CLAIMS, EXTRAS, VARIABLES
from lgw.tuning.verifying import (
    Context,
    Envelope,
    Judged,
    cert_list,
    cert_number,
)

__all__ = ["CLAIMS", "EXTRAS", "VARIABLES", "judge", "search"]

AXES = ("x", "y", "z")
BATCH = (1, 3)  # states per Hypothesis example (one batched simulation)
RECHECK = "the case flown alone at dt/2 (RK4; dopri5 where RK4 cannot carry it)"
# Measured chattering floors (docs/sim.md "Chattering floor and eps", Table I, RK4):
# max |s2| = 9.0e-3 m/s at dt = 0.05 s, fitted as 0.85 dt^1.5 over dt in [0.01, 0.2];
# max |s1| = 2.6e-6, 1.4e-4, 7.5e-4, 4.1e-3 m at dt = 0.01, 0.05, 0.1, 0.2 s: 0.22 dt^2.46
# (log-log fit through the end points; reproduces 1.35e-4 at 0.05 s).
S2_FLOOR_COEF = 0.85
S1_FLOOR_COEF = 0.22
S1_FLOOR_EXP = 2.46
NO_INTEGRATOR = "neither RK4 nor dopri5 carried it (nonfinite or step limit)"
NO_RECORD = "RK4 stepped over s1 = 0 and the band check needs a recorded trajectory"
# Search budgets per profile (per box, axis and problem: 1 or 2 free coordinates).
BUDGETS = {"ci": Budget(popsize=10, maxiter=8, local_evals=40, seed=0),
           "thorough": Budget(popsize=20, maxiter=30, local_evals=200, seed=0)}
# The whole domain the simulator carries (--domain whole): magnitudes, either sign.
WHOLE_R = (1e-6, 1e5)  # m
WHOLE_V = (1e-6, 1e3)  # m/s
BOUNDED_TABLES = ("bounded", "bounded-sat")


# --- what the gains file gives -------------------------------------------------------------

def _law_table(g: Gains) -> str | None:
    return next((t for t in BOUNDED_TABLES if t in (g.extra or {})), None)


def not_applicable(g: Gains, cert: Mapping[str, Any] | None, settings: Mapping[str, Any]
                   ) -> dict[str, str]:
    """Claims whose inputs the gain set does not give, and why."""
    law = _law_table(g)
    if law is not None:
        why = (f"the file is a gain set of the [{law}] law (lgw tune mars --law {law}): seed "
               "000's claims are about the corrected law (25), and this file's [gains] table is "
               "only the loader's placeholder")
        return dict.fromkeys(CLAIMS, why)
    if g.disturbance is None:
        why = ("the gains file has no [disturbance] table (a_max, theta1, theta2), and the "
               "practical bounds (39)-(45) are functions of it")
        return {"s2-39-40": why, "s1-31-45": why}
    return {}


def promises(g: Gains, cert: Mapping[str, Any] | None, shown: str
             ) -> dict[str, dict[str, Any]]:
    """The bounds a tuned file's [certificate] promises, as caps on the claims' bounds (a
    promise tighter than the derived bound is what is checked).  Every value read is checked
    by name; the envelope is read by ``default_envelope``."""
    if cert is None or _law_table(g) is not None:
        return {}
    _envelope_boxes(cert, shown)  # a malformed envelope is an error before any work
    out = {}
    for key, claim, disturbed in (("landing_time_bound", "landing-T2+T1", False),
                                  ("landing_time_bound_disturbed", "s1-31-45", True)):
        v = cert_number(cert, key, shown, "a finite number > 0 (s)")
        if v is None or (disturbed and g.disturbance is None):
            continue
        derived = landing_time_bound(g, disturbed)
        out[claim] = {"value": v, "derived": derived, "source": f"certificate.{key}",
                      "text": f"certificate.{key} = {v:.6g} s (derived: {derived:.6g} s)"}
    return out


def _envelope_boxes(cert: Mapping[str, Any], shown: str) -> list[tuple[list, list]] | None:
    env = cert.get("envelope")
    if env is None:
        return None
    if not isinstance(env, dict):
        raise ParameterError(f"--gains {shown} certificate.envelope", env, "must be a table")
    lo = cert_list(env, "boxes_lo", shown)
    hi = cert_list(env, "boxes_hi", shown)
    if lo is None and hi is None:
        return None
    if lo is None or hi is None or len(lo) != len(hi) or not lo:
        raise ParameterError(f"--gains {shown} certificate.envelope.boxes_lo/boxes_hi",
                             (lo, hi), "must be two lists of the same number of boxes")
    out = []
    for i, (a, b) in enumerate(zip(lo, hi, strict=True)):
        for nm, row in (("boxes_lo", a), ("boxes_hi", b)):
            ok = isinstance(row, list) and len(row) >= 6 and all(
                isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)
                for x in row[:6])
            if not ok:
                raise ParameterError(f"--gains {shown} certificate.envelope.{nm}[{i}]", row,
                                     "must be a list of finite numbers rx, ry, rz, vx, vy, vz"
                                     " (m, m/s), m0")
        out.append(([float(x) for x in a[:6]], [float(x) for x in b[:6]]))
    return out


def default_envelope(g: Gains | None, cert: Mapping[str, Any] | None) -> Envelope:
    """A tuned file's certificate envelope (what its gains were designed for), else seed 000's
    Table III box and Table II dispersion (mean +- 4 sigma), as ``lgw tune mars`` designs for."""
    names = tuple(v.name for v in VARIABLES)
    boxes = _envelope_boxes(cert, "") if cert is not None else None
    if boxes:
        name = cert["envelope"].get("name", "certificate envelope")
        return Envelope(f"{name} (the gains file's certificate)", names,
                        tuple((tuple(a), tuple(b)) for a, b in boxes),
                        source="certificate.envelope")
    from lgw.tuning.mars.design import envelope_from_name

    env = envelope_from_name("table3+table2")
    return Envelope("table3+table2", names,
                    tuple((tuple(float(x) for x in lo[:6]), tuple(float(x) for x in hi[:6]))
                          for lo, hi in env.boxes), source=env.note or "seed 000")


def whole_domain() -> Envelope:
    lo = (WHOLE_R[0],) * 3 + (WHOLE_V[0],) * 3
    hi = (WHOLE_R[1],) * 3 + (WHOLE_V[1],) * 3
    return Envelope("whole domain", tuple(v.name for v in VARIABLES), ((lo, hi),),
                    scales=("signed-log",) * 6,
                    source="magnitudes the simulator carries, either sign")


def gains_text(g: Gains, axis: str | None) -> str:
    a = g.axis(AXES.index(axis) if axis in AXES else 0)
    txt = ", ".join(f"{k} = {v:.6g}" for k, v in a.items())
    if g.disturbance is not None:
        d = g.disturbance
        txt += f"; a_max = {d.a_max:g}, theta1 = {d.theta1:g}, theta2 = {d.theta2:g}"
    return (f"axis {axis}: " if axis else "") + txt


# --- simulation --------------------------------------------------------------------------------

def s2_floor(dt: float) -> float:
    return S2_FLOOR_COEF * dt**1.5


def s1_floor(dt: float) -> float:
    return S1_FLOOR_COEF * dt**S1_FLOOR_EXP


def surface2(r: np.ndarray, v: np.ndarray, g: Gains) -> np.ndarray:
    """s2 of seed 000 (21), per axis (last dimension 3), from the SymPy surface
    (``lgw.theory.mars.mss.surfaces_numeric``)."""
    return surfaces_numeric()[1](r, v, g.beta1, g.beta2, g.q1, g.q2)


def on_surface2(r0: np.ndarray, g: Gains) -> np.ndarray:
    """The velocity that puts the state on s2 = 0 (21): then s1 obeys (16) alone."""
    return -(g.beta1 * np_sig(r0, g.q1) + g.beta2 * np_sig(r0, g.q2))


def unresolved(r: np.ndarray, v: np.ndarray, g: Gains, a_max: float, dt: float) -> np.ndarray:
    """(N,) cases with a step the integrator did not resolve: for the corrected law s2 obeys
    s2' = -alpha1 sig(s2,g1) - alpha2 sig(s2,g2) + a_p exactly (claim V2dot-corrected), so one
    step can move s2 by at most dt (alpha1|s2|^g1 + alpha2|s2|^g2 + a_max) (|s2| at the larger
    end) plus twice the chattering floor.  Measured with the default gains, dt = 0.05: resolved
    steps reach <= 0.9 of this, unresolved ones 20x to 350x.  A larger jump is RK4 stepping
    over the s1 = 0 singularity of the command with v != 0 (|s1|^(q1-1) v), not the loop."""
    s2 = surface2(r, v, g)
    a = np.maximum(np.abs(s2[:, 1:]), np.abs(s2[:, :-1]))
    rate = g.alpha1 * a**g.g1 + g.alpha2 * a**g.g2 + a_max
    jump = np.abs(np.diff(s2, axis=1))
    bad = jump > dt * rate + 2 * s2_floor(dt)
    return np.any(bad & np.isfinite(jump), axis=(1, 2))


def _bounds(g: Gains) -> dict[str, np.ndarray]:
    b = axis_bounds(g)
    return {k: np.array([b[a][k] for a in AXES]) for k in b["x"]}


def _horizon(ctx: Context, pairs: Sequence[tuple[str, np.ndarray]], dt: float,
             stretch: float = 1.0) -> float:
    """Simulated time: the largest bound (scaled up by --scale where it grows) x ``stretch``
    plus two steps, so a case slower than its bound is seen as such."""
    return float(max(np.max(b) * max(ctx.factors.get(c, 1.0), 1.0) for c, b in pairs)
                 * stretch + 2 * dt)


def _fly(g: Gains, r0, v0, dt: float, eps: float, t_max: float, *, seed: int = 0,
         case_offset: int = 0, disturbance: str = "none", record: bool = False,
         method: str = "rk4"):
    a_max = g.disturbance.a_max if g.disturbance is not None else 0.0
    kw = {"method": "dopri5", "max_step": dt} if method == "dopri5" else {"record": record}
    return simulate_batch(r0, v0, np.full(len(r0), M0), g, drag="none", dt=dt, eps=eps,
                          t_max=t_max, stop="t_max", disturbance=disturbance,
                          dist_amplitude=a_max, seed=seed, case_offset=case_offset,
                          blowup_accel=np.inf, **kw)


def _times(g: Gains, r0, v0, dt: float, eps: float, t_max: float):
    """Band times without disturbance: RK4, and for every case RK4 cannot carry (nonfinite, or
    a step over the s1 = 0 singularity) the adaptive dopri5 path with max_step = dt (its nodes
    are then as close as RK4's, so the one-step tolerance holds).
    Returns (t_s1, t_s2, t_s1_last_exit, y_end, carried (N,), by dopri5 (N,))."""
    res = _fly(g, r0, v0, dt, eps, t_max, record=True)
    with np.errstate(all="ignore"):
        bad = unresolved(res.trajectory["r"], res.trajectory["v"], g, 0.0, dt)
    good = ~res.nonfinite & ~bad
    out = [res.t_s1.copy(), res.t_s2.copy(), res.t_s1_last_exit.copy(), res.y_end.copy()]
    adaptive = np.zeros(len(r0), bool)
    if not good.all():
        idx = np.flatnonzero(~good)
        ad = _fly(g, r0[idx], v0[idx], dt, eps, t_max, method="dopri5")
        for arr, new in zip(out, (ad.t_s1, ad.t_s2, ad.t_s1_last_exit, ad.y_end), strict=True):
            arr[idx] = new
        carried = ~ad.nonfinite & ~ad.step_limit
        good[idx] = carried
        adaptive[idx] = carried
    return (*out, good, adaptive)


def _band(a: np.ndarray, lim: np.ndarray, t: np.ndarray, start: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """|s| (N, S, 3) against the band ``lim`` (3,) from node ``start`` (N, 3) on: first entry
    index (-1: never), entry time (inf: never), whether it left the band after entering, and
    (time, |s|) of that first exit."""
    idx = np.arange(a.shape[1])[None, :, None]
    inside = (a <= lim[None, None, :]) & (idx >= start[:, None, :])
    has = inside.any(axis=1)
    first = np.where(has, inside.argmax(axis=1), -1)
    t_in = np.where(has, t[np.maximum(first, 0)], np.inf)
    out = (a > lim[None, None, :]) & (idx > first[:, None, :]) & has[:, None, :]
    left = out.any(axis=1)
    k = out.argmax(axis=1)
    return first, t_in, left, np.stack([t[k], np.take_along_axis(a, k[:, None, :], 1)[:, 0]])


def _excluded_all(g: Gains, n: int) -> list[str | None]:
    if not 0.5 < g.q1 < 1.0:
        return [f"q1 = {g.q1:g} is outside (0.5, 1): the simulated corrected law's "
                "|s1|^(2 q1 - 1) term is singular (the search still checks the bounds)"] * n
    return [None] * n


def judge(ctx: Context, group: str, X: np.ndarray,
          extras: Sequence[Mapping[str, Any]] | None = None) -> dict[str, Judged]:
    """Fly the initial states ``X`` (N, 6: r, v) for the claims of ``group``."""
    g: Gains = ctx.gains
    dt = float(ctx.settings["dt"]) / (2.0 if ctx.fine else 1.0)
    eps = float(ctx.settings["eps"])
    r0, v0 = np.array(X[:, :3], float), np.array(X[:, 3:6], float)
    n = len(X)
    b = _bounds(g)
    skip = _excluded_all(g, n)
    if any(s is not None for s in skip):  # nothing the simulator can fly
        z = np.zeros((n, 3))
        bound = {"reaching-16": "T1_exact", "T2-26": "T2_exact",
                 "landing-T2+T1": "landing_time_bound", "s2-39-40": "T2_practical_exact",
                 "s1-31-45": "landing_time_bound_disturbed"}
        return {c: Judged(X, z, np.broadcast_to(b.get(bound[c], np.ones(3)), (n, 3)),
                          np.zeros((n, 3), bool), skip, dt)
                for c in CLAIMS if CLAIMS[c].group == group}
    if group == "reaching":
        vs = on_surface2(r0, g)
        t1 = b["T1_exact"]
        t_s1, _, _, _, ok, ad = _times(g, r0, vs, dt, eps,
                                       _horizon(ctx, [("reaching-16", t1)], dt))
        t_ex = reaching_time(r0, g.beta1, g.beta2, g.q1, g.q2)  # exact T(s0) <= T1_exact
        assert np.all(t_ex <= t1 * (1 + 1e-9)) and np.all(t1 <= b["T1_polyakov"] * (1 + 1e-9))
        obs = np.nan_to_num(t_s1, nan=np.inf) - dt  # entry located within one step
        return {"reaching-16": Judged(np.column_stack([r0, vs]), obs,
                                      np.broadcast_to(t1, (n, 3)), np.abs(r0) > eps,
                                      [None if k else NO_INTEGRATOR for k in ok], dt,
                                      fallback=ad)}
    if group == "undisturbed":
        t2, tl = b["T2_exact"], b["landing_time_bound"]
        t_s1, t_s2, t_exit, y_end, ok, ad = _times(
            g, r0, v0, dt, eps, _horizon(ctx, [("T2-26", t2), ("landing-T2+T1", tl)], dt))
        s2_0 = np.abs(surface2(r0, v0, g))
        excl = [None if k else NO_INTEGRATOR for k in ok]
        obs2 = np.nan_to_num(t_s2, nan=np.inf) - dt
        obs1 = np.nan_to_num(t_s1, nan=np.inf) - dt
        # never leaves: a last exit after entry counts as never having entered for good
        obs1 = np.where(np.isfinite(t_exit), np.maximum(obs1, t_exit - dt), obs1)
        # at the end (>= the bound): |s1_i| <= eps and, by (21) with |s1|, |s2| <= eps,
        # |v_i| <= eps' = eps + beta1 eps^q1 + beta2 eps^q2 (else it left and never came back)
        eps_v = eps + g.beta1 * eps**g.q1 + g.beta2 * eps**g.q2
        outside = (np.abs(y_end[:, :3]) > eps) | (np.abs(y_end[:, 3:6]) > eps_v)
        obs1 = np.where(outside, np.inf, obs1)
        return {"T2-26": Judged(X, obs2, np.broadcast_to(t2, (n, 3)), s2_0 > eps, excl, dt,
                                fallback=ad),
                "landing-T2+T1": Judged(X, obs1, np.broadcast_to(tl, (n, 3)),
                                        (np.abs(r0) > eps) | (s2_0 > eps), excl, dt,
                                        fallback=ad)}
    if group == "disturbed":
        return _disturbed(ctx, g, X, r0, v0, dt, b, extras)
    raise ValueError(f"unknown group {group}")


def _disturbed(ctx: Context, g: Gains, X, r0, v0, dt: float, b: dict[str, np.ndarray],
               extras) -> dict[str, Judged]:
    """(39)/(40) and (31)/(45) under the worst-case and a random disturbance (one flight per
    kind, or the kind of the witness)."""
    d = g.disturbance
    eps = float(ctx.settings["eps"])
    t2p, t1p = b["T2_practical_exact"], b["landing_time_bound_disturbed"]

    def step(c):  # the most one step of s2' of (25) can move s2 at |s2| = c
        return dt * (g.alpha1 * c**g.g1 + g.alpha2 * c**g.g2 + d.a_max)

    c = b["s2_bound"] + s2_floor(dt)
    lim2 = b["s2_bound"] + s2_floor(dt) + step(c + step(c))
    # s1's band (31) is (44) with eta = the s2 band; with s2 up to lim2 the same formula gives
    # the s1 band the integrator can hold, plus the s1 floor
    lim1 = neighborhood(lim2, g.beta1, g.beta2, g.q1, g.q2, d.theta2) + s1_floor(dt)
    t_end = _horizon(ctx, [("s2-39-40", t2p), ("s1-31-45", t1p)], dt, stretch=1.1)
    w = extras[0] if extras else None
    if w is not None and w.get("disturbance"):
        kinds = [(w["disturbance"], int(w.get("noise_seed", ctx.seed)),
                  int(w.get("noise_case", 0)))]
    else:
        kinds = [("worst", ctx.seed, 0), ("random", ctx.seed, 0)]
    parts: dict[str, list[Judged]] = {"s2-39-40": [], "s1-31-45": []}
    for kind, seed, offset in kinds:
        res = _fly(g, r0, v0, dt, eps, t_end, seed=seed, case_offset=offset,
                   disturbance=kind, record=True)
        tr = res.trajectory
        t, r, v = tr["t"], tr["r"], tr["v"]
        with np.errstate(all="ignore"):
            bad = unresolved(r, v, g, d.a_max, dt)
            s2 = np.nan_to_num(np.abs(surface2(r, v, g)), nan=np.inf)
        excl = [None if k else NO_RECORD for k in (~res.nonfinite & ~bad)]
        ext = [{"disturbance": kind} if kind == "worst" else
               {"disturbance": kind, "noise_seed": seed, "noise_case": offset + i}
               for i in range(len(X))]
        zero = np.zeros((len(X), 3), int)
        k2, t_in2, left2, ex2 = _band(s2, lim2, t, zero)
        a1 = np.nan_to_num(np.abs(r), nan=np.inf)
        start = np.where(k2 >= 0, k2, r.shape[1])
        k1, t_in1, left1, ex1 = _band(a1, lim1, t, start)
        s1_at = np.take_along_axis(a1, np.minimum(start, r.shape[1] - 1)[:, None, :], 1)[:, 0]
        for claim, t_in, left, ex, lim, inf_, what in (
                ("s2-39-40", t_in2, left2, ex2, lim2, s2[:, 0] > lim2, "|s2_i|"),
                ("s1-31-45", t_in1, left1, ex1, lim1, (s1_at > lim1) | (k2 < 0), "|r_i|")):
            obs = np.where(left, np.inf, t_in - dt)  # node-sampled entry: within one step
            notes = np.full(obs.shape, None, object)
            for i, a in zip(*np.nonzero(left), strict=True):
                notes[i, a] = (f"{what} entered its band at t = {t_in[i, a]:.4g} s and left it "
                               f"at t = {ex[0][i, a]:.4g} s ({what} = {ex[1][i, a]:.4g} > band + "
                               f"tolerance {lim[a]:.4g}): the band is not invariant")
            parts[claim].append(Judged(X, obs, np.broadcast_to(
                t2p if claim == "s2-39-40" else t1p, obs.shape), inf_, excl, dt, extras=ext,
                notes=notes))
    return {c: _concat(js) for c, js in parts.items()}


def _concat(js: list[Judged]) -> Judged:
    if len(js) == 1:
        return js[0]
    cat = np.concatenate
    return Judged(cat([j.states for j in js]), cat([j.observed for j in js]),
                  cat([np.asarray(j.bound) for j in js]), cat([j.informative for j in js]),
                  [e for j in js for e in j.excluded], js[0].tolerance,
                  extras=[e for j in js for e in j.extras], notes=cat([j.notes for j in js]))


def judge_states(g: Gains, r0: np.ndarray, v0: np.ndarray, claims: Sequence[str], *,
                 dt: float = 0.05, eps: float = 0.05, seed: int = 0) -> dict[str, Judged]:
    """The judged cases of ``claims`` for states (r0, v0), as ``lgw verify mars`` flies them
    (for property tests of the simulator against the bounds)."""
    ctx = Context(g, {"dt": dt, "eps": eps}, {}, seed)
    X = np.column_stack([r0, v0])
    out: dict[str, Judged] = {}
    for group in dict.fromkeys(CLAIMS[c].group for c in claims):
        out.update({c: j for c, j in judge(ctx, group, X).items() if c in claims})
    return out


# --- search: the engine on the reduced per-axis loop, this gain set ------------------------

def _fix(pr: Problem, values: Mapping[str, float]) -> Problem:
    return replace(pr, dims=tuple(d for d in pr.dims if d.name not in values),
                   fixed={**pr.fixed, **values})


def claim_problems(claim: str, g: Gains, axis: int, scale: float = 1.0,
                   cap: float = math.inf) -> list[Problem]:
    """The search problems of a claim for axis ``axis`` of the gain set on the whole domain
    (gains fixed; the initial surfaces free).  ``scale`` multiplies the claim's bound, ``cap``
    (a certificate's promise) bounds it."""
    vals: dict[str, float] = dict(g.axis(axis))
    if g.disturbance is not None:
        d = g.disturbance
        vals.update(a_max=d.a_max, theta1=d.theta1, theta2=d.theta2)
    if claim == "reaching-16":
        prs = [S._reaching_problem("T1*", "T1_exact", "s1", scale)]
    elif claim == "T2-26":
        prs = [S._reaching_problem("T2*", "T2_exact", "s2", scale)]
    elif claim == "landing-T2+T1":
        prs = [S._landing_problem("T1* + T2*", lambda p: min(S._sum_exact(p) * scale, cap))]
    elif claim == "s2-39-40":
        prs = [S._s2_band_problem(), S._t2_practical_problem("T2_practical_exact", scale)]
    elif claim == "s1-31-45":
        prs = [S._s1_band_problem(),
               S._disturbed_landing_problem("(40) + (45) exact",
                                            lambda p: min(S._t3_sum(p) * scale, cap))]
    else:
        raise ParameterError("claim", claim, f"one of {', '.join(CLAIMS)}")
    return [_fix(p, vals) for p in prs]


def on_box(pr: Problem, ax: Mapping[str, float], r_box: tuple[float, float],
           v_box: tuple[float, float], reaching: bool = False) -> Problem:
    """``pr`` over the initial states (r_i(0), v_i(0)) of one box of the envelope instead of
    its surface coordinates: s1 = r, s2 = v + beta1 sig(r)^q1 + beta2 sig(r)^q2 (21).  The
    reaching law (16) alone (``reaching``) starts on s2 = 0, so only r is searched for it."""
    orig = {d.name: d for d in pr.dims}
    if not orig:
        return pr
    dims, fixed = [], {}
    for nm, (lo, hi) in (("r0", r_box), ("v0", v_box)):
        if nm == "v0" and reaching:
            continue
        if lo < hi:
            dims.append(Dim(nm, lo, hi))
        else:
            fixed[nm] = lo

    def surfaces(p: Mapping[str, float]) -> dict[str, float] | None:
        r = float(p["r0"])
        s2 = 0.0 if reaching else float(p["v0"]) + float(
            ax["beta1"] * np_sig(r, ax["q1"]) + ax["beta2"] * np_sig(r, ax["q2"]))
        q = {k: v for k, v in p.items() if k not in ("r0", "v0")}
        for nm, d in orig.items():
            x = r if nm in ("s1_0", "s1_e") or (nm == "s0" and reaching) else s2
            if d.scale == "log":  # a magnitude: nothing to reach from 0
                if x == 0.0:
                    return None
                x = abs(x)
            q[nm] = x
        return q

    def guard(fn):
        def h(p):
            q = surfaces(p)
            return 1.0 if q is None else fn(q)
        return h

    valid = None if pr.valid is None else (lambda p: (q := surfaces(p)) is None or pr.valid(q))
    return replace(pr, dims=tuple(dims), fixed={**pr.fixed, **fixed}, margin=guard(pr.margin),
                   recheck=guard(pr.recheck), valid=valid)


def _evaluate_once(pr: Problem) -> Search:
    """A problem with nothing left to search (the sup over states is a closed form at this
    gain set, e.g. the equilibrium band): one exact evaluation, re-checked if negative."""
    p = pr.point([])
    m = float(pr.margin(p))
    w = None
    if m < 0:
        w = Witness(point=p, margin=m, method=pr.route, rechecked_margin=float(pr.recheck(p)),
                    recheck_method=pr.recheck_method)
    return Search(domain=pr.domain(), method=f"exact evaluation ({pr.route})", evaluations=1,
                  best_margin=m, best_point=p, counter=w, relative=pr.relative)


def search(ctx: Context, claim: str, envelope: Envelope | None, profile: str
           ) -> list[dict[str, Any]]:
    """Falsification searches of ``claim`` for this gain set, per axis and box of the
    envelope (``None``: the whole domain, per axis with distinct gains)."""
    g: Gains = ctx.gains
    budget = replace(BUDGETS[profile], seed=ctx.seed)
    scale = ctx.factors.get(claim, 1.0)
    out, seen = [], []
    for axis in range(3):
        ax = g.axis(axis)
        boxes = [None] if envelope is None else envelope.boxes
        for bi, box in enumerate(boxes):
            key = (ax, None if box is None else (box[0][axis], box[1][axis], box[0][axis + 3],
                                                   box[1][axis + 3]))
            if key in seen:
                continue
            seen.append(key)
            for pr in claim_problems(claim, g, axis, scale, ctx.caps.get(claim, math.inf)):
                if box is not None:
                    pr = on_box(pr, ax, (box[0][axis], box[1][axis]),
                                (box[0][axis + 3], box[1][axis + 3]), claim == "reaching-16")
                s = falsify(pr, budget) if pr.dims else _evaluate_once(pr)
                rec = {"axis": AXES[axis], "problem": pr.name, "route": pr.route,
                       "domain_name": "whole domain" if box is None else f"box {bi + 1}",
                       **s.to_dict(), "status": s.status}
                if s.status == "refuted":
                    rec["witness"] = _witness(g, claim, axis, s, box)
                out.append(rec)
    return out


def _witness(g: Gains, claim: str, axis: int, s: Search, box) -> dict[str, Any]:
    """The search witness as an initial state of the 3-axis simulator: the searched axis at
    the witness, the other axes at the box centre (the whole domain: the same on every axis)."""
    p = dict(s.counter.point)
    ax = g.axis(axis)
    if "r0" in p or box is not None:
        r = float(p.get("r0", box[0][axis]))
        v = float(p.get("v0", box[0][axis + 3]))
        row = [(lo + hi) / 2 or hi for lo, hi in zip(box[0], box[1], strict=True)]
        row[axis], row[axis + 3] = r, v
    else:
        s1 = float(p.get("s1_0", p.get("s0", p.get("s1_e", 1.0))))
        s2 = float(p.get("s2_0", 0.0 if claim == "reaching-16" else p.get("s0", 0.0)))
        if claim == "T2-26":
            s1, s2 = 1.0, float(p["s0"])
        v = s2 - (ax["beta1"] * np.sign(s1) * abs(s1) ** ax["q1"]
                  + ax["beta2"] * np.sign(s1) * abs(s1) ** ax["q2"])
        row = [s1] * 3 + [float(v)] * 3
    extra = {"disturbance": "worst"} if CLAIMS[claim].group == "disturbed" else {}
    return {"source": "search (reduced per-axis loop)", "axis": AXES[axis],
            "point": {k: float(x) for k, x in p.items()}, "margin": s.counter.margin,
            "rechecked_margin": s.counter.rechecked_margin,
            "recheck_method": s.counter.recheck_method, "confirmed": s.counter.confirmed,
            "row": row, "extra": extra}
