"""Seed 002's claims, derived from the laws of ``lgw.theory.eros.laws`` and checked.

Every verdict is computed from evidence (``lgw.theory.evidence``): SymPy identities (on each
sign branch of e where |e| appears), SymPy assumption queries, falsification searches over
stated domains whose counterexamples are re-checked by an independent route (an ODE solve, exact
arithmetic).  No printed formula is taken as true.  ``all_claims()`` lists them in report order.
The scenario claims (the paper's simulations) need the simulator and are built in
``lgw.tuning.eros.scenario``.
"""

from __future__ import annotations

import dataclasses
import math
from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.eros import bounds as B
from lgw.theory.eros import gravity as GR
from lgw.theory.eros import laws as L
from lgw.theory.eros import parameters as P
from lgw.theory.eros import reference as REF
from lgw.theory.eros.gains import Gains, default_gains
from lgw.theory.evidence import (
    Cited,
    Claim,
    Identity,
    Search,
    Step,
    Unproven,
    Witness,
)
from lgw.theory.provers import (
    identity_evidence,
    prove_identity,
    prove_nonneg,
    prove_z3,
    refute_nonneg_at,
)
from lgw.theory.report_math import At
from scipy.integrate import quad, solve_ivp

e, ed, r, alpha, beta, k, lam = L.e, L.ed, L.r, L.alpha, L.beta, L.k, L.lam
E = sp.Symbol("E", positive=True)  # |e| on a sign branch
e0 = sp.Symbol("e_0", positive=True)  # |e(0)|
c = sp.Symbol("c", positive=True)  # 1 - p/q, in (0, 1)
tt = sp.Symbol("t", nonnegative=True)
SEED = 2

# --- Display forms: the formulas the report renders (paper_expr / derived_expr / Step.expr).
# They are the SymPy objects the proofs use, renamed for reading (e' as edot, r as p/q, c as
# 1 - p/q, E as |e|); no verdict depends on them.
P_, Q_ = sp.symbols("p q", positive=True)
EDOT, EDDOT, SDOT, VDOT = sp.symbols("edot eddot sdot Vdot_1", real=True)
T_S, T_R = sp.symbols("t_s t_r", positive=True)
U_EQ, U_S = sp.symbols("u_eq u_s", real=True)
XDD = sp.Symbol("xddot_d", real=True)  # the reference acceleration x_2d'


EPOS = sp.Symbol("e", positive=True)  # |e| as an integration variable


def disp(expr: sp.Basic) -> sp.Basic:
    """``expr`` in the paper's names: e' as edot, r = p/q, c = 1 - p/q, E = |e| (an integration
    variable E: e > 0) (seed 002, eqs. (5)-(6), (11))."""
    has_int = bool(expr.atoms(sp.Integral))
    return expr.xreplace({ed: EDOT, E: EPOS if has_int else sp.Abs(e), L.xdd: XDD}).xreplace(
        {c: 1 - P_ / Q_}).xreplace({r: P_ / Q_})


def sig_disp(x: sp.Expr) -> sp.Expr:
    """sig(x)^(p/q) = |x|^(p/q) sgn(x) in display names."""
    return disp(L.sig(x, r))


def _with_expr(step: Step, expr: sp.Basic | tuple) -> Step:
    """``step`` (made by a prover) with the formula it asserts, for rendering."""
    return dataclasses.replace(step, expr=expr)


def on_branches(expr: sp.Expr, statement: str, **kw) -> Step:
    """``expr == 0`` on both sign branches e = E > 0 and e = -E < 0 (e = 0 excluded: |e|^(r-1)
    is undefined there, claim singular-term)."""
    for sg in (1, -1):
        ev = identity_evidence(sp.powsimp(sp.expand(expr.subs(e, sg * E)), force=True), **kw)
        if ev.status != "proved":
            return Step(f"{statement} [branch sgn(e) = {sg}]", ev)
    return Step(statement + " (both branches sgn(e) = +-1)",
                Identity(sp.Integer(0), "sympy.simplify on each sign branch of e"))


# --- ODE solves: the independent route for settling times -----------------------------------

EVENT_LEVEL = 1e-9  # the ODE solve stops at |e| = EVENT_LEVEL |e0|; quadrature does the rest


def ode_settling_time(e0v: float, alpha_v: float, beta_v: float, rv: float,
                      rtol: float = 1e-11) -> float:
    """Time for e' = -alpha e - beta e^r (alpha = 0: surface (5)) to go from e0 to 0: solve_ivp
    (DOP853, tight tolerances) to the event e = 1e-9 e0, plus the remaining time by quadrature.

    The absolute tolerance is 1e-14 of the event level (not of e0): near the event the state is
    1e-9 e0, and an absolute tolerance of 1e-14 e0 would locate the event with a relative error
    of 1e-5 in e there, i.e. a time error of that order when p/q is near 1 (the tail below the
    event is then a large part of t_s)."""
    def rhs(_t, y):
        x = max(y[0], 0.0)
        return [-alpha_v * x - beta_v * x**rv]

    def ev(_t, y):
        return y[0] - EVENT_LEVEL * e0v
    ev.terminal = True
    tmax = 10.0 * (B.ts_tsm(e0v, beta_v, rv) + 1.0)
    sol = solve_ivp(rhs, (0.0, tmax), [e0v], rtol=rtol, atol=1e-14 * EVENT_LEVEL * e0v,
                    events=ev, method="DOP853")
    t_ev = float(sol.t_events[0][0])
    # the tail from 1e-9 e0 to 0 by adaptive quadrature of dt = de / (alpha e + beta e^r)
    # (integrable singularity e^-r at 0; no closed form used)
    # (QAWS: the weight x^-r is integrated exactly, the rest 1/(alpha x^(1-r) + beta) is smooth)
    tail = quad(lambda x: 1.0 / (alpha_v * x ** (1.0 - rv) + beta_v), 0.0, EVENT_LEVEL * e0v,
                weight="alg", wvar=(-rv, 0.0), epsabs=0.0, epsrel=1e-8, limit=400)[0]
    return t_ev + tail


def _log_uniform(rng, lo, hi, n):
    return np.exp(rng.uniform(math.log(lo), math.log(hi), n))


PARAM_DOMAIN = {"p/q": "(0.05, 0.95)", "alpha": "[1e-2, 1e2] 1/s (log-uniform)",
                "beta": "[1e-2, 1e2] (log-uniform)", "|e0|": "[1e-3, 1e4] m (log-uniform)"}


def _sample(n: int, seed: int = SEED):
    rng = np.random.default_rng(seed)
    rv = rng.uniform(0.05, 0.95, n)
    return (rv, _log_uniform(rng, 1e-2, 1e2, n), _log_uniform(rng, 1e-2, 1e2, n),
            _log_uniform(rng, 1e-3, 1e4, n))


def _pq(rv: float) -> tuple[int, int]:
    fr = sp.Rational(rv).limit_denominator(40)
    return int(fr.p), int(fr.q)


# --- printed settling times against the derived ones -------------------------------------------

FORMULA_TOL = 1e-9  # relative: a printed formula "equals" the derived one to rounding


def _printed_time_search(statement: str, printed, derived, alpha_used: bool, seed: int) -> Step:
    """A printed settling-time formula against the derived closed form over PARAM_DOMAIN: the
    margin is FORMULA_TOL - |printed - derived|/derived (>= 0: equal to rounding); the worst
    point is re-checked against the ODE time (SETTLING_ODE_TOL - |printed - t_ode|/t_ode)."""
    rv, av, bv, ev_ = _sample(400, seed)
    margins = []
    for i in range(len(rv)):
        p_, q_ = _pq(rv[i])
        a_ = av[i] if alpha_used else 0.0
        d_ = float(derived(ev_[i], a_, bv[i], p_ / q_))
        margins.append(FORMULA_TOL - abs(float(printed(ev_[i], a_, bv[i], p_, q_)) - d_) / d_)
    j = int(np.argmin(margins))
    p_, q_ = _pq(rv[j])
    a_ = av[j] if alpha_used else 0.0
    pr = float(printed(ev_[j], a_, bv[j], p_, q_))
    pt = {"p": p_, "q": q_, **({"alpha": a_} if alpha_used else {}), "beta": bv[j],
          "e0": ev_[j], "printed": pr}
    w = None
    if margins[j] < 0:
        t_ode = ode_settling_time(ev_[j], a_, bv[j], p_ / q_)
        pt["ode"] = t_ode
        w = Witness(pt, margins[j], f"{FORMULA_TOL:g} - |printed - derived closed form| / "
                    "derived", SETTLING_ODE_TOL - abs(pr - t_ode) / t_ode,
                    f"{SETTLING_ODE_TOL:g} - |printed - solve_ivp (DOP853) time| / time", seed)
    return Step(statement, Search(PARAM_DOMAIN, "random sampling, p/q rationalised (q <= 40); "
                                  "relative margin", len(rv), float(margins[j]), pt, seed, w,
                                  relative=True))


# --- (5): terminal surface -----------------------------------------------------------------

@cache
def settling_tsm_claim() -> Claim:
    # separation of variables on e' = -beta e^r (e > 0; e < 0 by symmetry of sig):
    # dt = -de / (beta e^r), t_s = int_0^{e0} e^{-r} de / beta
    ts = sp.integrate(E ** (-(1 - c)), (E, 0, e0)) / beta  # r = 1 - c
    derived = e0**c / (beta * c)
    sol = (e0**c - beta * c * tt) ** (1 / c)  # e(t) on [0, t_s]
    Y = sp.Symbol("Y", positive=True)
    e_t = sp.Function("e")(tt)
    steps = [
        _with_expr(prove_identity(sp.simplify(ts - derived), "separation of variables: t_s = "
                                  "int_0^|e0| de/(beta e^(p/q)) = |e0|^(1-p/q)/(beta (1-p/q))"),
                   sp.Eq(disp(sp.Integral(E ** (-(1 - c)), (E, 0, e0)) / beta), disp(derived),
                         evaluate=False)),
        # chain rule with Y = |e0|^(1-r) - beta (1-r) t > 0 on [0, t_s): dY/dt = -beta (1-r)
        _with_expr(prove_identity(sp.simplify(sp.diff(Y ** (1 / c), Y) * (-beta * c)
                                              + beta * (Y ** (1 / c)) ** (1 - c)),
                                  "e(t) = (|e0|^(1-r) - beta (1-r) t)^(1/(1-r)) solves e' = "
                                  "-beta e^r"), sp.Eq(e_t, disp(sol), evaluate=False)),
        _with_expr(prove_identity(sol.subs(tt, derived) - 0, "and reaches 0 at t = t_s"),
                   sp.Eq(sp.Function("e")(T_S), 0, evaluate=False)),
    ]
    printed = B.ts_tsm_printed  # the formula after (5)
    pp, qq = sp.symbols("p q", positive=True)
    dd = sp.Symbol("d", positive=True)  # q - p > 0
    pr_sym = printed(e0, beta, pp, qq)  # the bound function on symbols
    neg = refute_nonneg_at(pr_sym.subs(qq, pp + dd), {pp: 3, dd: 2, beta: 1, e0: 2},
                           "the printed t_s is a time (>= 0) for every p < q, beta > 0, "
                           "e0 != 0 (q = p + d, d > 0)")
    search = _printed_time_search(
        "printed t_s = p/(beta(p-q)) |e0|^((p-q)/p) equals the settling time over the range",
        lambda e0v, _a, bv, p_, q_: printed(e0v, bv, p_, q_),
        lambda e0v, _a, bv, rv_: B.ts_tsm(e0v, bv, rv_), False, SEED)
    swap = prove_identity(pr_sym.subs({pp: qq, qq: pp}, simultaneous=True).subs(
        qq, 1).subs(pp, 1 - c) - derived.subs(e0, e0),
        "the printed formula is the derived one with p and q exchanged (q/p, the convention "
        "of Yu & Man 2002 where the exponent is q/p < 1)")
    return Claim("settling-tsm", "(5)", "Settling time on the terminal surface (5)",
                 "t_s = (p/(beta(p-q))) |e1(0)|^((p-q)/p)",
                 "t_s = q/(beta(q-p)) |e0|^((q-p)/q) (separation of variables); the printed "
                 "one is negative for every p < q", tuple(steps) + (search, neg),
                 scope="all-gains", remarks=(swap,),
                 numbers={"witness": search.witness.to_dict() if search.witness else None},
                 paper_expr=sp.Eq(T_S, pr_sym, evaluate=False),
                 derived_expr=sp.Eq(T_S, disp(derived), evaluate=False))


@cache
def settling_ftsm_claim() -> Claim:
    # separation of variables on e' = -alpha e - beta e^r: F(e) = ln(alpha e^(1-r) + beta) /
    # (alpha (1-r)) is an antiderivative of 1/(alpha e + beta e^r) (check by differentiation)
    F = sp.log(alpha * E**c + beta) / (alpha * c)
    integrand = 1 / (alpha * E + beta * E ** (1 - c))
    derived = sp.log(1 + alpha * e0**c / beta) / (alpha * c)
    steps = [
        _with_expr(prove_identity(sp.simplify(sp.diff(F, E) - integrand),
                                  "d/de [ln(alpha e^(1-r) + beta)/(alpha(1-r))] = 1/(alpha e + "
                                  "beta e^r)"),
                   sp.Eq(sp.Derivative(disp(F), e), disp(integrand), evaluate=False)),
        _with_expr(prove_identity(sp.expand_log(F.subs(E, e0) - sp.limit(F, E, 0, "+") - derived,
                                                force=True),
                                  "t_s = F(|e0|) - F(0+) = ln(1 + alpha|e0|^(1-r)/beta)/(alpha"
                                  "(1-r))"),
                   sp.Eq(T_S, disp(sp.Integral(integrand, (E, 0, e0))), evaluate=False)),
    ]
    search = _printed_time_search("printed (7) equals the settling time over the range",
                                  B.ts_ftsm_printed, B.ts_ftsm, True, SEED + 1)
    pp, qq = sp.symbols("p q", positive=True)
    pr_sym = B.ts_ftsm_printed(e0, alpha, beta, pp, qq)  # the bound function on symbols
    swap = prove_identity(sp.expand_log(pr_sym.subs({pp: qq, qq: pp}, simultaneous=True)
                                        .subs(qq, 1).subs(pp, 1 - c) - derived, force=True),
                          "the printed (7) is the derived one with p and q exchanged")
    return Claim("settling-ftsm", "(6), (7)", "Settling time on the fast terminal surface (6)",
                 "t_s = p/(alpha(p-q)) (ln(alpha e1^((p-q)/p) + beta) - ln beta)",
                 "t_s = q/(alpha(q-p)) ln(1 + alpha|e0|^((q-p)/q)/beta); the printed (7) is "
                 "negative for every p < q", tuple(steps) + (search,), remarks=(swap,),
                 numbers={"witness": search.witness.to_dict() if search.witness else None},
                 paper_expr=sp.Eq(T_S, pr_sym, evaluate=False),
                 derived_expr=sp.Eq(T_S, disp(derived), evaluate=False))


SETTLING_ODE_TOL = 1e-6  # relative agreement the check needs (the ODE route's error ~1e-10)


def _settling_worst(rv, av, bv, ev_, rtol: float = 1e-11) -> tuple[float, dict]:
    worst, wpt = -1.0, {}
    for i in range(len(rv)):
        for a_ in (0.0, av[i]):
            closed = (B.ts_tsm(ev_[i], bv[i], rv[i]) if a_ == 0.0
                      else B.ts_ftsm(ev_[i], a_, bv[i], rv[i]))
            rel = abs(ode_settling_time(ev_[i], a_, bv[i], rv[i], rtol) - closed) / closed
            if rel > worst:
                worst, wpt = rel, {"r": rv[i], "alpha": a_, "beta": bv[i], "e0": ev_[i]}
    return worst, wpt


@cache
def settling_ode_claim() -> Claim:
    """The derived closed forms against an independent ODE solve over the range: checked only
    when the worst relative disagreement is within SETTLING_ODE_TOL; a larger one is re-solved
    at rtol 1e-13 and refutes the closed form only if the re-check disagrees too."""
    rv, av, bv, ev_ = _sample(60, SEED + 2)
    worst, wpt = _settling_worst(rv, av, bv, ev_)
    tol = SETTLING_ODE_TOL
    counter = None
    if worst > tol:
        closed = (B.ts_tsm(wpt["e0"], wpt["beta"], wpt["r"]) if wpt["alpha"] == 0.0
                  else B.ts_ftsm(wpt["e0"], wpt["alpha"], wpt["beta"], wpt["r"]))
        re = abs(ode_settling_time(wpt["e0"], wpt["alpha"], wpt["beta"], wpt["r"], 1e-13)
                 - closed) / closed
        counter = Witness(wpt, tol - worst, "solve_ivp DOP853 rtol 1e-11 against the closed "
                          "form", tol - re, "the same at rtol 1e-13", SEED + 2)
    step = Step(f"|t_ode - t_closed| / t_closed <= {tol} (surfaces (5) alpha = 0 and (6))",
                Search(PARAM_DOMAIN, "random sampling, solve_ivp DOP853 rtol 1e-11, atol 1e-14 "
                       "of the event level, tail by QAWS quadrature", 2 * len(rv), tol - worst,
                       wpt, SEED + 2, counter))
    t_ode = sp.Symbol("t_ode", positive=True)
    rel_e = sp.Le(sp.Abs(t_ode - T_S) / T_S, sp.Float(tol, 2), evaluate=False)
    return Claim("settling-ode", "(5), (6)", "Derived settling times against an ODE solve",
                 "-", f"closed forms agree with the ODE to {worst:.2e} relative (worst of "
                 f"{2 * len(rv)} cases; tolerance {tol:g})",
                 (dataclasses.replace(step, expr=rel_e),), statement="workbench",
                 numbers={"worst_relative_error": worst, "tolerance": tol},
                 derived_expr=(sp.Eq(EDOT, -alpha * e - beta * sig_disp(e), evaluate=False),
                               rel_e))


@cache
def growth_claim() -> Claim:
    derived = e0**c / (beta * c)
    d_dt = sp.diff(derived, e0)
    grow = prove_nonneg(d_dt, "d t_s / d|e0| > 0: the time grows with |e0| (derived t_s of (5))",
                        strict=True)
    pp, qq, dd = sp.symbols("p q d", positive=True)
    # the printed exponent: the logarithmic derivative of the printed t_s (bounds function)
    pr = B.ts_tsm_printed(e0, beta, pp, qq)
    expo = sp.simplify(e0 * sp.diff(pr, e0) / pr)
    neg = refute_nonneg_at(expo.subs(qq, pp + dd), {pp: 3, dd: 2},
                           "the printed t_s grows with |e0|: its exponent d ln t_s / d ln|e0| "
                           "is >= 0 for p < q (q = p + d)")
    # witness: the printed proportionality predicts a shorter time for a 10x larger e0
    p_, q_, bv = 3, 5, 1.0
    ratio_pr = float(B.ts_tsm_printed(10.0, bv, p_, q_) / B.ts_tsm_printed(1.0, bv, p_, q_))
    ratio_ode = ode_settling_time(10.0, 0, bv, p_ / q_) / ode_settling_time(1.0, 0, bv, p_ / q_)
    w = Witness({"p": p_, "q": q_, "beta": bv, "e0": [1.0, 10.0], "printed_ratio": ratio_pr,
                 "ode_ratio": ratio_ode}, ratio_pr - 1.0,
                "printed proportionality |e0|^((p-q)/p): t(10)/t(1) - 1",
                (ratio_pr - 1.0) * np.sign(ratio_ode - 1.0), "solve_ivp times: the ODE ratio "
                "is > 1 where the printed one is < 1", SEED)
    step = Step("the time grows proportional to |e0|^((p-q)/p)",
                Search({"e0": "{1, 10} m", "p/q": "3/5"}, "two-point check", 2, w.margin,
                       w.point, SEED, w))
    return Claim("growth-e0", "(5)", "Growth of the settling time with |e0|",
                 "the convergence time increases proportional to |e1(0)|^((p-q)/p)",
                 "it grows as |e0|^((q-p)/q) (true growth); the printed exponent is negative",
                 (_with_expr(grow, sp.Gt(sp.Derivative(T_S, e0), 0, evaluate=False)), step, neg),
                 numbers={"ratio_ode": ratio_ode, "ratio_printed": ratio_pr},
                 paper_expr=(sp.Eq(T_S, sp.Symbol("C", positive=True)
                                   * e0 ** ((P_ - Q_) / P_), evaluate=False),),
                 derived_expr=(sp.Eq(T_S, disp(derived), evaluate=False),
                               sp.Eq(sp.Derivative(T_S, e0), disp(d_dt), evaluate=False)))


@cache
def ftsm_faster_claim() -> Claim:
    x = sp.Symbol("x", positive=True)  # alpha |e0|^(1-r) / beta
    t_tsm = e0**c / (beta * c)
    t_ftsm = sp.log(1 + alpha * e0**c / beta) / (alpha * c)
    h = x - sp.log(1 + x)
    diff = prove_identity(sp.simplify((t_tsm - t_ftsm) - h.subs(x, alpha * e0**c / beta)
                                      / (alpha * c)),
                          "t_TSM - t_FTSM = (x - ln(1+x))/(alpha(1-r)), x = alpha|e0|^(1-r)/beta")
    h0 = prove_identity(h.subs(x, 0), "h(0) = 0 for h(x) = x - ln(1+x)")
    hp = prove_nonneg(sp.diff(h, x), "h'(x) = x/(1+x) > 0 for x > 0", strict=True)
    mono = Step("h(x) > 0 for x > 0", Cited("mean value theorem", "h(0) = 0 and h' > 0 on "
                                            "(0, oo) give h > 0 on (0, oo)", (h0, hp)))
    ratio = sp.Symbol("e", positive=True)
    quot = sp.powsimp((alpha * ratio) / (beta * ratio ** (1 - c)), force=True)
    far = prove_identity(1 / sp.limit(quot, ratio, sp.oo),
                         "alpha|e| / (beta|e|^r) -> oo as |e| -> oo (far: e' ~ -alpha e)")
    near = prove_identity(sp.limit(quot, ratio, 0, "+"),
                          "alpha|e| / (beta|e|^r) -> 0 as e -> 0 (near: e' ~ -beta e^r)")
    t_t, t_f = sp.symbols("t_TSM t_FTSM", positive=True)
    diff = _with_expr(diff, sp.Eq(t_t - t_f, disp(h.subs(x, alpha * e0**c / beta) / (alpha * c)),
                                  evaluate=False))
    far = _with_expr(far, sp.Eq(sp.Limit(disp(quot), ratio, sp.oo), sp.oo, evaluate=False))
    near = _with_expr(near, sp.Eq(sp.Limit(disp(quot), ratio, 0, "+"), 0, evaluate=False))
    return Claim("ftsm-faster", "(6)", "The alpha term lowers the convergence time",
                 "adding alpha e lowers the convergence time; far: e' ~ -alpha e, near: "
                 "e' ~ -beta e^(p/q)", "t_FTSM < t_TSM for every e0 != 0, alpha, beta > 0",
                 (diff, mono, far, near),
                 paper_expr=(sp.Lt(t_f, t_t, evaluate=False),),
                 derived_expr=(sp.Eq(t_t, disp(t_tsm), evaluate=False),
                               sp.Eq(t_f, disp(t_ftsm), evaluate=False),
                               sp.Lt(t_f, t_t, evaluate=False)))


# --- reaching ------------------------------------------------------------------------------

def _reach_sim(s0: float, k_: float, dbar: float, freq: float, phase: float) -> float:
    """Time for s' = D(t) - k sgn(s), D = dbar sin(freq t + phase), to reach 0 (solve_ivp,
    terminal event s = 0)."""
    sg = np.sign(s0)

    def rhs(t, y):
        return [dbar * math.sin(freq * t + phase) - k_ * sg]

    def ev(_t, y):
        return y[0]
    ev.terminal = True
    sol = solve_ivp(rhs, (0, 10 * abs(s0) / (k_ - dbar) + 1), [s0], events=ev, rtol=1e-10,
                    atol=1e-12, max_step=0.05)
    return float(sol.t_events[0][0])


@cache
def reaching_claim() -> Claim:
    sv = sp.Symbol("s", real=True, nonzero=True)
    D, dbar, delta = sp.symbols("D dbar delta", real=True)
    dbar_p, delta_p = sp.symbols("dbar delta", nonnegative=True)
    # V' = s (D - k sgn s) <= -(k - dbar)|s|:  dbar|s| - s D >= 0 for |D| <= dbar
    S = sp.Symbol("S", positive=True)
    pos = prove_nonneg((dbar_p * S - S * (dbar_p - delta_p)),
                       "s > 0, D = dbar - delta (delta >= 0): dbar|s| - s D >= 0")
    neg = prove_nonneg((dbar_p * S + S * (-dbar_p + delta_p)),
                       "s < 0, D = -dbar + delta: dbar|s| - s D >= 0")
    known = prove_identity(sv * (-k * sp.sign(sv)) + k * sp.Abs(sv),
                           "known D (14): V' = s u_s = -k|s| (equality)")
    cmp_ = Step("|s(t)| <= |s0| - (k - dbar) t, so s = 0 by t_r <= |s0|/(k - dbar)",
                Cited("comparison lemma (Khalil, Nonlinear Systems, 3rd ed., Lemma 3.4)",
                      "d|s|/dt <= -(k - dbar) for s != 0", (known, pos, neg)))
    rng = np.random.default_rng(SEED)
    n, worst, wpt = 40, math.inf, {}
    for _ in range(n):
        k_ = float(rng.uniform(0.1, 5.0))
        db = float(rng.uniform(0, 0.95)) * k_
        s0 = float(rng.uniform(-10, 10))
        fr, ph = float(rng.uniform(0.1, 10)), float(rng.uniform(0, 6.3))
        margin = float(B.t_reach_sign(s0, k_, db)) - _reach_sim(s0, k_, db, fr, ph)
        if margin < worst:
            worst, wpt = margin, {"k": k_, "dbar": db, "s0": s0, "freq": fr, "phase": ph}
    search = Step("simulated reaching time <= |s0|/(k - dbar), D = dbar sin(w t + phase)",
                  Search({"k": "[0.1, 5] m/s^2", "dbar/k": "[0, 0.95]", "s0": "[-10, 10] m/s",
                          "w": "[0.1, 10] rad/s"}, "random sampling, solve_ivp rtol 1e-10", n,
                         worst, wpt, SEED))
    s0s = sp.Symbol("s_0", real=True)
    bound = sp.Le(T_R, sp.Abs(s0s) / (k - dbar_p), evaluate=False)
    return Claim("reaching-sign", "(15)-(18)", "Reaching time under the switching law",
                 "u_s = -k1 sgn(s1) drives the states to the sliding surface",
                 "known D: t_r = |s0|/k exactly; |D| <= dbar < k unknown: t_r <= |s0|/(k-dbar)",
                 (dataclasses.replace(cmp_, expr=bound), search),
                 numbers={"worst_margin_s": worst},
                 paper_expr=(sp.Eq(U_S, L.u_switch("sign", sv), evaluate=False),),
                 derived_expr=(sp.Eq(T_R, sp.Abs(s0s) / k, evaluate=False), bound))


@cache
def reaching_tanh_claim() -> Claim:
    S = sp.Symbol("S", positive=True)
    phi = L.phi
    sym = prove_identity(S * sp.tanh(S / phi) - (-S) * sp.tanh(-S / phi),
                         "s tanh(s/phi) = |s| tanh(|s|/phi) (even in s)")
    # for |s| >= s_b: s s' <= |s| (dbar - k tanh(|s|/phi)) <= -|s| (k tanh(s_b/phi) - dbar)
    mono = prove_nonneg(sp.diff(sp.tanh(S / phi), S), "tanh(|s|/phi) is increasing in |s|")
    rate = Step("outside |s| <= s_b: d|s|/dt <= -(k tanh(s_b/phi) - dbar) < 0 if "
                "s_b > phi artanh(dbar/k); entry time <= (|s0| - s_b)/(k tanh(s_b/phi) - dbar)",
                Cited("comparison lemma (Khalil, Lemma 3.4)", "rate bound outside the band",
                      (sym, mono)))
    inner = Step("s = 0 is not reached in finite time with tanh unless D = 0: the "
                 "band |s| <= phi artanh(dbar/k) is all the theory gives",
                 Unproven("a practical (ultimate-boundedness) result: the boundary layer trades "
                          "finite-time reaching for a band; nothing finer is claimed"))
    sb, s0s = sp.Symbol("s_b", positive=True), sp.Symbol("s_0", real=True)
    dbar = sp.Symbol("dbar", nonnegative=True)
    band = sp.Le(sp.Abs(L.s), phi * sp.atanh(dbar / k), evaluate=False)
    entry = sp.Le(T_R, (sp.Abs(s0s) - sb) / (k * sp.tanh(sb / phi) - dbar), evaluate=False)
    rate = dataclasses.replace(rate, expr=entry)
    return Claim("reaching-tanh", "(18) with tanh", "Reaching with the tanh 'saturation'",
                 "tanh instead of sgn removes chattering and keeps the tracking",
                 "only a band |s| <= phi artanh(dbar/k) is reached, in time <= (|s0| - s_b)/"
                 "(k tanh(s_b/phi) - dbar); with known D (dbar = 0) s -> 0 exponentially near 0",
                 (rate,), remarks=(inner,),
                 paper_expr=(sp.Eq(U_S, L.u_switch("tanh"), evaluate=False),),
                 derived_expr=(band, entry))


# --- (11)-(19): control design ---------------------------------------------------------------

@cache
def sdot_claim() -> Claim:
    # total derivative of s along e' = ed, ed' = edd: ds/dt = ds/de ed + edd (e != 0)
    edd = EDDOT
    s_f = L.surface_ftsm()  # the law's surface (6)
    # (11) as printed, e^(p/q-1) read as |e|^(p/q-1) (the sig reading of e^(p/q))
    printed11 = edd + ed * (alpha + beta * r * sp.Abs(e) ** (r - 1))
    total = sp.diff(s_f.subs(e, E), E) * ed + edd
    st_pos = prove_identity(sp.simplify(total - printed11.subs(e, E)),
                            "e > 0: ds/dt of the law's surface (6) = e'' + e'(alpha + beta "
                            "(p/q) e^(p/q-1)) (11)")
    totneg = sp.diff(s_f.subs(e, -E), E) * (-ed) + edd  # d/dt with e = -E(t), E' = -ed
    st_neg = prove_identity(sp.simplify(totneg - printed11.subs(e, -E)),
                            "e < 0: the same with |e|^(p/q-1) (sig reading of e^(p/q))")
    st_pos = _with_expr(st_pos, sp.Eq(SDOT, disp(total), evaluate=False))
    printed11 = sp.Eq(SDOT, EDDOT + EDOT * (alpha + beta * (P_ / Q_) * e ** (P_ / Q_ - 1)),
                      evaluate=False)
    derived11 = sp.Eq(SDOT, disp(L.ds_de("ftsm") * ed + edd), evaluate=False)
    return Claim("sdot-11", "(11)", "Derivative of the fast terminal surface",
                 "s1' = e'' + e'(alpha + beta (p/q) e^(p/q-1))",
                 "s' = e'' + e'(alpha + beta (p/q)|e|^(p/q-1)) for e != 0 (sig reading)",
                 (st_pos, st_neg), law="ftsmc",
                 paper_expr=(sp.Eq(L.s, disp(s_f), evaluate=False), printed11),
                 derived_expr=(derived11,))


@cache
def ueq_claim() -> Claim:
    w = sp.Symbol("omega", positive=True)
    x1, x2, x4, gx, x2d_dot, Dx = sp.symbols("x1 x2 x4 g_x xdd_ref D_x", real=True)
    ue = L.u_eq("ftsmc", floor=False)
    sdot0 = L.sdot("ftsmc", ue).subs(L.Dk, L.Dist)
    st = on_branches(sdot0, "s' = 0 under u = u_eq with D_k = D (14 solves s' = 0)")
    # the printed (14) with f = 2 w x4 + w^2 x1 + g_x and e' = x2 - x2d
    printed = (-(2 * w * x4 + w**2 * x1 + gx + Dx - x2d_dot)
               - ed * (alpha + beta * r * sp.Abs(e) ** (r - 1)))
    mine = ue.subs({L.f: 2 * w * x4 + w**2 * x1 + gx, L.Dk: Dx, L.xdd: x2d_dot})
    same = prove_identity(sp.simplify(printed - mine), "the workbench's u_eq is the printed "
                          "(14) with f = 2 w x4 + w^2 x1 + g_x")
    st = _with_expr(st, sp.Eq(SDOT, 0, evaluate=False))
    same = _with_expr(same, sp.Eq(U_EQ, disp(printed), evaluate=False))
    return Claim("ueq-14", "(12)-(14)", "Equivalent control", "u_xeq = -(2 w x4 + w^2 x1 + g_x "
                 "+ D_x - x2d') - (x2 - x2d)(alpha + beta (p/q) e^(p/q-1))",
                 "as printed; it needs D_x known (the unknown-D variant drops it)", (st, same),
                 law="ftsmc", paper_expr=(sp.Eq(U_EQ, disp(printed), evaluate=False),),
                 derived_expr=(sp.Eq(U_EQ, disp(ue), evaluate=False),))


@cache
def lyapunov_claim() -> Claim:
    sv = sp.Symbol("s", real=True, nonzero=True)
    steps = []
    for law in ("ftsmc", "pdsmc"):
        us = sp.Symbol("u_s", real=True)
        sd = L.sdot(law, L.u_eq(law, floor=False) + us).subs(L.Dk, L.Dist)
        steps.append(on_branches(sd - us, f"{law}: s' = u_s under u = u_eq + u_s, known D "
                                 "(16) -> (17)"))
    for i in range(2):
        steps[i] = _with_expr(steps[i], sp.Eq(SDOT, U_S, evaluate=False))
    vdot = sp.Eq(VDOT, sv * L.u_switch("sign", sv), evaluate=False)
    steps.append(_with_expr(prove_nonneg(k * sp.Abs(sv), "V' = s u_s = -k|s| < 0 for s != 0 "
                                         "(18)", strict=True),
                            (vdot, sp.Lt(-k * sp.Abs(sv), 0, evaluate=False))))
    steps.append(_with_expr(prove_identity(sp.diff(sv**2 / 2, sv) - sv, "V1 = s^2/2 gives V1' "
                                           "= s s' (15)"),
                            sp.Eq(VDOT, sp.Symbol("s") * SDOT, evaluate=False)))
    return Claim("lyapunov-17", "(15)-(19)", "Lyapunov argument for the control (19)",
                 "V1' = s1 u_xs < 0 with u_xs = -k1 sgn(s1)",
                 "proved for e != 0 with D known exactly and continuous-time control; the "
                 "reaching is finite-time (V' = -k|s| = -k sqrt(2 V)), stronger than the "
                 "asymptotic stability the paper states", tuple(steps), law="ftsmc",
                 paper_expr=(sp.Lt(sp.Symbol("s") * U_S, 0, evaluate=False),
                             sp.Eq(U_S, L.u_switch("sign", sp.Symbol("s")), evaluate=False)),
                 derived_expr=(sp.Eq(VDOT, -k * sp.Abs(sv), evaluate=False),
                               sp.Eq(VDOT, -k * sp.sqrt(2 * sp.Symbol("V_1", positive=True)),
                                     evaluate=False)))


@cache
def printed_exponent_claim() -> Claim:
    pp, qq = sp.symbols("p q", positive=True)
    us = sp.Symbol("u_s", real=True)
    printed_u = (-(L.f + L.Dk - L.xdd) - ed * (alpha + beta * (pp / qq) * sp.Abs(e)
                                               ** ((pp - 1) / qq)) + us)
    sd = L.sdot("ftsmc", printed_u).subs({L.Dk: L.Dist, r: pp / qq})
    resid = sp.simplify(sd - us).subs(e, E)
    ev = identity_evidence(resid, ranges={pp: (1, 4), qq: (5, 9)}, seed=SEED)
    step = Step("with the exponent (p-1)/q of (16)/(19) as extracted, s' = u_s", ev,
                sp.Eq(SDOT - U_S, disp(sp.factor(resid).xreplace({E: sp.Abs(e)})),
                      evaluate=False))
    return Claim("printed-exponent-19", "(16), (19)", "The exponent in (16) and (19)",
                 "u_x = ... - (x2 - x2d)(alpha + beta (p/q)(e1x)^((p-1)/q)) - k1 sgn(s1)",
                 "(p-1)/q != p/q - 1 unless q = 1: with the extracted exponent (17) fails; the "
                 "workbench uses p/q - 1 of (11), (14)", (step,), law="ftsmc (printed (19))",
                 paper_expr=(sp.Eq(sp.Symbol("u_x"), disp(printed_u), evaluate=False),),
                 derived_expr=(sp.Eq(sp.Symbol("u_x"), disp(L.u_eq("ftsmc", floor=False) + us),
                                     evaluate=False),))


@cache
def singular_claim() -> Claim:
    # (a) off the surface: e'|e|^(r-1) -> oo as e -> 0 with e' != 0
    edp = sp.Symbol("e_d", positive=True)
    off = prove_identity(sp.limit(1 / (edp * E ** (-c)), E, 0, "+"),
                         "off the surface, 1/(e'|e|^(p/q-1)) -> 0 as e -> 0 with e' != 0: "
                         "the term is unbounded (p/q < 1)")
    # (b) on the surface e' = -alpha e - beta sig(e)^r: e'|e|^(r-1) = -alpha|e|^r sgn e -
    # beta |e|^(2r-1) sgn e, bounded iff r >= 1/2
    ed_on = sp.solve(sp.Eq(L.surface_ftsm(), 0), ed)[0]  # e' on the law's surface s = 0
    on = on_branches(ed_on * sp.Abs(e) ** (r - 1)
                     - (-alpha * sp.Abs(e) ** r - beta * sp.Abs(e) ** (2 * r - 1)) * sp.sign(e),
                     "on the surface: e'|e|^(r-1) = -(alpha|e|^r + beta|e|^(2r-1)) sgn(e), "
                     "bounded near 0 iff 2 p/q - 1 >= 0")
    # (c) the floor: |e| -> max(|e|, e_floor) leaves, per crossing of |e| < e_floor, an
    # uncancelled change of s of int beta r (|e|^(r-1) - e_floor^(r-1)) de = 2 beta e_floor^r (1-r)
    eps = L.eps
    jump = 2 * sp.integrate(beta * r * (E ** (r - 1) - eps ** (r - 1)), (E, 0, eps),
                            conds="none")
    floor = prove_identity(sp.simplify(jump - 2 * beta * eps**r * (1 - r)),
                           "floor: the uncancelled change of s across |e| < e_floor is "
                           "int beta r (|e|^(r-1) - e_floor^(r-1)) de = 2 beta e_floor^r (1-r)")
    off = _with_expr(off, sp.Eq(sp.Limit(disp(edp * E ** (-c)).xreplace({edp: EDOT}), EPOS, 0,
                                         "+"), sp.oo, evaluate=False))
    on_form = disp((-alpha * sp.Abs(e) ** r - beta * sp.Abs(e) ** (2 * r - 1)) * sp.sign(e))
    on = _with_expr(on, sp.Eq(disp(ed_on * sp.Abs(e) ** (r - 1)), on_form, evaluate=False))
    jump_disp = sp.Eq(disp(2 * sp.Integral(beta * r * (E ** (r - 1) - eps ** (r - 1)),
                                           (E, 0, eps))), disp(2 * beta * eps**r * (1 - r)),
                      evaluate=False)
    floor = _with_expr(floor, jump_disp)
    sgn0 = Step("sgn(s) at s = 0 and sgn(e) at e = 0: the implementation uses numpy.sign "
                "(0 at 0); tanh(s/phi) is smooth; the fuzzy D = 0 gives a = 1, b = 0",
                Unproven("an implementation convention, not a theorem (Filippov solutions "
                         "are not computed)"))
    return Claim("singular-term", "(11), (14), (19)", "Singular terms of the control",
                 "(not discussed in the paper)",
                 "beta (p/q)|e|^(p/q-1) e' is unbounded at e = 0 off the surface for every "
                 "p/q < 1, and on it for p/q < 1/2; the implementation floors |e| at e_floor "
                 "(named gain), leaving a change of s of at most 2 beta e_floor^(p/q)(1-p/q) "
                 "per crossing", (off, on, floor), remarks=(sgn0,), law="ftsmc",
                 statement="workbench",
                 derived_expr=(sp.Eq(sp.Symbol("u_sing"), disp(-ed * beta * r * sp.Abs(e)
                                                              ** (r - 1)), evaluate=False),
                               sp.Eq(sp.Symbol("u_sing"), disp(-ed * beta * r * sp.Max(
                                   sp.Abs(e), eps) ** (r - 1)), evaluate=False),
                               jump_disp))


def _tanh_map_tail(k_: float, phi_: float, dt_: float, s0: float, n: int = 2000,
                   digits: int | None = None) -> float:
    """max |s_k| over the last 100 of n iterations of s_{k+1} = s_k - dt k tanh(s_k/phi) (the
    sampled loop's surface to leading order: u_s held over dt, u_eq cancelling the rest);
    ``digits``: iterate in mpmath at that precision (the re-check)."""
    if digits is None:
        x, tail = s0, 0.0
        for i in range(n):
            x = x - dt_ * k_ * math.tanh(x / phi_)
            if i >= n - 100:
                tail = max(tail, abs(x))
        return tail
    import mpmath as mp

    with mp.workdps(digits):
        x, tail = mp.mpf(s0), mp.mpf(0)
        for i in range(n):
            x = x - mp.mpf(dt_) * k_ * mp.tanh(x / phi_)
            if i >= n - 100:
                tail = max(tail, abs(x))
        return float(tail)


def _sampled_multiplier() -> Step:
    """d s_{k+1}/d s_k at 0 of the zero-order-hold map of the tanh boundary layer."""
    dt_, sk = sp.symbols("dt s_k", positive=True)
    phi = L.phi
    step_map = sk - dt_ * k * sp.tanh(sk / phi)
    mult = prove_identity(sp.diff(step_map, sk).subs(sk, 0) - (1 - k * dt_ / phi),
                          "d s_{k+1}/d s_k at 0 = 1 - k dt/phi (the sampled boundary layer)")
    s_next = sp.Symbol("s_k+1", real=True)
    return _with_expr(mult, sp.Eq(At(sp.Derivative(s_next, sk), 0), 1 - k * dt_ / phi,
                                  evaluate=False))


def _tanh_tail_step(g: Gains, dt_: float, statement: str) -> tuple[Step, float]:
    """Iterate the sampled map at the gains ``g`` and sampling time ``dt_``: checked when the
    tail settles (max |s_k| over the last 100 of 2000 steps <= 1e-9 m/s), else refuted once the
    40-digit mpmath iteration confirms the tail."""
    tail = _tanh_map_tail(g.k, g.phi, dt_, 1.0)
    w = None
    if tail > 1e-9:
        tail_mp = _tanh_map_tail(g.k, g.phi, dt_, 1.0, digits=40)
        w = Witness({"k": g.k, "phi": g.phi, "dt": dt_, "k_dt_over_phi": g.k * dt_ / g.phi,
                     "tail_max_abs_s": tail}, 1e-9 - tail,
                    "float iteration: 1e-9 minus the last-100 max |s_k|", 1e-9 - tail_mp,
                    "the same iteration in mpmath at 40 digits", SEED)
    return Step(statement, Search({"s0": "1 m/s", "iterations": 2000, "dt": f"{dt_:g} s",
                                   "k": g.k, "phi": g.phi}, "iterate the map", 2000,
                                  1e-9 - tail, {"tail": tail}, SEED, w)), tail


def sampled_tanh_claim(g: Gains | None = None) -> Claim:
    """The paper's "tanh eliminates the chattering", at its sampling time, for the gains in use
    (the map s_{k+1} = s_k - dt k tanh(s_k/phi) near s = 0, multiplier 1 - k dt/phi)."""
    return _sampled_tanh_claim(g or default_gains())


@cache
def _sampled_tanh_claim(g: Gains) -> Claim:
    x = g.k * P.DT_SAMPLE / g.phi
    nominal, tail = _tanh_tail_step(g, P.DT_SAMPLE, f"at the paper's dt = {P.DT_SAMPLE} s and "
                                    f"these gains (k dt/phi = {x:.3g}) the sampled surface "
                                    "settles (the boundary layer removes the chattering)")
    dt_, sk = sp.symbols("dt s_k", positive=True)
    return Claim("sampled-tanh", "(18) with tanh, 'sampling time 0.01 s'",
                 "The tanh boundary layer under the paper's sampling",
                 "the hyperbolic tangent eliminates the chattering (sampling time 0.01 s)",
                 f"for k = {g.k:g} m/s^2, phi = {g.phi:g} m/s at dt = {P.DT_SAMPLE} s, k dt/phi "
                 f"= {x:.3g} {'<' if x < 2 else '>='} 2: the sampled boundary layer "
                 + ("settles" if x < 2 else "is a limit cycle (claim sampled-tanh-limit)"),
                 (_sampled_multiplier(), nominal), law="tanh", scope="gain-set",
                 paper_expr=(sp.Eq(U_S, L.u_switch("tanh"), evaluate=False),),
                 derived_expr=(sp.Eq(sp.Symbol("s_k+1", real=True), sk - dt_ * k * sp.tanh(
                     sk / L.phi), evaluate=False),),
                 numbers={"k_dt_over_phi": x, "tail_dt_paper": tail})


def sampled_tanh_limit_claim(g: Gains | None = None) -> Claim:
    """Zero-order hold: the boundary layer is stable iff k dt/phi < 2; a limit cycle beyond,
    shown at the gains in use with dt = 4 phi/k."""
    return _sampled_tanh_limit_claim(g or default_gains())


@cache
def _sampled_tanh_limit_claim(g: Gains) -> Claim:
    xx = sp.Symbol("x", real=True)  # k dt / phi
    stable = prove_z3(sp.Equivalent(sp.And(sp.Gt(1 - xx, -1), sp.Lt(1 - xx, 1)),
                                    sp.And(sp.Gt(xx, 0), sp.Lt(xx, 2))), [],
                      "|1 - k dt/phi| < 1 iff 0 < k dt/phi < 2 (the fixed point s = 0 of the "
                      "sampled map is attracting)")
    dt_bad = 4.0 * g.phi / g.k
    tail = _tanh_map_tail(g.k, g.phi, dt_bad, 1.0)
    tail_mp = _tanh_map_tail(g.k, g.phi, dt_bad, 1.0, digits=40)
    cyc = Step(f"beyond the limit, at dt = 4 phi/k = {dt_bad:.3g} s (k dt/phi = 4), the sampled "
               "surface stays on a limit cycle: last-100 max |s_k| >= phi/10",
               Search({"s0": "1 m/s", "iterations": 2000, "dt": f"{dt_bad:.3g} s", "k": g.k,
                       "phi": g.phi}, "iterate the map (float; mpmath 40 digits gives "
                       f"{tail_mp:.6g})", 2000, min(tail, tail_mp) - g.phi / 10,
                       {"tail": tail, "tail_mpmath": tail_mp}, SEED))
    dt_, sk = sp.symbols("dt s_k", positive=True)
    return Claim("sampled-tanh-limit", "(18) with tanh", "The tanh boundary layer under sampling",
                 "-", "under a zero-order hold the boundary layer is stable iff k dt/phi < 2; "
                 f"for k = {g.k:g} m/s^2, phi = {g.phi:g} m/s the paper's dt = {P.DT_SAMPLE} s "
                 f"gives {g.k * P.DT_SAMPLE / g.phi:.3g}, and dt = {dt_bad:.3g} s (4) a limit "
                 f"cycle of amplitude {tail:.3g} m/s", (_sampled_multiplier(), stable, cyc),
                 law="tanh", scope="gain-set", statement="workbench",
                 derived_expr=(sp.Eq(sp.Symbol("s_k+1", real=True), sk - dt_ * k * sp.tanh(
                     sk / L.phi), evaluate=False),
                               sp.Lt(sp.Abs(1 - k * dt_ / L.phi), 1, evaluate=False)),
                 numbers={"dt_limit_cycle": dt_bad, "tail_limit_cycle": tail,
                          "k_dt_over_phi_paper": g.k * P.DT_SAMPLE / g.phi})


# --- (20)-(22): fuzzy blend ------------------------------------------------------------------

def _ratio_sup_search(n: int = 2000, seed: int = SEED) -> tuple[float, dict]:
    """max over (N, M, D) of (1 - a)/b / max(1, N/M) - 1 (should be < 0)."""
    rng = np.random.default_rng(seed)
    Nv, Mv = _log_uniform(rng, 1e-2, 1e2, n), _log_uniform(rng, 1e-2, 1e2, n)
    Dv = _log_uniform(rng, 1e-6, 1e3, n)
    ratio = -np.expm1(-Nv * Dv) / -np.expm1(-Mv * Dv) / np.maximum(1.0, Nv / Mv) - 1.0
    i = int(np.argmax(ratio))
    return float(-ratio[i]), {"N": Nv[i], "M": Mv[i], "D": Dv[i]}


def _exp_minus_one_positive() -> Step:
    """e^y - 1 > 0 for y > 0 (h(0) = 0, h' = e^y > 0, mean value theorem)."""
    y = sp.Symbol("y", positive=True)
    h0 = prove_identity(sp.exp(y).subs(y, 0) - 1, "h(0) = 0 for h(y) = e^y - 1")
    hp = prove_nonneg(sp.exp(y), "h'(y) = e^y > 0", strict=True)
    return Step("e^y - 1 > 0 for y > 0", Cited("mean value theorem", "h(0) = 0, h' > 0",
                                                  (h0, hp)))


def _ratio_bound_step() -> Step:
    """(1 - e^{-N D}) / (1 - e^{-M D}) <= max(1, N/M) for D > 0, by cases (d > 0):
    N = M - d: 1 - a <= b since e^{-ND} - e^{-MD} = e^{-MD}(e^{dD} - 1) >= 0;
    N = M + d: g = N b - M (1 - a) has g(0) = 0, g' = M N e^{-ND}(e^{dD} - 1) >= 0."""
    x, d, W = sp.symbols("D d W", positive=True)  # W stands for e^{d D} - 1 > 0
    Mm = L.M
    ex = _exp_minus_one_positive()
    # case N < M (N = M - d)
    diff1 = sp.exp(-(Mm - d) * x) - sp.exp(-Mm * x)
    fac1 = prove_identity(sp.simplify(diff1 - sp.exp(-Mm * x) * (sp.exp(d * x) - 1)),
                          "N = M - d: b - (1 - a) = e^{-MD}(e^{dD} - 1)")
    pos1 = prove_nonneg(sp.exp(-Mm * x) * W, "e^{-MD} W >= 0 with W = e^{dD} - 1 > 0")
    # case N > M (N = M + d)
    Nv = Mm + d
    g = Nv * (1 - sp.exp(-Mm * x)) - Mm * (1 - sp.exp(-Nv * x))
    g0 = prove_identity(g.subs(x, 0), "N = M + d: g(0) = 0 for g = N b - M (1 - a)")
    gp_form = Mm * Nv * sp.exp(-Nv * x) * (sp.exp(d * x) - 1)
    gfac = prove_identity(sp.simplify(sp.diff(g, x) - gp_form),
                          "g'(D) = M N e^{-ND} (e^{dD} - 1)")
    gpos = prove_nonneg(Mm * Nv * sp.exp(-Nv * x) * W, "M N e^{-ND} W >= 0")
    mono = Step("g(D) >= 0 for D > 0, i.e. (1 - a)/b <= N/M",
                Cited("mean value theorem", "g(0) = 0 and g' >= 0", (g0, gfac, gpos, ex)))
    eq = prove_identity(sp.simplify((1 - sp.exp(-Mm * x)) / (1 - sp.exp(-Mm * x)) - 1),
                        "N = M: (1 - a)/b = 1")
    return Step("(1 - a(D))/b(D) <= max(1, N/M) for every D > 0 (with the limits above: "
                "the supremum is max(1, N/M))",
                Cited("case analysis N < M, N = M, N > M", "each case proved",
                      (fac1, pos1, ex, mono, eq)))


def fuzzy_vdot(state: dict) -> float:
    """V' = s s' of one axis under the fuzzy law (20) at a state (sympy, exact rationals).

    ``state``: e, ed, f, D, xdd, d (fuzzy distance) and the gains; sign switching, D known."""
    ctl = L.control("fuzzy", "sign", floor=False).subs(L.Dk, L.Dist)
    vd = L.surface("fuzzy") * L.sdot("fuzzy", ctl)
    subs = {L.e: state["e"], L.ed: state["ed"], L.f: state["f"], L.Dist: state["D"],
            L.xdd: state["xdd"], L.dist: state["d"], alpha: state["alpha"],
            beta: state["beta"], r: state["r"], k: state["k"], L.N: state["N"],
            L.M: state["M"]}
    return float(sp.N(vd.subs({a: sp.nsimplify(b) for a, b in subs.items()}), 30))


def fuzzy_vdot_fd(state: dict, h: float = 1e-7) -> float:
    """The same V' by an independent route: s at (e, ed) and at (e + h ed, ed + h e'') with
    e'' = f + u + D - xdd from plain floats (numpy), finite difference of s^2/2."""
    a_ = math.exp(-state["N"] * state["d"])
    b_ = 1 - math.exp(-state["M"] * state["d"])

    def surf(ee, eed):
        return eed + state["alpha"] * ee + state["beta"] * np.sign(ee) * abs(ee) ** state["r"]
    s0 = surf(state["e"], state["ed"])
    dsde = state["alpha"] + state["beta"] * state["r"] * abs(state["e"]) ** (state["r"] - 1)
    ueq = -(state["f"] + state["D"] - state["xdd"]) - state["ed"] * dsde
    u = a_ * ueq + b_ * (-state["k"] * np.sign(s0))
    edd = state["f"] + u + state["D"] - state["xdd"]
    s1 = surf(state["e"] + h * state["ed"], state["ed"] + h * edd)
    sm = surf(state["e"] - h * state["ed"], state["ed"] - h * edd)
    return float((s1**2 - sm**2) / (4 * h))


@cache
def fuzzy_condition_claim() -> Claim:
    """(20)-(22): the reaching condition of the fuzzy blend, derived (all gains)."""
    a, b = L.fuzzy_weights()
    us = sp.Symbol("u_s", real=True)
    Fd = -L.u_eq("fuzzy", floor=False).subs(L.Dk, L.Dist)  # the drift the u_eq cancels
    sd = L.sdot("fuzzy", a * L.u_eq("fuzzy", floor=False).subs(L.Dk, L.Dist) + b * us)
    blend = on_branches(sd - ((1 - a) * Fd + b * us),
                        "s' = (1 - a) F + b u_s, F = -u_eq = f + D - xdd + e' ds/de")
    sv = sp.Symbol("s", real=True, nonzero=True)
    Fs = sp.Symbol("F", real=True)
    vdot = (1 - a) * Fs * sv - b * k * sp.Abs(sv)
    vd_id = prove_identity(sp.expand(sv * ((1 - a) * Fs + b * (-k * sp.sign(sv))) - vdot),
                           "V1' = (1 - a(D)) F s - b(D) k |s| (exact): reaching iff "
                           "(1 - a) F sgn(s) < b k")
    lim0 = prove_identity(sp.limit((1 - a) / b, L.dist, 0, "+") - L.N / L.M,
                          "(1 - a)/b -> N/M as D -> 0+")
    limoo = prove_identity(sp.limit((1 - a) / b, L.dist, sp.oo) - 1, "(1 - a)/b -> 1 as D -> oo")
    sup = _ratio_bound_step()
    best, bpt = _ratio_sup_search()
    sup_num = Step("(1 - a(D))/b(D) < max(1, N/M) numerically over a wide range",
                   Search({"N": "[1e-2, 1e2] s/m", "M": "[1e-2, 1e2] s/m",
                           "D": "[1e-6, 1e3] m/s"}, "log-uniform random sampling", 2000, best,
                          bpt, SEED, relative=True))
    blend = _with_expr(blend, sp.Eq(SDOT, (1 - a) * Fs + b * us, evaluate=False))
    vd_id = _with_expr(vd_id, sp.Eq(VDOT, vdot, evaluate=False))
    lim0 = _with_expr(lim0, sp.Eq(sp.Limit((1 - a) / b, L.dist, 0, "+"), L.N / L.M,
                                  evaluate=False))
    limoo = _with_expr(limoo, sp.Eq(sp.Limit((1 - a) / b, L.dist, sp.oo), 1, evaluate=False))
    sup = dataclasses.replace(sup, expr=sp.Le((1 - a) / b, sp.Max(1, L.N / L.M),
                                              evaluate=False))
    Fbar = sp.Symbol("Fbar", positive=True)
    weights = (sp.Eq(sp.Symbol("a"), a, evaluate=False), sp.Eq(sp.Symbol("b"), b,
                                                                evaluate=False))
    u20 = sp.Eq(sp.Symbol("u"), sp.Symbol("a") * U_EQ + sp.Symbol("b") * U_S, evaluate=False)
    derived = ("V1' = (1-a)F s - b k|s|; the reaching condition holds at every state with "
               "|F| <= Fbar iff k >= Fbar max(1, N/M) (strict if N = M), F the drift the "
               "equivalent control cancels, not the disturbance")
    return Claim("fuzzy-condition", "(20)-(22)", "Reaching condition of the fuzzy blend",
                 "-", derived, (blend, vd_id, lim0, limoo, sup), law="fuzzy",
                 statement="workbench",
                 remarks=(sup_num,), paper_expr=(u20, *weights),
                 derived_expr=(sp.Eq(VDOT, vdot, evaluate=False),
                               sp.Ge(k, Fbar * sp.Max(1, L.N / L.M), evaluate=False)))


def fuzzy_witness_state(g: Gains) -> dict:
    """A state at which the fuzzy blend (20) with the gains ``g`` violates V1' < 0 (constructed
    from the condition of claim fuzzy-condition): one axis off its surface (the others on
    theirs), e = 0.1 m, D = f = xdd = 0, and e' such that the drift the equivalent control
    cancels, F = e' (alpha + beta (p/q)|e|^(p/q-1)), is 2 k max(1, M/N) -- above k b/(1 - a),
    whose supremum over the distance is k max(1, M/N)."""
    r_ = g.p / g.q
    ev = 0.1
    dsde = g.alpha + g.beta * r_ * ev ** (r_ - 1.0)
    ed_ = 2.0 * g.k * max(1.0, g.M / g.N) / dsde
    st = {"e": ev, "ed": ed_, "f": 0.0, "D": 0.0, "xdd": 0.0, "alpha": g.alpha, "beta": g.beta,
          "r": r_, "k": g.k, "N": g.N, "M": g.M}
    s_st = ed_ + g.alpha * ev + g.beta * ev ** r_
    # the distance (21)-(22) of the law, the other axes on their surfaces
    st["d"] = float(L.fuzzy_distance((sp.nsimplify(s_st), 0, 0)).subs(L.alpha,
                                                                     sp.nsimplify(g.alpha)))
    return st


def fuzzy_reaching_claim(g: Gains | None = None) -> Claim:
    """The paper's claim that the fuzzy FTSMC keeps the reaching condition, judged at a state
    constructed for the gains in use."""
    return _fuzzy_reaching_claim(g or default_gains())


@cache
def _fuzzy_reaching_claim(g: Gains) -> Claim:
    a, b = L.fuzzy_weights()
    st = fuzzy_witness_state(g)
    v_exact = fuzzy_vdot(st)
    v_fd = fuzzy_vdot_fd(st)
    w = Witness(dict(st), -v_exact, "V1' by SymPy at the state (30 digits); margin = -V1'",
                -v_fd, "central finite difference of s^2/2 along the plant (floats)", SEED)
    refute = Step("V1' < 0 under u = a u_eq + b u_s for every k > 0 (the Lyapunov argument "
                  "(15)-(18) carried over to (20))",
                  Search({"state": f"the gains in use, e = 0.1 m, e' = {st['ed']:.6g} m/s (|F| = "
                          "2 k max(1, M/N))"}, "constructed from the condition: |F| > k "
                          "max(1, M/N)", 1, -v_exact, st, SEED, w))
    Fs = sp.Symbol("F", real=True)
    sv = sp.Symbol("s", real=True, nonzero=True)
    vdot = (1 - a) * Fs * sv - b * k * sp.Abs(sv)
    u20 = sp.Eq(sp.Symbol("u"), sp.Symbol("a") * U_EQ + sp.Symbol("b") * U_S, evaluate=False)
    return Claim("fuzzy-reaching", "(20)-(22)", "The fuzzy FTSMC keeps the reaching condition",
                 "the fuzzy coefficients put the modes on the sliding surface in a short, "
                 "limited time (the Lyapunov argument is given only for (19))",
                 f"V1' = (1-a)F s - b k|s| (claim fuzzy-condition): at k = {g.k:g} m/s^2, N = "
                 f"{g.N:g}, M = {g.M:g} the state e = 0.1 m, e' = {st['ed']:.4g} m/s has V1' = "
                 f"{v_exact:.4g} > 0", (refute,), law="fuzzy", scope="gain-set",
                 numbers={"vdot_exact": v_exact, "vdot_fd": v_fd, "ed": st["ed"]},
                 paper_expr=(u20, sp.Lt(VDOT, 0, evaluate=False)),
                 derived_expr=(sp.Eq(VDOT, vdot, evaluate=False),))


def fuzzy_finite_time_claim(g: Gains | None = None) -> Claim:
    """Near s = 0 both (1 - a) and b vanish like D: the reaching is asymptotic (the time to
    |s| = 1e-3 m/s computed for the gains in use)."""
    return _fuzzy_finite_time_claim(g or default_gains())


@cache
def _fuzzy_finite_time_claim(gains: Gains) -> Claim:
    mu = sp.Symbol("mu", positive=True)  # M / sqrt(1 + alpha^2) (one axis, D = |s| mu/M)
    S, se = sp.Symbol("S", positive=True), sp.Symbol("s_e", positive=True)
    # F = 0: s' = -k (1 - exp(-mu s)) for s > 0: t(s0 -> s_e) = int ds / (k (1 - e^{-mu s}))
    anti = (S + sp.log(1 - sp.exp(-mu * S)) / mu) / k
    chk = prove_identity(sp.simplify(sp.diff(anti, S) - 1 / (k * (1 - sp.exp(-mu * S)))),
                         "antiderivative of 1/(k(1 - exp(-mu s)))")
    lim = prove_identity(1 / sp.limit(anti.subs(S, 1) - anti.subs(S, se), se, 0, "+"),
                         "t(s0 -> s_e) -> oo as s_e -> 0: s = 0 is reached only asymptotically")
    t_reach = sp.Symbol("t", positive=True)
    time_int = sp.Eq(t_reach, sp.Integral(1 / (k * (1 - sp.exp(-mu * S))), (S, se, 1)),
                     evaluate=False)
    chk = _with_expr(chk, sp.Eq(sp.Derivative(anti, S), 1 / (k * (1 - sp.exp(-mu * S))),
                                evaluate=False))
    lim = _with_expr(lim, sp.Eq(sp.Limit(anti.subs(S, 1) - anti.subs(S, se), se, 0, "+"), sp.oo,
                                evaluate=False))
    g = {"k": gains.k, "M": gains.M, "alpha": gains.alpha}
    muv = g["M"] / math.sqrt(1 + g["alpha"] ** 2)
    s0v, sev = 1.0, 1e-3

    def t_fuzzy(s_a: float, s_b: float) -> float:  # closed form, expm1 for precision
        return (s_a - s_b + (math.log(-math.expm1(-muv * s_a))
                             - math.log(-math.expm1(-muv * s_b))) / muv) / g["k"]
    t_closed = t_fuzzy(s0v, sev)
    t_ftsmc = float(B.t_reach_sign(s0v, g["k"]))  # (17): s = 0 exactly at |s0|/k

    def ev(_t, y):
        return y[0] - sev
    ev.terminal = True
    sol = solve_ivp(lambda _t, y: [-g["k"] * (-math.expm1(-muv * y[0]))], (0, 100), [s0v],
                    events=ev, rtol=1e-10, atol=1e-12)
    t_ode = float(sol.t_events[0][0])
    w = Witness({"s0": s0v, "s_e": sev, "k": g["k"], "M": g["M"], "alpha": g["alpha"],
                 "t_ftsmc_to_0": t_ftsmc, "t_fuzzy_to_s_e": t_closed, "t_ode": t_ode},
                t_ftsmc - t_closed, "FTSMC time to s = 0 minus the fuzzy blend's closed-form "
                "time to |s| = s_e", t_ftsmc - t_ode, "the same with solve_ivp for the fuzzy "
                "blend", SEED)
    step = Step("the fuzzy blend reaches the surface faster than the FTSMC (19)",
                Search({"s0": "1 m/s", "s_e": "1e-3 m/s", "F": "0 (the blend's best case)",
                        "gains": "in use"}, "constructed from the closed form", 1, w.margin,
                       w.point, SEED, w))
    return Claim("fuzzy-finite-time", "(20)-(22)", "Finite-time reaching of the fuzzy FTSMC",
                 "ensures the system modes are placed on the sliding surface in a short, "
                 "limited time; raises the convergence speed",
                 "b(D) ~ M D near the surface, so s' ~ -k M D: the reaching is exponential "
                 f"(rate k M/sqrt(1+alpha^2) = {g['k'] * muv:.3g} 1/s for these gains), s = 0 "
                 f"is never reached; |s| = 1 -> 1e-3 m/s takes {t_closed:.2f} s with F = 0, "
                 f"where the FTSMC reaches s = 0 in {t_ftsmc:.2f} s",
                 (chk, lim, step), law="fuzzy", scope="gain-set",
                 numbers={"t_closed": t_closed, "t_ode": t_ode, "t_ftsmc": t_ftsmc},
                 derived_expr=(sp.Eq(sp.Symbol("sdot"), -k * (1 - sp.exp(-mu * S)),
                                     evaluate=False), time_int,
                               sp.Eq(t_reach, anti.subs(S, 1) - anti.subs(S, se),
                                     evaluate=False)))


def fuzzy_invariance_claim(g: Gains | None = None) -> Claim:
    """D of (22) mixes the axes: s_x = 0 with s_y != 0 gives a < 1, so s_x' = (1-a) F_x != 0
    (at the gains in use)."""
    return _fuzzy_invariance_claim(g or default_gains())


@cache
def _fuzzy_invariance_claim(gains: Gains) -> Claim:
    a, b = L.fuzzy_weights()
    g = {"N": gains.N, "alpha": gains.alpha}
    # s_y = 1 m/s, s_x = s_z = 0: the distance (21)-(22) of the law
    dv = float(L.fuzzy_distance((0, 1, 0)).subs(L.alpha, sp.nsimplify(g["alpha"])))
    Fx = 0.5  # m/s^2, the drift on x (e.g. e' ds/de for e' = 0.5, alpha = 1)
    sdx = float(((1 - a) * Fx).subs({L.N: g["N"], L.dist: dv}))
    # independent: floats
    sdx2 = (1 - math.exp(-g["N"] * dv)) * Fx
    w = Witness({"s": [0, 1, 0], "F_x": Fx, "N": g["N"], "alpha": g["alpha"],
                 "s_x_dot": sdx}, -abs(sdx), "s_x' on s_x = 0 (SymPy), margin -|s_x'|",
                -abs(sdx2), "the same in floats (math.exp)", SEED)
    step = Step("on the sliding surface a = 1 and b = 0, so the surface is invariant",
                Search({"state": "s_x = 0, s_y = 1 m/s, F_x = 0.5 m/s^2"}, "constructed", 1,
                       w.margin, w.point, SEED, w))
    s_ax = sp.symbols("s_x s_y s_z", real=True)
    Fx_s = sp.Symbol("F_x", real=True)
    dist_def = sp.Eq(L.dist, L.fuzzy_distance(s_ax), evaluate=False)
    step = dataclasses.replace(step, expr=sp.Eq(sp.Symbol("sdot_x"), (1 - a) * Fx_s,
                                                evaluate=False))
    return Claim("fuzzy-invariance", "(20)-(22)", "Invariance of one axis's surface",
                 "should the modes be on the sliding surface, a = 1 and b = 0",
                 "a = 1 only when all three s_i = 0 (D of (22) sums the axes): an axis on its "
                 "surface is pushed off by (1 - a) F while another axis is not",
                 (step,), law="fuzzy", numbers={"s_x_dot": sdx}, scope="gain-set",
                 paper_expr=(sp.Eq(sp.Symbol("a"), 1, evaluate=False),
                             sp.Eq(sp.Symbol("b"), 0, evaluate=False)),
                 derived_expr=(dist_def, sp.Eq(sp.Symbol("a"), a, evaluate=False),
                               sp.Eq(sp.Symbol("sdot_x"), (1 - a) * Fx_s, evaluate=False)))


# --- PD sliding mode -----------------------------------------------------------------------

@cache
def pd_claim() -> Claim:
    us = sp.Symbol("u_s", real=True)
    sd = L.sdot("pdsmc", L.u_eq("pdsmc") + us).subs(L.Dk, L.Dist)
    cancel = prove_identity(sp.simplify(sd - us), "PD: s' = u_s under u = u_eq + u_s (known D)")
    sol = e0 * sp.exp(-lam * tt)
    slide = prove_identity(sp.diff(sol, tt) + lam * sol, "on s = e' + lambda e = 0: "
                           "e = e0 exp(-lambda t)")
    never = prove_nonneg(sol, "e(t) = e0 exp(-lambda t) > 0 for all t: no finite settling time",
                         strict=True)
    tol = sp.Symbol("epsilon", positive=True)
    t_tol = prove_identity(sp.simplify(sol.subs(tt, sp.log(e0 / tol) / lam) - tol),
                           "|e| = epsilon at t = ln(|e0|/epsilon)/lambda")
    e_t, t_eps = sp.Function("e")(tt), sp.Symbol("t_epsilon", positive=True)
    cancel = _with_expr(cancel, sp.Eq(SDOT, U_S, evaluate=False))
    slide = _with_expr(slide, sp.Eq(e_t, sol, evaluate=False))
    t_tol = _with_expr(t_tol, sp.Eq(t_eps, sp.log(e0 / tol) / lam, evaluate=False))
    return Claim("pd-smc", "(Figs. 3-6, 'classic PD sliding mode')",
                 "The PD sliding mode (linear surface)",
                 "the classic PD sliding mode tracks in 8 s",
                 "s = e' + lambda e: reaching as in (17) (t_r = |s0|/k, known D), then "
                 "exponential sliding e = e0 exp(-lambda t): no finite settling time; "
                 "|e| <= epsilon after ln(|e0|/epsilon)/lambda",
                 (cancel, slide, never, t_tol), law="pdsmc", statement="workbench",
                 derived_expr=(sp.Eq(L.s, disp(L.surface_pd()), evaluate=False),
                               sp.Eq(e_t, sol, evaluate=False),
                               sp.Eq(t_eps, sp.log(e0 / tol) / lam, evaluate=False)))


# --- (8)-(10): reference ---------------------------------------------------------------------

@cache
def cubic_claim() -> Claim:
    exact = REF.exact_coefficients()
    steps = []
    t_ = REF.t
    T = sp.Rational(repr(P.T_LAND))
    for i, ax in enumerate(REF.AXES):
        xd = sum(ci * t_**j for j, ci in enumerate(exact[i]))
        steps.append(prove_identity(xd.subs(t_, T) - sp.Rational(repr(float(P.RF[i]))),
                                    f"{ax}: exact coefficients meet x_d(T) = target (9)"))
    # printed = exact rounded to 3 significant digits (exact rational arithmetic)
    def round3(x: sp.Rational) -> sp.Rational:
        if x == 0:
            return x
        ex = sp.floor(sp.log(abs(x), 10))
        scale = sp.Integer(10) ** (ex - 2)
        return sp.Rational(round(x / scale)) * scale
    for i in range(3):
        for j in (2, 3):
            pv = sp.Rational(repr(float(P.CUBIC_PRINTED[i, j])))
            res = round3(exact[i][j]) - pv
            wr = None
            if res != 0:
                wr = Witness({"axis": REF.AXES[i], "coefficient": f"c{j}",
                              "exact": str(exact[i][j]),
                              "exact_float": float(exact[i][j]), "printed": float(pv)},
                             -abs(float(res)), "3-digit rounding of the exact rational minus "
                             "the printed value", -abs(float(f"{float(exact[i][j]):.3g}")
                                                        - float(pv)),
                             "the same by float formatting ('%.3g')", SEED)
            steps.append(Step(f"{REF.AXES[i]}: printed c{j} = exact rounded to 3 significant "
                              "digits", Identity(res, "exact rational arithmetic",
                                                 point_witness=wr)))
    cs = sp.symbols("c_0:4", real=True)
    cubic8 = sp.Eq(sp.Symbol("x_d"), sum(ci * t_**j for j, ci in enumerate(cs)),
                   evaluate=False)
    miss = REF.endpoint_miss()
    # the printed coefficients miss the endpoint: exact-arithmetic residual and float re-check
    pr = [sum(sp.Rational(repr(float(P.CUBIC_PRINTED[i, j]))) * T**j for j in range(4))
          - sp.Rational(repr(float(P.RF[i]))) for i in range(3)]
    worst = int(np.argmax([abs(float(x)) for x in pr]))
    w = Witness({"axis": REF.AXES[worst], "t": P.T_LAND, "miss_exact_m": float(pr[worst])},
                -abs(float(pr[worst])), "printed cubic at T minus target (exact rationals)",
                -abs(miss["position_m"][worst]), "the same in floats (numpy)", SEED)
    steps.append(Step("the printed coefficients land the reference on the landing point",
                      Identity(sp.nsimplify(pr[worst]), "exact rational arithmetic",
                               point_witness=w)))
    return Claim("cubic-9-10", "(8)-(10)", "Cubic reference coefficients",
                 "x2 = 2.83e-4, x3 = -1.73e-8; y: -6.74e-5, 4.58e-9; z: 9.57e-5, -2.76e-9",
                 "exact coefficients round to the printed ones, but the 3-digit rounding moves "
                 "the endpoint by " + ", ".join(f"{m:+.2f}" for m in miss["position_m"])
                 + " m (x, y, z) and the end velocity by " + ", ".join(
                     f"{v:+.2e}" for v in miss["velocity_m_s"]) + " m/s",
                 tuple(steps), numbers={"exact": [[str(x) for x in row] for row in exact],
                                        "exact_float": REF.coefficients().tolist(), **miss},
                 scope="scenario", paper_expr=(cubic8,))


@cache
def reference_claim() -> Claim:
    """Monotonicity and the acceleration the reference asks for (gravity: the polyhedron)."""
    from lgw.theory.eros.polyhedron import eros_accel, eros_polyhedron, inside

    roots = REF.velocity_roots()
    turn = {ax: [t for t in rts if 0 < t < P.T_LAND] for ax, rts in zip(REF.AXES, roots,
                                                                          strict=True)}
    tt_ = np.linspace(0, P.T_LAND, 161)
    pos, vel, acc = REF.evaluate(REF.coefficients(), tt_)
    g = eros_accel(pos.T)
    gnorm = np.linalg.norm(g, axis=1)
    anorm = np.linalg.norm(acc, axis=0)
    ins = inside(eros_polyhedron(), pos.T)
    z_ok = Step("z_d is monotone on [0, T] (z_d' has no root inside (0, T))",
                Identity(sp.Integer(len(turn["z"])), "real roots of z_d' (SymPy real_roots)"))
    outside = Step("the reference path stays outside the shape model",
                   Search({"t": "161 points on [0, 8000] s"}, "solid-angle inside test", len(tt_),
                          float(-ins.sum()), {"inside_count": int(ins.sum())}, SEED))
    return Claim("reference-shape", "(8)-(10)", "What the cubic reference asks for",
                 "a third-degree polynomial keeps the vertical speed low for a safe landing",
                 f"x_d turns at t = {turn['x']} s, y_d at {turn['y']} s (non-monotone), z_d "
                 f"monotone; |x_d''| <= {anorm.max():.2e} m/s^2 against |g| in "
                 f"[{gnorm.min():.2e}, {gnorm.max():.2e}] m/s^2 along the path; max speed "
                 f"{np.linalg.norm(vel, axis=0).max():.3f} m/s",
                 (z_ok, outside), numbers={"turning_times_s": turn,
                                           "max_ref_accel": float(anorm.max()),
                                           "g_min": float(gnorm.min()),
                                           "g_max": float(gnorm.max())}, scope="scenario")


def surface_altitude(pt: np.ndarray, tol: float = 0.5) -> float:
    """Height (m) of an outside point above the shape model along the ray from the centroid
    (bisection on the solid-angle inside test)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron, inside

    E_ = eros_polyhedron()
    lo, hi = 0.0, 1.0
    while (hi - lo) * np.linalg.norm(pt) > tol:
        mid = 0.5 * (lo + hi)
        if inside(E_, mid * pt[None])[0]:
            lo = mid
        else:
            hi = mid
    return float((1.0 - hi) * np.linalg.norm(pt))


LANDING_TOL = 10.0  # m, chosen: "on the surface" within the shape model's resolution (~200 m
#                     edges at this scale would be generous; 10 m is a touchdown tolerance)


@cache
def landing_point_claim() -> Claim:
    from lgw.theory.eros.polyhedron import eros_polyhedron, inside

    h = surface_altitude(P.RF)
    below = P.RF * (1.0 - (h - LANDING_TOL) / np.linalg.norm(P.RF))
    still_out = not bool(inside(eros_polyhedron(), below[None])[0])
    w = Witness({"RF_m": P.RF.tolist(), "altitude_m": h, "tolerance_m": LANDING_TOL},
                LANDING_TOL - h, "bisection on the solid-angle inside test along the ray",
                -1.0 if still_out else 1.0, "the point h - 10 m below RF on the ray is still "
                "outside (total solid angle 0): margin -1 if so", SEED)
    step = Step("Table 1's landing position lies on the asteroid's surface",
                Search({"RF": "Table 1"}, "ray bisection", 1, w.margin, w.point, SEED, w))
    return Claim("landing-point", "Table 1, Fig. 12", "Where the landing point is",
                 "landing position [2837 928.1 5708] m", f"it lies {h:.0f} m above the shape "
                 "model (measured volume, centroid frame, long axis x): the reference ends in "
                 "a hover, not a touchdown", (step,), numbers={"altitude_m": h}, scope="scenario")


# --- (1), (2), Table 1 --------------------------------------------------------------------------

@cache
def dynamics_claim() -> Claim:
    printed, derived = L.rotating_frame_accel()
    steps = [prove_identity(sp.expand(a - b), f"axis {ax}: printed (4) = -2 W x v - W x (W x r)")
             for ax, a, b in zip("xyz", printed, derived, strict=True)]
    accel = sp.MatrixSymbol("a_rot", 3, 1)
    rel = abs(P.OMEGA_PRINTED - P.OMEGA) / P.OMEGA
    return Claim("dynamics-1", "(1), (3), (4)", "Rotating-frame dynamics",
                 "x'' - 2 w y' - w^2 x = g_x + u_x + D_x, ...; w = 3.3118e-4",
                 f"the Coriolis and centrifugal terms of a frame spinning about z; w printed "
                 f"differs from the measured 1639.389232 deg/day by {rel:.1e} relative",
                 tuple(steps), numbers={"omega_measured": P.OMEGA, "relative_diff": rel},
                 paper_expr=(sp.Eq(accel, sp.Matrix(printed), evaluate=False),),
                 derived_expr=(sp.Eq(accel, sp.Matrix(derived), evaluate=False),))


@cache
def gravity_claim() -> Claim:
    der = GR.gradient()
    pr = GR.gradient_printed()
    ranges = {GR.x: (5, 9), GR.y: (5, 9), GR.z: (5, 9)}
    # sp.expand suffices (both sides are sums of the same monomials in (x - x_i), Q_i^(-3/2));
    # sp.simplify on these takes minutes
    st = [Step(f"g_{ax} as printed in (2) = dU/d{ax}",
               identity_evidence(p_ - d_, ranges=ranges, seed=SEED, method="sympy.expand",
                                 simplified=sp.expand(p_ - d_)))
          for ax, p_, d_ in zip("xyz", pr, der, strict=True)]
    attract = prove_identity(pr[0] + der[0], "printed g = -grad U (a repulsive field): the "
                             "printed sign is the gradient of -U", method="sympy.expand",
                             simplified=sp.expand(pr[0] + der[0]))
    ux = sp.diff(GR.potential_printed(), GR.x) - pr[0]
    Uprinted = Step("U as extracted (M1/r1 + M2/r2, no G) has dU/dx = printed g_x",
                    identity_evidence(ux, ranges=ranges, seed=SEED, method="sympy.expand",
                                      simplified=sp.expand(ux)))
    r1s, r2s = sp.symbols("r_1 r_2", positive=True)

    def radii(ex: sp.Expr) -> sp.Expr:  # the distances to the mass points as r_1, r_2
        return ex.subs({GR._rho(GR.x1, GR.y1, GR.z1) ** 2: r1s ** 2,
                        GR._rho(GR.x2, GR.y2, GR.z2) ** 2: r2s ** 2}).subs(
            {GR._rho(GR.x1, GR.y1, GR.z1): r1s, GR._rho(GR.x2, GR.y2, GR.z2): r2s})
    gx = sp.Symbol("g_x", real=True)
    st[0] = _with_expr(st[0], sp.Eq(radii(pr[0]), radii(der[0]), evaluate=False))
    attract = _with_expr(attract, sp.Eq(radii(pr[0]), -radii(der[0]), evaluate=False))
    Uprinted = _with_expr(Uprinted, sp.Eq(sp.Derivative(GR.potential_printed(), GR.x),
                                          radii(pr[0]), evaluate=False))
    return Claim("gravity-2", "(2)", "Two-mass-point gravity", "g_x = dU/dx = G M1 (x-x1)/r1^3 "
                 "+ G M2 (x-x2)/r2^3", "g = grad(G M1/r1 + G M2/r2) = -G M1 (x-x1)/r1^3 - ...: "
                 "the printed g has the wrong sign (repulsive) and U lacks G (possibly lost "
                 "in extraction; the simulator uses the derived attraction)",
                 tuple(st) + (Uprinted,), remarks=(attract,),
                 paper_expr=(sp.Eq(sp.Symbol("U"), radii(GR.potential_printed()), evaluate=False),
                             sp.Eq(gx, radii(pr[0]), evaluate=False)),
                 derived_expr=(sp.Eq(sp.Symbol("U"), radii(GR.potential()), evaluate=False),
                               sp.Eq(gx, radii(der[0]), evaluate=False)))


@cache
def mass_claim() -> Claim:
    Mp, Mm = sp.Rational(repr(P.MASS_PRINTED)), sp.Rational(repr(P.MASS))
    gm_printed = P.G * P.MASS_PRINTED
    w = Witness({"M_printed_kg": P.MASS_PRINTED, "M_measured_kg": P.MASS},
                -abs(float(Mp / Mm - 1)), "-|M_printed / M_measured - 1| (exact)",
                -abs(gm_printed / P.GM_NEAR - 1), "-|G M_printed / GM(NEAR) - 1|", SEED)
    step = Step("Table 1's 6.69e5 kg is the mass of Eros",
                Identity(Mp / Mm - 1, "exact rationals", point_witness=w))
    rad = Step("Table 1's 16000 m is an average radius",
               Search({"R": f"{P.RADIUS_PRINTED:g} m"}, "compare with the volume-equivalent "
                      "radius", 1, -abs(float(P.R_MEAN - P.RADIUS_PRINTED)),
                      {"R_mean_m": P.R_MEAN}, SEED,
                      Witness({"R_printed": P.RADIUS_PRINTED, "R_mean": P.R_MEAN},
                              -abs(float(P.R_MEAN - P.RADIUS_PRINTED)),
                              "-|(3V/4pi)^(1/3) - R_printed|, V = 2503 km^3",
                              float(P.R_MEAN * 1.3 - P.RADIUS_PRINTED),
                              "with V 2.2x larger than measured (+30 % radius) still < R_printed",
                              SEED)))
    return Claim("table1-constants", "Table 1", "Table 1 constants",
                 "mass 6.69e5 kg, average radius 16000 m",
                 f"measured mass 6.687e15 kg (1e10 x); mean radius {P.R_MEAN:.0f} m (16 km is "
                 "the NEAR gravity field's reference radius)", (step, rad), scope="scenario")


def all_claims(gains: Gains | None = None) -> list[Claim]:
    """Every checkable claim of seed 002 that does not need the simulator, in report order;
    the gain-set claims judged for ``gains`` (default: the documented defaults)."""
    g = gains or default_gains()
    return [dynamics_claim(), gravity_claim(), mass_claim(), settling_tsm_claim(),
            growth_claim(), settling_ftsm_claim(), settling_ode_claim(), ftsm_faster_claim(),
            cubic_claim(), reference_claim(), landing_point_claim(), sdot_claim(), ueq_claim(),
            lyapunov_claim(),
            printed_exponent_claim(), singular_claim(), reaching_claim(), reaching_tanh_claim(),
            sampled_tanh_claim(g), sampled_tanh_limit_claim(g), fuzzy_condition_claim(),
            fuzzy_reaching_claim(g), fuzzy_finite_time_claim(g), fuzzy_invariance_claim(g),
            pd_claim()]


MODULES = ("lgw.theory.eros.laws", "lgw.theory.eros.claims", "lgw.theory.eros.reference",
           "lgw.theory.eros.gravity", "lgw.theory.eros.polyhedron")


def clear_caches() -> None:
    """Forget every cached claim and intermediate result (a changed law, bound or constant is
    then derived afresh: the mutation tests use it)."""
    import sys

    for name in MODULES:
        mod = sys.modules.get(name)
        for obj in vars(mod).values() if mod else ():
            if callable(getattr(obj, "cache_clear", None)):
                obj.cache_clear()


# --- the whole descent: where the fitted two-point model holds ------------------------------------

@cache
def gravity_scope_claim() -> Claim:
    """Seed 002's two-point model (2) "describes the weak gravity around the asteroid": judged
    for the workbench's fit (the paper prints no masses or positions) against the polyhedron,
    along the whole descent to touchdown (lgw.theory.eros.descent) and around the body (20 to
    1000 km, 26 directions), where it is compared with the simplest model, a point mass at the
    centroid.  A far-field witness is re-checked with the polyhedron's gravity by Gauss-Legendre
    quadrature over its tetrahedra (independent of Werner & Scheeres)."""
    from lgw.theory.eros import descent as TD
    from lgw.theory.eros.gravity import two_point_accel

    prof = TD.descent_profile()
    tt = np.linspace(0.0, prof.t_touchdown, 161)
    err = TD.fit_error(prof.evaluate(tt)[0].T)
    j = int(np.argmax(err["rel"]))
    local = Step(f"along the descent to touchdown the fitted (2) is within "
                 f"{P.TWO_POINT_FIT_MAX:.2%} of the polyhedron (the fit's own largest residual)",
                 Search({"t": f"161 reference points on [0, {prof.t_touchdown:g}] s"},
                        "grid along the descent profile", len(tt),
                        float(P.TWO_POINT_FIT_MAX - err["rel"][j]),
                        {"t": float(tt[j]), "rel_error": float(err["rel"][j])}, SEED))
    far = TD.far_field_error()
    margins = [r["point_mass_max"] - r["two_point_max"] for r in far]
    k = int(np.argmin([m / r["point_mass_max"] for m, r in zip(margins, far, strict=True)]))
    r_w = far[k]["radius_m"]
    pt = np.array([r_w, 0.0, 0.0])
    gq = TD.quadrature_accel(pt, 4)
    e2 = float(np.linalg.norm(two_point_accel(pt[None], P.TWO_POINT_P1, P.TWO_POINT_P2,
                                              *P.TWO_POINT_GM)[0] - gq) / np.linalg.norm(gq))
    epm = float(np.linalg.norm(two_point_accel(pt[None], np.zeros(3), np.zeros(3), P.GM,
                                               0.0)[0] - gq) / np.linalg.norm(gq))
    w = Witness({"radius_m": r_w, "two_point_max": far[k]["two_point_max"],
                 "point_mass_max": far[k]["point_mass_max"]}, float(margins[k]),
                "26 directions per radius, Werner-Scheeres polyhedron", epm - e2,
                "the point (r, 0, 0), the polyhedron by 4^3-node Gauss-Legendre quadrature "
                "over its tetrahedra", SEED)
    around = Step("around the asteroid (20 to 1000 km) the fitted (2) is at least as accurate "
                  "as a point mass at the centroid",
                  Search({"radius_km": [r["radius_m"] / 1e3 for r in far], "directions": 26},
                         "grid of radii and directions", 26 * len(far), float(margins[k]),
                         w.point, SEED, w if margins[k] < 0 else None))
    cm = TD.two_point_centre()
    return Claim("gravity-scope", "(2), abstract", "Where the two-point model holds",
                 "the two-point barycentric gravitational model describes the weak gravity "
                 "around the asteroid",
                 f"a local surrogate: fitted about the paper's path, within "
                 f"{100 * float(err['rel'].max()):.2f} % of the polyhedron all the way to "
                 f"touchdown; its centre of mass is {np.linalg.norm(cm):.0f} m from the body's, "
                 f"so far away it is worse than a point mass ({100 * far[-1]['two_point_max']:.2f}"
                 f" % against {100 * far[-1]['point_mass_max']:.3f} % at "
                 f"{far[-1]['radius_m'] / 1e3:g} km)", (local, around), scope="scenario",
                 numbers={"descent_max_rel": float(err["rel"].max()),
                          "far_field": far, "centre_offset_m": float(np.linalg.norm(cm))})
