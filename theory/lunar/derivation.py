"""Seed 001 Section 3 derived and checked: V2' (12)-(13), its hypotheses, (14) and Vlambda
(15)-(17).  The L2 bounds (18)-(21) are in ``lgw.theory.lunar.l2``.

Every claim's verdict is computed from ``lgw.theory.evidence`` steps; nothing is typed.  The
derivation differentiates V2 (12) along the closed loop built in ``lgw.theory.lunar.law`` (the
same expressions the simulator runs) and compares with (13) term by term.  Where the paper's
statement as printed fails and the workbench proves a corrected one, they are two claims: the
paper's (``statement="paper"``, judged as printed, with its witness) and the workbench's
(``statement="workbench"``, ``corrects`` naming the first).
"""

from __future__ import annotations

import dataclasses
import json
from functools import cache

import sympy as sp
from lgw.theory import report_math as RM
from lgw.theory.evidence import Cited, Claim, FromClaim, Step, Unproven
from lgw.theory.lunar import law as L
from lgw.theory.lunar.gains import Gains, paper_gains
from lgw.theory.lunar.hypotheses import f2bar_minus_f3, quantities
from lgw.theory.lunar.parameters import M0, ORBIT_GAINS
from lgw.theory.provers import identity_evidence, prove_identity, prove_nonneg, refute_nonneg_at
from lgw.theory.symbolic import memo

CAUCHY = ("Cauchy-Schwarz inequality: z^T d <= ||z|| ||d||")
RAYLEIGH = ("Rayleigh quotient: x^T F x >= lambda_min(F) ||x||^2 for symmetric F (Horn & "
            "Johnson, Matrix Analysis, Thm 4.2.2)")
LASALLE = ("LaSalle-Yoshizawa theorem (Krstic, Kanellakopoulos, Kokotovic, Nonlinear and "
           "Adaptive Control Design, Wiley 1995, Thm A.8; seed 001 ref. [13])")
MINKOWSKI = "Minkowski inequality in L2[0, t]: ||a + b|| <= ||a|| + ||b||"


# --- Display forms: the formulas the report renders (paper_expr / derived_expr / Step.expr).
# They are the scalar instance (n1 = n2 = m = 1, where z^T F z = F z^2 and ||z|| = |z|) of the
# same SymPy objects the proofs use, with readable names; no verdict depends on them.
X1, Z1, Z2, DIST = sp.symbols("x_1 z_1 z_2 d", real=True)
LAM1, LAM2, DU = sp.symbols("lambda_1 lambda_2 Delta_u", real=True)
F1S, F2S, F3S = sp.symbols("F_1 F_2 f_3", positive=True)
F1B, F2B, F3B = sp.symbols("fbar_1 fbar_2 fbar_3", positive=True)
V2DOT, VLDOT = sp.symbols("Vdot_2 Vdot_lambda", real=True)
V2S, VLS = sp.symbols("V_2 V_lambda", nonnegative=True)
B0S = sp.Symbol("B_0", real=True)
T_ = sp.Symbol("t", nonnegative=True)
Z1D, Z2D = Z1, Z2  # for functions whose local names shadow Z1, Z2


def scalar_display(expr: sp.Expr, z: bool = True) -> sp.Expr:
    """``expr`` of the scalar instance (``law.scalar_system``) in display names: x1 as x_1,
    lambda1 = x1 - z1 (so that z1 (9a) appears; ``z=False`` keeps lambda_1), z2 (9b),
    ||z2|| = |z2|, F1 = k1 f1(x1)^2 (10) as F_1, F2 as F_2, f3 as f_3, b as B_0, Du as
    Delta_u.  seed 001, eqs. (9)-(10)."""
    S = systems()[0]
    f1x = S.f1[0, 0]
    k1 = S.K1[0, 0]
    e = expr.subs(S.lam1[0], S.x1[0] - Z1) if z else expr
    e = e.subs(k1, F1S / f1x ** 2)
    return e.xreplace({S.x1[0]: X1, S.z2s[0]: Z2, S.nz: sp.Abs(Z2), S.lam1[0]: LAM1,
                       S.lam2[0]: LAM2, S.d[0]: DIST, S.du[0]: DU, S.F2[0, 0]: F2S,
                       S.f3: F3S, S.B0[0, 0]: B0S})


def at0(x: sp.Expr) -> sp.Expr:
    """x(0), the initial value of ``x``, for display (seed 001 (19)-(21))."""
    return RM.At(x, 0)


def relabel(rel: sp.Basic, fn) -> sp.Basic:
    """A relation with ``fn`` applied to both sides, not evaluated (a renamed q ||z2|| >= 0
    stays a relation rather than becoming True)."""
    if isinstance(rel, sp.core.relational.Relational):
        return rel.func(fn(rel.lhs), fn(rel.rhs), evaluate=False)
    return fn(rel)


def lemma(statement: str, claim: Claim) -> Step:
    """A step that uses another claim of this report as a lemma.  A proved or proved-given
    lemma is cited with its own steps as the hypotheses (so its evidence stays in view); any
    other verdict goes through ``FromClaim``: a checked lemma stays checked, and a lemma the
    workbench refutes or leaves unproven makes the step unproven, never proved."""
    if claim.verdict in ("proved", "proved-given"):
        return Step(statement, Cited(f"claim {claim.id} of this report", claim.title,
                                     claim.steps))
    return Step(statement, FromClaim(claim))


def _with_expr(step: Step, expr: sp.Basic | tuple) -> Step:
    """``step`` (made by a prover) with the formula it asserts, for rendering."""
    return dataclasses.replace(step, expr=expr)


def paper_13() -> tuple[sp.Basic, ...]:
    """Seed 001, eq. (13) as printed, in the scalar instance's display names."""
    return (sp.Le(V2DOT, -F1S * Z1**2 - F2S * Z2**2 + F3B * Z2**2, evaluate=False),
            sp.Le(V2DOT, -F1B * Z1**2 - (F2B - F3B) * Z2**2, evaluate=False))


@cache
def systems() -> tuple[L.GeneralSystem, ...]:
    return (L.scalar_system(), L.orbit_system(), L.attitude_system())


def v2dot_residual(S: L.GeneralSystem, literal_d: bool = False) -> sp.Expr:
    """V2' (derived) minus the exact remainder form (``remainder_13``), in z coordinates with
    ||z2|| = sqrt(z2^T z2).  Zero when the derivation reproduces (13)'s structure."""
    r = S.V2dot_z - S.remainder_13()
    return S.norm_subs(sp.expand(r))


@cache
def residual_steps() -> tuple[Step, ...]:
    """The residual identity for every instance (computed once; both V2' claims use it)."""
    return tuple(_residual_step(S) for S in systems())


def _residual_step(S: L.GeneralSystem) -> Step:
    r = v2dot_residual(S)
    simp = sp.simplify(sp.together(sp.expand(r)))
    return Step(f"{S.name} (n1={S.n1}, n2={S.n2}, m={S.m}): V2' along (5), (7), (8), (11) "
                "equals -z1^T F1 z1 - z2^T F2 z2 + [z2^T d - D||z2||] + R - (d0e - D) D'/q, "
                "R = f3 d0e ||z2||^2 / (d0e + f3 ||z2||)",
                identity_evidence(r, simplified=simp), _residual_display(S))


def _residual_display(S: L.GeneralSystem) -> sp.Basic:
    """What the residual step asserts: for the scalar instance V2' = (13)'s exact form (the
    ``remainder_13`` object in display names); for the others, named: V2' - (that form) = 0."""
    if S.name == "scalar":
        return sp.Eq(V2DOT, scalar_display(S.remainder_13()), evaluate=False)
    return sp.Eq(V2DOT - sp.Symbol(f"Vdot_2^({S.name})"), 0, evaluate=False)


def _rhs_13(S: L.GeneralSystem) -> sp.Expr:
    """The first right-hand side of (13) as printed, in z coordinates:
    -z1^T F1 z1 - z2^T F2 z2 + f3bar ||z2||^2 (seed 001, eq. (13))."""
    z1, z2 = S.z1, S.z2s
    return -(z1.T * S.F1 * z1)[0] - (z2.T * S.F2 * z2)[0] + S.f3 * S.nz ** 2


def _orbit_point(S: L.GeneralSystem) -> dict:
    """An exact state of the orbit instance at seed 001 Section 5's orbit gains (K1, F2, f3, q,
    m0) where the disturbance's norm grows: d = [0, 0, 1] m/s^2 = ||d|| D, d/dt ||d|| = 1
    m/s^3, d0e = 0, z2 = [0, 0, 1/10] m/s, e_h = 0, lambda = 0, du = 0 (no saturation)."""
    g = ORBIT_GAINS
    R = sp.Rational
    pt = {S.x1[0]: 0, S.lam1[0]: 0, S.d0e: 0, S.D: 1, S.Ddot: 1,
          S.q: R(repr(g["q"])), S.f3: R(repr(g["f3"])), sp.Symbol("m", positive=True): int(M0)}
    for i in range(3):
        pt[S.lam2[i]] = 0
        pt[S.du[i]] = 0
        pt[S.d[i]] = 1 if i == 2 else 0
        pt[S.z2s[i]] = R(1, 10) if i == 2 else 0
        pt[S.K1[i, i]] = R(repr(g["K1"][i]))
        pt[S.F2[i, i]] = R(repr(g["F2"][i]))
    return pt


@cache
def v2dot_claim() -> Claim:
    """Seed 001 (12)-(13) as printed: d^_0 = d0e - ||d(t)|| with the time-varying ||d|| of the
    paper's disturbance; (13) judged on V2' derived from the law at an exact state."""
    S0 = systems()[0]
    d0e, q = S0.d0e, S0.q
    steps = list(residual_steps())
    # (13) as printed: V2' <= -z1^T F1 z1 - z2^T F2 z2 + f3bar ||z2||^2 for every state of the
    # closed loop, with the paper's V2 (12) (D = ||d(t)||, D' = d/dt ||d||)
    So = systems()[1]
    margin = So.norm_subs(_rhs_13(So) - So.V2dot_z)
    pt = _orbit_point(So)
    st = refute_nonneg_at(margin, pt, "orbit instance at an exact state of Section 5's orbit "
                          "gains with a growing ||d(t)||: (13) right-hand side - V2' >= 0")
    steps.append(_with_expr(st, sp.Le(V2DOT, paper_13()[0].rhs, evaluate=False)))
    Ddot = S0.Ddot
    extra = -(d0e - S0.D) * Ddot / q
    excess = (f"; at the exact state of step {len(steps)} V2' exceeds (13)'s right-hand side "
              f"by {-st.witness.margin:.6g}") if st.witness is not None else ""
    return Claim("V2dot", "(7), (8), (10)-(13)", "Lyapunov derivative of V2 along the closed loop",
                 "V2' <= -z1^T F1 z1 - z2^T F2 z2 + f3bar ||z2||^2 <= -f1bar||z1||^2 - "
                 "(f2bar - f3bar)||z2||^2, with d^_0 = d0e - ||d|| in V2 (12) and d an unknown "
                 "bounded time-varying disturbance (Section 5's has a time-varying norm)",
                 "V2' = -z1^T F1 z1 - z2^T F2 z2 + (z2^T d - ||d|| ||z2||) + f3 d0e ||z2||^2/"
                 "(d0e + f3||z2||) - (d0e - ||d||)(d/dt ||d||)/q: the last term, which (13) "
                 "omits, is positive when d0e < ||d|| and ||d|| grows" + excess, tuple(steps),
                 numbers={"extra_term_time_varying_d": sp.sstr(extra),
                          "witness_V2dot_minus_rhs13": (-st.witness.margin if st.witness
                                                        else None)},
                 paper_expr=paper_13(),
                 derived_expr=(sp.Eq(V2DOT, scalar_display(S0.remainder_13()), evaluate=False),))


@cache
def v2dot_bound_claim() -> Claim:
    """(13) with a constant bound D >= ||d(t)|| in V2 (12): the workbench's reading."""
    S0 = systems()[0]
    f3, d0e, nz, q = S0.f3, S0.d0e, S0.nz, S0.q
    R = f3 * d0e * nz ** 2 / (d0e + f3 * nz)
    steps = list(residual_steps())

    def shown(step: Step) -> Step:  # the prover's relation in display names
        return _with_expr(step, relabel(step.expr, scalar_display))
    F2g = sp.Matrix(3, 3, sp.symbols("F2_1:10", real=True))
    zz = sp.Matrix(sp.symbols("z2_1:4", real=True))
    extra = -(d0e - S0.D) * S0.Ddot / q
    steps += [
        shown(prove_nonneg(q * nz, "d0e' = q ||z2|| >= 0 (8), so d0e(t) >= d0e(0) >= 0")),
        shown(prove_nonneg(f3 * nz ** 2 - R, "remainder R <= f3 ||z2||^2 when d0e >= 0 (the "
                           "term f3bar ||z2||^2 of (13))")),
        shown(prove_nonneg(R, "remainder R >= 0: (13)'s f3bar ||z2||^2 is not slack")),
        _with_expr(prove_identity(extra.subs(S0.Ddot, 0), "D constant (D' = 0): the term "
                                  "-(d0e - D) D'/q of V2' vanishes"),
                   sp.Eq(scalar_display(extra.subs(S0.Ddot, 0)), 0, evaluate=False)),
        Step("z2^T d - D ||z2|| <= 0 when ||d(t)|| <= D for all t (D constant)",
             Cited(CAUCHY, "z2^T d <= ||z2|| ||d|| <= D ||z2||", (
                 prove_nonneg(nz, "||z2|| >= 0"),)),
             sp.Le(DIST * Z2 - S0.D * sp.Abs(Z2), 0, evaluate=False)),
        Step("-z1^T F1 z1 - z2^T F2 z2 + f3bar||z2||^2 <= -f1bar||z1||^2 - (f2bar - "
             "f3bar)||z2||^2 (f1bar, f2bar the minimum eigenvalues of the symmetric parts)",
             Cited(RAYLEIGH, "lambda_min bounds for F1 (f1bar) and F2 (f2bar)", (
                 prove_identity(sp.expand((zz.T * (F2g - F2g.T) * zz)[0]),
                                "only the symmetric part of F2 enters z2^T F2 z2 (the "
                                "antisymmetric part's form vanishes)"),)),
             sp.Le(-F1S * Z1**2 - F2S * Z2**2 + F3B * Z2**2, -F1B * Z1**2 - (F2B - F3B) * Z2**2,
                   evaluate=False)),
    ]
    return Claim("V2dot-bound", "(7), (8), (10)-(13)",
                 "Lyapunov derivative of V2 with a constant disturbance bound",
                 "V2' <= -z1^T F1 z1 - z2^T F2 z2 + f3bar ||z2||^2 <= -f1bar||z1||^2 - "
                 "(f2bar - f3bar)||z2||^2",
                 "(13) holds with d^_0 = d0e - D in V2 (12), D a constant with ||d(t)|| <= D "
                 "for all t, B0 B0^+ = I (claim B0-rank) and d0e(0) >= 0: V2' = -z1^T F1 z1 - "
                 "z2^T F2 z2 + (z2^T d - D||z2||) + f3 d0e ||z2||^2/(d0e + f3||z2||), derived "
                 "for n1=n2=m=1 (f1, f2 unspecified functions), the orbit instance (1, 3, 3) and "
                 "the attitude instance (3, 3, 3).  The second inequality of (13) holds for any "
                 "gains; f2bar - f3bar > 0 is needed only where it is divided by or used as a "
                 "decay rate ((14), (19)), and is checked there on the gains in use",
                 tuple(steps), statement="workbench", corrects="V2dot",
                 numbers={"remainder_R": sp.sstr(R)},
                 paper_expr=paper_13(),
                 derived_expr=(sp.Eq(V2DOT, scalar_display(S0.remainder_13().subs(
                     S0.Ddot, 0)), evaluate=False),
                               sp.Le(V2DOT, scalar_display(
                                   S0.remainder_13().subs(S0.Ddot, 0)
                                   - (S0.d[0] * S0.z2s[0] - S0.D * nz) - R + f3 * nz ** 2),
                                   evaluate=False),
                               paper_13()[1]))


def _rank_display() -> sp.Basic:
    """The remainder of claim B0-rank in matrix notation (n2 = 2, m = 1): V2' minus the form
    of (13) = z2^T (I - B0 B0^+)(F2 (x2 - p) + f1^T x1 + f2 - p' + Phi), seed 001 (7), (13)."""
    n2, m, n1 = 2, 1, 1
    Ms = sp.MatrixSymbol
    z2, B0, B0p = Ms("z_2", n2, 1), Ms("B_0", n2, m), Ms("B_0^+", m, n2)
    inner = (Ms("F_2", n2, n2) * (Ms("x_2", n2, 1) - Ms("p", n2, 1))
             + Ms("f_1", n1, n2).T * Ms("x_1", n1, 1) + Ms("f_2", n2, 1) - Ms("pdot", n2, 1)
             + Ms("Phi", n2, 1))
    return sp.Eq(Ms("Vdot_2", 1, 1) - Ms("Vdot_2^(13)", 1, 1),
                 z2.T * (sp.Identity(n2) - B0 * B0p) * inner, evaluate=False)


@cache
def rank_claim() -> Claim:
    """B0 B0^+ = I is needed: the underactuated case shows the remainder."""
    S = L.underactuated_system()
    P = sp.simplify(S.B0 * S.B0pinv)
    inner = (S.F2 * (S.x2 - S.p) + S.f1.T * S.x1 + S.f2 - S.pdot + S.Phi)
    extra = S.in_z((S.z2.T * (sp.eye(S.n2) - P) * inner)[0])
    r = v2dot_residual(S)
    def pinv_eq(T: L.GeneralSystem) -> sp.Basic:
        return sp.Eq(sp.MatMul(T.B0, T.B0pinv, evaluate=False), sp.eye(T.n2), evaluate=False)
    steps = [
        _with_expr(prove_identity(sp.simplify(systems()[1].B0 * systems()[1].B0pinv
                                              - sp.eye(3)).norm() ** 2,
                                  "orbit: B0 B0^+ = I for B0 = -I/m"), pinv_eq(systems()[1])),
        _with_expr(prove_identity(sp.simplify(systems()[2].B0 * systems()[2].B0pinv
                                              - sp.eye(3)).norm() ** 2,
                                  "attitude: B0 B0^+ = I for B0 = J^-1"), pinv_eq(systems()[2])),
        Step("n2 = 2, m = 1 (rank B0 < n2): V2' - (13)'s form = z2^T (I - B0 B0^+)(F2(x2 - p) + "
             "f1^T x1 + f2 - p' + Phi)", identity_evidence(
                 sp.simplify(sp.together(r - S.norm_subs(sp.expand(extra))))),
             _rank_display()),
    ]
    return Claim("B0-rank", "(7), (13)", "B0 B0^+ = I is a hypothesis of (13)",
                 "(7) with the Moore-Penrose pseudoinverse for any B0",
                 "(13) needs B0 B0^+ = I (B0 of full row rank n2 <= m); otherwise the "
                 "remainder z2^T (I - B0 B0^+)(...) is sign-indefinite.  Both instances of the "
                 "paper satisfy it.", tuple(steps),
                 numbers={"I - B0 B0^+ (n2=2, m=1)": sp.sstr(sp.eye(2) - P)},
                 derived_expr=(sp.Eq(sp.Identity(2) - sp.MatMul(
                     sp.MatrixSymbol("B_0", 2, 1), sp.MatrixSymbol("B_0^+", 1, 2)),
                     (sp.eye(2) - P).applyfunc(sp.factor), evaluate=False), _rank_display()))


@cache
def smooth_claim() -> Claim:
    """The command (7) of the law is discontinuous at z2 = 0 when d0e > 0: its one-sided
    limits along z2 = +-s e_z of the orbit instance, computed from ``law.GeneralSystem.uc``."""
    S = systems()[1]
    s = sp.Symbol("s", positive=True)
    d0e = sp.Symbol("d_0e", positive=True)
    u = S.norm_subs(S.in_z(S.uc[2])).subs(S.d0e, d0e)

    def along(z: sp.Expr) -> sp.Expr:  # u_c,z at z2 = z e_z
        return u.subs({S.z2s[0]: 0, S.z2s[1]: 0, S.z2s[2]: z})

    def lim(x: sp.Expr) -> sp.Expr:  # unevaluated, for display
        return sp.Limit(x, s, 0, "+")
    lim_p = sp.limit(along(s), s, 0, "+")
    lim_m = sp.limit(along(-s), s, 0, "+")
    jump = sp.simplify(lim_p - lim_m)
    uz = sp.Symbol("u_cz", real=True)
    steps = [Step("orbit instance: the command u_c,z of (7) has the same one-sided limits at "
                  "z2 = 0 from z2 = +s e_z and z2 = -s e_z (continuity across {z2 = 0})",
                  identity_evidence(jump, ranges={d0e: (0.1, 3.0)}),
                  sp.Eq(lim(uz.subs(uz, sp.Symbol("u_cz(+s)"))) - lim(sp.Symbol("u_cz(-s)")),
                        jump, evaluate=False))]
    phi = lambda z: d0e ** 2 * z / (sp.Abs(z) * (d0e + S.f3 * sp.Abs(z)))  # noqa: E731
    return Claim("smooth-7", "(5), (7)", "Smoothness (local Lipschitz) of the command (7)",
                 "f1 continuously differentiable, f2 smooth; (7) used with LaSalle-Yoshizawa",
                 "the command (7) is not defined at z2 = 0 and has no continuous extension "
                 f"there once d0e > 0: its jump across z2 = 0 is {sp.sstr(jump)} (orbit "
                 "instance, z component; the term d0e^2 z2/(||z2|| d0e + f3||z2||^2) is "
                 "sign-like of size d0e): the closed loop is discontinuous on {z2 = 0}, so the "
                 "locally Lipschitz hypothesis of LaSalle-Yoshizawa fails there (claim "
                 "LaSalle-14)", tuple(steps),
                 numbers={"limit_plus": sp.sstr(lim_p), "limit_minus": sp.sstr(lim_m),
                          "jump": sp.sstr(jump)},
                 paper_expr=(sp.Eq(sp.Symbol("Phi"), phi(Z2), evaluate=False),),
                 derived_expr=(sp.Eq(sp.Symbol("u_cz(0+) - u_cz(0-)"), jump, evaluate=False),))


# --- gain sets as cache keys -----------------------------------------------------------------

def gains_key(g: Gains) -> str:
    """A gain set as a memo key (``lgw.theory.symbolic.memo``): its exact TOML values, as
    canonical JSON."""
    return json.dumps(g.to_dict(), sort_keys=True)


def lasalle_claim(g: Gains | None = None) -> Claim:
    """(14) from LaSalle-Yoshizawa for the gains in use: hypotheses as steps."""
    return _lasalle_claim(g or paper_gains())


@memo(key=gains_key)
def _lasalle_claim(g: Gains) -> Claim:
    S = systems()[0]
    V2 = S.in_z(S.V2)
    Qs = [quantities(loop, getattr(g, loop)) for loop in ("orbit", "attitude")]
    W = Cited("claim V2dot-bound of this report (the corrected (13); the printed one, with a "
              "time-varying ||d||, is refuted: claim V2dot)", "(13)",
              (lemma("V2' <= -f1bar||z1||^2 - (f2bar - f3bar)||z2||^2",
                     v2dot_bound_claim()),
               *(f2bar_minus_f3(Q) for Q in Qs)))
    hyps = (
        prove_nonneg(S.in_z(S.V2).subs(S.D, S.d0e - sp.Symbol("dhat", real=True)),
                     "V2 >= 0 (positive definite and radially unbounded in (z1, z2, d^_0))"),
        Step("V2' <= -W(z) = -f1bar||z1||^2 - (f2bar - f3bar)||z2||^2 with W continuous and "
             "positive semidefinite (f2bar - f3bar > 0 on the gains in use)", W),
        lemma("the closed-loop vector field is locally Lipschitz in the state, uniformly in t",
              smooth_claim()),
        Step("f1bar > 0 uniformly in t (F1 bounded below along the run)",
             Unproven("orbit: F1 = K1_zz constant (holds); attitude: f1bar = lambda_min(K1) "
                      "eq0^2/4 needs |eq0| bounded away from 0 along the run, a property of the "
                      "trajectory, not of the gains (claim attitude-F1; checked on the Section "
                      "5 run in claim s5-tracking)")),
    )
    steps = [Step("z1 -> 0, z2 -> 0, d0e bounded (14a), (14b)", Cited(LASALLE,
                  "bounded solutions and W(z(t)) -> 0", hyps))]
    remarks = (Step("x1, x2 -> 0 further needs lambda1, lambda2 -> 0, which holds only if "
                    "du -> 0 (no saturation, no failure after some time); with the persistent "
                    "30% failure (26) du does not vanish (claim failure-26-model)",
                    Unproven("not implied under saturation or failure")),
               Step("d0e -> ||d|| does not follow: the theorem gives boundedness of d^_0 only",
                    Unproven("no persistence-of-excitation argument in the paper")))
    nums = {"V2_z": sp.sstr(V2)}
    for Q in Qs:
        nums[f"{Q.loop}.f2bar-f3"] = float(Q.f2bar - Q.f3)
    return Claim("LaSalle-14", "(14)", "Convergence of z1, z2 by LaSalle-Yoshizawa",
                 "lim z1 = lim (x1 - lambda1) = 0, lim z2 = lim (x2 - p - lambda2) = 0",
                 "follows from (13) by LaSalle-Yoshizawa only with a locally Lipschitz closed "
                 "loop and a uniform f1bar > 0; (7) violates the first at z2 = 0 (claim "
                 "smooth-7)", tuple(steps), remarks=remarks, numbers=nums, scope="gain-set",
                 paper_expr=(sp.Eq(sp.Limit(Z1, T_, sp.oo), 0, evaluate=False),
                             sp.Eq(sp.Limit(Z2, T_, sp.oo), 0, evaluate=False)),
                 derived_expr=(sp.Eq(V2S, scalar_display(V2), evaluate=False), paper_13()[1]))


@cache
def vlambda_claim() -> Claim:
    """(15)-(17): Vlambda' along (11) and Young's inequality."""
    S = systems()[2]  # attitude instance: f1 state dependent, 3x3
    l1, l2, du = S.lam1, S.lam2, S.du
    rates = S.rates
    Vl = ((l1.T * l1)[0] + (l2.T * l2)[0]) / 2
    Vl_dot = sum(sp.diff(Vl, s) * rates[s] for s in list(l1) + list(l2))
    w = S.B0 * du
    printed16 = -(l1.T * S.F1 * l1)[0] - (l2.T * S.F2 * l2)[0] + (l2.T * w)[0]
    young = ((l2.T * l2)[0] + (w.T * w)[0]) / 2 - (l2.T * w)[0]
    Ms = sp.MatrixSymbol
    ml1, ml2, mw = Ms("lambda_1", 3, 1), Ms("lambda_2", 3, 1), Ms("B_0", 3, 3) * Ms("Delta_u", 3, 1)
    vec16 = sp.Eq(Ms("Vdot_lambda", 1, 1), -ml1.T * Ms("F_1", 3, 3) * ml1
                  - ml2.T * Ms("F_2", 3, 3) * ml2 + ml2.T * mw, evaluate=False)
    ws = sp.Symbol("w", real=True)
    steps = [_with_expr(prove_identity(sp.expand(Vl_dot - printed16), "(16): Vlambda' = -l1^T "
                                       "F1 l1 - l2^T F2 l2 + l2^T B0 du (the f1 cross terms "
                                       "cancel)"), vec16),
             _with_expr(prove_identity(sp.expand(young - ((l2 - w).T * (l2 - w))[0] / 2),
                                       "l2^T w <= |l2|^2/2 + |w|^2/2 since the difference is "
                                       "|l2 - w|^2/2"),
                        sp.Eq((LAM2**2 + ws**2) / 2 - LAM2 * ws, (LAM2 - ws) ** 2 / 2,
                              evaluate=False)),
             prove_nonneg(sp.Symbol("a", real=True) ** 2 / 2, "|l2 - w|^2 / 2 >= 0"),
             Step("(17b) with f1bar, f2bar the minimum eigenvalues of the symmetric parts "
                  "(F1(t) >= f1bar along the run): it holds whatever the sign of f2bar - 1/2, "
                  "which matters only when (17b) is integrated (claim L2-18)",
                  Cited(RAYLEIGH, "x^T F x >= lambda_min ||x||^2", (
                      prove_identity(sp.expand((l1.T * (S.F1 - S.F1.T) * l1)[0]),
                                     "only the symmetric part of F1 enters l1^T F1 l1 "
                                     "(the antisymmetric part's form vanishes)"),
                      prove_identity(sp.expand((l2.T * (S.F2 - S.F2.T) * l2)[0]),
                                     "only the symmetric part of F2 enters l2^T F2 l2"))))]
    return Claim("Vlambda-16-17", "(15)-(17)", "Derivative of Vlambda along the filter (11)",
                 "Vlambda' = -l1^T F1 l1 - l2^T F2 l2 + l2^T B0 du <= -f1bar|l1|^2 - "
                 "(f2bar - 1/2)|l2|^2 + |B0 du|^2/2",
                 "as printed (attitude instance, f1 = (eq0 I + S(eq))/2, 3x3 symbolic F2)",
                 tuple(steps), paper_expr=(vec16, sp.Le(VLDOT, -F1B * LAM1**2 - (F2B - sp.S.Half)
                                                        * LAM2**2 + (B0S * DU) ** 2 / 2,
                                                        evaluate=False)),
                 derived_expr=(sp.Eq(VLDOT, _vlambda_scalar(), evaluate=False),))


def _vlambda_scalar() -> sp.Expr:
    """Vlambda' of (15) along (11) for the scalar instance, in display names (the attitude
    instance is the claim's evidence; this is the same computation for n1 = n2 = m = 1)."""
    S = systems()[0]
    Vl = (S.lam1[0] ** 2 + S.lam2[0] ** 2) / 2
    return scalar_display(sp.expand(sum(sp.diff(Vl, x) * S.rates[x]
                                        for x in (S.lam1[0], S.lam2[0]))), z=False)
