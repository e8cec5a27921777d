"""Seed 001's client of the generic integrator (``lgw.sim.integrate``): the closed loop of
Section 5 (``lgw.sim.lunar.closed_loop.field``, the same equations) as hooks of a compiled kernel.

The law (7) of both loops is generated from the SymPy expressions of ``lgw.theory.lunar.law``
(the expressions whose V2' is checked against (13)) by ``lgw.sim.codegen.vector_source``:
``orbit_uc``, ``orbit_z2``, ``orbit_v2`` and ``attitude_uc``, ``attitude_z2``, ``attitude_v2``.
The plant (1), (2), (27) and the actuators (24), (26), (28) are the scalar form of
``lgw.sim.lunar.plant`` (numpy, batched), which stays as the independent route the tests
compare against.  The reference (3)-(4) is evaluated from the BVP's piecewise cubic
(``Reference.spline``), exactly as ``Reference.state``.

State y (30): as ``lgw.sim.lunar.closed_loop`` (r, phi, lon, u, v, w, m; orbit lambda1,
lambda2, d0e; Q, omega; attitude lambda1, lambda2, d0e; command filter).  Auxiliary outputs X
(``AUX`` below, NX): the sampled signals, recorded at every node with record=True; the
generated law writes into slices of X (no allocation per call).

Per-case inputs C = (X0 (N, 30), K1o, F2o (N, 3, 3), f3o, qo (N), K1a, F2a, f3a, qa); shared
Q = (spline x, spline c, a1, a2, a3, tf, T_max, M_max, sat code, failure code, T_a, t_c,
dist_amp, cmd_wn, pointing code, J (3), m_dry, quaternion-norm tolerance); results R =
``RESULT_FIELDS``.

Events of a step (``sys_step``), the earliest wins: r below the lunar surface R_MOON and the mass
at m_dry are located inside the step (bisection on the cubic Hermite interpolant, STOP_INSIDE);
the quaternion norm drifting more than the tolerance from 1 is detected at the node
(STOP_AT_NODE).  Non-finite states are the integrator's (``nonfinite``).
"""

from __future__ import annotations

import functools
import math

import numba
import numpy as np
import sympy as sp
from lgw.theory.lunar import parameters as P

NY = 30
# auxiliary outputs: name -> (first slot, size)
AUX = {"eh": (0, 1), "ev": (1, 3), "d_orbit": (4, 3), "eq": (7, 4), "ew": (11, 3),
       "thrust": (14, 1), "thrust_cmd": (15, 1), "torque": (16, 3), "torque_cmd": (19, 3),
       "orbit_saturated": (22, 1), "torque_saturated": (23, 1), "z1o": (24, 1),
       "z2o": (25, 3), "z1a": (28, 3), "z2a": (31, 3), "V2o_part": (34, 1),
       "V2a_part": (35, 1), "B0du_o": (36, 3), "B0du_a": (39, 3), "height": (42, 1),
       "quat_norm_err": (43, 1), "failure_factor": (44, 1), "uco": (45, 3), "nzo": (48, 1),
       "nza": (49, 1), "f2a": (50, 3), "lam_sq": (56, 4)}
# after the sampled signals: over the rhs calls of the current step attempt (reset at its
# first stage), the max delivered thrust (53) and the max commanded magnitude (54)
XPKT = 53
XPKTC = 54
# 1.0 if a rhs call of the current step attempt asked for a blown-up command (sys_rhs)
XBLOWN = 55
# lam_sq: |lambda1|^2, |lambda2|^2 of the orbit filter (11), then of the attitude filter (the
# integrands of the measured ||lambda||_L2 that (18) bounds)
NX = 60
# outcome codes (names in lgw.sim.lunar.outcomes.OUTCOMES)
COMPLETED, SURFACE, DRY, QUAT, NONFINITE, STEPLIM, BLOWN, BELOW = range(8)
# A delivered thrust above BLOWUP_ACCEL m0 (N; m0 the case's initial mass) is no thrust (1e5
# m/s^2, ~10^4 g, as seed 000's lgw.sim.mars.batch.BLOWUP_ACCEL; the Section 5 case asks for
# ~7 m/s^2): a step whose stage asks for it (or for any thrust at a mass <= 0) is far too large
# for the dynamics, and an event located on its interpolant is meaningless (found by
# benchmarks/adversarial_lunar.py: "propellant exhausted" after one step at -3.5e14 kg, stage
# thrusts of 1e35 N with the "nominal" reading of (24), which does not limit the thrust)
BLOWUP_ACCEL = 1e5
# tracker slots
(PKT, PKTC, PKM, TSO, TSA, NENT, TENT, TEXIT, TFAIL, TEXC, V2OMAX, V2AMAX, HMIN, OUT, TOUT,
 PKTS, PKTCS, TAI, TAFT, TSOAF, PKTCAF, EHMAX, EVMAX, EHMAXAF, MINEQ0, L2BO, L2BA, TSAI,
 TSAE, TSAIO, L2L1O, L2L2O, L2L1A, L2L2A) = range(34)
NS = 34
# peak_thrust, peak_thrust_cmd: at the nodes (t = 0 and each accepted step's left node);
# peak_thrust_stages, peak_thrust_cmd_stages: also over every rhs evaluation of those steps
# (trial states and new node; >= the node peaks), as seed 000 (lgw.sim.mars.batch)
# time_saturated_orbit_after_failure, peak_thrust_cmd_after_failure, max_abs_eh_after_failure:
# over the accepted nodes from t_after (C) on (NaN: the case stopped before t_after);
# max_abs_eh, max_abs_ev, min_abs_eq0: over the accepted nodes (the Monte Carlo statistics, no
# records); B0du_orbit_L2, B0du_attitude_L2: sqrt of the integral of |B0 du|^2 over the flight
# (trapezoidal rule on every accepted step; the inputs of (18)); lambda1_orbit_L2, ...,
# lambda2_attitude_L2: the same for the filter states (11) (the outputs (18) bounds);
# time_saturated_torque_initial: the length of the torque saturation that starts at t = 0 (0 s
# when the command starts within its limit); torque_saturation_end: the time from which the
# torque command stays within its limit (0 s: never saturated).  A step counts as saturated
# when its left node is (as time_saturated_torque).  Unlike the total time saturated, both
# converge when the relay of (7) makes the command chatter across the limit
# (lgw.sim.lunar.parameters, DT)
RESULT_FIELDS = ("outcome", "t_outcome", "peak_thrust", "peak_thrust_cmd", "peak_torque",
                 "time_saturated_orbit", "time_saturated_torque", "sat_entries",
                 "sat_first_entry", "sat_last_exit", "t_failure", "thrust_excess_saturated",
                 "V2o_part_max", "V2a_part_max", "min_height", "peak_thrust_stages",
                 "peak_thrust_cmd_stages", "time_saturated_orbit_after_failure",
                 "peak_thrust_cmd_after_failure", "max_abs_eh", "max_abs_ev",
                 "max_abs_eh_after_failure", "min_abs_eq0", "B0du_orbit_L2",
                 "B0du_attitude_L2", "time_saturated_torque_initial", "torque_saturation_end",
                 "lambda1_orbit_L2", "lambda2_orbit_L2", "lambda1_attitude_L2",
                 "lambda2_attitude_L2")
ZETA = 0.9  # damping of the desired-attitude command filter (lgw.sim.lunar.closed_loop.ZETA)
TINY = 1e-150  # ||z2|| floor of the adaptive term (lgw.sim.lunar.laws.TINY)


# --- generated law ------------------------------------------------------------------------

def _loop_sources(prefix: str, S, extra: list[tuple[str, object]]) -> list[tuple[str, str]]:
    from lgw.sim.codegen import vector_source
    args = [("x1", S.x1), ("x2", S.x2), ("lam1", S.lam1), ("lam2", S.lam2), ("d0e", S.d0e),
            *extra, ("K1", S.K1), ("F2", S.F2), ("f3", S.f3), ("nz", S.nz)]
    v2 = ((S.z1.T * S.z1)[0] + (S.z2.T * S.z2)[0]) / 2
    return [(f"{prefix}_uc", vector_source(f"{prefix}_uc", args, S.uc)),
            (f"{prefix}_z2", vector_source(f"{prefix}_z2", args, S.z2)),
            (f"{prefix}_v2", vector_source(f"{prefix}_v2", args, v2))]


@functools.cache
def law_functions() -> list[tuple[str, str]]:
    """(name, source) of the generated law of both loops (seed 001 (7), (9), (10), (12))."""
    from lgw.theory.lunar import law as L
    So = L.orbit_system(full=True)
    Sa = L.attitude_system()
    J = sp.Matrix(sp.symbols("J_1:4", positive=True))
    return (_loop_sources("orbit", So, [("m", sp.Symbol("m", positive=True))])
            + _loop_sources("attitude", Sa, [("e_q0", sp.Symbol("e_q0", real=True)),
                                              ("f2", Sa.f2), ("J", J)]))


def law_header() -> str:
    from lgw.sim.codegen import VECTOR_IMPORTS
    from lgw.sim.integrate import callee_source
    return "\n".join([*VECTOR_IMPORTS[1:], "", *callee_source(law_functions())])


# --- compiled plant helpers (seed 001 (1), (2), (27); lgw.sim.lunar.plant) ------------------

@numba.njit(error_model="numpy", inline="always", cache=True)
def _qmul(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product, scalar first (lgw.sim.lunar.plant.qmul)."""
    return (a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
            a0 * b1 + b0 * a1 + a2 * b3 - a3 * b2,
            a0 * b2 + b0 * a2 + a3 * b1 - a1 * b3,
            a0 * b3 + b0 * a3 + a1 * b2 - a2 * b1)


@numba.njit(error_model="numpy", inline="always", cache=True)
def _dcm(q0, q1, q2, q3):
    """L(q) row by row (lgw.sim.lunar.plant.dcm): 2 v v^T + (q0^2 - v^T v) I - 2 q0 S(v)."""
    n = q0 * q0 - (q1 * q1 + q2 * q2 + q3 * q3)
    return (2 * q1 * q1 + n, 2 * q1 * q2 + 2 * q0 * q3, 2 * q1 * q3 - 2 * q0 * q2,
            2 * q2 * q1 - 2 * q0 * q3, 2 * q2 * q2 + n, 2 * q2 * q3 + 2 * q0 * q1,
            2 * q3 * q1 + 2 * q0 * q2, 2 * q3 * q2 - 2 * q0 * q1, 2 * q3 * q3 + n)


@numba.njit(error_model="numpy", inline="always", cache=True)
def _mv(L, x0, x1, x2):
    return (L[0] * x0 + L[1] * x1 + L[2] * x2, L[3] * x0 + L[4] * x1 + L[5] * x2,
            L[6] * x0 + L[7] * x1 + L[8] * x2)


@numba.njit(error_model="numpy", inline="always", cache=True)
def _cross(a0, a1, a2, b0, b1, b2):
    return (a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0)


@numba.njit(error_model="numpy", cache=True)
def _spline(sx, sc, tau, k):
    """Component k of the reference's piecewise cubic at tau (scipy PPoly: highest power
    first; tau outside [0, 1] is clipped by the caller)."""
    j = np.searchsorted(sx, tau, side="right") - 1
    if j < 0:
        j = 0
    if j > sx.shape[0] - 2:
        j = sx.shape[0] - 2
    d = tau - sx[j]
    return ((sc[0, j, k] * d + sc[1, j, k]) * d + sc[2, j, k]) * d + sc[3, j, k]


# --- templates ----------------------------------------------------------------------------

def sys_init(i, C, Q, y, S):  # noqa: N803
    X0 = C[0]
    for j in range(NY):  # noqa: F821
        y[j] = X0[i, j]
    S[PKT] = 0.0  # noqa: F821
    S[PKTC] = 0.0  # noqa: F821
    S[PKTS] = 0.0  # noqa: F821
    S[PKTCS] = 0.0  # noqa: F821
    S[PKM] = 0.0  # noqa: F821
    S[TSO] = 0.0  # noqa: F821
    S[TSA] = 0.0  # noqa: F821
    S[NENT] = 0.0  # noqa: F821
    S[TENT] = math.nan  # noqa: F821
    S[TEXIT] = math.nan  # noqa: F821
    S[TFAIL] = math.nan  # noqa: F821
    S[TEXC] = -math.inf  # noqa: F821
    S[V2OMAX] = -math.inf  # noqa: F821
    S[V2AMAX] = -math.inf  # noqa: F821
    S[HMIN] = y[0] - R_MOON  # noqa: F821
    S[OUT] = COMPLETED  # noqa: F821
    S[TOUT] = math.nan  # noqa: F821
    S[TAI] = C[9][i]  # noqa: F821  (this case's T_a, for the failure-time level)
    S[TAFT] = C[11][i]  # noqa: F821
    S[TSOAF] = math.nan  # noqa: F821
    S[PKTCAF] = math.nan  # noqa: F821
    S[EHMAX] = 0.0  # noqa: F821
    S[EVMAX] = 0.0  # noqa: F821
    S[EHMAXAF] = math.nan  # noqa: F821
    S[MINEQ0] = math.inf  # noqa: F821
    S[L2BO] = 0.0  # noqa: F821
    S[L2BA] = 0.0  # noqa: F821
    S[TSAI] = 0.0  # noqa: F821
    S[TSAE] = 0.0  # noqa: F821
    S[TSAIO] = 1.0  # noqa: F821  (the initial saturation is still running)
    S[L2L1O] = 0.0  # noqa: F821
    S[L2L2O] = 0.0  # noqa: F821
    S[L2L1A] = 0.0  # noqa: F821
    S[L2L2A] = 0.0  # noqa: F821


def sys_rhs(t, Y, yr, K, kr, X, i, C, Q):  # noqa: N803
    """The closed loop (lgw.sim.lunar.closed_loop.field, term by term) at (t, Y[yr])."""
    X0, K1o, F2o, f3o, qo, K1a, F2a, f3a, qa, TaC, tcC, taftC = C
    Ta = TaC[i]
    tc = tcC[i]
    (sx, sc, a1, a2, a3, tf, Tmax, Mmax, satc, failc, damp, wn, pointc, J, m_dry,
     qtol) = Q
    y = Y[yr]
    r, phi, u, v, w, m = y[0], y[1], y[3], y[4], y[5], y[6]
    # reference (3)-(4): state from the BVP spline, steering angles in closed form
    tcl = min(max(t, 0.0), tf)
    tau = tcl / tf
    rs0 = _spline(sx, sc, tau, 0)  # noqa: F821
    rs1 = _spline(sx, sc, tau, 1)  # noqa: F821
    rs2 = _spline(sx, sc, tau, 2)  # noqa: F821
    rs3 = _spline(sx, sc, tau, 3)  # noqa: F821
    rs4 = _spline(sx, sc, tau, 4)  # noqa: F821
    alpha_d = math.atan(a2 * tcl + a3)
    psi_d = math.atan(a1)
    un0 = T_NOMINAL * math.cos(alpha_d) * math.cos(psi_d)  # noqa: F821
    un1 = T_NOMINAL * math.cos(alpha_d) * math.sin(psi_d)  # noqa: F821
    un2 = T_NOMINAL * math.sin(alpha_d)  # noqa: F821
    X[0] = r - rs0
    X[1] = u - rs1
    X[2] = v - rs2
    X[3] = w - rs3
    # orbit loop (22): the generated (7); z2 does not depend on f3 or ||z2||
    orbit_z2(X[0:1], X[1:4], y[7:8], y[8:11], y[11], m, K1o[i], F2o[i], 0.0, 1.0,  # noqa: F821
             X[25:28])
    nzo = math.sqrt(X[25] * X[25] + X[26] * X[26] + X[27] * X[27])
    nzs = max(nzo, TINY)  # noqa: F821
    X[48] = nzo
    orbit_uc(X[0:1], X[1:4], y[7:8], y[8:11], y[11], m, K1o[i], F2o[i], f3o[i], nzs,  # noqa: F821
             X[45:48])
    orbit_v2(X[0:1], X[1:4], y[7:8], y[8:11], y[11], m, K1o[i], F2o[i], f3o[i], nzs,  # noqa: F821
             X[34:35])
    X[24] = X[0] - y[7]
    uc0 = X[45]
    uc1 = X[46]
    uc2 = X[47]
    # (24) thrust saturation
    tot0 = uc0 + un0
    tot1 = uc1 + un1
    tot2 = uc2 + un2
    mag = math.sqrt(tot0 * tot0 + tot1 * tot1 + tot2 * tot2)
    Tread = mag if satc == 0 else T_NOMINAL  # noqa: F821  (|u_norm| = T_d)
    if mag >= Tmax:
        den = Tread if Tread > 0 else 1.0
        s0 = tot0 * Tmax / den - un0
        s1 = tot1 * Tmax / den - un1
        s2 = tot2 * Tmax / den - un2
    else:
        s0 = uc0
        s1 = uc1
        s2 = uc2
    # (26) failure
    if failc == 2:
        fac = 1.0
    elif failc == 1:
        fac = 1.0 if t <= tc else Ta
    else:
        fac = (1 + Ta) / 2 * (1 - 2 / math.pi * (1 - Ta) / (1 + Ta) * math.atan(2 * t - tc))
    c0 = s0 + un0
    c1 = s1 + un1
    c2 = s2 + un2
    cn = math.sqrt(c0 * c0 + c1 * c1 + c2 * c2)
    T = fac * cn
    # a blown-up command (BLOWUP_ACCEL): the step that asked for it is never accepted (sys_step
    # ends the case at its start), so the stage gets a finite stand-in, no thrust
    blown = not (T <= BLOW_ACC * X0[i, 6]) or not (m > 0.0)  # noqa: F821
    if blown:
        T = 0.0
    q0 = y[12]
    q1 = y[13]
    q2 = y[14]
    q3 = y[15]
    LBH = _dcm(q0, q1, q2, q3)  # noqa: F821
    if pointc == 0:  # coupled: the body x axis, n = L_BH^T e_x (2)
        n0 = LBH[0]
        n1 = LBH[1]
        n2 = LBH[2]
    else:
        n0 = c0 / cn
        n1 = c1 / cn
        n2 = c2 / cn
    F0 = -T * n0
    F1 = -T * n1
    F2 = -T * n2
    du0 = (T * n0 - un0) - uc0
    du1 = (T * n1 - un1) - uc1
    du2 = (T * n2 - un2) - uc2
    # (1a)-(1g)
    tp = math.tan(phi)
    yd0 = -w
    yd1 = u / r
    yd3 = -v * v / r * tp + u * w / r + F0 / m
    yd4 = u * v / r * tp + v * w / r + F1 / m
    yd5 = -(u * u + v * v) / r + MU_MOON / r ** 2 + F2 / m  # noqa: F821
    K[kr, 0] = yd0
    K[kr, 1] = yd1
    K[kr, 2] = v / (r * math.cos(phi))
    K[kr, 3] = yd3
    K[kr, 4] = yd4
    K[kr, 5] = yd5
    K[kr, 6] = -T / (ISP * G0)  # noqa: F821
    # (11a), (11b) with f1 = a_h = [0, 0, -1], B0 = -I/m; (8)
    K[kr, 7] = -K1o[i, 2, 2] * y[7] - y[10]
    for a in range(3):
        acc = 0.0
        for b in range(3):
            acc += F2o[i, a, b] * y[8 + b]
        K[kr, 8 + a] = -acc
    K[kr, 10] += y[7]
    K[kr, 8] -= du0 / m
    K[kr, 9] -= du1 / m
    K[kr, 10] -= du2 / m
    K[kr, 11] = qo[i] * nzo
    X[36] = -du0 / m
    X[37] = -du1 / m
    X[38] = -du2 / m
    # command filter of the desired attitude (input: the commanded thrust direction)
    af = y[26]
    afd = y[27]
    pf = y[28]
    pfd = y[29]
    ac = math.asin(min(max(c2 / cn, -1.0), 1.0))
    pc = math.atan2(c1 / cn, c0 / cn)
    afdd = wn * wn * (ac - af) - 2 * ZETA * wn * afd  # noqa: F821
    dp = pc - pf  # the azimuth error the short way round: atan2 wraps at +-pi
    dp = math.atan2(math.sin(dp), math.cos(dp))
    pfdd = wn * wn * dp - 2 * ZETA * wn * pfd  # noqa: F821
    th = -af
    thd = -afd
    thdd = -afdd
    cy = math.cos(pf / 2)
    sy = math.sin(pf / 2)
    cp = math.cos(th / 2)
    sp_ = math.sin(th / 2)
    sth = math.sin(th)
    cth = math.cos(th)
    wd0 = -pfd * sth
    wd1 = thd
    wd2 = pfd * cth
    wdd0 = -pfdd * sth - pfd * thd * cth
    wdd1 = thdd
    wdd2 = pfdd * cth - pfd * thd * sth
    # e_Q = Q_d^* (x) Q, Q_d from yaw pf and pitch th (3-2-1, roll 0)
    e0, e1, e2, e3 = _qmul(cy * cp, sy * sp_, -cy * sp_, -sy * cp, q0, q1, q2, q3)  # noqa: F821
    X[7] = e0
    X[8] = e1
    X[9] = e2
    X[10] = e3
    Le = _dcm(e0, e1, e2, e3)  # noqa: F821
    lw0, lw1, lw2 = _mv(Le, wd0, wd1, wd2)  # noqa: F821
    om0 = y[16]
    om1 = y[17]
    om2 = y[18]
    X[11] = om0 - lw0
    X[12] = om1 - lw1
    X[13] = om2 - lw2
    # omega_HP and its rate (lgw.sim.lunar.plant.omega_hp)
    cph = math.cos(phi)
    sec2 = 1.0 / (cph * cph)
    wh0 = v / r
    wh1 = -u / r
    wh2 = -v * tp / r
    dw0 = yd4 / r - v * yd0 / r ** 2
    dw1 = -yd3 / r + u * yd0 / r ** 2
    dw2 = -(yd4 * tp + v * sec2 * yd1) / r + v * tp * yd0 / r ** 2
    A0, A1, A2 = _mv(LBH, wh0, wh1, wh2)  # noqa: F821
    D0, D1, D2 = _mv(LBH, dw0, dw1, dw2)  # noqa: F821
    O0 = om0 + A0
    O1 = om1 + A1
    O2 = om2 + A2
    g0, g1, g2 = _cross(O0, O1, O2, J[0] * O0, J[1] * O1, J[2] * O2)  # noqa: F821
    h0, h1, h2 = _cross(om0, om1, om2, A0, A1, A2)  # noqa: F821
    k0, k1, k2 = _cross(X[11], X[12], X[13], lw0, lw1, lw2)  # noqa: F821
    ld0, ld1, ld2 = _mv(Le, wdd0, wdd1, wdd2)  # noqa: F821
    # the known part of (27b), derived (claim attitude-27b)
    X[50] = -g0 / J[0] - D0 + h0 + k0 - ld0
    X[51] = -g1 / J[1] - D1 + h1 + k1 - ld1
    X[52] = -g2 / J[2] - D2 + h2 + k2 - ld2
    # attitude loop (27): the generated (7)
    attitude_z2(X[8:11], X[11:14], y[19:22], y[22:25], y[25], e0, X[50:53], J,  # noqa: F821
                K1a[i], F2a[i], 0.0, 1.0, X[31:34])
    nza = math.sqrt(X[31] * X[31] + X[32] * X[32] + X[33] * X[33])
    nzsa = max(nza, TINY)  # noqa: F821
    X[49] = nza
    attitude_uc(X[8:11], X[11:14], y[19:22], y[22:25], y[25], e0, X[50:53], J,  # noqa: F821
                K1a[i], F2a[i], f3a[i], nzsa, X[19:22])
    attitude_v2(X[8:11], X[11:14], y[19:22], y[22:25], y[25], e0, X[50:53], J,  # noqa: F821
                K1a[i], F2a[i], f3a[i], nzsa, X[35:36])
    for a in range(3):
        X[28 + a] = X[8 + a] - y[19 + a]
    # (28) torque saturation, the disturbance torque of Section 5
    tsat = False
    for a in range(3):
        mc = X[19 + a]
        X[16 + a] = Mmax if mc > Mmax else (-Mmax if mc < -Mmax else mc)
        if abs(mc) >= Mmax:
            tsat = True
        X[39 + a] = (X[16 + a] - mc) / J[a]
    M0 = X[16] + damp * math.cos(t)
    M1 = X[17] + damp * math.sin(t)
    M2 = X[18] + damp * math.cos(2 * t)
    # Euler's equation for Omega = omega + a, quaternion kinematics
    K[kr, 16] = (-g0 + M0) / J[0] - D0 + h0
    K[kr, 17] = (-g1 + M1) / J[1] - D1 + h1
    K[kr, 18] = (-g2 + M2) / J[2] - D2 + h2
    p0, p1, p2, p3 = _qmul(q0, q1, q2, q3, 0.0, om0, om1, om2)  # noqa: F821
    K[kr, 12] = 0.5 * p0
    K[kr, 13] = 0.5 * p1
    K[kr, 14] = 0.5 * p2
    K[kr, 15] = 0.5 * p3
    # (11a), (11b) of the attitude loop: f1 = (e0 I + S(e))/2, F1 = f1 K1 f1^T, B0 = J^-1
    f1 = np.empty((3, 3))
    f1[0, 0] = 0.5 * e0
    f1[0, 1] = -0.5 * e3
    f1[0, 2] = 0.5 * e2
    f1[1, 0] = 0.5 * e3
    f1[1, 1] = 0.5 * e0
    f1[1, 2] = -0.5 * e1
    f1[2, 0] = -0.5 * e2
    f1[2, 1] = 0.5 * e1
    f1[2, 2] = 0.5 * e0
    for a in range(3):
        acc = 0.0
        for b in range(3):
            fk = 0.0  # (f1 K1 f1^T)[a, b]
            for c in range(3):
                for d in range(3):
                    fk += f1[a, c] * K1a[i, c, d] * f1[b, d]
            acc += -fk * y[19 + b] + f1[a, b] * y[22 + b]
        K[kr, 19 + a] = acc
        acc = 0.0
        for b in range(3):
            acc += -F2a[i, a, b] * y[22 + b] - f1[b, a] * y[19 + b]
        K[kr, 22 + a] = acc + X[39 + a]
    K[kr, 25] = qa[i] * nza
    K[kr, 26] = afd
    K[kr, 27] = afdd
    K[kr, 28] = pfd
    K[kr, 29] = pfdd
    # sampled signals
    X[14] = T
    X[15] = mag
    if kr <= 1:  # the t = 0 call or the first stage of a step attempt
        X[XPKT] = 0.0  # noqa: F821
        X[XPKTC] = 0.0  # noqa: F821
        X[XBLOWN] = 0.0  # noqa: F821
    if blown:
        X[XBLOWN] = 1.0  # noqa: F821
    X[XPKT] = max(X[XPKT], T)  # noqa: F821
    X[XPKTC] = max(X[XPKTC], mag)  # noqa: F821
    X[22] = 1.0 if mag >= Tmax else 0.0
    X[23] = 1.0 if tsat else 0.0
    X[42] = r - R_MOON  # noqa: F821
    X[43] = abs(math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3) - 1.0)
    X[44] = fac
    X[56] = y[7] * y[7]
    X[57] = y[8] * y[8] + y[9] * y[9] + y[10] * y[10]
    X[58] = y[19] * y[19] + y[20] * y[20] + y[21] * y[21]
    X[59] = y[22] * y[22] + y[23] * y[23] + y[24] * y[24]
    # the lumped disturbance of (22b), d_o = e_v' + u_o / m (the reference's own model)
    s = a2 * t + a3
    ca = math.cos(math.atan(s))
    sa = math.sin(math.atan(s))
    X[4] = yd3 - (-T_NOMINAL * ca * math.cos(psi_d) / rs4) + (T * n0 - un0) / m  # noqa: F821
    X[5] = yd4 - (-T_NOMINAL * ca * math.sin(psi_d) / rs4) + (T * n1 - un1) / m  # noqa: F821
    X[6] = (yd5 - (-(rs1 * rs1 + rs2 * rs2) / rs0 + MU_MOON / rs0 ** 2  # noqa: F821
                   - T_NOMINAL * sa / rs4) + (T * n2 - un2) / m)  # noqa: F821


def _node_metrics(t, XL, X, S, C, Q, frac, h):  # noqa: N803
    """Metrics of one step from its left node (XL), over the fraction ``frac`` it ran."""
    (sx, sc, a1, a2, a3, tf, Tmax, Mmax, satc, failc, damp, wn, pointc, J, m_dry,
     qtol) = Q
    S[PKT] = max(S[PKT], XL[14])  # noqa: F821
    S[PKTC] = max(S[PKTC], XL[15])  # noqa: F821
    S[PKTS] = max(S[PKTS], XL[14], X[XPKT])  # noqa: F821  (every rhs call of the step)
    S[PKTCS] = max(S[PKTCS], XL[15], X[XPKTC])  # noqa: F821
    for a in range(3):
        S[PKM] = max(S[PKM], abs(XL[16 + a]))  # noqa: F821
    if XL[22] != 0.0:
        S[TSO] += frac * h  # noqa: F821
        # after the saturation the delivered thrust is at most fac T_max (24), (26)
        S[TEXC] = max(S[TEXC], XL[14] - XL[44] * Tmax)  # noqa: F821
    if XL[23] != 0.0:
        S[TSA] += frac * h  # noqa: F821
        S[TSAE] = t + frac * h  # noqa: F821
        if S[TSAIO] != 0.0:  # noqa: F821
            S[TSAI] += frac * h  # noqa: F821
    else:
        S[TSAIO] = 0.0  # noqa: F821
    eh = abs(XL[0])
    ev = math.sqrt(XL[1] * XL[1] + XL[2] * XL[2] + XL[3] * XL[3])
    S[EHMAX] = max(S[EHMAX], eh)  # noqa: F821
    S[EVMAX] = max(S[EVMAX], ev)  # noqa: F821
    S[MINEQ0] = min(S[MINEQ0], abs(XL[7]))  # noqa: F821
    # trapezoidal rule on a whole step (X: the aux at its right node), the left node on the
    # part of a step before an event inside it (X is not at the event)
    wr = 0.5 if frac >= 1.0 else 0.0
    S[L2BO] += frac * h * ((1.0 - wr) * (XL[36] * XL[36] + XL[37] * XL[37] + XL[38] * XL[38])  # noqa: F821
                           + wr * (X[36] * X[36] + X[37] * X[37] + X[38] * X[38]))
    S[L2BA] += frac * h * ((1.0 - wr) * (XL[39] * XL[39] + XL[40] * XL[40] + XL[41] * XL[41])  # noqa: F821
                           + wr * (X[39] * X[39] + X[40] * X[40] + X[41] * X[41]))
    S[L2L1O] += frac * h * ((1.0 - wr) * XL[56] + wr * X[56])  # noqa: F821
    S[L2L2O] += frac * h * ((1.0 - wr) * XL[57] + wr * X[57])  # noqa: F821
    S[L2L1A] += frac * h * ((1.0 - wr) * XL[58] + wr * X[58])  # noqa: F821
    S[L2L2A] += frac * h * ((1.0 - wr) * XL[59] + wr * X[59])  # noqa: F821
    if t >= S[TAFT]:  # noqa: F821  (after the failure: from t_after on)
        if math.isnan(S[TSOAF]):  # noqa: F821
            S[TSOAF] = 0.0  # noqa: F821
            S[PKTCAF] = 0.0  # noqa: F821
            S[EHMAXAF] = 0.0  # noqa: F821
        if XL[22] != 0.0:
            S[TSOAF] += frac * h  # noqa: F821
        S[PKTCAF] = max(S[PKTCAF], XL[15])  # noqa: F821
        S[EHMAXAF] = max(S[EHMAXAF], eh)  # noqa: F821
    S[V2OMAX] = max(S[V2OMAX], XL[34])  # noqa: F821
    S[V2AMAX] = max(S[V2AMAX], XL[35])  # noqa: F821
    if frac >= 1.0:
        if X[22] != XL[22]:  # entries and exits at the nodes (as the stand-in's records)
            if X[22] != 0.0:
                S[NENT] += 1.0  # noqa: F821
                if math.isnan(S[TENT]):  # noqa: F821
                    S[TENT] = t + h  # noqa: F821
            else:
                S[TEXIT] = t + h  # noqa: F821
        lev = 0.5 * (1.0 + S[TAI])  # noqa: F821  (the fraction crosses half-way to T_a)
        if math.isnan(S[TFAIL]) and XL[44] > lev >= X[44]:  # noqa: F821
            S[TFAIL] = t + h * (XL[44] - lev) / (XL[44] - X[44])  # noqa: F821


def sys_start(i, y, X, S, C, Q, R):  # noqa: N803
    """Outcomes at t = 0: a non-finite state, r below the surface, dry, a non-unit Q."""
    (sx, sc, a1, a2, a3, tf, Tmax, Mmax, satc, failc, damp, wn, pointc, J, m_dry,
     qtol) = Q
    if X[22] != 0.0:
        S[NENT] = 1.0  # noqa: F821
        S[TENT] = 0.0  # noqa: F821
    for j in range(NY):  # noqa: F821
        if not math.isfinite(y[j]):
            S[OUT] = NONFINITE  # noqa: F821
            S[TOUT] = 0.0  # noqa: F821
            return True
    code = COMPLETED  # noqa: F821
    if y[0] < R_MOON:  # noqa: F821
        code = BELOW  # noqa: F821  (starts below the surface: named, not flown)
    elif y[6] <= m_dry:
        code = DRY  # noqa: F821
    elif X[43] > qtol:
        code = QUAT  # noqa: F821
    elif X[XBLOWN] != 0.0:  # noqa: F821
        code = BLOWN  # noqa: F821  (the command at t = 0 cannot be flown)
    if code != COMPLETED:  # noqa: F821
        S[OUT] = code  # noqa: F821
        S[TOUT] = 0.0  # noqa: F821
        return True
    return False


def sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R):  # noqa: N803
    """Surface contact and dry mass (located inside the step), quaternion-norm drift (at the
    node), and the step's metrics."""
    (sx, sc, a1, a2, a3, tf, Tmax, Mmax, satc, failc, damp, wn, pointc, J, m_dry,
     qtol) = Q
    if X[XBLOWN] != 0.0:  # noqa: F821
        # a blown-up command at a stage of this step: the step is not accepted and the case
        # ends at its start (theta = 0 on the interpolant between y and itself returns y)
        S[OUT] = BLOWN  # noqa: F821
        S[TOUT] = t  # noqa: F821
        for j in range(NY):  # noqa: F821
            yn[j] = y[j]
            k1n[j] = k1[j]
        return STOP_INSIDE, 0.0  # noqa: F821
    th = 2.0
    code = COMPLETED  # noqa: F821
    if yn[0] < R_MOON:  # noqa: F821
        th = _herm_first_below(y[0], k1[0], yn[0], k1n[0], h, R_MOON)  # noqa: F821
        code = SURFACE  # noqa: F821
    if yn[6] <= m_dry:
        thm = _herm_first_below(y[6], k1[6], yn[6], k1n[6], h, m_dry)  # noqa: F821
        if thm < th:
            th = thm
            code = DRY  # noqa: F821
    hmin = _herm_min(y[0], k1[0], yn[0], k1n[0], h, min(th, 1.0)) - R_MOON  # noqa: F821
    S[HMIN] = min(S[HMIN], hmin)  # noqa: F821
    if code != COMPLETED:  # noqa: F821
        for j in range(NY):  # noqa: F821
            if not math.isfinite(k1n[j]):
                # y' at the new node is NaN / inf: the interpolant that would locate the event
                # is meaningless (found by tests/lunar/test_outcomes.py: a body rate of 1e12
                # rad/s gave "surface contact" at 4e-20 s with a NaN state)
                S[OUT] = NONFINITE  # noqa: F821
                S[TOUT] = t  # noqa: F821
                return STOP_AT_NODE, 1.0  # noqa: F821
        _node_metrics_fn(t, XL, X, S, C, Q, th, h)  # noqa: F821
        S[OUT] = code  # noqa: F821
        S[TOUT] = t + th * h  # noqa: F821
        return STOP_INSIDE, th  # noqa: F821
    _node_metrics_fn(t, XL, X, S, C, Q, 1.0, h)  # noqa: F821
    if X[43] > qtol:
        S[OUT] = QUAT  # noqa: F821
        S[TOUT] = t + h  # noqa: F821
        return STOP_AT_NODE, 1.0  # noqa: F821
    return CONTINUE, 1.0  # noqa: F821


def sys_finish(i, t, y, S, C, Q, R):  # noqa: N803
    (outc, tout, pkt, pktc, pkm, tso, tsa, nent, tent, texit, tfail, texc, v2o, v2a,
     hmin, pkts, pktcs, tsoaf, pktcaf, ehmax, evmax, ehmaxaf, mineq0, l2bo, l2ba, tsai,
     tsae, l2l1o, l2l2o, l2l1a, l2l2a) = R
    outc[i] = int(S[OUT])  # noqa: F821
    tout[i] = S[TOUT] if S[OUT] != COMPLETED else t  # noqa: F821
    pkt[i] = S[PKT]  # noqa: F821
    pktc[i] = S[PKTC]  # noqa: F821
    pkm[i] = S[PKM]  # noqa: F821
    tso[i] = S[TSO]  # noqa: F821
    tsa[i] = S[TSA]  # noqa: F821
    nent[i] = int(S[NENT])  # noqa: F821
    tent[i] = S[TENT]  # noqa: F821
    texit[i] = S[TEXIT]  # noqa: F821
    tfail[i] = S[TFAIL]  # noqa: F821
    texc[i] = S[TEXC]  # noqa: F821
    v2o[i] = S[V2OMAX]  # noqa: F821
    v2a[i] = S[V2AMAX]  # noqa: F821
    hmin[i] = S[HMIN]  # noqa: F821
    pkts[i] = S[PKTS]  # noqa: F821
    pktcs[i] = S[PKTCS]  # noqa: F821
    tsoaf[i] = S[TSOAF]  # noqa: F821
    pktcaf[i] = S[PKTCAF]  # noqa: F821
    ehmax[i] = S[EHMAX]  # noqa: F821
    evmax[i] = S[EVMAX]  # noqa: F821
    ehmaxaf[i] = S[EHMAXAF]  # noqa: F821
    mineq0[i] = S[MINEQ0]  # noqa: F821
    l2bo[i] = math.sqrt(S[L2BO])  # noqa: F821
    l2ba[i] = math.sqrt(S[L2BA])  # noqa: F821
    tsai[i] = S[TSAI]  # noqa: F821
    tsae[i] = S[TSAE]  # noqa: F821
    l2l1o[i] = math.sqrt(S[L2L1O])  # noqa: F821
    l2l2o[i] = math.sqrt(S[L2L2O])  # noqa: F821
    l2l1a[i] = math.sqrt(S[L2L1A])  # noqa: F821
    l2l2a[i] = math.sqrt(S[L2L2A])  # noqa: F821


HOOKS = (sys_init, sys_rhs, _node_metrics, sys_start, sys_step, sys_finish)
SLOTS = {"PKT": PKT, "PKTC": PKTC, "PKM": PKM, "TSO": TSO, "TSA": TSA, "NENT": NENT,
         "TENT": TENT, "TEXIT": TEXIT, "TFAIL": TFAIL, "TEXC": TEXC, "V2OMAX": V2OMAX,
         "V2AMAX": V2AMAX, "HMIN": HMIN, "OUT": OUT, "TOUT": TOUT, "PKTS": PKTS,
         "PKTCS": PKTCS, "TAI": TAI, "TAFT": TAFT, "TSOAF": TSOAF, "PKTCAF": PKTCAF,
         "EHMAX": EHMAX, "EVMAX": EVMAX, "EHMAXAF": EHMAXAF, "MINEQ0": MINEQ0,
         "L2BO": L2BO, "L2BA": L2BA, "TSAI": TSAI, "TSAE": TSAE, "TSAIO": TSAIO,
         "L2L1O": L2L1O, "L2L2O": L2L2O, "L2L1A": L2L1A, "L2L2A": L2L2A,
         "XPKT": XPKT, "XPKTC": XPKTC, "XBLOWN": XBLOWN, "BLOWN": BLOWN,
         "COMPLETED": COMPLETED, "BELOW": BELOW,
         "SURFACE": SURFACE, "DRY": DRY, "QUAT": QUAT, "NONFINITE": NONFINITE}
CONSTS = {"BLOW_ACC": BLOWUP_ACCEL, "R_MOON": P.R_MOON, "MU_MOON": P.MU_MOON,
          "T_NOMINAL": P.T_NOMINAL, "ISP": P.ISP, "G0": P.G0, "ZETA": ZETA, "TINY": TINY}


def hooks_source() -> str:
    """The hooks as written into a kernel module, with their slots and constants."""
    from lgw.sim.integrate import hooks_text
    return hooks_text([f for f in HOOKS if f is not _node_metrics], [_node_metrics],
                      consts={**SLOTS, **CONSTS},
                      imports=("from lgw.sim.integrate import BISECT_ITERS",
                               "from lgw.sim.lunar.kernel import _cross, _dcm, _mv, _qmul, "
                               "_spline"))


def _deps() -> list[str]:
    """The sources of the modules the generated kernel imports compiled code and constants
    from (numba does not check them), as first read in this process (lgw.sim.kernel_cache)."""
    from lgw.sim import codegen, integrate, kernel_cache
    from lgw.sim.lunar import kernel
    return kernel_cache.imported_sources(codegen, integrate, kernel)


def kernel_text() -> str:
    """The full text of the generated kernel module (what the cache keys)."""
    from lgw.sim import integrate
    return integrate.kernel_module_source(law_header(), hooks_source(),
                                          {"NY": NY, "NX": NX, "NS": NS})


@functools.cache
def kernel_module():
    """The generated kernel module of seed 001's closed loop (``kernel`` and the generated
    law), from the disk cache, keyed by its text and found by its inputs
    (``lgw.sim.kernel_cache.generated_module``)."""
    from lgw.sim import kernel_cache
    return kernel_cache.generated_module("lunar_kernel", kernel_text, _deps())


_deps()  # read the sources the kernel imports now, at this module's import (see _deps)
