"""Symbolic proofs of the general settling-time results of seed 000: Lemma 1, Lemma 2 (3),
the exact bound T*, the exact T(V0), and Theorem 1 (5)-(6).

Every step's status comes from its evidence (``lgw.theory.evidence``); published lemmas are
``Cited`` with their hypotheses as checked steps.

Exponent conditions are encoded by reparametrising (p k = 1 - e1, g k = 1 + e2 with e1 in (0, 1),
e2 > 0) so that SymPy's integrals converge without side conditions.
"""

from __future__ import annotations

import math

import sympy as sp
from lgw.theory.evidence import Cited, Claim, Step
from lgw.theory.provers import (
    identity_evidence,
    prove_identity,
    prove_nonneg,
    prove_z3,
    witness_step,
)
from lgw.theory.symbolic import memo, sig

V, V0, t, u = sp.symbols("V V_0 t u", positive=True)
a, b, k, eta = sp.symbols("a b k eta", positive=True)
e1, e2 = sp.symbols("epsilon_1 epsilon_2", positive=True)  # 1 - p k, g k - 1
theta = sp.Symbol("theta", positive=True)
p_sym = (1 - e1) / k
g_sym = (1 + e2) / k
# The hypotheses as sampling ranges for a witness (pk = 1 - e1 in (0, 1), 0 < theta < 1): an
# identity that fails is refuted only at a point where the lemma claims it.
HYPOTHESES = {e1: (0.0, 1.0), theta: (0.0, 1.0)}


def _identity(expr: sp.Expr, statement: str) -> Step:
    """``prove_identity`` with the witness sampler kept inside ``HYPOTHESES``."""
    return prove_identity(expr, statement, ranges=HYPOTHESES)


def polyakov_expr(a_, b_, p_, g_, k_) -> sp.Expr:
    """Seed 000, eq. (3)."""
    return 1 / (a_**k_ * (1 - p_ * k_)) + 1 / (b_**k_ * (g_ * k_ - 1))


def exact_expr(a_, b_, p_, g_, k_) -> sp.Expr:
    """T* = Gamma(m_p) Gamma(m_g) / (a^k Gamma(k) (g - p)) (a/b)^m_p (Aldana-Lopez et al. 2019)."""
    d = g_ - p_
    mp, mg = (1 - k_ * p_) / d, (k_ * g_ - 1) / d
    return sp.gamma(mp) * sp.gamma(mg) / (a_**k_ * sp.gamma(k_) * d) * (a_ / b_) ** mp


def _log_ratio(lhs: sp.Expr, rhs: sp.Expr) -> sp.Expr:
    """log(lhs) - log(rhs) for positive expressions, reduced as a linear combination of logs
    whose coefficients are cancelled one by one (zero iff lhs == rhs)."""
    lhs, rhs = (sp.factor(sp.together(x)) for x in (lhs, rhs))
    expr = sp.expand(sp.expand_log(sp.log(lhs) - sp.log(rhs), force=True))
    logs = sorted(expr.atoms(sp.log), key=sp.default_sort_key)
    coeffs = sp.collect(expr, logs, evaluate=False)
    return sp.Add(*(sp.cancel(sp.together(c)) * (1 if term == 1 else term)
                    for term, c in coeffs.items()))


# Published results the proofs cite (their hypotheses are checked steps).
COMPARISON = "H. K. Khalil, Nonlinear Systems, 3rd ed., Prentice Hall 2002, Lemma 3.4 " \
             "(comparison lemma)"
INTEGRAL_MONOTONE = "W. Rudin, Principles of Mathematical Analysis, 3rd ed., Thm 6.12(b) " \
                    "(monotonicity of the integral; improper integrals as limits)"
INVARIANCE = "H. K. Khalil, Nonlinear Systems, 3rd ed., Sec. 4.8 (a sublevel set on whose " \
             "boundary V' < 0 is positively invariant)"


def _integral_step(integrand, lo, hi, expected, statement) -> Step:
    val = sp.integrate(integrand, (V, lo, hi), conds="none")
    return Step(statement, identity_evidence(sp.simplify(val - expected),
                                             method="sympy.integrate, then sympy.simplify",
                                             ranges=HYPOTHESES),
                sp.Eq(sp.Integral(integrand, (V, lo, hi)), expected, evaluate=False))


def _increasing_power(kk: sp.Expr, statement: str) -> Step:
    """x -> x^k is increasing on x > 0 for k > 0: its derivative k x^(k-1) is > 0."""
    x = sp.Symbol("x", positive=True)
    return prove_nonneg(sp.diff(x**kk, x), statement, strict=True)


@memo
def lemma1() -> Claim:
    p1 = 1 - e1  # 0 < p < 1
    h_pos = prove_nonneg(a * V**p1, "h(V) = a V^p > 0 on V > 0 (hypothesis of the comparison "
                         "lemma)", strict=True)
    integral = _integral_step(1 / (a * V**p1), 0, V0, V0 ** (1 - p1) / (a * (1 - p1)),
                              "int_0^V0 dV/(a V^p) = V0^(1-p)/(a (1-p))")
    steps = [
        h_pos,
        Step("V' <= -h(V) with h > 0 reaches 0 no later than the solution of V' = -h(V), "
             "i.e. within int_0^V0 dV/h(V)",
             Cited(COMPARISON, "comparison lemma, with separation of variables for V' = -h(V)",
                   (h_pos,))),
        integral,
    ]
    return Claim("lemma1", "Lemma 1, (1)", "Finite-time stability: settling-time bound",
                 "V' <= -a V^p, 0<p<1  =>  T <= V0^(1-p)/(a(1-p))",
                 "Same bound; it is attained by V' = -a V^p (equality), so it is tight.", steps)


def _lemma2_pointwise() -> tuple[Step, ...]:
    p_, g_ = p_sym, g_sym
    return (
        prove_nonneg(b * V**g_, "b V^g >= 0, so a V^p + b V^g >= a V^p"),
        prove_nonneg(a * V**p_, "a V^p >= 0, so a V^p + b V^g >= b V^g"),
        _increasing_power(k, "x -> x^k is increasing on x > 0 (k > 0), so (a V^p + b V^g)^k "
                          ">= (a V^p)^k and >= (b V^g)^k"),
    )


def _lemma2_integrals() -> tuple[Step, ...]:
    p_, g_ = p_sym, g_sym
    return (
        _integral_step((a * V**p_) ** (-k), 0, 1, 1 / (a**k * (1 - p_ * k)),
                       "int_0^1 dV/(a V^p)^k = 1/(a^k (1 - p k))  (p k < 1)"),
        _integral_step((b * V**g_) ** (-k), 1, sp.oo, 1 / (b**k * (g_ * k - 1)),
                       "int_1^oo dV/(b V^g)^k = 1/(b^k (g k - 1))  (g k > 1)"),
    )


def _split_integral_step(statement: str) -> Step:
    pw = _lemma2_pointwise()
    return Step(statement, Cited(INTEGRAL_MONOTONE, "int_0^oo f <= int_0^1 f1 + int_1^oo f2 "
                                 "when f <= f1 on (0, 1) and f <= f2 on (1, oo)",
                                 pw + _lemma2_integrals()))


@memo
def lemma2() -> Claim:
    pw = _lemma2_pointwise()
    h_pos = prove_nonneg((a * V**p_sym + b * V**g_sym) ** k, "(a V^p + b V^g)^k > 0 on V > 0 "
                         "(hypothesis of the comparison lemma)", strict=True)
    steps = [
        *pw,
        Step("T <= int_0^oo dV/(a V^p + b V^g)^k",
             Cited(COMPARISON, "comparison lemma: V reaches 0 no later than the solution of "
                   "V' = -(a V^p + b V^g)^k from V0, which takes int_0^V0 <= int_0^oo", (h_pos,))),
        _split_integral_step("int_0^oo dV/(a V^p + b V^g)^k <= int_0^1 dV/(a V^p)^k + "
                             "int_1^oo dV/(b V^g)^k"),
        *_lemma2_integrals(),
    ]
    return Claim("lemma2", "(2)-(3)", "Lemma 2: fixed-time settling bound (Polyakov form)",
                 "V' <= -(a V^p + b V^g)^k, pk<1<gk  =>  T <= 1/(a^k(1-pk)) + 1/(b^k(gk-1))",
                 "Holds; it splits the integral at V = 1, so it is not tight and not invariant "
                 "under V -> cV.  The least upper bound is T* (claim 'exact-bound').", steps)


def _substitution_steps() -> tuple[Step, ...]:
    """V = (t/c)^(1/d) turns int dV/(aV^p+bV^g)^k into a^-k c^-m/d int t^(m-1)(1+t)^-k dt."""
    p_, g_ = p_sym, g_sym
    d = g_ - p_
    m = (1 - k * p_) / d
    c = b / a
    # In three monomial steps SymPy can reduce:
    # a V^p + b V^g = a V^p (1 + c V^d);  c V^d = t;  (dV/dt) V^(-kp) = c^-m t^(m-1) / d.
    Vt = (t / c) ** (1 / d)
    sub1 = sp.expand(a * V**p_ * (1 + c * V**d)) - (a * V**p_ + b * V**g_)
    sub2 = _log_ratio(c * Vt**d, t)
    sub3 = _log_ratio(sp.diff(Vt, t) * Vt ** (-k * p_), c ** (-m) * t ** (m - 1) / d)
    return (
        _identity(sp.powsimp(sub1, force=True),
                       "a V^p + b V^g = a V^p (1 + c V^d), c = b/a, d = g - p"),
        _identity(sub2, "with V = (t/c)^(1/d): c V^d = t (log form)"),
        _identity(sub3, "(dV/dt) V^(-kp) = c^(-m) t^(m-1)/d, m = (1-kp)/d; hence "
                       "dV/(aV^p+bV^g)^k = a^-k c^-m/d * t^(m-1) (1+t)^-k dt (log form)"),
    )


@memo
def exact_bound_claim() -> Claim:
    p_, g_ = p_sym, g_sym
    d = g_ - p_
    m = (1 - k * p_) / d
    c = b / a
    mm, kk = sp.symbols("m k", positive=True)
    beta_int = sp.integrate(t ** (mm - 1) * (1 + t) ** (-kk), (t, 0, sp.oo), conds="none")
    steps = [
        *_substitution_steps(),
        _identity(beta_int - sp.gamma(mm) * sp.gamma(kk - mm) / sp.gamma(kk),
                       "int_0^oo t^(m-1) (1+t)^-k dt = Gamma(m) Gamma(k-m)/Gamma(k)  (0 < m < k)"),
        _identity(sp.simplify(a ** (-k) * c ** (-m) / d * sp.gamma(m) * sp.gamma(k - m)
                                   / sp.gamma(k) - exact_expr(a, b, p_, g_, k)),
                       "a^-k c^-m B(m, k-m)/d equals the closed form T*; k - m = (kg-1)/d"),
        # T* <= (3): SymPy's assumptions answer None on the closed forms (unproven); the
        # inequality holds because T* is the integral that Lemma 2's split bounds.
        _split_integral_step("T* = int_0^oo dV/(aV^p+bV^g)^k <= (3), by Lemma 2's split of the "
                             "same integral"),
    ]
    return Claim("exact-bound", "(2)-(3), not in the paper",
                 "Least upper bound of the settling time under (2)",
                 "(not stated; the paper uses (3))",
                 "T* = Gamma(m_p) Gamma(m_g) (a/b)^m_p / (a^k Gamma(k) (g-p)), "
                 "m_p = (1-kp)/(g-p), m_g = (kg-1)/(g-p); attained as V0 -> oo by "
                 "V' = -(aV^p+bV^g)^k; T* <= (3).", steps, statement="workbench",
                 remarks=(prove_nonneg(polyakov_expr(a, b, p_, g_, k) - exact_expr(a, b, p_, g_, k),
                                       "T* <= (3) directly on the closed forms (SymPy "
                                       "assumptions; None is unproven, so the proof goes "
                                       "through the integral instead)"),))


@memo
def exact_time_claim() -> Claim:
    p_, g_ = p_sym, g_sym
    d = g_ - p_
    m = (1 - k * p_) / d
    # Second substitution t = u/(1-u) turns int_0^t0 t^(m-1)(1+t)^-k dt into the incomplete
    # Beta integral int_0^u0 u^(m-1) (1-u)^(k-m-1) du.
    # Checked in the direction u = t/(1+t), where every base is manifestly positive.
    ut = t / (1 + t)
    lhs = sp.diff(ut, t) * ut ** (m - 1) * (1 - ut) ** (k - m - 1)
    rhs = t ** (m - 1) * (1 + t) ** (-k)
    res = _log_ratio(lhs, rhs)
    steps = [
        *_substitution_steps(),
        _identity(res, "t = u/(1-u) maps t^(m-1)(1+t)^-k dt to u^(m-1)(1-u)^(k-m-1) du, "
                       "u0 = t0/(1+t0), t0 = c V0^d (log form)"),
    ]
    return Claim("exact-time", "(16), not in the paper",
                 "Exact settling time from a given initial value",
                 "(not stated)",
                 "T(V0) = T* I_u0(m_p, m_g), u0 = c V0^d/(1 + c V0^d), I the regularised "
                 "incomplete Beta function; for the reaching law (16) take V = |s1|, "
                 "(a, b, p, g) = (beta1, beta2, q1, q2), k = 1.  The numeric implementation is "
                 "cross-checked against quadrature and an ODE solve in tests.", steps,
                 statement="workbench")


# Theorem 1's counterexample system, seed 000 (1) with f(x) = -sig(x,1/2) - sig(x,2) + 1, and
# the constants of (4) it satisfies with V = |x|.
X_CE = sp.Symbol("x", real=True)
CE_SYSTEM = -sig(X_CE, sp.Rational(1, 2)) - sig(X_CE, 2) + 1
CE_CONSTANTS = {"a": sp.Integer(1), "b": sp.Integer(1), "p": sp.Rational(1, 2),
                "g": sp.Integer(2), "k": sp.Integer(1), "eta": sp.Integer(1)}


def theorem1_counterexample(f: sp.Expr = CE_SYSTEM) -> tuple[float, float]:
    """The positive equilibrium x* of x' = f(x) (seed 000 Theorem 1's counterexample system
    by default), by two routes: exact (with x = y^2, y > 0, f(y^2) is a polynomial in y; its
    positive real roots by SymPy, at 30 digits, squared) and bracketing (scipy brentq on f
    over [0, 1], evaluated in floating point)."""
    from scipy.optimize import brentq

    y = sp.Symbol("y", positive=True)
    poly = sp.Poly(sp.expand(f.subs(X_CE, y**2)), y)
    roots = [rt for rt in poly.real_roots() if rt.is_positive]
    x_exact = float(sp.N(roots[0] ** 2, 30))
    fx = sp.lambdify(X_CE, f, modules=[{"sig": lambda a_, q: math.copysign(abs(a_) ** q, a_)},
                                       "math"])
    x_brent = brentq(fx, 0.0, 1.0, xtol=1e-15, rtol=1e-15)
    return x_exact, x_brent


def _condition4_steps(f: sp.Expr = CE_SYSTEM) -> list[Step]:
    """(4) for x' = f(x) with V = |x| and CE_CONSTANTS, computed on each sign branch of x:
    V' = sgn(x) f(x), and (-(a V^p + b V^g)^k + eta) - V' >= 0."""
    c = CE_CONSTANTS
    xp = sp.Symbol("x_abs", positive=True)
    out = []
    for sg in (1, -1):
        vdot = (sp.diff(sp.Abs(X_CE), X_CE) * f).subs(X_CE, sg * xp)
        bound = -(c["a"] * xp ** c["p"] + c["b"] * xp ** c["g"]) ** c["k"] + c["eta"]
        out.append(prove_nonneg(sp.simplify(bound - vdot),
                                f"(4) holds for x' = f(x) on x {'>' if sg > 0 else '<'} 0: "
                                "(-(a V^p + b V^g)^k + eta) - V' >= 0 with V = |x|, V' = sgn(x) "
                                "f(x) (computed from f)"))
    return out


@memo
def theorem1_corrected() -> Claim:
    """What the workbench proves of Theorem 1: V reaches the set (5) within (6) and stays."""
    p_, g_ = p_sym, g_sym
    X = sp.Symbol("X", positive=True)  # X = a V^p + b V^g
    th = theta
    Y, A_, tk, et = sp.symbols("Y A t_k eta", real=True)  # Y = X^k, A = (aV^p)^k, tk = theta^k
    outside = prove_z3(sp.Le(-(1 - tk) * Y + et, 0),
                       [sp.Ge(Y, A_), sp.Ge(A_ * (1 - tk), et), sp.Gt(tk, 0), sp.Lt(tk, 1)],
                       "(8)-(9): if X^k >= A with A >= eta/(1-theta^k) (A = (a V^p)^k or (b V^g)^k)"
                       ", then -(1-theta^k) X^k + eta <= 0, so V' <= -theta^k X^k")
    mono = _lemma2_pointwise()
    dec = prove_nonneg(th**k * X**k, "theta^k X^k > 0: outside (5) V' < 0", strict=True)
    printed6 = 1 / (a**k * th**k * (1 - p_ * k)) + 1 / (b**k * th**k * (g_ * k - 1))
    scaled = _identity(polyakov_expr(th * a, th * b, p_, g_, k) - printed6,
                            "(6) is Lemma 2's (3) with (a, b) -> (theta a, theta b)")
    steps = [
        _identity(-(X**k) + eta - (-(1 - th**k) * X**k - th**k * X**k + eta),
                       "(7): -(X)^k + eta = -(1-theta^k) X^k - theta^k X^k + eta"),
        *mono, outside, dec,
        Step("outside the set (5), V' <= -((theta a) V^p + (theta b) V^g)^k < 0: V reaches (5) "
             "within (6) and never leaves it",
             Cited(COMPARISON + "; " + INVARIANCE, "comparison lemma applied with Lemma 2 to "
                   "(theta a, theta b); positive invariance of the sublevel set",
                   (outside, dec, scaled))),
        scaled,
    ]
    return Claim("theorem1-corrected", "(4)-(6), (7)-(9)",
                 "Theorem 1 as the workbench proves it: practical fixed-time stability",
                 "V' <= -(aV^p+bV^g)^k + eta => the origin is fixed-time stable, V reaches "
                 "(5) within (6)",
                 "V reaches the set (5) within (6) and stays there (proved, given the comparison "
                 "lemma): practical fixed-time stability of the set (5), not of the origin.",
                 steps, statement="workbench", corrects="theorem1")


@memo
def theorem1() -> Claim:
    """Theorem 1 as printed: 'the origin of (1) is fixed-time stable, and V reaches (5) within
    (6)'.  The first part fails for x' = f(x) of ``CE_SYSTEM``, which satisfies (4)."""
    from lgw.theory.evidence import FromClaim

    x_star, x_brent = theorem1_counterexample()
    f_txt = "x' = -sig(x,1/2) - sig(x,2) + 1"
    wording = witness_step(
        "'the origin of (1) is fixed-time stable': every trajectory reaches x = 0",
        {"system": f_txt, "V": "|x|", **{k_: sp.sstr(v_) for k_, v_ in CE_CONSTANTS.items()},
         "x(0) = x*": x_star, "x*": "equilibrium: the positive root of f(x) = 0"},
        -x_star, "the trajectory from the equilibrium x* stays at |x| = x*: margin -x* (x* from "
        "the positive real root of f(y^2) = 0, a polynomial in y = sqrt(x), SymPy, 30 digits)",
        -x_brent if abs(x_brent - x_star) < 1e-12 and abs(float(CE_SYSTEM.subs(
            X_CE, sp.Float(x_brent, 30)))) < 1e-12 else None,
        "scipy brentq on f over [0, 1]; agrees with the exact root to 1e-12",
        domain={"x(0)": "(0, oo)"})
    steps = [*_condition4_steps(), wording,
             Step("[claim theorem1-corrected] V reaches (5) within (6)",
                  FromClaim(theorem1_corrected()))]
    return Claim("theorem1", "(4)-(6), (7)-(9)", "Theorem 1: practical fixed-time stability",
                 "V' <= -(aV^p+bV^g)^k + eta => the origin is fixed-time stable, V reaches "
                 "(5) within (6)",
                 "The sentence 'the origin is fixed-time stable' is false: x' = f(x) above "
                 "satisfies (4) (computed) and has an equilibrium x* != 0 "
                 f"(x* = {x_star:.10f}).  What holds is claim theorem1-corrected.", steps,
                 numbers={"x_star": x_star, "x_star_brentq": x_brent})
