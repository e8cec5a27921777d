"""Batched sampled-data simulation of seed 002's closed loop (all cases advance together).

STAND-IN: a compact numpy-vectorised RK4 over cases, to be replaced by the shared numba
integrator ``lgw.sim.integrate`` when it lands (same role: advance the plant between samples).

Sampled-data control (seed 002: "sampling time 0.01 s"): at each sample t_k the controller reads
the state, the reference (8)-(10) and (known-D case) the disturbance D(t_k), computes u_k by the
generated law (lgw.sim.eros.laws) and holds it (zero-order hold) until t_k + dt; the plant
(lgw.sim.eros.plant) is integrated in between by ``n_sub`` classical RK4 steps with the
continuous disturbance D(t) at the stage times.  ``reference_solve`` integrates the same
sampled-data loop per case with solve_ivp (DOP853, tight tolerances) between samples: the
independent route the tests compare against.

Per case (``metrics``): tracking error history, reaching and settling ("tracked") times per axis,
control peak and effort, chattering (total variation of u), the Table 2 analogue (IAE), the
final state.  A case whose state or control becomes non-finite is flagged ``nonfinite`` and
frozen (never silently dropped).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from lgw.sim.eros import laws as SL
from lgw.sim.eros import plant as PL
from lgw.theory.eros import parameters as P
from lgw.theory.eros import reference as REF
from lgw.theory.eros.gains import Gains
from lgw.theory.errors import ParameterError
from scipy.integrate import solve_ivp

DIST_MODES = ("known", "unknown", "none")


@dataclass(frozen=True)
class SimOptions:
    """What to fly: the law variant, horizon, sampling, plant models."""

    law: str = "ftsmc"
    switch: str = "sign"
    t_final: float = P.T_SCENARIO  # s
    dt: float = P.DT_SAMPLE  # s, sampling time (zero-order hold)
    n_sub: int = 2  # RK4 steps per sample
    gravity: str = "two-point"  # plant gravity; the controller always uses the two-point model
    disturbance: str = "known"  # "known": D in u_eq (14); "unknown": u_eq without D; "none"
    dist: PL.Disturbance = field(default_factory=PL.Disturbance)
    reference: str = "exact"  # cubic coefficients: "exact" or "printed"
    t0: float = 0.0  # s, start time on the reference

    def __post_init__(self) -> None:
        if (self.law, self.switch) not in SL.VARIANTS:
            raise ParameterError("law", f"{self.law}-{self.switch}",
                                 "one of " + ", ".join(SL.variant_name(*v) for v in SL.VARIANTS))
        for name, val in (("t_final", self.t_final), ("dt", self.dt)):
            if not (isinstance(val, int | float) and np.isfinite(val) and val > 0):
                raise ParameterError(name, val, "must be a finite number > 0 (s)")
        if not (isinstance(self.n_sub, int) and self.n_sub >= 1):
            raise ParameterError("n_sub", self.n_sub, "must be an integer >= 1")
        if self.gravity not in PL.GRAVITY_MODELS:
            raise ParameterError("gravity", self.gravity, "one of " + ", ".join(PL.GRAVITY_MODELS))
        if self.disturbance not in DIST_MODES:
            raise ParameterError("disturbance", self.disturbance, "one of "
                                 + ", ".join(DIST_MODES))
        if self.reference not in ("exact", "printed"):
            raise ParameterError("reference", self.reference, "exact or printed")


@dataclass
class Result:
    """Histories at the samples t_k (k = 0..K): arrays (K+1, cases, 3) unless noted."""

    t: np.ndarray  # (K+1,)
    e: np.ndarray  # position error
    ed: np.ndarray  # velocity error
    s: np.ndarray  # surface value at the samples
    u: np.ndarray  # (K, cases, 3): the held control on [t_k, t_k+1)
    pos: np.ndarray  # (cases, 3) final position
    vel: np.ndarray  # (cases, 3) final velocity
    nonfinite: np.ndarray  # (cases,) bool
    options: SimOptions
    gains: Gains


def _ref_coef(opts: SimOptions) -> np.ndarray:
    return REF.coefficients(printed=opts.reference == "printed")


def _controller(opts: SimOptions, g: Gains, coef: np.ndarray, t: float, pos, vel,
                case_phase) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    rp, rv, ra = REF.evaluate(coef, t)
    e, ed = pos - rp, vel - rv
    f = PL.rotating_terms(pos, vel) + PL.gravity(pos, "two-point")
    Dk = (opts.dist(t, case_phase) if opts.disturbance == "known" else np.zeros_like(pos))
    xdd = np.broadcast_to(ra, pos.shape)
    u, s = SL.evaluate(opts.law, opts.switch, e, ed, f, Dk, xdd, g)
    return u, s, e, ed


def initial_state(e0: np.ndarray, ed0: np.ndarray, opts: SimOptions) -> tuple[np.ndarray, ...]:
    rp, rv, _ = REF.evaluate(_ref_coef(opts), opts.t0)
    return rp[None, :] + np.atleast_2d(e0), rv[None, :] + np.atleast_2d(ed0)


def simulate(e0: np.ndarray, ed0: np.ndarray, g: Gains, opts: SimOptions,
             case_phase: np.ndarray | None = None) -> Result:
    """Fly every case (rows of e0, ed0: initial position and velocity errors, m and m/s)."""
    e0, ed0 = np.atleast_2d(np.asarray(e0, float)), np.atleast_2d(np.asarray(ed0, float))
    if e0.shape != ed0.shape or e0.shape[1] != 3:
        raise ParameterError("e0", e0.shape, "e0 and ed0 must both be (cases, 3)")
    if not (np.all(np.isfinite(e0)) and np.all(np.isfinite(ed0))):
        raise ParameterError("e0", "non-finite", "initial errors must be finite")
    n = len(e0)
    cp = np.zeros(n) if case_phase is None else np.asarray(case_phase, float)
    coef = _ref_coef(opts)
    K = int(round(opts.t_final / opts.dt))
    pos, vel = initial_state(e0, ed0, opts)
    ts = opts.t0 + opts.dt * np.arange(K + 1)
    E, ED, S = (np.empty((K + 1, n, 3)) for _ in range(3))
    U = np.empty((K, n, 3))
    bad = np.zeros(n, dtype=bool)
    h = opts.dt / opts.n_sub

    def f(t, p, v, u):
        if opts.disturbance == "none":
            return v, PL.rotating_terms(p, v) + PL.gravity(p, opts.gravity) + u
        return v, PL.accel(t, p, v, u, opts.dist, cp, opts.gravity)

    for kk in range(K + 1):
        t = ts[kk]
        u, s, e, ed = _controller(opts, g, coef, t, pos, vel, cp)
        E[kk], ED[kk], S[kk] = e, ed, s
        if kk == K:
            break
        nf = ~np.all(np.isfinite(u), axis=1)
        if nf.any():
            bad |= nf
            u = np.where(nf[:, None], 0.0, u)
        U[kk] = u
        for j in range(opts.n_sub):
            tj = t + j * h
            k1p, k1v = f(tj, pos, vel, u)
            k2p, k2v = f(tj + h / 2, pos + h / 2 * k1p, vel + h / 2 * k1v, u)
            k3p, k3v = f(tj + h / 2, pos + h / 2 * k2p, vel + h / 2 * k2v, u)
            k4p, k4v = f(tj + h, pos + h * k3p, vel + h * k3v, u)
            npos = pos + h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p)
            nvel = vel + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            ok = np.all(np.isfinite(npos), axis=1) & np.all(np.isfinite(nvel), axis=1) & ~bad
            bad |= ~ok
            pos = np.where(ok[:, None], npos, pos)
            vel = np.where(ok[:, None], nvel, vel)
    return Result(ts, E, ED, S, U, pos, vel, bad, opts, g)


def reference_solve(e0: np.ndarray, ed0: np.ndarray, g: Gains, opts: SimOptions,
                    case_phase: float = 0.0, rtol: float = 1e-11,
                    atol: float = 1e-11) -> Result:
    """One case by solve_ivp (DOP853) between samples, same sampled-data controller: the
    independent route for the batched RK4."""
    e0, ed0 = np.atleast_2d(e0), np.atleast_2d(ed0)
    coef = _ref_coef(opts)
    K = int(round(opts.t_final / opts.dt))
    pos, vel = initial_state(e0, ed0, opts)
    y = np.concatenate([pos[0], vel[0]])
    cp = np.array([case_phase])
    ts = opts.t0 + opts.dt * np.arange(K + 1)
    E, ED, S = (np.empty((K + 1, 1, 3)) for _ in range(3))
    U = np.empty((K, 1, 3))
    for kk in range(K + 1):
        u, s, e, ed = _controller(opts, g, coef, ts[kk], y[None, :3], y[None, 3:], cp)
        E[kk], ED[kk], S[kk] = e, ed, s
        if kk == K:
            break
        U[kk] = u

        def rhs(t, yy, u=u):
            p, v = yy[None, :3], yy[None, 3:]
            if opts.disturbance == "none":
                a = PL.rotating_terms(p, v) + PL.gravity(p, opts.gravity) + u
            else:
                a = PL.accel(t, p, v, u, opts.dist, cp, opts.gravity)
            return np.concatenate([yy[3:], a[0]])
        sol = solve_ivp(rhs, (ts[kk], ts[kk + 1]), y, method="DOP853", rtol=rtol, atol=atol)
        y = sol.y[:, -1]
    return Result(ts, E, ED, S, U, y[None, :3], y[None, 3:], np.zeros(1, bool), opts, g)


# --- per-case measures ------------------------------------------------------------------------

S_TOL = 1e-3  # m/s: "on the surface" for the reaching time (chosen; the sign law's sampled
#               chattering band is ~k dt = 0.02 m/s, so the first crossing also counts)


def _first_true(mask: np.ndarray, t: np.ndarray) -> np.ndarray:
    """First time along axis 0 where mask holds (NaN if never): mask (K+1, n, 3)."""
    any_ = mask.any(axis=0)
    idx = mask.argmax(axis=0)
    return np.where(any_, t[idx], np.nan)


def metrics(res: Result, track_tol: float = P.TRACK_TOL) -> dict[str, np.ndarray]:
    """Per case (and axis) measures.  Definitions:

    t_reach   first sample with |s_i| <= S_TOL or s_i changed sign since t0 (s);
    t_track   "tracked in": the first sample after which |e_i| <= track_tol for the rest of
              the run (NaN if never) -- the paper's "tracked in 8 / 5 / 4 s";
    u_peak    max |u_i| over the run (m/s^2); effort: sum |u_i| dt (m/s);
    chatter   total variation sum_k |u_i(k+1) - u_i(k)| (m/s^2);
    iae       Table 2 analogue: sum over samples and axes of |e_i(t_k)| (m) -- MATLAB's
              sum(abs(e)) over the 0.01 s samples; iae_int = the same times dt (m s);
    e_final, ed_final: errors at t_final."""
    t, e, s, u = res.t, res.e, res.s, res.u
    crossed = np.sign(s) != np.sign(s[:1])
    t_reach = _first_true((np.abs(s) <= S_TOL) | crossed, t)
    out_band = np.abs(e) > track_tol
    last_out = np.where(out_band.any(axis=0), len(t) - 1 - out_band[::-1].argmax(axis=0), -1)
    t_track = np.where(last_out < len(t) - 1, t[np.minimum(last_out + 1, len(t) - 1)], np.nan)
    dt = res.options.dt
    return {
        "t_reach": t_reach, "t_track": t_track,
        "t_track_all": np.nanmax(np.where(np.isnan(t_track), np.inf, t_track), axis=1),
        "u_peak": np.abs(u).max(axis=0), "effort": np.abs(u).sum(axis=0) * dt,
        "chatter": np.abs(np.diff(u, axis=0)).sum(axis=0),
        "iae": np.abs(e).sum(axis=(0, 2)), "iae_int": np.abs(e).sum(axis=(0, 2)) * dt,
        "e_final": e[-1], "ed_final": res.ed[-1], "nonfinite": res.nonfinite,
    }
