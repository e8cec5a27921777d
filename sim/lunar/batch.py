"""Batched simulation of seed 001's closed loop, and a tight ``solve_ivp`` reference.

STAND-IN: ``rk4_batch`` is a compact numpy-vectorised fixed-step RK4 over all cases, written
here until the shared numba integrator ``lgw.sim.integrate`` is available; replace it by that
integrator (the vector field ``closed_loop.field`` and the records stay).

Records per case: tracking errors, thrust and torque, time saturated, d0e, V2 and Vlambda along
the run, failure time, saturation entries/exits.  A case that leaves the model's domain
(non-finite state, quaternion norm drift above ``QUAT_NORM_TOL``, r below the lunar surface)
is flagged with the time and reason and frozen from then on, never dropped.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from lgw.sim.lunar.closed_loop import Context
from lgw.sim.lunar.closed_loop import field as cl_field
from lgw.theory.lunar import parameters as P
from scipy.integrate import solve_ivp


@dataclass
class BatchResult:
    t: np.ndarray  # (K,) record times
    X: np.ndarray  # (K, 30, N) states at the record times
    out: dict  # name -> (K, ...) signals at the record times
    flagged: list = field(default_factory=list)  # (case, time, reason)
    dt: float = 0.0

    @property
    def n_cases(self) -> int:
        return self.X.shape[2]


def _domain_check(t, X, alive, flagged):
    bad_nan = ~np.all(np.isfinite(X), axis=0)
    bad_q = np.abs(np.linalg.norm(X[12:16], axis=0) - 1.0) > P.QUAT_NORM_TOL
    bad_r = X[0] < P.R_MOON
    for reason, bad in (("non-finite state", bad_nan), ("quaternion norm drift", bad_q),
                        ("r below the lunar surface", bad_r)):
        for i in np.flatnonzero(bad & alive):
            flagged.append((int(i), float(t), reason))
            alive[i] = False


def rk4_batch(ctx: Context, X0: np.ndarray, record_every: int = 5) -> BatchResult:
    """Fixed-step RK4 (step ``ctx.opts.dt``) of all cases together on [0, t_end]."""
    o = ctx.opts
    t_end = ctx.tf if o.t_end is None else o.t_end
    n = int(round(t_end / o.dt))
    h = t_end / n
    X = X0.copy()
    alive = np.ones(X.shape[1], dtype=bool)
    flagged: list = []
    ts, Xs, outs = [], [], []

    def rec(t):
        _, out = cl_field(t, X, ctx, outputs=True)
        ts.append(t)
        Xs.append(X.copy())
        outs.append(out)

    for k in range(n):
        t = k * h
        if k % record_every == 0:
            rec(t)
        k1 = cl_field(t, X, ctx)
        k2 = cl_field(t + h / 2, X + h / 2 * k1, ctx)
        k3 = cl_field(t + h / 2, X + h / 2 * k2, ctx)
        k4 = cl_field(t + h, X + h * k3, ctx)
        Xn = X + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        X = np.where(alive, Xn, X)  # a flagged case is frozen where it left the domain
        with np.errstate(invalid="ignore"):
            _domain_check(t + h, X, alive, flagged)
    rec(n * h)
    out = {k: np.array([o_[k] for o_ in outs]) for k in outs[0]}
    return BatchResult(np.array(ts), np.array(Xs), out, flagged, h)


def solve_ivp_case(ctx: Context, x0: np.ndarray, t_eval: np.ndarray, rtol: float = 1e-10,
                   atol: float = 1e-10, method: str = "DOP853"):
    """A tight adaptive reference for one case (``ctx`` gains must be for one case)."""
    o = ctx.opts
    t_end = ctx.tf if o.t_end is None else o.t_end

    def f(t, x):
        return cl_field(t, x[:, None], ctx)[:, 0]

    return solve_ivp(f, (0.0, t_end), x0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)


def l2_norm(t: np.ndarray, sig: np.ndarray) -> np.ndarray:
    """sqrt(int_0^t |sig|^2) by the trapezoidal rule over the record times; sig (K, ..., N)."""
    s2 = sig ** 2
    while s2.ndim > 2:
        s2 = s2.sum(axis=1)
    return np.sqrt(np.trapezoid(s2, t, axis=0))


def events(res: BatchResult, key: str = "orbit_saturated") -> list[list[tuple[str, float]]]:
    """Entries and exits of a boolean signal per case: [("enter", t), ("exit", t), ...]."""
    s = res.out[key]
    ev = []
    for i in range(s.shape[1]):
        d = np.diff(s[:, i].astype(int))
        e = [("enter", float(res.t[j + 1])) for j in np.flatnonzero(d == 1)]
        e += [("exit", float(res.t[j + 1])) for j in np.flatnonzero(d == -1)]
        if s[0, i]:
            e.insert(0, ("enter", float(res.t[0])))
        ev.append(sorted(e, key=lambda x: x[1]))
    return ev
