"""Seed 001's plant and law as python-control nonlinear I/O blocks (``control.nlsys``).

    P = plant()                  rigid body (1), (27): states r, phi, lon, u, v, w, m, Q, omega
    C = law(paper_gains())       the generated law (7)-(11), both loops, with the actuators
    loop = closed_loop(paper_gains())        # control.interconnect([P, C]) by signal name
    resp = control.input_output_response(loop, T, X0=initial_state(), params={"orbit_q": 0.02})

The blocks are the closed loop of ``lgw.sim.lunar.closed_loop.field`` cut at the applied
thrust and torque: the plant integrates the translational dynamics (1) in polar form with the
mass flow and the attitude dynamics (27) under the applied thrust vector F (N, in F_H) and the
applied torque M (N m, body axes), plus the Section 5 disturbance torque; the law block holds
everything on the vehicle's side of that cut: the orbit and attitude laws (7)-(11) with their
virtual (lambda) and adaptive (d0e) states, the command filter of the desired attitude, and the
actuators (saturation (24), failure (26), pointing (2), torque saturation (28)).  The actuators
sit in the law block, not the plant, because the law's filter (11) reads du, the applied minus
the commanded input, in the same instant: split there, python-control's interconnection would
need more fixed-point passes than it makes (it reports an algebraic loop).

Gains are params: ``<loop>_K1_<i><j>``, ``<loop>_F2_<i><j>``, ``<loop>_f3``, ``<loop>_q``
(loop orbit or attitude, i, j in 0..2); ``d0e0`` is an initial state (``initial_state``).
State order: the plant's 14 then the law's 16 make ``closed_loop.N_STATE`` = 30, the same order
as ``lgw.sim.lunar.closed_loop.initial_state``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import control
import numpy as np
from lgw.sim.lunar import plant as PL
from lgw.sim.lunar.closed_loop import Context, RunOptions, field, make_context
from lgw.sim.lunar.closed_loop import initial_state as _initial_state
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import Gains, LoopGains

PLANT_STATES = ("r", "phi", "lon", "u", "v", "w", "m", "q0", "q1", "q2", "q3", "wx", "wy", "wz")
LAW_STATES = ("lam1_o", "lam2_o1", "lam2_o2", "lam2_o3", "d0e_o", "lam1_a1", "lam1_a2",
              "lam1_a3", "lam2_a1", "lam2_a2", "lam2_a3", "d0e_a", "alpha_f", "alpha_f_dot",
              "psi_f", "psi_f_dot")
FORCES = ("Fx", "Fy", "Fz")  # applied thrust, N, in F_H
TORQUES = ("Mx", "My", "Mz")  # applied control torque, N m, body axes
LOOPS = ("orbit", "attitude")
# the law block's states inside closed_loop's 30-vector (its own order: orbit, attitude, filter)
_LAW_INDEX = np.r_[7:12, 19:26, 26:30]
_PLANT_INDEX = np.r_[0:7, 12:19]


def gain_params(g: Gains) -> dict[str, float]:
    """A gain set as python-control params (names in the module docstring)."""
    out: dict[str, float] = {}
    for loop in LOOPS:
        lg: LoopGains = getattr(g, loop)
        for mat in ("K1", "F2"):
            M = np.asarray(getattr(lg, mat), float)
            out.update({f"{loop}_{mat}_{i}{j}": float(M[i, j]) for i in range(3)
                        for j in range(3)})
        out[f"{loop}_f3"] = float(lg.f3)
        out[f"{loop}_q"] = float(lg.q)
    return out


def gains_of(params: dict[str, Any], base: Gains) -> Gains:
    """The gain set of ``params`` (absent names from ``base``)."""
    loops = {}
    for loop in LOOPS:
        lg: LoopGains = getattr(base, loop)
        mats = {m: np.array([[float(params.get(f"{loop}_{m}_{i}{j}", getattr(lg, m)[i][j]))
                              for j in range(3)] for i in range(3)]) for m in ("K1", "F2")}
        loops[loop] = replace(lg, K1=mats["K1"], F2=mats["F2"],
                              f3=float(params.get(f"{loop}_f3", lg.f3)),
                              q=float(params.get(f"{loop}_q", lg.q)))
    return Gains(loops["orbit"], loops["attitude"])


def initial_state(g: Gains, ref: Any = None, dh0: float = P.DH0, dv0: Any = None,
                  q0: Any = None) -> np.ndarray:
    """[plant's 14, law's 16] initial state of one case (default: the Section 5 case)."""
    from lgw.sim.lunar.reference import reference

    ref = reference() if ref is None else ref
    dv0 = P.DV0 if dv0 is None else np.asarray(dv0, float)
    q0 = P.Q0 if q0 is None else np.asarray(q0, float)
    X = _initial_state(ref, np.array([dh0]), dv0[:, None], q0[:, None], np.zeros((3, 1)), [g])
    return to_blocks(X[:, 0])


def to_blocks(x30: np.ndarray) -> np.ndarray:
    """closed_loop's 30-state order -> [plant's 14, law's 16]."""
    return np.concatenate([x30[_PLANT_INDEX], x30[_LAW_INDEX]])


def from_blocks(x: np.ndarray) -> np.ndarray:
    """[plant's 14, law's 16] -> closed_loop's 30-state order."""
    out = np.empty(30)
    out[_PLANT_INDEX] = x[:14]
    out[_LAW_INDEX] = x[14:30]
    return out


def plant(*, dist_amp: float = P.DIST_TORQUE_AMP, name: str = "lunar_plant"
          ) -> control.NonlinearIOSystem:
    """Seed 001's vehicle: translational dynamics (1) with the mass flow, attitude (27) with
    the Section 5 disturbance torque (params ``dist_amp``, N m); inputs F (N, F_H), M (N m);
    outputs its states."""
    J = P.J_DIAG[:, None]

    def updfcn(t, x, u, params):
        y, Q, om = x[:7, None], x[7:11, None], x[11:14, None]
        F, M = np.asarray(u[:3], float)[:, None], np.asarray(u[3:6], float)[:, None]
        T = np.linalg.norm(F, axis=0)
        ydot = PL.translational_rhs(y, F, T)
        w_hp, w_hp_dot = PL.omega_hp(y, ydot)
        LBH = PL.dcm(Q)
        a, adot = PL.matvec(LBH, w_hp), PL.matvec(LBH, w_hp_dot)
        dM = PL.disturbance_torque(t, float(params.get("dist_amp", dist_amp)))
        Qdot, omdot = PL.attitude_rates(Q, om, J, a, adot, M + dM)
        return np.concatenate([ydot[:, 0], Qdot[:, 0], omdot[:, 0]])

    return control.nlsys(updfcn, lambda t, x, u, params: np.asarray(x, float),
                         inputs=FORCES + TORQUES, outputs=PLANT_STATES, states=PLANT_STATES,
                         name=name, params={"dist_amp": float(dist_amp)})


def law(g: Gains, opts: RunOptions | None = None, *, ref: Any = None, name: str = "lunar_law"
        ) -> control.NonlinearIOSystem:
    """The orbit and attitude laws (7)-(11), the command filter and the actuators of
    ``lgw.sim.lunar.closed_loop.field`` (``opts``: saturation reading, failure, pointing,
    limits; ``ref``: the reference trajectory, solved once); inputs the plant's states, outputs
    the applied F and M; gains as params (``gain_params``).  It evaluates ``field`` itself on
    the whole state (the plant's from its inputs, its own) and keeps the vehicle's side: one
    closed loop, written once."""
    from lgw.sim.lunar.reference import reference

    ref = reference() if ref is None else ref
    opts = RunOptions() if opts is None else opts
    cache: dict[tuple, Context] = {}

    def ctx_for(params: dict[str, Any]) -> Context:
        key = tuple(sorted((k, v) for k, v in params.items()))
        if key not in cache:
            cache.clear()
            cache[key] = make_context(ref, [gains_of(params, g)], opts)
        return cache[key]

    def whole(x, u) -> np.ndarray:
        return from_blocks(np.concatenate([np.asarray(u, float), np.asarray(x, float)]))[:, None]

    def updfcn(t, x, u, params):
        if not _vehicle(u):
            return np.zeros(len(LAW_STATES))
        return field(t, whole(x, u), ctx_for(params))[_LAW_INDEX, 0]

    def outfcn(t, x, u, params):
        if not _vehicle(u):
            return np.zeros(6)
        _, out = field(t, whole(x, u), ctx_for(params), outputs=True)
        return np.concatenate([out["force"][:, 0], out["torque"][:, 0]])

    return control.nlsys(updfcn, outfcn, inputs=PLANT_STATES, outputs=FORCES + TORQUES,
                         states=LAW_STATES, name=name, params=gain_params(g))


def _vehicle(u: Any) -> bool:
    """A physical vehicle state (python-control's first pass through an interconnection
    evaluates the blocks at zero inputs: r = m = 0 and a zero quaternion)."""
    u = np.asarray(u, float)
    return bool(u[0] > 0 and u[6] > 0 and np.linalg.norm(u[7:11]) > 0)


def closed_loop(g: Gains, opts: RunOptions | None = None, *, ref: Any = None
                ) -> control.InterconnectedSystem:
    """``plant()`` and ``law(g, opts)`` interconnected by signal name; outputs the plant's
    states (no external input: the disturbance torque is the plant's)."""
    from lgw.sim.lunar.reference import reference

    ref = reference() if ref is None else ref
    opts = RunOptions() if opts is None else opts
    return control.interconnect([plant(dist_amp=opts.dist_amp), law(g, opts, ref=ref)],
                                inputs=[], outputs=list(PLANT_STATES), name="lunar_loop")
