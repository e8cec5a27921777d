"""Batched simulation of seed 001's closed loop, and a tight ``solve_ivp`` reference.

``rk4_batch`` (and ``simulate`` with dopri5) runs the compiled kernel ``lgw.sim.lunar.kernel`` on
the shared integrator ``lgw.sim.integrate``: the law generated from the SymPy expressions, the
plant and actuators of ``closed_loop.field`` in scalar form, in parallel over cases.
``rk4_numpy`` is the earlier numpy-vectorised fixed-step RK4 of ``closed_loop.field`` itself; it
is kept as the independent route the tests and the benchmark compare the kernel against.

Records per case: tracking errors, thrust and torque, time saturated, d0e, V2 and Vlambda along
the run, failure time, saturation entries/exits, and one outcome with its time
(``lgw.sim.lunar.outcomes``).  A case that leaves the model's domain (non-finite state,
quaternion norm drift above ``QUAT_NORM_TOL``, r below the lunar surface, mass at the dry mass)
stops there with that outcome; its records are frozen at its last accepted node, never dropped.
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
    cases: dict = field(default_factory=dict)  # per-case results of the kernel (N,) arrays

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


def rk4_numpy(ctx: Context, X0: np.ndarray, record_every: int = 5) -> BatchResult:
    """Fixed-step numpy RK4 (step ``ctx.opts.dt``) of ``closed_loop.field``, all cases in one
    array, on [0, t_end]: the cross-check of the compiled kernel."""
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


def failure_centres(ctx: Context, t_fail: np.ndarray | float | None = None) -> np.ndarray:
    """t_c of the kernel per case: the atan's centre 2 t_fail (default t_f, seed 001 (26):
    atan(2t - t_f)) or the step time t_fail (default t_f / 2)."""
    o = ctx.opts
    tf_ = t_fail if t_fail is not None else o.t_fail
    if o.failure == "atan":
        return np.asarray(ctx.ref.tf if tf_ is None else 2.0 * np.asarray(tf_, float), float)
    return np.asarray(ctx.ref.tf / 2 if tf_ is None else tf_, float)


def failure_times(ctx: Context, t_fail: np.ndarray | float | None = None) -> np.ndarray:
    """The failure time per case (s): ``t_fail`` or t_f / 2 (seed 001 Section 5)."""
    tf_ = t_fail if t_fail is not None else ctx.opts.t_fail
    return np.asarray(ctx.ref.tf / 2 if tf_ is None else tf_, float)


def _kernel_inputs(ctx: Context, X0: np.ndarray,
                   failures: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[tuple, tuple]:
    """(C, Q) of the kernel (lgw.sim.lunar.kernel) for the context and initial states;
    ``failures`` = (T_a (N,), t_fail (N,) s) per case (a Monte Carlo campaign), else the run's
    ``Ta`` and ``t_fail`` for every case."""
    from lgw.sim import integrate
    from lgw.sim.lunar.outcomes import AFTER_FAILURE_S

    o = ctx.opts
    ref = ctx.ref
    n = X0.shape[1]

    def mats(g, k):
        return np.ascontiguousarray(np.moveaxis(np.broadcast_to(g[k], (3, 3, n)), -1, 0),
                                    dtype=float)

    def vecs(g, k):
        return np.ascontiguousarray(np.broadcast_to(g[k], (n,)), dtype=float)

    ta, tfail = (o.Ta, None) if failures is None else failures

    def per_case(x):
        return np.ascontiguousarray(np.broadcast_to(np.asarray(x, float), (n,)), dtype=float)

    C = (np.ascontiguousarray(X0.T, dtype=float), mats(ctx.go, "K1"), mats(ctx.go, "F2"),
         vecs(ctx.go, "f3"), vecs(ctx.go, "q"), mats(ctx.ga, "K1"), mats(ctx.ga, "F2"),
         vecs(ctx.ga, "f3"), vecs(ctx.ga, "q"), per_case(ta),
         per_case(failure_centres(ctx, tfail)),
         per_case(failure_times(ctx, tfail) + AFTER_FAILURE_S))
    sx, sc = ref.spline
    Q = (sx, sc, float(ref.a1), float(ref.a2), float(ref.a3), float(ref.tf),
         float(o.thrust_max), float(o.torque_max), SAT_CODE[o.sat_reading],
         FAILURE_CODE[o.failure], float(o.dist_amp), float(o.cmd_wn),
         POINTING_CODE[o.thrust_pointing], np.ascontiguousarray(ctx.J[:, 0], dtype=float),
         float(o.m_dry), float(P.QUAT_NORM_TOL))
    return integrate.kernel_args(C), integrate.kernel_args(Q)


SAT_CODE = {"commanded": 0, "nominal": 1}
FAILURE_CODE = {"atan": 0, "step": 1, "none": 2}
POINTING_CODE = {"coupled": 0, "ideal": 1}


def simulate(ctx: Context, X0: np.ndarray, *, method: str = "rk4", record: bool = True,
             record_every: int = 5, rtol: float = 1e-6, atol: float = 1e-6,
             max_step: float = 1.0, max_steps: int = 200_000, parallel: bool = True,
             chunk: int = 1024, failures: tuple[np.ndarray, np.ndarray] | None = None
             ) -> BatchResult:
    """All cases of X0 (30, N) on the compiled kernel, RK4 at ``ctx.opts.dt`` (adjusted so that
    an integer number of steps ends exactly at t_end, as ``rk4_numpy``) or dopri5 (rtol, atol,
    max_step s, max_steps attempts).  record (RK4 only): the states and signals at every
    ``record_every``-th node (and the last), as ``BatchResult.X`` / ``out``.  ``failures``:
    (T_a (N,), t_fail (N,) s) per case, else the run's (``ctx.opts``)."""
    from lgw.sim import executors, integrate
    from lgw.sim.kernel_cache import CompileNotice
    from lgw.sim.lunar import kernel as K
    from lgw.sim.lunar.outcomes import OUTCOMES
    from lgw.sim.options import IntegrationOptions

    o = ctx.opts
    t_end = ctx.tf if o.t_end is None else o.t_end
    nst = max(1, int(round(t_end / o.dt)))
    h = t_end / nst
    record = bool(record) and method == "rk4"
    opt = IntegrationOptions(method=method, dt=h, rtol=rtol, atol=atol, max_step=max_step,
                             max_steps=max_steps, record=record)
    O = integrate.integration_tuple(opt, t_end)
    n = X0.shape[1]
    C, Q = _kernel_inputs(ctx, X0, failures)
    R = tuple(np.zeros(n, np.int64) if k in ("outcome", "sat_entries") else np.full(n, np.nan)
              for k in K.RESULT_FIELDS)
    G = tuple(integrate.generic_outputs(n, K.NY)[k] for k in integrate.GENERIC_FIELDS)
    shape = (n, O[2] + 1) if record else (1, 1)
    rec_y = np.full((*shape, K.NY), np.nan)
    rec_x = np.full((*shape, K.NX), np.nan)
    mod = K.kernel_module()
    with CompileNotice(mod.kernel, "the lunar kernel", "~20-40 s"):
        executors.run_local(lambda sl: integrate.run_chunk(mod.kernel, sl, C, Q, R, O, G, rec_y,
                                                           rec_x, parallel), n, chunk)
    res = dict(zip(K.RESULT_FIELDS, R, strict=True))
    res.update(zip(integrate.GENERIC_FIELDS, G, strict=True))
    code = res["outcome"].copy()
    code[res["step_limit"]] = K.STEPLIM
    code[res["nonfinite"]] = K.NONFINITE
    res["outcome"] = code
    res["t_outcome"] = np.where(res["nonfinite"] | res["step_limit"], res["t_end"],
                                res["t_outcome"])
    flagged = [(int(i), float(res["t_outcome"][i]), OUTCOMES[code[i]])
               for i in np.flatnonzero(code != K.COMPLETED)]
    if not record:
        return BatchResult(np.array([0.0, t_end]), np.stack([X0, res["y_end"].T]), {}, flagged,
                           h, res)
    steps = res["steps"]
    for i in range(n):  # a stopped case is frozen at its last accepted node
        rec_y[i, steps[i] + 1:] = rec_y[i, steps[i]]
        rec_x[i, steps[i] + 1:] = rec_x[i, steps[i]]
    idx = np.arange(0, O[2] + 1, max(1, int(record_every)))
    if idx[-1] != O[2]:
        idx = np.append(idx, O[2])
    Xr = np.moveaxis(rec_y[:, idx], 0, -1)  # (K, 30, N)
    xr = np.moveaxis(rec_x[:, idx], 0, -1)  # (K, NX, N)
    out = {}
    for name, (a, size) in K.AUX.items():
        out[name] = xr[:, a] if size == 1 else xr[:, a:a + size]
    for name in ("orbit_saturated", "torque_saturated"):
        out[name] = out[name] != 0.0
    out["d0e_orbit"], out["d0e_attitude"] = Xr[:, 11], Xr[:, 25]
    out["lam1o"], out["lam2o"] = Xr[:, 7], Xr[:, 8:11]
    out["lam1a"], out["lam2a"] = Xr[:, 19:22], Xr[:, 22:25]
    out["Vlam_o"] = 0.5 * (Xr[:, 7] ** 2 + np.sum(Xr[:, 8:11] ** 2, axis=1))
    out["Vlam_a"] = 0.5 * (np.sum(Xr[:, 19:22] ** 2, axis=1) + np.sum(Xr[:, 22:25] ** 2, axis=1))
    return BatchResult(idx * h, Xr, out, flagged, h, res)


def rk4_batch(ctx: Context, X0: np.ndarray, record_every: int = 5) -> BatchResult:
    """Fixed-step RK4 (step ``ctx.opts.dt``) of all cases on [0, t_end], compiled
    (``simulate``)."""
    return simulate(ctx, X0, record_every=record_every)


def solve_ivp_case(ctx: Context, x0: np.ndarray, t_eval: np.ndarray, rtol: float = 1e-10,
                   atol: float = 1e-10, method: str = "DOP853"):
    """A tight adaptive reference for one case (``ctx`` gains must be for one case)."""
    o = ctx.opts
    t_end = ctx.tf if o.t_end is None else o.t_end

    def f(t, x):
        return cl_field(t, x[:, None], ctx)[:, 0]

    return solve_ivp(f, (0.0, t_end), x0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)


def solve_ivp_compiled(ctx: Context, x0: np.ndarray, t_eval: np.ndarray | None = None,
                       rtol: float = 1e-10, atol: float = 1e-10, method: str = "DOP853"):
    """A tight adaptive reference for one case: scipy's ``solve_ivp`` on the compiled vector
    field of the kernel (``sys_rhs``, checked against ``closed_loop.field`` by the tests), an
    integrator independent of the kernel's RK4 and dopri5 and ~20x faster per call than the
    numpy field.  Note: after the loop starts sliding on z2 = 0 (claim smooth-7) an adaptive
    step must resolve every switch of the relay of (7): the whole Section 5 run at rtol = atol
    = 1e-6 takes ~3.7 M evaluations (~9 min); LSODA did not finish it in 30 min."""
    from lgw.sim.lunar import kernel as K

    o = ctx.opts
    t_end = ctx.tf if o.t_end is None else o.t_end
    C, Q = _kernel_inputs(ctx, x0[:, None])
    rhs = K.kernel_module().sys_rhs
    Y = np.zeros((1, K.NY))
    Kk = np.zeros((1, K.NY))
    X = np.zeros(K.NX)

    def f(t, x):
        Y[0] = x
        rhs(t, Y, 0, Kk, 0, X, 0, C, Q)
        return Kk[0].copy()

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


def torque_saturation(t: np.ndarray, dt: np.ndarray, sat: np.ndarray) -> dict[str, float]:
    """The two converged measures of the torque saturation from samples at times t (s), each
    counting the interval dt after it (s) when its flag sat is set (the kernel's left-node rule,
    ``lgw.sim.lunar.kernel``): the length of the saturation that starts at t = 0
    (``torque_saturated_initial_s``, 0 when the first sample is within the limit) and the time
    from which the command stays within its limit (``torque_saturation_end_s``, 0 when never
    saturated).  The total time above the limit is not among them: the relay of (7) makes the
    command chatter across the limit, and that total does not converge with the step
    (``lgw.sim.lunar.parameters``, DT)."""
    idx = np.flatnonzero(sat)
    first_in = np.flatnonzero(~sat)
    n0 = int(first_in[0]) if first_in.size else sat.size
    return {"torque_saturated_initial_s": float(np.sum(dt[:n0])),
            "torque_saturation_end_s": float(t[idx[-1]] + dt[idx[-1]]) if idx.size else 0.0}


def warmup_kernels() -> list[tuple[str, object]]:
    """The compiled kernels of seed 001, as (name, build): the closed loop's kernel
    (``lgw.sim.lunar.kernel``), built by flying the Section 5 case for 0.1 s through
    ``simulate`` (the argument types of every run)."""
    from lgw.sim.lunar.closed_loop import RunOptions
    from lgw.sim.lunar.scenario import section5_case

    def build() -> None:
        ctx, X0 = section5_case(opts=RunOptions(t_end=0.1))
        simulate(ctx, X0, parallel=False)

    return [("lunar", build)]


# the L2 norms of the filter states (11) of both loops over the flight (the kernel's
# integrals, lgw.sim.lunar.kernel): what (18) bounds by the L2 norm of B0 du
LAMBDA_L2 = ("lambda1_orbit_L2", "lambda2_orbit_L2", "lambda1_attitude_L2",
             "lambda2_attitude_L2")
# the integrands solve_ivp_numbers carries as extra states, in order: |B0 du|^2 of both loops,
# the indicators of the orbit's saturated time (all, and after t_after), |lambda|^2
_QUAD = ("B0du_orbit_L2", "B0du_attitude_L2", "orbit_saturated_s",
         "orbit_saturated_after_failure_s", *LAMBDA_L2)


def solve_ivp_numbers(ctx: Context, x0: np.ndarray, rtol: float = 1e-8, atol: float = 1e-8,
                      method: str = "DOP853") -> tuple[dict, object]:
    """The quoted numbers of one case (``lgw.sim.lunar.convergence.QUOTED``, the keys of
    ``lgw.sim.lunar.scenario.case_numbers``) from a tight adaptive ``solve_ivp`` of the compiled
    vector field, an integrator independent of the kernel's RK4 and dopri5.

    The integrals (the L2 norms of B0 du, int |B0 du|^2 dt; the times saturated, the integral of
    the saturation indicator) are extra states of the ODE, so they are integrated by the same
    steps and stages as the loop, not summed over samples; they are left out of the error
    control (atol 1e30: their integrands are discontinuous at every saturation switch, and
    their own error does not feed back into the loop).  Maxima and minima are over the accepted
    steps (the kernel's are over its nodes).  Returns (numbers, the solve_ivp result)."""
    from lgw.sim.lunar import kernel as K

    o = ctx.opts
    t_end = ctx.tf if o.t_end is None else o.t_end
    C, Q = _kernel_inputs(ctx, x0[:, None])
    t_after = float(C[11][0])
    rhs = K.kernel_module().sys_rhs
    nq = len(_QUAD)
    Y = np.zeros((1, K.NY))
    Kk = np.zeros((1, K.NY))
    X = np.zeros(K.NX)

    def aux(t, x):
        Y[0] = x[:K.NY]
        rhs(t, Y, 0, Kk, 0, X, 0, C, Q)
        return X

    def f(t, x):
        X = aux(t, x)
        q = (X[36] ** 2 + X[37] ** 2 + X[38] ** 2, X[39] ** 2 + X[40] ** 2 + X[41] ** 2,
             X[22], X[22] * (t >= t_after), X[56], X[57], X[58], X[59])
        return np.concatenate([Kk[0], q])

    z0 = np.concatenate([x0, np.zeros(nq)])
    at = np.concatenate([np.full(K.NY, atol), np.full(nq, 1e30)])
    sol = solve_ivp(f, (0.0, t_end), z0, method=method, rtol=rtol, atol=at)
    y = sol.y[:, -1]
    rs = ctx.ref.state(t_end)
    ev = y[3:6] - rs[1:4]
    eh = np.empty(sol.t.size)
    eq0 = np.empty(sol.t.size)
    tcmd = np.empty(sol.t.size)
    tsat = np.empty(sol.t.size, bool)
    for j, t in enumerate(sol.t):  # the node signals, as the kernel's trackers see them
        Xj = aux(t, sol.y[:, j])
        eh[j], eq0[j], tcmd[j], tsat[j] = Xj[0], Xj[7], Xj[15], Xj[23] != 0.0
    after = sol.t >= t_after
    q = dict(zip(_QUAD, y[K.NY:], strict=True))
    n = {"eh_final_m": float(y[0] - rs[0]), "ev_final_norm_m_s": float(np.linalg.norm(ev)),
         "max_abs_eh_m": float(np.max(np.abs(eh))),
         "max_abs_eh_after_failure_m": float(np.max(np.abs(eh[after]))) if after.any()
         else float("nan"),
         "thrust_cmd_max_after_failure_N": float(np.max(tcmd[after])) if after.any()
         else float("nan"),
         "min_abs_eq0": float(np.min(np.abs(eq0))),
         "d0e_orbit_final": float(y[11]), "d0e_attitude_final": float(y[25]),
         "B0du_orbit_L2": float(np.sqrt(q["B0du_orbit_L2"])),
         "B0du_attitude_L2": float(np.sqrt(q["B0du_attitude_L2"])),
         **{k: float(q[k]) for k in _QUAD[2:4]},
         **{k: float(np.sqrt(q[k])) for k in LAMBDA_L2},
         **torque_saturation(sol.t, np.diff(sol.t, append=sol.t[-1]), tsat),
         "evaluations": int(sol.nfev), "steps": int(sol.t.size - 1)}
    return n, sol
