"""Seed 001 Section 4: the orbit instance (22)-(26) and the attitude instance (27)-(28), derived
and checked against the printed forms.  Every verdict is computed from evidence."""

from __future__ import annotations

import dataclasses
from functools import cache

import sympy as sp
from lgw.theory.evidence import Claim, Identity, Step, Witness
from lgw.theory.lunar.law import skew
from lgw.theory.lunar.quaternion import dcm, qmul, reduce_unit
from lgw.theory.provers import prove_identity
from lgw.theory.report_math import At
from lgw.theory.report_math import Norm as norm

Ms = sp.MatrixSymbol  # display names of vectors and matrices (no verdict depends on them)


def _with_expr(step: Step, expr: sp.Basic | tuple) -> Step:
    """``step`` (made by a prover) with the formula it asserts, for rendering."""
    return dataclasses.replace(step, expr=expr)


def thrust_vector(T, alpha, psi) -> sp.Matrix:
    """[Tx, Ty, Tz] of seed 001 (2) in F_H."""
    return sp.Matrix([-T * sp.cos(alpha) * sp.cos(psi), -T * sp.cos(alpha) * sp.sin(psi),
                      -T * sp.sin(alpha)])


def failure_factor(t, tf, Ta):
    """The thrust fraction of seed 001 (26): f_a(v) = factor (v + u_norm) - u_norm with
    factor = (1 + Ta)/2 (1 - (2/pi) (1 - Ta)/(1 + Ta) atan(2 t - tf))."""
    return (1 + Ta) / 2 * (1 - 2 / sp.pi * (1 - Ta) / (1 + Ta) * sp.atan(2 * t - tf))


@cache
def orbit_claim() -> Claim:
    r, rd, R = sp.symbols("r r_d R_M", positive=True)
    w, wd = sp.symbols("w w_d", real=True)
    V, Vd = sp.Matrix(sp.symbols("u v w", real=True)), sp.Matrix(sp.symbols("u_d v_d w_d",
                                                                          real=True))
    a_h = sp.Matrix([[0, 0, -1]])
    # h = r - R_M, r' = -w (1a): e_h' = -w + w_d
    eh_dot = (-V[2]) - (-Vd[2])
    T, Td, al, ps, ald, psd, m = sp.symbols("T T_d alpha_B psi_B alpha_Bd psi_Bd m",
                                            positive=True)
    u_o = sp.Matrix([T * sp.cos(al) * sp.cos(ps) - Td * sp.cos(ald) * sp.cos(psd),
                     T * sp.cos(al) * sp.sin(ps) - Td * sp.cos(ald) * sp.sin(psd),
                     T * sp.sin(al) - Td * sp.sin(ald)])  # (23)
    u_norm = sp.Matrix([Td * sp.cos(ald) * sp.cos(psd), Td * sp.cos(ald) * sp.sin(psd),
                        Td * sp.sin(ald)])  # (25)
    ehd = sp.Symbol("edot_h", real=True)
    e22a = sp.Eq(ehd, sp.MatMul(a_h, V - Vd, evaluate=False), evaluate=False)
    thrust = sp.Eq(thrust_vector(T, al, ps), -(Ms("u_o", 3, 1) + Ms("u_norm", 3, 1)),
                   evaluate=False)
    steps = [_with_expr(prove_identity(sp.expand(eh_dot - (a_h * (V - Vd))[0]),
                                       "(22a): e_h' = a_h e_v with a_h = [0, 0, -1], from h = "
                                       "r - R_M and (1a) r' = -w"),
                        (sp.Eq(ehd, eh_dot, evaluate=False), e22a)),
             _with_expr(prove_identity(sp.expand(thrust_vector(T, al, ps) / m
                                                 + (u_o + u_norm) / m).norm() ** 2,
                                       "(2), (23), (25): the thrust acceleration is "
                                       "-(u_o + u_norm)/m, so (22b) has B0 = -I/m and d_o = "
                                       "(the rest of (1d)-(1f)) - V_d' - u_norm/m"), thrust)]
    return Claim("orbit-22-23", "(1), (2), (22), (23), (25)", "Orbit tracking is of the form (5)",
                 "x1 = e_h, x2 = e_v, f1 = a_h, f2 = 0, B0 = -1/m, d = d_o",
                 "as printed; d_o = gravity, transport terms of (1) minus the reference's own "
                 "acceleration minus u_norm/m (it contains the nominal thrust: ||d_o|| is not "
                 "small, about T_d/m ~ 4.7 m/s^2 at the start)", tuple(steps),
                 paper_expr=(sp.Eq(Ms("u_o", 3, 1), u_o, evaluate=False),
                             sp.Eq(Ms("u_norm", 3, 1), u_norm, evaluate=False)),
                 derived_expr=(e22a, thrust))


@cache
def saturation_claim() -> Claim:
    uc = sp.Matrix(sp.symbols("u_c1:4", real=True))
    un = sp.Matrix(sp.symbols("u_n1:4", real=True))
    Tmax, Td = sp.symbols("T_max T_d", positive=True)
    tot = uc + un
    T_cmd = sp.sqrt((tot.T * tot)[0])
    sat_total = tot * Tmax / T_cmd  # (24) upper branch + u_norm
    resid = sp.simplify((sat_total.T * sat_total)[0] - Tmax ** 2)
    # alternative reading T := T_d: the "saturated" total thrust magnitude is |uc+un| Tmax/Td
    pt = {uc[0]: sp.Integer(16000), uc[1]: 0, uc[2]: 0, un[0]: sp.Integer(24000), un[1]: 0,
          un[2]: 0, Tmax: sp.Integer(34000), Td: sp.Integer(24000)}
    alt = sp.sqrt(((tot * Tmax / Td).T * (tot * Tmax / Td))[0]) - Tmax
    val = alt.subs(pt)
    w = Witness({str(k): str(v) for k, v in pt.items()}, -float(val),
                "|sat(u_c) + u_norm| - T_max with T := T_d (exact)", -float(sp.N(val, 60)),
                "60 digits")
    T = sp.Symbol("T", positive=True)
    uco, unm = Ms("u_co", 3, 1), Ms("u_norm", 3, 1)
    printed = sp.Eq(Ms("u_sat", 3, 1), (uco + unm) * Tmax / T - unm, evaluate=False)
    mag = sp.Eq(norm(sp.Symbol("u_sat") + sp.Symbol("u_norm")), Tmax, evaluate=False)
    steps = [_with_expr(prove_identity(resid, "(24) with T := |u_co + u_norm| (the commanded "
                                       "thrust magnitude): the saturated total thrust has "
                                       "magnitude T_max"), mag)]
    remarks = (Step("(24) with T := T_d (the nominal thrust) limits nothing: it scales the "
                    "command up by T_max/T_d, e.g. 40 kN commanded gives 56.7 kN",
                    Identity(alt, "sympy (exact point)", w)),)
    return Claim("sat-24", "(24)", "Orbit-thrust saturation", "sat(u_co) = (u_co + u_norm) "
                 "T_max/T - u_norm when |u_co + u_norm| >= T_max",
                 "T in (24) must be |u_co + u_norm| (the magnitude of the commanded total "
                 "thrust) for (24) to be a saturation at T_max; the simulator implements that "
                 "reading (reading 'nominal', T = T_d, stays selectable)", tuple(steps),
                 remarks=remarks, paper_expr=(printed,),
                 derived_expr=(printed, sp.Eq(T, T_cmd, evaluate=False), mag))


@cache
def failure_claim() -> Claim:
    t = sp.Symbol("t", real=True)
    tf = sp.Symbol("t_f", positive=True)
    Ta = sp.Symbol("T_a", positive=True)
    fac = failure_factor(t, tf, Ta)
    kappa = sp.Symbol("kappa", positive=True)  # the factor, for display
    steps = [_with_expr(prove_identity(sp.simplify(sp.limit(fac, t, sp.oo) - Ta),
                                       "factor -> T_a as t -> oo (70% thrust after the "
                                       "failure)"),
                        sp.Eq(sp.Limit(kappa, t, sp.oo), Ta, evaluate=False)),
             _with_expr(prove_identity(sp.simplify(sp.limit(fac, t, -sp.oo) - 1),
                                       "factor -> 1 as t -> -oo"),
                        sp.Eq(sp.Limit(kappa, t, -sp.oo), 1, evaluate=False)),
             _with_expr(prove_identity(sp.simplify(fac.subs(t, tf / 2) - (1 + Ta) / 2),
                                       "factor = (1 + T_a)/2 at t = t_f/2 (the midpoint of the "
                                       "failure)"),
                        sp.Eq(At(kappa, tf / 2), (1 + Ta) / 2, evaluate=False))]
    v, un = Ms("v", 3, 1), Ms("u_norm", 3, 1)
    return Claim("failure-26", "(26)", "Failure model", "actual thrust = command for t <= tf/2 "
                 "and 70% of it after, approximated by atan",
                 "f_a(v) = factor(t) (v + u_norm) - u_norm scales the total thrust; factor goes "
                 "from ~1 to T_a over a few seconds (the argument 2t - t_f is in seconds: the "
                 "transition half-width is 0.5 s); at t = 0 it is 1 - (1 - T_a)/pi "
                 "(pi/2 - atan(t_f)) ~ 1, not exactly 1; the failure persists, so du does not "
                 "vanish", tuple(steps),
                 paper_expr=(sp.Eq(kappa, fac, evaluate=False),),
                 derived_expr=(sp.Eq(Ms("f_a", 3, 1), kappa * (v + un) - un, evaluate=False),
                               sp.Eq(kappa, fac, evaluate=False),
                               sp.Eq(At(kappa, 0), fac.subs(t, 0),
                                     evaluate=False)))


GROEBNER = "remainder modulo |e_Q|^2 - 1 (sympy.reduced), then sympy.simplify"


def _q(name: str) -> sp.Matrix:
    return sp.Matrix(sp.symbols(f"{name}0:4", real=True))


@cache
def attitude_kinematics_claim() -> Claim:
    Q, Qd = _q("Q"), _q("Qd")
    w, wd = sp.Matrix(sp.symbols("w1:4", real=True)), sp.Matrix(sp.symbols("wd1:4", real=True))
    e = _q("e")
    ew = sp.Matrix(sp.symbols("ew1:4", real=True))
    # d/dt (conj(Qd) x Q) with Q' = Q x [0, w]/2, Qd' = Qd x [0, wd]/2, written in e = conj(Qd) x Q:
    # = (e x [0, w] - [0, wd] x e)/2; claim: = e x [0, w - L(e) wd]/2 on unit e.
    lhs = (qmul(e, sp.Matrix([0, *w])) - qmul(sp.Matrix([0, *wd]), e)) / 2
    rhs = qmul(e, sp.Matrix([0, *(w - dcm(e) * wd)])) / 2
    red = [reduce_unit(x, e) for x in (lhs - rhs)]
    vec_rate = rhs[1:, 0]
    printed = (e[0] * sp.eye(3) + skew(sp.Matrix(e[1:]))) * (w - dcm(e) * wd) / 2
    # L(e)' = -S(e_w) L(e) along e' = e x [0, e_w]/2
    edot = qmul(e, sp.Matrix([0, *ew])) / 2
    Ldot = sum((dcm(e).diff(e[i]) * edot[i] for i in range(4)), sp.zeros(3, 3))
    redL = [reduce_unit(x, e) for x in (Ldot + skew(ew) * dcm(e))]
    # the conjugate-product identity behind e = conj(Qd) x Q (e' computed from Q', Qd')
    ed = qmul(qmul(sp.Matrix([Qd[0], *(-Qd[1:, 0])]), Q), sp.Matrix([1, 0, 0, 0]))
    e_dot_direct = (qmul(sp.Matrix([Qd[0], *(-Qd[1:, 0])]), qmul(Q, sp.Matrix([0, *w])) / 2)
                    + qmul(-qmul(sp.Matrix([0, *wd]), sp.Matrix([Qd[0], *(-Qd[1:, 0])])) / 2,
                           Q))
    e_dot_form = (qmul(ed, sp.Matrix([0, *w])) - qmul(sp.Matrix([0, *wd]), ed)) / 2
    e_w = Ms("e_w", 3, 1)
    ew_def = sp.Eq(e_w, Ms("omega", 3, 1) - Ms("L", 3, 3) * Ms("omega_d", 3, 1), evaluate=False)
    eqd = Ms("edot_q", 3, 1)
    ew_names = {a: sp.Symbol(f"e_w{i}", real=True) for i, a in enumerate(ew, 1)}
    printed_disp = sp.Eq(eqd, ((e[0] * sp.eye(3) + skew(sp.Matrix(e[1:]))) * ew / 2)
                         .xreplace(ew_names), evaluate=False)
    steps = [prove_identity(sp.expand(e_dot_direct - e_dot_form).norm() ** 2,
                            "e_Q = conj(Q_d) x Q: e_Q' = (e_Q x [0, w] - [0, w_d] x e_Q)/2"),
             _with_expr(prove_identity(sum(x ** 2 for x in red), "on unit e_Q: e_Q' = e_Q x "
                                       "[0, e_w]/2 with e_w = w - L(e_Q) w_d", method=GROEBNER),
                        ew_def),
             _with_expr(prove_identity(sp.expand(vec_rate - printed).norm() ** 2,
                                       "(27a): its vector part is e_q' = (eq0 I + S(e_q)) e_w "
                                       "/ 2"), printed_disp),
             _with_expr(prove_identity(sum(x ** 2 for x in redL), "L(e_Q)' = -S(e_w) L(e_Q) on "
                                       "unit e_Q (used in (27b))", method=GROEBNER),
                        sp.Eq(Ms("Ldot", 3, 3), -sp.MatMul(skew(ew).xreplace(ew_names),
                                                           Ms("L", 3, 3)), evaluate=False))]
    return Claim("attitude-27a", "(27a)", "Error-quaternion kinematics",
                 "e_q' = [eq0 I3 + S(e_q)] e_w / 2", "as printed, for unit quaternions, "
                 "e_Q = conj(Q_d) x Q, e_w = w - L(e_Q) w_d, Hamilton product, scalar first",
                 tuple(steps), paper_expr=(printed_disp,), derived_expr=(printed_disp, ew_def))


@cache
def attitude_dynamics_claim() -> Claim:
    J = sp.diag(*sp.symbols("J1:4", positive=True))
    w = sp.Matrix(sp.symbols("w1:4", real=True))
    a = sp.Matrix(sp.symbols("a1:4", real=True))  # L_BH w_HP^H
    LwHPdot = sp.Matrix(sp.symbols("b1:4", real=True))  # L_BH d(w_HP^H)/dt
    M = sp.Matrix(sp.symbols("M1:4", real=True))
    Om = w + a  # inertial rate (F_P taken inertial)
    # Euler: J Om' = -Om x J Om + M; Om' = w' + d/dt(L_BH w_HP) = w' + L_BH w_HP' - S(w) a
    w_dot_euler = J.inv() * (-skew(Om) * J * Om + M) - LwHPdot + skew(w) * a
    Cr = J * skew(a) - skew(J * (w + a)) + skew(a) * J
    nr = skew(a) * J * a + J * LwHPdot  # J' = 0
    w_dot_printed = -J.inv() * (Cr * w + nr) + J.inv() * M
    steps = [prove_identity(sp.simplify(w_dot_euler - w_dot_printed).norm() ** 2,
                            "(27b) C_r, n_r: w' = -J^-1 (C_r w + n_r) + J^-1 M is Euler's "
                            "equation for the inertial rate w + L_BH w_HP (J constant)")]
    # n_do: e_w' = w' - d/dt(L(e) w_d) = w' + S(e_w) L w_d - L w_d'
    ew, Lwd, Lwdd = (sp.Matrix(sp.symbols(f"{n}1:4", real=True)) for n in ("ew", "Lwd", "Lwdd"))
    derived = skew(ew) * Lwd - Lwdd  # e_w' - w'
    printed = -(skew(ew) * Lwd + Lwdd)  # -n_do as printed
    resid = (derived - printed)[0]
    pt = {ew[1]: sp.Integer(1), Lwd[2]: sp.Integer(1), ew[0]: 0, ew[2]: 0, Lwd[0]: 0, Lwd[1]: 0,
          Lwdd[0]: 0, Lwdd[1]: 0, Lwdd[2]: 0}
    wit = Witness({str(k): str(v) for k, v in pt.items()}, -abs(float(resid.subs(pt))),
                  "first component of (derived - printed) at an exact point",
                  -abs(float(sp.N(resid.subs(pt), 60))), "60 digits")
    steps[0] = _with_expr(steps[0], sp.Eq(Ms("omegadot", 3, 1), -Ms("J", 3, 3).inv() * (
        Ms("C_r", 3, 3) * Ms("omega", 3, 1) + Ms("n_r", 3, 1)) + Ms("J", 3, 3).inv()
        * Ms("M", 3, 1), evaluate=False))
    # n_do in vector form: S(e_w) written out in display names e_w1..3, L w_d and L w_d' named
    ndo = Ms("n_do", 3, 1)
    S_ew = skew(sp.Matrix(sp.symbols("e_w1:4", real=True)))
    Lw, Lwd_ = Ms("L", 3, 3) * Ms("omega_d", 3, 1), Ms("L", 3, 3) * Ms("omegadot_d", 3, 1)
    paper_n = sp.Eq(ndo, sp.MatMul(S_ew, Lw) + Lwd_, evaluate=False)  # -(printed)
    derived_n = sp.Eq(ndo, -sp.MatMul(S_ew, Lw) + Lwd_, evaluate=False)  # -(derived)
    steps.append(Step("(27b) n_do as printed: e_w' - w' = -(S(e_w) L w_d + L w_d')",
                      Identity(sp.expand((derived - printed).norm() ** 2), "sympy.expand", wit),
                      sp.Eq(derived, printed, evaluate=False)))
    return Claim("attitude-27b", "(27b)", "Error-rate dynamics",
                 "e_w' = -J^-1 (C_r w + n_r) - n_do + J^-1 M + J^-1 d_M, n_do = S(e_w) L w_d + "
                 "L w_d'", "C_r, n_r as printed (Euler's equation); but L(e_Q)' = -S(e_w) L "
                 "gives n_do = -S(e_w) L w_d + L w_d': the printed sign of S(e_w) L w_d is "
                 "wrong (the simulator and the law use the derived sign)", tuple(steps),
                 paper_expr=(paper_n,), derived_expr=(derived_n,))


@cache
def attitude_F1_claim() -> Claim:
    e0 = sp.Symbol("e_q0", real=True)
    eq = sp.Matrix(sp.symbols("e_q1:4", real=True))
    f1 = (e0 * sp.eye(3) + skew(eq)) / 2
    n2 = (eq.T * eq)[0]
    f1s = Ms("f_1", 3, 3)
    det_eq = sp.Eq(sp.Determinant(2 * f1s), e0 * (e0 ** 2 + n2), evaluate=False)
    gram = sp.Eq(f1s * f1s.T, ((e0 ** 2 + n2) * sp.Identity(3) - Ms("e_q", 3, 1)
                              * Ms("e_q", 3, 1).T) / 4, evaluate=False)
    steps = [_with_expr(prove_identity(sp.expand(sp.det(2 * f1) - e0 * (e0 ** 2 + n2)),
                                       "det(2 f1) = eq0 (eq0^2 + |e_q|^2) = eq0 on unit e_Q"),
                        det_eq),
             _with_expr(prove_identity(sp.expand(f1 * f1.T - ((e0 ** 2 + n2) * sp.eye(3)
                                                             - eq * eq.T) / 4).norm() ** 2,
                                       "f1 f1^T = ((eq0^2 + |e_q|^2) I - e_q e_q^T)/4 = "
                                       "(I - e_q e_q^T)/4 on unit e_Q: eigenvalues 1/4, 1/4, "
                                       "eq0^2/4"), gram)]
    return Claim("attitude-F1", "(10), (27)", "F1 = f1 K1 f1^T for the attitude loop",
                 "F1 := f1 K1 f1^T is a positive definite matrix",
                 "F1 is positive definite iff eq0 != 0 (for K1 with positive definite "
                 "symmetric part); lambda_min(F1) >= lambda_min(K1) eq0^2/4, exact for K1 = k I: "
                 "f1bar -> 0 as the error approaches 180 degrees (eq0 -> 0), so a uniform f1bar "
                 "is a property of the run", tuple(steps),
                 paper_expr=(sp.Eq(Ms("F_1", 3, 3), f1s * Ms("K_1", 3, 3) * f1s.T,
                                   evaluate=False),),
                 derived_expr=(sp.Eq(f1s, f1, evaluate=False), det_eq, gram))
