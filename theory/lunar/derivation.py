"""Seed 001 Section 3 derived and checked: V2' (12)-(13), its hypotheses, (14), Vlambda (15)-(17),
the L2 bounds (18)-(19) and the transient bounds (20)-(21).

Every claim's verdict is computed from ``lgw.theory.evidence`` steps; nothing is typed.  The
derivation differentiates V2 (12) along the closed loop built in ``lgw.theory.lunar.law`` (the
same expressions the simulator runs) and compares with (13) term by term.
"""

from __future__ import annotations

import math
from functools import cache

import sympy as sp
from lgw.theory.evidence import Cited, Claim, Identity, Search, Step, Unproven, Witness
from lgw.theory.lunar import law as L
from lgw.theory.lunar.bounds import attitude_bounds, orbit_bounds
from lgw.theory.lunar.gains import paper_gains
from lgw.theory.provers import identity_evidence, prove_identity, prove_nonneg

CAUCHY = ("Cauchy-Schwarz inequality: z^T d <= ||z|| ||d||")
RAYLEIGH = ("Rayleigh quotient: x^T F x >= lambda_min(F) ||x||^2 for symmetric F (Horn & "
            "Johnson, Matrix Analysis, Thm 4.2.2)")
LASALLE = ("LaSalle-Yoshizawa theorem (Krstic, Kanellakopoulos, Kokotovic, Nonlinear and "
           "Adaptive Control Design, Wiley 1995, Thm A.8; seed 001 ref. [13])")
MINKOWSKI = "Minkowski inequality in L2[0, t]: ||a + b|| <= ||a|| + ||b||"


@cache
def systems() -> tuple[L.GeneralSystem, ...]:
    return (L.scalar_system(), L.orbit_system(), L.attitude_system())


def v2dot_residual(S: L.GeneralSystem, literal_d: bool = False) -> sp.Expr:
    """V2' (derived) minus the exact remainder form (``remainder_13``), in z coordinates with
    ||z2|| = sqrt(z2^T z2).  Zero when the derivation reproduces (13)'s structure."""
    r = S.in_z(S.V2dot) - S.remainder_13()
    return S.norm_subs(sp.expand(r))


def _residual_step(S: L.GeneralSystem) -> Step:
    r = v2dot_residual(S)
    simp = sp.simplify(sp.together(sp.expand(r)))
    return Step(f"{S.name} (n1={S.n1}, n2={S.n2}, m={S.m}): V2' along (5), (7), (8), (11) "
                "equals -z1^T F1 z1 - z2^T F2 z2 + [z2^T d - D||z2||] + R - (d0e - D) D'/q, "
                "R = f3 d0e ||z2||^2 / (d0e + f3 ||z2||)",
                identity_evidence(r, simplified=simp), sp.Eq(S.V2dot, S.remainder_13()))


@cache
def v2dot_claim() -> Claim:
    """Seed 001 (12)-(13): the derived V2' and the inequality (13)."""
    S0 = systems()[0]
    f3, d0e, nz, q = S0.f3, S0.d0e, S0.nz, S0.q
    R = f3 * d0e * nz ** 2 / (d0e + f3 * nz)
    steps = [_residual_step(S) for S in systems()]
    steps += [
        prove_nonneg(q * nz, "d0e' = q ||z2|| >= 0 (8), so d0e(t) >= d0e(0) >= 0"),
        prove_nonneg(f3 * nz ** 2 - R, "remainder R <= f3 ||z2||^2 when d0e >= 0 (the term "
                     "f3bar ||z2||^2 of (13))"),
        prove_nonneg(R, "remainder R >= 0: (13)'s f3bar ||z2||^2 is not slack"),
        Step("z2^T d - D ||z2|| <= 0 when ||d(t)|| <= D for all t (D constant)",
             Cited(CAUCHY, "z2^T d <= ||z2|| ||d|| <= D ||z2||", (
                 prove_nonneg(nz, "||z2|| >= 0"),))),
        Step("with D constant (D' = 0) the last term vanishes; -z1^T F1 z1 - z2^T F2 z2 + "
             "f3bar||z2||^2 <= -f1bar||z1||^2 - (f2bar - f3bar)||z2||^2",
             Cited(RAYLEIGH, "lambda_min bounds for F1 (f1bar) and F2 (f2bar)", (
                 prove_nonneg(sp.Symbol("eps", positive=True), "f2bar - f3bar = eps > 0: a gain "
                              "hypothesis the gains loader enforces (0 < f3 < f2bar)",
                              strict=True),))),
    ]
    # The paper's literal d^_0 = d0e - ||d(t)|| with a time-varying ||d||: the extra term.
    Ddot = S0.Ddot
    extra = -(d0e - S0.D) * Ddot / q
    pt = {d0e: sp.Rational(0), S0.D: sp.Rational(1), Ddot: sp.Rational(1), q: sp.Rational(1)}
    w = Witness({str(k): str(v) for k, v in pt.items()}, -float(extra.subs(pt)),
                "the extra term -(d0e - ||d||) (d/dt ||d||)/q at an exact point",
                -float(sp.N(extra.subs(pt), 60)), "the same term at 60 digits")
    remarks = (Step("with the paper's d^_0 = d0e - ||d(t)|| and a time-varying ||d|| (Section 5: "
                    "||J^-1 d_M|| varies), V2' has the extra term -(d0e - ||d||) (d/dt||d||)/q, "
                    "positive e.g. at d0e = 0, ||d|| = 1, d/dt||d|| = 1, q = 1: (13) then needs "
                    "a constant bound D in place of ||d(t)||",
                    Identity(extra, "sympy (extra term)", w)),)
    return Claim("V2dot", "(7), (8), (10)-(13)", "Lyapunov derivative of V2 along the closed loop",
                 "V2' <= -z1^T F1 z1 - z2^T F2 z2 + f3bar ||z2||^2 <= -f1bar||z1||^2 - "
                 "(f2bar - f3bar)||z2||^2",
                 "V2' = -z1^T F1 z1 - z2^T F2 z2 + (z2^T d - D||z2||) + f3 d0e ||z2||^2/(d0e + "
                 "f3||z2||), derived for n1=n2=m=1 (f1, f2 unspecified functions), the orbit "
                 "instance (1, 3, 3) and the attitude instance (3, 3, 3); (13) follows when "
                 "B0 B0^+ = I, d0e(0) >= 0 and ||d(t)|| <= D with D constant (the paper's "
                 "||d|| read as a constant bound)", tuple(steps), remarks=remarks,
                 numbers={"remainder_R": sp.sstr(R),
                          "extra_term_time_varying_d": sp.sstr(extra)})


@cache
def rank_claim() -> Claim:
    """B0 B0^+ = I is needed: the underactuated case shows the remainder."""
    S = L.underactuated_system()
    P = sp.simplify(S.B0 * S.B0pinv)
    inner = (S.F2 * (S.x2 - S.p) + S.f1.T * S.x1 + S.f2 - S.pdot + S.Phi)
    extra = S.in_z((S.z2.T * (sp.eye(S.n2) - P) * inner)[0])
    r = v2dot_residual(S)
    steps = [
        prove_identity(sp.simplify(systems()[1].B0 * systems()[1].B0pinv - sp.eye(3)).norm() ** 2,
                       "orbit: B0 B0^+ = I for B0 = -I/m"),
        prove_identity(sp.simplify(systems()[2].B0 * systems()[2].B0pinv - sp.eye(3)).norm() ** 2,
                       "attitude: B0 B0^+ = I for B0 = J^-1"),
        Step("n2 = 2, m = 1 (rank B0 < n2): V2' - (13)'s form = z2^T (I - B0 B0^+)(F2(x2 - p) + "
             "f1^T x1 + f2 - p' + Phi)", identity_evidence(
                 sp.simplify(sp.together(r - S.norm_subs(sp.expand(extra)))))),
    ]
    return Claim("B0-rank", "(7), (13)", "B0 B0^+ = I is a hypothesis of (13)",
                 "(7) with the Moore-Penrose pseudoinverse for any B0",
                 "(13) needs B0 B0^+ = I (B0 of full row rank n2 <= m); otherwise the "
                 "remainder z2^T (I - B0 B0^+)(...) is sign-indefinite.  Both instances of the "
                 "paper satisfy it.", tuple(steps),
                 numbers={"I - B0 B0^+ (n2=2, m=1)": sp.sstr(sp.eye(2) - P)})


@cache
def smooth_claim() -> Claim:
    """The adaptive term of (7) is discontinuous at z2 = 0 when d0e > 0."""
    s = sp.Symbol("s", positive=True)
    d0e = sp.Symbol("d_0e", positive=True)
    f3 = sp.Symbol("f3", positive=True)
    # scalar z2 = +s and -s: Phi = d0e^2 z2 / (|z2| (d0e + f3 |z2|))
    phi = lambda z: d0e ** 2 * z / (sp.Abs(z) * (d0e + f3 * sp.Abs(z)))  # noqa: E731
    lim_p = sp.limit(phi(s), s, 0, "+")
    lim_m = sp.limit(phi(-s), s, 0, "+")
    jump = sp.simplify(lim_p - lim_m)
    steps = [Step("the adaptive term d0e^2 z2/(||z2|| d0e + f3||z2||^2) of (7) has one-sided "
                  "limits +d0e and -d0e at z2 = 0 (direction z2/||z2||): its jump is zero only "
                  "if d0e = 0", identity_evidence(jump, ranges={d0e: (0.1, 3.0)}),
                  sp.Eq(jump, 0))]
    return Claim("smooth-7", "(5), (7)", "Smoothness (local Lipschitz) of the command (7)",
                 "f1 continuously differentiable, f2 smooth; (7) used with LaSalle-Yoshizawa",
                 "the command (7) is not defined at z2 = 0 and has no continuous extension "
                 "there once d0e > 0 (a sign-like term of size d0e): the closed loop is "
                 "discontinuous on {z2 = 0}, so the locally Lipschitz hypothesis of "
                 "LaSalle-Yoshizawa fails there (claim LaSalle-14)", tuple(steps),
                 numbers={"limit_plus": sp.sstr(lim_p), "limit_minus": sp.sstr(lim_m)})


@cache
def lasalle_claim() -> Claim:
    """(14) from LaSalle-Yoshizawa: hypotheses as steps."""
    S = systems()[0]
    V2 = S.in_z(S.V2)
    hyps = (
        prove_nonneg(S.in_z(S.V2).subs(S.D, S.d0e - sp.Symbol("dhat", real=True)),
                     "V2 >= 0 (positive definite and radially unbounded in (z1, z2, d^_0))"),
        Step("V2' <= -W(z) = -f1bar||z1||^2 - (f2bar - f3bar)||z2||^2 with W continuous, "
             "positive semidefinite (claim V2dot; needs ||d|| <= D constant, B0 B0^+ = I)",
             Cited("claim V2dot of this report", "(13)", v2dot_claim().steps)),
        Step("the closed-loop vector field is locally Lipschitz in the state, uniformly in t",
             Unproven("fails on {z2 = 0} when d0e > 0 (claim smooth-7); a nonsmooth "
                      "(Filippov / Clarke) version of the theorem would be needed, with "
                      "solutions understood in that sense: not checked here")),
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
                    "30% failure (26) du does not vanish (claim L2-finite)",
                    Unproven("not implied under saturation or failure")),
               Step("d0e -> ||d|| does not follow: the theorem gives boundedness of d^_0 only",
                    Unproven("no persistence-of-excitation argument in the paper")))
    return Claim("LaSalle-14", "(14)", "Convergence of z1, z2 by LaSalle-Yoshizawa",
                 "lim z1 = lim (x1 - lambda1) = 0, lim z2 = lim (x2 - p - lambda2) = 0",
                 "follows from (13) by LaSalle-Yoshizawa only with a locally Lipschitz closed "
                 "loop and a uniform f1bar > 0; (7) violates the first at z2 = 0",
                 tuple(steps), remarks=remarks, numbers={"V2_z": sp.sstr(V2)})


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
    steps = [prove_identity(sp.expand(Vl_dot - printed16), "(16): Vlambda' = -l1^T F1 l1 - "
                            "l2^T F2 l2 + l2^T B0 du (the f1 cross terms cancel)"),
             prove_identity(sp.expand(young - ((l2 - w).T * (l2 - w))[0] / 2),
                            "l2^T w <= |l2|^2/2 + |w|^2/2 since the difference is |l2 - w|^2/2"),
             prove_nonneg(sp.Symbol("a", real=True) ** 2 / 2, "|l2 - w|^2 / 2 >= 0"),
             Step("(17b) with f1bar, f2bar the minimum eigenvalues (F1 uniformly >= f1bar)",
                  Cited(RAYLEIGH, "x^T F x >= lambda_min ||x||^2", (
                      prove_identity(sp.expand((l1.T * (S.F1 - S.F1.T) * l1)[0]),
                                     "only the symmetric part of F1 enters l1^T F1 l1 "
                                     "(the antisymmetric part's form vanishes)"),
                      prove_nonneg(sp.Symbol("eps", positive=True), "f2bar - 1/2 = eps > 0 "
                                   "(gains loader)", strict=True))))]
    return Claim("Vlambda-16-17", "(15)-(17)", "Derivative of Vlambda along the filter (11)",
                 "Vlambda' = -l1^T F1 l1 - l2^T F2 l2 + l2^T B0 du <= -f1bar|l1|^2 - "
                 "(f2bar - 1/2)|l2|^2 + |B0 du|^2/2",
                 "as printed (attitude instance, f1 = (eq0 I + S(eq))/2, 3x3 symbolic F2)",
                 tuple(steps))


def _hinf_search(name: str, gain: float, hinf: dict, key: str) -> Step:
    margin = gain - hinf[f"{key}_hinf"]
    return Step(f"{name}: true L2 gain of (11) to {key} (python-control linfnorm, SLICOT AB13DD; "
                f"dense frequency sweep {hinf[f'{key}_sweep']:.6g}) = {hinf[f'{key}_hinf']:.6g} "
                f"<= the (18) constant {gain:.6g}",
                Search({"frequency": "[0, 1e4] rad/s", "system": name}, "linfnorm + sweep",
                       4001, margin, {"peak_rad_s": hinf[f"{key}_peak_rad_s"]}))


@cache
def l2_claim() -> Claim:
    """(18): derived constants and the true filter gains for the paper's gains."""
    f1b, f2b, W, X1, X2 = sp.symbols("f1bar f2bar W X1 X2", positive=True)
    # Integrating (17b) from 0 to t with Vlambda(0) = 0: f1bar X1 <= W/2, (f2bar - 1/2) X2 <= W/2
    # (X = ||lambda||^2, W = ||B0 du||^2): X1 <= W/(2 f1bar), X2 <= W/(2 f2bar - 1).
    c1 = sp.sqrt(W / (2 * f1b)) / sp.sqrt(W)
    eps = sp.Symbol("eps", positive=True)  # f2bar - 1/2 > 0
    c2 = (sp.sqrt(W / (2 * (f2b - sp.Rational(1, 2)))) / sp.sqrt(W)).subs(f2b, eps + sp.S.Half)
    g = paper_gains()
    ob, ab = orbit_bounds(g.orbit), attitude_bounds(g.attitude, 1.0)
    steps = [prove_identity(sp.simplify(c1 - 1 / sp.sqrt(2 * f1b)),
                            "(18a) constant 1/sqrt(2 f1bar) from integrating (17b)"),
             prove_identity(sp.simplify(c2 - 1 / sp.sqrt(2 * (eps + sp.S.Half) - 1)),
                            "(18b) constant 1/sqrt(2 f2bar - 1) from integrating (17b)"),
             _hinf_search("orbit (paper gains)", ob.lambda1_gain, ob.hinf, "lambda1"),
             _hinf_search("orbit (paper gains)", ob.lambda2_gain, ob.hinf, "lambda2"),
             _hinf_search("attitude frozen at e_Q = [1,0,0,0]", ab.lambda1_gain, ab.hinf,
                          "lambda1"),
             _hinf_search("attitude frozen at e_Q = [1,0,0,0]", ab.lambda2_gain, ab.hinf,
                          "lambda2")]
    nums = {"orbit": ob.to_dict(), "attitude_eq0_1": ab.to_dict()}
    return Claim("L2-18", "(17), (18)", "L2 bounds on the virtual states",
                 "||lambda1|| <= ||B0 du||/sqrt(2 f1bar), ||lambda2|| <= ||B0 du||/sqrt(2 f2bar "
                 "- 1)", "as printed, norms in L2[0, t] for every t; beside them the true "
                 "H-infinity gains of the filter (orbit: LTI; attitude: frozen at the target)",
                 tuple(steps), scope="gain-set", numbers=nums)


@cache
def z_l2_claim() -> Claim:
    """(19)-(20) derived from (13)."""
    f1b, f2b, f3b, V0 = sp.symbols("f1bar f2bar f3bar V20", positive=True)
    d0e0, Dd, q = sp.symbols("d0e0 D q", nonnegative=True)
    # (13) integrated: f1bar Z1 + (f2bar - f3bar) Z2 <= V2(0) - V2(t) <= V2(0)
    Z2_derived = V0 / (f2b - f3b)
    Z2_printed = V0 / f2b
    diff = sp.simplify(Z2_printed - Z2_derived)
    pt = {f2b: sp.Integer(1), f3b: sp.Rational(1, 4), V0: sp.Integer(1)}
    w = Witness({str(k): str(v) for k, v in pt.items()}, float(diff.subs(pt)),
                "printed minus derived constant of (19b) at an exact point",
                float(sp.N(diff.subs(pt), 60)), "60 digits")
    Z1, Z2, sl = sp.symbols("Z1 Z2 slack", nonnegative=True)
    # (13) integrated from 0 to t: f1bar Z1 + (f2bar - f3bar) Z2 + slack = V2(0), slack =
    # V2(t) + the integral of the dropped nonpositive terms >= 0; Z = squared L2 norms.
    Z1_of = (V0 - (f2b - f3b) * Z2 - sl) / f1b
    Z2_of = (V0 - f1b * Z1 - sl) / (f2b - f3b)
    gap = sp.Symbol("eps", positive=True)  # f2bar - f3bar
    steps = [
        prove_nonneg(sp.simplify((V0 / f1b - Z1_of).subs(f2b, f3b + gap)),
                     "(19a): V2(0)/f1bar - ||z1||^2 >= 0 from integrating (13)"),
        prove_nonneg(sp.simplify((V0 / (f2b - f3b) - Z2_of).subs(f2b, f3b + gap)),
                     "(19b) derived: V2(0)/(f2bar - f3bar) - ||z2||^2 >= 0"),
        Step("(19b) printed is nonetheless true",
             Unproven("(13) gives only f2bar - f3bar; the printed constant is smaller than the "
                      "derived one (it claims more) and no other argument is offered")),
        Step("(20) V2(0) omits (d0e(0) - ||d||)^2/(2q) of (12); z2(0) = x2(0) - A1 f1^T x1(0) "
             "with A1 undefined, read A1 = -K1 (p(0) = -K1 f1^T x1(0), lambda(0) = 0)",
             Unproven("the printed V2(0) is smaller than V2(0) of (12) by (d0e(0) - D)^2/(2q) "
                      "unless d0e(0) = D; the bound uses the full V2(0)")),
    ]
    return Claim("L2-19-20", "(19), (20)", "L2 bounds on z1, z2",
                 "||z1||^2 <= V2(0)/f1bar, ||z2||^2 <= V2(0)/f2bar, V2(0) = |z1(0)|^2/2 + "
                 "|z2(0)|^2/2", "||z1||^2 <= V2(0)/f1bar, ||z2||^2 <= V2(0)/(f2bar - f3bar), "
                 "V2(0) = |z1(0)|^2/2 + |z2(0)|^2/2 + (d0e(0) - D)^2/(2q), z2(0) = x2(0) + K1 "
                 "f1^T x1(0)", tuple(steps), remarks=(
                     Step("(19b) as printed (V2(0)/f2bar) equals what (13) gives "
                          "(V2(0)/(f2bar - f3bar))", Identity(diff, "sympy.simplify", w),
                          sp.Eq(Z2_printed, Z2_derived)),))


@cache
def transient_claim() -> Claim:
    """(21) from (18), (19) by Minkowski."""
    f1b, V0, W = sp.symbols("f1bar V20 W", positive=True)
    derived_a = sp.sqrt(V0 / f1b) + W / sp.sqrt(2 * f1b)
    printed_a = (sp.sqrt(2 * V0) + W) / sp.sqrt(2 * f1b)
    S = systems()[1]
    steps = [Step("x1 = z1 + lambda1 (9a)", Cited(MINKOWSKI, "||x1|| <= ||z1|| + ||lambda1||", (
        prove_identity(sp.expand(S.x1 - S.lam1 - S.z1).norm() ** 2, "x1 - lambda1 - z1 = 0 "
                       "(orbit instance)"),
        prove_identity(sp.expand(S.x2 - S.lam2 - S.p - S.z2).norm() ** 2,
                       "x2 - lambda2 - p - z2 = 0 (for (21b))")))),
             prove_identity(sp.simplify(derived_a - printed_a), "(21a): sqrt(V2(0)/f1bar) + "
                            "||B0 du||/sqrt(2 f1bar) = (sqrt(2 V2(0)) + ||B0 du||)/sqrt(2 "
                            "f1bar)")]
    remarks = (Step("(21b) as printed: its first term uses the printed (19b) (1/sqrt(f2bar)), "
                    "c2bar is never defined (read f2bar - 1/2, the (18b) constant), A1 is never "
                    "defined (read -K1) and ||A1 f1^T|| ||x1|| needs the supremum over the run "
                    "of the operator norm; the workbench's (21b) has sqrt(V2(0)/(f2bar - f3bar))",
                    Unproven("inherits (19b)")),)
    return Claim("transient-21", "(21)", "Transient L2 bounds on x1 and x2",
                 "(21a) ||x1|| <= (sqrt(2 V2(0)) + ||B0 du||)/sqrt(2 f1bar); (21b) ||x2|| <= "
                 "sqrt(V2(0)/f2bar) + ||B0 du||/sqrt(2 c2bar) + ||A1 f1^T|| ||x1||",
                 "(21a) as printed with V2(0) of (12); (21b) with f2bar - f3bar, c2bar = f2bar "
                 "- 1/2, A1 = -K1 (bounds.transient_bounds)", tuple(steps), remarks=remarks)


def sqrt_or_nan(x: float) -> float:
    return math.sqrt(x) if x >= 0 else float("nan")
