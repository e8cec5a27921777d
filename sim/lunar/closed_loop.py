"""The closed loop of seed 001 Section 5, batched: plant (1), (2), (27), actuators (24), (26),
(28), the generated law (7)-(11) for the orbit and the attitude loop, the reference (3)-(4).

State per case (30 components, components first, case index last):
   0-6   r, phi, lon, u, v, w, m              translational state of (1)
   7     lambda1 (orbit), 8-10 lambda2 (orbit), 11 d0e (orbit)          (11), (8)
   12-15 Q (scalar first, F_H -> F_B), 16-18 omega (F_B w.r.t. F_H, in F_B)
   19-21 lambda1 (attitude), 22-24 lambda2 (attitude), 25 d0e (attitude)
   26-29 alpha_f, alpha_f', psi_f, psi_f'     command filter of the desired attitude

Departures from the paper, each needed to run it, each documented:
- The desired attitude Q_d comes from the direction of the commanded (saturated) total thrust,
  as the paper says, passed through a second-order command filter (natural frequency
  ``cmd_wn``, damping ``lgw.sim.lunar.parameters.CMD_ZETA``) so that omega_d and omega_d' exist
  and are exact: the paper's (27) needs them but does not say how they are obtained.  The
  default bandwidth and why: ``lgw.sim.lunar.parameters.CMD_WN``.  The filter's input is the
  commanded azimuth the short way round from its state (psi_f + wrap(psi_c - psi_f)): atan2
  is cut at +-pi, and a command crossing the cut would otherwise be a 2 pi step into the
  filter, a full turn of the desired attitude for no change of the command.
- n_do uses the derived sign (claim attitude-27b).
- u_o of (23) is the actual thrust vector (actual T, alpha_B, psi_B from the attitude) minus
  u_norm, so du of (11) contains the pointing error as well as saturation and failure.
- omega_HP' uses the translational accelerations of this instant (known to the navigation
  system through the accelerometers).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from lgw.sim.lunar import laws
from lgw.sim.lunar import parameters as SP
from lgw.sim.lunar import plant as PL
from lgw.sim.lunar.reference import Reference, simplified_rhs
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import Gains, LoopGains

N_STATE = 30
ZETA = SP.CMD_ZETA
SAT_READINGS = ("commanded", "nominal")
FAILURES = ("atan", "step", "none")
POINTINGS = ("coupled", "ideal")
DT_MAX = 0.1  # s: RK4 with F2 up to ~20 1/s (dt * 20 inside RK4's stability interval 2.78)


@dataclass(frozen=True)
class RunOptions:
    """Options of a run (all cases share them), validated on construction (named errors).

    ``dt``: RK4 step, s (default ``lgw.sim.lunar.parameters.DT``: chosen by convergence);
    ``t_end``: horizon, s (default the reference's t_f); ``sat_reading``: the T of (24);
    ``failure``: (26) "atan" as printed, "step" or "none", at ``t_fail`` s (default t_f/2) to
    the fraction ``Ta``; ``thrust_max`` N, ``torque_max`` N m, ``dist_amp`` N m;
    ``cmd_wn``: the command filter's natural frequency, rad/s
    (``lgw.sim.lunar.parameters.CMD_WN``); ``thrust_pointing``: "coupled" (the thrust points
    along the body axis of the simulated attitude (2)) or "ideal" (along the command: the
    orbit loop alone, as (22) treats u_o as the input; the attitude loop still flies,
    decoupled); ``m_dry`` kg: chosen, seed 001 gives none; 1 t below the reference's final
    mass of 3012 kg, so the Section 5 case and its neighbours never reach it: the compiled
    simulator stops a case there, outcome "propellant_exhausted"."""

    dt: float = SP.DT
    t_end: float | None = None
    sat_reading: str = "commanded"
    failure: str = "atan"
    t_fail: float | None = None
    Ta: float = P.T_A
    thrust_max: float = P.T_MAX
    torque_max: float = P.M_MAX
    dist_amp: float = P.DIST_TORQUE_AMP
    cmd_wn: float = SP.CMD_WN
    thrust_pointing: str = "coupled"
    m_dry: float = 2000.0

    def __post_init__(self) -> None:
        import math

        from lgw.theory.errors import ParameterError

        def num(name: str, lo: float, hi: float, lo_open: bool = True,
                none: bool = False) -> None:
            v = getattr(self, name)
            if v is None and none:
                return
            ok = (isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
                  and (v > lo if lo_open else v >= lo) and v <= hi)
            if not ok:
                raise ParameterError(f"RunOptions.{name}", v, f"must be a number in "
                                     f"{'(' if lo_open else '['}{lo:g}, {hi:g}]")

        num("dt", 0.0, DT_MAX)
        num("t_end", 0.0, 1e5, none=True)
        num("t_fail", 0.0, 1e5, lo_open=False, none=True)
        num("Ta", 0.0, 1.0)
        num("thrust_max", 0.0, 1e9)
        num("torque_max", 0.0, 1e9)
        num("dist_amp", 0.0, 1e9, lo_open=False)
        num("cmd_wn", 0.0, 1e3)
        num("m_dry", 0.0, 1e9, lo_open=False)
        for name, allowed in (("sat_reading", SAT_READINGS), ("failure", FAILURES),
                              ("thrust_pointing", POINTINGS)):
            if getattr(self, name) not in allowed:
                raise ParameterError(f"RunOptions.{name}", getattr(self, name),
                                     f"one of {', '.join(allowed)}")


def gain_arrays(gs: list[LoopGains]) -> dict[str, np.ndarray]:
    return {"K1": np.stack([g.K1 for g in gs], axis=-1), "F2": np.stack([g.F2 for g in gs],
            axis=-1), "f3": np.array([g.f3 for g in gs]), "q": np.array([g.q for g in gs])}


@dataclass
class Context:
    ref: Reference
    opts: RunOptions
    go: dict
    ga: dict
    J: np.ndarray  # (3, 1)

    @property
    def tf(self) -> float:
        return self.ref.tf


def make_context(ref: Reference, gains: list[Gains], opts: RunOptions) -> Context:
    return Context(ref, opts, gain_arrays([g.orbit for g in gains]),
                   gain_arrays([g.attitude for g in gains]), P.J_DIAG[:, None])


def desired_direction(total: np.ndarray):
    n = total / np.linalg.norm(total, axis=0)
    return np.arcsin(np.clip(n[2], -1, 1)), np.arctan2(n[1], n[0])


def initial_state(ref: Reference, dh0: np.ndarray, dv0: np.ndarray, Q0: np.ndarray,
                  w0: np.ndarray, gains: list[Gains]) -> np.ndarray:
    """Cases' initial states: reference at t = 0 plus errors (dh0 (N,), dv0 (3, N)), attitude
    Q0 (4, N), omega0 (3, N); virtual states 0 (seed 001 below (11)); d0e(0) from the gains;
    command filter at the nominal direction with the reference's rate."""
    N = dh0.shape[0]
    X = np.zeros((N_STATE, N))
    rs = ref.state(0.0)
    X[0] = rs[0] + dh0
    X[1], X[2] = P.PHI0, P.LON0
    X[3:6] = rs[1:4][:, None] + dv0
    X[6] = rs[4]
    X[11] = [g.orbit.d0e0 for g in gains]
    X[12:16] = Q0 / np.linalg.norm(Q0, axis=0)
    X[16:19] = w0
    X[25] = [g.attitude.d0e0 for g in gains]
    a, p, ad, _ = ref.angles(0.0)
    X[26], X[27], X[28], X[29] = a, ad, p, 0.0
    return X


def field(t: float, X: np.ndarray, ctx: Context, outputs: bool = False):
    """X' of the closed loop at time t; with ``outputs`` also a dict of per-case signals."""
    o = ctx.opts
    y = X[0:7]
    m = X[6]
    lam1o, lam2o, d0eo = X[7], X[8:11], X[11]
    Q, om = X[12:16], X[16:19]
    lam1a, lam2a, d0ea = X[19:22], X[22:25], X[25]
    af, afd, pf, pfd = X[26], X[27], X[28], X[29]
    J = ctx.J
    rs = ctx.ref.state(t)
    alpha_d, psi_d, _, _ = ctx.ref.angles(t)
    unorm = P.T_NOMINAL * np.array([np.cos(alpha_d) * np.cos(psi_d),
                                    np.cos(alpha_d) * np.sin(psi_d), np.sin(alpha_d)])[:, None]
    eh = (y[0] - rs[0])
    ev = y[3:6] - rs[1:4][:, None]
    # orbit loop (22): generated (7)
    uco, z2o, nzo, v2o = laws.orbit_command(eh, ev, lam1o, lam2o, d0eo, m, ctx.go)
    sat = PL.saturate_thrust(uco, unorm, o.thrust_max, o.sat_reading)
    fac = PL.failure_factor(t, ctx.tf, o.failure, o.Ta, o.t_fail)
    total_cmd = sat + unorm
    T = fac * np.linalg.norm(total_cmd, axis=0)
    n_act = (PL.thrust_axis(Q) if o.thrust_pointing == "coupled"
             else total_cmd / np.linalg.norm(total_cmd, axis=0))
    F = -T * n_act
    du_o = (T * n_act - unorm) - uco
    ydot = PL.translational_rhs(y, F, T)
    K1o, F2o = ctx.go["K1"], ctx.go["F2"]
    F1o = K1o[2, 2]
    l1o_dot = -F1o * lam1o - lam2o[2]  # (11a) with f1 = a_h
    l2o_dot = (-np.einsum("ijn,jn->in", F2o, lam2o) + np.array([0 * lam1o, 0 * lam1o, lam1o])
               - du_o / m)  # (11b), B0 = -1/m
    d0eo_dot = ctx.go["q"] * nzo  # (8)
    # command filter of the desired attitude (input: commanded thrust direction)
    ac, pc = desired_direction(total_cmd)
    wn = o.cmd_wn
    afdd = wn * wn * (ac - af) - 2 * ZETA * wn * afd
    dp = pc - pf  # the azimuth error the short way round (atan2 wraps at +-pi)
    pfdd = wn * wn * np.arctan2(np.sin(dp), np.cos(dp)) - 2 * ZETA * wn * pfd
    th, thd, thdd = -af, -afd, -afdd
    Qd = PL.quat_from_yaw_pitch(pf, th)
    wd = np.array([-pfd * np.sin(th), thd, pfd * np.cos(th)])
    wdd = np.array([-pfdd * np.sin(th) - pfd * thd * np.cos(th), thdd,
                    pfdd * np.cos(th) - pfd * thd * np.sin(th)])
    eQ = PL.qmul(PL.qconj(Qd), Q)
    Le = PL.dcm(eQ)
    Lwd = PL.matvec(Le, wd)
    ew = om - Lwd
    LBH = PL.dcm(Q)
    w_hp, w_hp_dot = PL.omega_hp(y, ydot)
    a = PL.matvec(LBH, w_hp)
    adot = PL.matvec(LBH, w_hp_dot)
    Om = om + a
    f2 = (-PL.cross(Om, J * Om) / J - adot + PL.cross(om, a) + PL.cross(ew, Lwd)
          - PL.matvec(Le, wdd))  # known part of (27b), derived
    Jb = np.broadcast_to(J, om.shape)
    Mc, z2a, nza, v2a = laws.attitude_command(eQ[0], eQ[1:], ew, lam1a, lam2a, d0ea, f2, Jb,
                                              ctx.ga)
    M = PL.saturate_torque(Mc, o.torque_max)
    dM = PL.disturbance_torque(t, o.dist_amp)
    Qdot, omdot = PL.attitude_rates(Q, om, J, a, adot, M + dM)
    du_a = M - Mc
    e0, ev_ = eQ[0], eQ[1:]
    f1 = 0.5 * (e0 * np.eye(3)[:, :, None] + PL.skew(ev_))
    K1a, F2a = ctx.ga["K1"], ctx.ga["F2"]
    F1a = np.einsum("ijn,jkn,lkn->iln", f1, K1a, f1)
    l1a_dot = -PL.matvec(F1a, lam1a) + PL.matvec(f1, lam2a)
    l2a_dot = (-PL.matvec(F2a, lam2a) - np.einsum("jin,jn->in", f1, lam1a) + du_a / J)
    d0ea_dot = ctx.ga["q"] * nza
    Xd = np.concatenate([ydot, l1o_dot[None], l2o_dot, d0eo_dot[None], Qdot, omdot, l1a_dot,
                         l2a_dot, d0ea_dot[None], afd[None], afdd[None], pfd[None],
                         pfdd[None]], axis=0)
    if not outputs:
        return Xd
    # the lumped disturbance of (22b), d_o = e_v' - B0 u_o = e_v' + u_o/m, along the run
    Vd_dot = simplified_rhs(t, rs, ctx.ref.a1, ctx.ref.a2, ctx.ref.a3)[1:4]
    d_o = (ydot[3:6] - Vd_dot[:, None]) + (T * n_act - unorm) / m
    out = {"eh": eh, "ev": ev, "d_orbit": d_o, "eq": eQ, "ew": ew, "thrust": T, "force": F,
           "thrust_cmd": np.linalg.norm(uco + unorm, axis=0), "torque": M, "torque_cmd": Mc,
           "orbit_saturated": np.linalg.norm(uco + unorm, axis=0) >= o.thrust_max,
           "torque_saturated": np.any(np.abs(Mc) >= o.torque_max, axis=0),
           "d0e_orbit": d0eo, "d0e_attitude": d0ea,
           "z1o": eh - lam1o, "z2o": z2o, "z1a": eQ[1:] - lam1a, "z2a": z2a,
           "V2o_part": v2o, "V2a_part": v2a,
           "Vlam_o": 0.5 * (lam1o ** 2 + np.sum(lam2o ** 2, axis=0)),
           "Vlam_a": 0.5 * (np.sum(lam1a ** 2, axis=0) + np.sum(lam2a ** 2, axis=0)),
           "B0du_o": -du_o / m, "B0du_a": du_a / J, "lam1o": lam1o, "lam2o": lam2o,
           "lam1a": lam1a, "lam2a": lam2a, "height": y[0] - P.R_MOON,
           "quat_norm_err": np.abs(np.linalg.norm(Q, axis=0) - 1.0), "failure_factor": fac}
    return Xd, out
