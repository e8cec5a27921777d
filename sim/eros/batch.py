"""Batched sampled-data simulation of seed 002's closed loop (all cases advance together).

Two implementations of the same loop, selected by ``SimOptions.engine``:

  "kernel" (default)  the compiled kernel ``lgw.sim.eros.kernel`` on the shared integrator
                      ``lgw.sim.integrate`` with its zero-order hold: RK4 with n_sub steps per
                      sample, or (method="dopri5") Dormand-Prince 5(4) with rtol / atol and its
                      steps clipped at the samples; cases in parallel (threads);
  "numpy"             ``simulate_numpy``, the numpy-vectorised RK4 stand-in this module had
                      before, kept as the independent cross-check (same ZOH, same substeps:
                      the two agree to rounding, tests/eros/test_kernel.py).

The kernel has the two-point and "none" gravity; ``gravity="polyhedron"`` (the Werner-Scheeres
sum over the whole mesh in every right-hand side) runs on the numpy path whatever the engine,
and so do gains whose expressions overflow in Python floats (``_controller``: every case is
flagged non-finite at t0, as before).

Sampled-data control (seed 002: "sampling time 0.01 s"): at each sample t_k the controller reads
the state, the reference (8)-(10) and (known-D case) the disturbance D(t_k), computes u_k by the
generated law (lgw.sim.eros.laws) and holds it (zero-order hold) until t_k + dt; the plant
(lgw.sim.eros.plant) is integrated in between by ``n_sub`` classical RK4 steps with the
continuous disturbance D(t) at the stage times.  ``reference_solve`` integrates the same
sampled-data loop per case with solve_ivp (DOP853, tight tolerances) between samples: the
independent route the tests compare against.

Per case (``metrics``): tracking error history, reaching and settling ("tracked") times per axis,
control peak and effort, chattering (total variation of u), the Table 2 analogue (IAE), the
final state.

Outcomes (``OUTCOMES``): every case ends in exactly one, with its time (``Result.outcome``,
``Result.t_outcome``), the first thing that happened:

  "crashed"          the sampled position is inside the shape model of Eros (the polyhedron of
                     lgw.theory.eros.polyhedron; checked at every sample t_k, after a bounding-box
                     screen); time: the first such sample.  The case is frozen there (a crash:
                     the plant (4) does not model contact; the shared vocabulary's name,
                     lgw.sim.results).  Between samples a contact is not
                     located (a probe faster than ~1e5 m/s could cross the body unseen).
  "nonfinite"        the control u_k or the state became NaN / inf; time: the start t_k of the
                     sample interval that blew up (u_k itself, or an RK4 stage within it).  The
                     case is frozen at its last finite state and its held control recorded as 0
                     (the blown-up command is not a number a peak could report).
  "tracked"          neither, and |e_i| <= TRACK_TOL on every axis from some sample to t_final
                     (metrics' t_track_all); time: that sample.
  "horizon"          none of these by t_final; time: t_final.

The reference route (``reference_solve``) applies the same rules, with a solve_ivp failure
counted as "nonfinite" (it only fails here when the state or control overflows).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cache

import numpy as np
from lgw.sim.eros import laws as SL
from lgw.sim.eros import plant as PL
from lgw.sim.results import names as _shared_names
from lgw.theory.eros import parameters as P
from lgw.theory.eros import reference as REF
from lgw.theory.eros.gains import Gains
from lgw.theory.errors import ParameterError
from scipy.integrate import solve_ivp

DIST_MODES = ("known", "unknown", "none")
ENGINES = ("kernel", "numpy")
OUTCOMES = _shared_names("crashed", "nonfinite", "tracked", "horizon")  # lgw.sim.results


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
    engine: str = "kernel"  # "kernel" (lgw.sim.eros.kernel) or "numpy" (simulate_numpy)
    method: str = "rk4"  # kernel only: "rk4" (n_sub steps per sample) or "dopri5"
    rtol: float = 1e-10  # dopri5 only: relative tolerance
    atol: float = 1e-10  # dopri5 only: absolute tolerance (m, m/s)

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
        if self.engine not in ENGINES:
            raise ParameterError("engine", self.engine, "one of " + ", ".join(ENGINES))
        if self.method not in ("rk4", "dopri5"):
            raise ParameterError("method", self.method, "rk4 or dopri5")
        if self.method == "dopri5" and self.engine == "numpy":
            raise ParameterError("method", self.method, "dopri5 needs engine='kernel'")
        for name, val in (("rtol", self.rtol), ("atol", self.atol)):
            if not (isinstance(val, int | float) and np.isfinite(val) and val > 0):
                raise ParameterError(name, val, "must be a finite number > 0")
        if self.rtol < 1e-13:
            raise ParameterError("rtol", self.rtol, "must be >= 1e-13 (double precision)")


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
    contact: np.ndarray | None = None  # (cases,) bool: surface contact (see OUTCOMES)
    t_event: np.ndarray | None = None  # (cases,) s: time of the contact / blow-up (NaN: none)
    outcome: np.ndarray | None = None  # (cases,) int index into OUTCOMES (set by classify)
    t_outcome: np.ndarray | None = None  # (cases,) s

    def __post_init__(self) -> None:
        n = len(self.nonfinite)
        if self.contact is None:
            self.contact = np.zeros(n, bool)
        if self.t_event is None:
            self.t_event = np.full(n, np.nan)
        if self.outcome is None:
            self.outcome, self.t_outcome = classify(self)


@cache
def _body() -> tuple[np.ndarray, ...]:
    """Box of the mesh vertices; per face a vertex, the unit normal, the centroid and the
    radius of the ball about the centroid that holds the face (m)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron

    P = eros_polyhedron()
    tri = P.vertices[P.faces]
    cen = tri.mean(axis=1)
    rad = np.linalg.norm(tri - cen[:, None], axis=2).max(axis=1)
    return P.vertices.min(axis=0), P.vertices.max(axis=0), tri[:, 0], P.normals, cen, rad


def clearance(pos: np.ndarray) -> np.ndarray:
    """A lower bound (m) on the distance from each point (m, 3) to the mesh surface: the
    minimum over faces of max(distance to the face's plane, distance to the ball about its
    centroid that holds it) -- each is <= the distance to the face."""
    _, _, a, n, cen, rad = _body()
    out = np.empty(len(pos))
    for i in range(0, len(pos), 16):
        x = pos[i:i + 16, None, :]
        plane = np.abs(np.einsum("pfi,fi->pf", x - a[None], n))
        ball = np.linalg.norm(x - cen[None], axis=2) - rad[None]
        out[i:i + 16] = np.maximum(plane, ball).min(axis=1)
    return out


def in_body(pos: np.ndarray) -> np.ndarray:
    """True where a position (cases, 3) is inside the shape model of Eros (non-finite: False):
    a bounding-box screen, then the solid-angle test (lgw.theory.eros.polyhedron.inside)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron, inside

    lo, hi = _body()[:2]
    with np.errstate(invalid="ignore"):
        cand = np.all((pos >= lo) & (pos <= hi), axis=1)
    out = np.zeros(len(pos), bool)
    if cand.any():
        out[cand] = inside(eros_polyhedron(), pos[cand])
    return out


class ContactMonitor:
    """``in_body`` at every sample of a batch, exact but lazy: a case keeps its last
    exactly-tested status until its path since that test (the sum of its sample-to-sample
    displacements, >= its distance from the tested point) reaches the tested point's
    ``clearance`` (a ball that does not meet the surface is all inside or all outside).
    Points outside the vertex box are outside."""

    def __init__(self, n: int) -> None:
        self.status = np.zeros(n, bool)
        self.clear = np.full(n, -1.0)  # clearance at the last exact test (< 0: test next time)
        self.path = np.zeros(n)
        self.last: np.ndarray | None = None

    def __call__(self, pos: np.ndarray, skip: np.ndarray) -> np.ndarray:
        """Inside-status at this sample; cases in ``skip`` (frozen) are not re-tested."""
        from lgw.theory.eros.polyhedron import eros_polyhedron, inside

        lo, hi = _body()[:2]
        with np.errstate(invalid="ignore", over="ignore"):
            if self.last is not None:
                self.path += np.linalg.norm(pos - self.last, axis=1)
            self.last = pos.copy()
            fin = np.all(np.isfinite(pos), axis=1)
            box = fin & np.all((pos >= lo) & (pos <= hi), axis=1)
        self.status[~box] = False
        self.clear[~box] = -1.0
        need = box & ~(self.path < self.clear) & ~skip
        if need.any():
            idx = np.flatnonzero(need)
            self.status[idx] = inside(eros_polyhedron(), pos[idx])
            self.clear[idx] = clearance(pos[idx])
            self.path[idx] = 0.0
        return self.status.copy()


def track_times(e: np.ndarray, t: np.ndarray, track_tol: float = P.TRACK_TOL) -> np.ndarray:
    """Per case and axis: the first sample after which |e_i| <= track_tol for the rest of the
    run (NaN if never).  e: (K+1, n, 3)."""
    with np.errstate(invalid="ignore"):
        out_band = ~(np.abs(e) <= track_tol)  # NaN counts as out of band
    last_out = np.where(out_band.any(axis=0), len(t) - 1 - out_band[::-1].argmax(axis=0), -1)
    return np.where(last_out < len(t) - 1, t[np.minimum(last_out + 1, len(t) - 1)], np.nan)


def classify(res: Result) -> tuple[np.ndarray, np.ndarray]:
    """(index into OUTCOMES, time in s) per case: exactly one outcome each (module docstring)."""
    contact = np.asarray(res.contact, bool)
    bad = np.asarray(res.nonfinite, bool) & ~contact
    tt = track_times(res.e, res.t)
    t_all = np.where(np.isnan(tt).any(axis=1), np.nan, np.nanmax(
        np.where(np.isnan(tt), -np.inf, tt), axis=1))
    tracked = ~contact & ~bad & np.isfinite(t_all)
    code = np.select([contact, bad, tracked], [0, 1, 2], default=3)
    t_end = float(res.t[-1])
    t = np.select([contact | bad, tracked], [np.asarray(res.t_event, float), t_all],
                  default=t_end)
    return code, t


def outcome_counts(code: np.ndarray) -> dict[str, int]:
    """Cases per outcome (every outcome listed, zeros included)."""
    return {name: int(np.sum(np.asarray(code) == i)) for i, name in enumerate(OUTCOMES)}


def _ref_coef(opts: SimOptions) -> np.ndarray:
    return REF.coefficients(printed=opts.reference == "printed")


def _controller(opts: SimOptions, g: Gains, coef: np.ndarray, t: float, pos, vel,
                case_phase) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    rp, rv, ra = REF.evaluate(coef, t)
    e, ed = pos - rp, vel - rv
    f = PL.rotating_terms(pos, vel) + PL.gravity(pos, "two-point")
    Dk = (opts.dist(t, case_phase) if opts.disturbance == "known" else np.zeros_like(pos))
    xdd = np.broadcast_to(ra, pos.shape)
    try:
        u, s = SL.evaluate(opts.law, opts.switch, e, ed, f, Dk, xdd, g)
    except OverflowError:
        # a gain expression in Python floats overflowed (e.g. alpha**2 of the fuzzy distance
        # at alpha = 1e300): the law cannot be evaluated, every case is flagged non-finite
        u = s = np.full(pos.shape, np.nan)
    return u, s, e, ed


def initial_state(e0: np.ndarray, ed0: np.ndarray, opts: SimOptions) -> tuple[np.ndarray, ...]:
    rp, rv, _ = REF.evaluate(_ref_coef(opts), opts.t0)
    return rp[None, :] + np.atleast_2d(e0), rv[None, :] + np.atleast_2d(ed0)


def _checked(e0, ed0) -> tuple[np.ndarray, np.ndarray]:
    e0, ed0 = np.atleast_2d(np.asarray(e0, float)), np.atleast_2d(np.asarray(ed0, float))
    if e0.ndim != 2 or e0.shape != ed0.shape or e0.shape[1] != 3:
        raise ParameterError("e0", e0.shape, "e0 and ed0 must both be (cases, 3)")
    if not (np.all(np.isfinite(e0)) and np.all(np.isfinite(ed0))):
        raise ParameterError("e0", "non-finite", "initial errors must be finite")
    return e0, ed0


def _overflows(opts: SimOptions, g: Gains, e0: np.ndarray, ed0: np.ndarray) -> bool:
    """True if the generated numpy law raises OverflowError for these gains (a gain expression
    in Python floats, e.g. alpha**2 at alpha = 1e300; ``_controller`` then flags every case
    non-finite at t0): such a gain set is flown by the numpy path, which does exactly that."""
    pos, vel = initial_state(e0[:1], ed0[:1], opts)
    rp, rv, ra = REF.evaluate(_ref_coef(opts), opts.t0)
    try:
        with np.errstate(all="ignore"):
            f = PL.rotating_terms(pos, vel) + PL.gravity(pos, "two-point")
            SL.evaluate(opts.law, opts.switch, pos - rp, vel - rv, f, np.zeros_like(pos),
                        np.broadcast_to(ra, pos.shape), g)
    except OverflowError:
        return True
    return False


def simulate(e0: np.ndarray, ed0: np.ndarray, g: Gains, opts: SimOptions,
             case_phase: np.ndarray | None = None) -> Result:
    """Fly every case (rows of e0, ed0: initial position and velocity errors, m and m/s) with
    ``opts.engine`` (module docstring): the compiled kernel, or the numpy stand-in.

    A case that touches the body or blows up is frozen from that sample on (module docstring);
    the histories of a frozen case keep its last state, and its held control is 0."""
    e0, ed0 = _checked(e0, ed0)
    if _overflows(opts, g, e0, ed0):
        return simulate_numpy(e0, ed0, g, replace(opts, method="rk4"), case_phase)
    if opts.engine == "numpy" or opts.gravity == "polyhedron":
        if opts.method != "rk4":
            raise ParameterError("method", opts.method,
                                 "dopri5 needs the kernel (two-point or no gravity)")
        return simulate_numpy(e0, ed0, g, opts, case_phase)
    return simulate_kernel(e0, ed0, g, opts, case_phase)


def simulate_kernel(e0: np.ndarray, ed0: np.ndarray, g: Gains, opts: SimOptions,
                    case_phase: np.ndarray | None = None, chunk: int = 256,
                    parallel: bool = True) -> Result:
    """The compiled kernel (lgw.sim.eros.kernel) on the shared integrator's zero-order hold:
    the same loop, outcomes and histories as ``simulate_numpy``; two-point or no gravity.
    Cases run in chunks of ``chunk`` (in threads inside a chunk when ``parallel``)."""
    from lgw.sim import executors, integrate
    from lgw.sim.eros import kernel as KN
    from lgw.sim.options import IntegrationOptions

    e0, ed0 = _checked(e0, ed0)
    if opts.gravity not in KN.GRAVITY_CODE:
        raise ParameterError("gravity", opts.gravity, "the kernel has "
                             + ", ".join(KN.GRAVITY_CODE) + " (polyhedron: engine='numpy')")
    n = len(e0)
    cp = np.zeros(n) if case_phase is None else np.asarray(case_phase, float)
    if cp.shape != (n,) or not np.all(np.isfinite(cp)):
        raise ParameterError("case_phase", cp.shape, f"must be {n} finite numbers (rad)")
    mod = KN.kernel_module()
    K = int(round(opts.t_final / opts.dt))
    pos0, vel0 = initial_state(e0, ed0, opts)
    d = opts.dist
    gm = np.array(P.TWO_POINT_GM, float)
    Q = (KN.LAW_CODE[opts.law], KN.SWITCH_CODE[opts.switch],
         np.array(SL.gain_values(g), float), np.ascontiguousarray(_ref_coef(opts)),
         float(opts.t0), float(opts.dt), float(d.amp), float(d.freq),
         np.asarray(d.phase, float), KN.DIST_CODE[opts.disturbance],
         KN.GRAVITY_CODE[opts.gravity], float(P.OMEGA), np.asarray(P.TWO_POINT_P1, float),
         np.asarray(P.TWO_POINT_P2, float), gm, True, *KN.body_arrays())
    E, ED, SV = (np.empty((n, K + 1, 3)) for _ in range(3))
    U = np.empty((n, K, 3))
    code = np.zeros(n, np.int64)
    t_ev = np.full(n, np.nan)
    klast = np.zeros(n, np.int64)
    pos, vel = np.empty((n, 3)), np.empty((n, 3))
    R = (E, ED, SV, U, code, t_ev, klast, pos, vel)
    io = IntegrationOptions(method=opts.method, dt=opts.dt, rtol=opts.rtol, atol=opts.atol,
                            max_step=opts.dt, max_steps=50 * K + 1000)
    O = integrate.integration_tuple(io, K * opts.dt, sample=(opts.dt, opts.n_sub))  # noqa: N806
    gout = integrate.generic_outputs(n, KN.NY)
    G = tuple(gout[k] for k in integrate.GENERIC_FIELDS)  # noqa: N806
    C = (np.ascontiguousarray(pos0), np.ascontiguousarray(vel0), np.ascontiguousarray(cp))
    C, Q = integrate.kernel_args(C), integrate.kernel_args(Q)  # noqa: N806
    empty = np.empty((1, 1, 1))
    executors.run_local(lambda sl: integrate.run_chunk(mod.kernel, sl, C, Q, R, O, G, empty,
                                                       empty, parallel), n, chunk)
    # a step that blew up (or, dopri5, the step limit) ends the case inside sample interval
    # k_last: non-finite, at that interval's t_k (as the stand-in)
    blew = (gout["nonfinite"] | gout["step_limit"]) & (code == KN.RUNNING)
    code[blew] = KN.NONFINITE
    t_ev[blew] = opts.t0 + klast[blew] * opts.dt
    ts = opts.t0 + opts.dt * np.arange(K + 1)
    def tr(a: np.ndarray) -> np.ndarray:  # (cases, K, 3) -> (K, cases, 3), as the stand-in
        return np.ascontiguousarray(np.moveaxis(a, 0, 1))

    return Result(ts, tr(E), tr(ED), tr(SV), tr(U), pos, vel, code == KN.NONFINITE, opts, g,
                  code == KN.CONTACT, t_ev)


def simulate_numpy(e0: np.ndarray, ed0: np.ndarray, g: Gains, opts: SimOptions,
                   case_phase: np.ndarray | None = None) -> Result:
    """The numpy stand-in: every case advanced together by vectorised RK4, n_sub steps per
    sample (module docstring; the independent route for the kernel)."""
    e0, ed0 = _checked(e0, ed0)
    n = len(e0)
    cp = np.zeros(n) if case_phase is None else np.asarray(case_phase, float)
    coef = _ref_coef(opts)
    K = int(round(opts.t_final / opts.dt))
    pos, vel = initial_state(e0, ed0, opts)
    ts = opts.t0 + opts.dt * np.arange(K + 1)
    E, ED, S = (np.empty((K + 1, n, 3)) for _ in range(3))
    U = np.empty((K, n, 3))
    bad = ~(np.all(np.isfinite(pos), axis=1) & np.all(np.isfinite(vel), axis=1))
    contact = np.zeros(n, dtype=bool)
    t_event = np.where(bad, ts[0], np.nan)
    h = opts.dt / opts.n_sub

    def f(t, p, v, u):
        if opts.disturbance == "none":
            return v, PL.rotating_terms(p, v) + PL.gravity(p, opts.gravity) + u
        return v, PL.accel(t, p, v, u, opts.dist, cp, opts.gravity)

    monitor = ContactMonitor(n)
    with np.errstate(all="ignore"):  # overflow is detected and flagged per case below
        for kk in range(K + 1):
            t = ts[kk]
            hit = monitor(pos, bad | contact) & ~bad & ~contact
            if hit.any():
                contact |= hit
                t_event = np.where(hit, t, t_event)
            u, s, e, ed = _controller(opts, g, coef, t, pos, vel, cp)
            E[kk], ED[kk], S[kk] = e, ed, s
            stopped = bad | contact
            nf = ~(np.all(np.isfinite(u), axis=1) & np.all(np.isfinite(s), axis=1)) & ~stopped
            if nf.any():
                bad |= nf
                t_event = np.where(nf, t, t_event)
            if kk == K:
                break
            stopped = bad | contact
            u = np.where(stopped[:, None], 0.0, u)
            U[kk] = u
            for j in range(opts.n_sub):
                tj = t + j * h
                k1p, k1v = f(tj, pos, vel, u)
                k2p, k2v = f(tj + h / 2, pos + h / 2 * k1p, vel + h / 2 * k1v, u)
                k3p, k3v = f(tj + h / 2, pos + h / 2 * k2p, vel + h / 2 * k2v, u)
                k4p, k4v = f(tj + h, pos + h * k3p, vel + h * k3v, u)
                npos = pos + h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p)
                nvel = vel + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
                ok = np.all(np.isfinite(npos), axis=1) & np.all(np.isfinite(nvel), axis=1)
                blew = ~ok & ~stopped
                bad |= blew
                t_event = np.where(blew, t, t_event)
                stopped = bad | contact
                pos = np.where(stopped[:, None], pos, npos)
                vel = np.where(stopped[:, None], vel, nvel)
    return Result(ts, E, ED, S, U, pos, vel, bad, opts, g, contact, t_event)


def reference_solve(e0: np.ndarray, ed0: np.ndarray, g: Gains, opts: SimOptions,
                    case_phase: float = 0.0, rtol: float = 1e-11,
                    atol: float = 1e-11) -> Result:
    """One case by solve_ivp (DOP853) between samples, same sampled-data controller and the
    same outcome rules (module docstring): the independent route for the batched RK4."""
    e0, ed0 = np.atleast_2d(e0), np.atleast_2d(ed0)
    coef = _ref_coef(opts)
    K = int(round(opts.t_final / opts.dt))
    pos, vel = initial_state(e0, ed0, opts)
    y = np.concatenate([pos[0], vel[0]])
    cp = np.array([case_phase])
    ts = opts.t0 + opts.dt * np.arange(K + 1)
    E, ED, S = (np.empty((K + 1, 1, 3)) for _ in range(3))
    U = np.empty((K, 1, 3))
    bad = contact = False
    t_event = np.nan
    with np.errstate(all="ignore"):
        for kk in range(K + 1):
            if not (bad or contact) and in_body(y[None, :3])[0]:
                contact, t_event = True, ts[kk]
            u, s, e, ed = _controller(opts, g, coef, ts[kk], y[None, :3], y[None, 3:], cp)
            E[kk], ED[kk], S[kk] = e, ed, s
            if not (bad or contact) and not (np.all(np.isfinite(u)) and np.all(np.isfinite(s))):
                bad, t_event = True, ts[kk]
            if kk == K:
                break
            if bad or contact:
                U[kk] = 0.0
                continue
            U[kk] = u

            # integrate z = y / c, c a power of two >= the scale of y and of the interval's
            # velocity change |u| dt (exact in floating point): solve_ivp's RMS error norm
            # squares the state, which overflows for states beyond ~1e154 that the loop itself
            # still represents.  atol on z is floored at 1e-16 (relative to c): it only binds
            # for c > 1e5 m, where 1e-11 m absolute is below the state's own resolution.
            dt_k = ts[kk + 1] - ts[kk]
            c = 2.0 ** np.ceil(np.log2(max(1.0, float(np.max(np.abs(y))),
                                           float(np.max(np.abs(u))) * dt_k)))

            def rhs(t, zz, u=u, c=c):
                yy = zz * c
                p, v = yy[None, :3], yy[None, 3:]
                if opts.disturbance == "none":
                    a = PL.rotating_terms(p, v) + PL.gravity(p, opts.gravity) + u
                else:
                    a = PL.accel(t, p, v, u, opts.dist, cp, opts.gravity)
                return np.concatenate([yy[3:], a[0]]) / c
            try:
                sol = solve_ivp(rhs, (ts[kk], ts[kk + 1]), y / c, method="DOP853", rtol=rtol,
                                atol=max(atol / c, 1e-16))
                ynew = sol.y[:, -1] * c
                ok = sol.success and bool(np.all(np.isfinite(ynew)))
            except (ValueError, OverflowError, FloatingPointError):
                ok = False
            if not ok:
                bad, t_event = True, ts[kk]
                continue
            y = ynew
    return Result(ts, E, ED, S, U, y[None, :3], y[None, 3:], np.array([bad]), opts, g,
                  np.array([contact]), np.array([t_event]))


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
    e_final, ed_final: errors at t_final;
    outcome, t_outcome: the case's one outcome (index into OUTCOMES) and its time (s)."""
    t, e, s, u = res.t, res.e, res.s, res.u
    crossed = np.sign(s) != np.sign(s[:1])
    t_reach = _first_true((np.abs(s) <= S_TOL) | crossed, t)
    t_track = track_times(e, t, track_tol)
    dt = res.options.dt
    return {
        "t_reach": t_reach, "t_track": t_track,
        "t_track_all": np.nanmax(np.where(np.isnan(t_track), np.inf, t_track), axis=1),
        "u_peak": np.abs(u).max(axis=0), "effort": np.abs(u).sum(axis=0) * dt,
        "chatter": np.abs(np.diff(u, axis=0)).sum(axis=0),
        "iae": np.abs(e).sum(axis=(0, 2)), "iae_int": np.abs(e).sum(axis=(0, 2)) * dt,
        "e_final": e[-1], "ed_final": res.ed[-1], "nonfinite": res.nonfinite,
        "outcome": res.outcome, "t_outcome": res.t_outcome,
    }


def warmup_kernels() -> list[tuple[str, object]]:
    """The compiled kernels of seed 002, as (name, build): the sampled-data tracking loop's
    kernel with all six variants (``lgw.sim.eros.kernel``), built by flying the paper's
    scenario for two samples through ``simulate_kernel``, and the whole descent's kernel
    (``lgw.sim.eros.descent_kernel``), built by flying the descent for two samples through
    ``simulate_descent`` (the argument types of every run)."""
    from lgw.theory.eros.gains import default_gains

    def build() -> None:
        opts = SimOptions(t_final=2 * P.DT_SAMPLE)
        simulate_kernel(P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], default_gains(),
                        opts, parallel=False)

    def build_descent() -> None:
        from lgw.sim.eros.descent import DescentOptions, descent_gains, simulate_descent
        z = np.zeros((1, 3))
        simulate_descent(z, z, descent_gains(), DescentOptions(t_max=2 * P.DESCENT_DT),
                         parallel=False)

    return [("eros", build), ("eros/descent", build_descent)]
