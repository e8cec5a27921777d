"""Seed 000's claims, derived from the law and checked: each verdict is computed from evidence.

Everything here is derived from the SymPy expressions of ``lgw.theory.mars.mss``; no printed
formula is taken as true, and no status is written by hand: every step carries the evidence a
prover made (``lgw.theory.provers``).  A step that rests on another claim uses it as a lemma
(``FromClaim``: its verdict carries over, and a refuted or unproven lemma leaves the step
unproven), so a conclusion is never stronger than what it rests on.

Every step computes from the law, plant and gains in use: V2' is derived from the law's closed
loop (a witness, drawn inside the gain hypotheses ``mss.SAMPLE_RANGES``, refutes a printed
identity), the command's exponents are read from the law, the reduced loops take their s2
drift from the law.  Change the law and exactly the verdicts whose mathematics changed change
(tests/mars/test_mutations.py).

Where the workbench corrects a printed statement there are two claims: the paper's, judged as
printed (``statement="paper"``, refuted with its witness), and the workbench's correction
(``statement="workbench"``, ``corrects`` = the paper claim's id).

``general_claims()`` lists the claims that hold or fail whatever the valid gains (scope
"all-gains") in report order; ``all_claims(gains)`` adds ``gain_set_claims(gains)``, the
gain-dependent statements judged for that gain set (scope "gain-set"), and the claims on the
paper's simulations (``lgw.theory.mars.scenario_claims``, from the report layer's record).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import random

import numpy as np
import sympy as sp
from lgw.theory import settling_proofs as SP
from lgw.theory.evidence import Cited, Claim, FromClaim, Identity, Search, Step, Unproven
from lgw.theory.falsify import Budget
from lgw.theory.mars import mss as M
from lgw.theory.mars.bounds import tf_min, tf_min_printed
from lgw.theory.mars.parameters import G_MARS, M0, R0, THRUST_MAX_AXIS, V0
from lgw.theory.mars.reduced import surface_trajectory, trajectory
from lgw.theory.provers import (
    identity_at,
    identity_evidence,
    prove_arb,
    prove_identity,
    prove_nonneg,
    prove_z3,
    refute_nonneg_at,
    search_step,
    witness_step,
)
from lgw.theory.settling import polyakov_bound
from lgw.theory.symbolic import memo, sig

# Budget of the full-domain searches run by the report (``lgw.theory.mars.searches``): small
# enough for a report (~20 s for landing-time), large enough to re-find the paper's
# max{T1, T2} counterexample from scratch; docs/verify.md lists the larger FULL budget's results.
REPORT_SEARCH_BUDGET = Budget(popsize=4, maxiter=6, local_evals=60, seed=0)
# The searches whose fast route and re-check take the corrected law's exact cancellation,
# s2' = -alpha1 sig(s2,g1) - alpha2 sig(s2,g2) (+ a_p): run only while the law in force gives it.
NEEDS_EXACT_CANCELLATION = frozenset({"T2-corrected", "landing-time", "T3"})

r, v, ap = M.r, M.v, M.ap
b1, b2, a1, a2 = M.beta1, M.beta2, M.alpha1, M.alpha2
q1, q2, g1, g2 = M.q1, M.q2, M.g1, M.g2
S2 = M.S2  # the second surface as a coordinate
amax = sp.Symbol("a_max", positive=True)
th1, th2 = sp.symbols("theta_1 theta_2", positive=True)

# A concrete gain set for counterexamples that need a trajectory (the example of).
EXAMPLE_GAINS = {"beta1": 0.2, "beta2": 0.05, "alpha1": 0.5, "alpha2": 0.1,
                 "q1": 0.7, "q2": 1.3, "g1": 0.7, "g2": 1.3}
# Rational points for symbolic counterexamples (exact arithmetic).
PT = {b1: sp.Integer(1), b2: sp.Integer(1), a1: sp.Integer(1), a2: sp.Integer(1),
      q1: sp.Rational(1, 2), q2: sp.Integer(2), g1: sp.Rational(1, 2), g2: sp.Integer(2)}


# --- Display forms: the formulas the report renders (paper_expr / derived_expr).  They are
# built from the same SymPy objects the proofs use; no verdict depends on them.
S1 = sp.Symbol("s_1", real=True)
A_CMD, G_I, AM_I, AP_I = sp.symbols("a g a_m a_p", real=True)
S1DOT, S2DOT = sp.symbols("sdot_1 sdot_2", real=True)
V1DOT, V2DOT, V1S, V2S = sp.symbols("Vdot_1 Vdot_2 V_1 V_2", real=True)
T1S, T2S, T1X, T2X, T3S = sp.symbols("T_1 T_2 T_1^* T_2^* T_3", positive=True)
T_LAND = sp.Symbol("t_land", positive=True)
MI = sp.Symbol("M_i", positive=True)


def _disp(expr: sp.Expr) -> sp.Expr:
    """expr in the paper's coordinates: the second surface (21) as s2, r as s1, the gravity,
    drag and disturbance components as g, a_m, a_p."""
    return expr.xreplace({M.surface2(): S2}).xreplace({r: S1, M.grav: G_I, M.am: AM_I,
                                                       ap: AP_I})


def _with_exprs(claim: Claim, paper=None, derived=None) -> Claim:
    """``claim`` (made elsewhere, e.g. lgw.theory.settling_proofs) with formulas to render."""
    return dataclasses.replace(claim, paper_expr=paper, derived_expr=derived)


def _settling_exprs() -> dict[str, tuple]:
    """Lemma 2 (2)-(3) and the least upper bound T* in the symbols of settling_proofs."""
    a_, b_, k_, V_ = SP.a, SP.b, SP.k, SP.V
    p_, g_ = sp.symbols("p g", positive=True)
    T, Ts, Vd = sp.Symbol("T", positive=True), sp.Symbol("T^*", positive=True), \
        sp.Symbol("Vdot", real=True)
    rate = (a_ * V_**p_ + b_ * V_**g_) ** k_
    integral = sp.Integral(1 / rate, (V_, 0, sp.oo))
    hyp = sp.Le(Vd, -rate, evaluate=False)
    polyakov = sp.Le(T, SP.polyakov_expr(a_, b_, p_, g_, k_), evaluate=False)
    return {"lemma2": ((hyp, polyakov), (hyp, sp.Le(T, integral, evaluate=False), polyakov)),
            "exact-bound": ((), (sp.Eq(Ts, integral, evaluate=False),
                                 sp.Eq(Ts, SP.exact_expr(a_, b_, p_, g_, k_), evaluate=False),
                                 sp.Le(Ts, SP.polyakov_expr(a_, b_, p_, g_, k_),
                                       evaluate=False)))}


def _identity(expr: sp.Expr, statement: str) -> Step:
    """``prove_identity`` with a failing identity's witness drawn inside the hypotheses of
    (16), (25) and Theorem 4 (0 < q1, g1 < 1 < q2, g2; 0 < theta1, theta2 < 1)."""
    return prove_identity(expr, statement, ranges={**M.SAMPLE_RANGES, th1: (0.0, 1.0),
                                                   th2: (0.0, 1.0)})


def _lemma(claim: Claim, what: str = "") -> Step:
    """``claim`` used as a lemma: its verdict carries over (a refuted or unproven lemma leaves
    the step unproven: the conclusion rests on something not shown)."""
    return Step(f"[claim {claim.id}] {what or claim.title}", FromClaim(claim))


def _surface_coords(expr: sp.Expr) -> sp.Expr:
    """Write expr(r, v) in (s1, s2) = (r, S2): v = S2 - beta1 sig(r,q1) - beta2 sig(r,q2)."""
    return expr.subs(v, S2 + M.reaching_law_rhs(r))


def prove_branches(expr: sp.Expr, reals: tuple[sp.Symbol, ...], statement: str) -> Step:
    """expr == 0 on every sign branch of the real symbols (x = 0 excluded: measure zero, and
    the surfaces' derivatives are taken for x != 0 as in seed 000 (22)).  The evidence is the
    first branch whose residual does not reduce to 0, else residual 0 on every branch; a
    witness is drawn only inside the gain hypotheses (``mss.SAMPLE_RANGES``)."""
    names = ", ".join(s.name for s in reals)
    for signs in itertools.product((1, -1), repeat=len(reals)):
        pairs = list(zip(reals, signs, strict=True))
        subs = {s: sg * sp.Symbol(f"{s.name}_abs", positive=True) for s, sg in pairs}
        e = sp.powsimp(sp.expand(expr.subs(subs)), force=True)
        ev = identity_evidence(e, method="sympy.simplify on the sign branch "
                               + str({s.name: sg for s, sg in pairs}), ranges=M.SAMPLE_RANGES)
        if ev.status != "proved":
            return Step(statement, ev, sp.Eq(expr, 0, evaluate=False))
    return Step(statement, Identity(sp.Integer(0), f"sympy.simplify on every sign branch of "
                                    f"{names}"), sp.Eq(expr, 0, evaluate=False))


def _dbeta() -> sp.Expr:
    """d/ds1 (beta1 sig(s1,q1) + beta2 sig(s1,q2)) = beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)."""
    return b1 * q1 * sp.Abs(r) ** (q1 - 1) + b2 * q2 * sp.Abs(r) ** (q2 - 1)


# --- (15), (16), (19)-(20), (18) ---------------------------------------------------------

@memo
def surface_claim() -> Claim:
    steps = [_identity(M.surface2().subs(v, M.reaching_law_rhs(r)),
                            "s2 of (21) vanishes exactly when s1' = v obeys the reaching law (16)")]
    rd = sp.Symbol("r_d", real=True)
    paper = (sp.Eq(S1, sp.Symbol("r", real=True) - rd, evaluate=False),
             sp.Eq(S1DOT, _disp(M.reaching_law_rhs(r)), evaluate=False),
             sp.Eq(S2, S1DOT - _disp(M.reaching_law_rhs(r)), evaluate=False))
    derived = (sp.Equivalent(sp.Eq(S2, 0), sp.Eq(S1DOT, _disp(M.reaching_law_rhs(r))),
                             evaluate=False),)
    return Claim("surface2", "(15), (16), (21)", "The second surface encodes the reaching law",
                 "once s2 = 0 the first reaching law (16) is established automatically",
                 "s2 = 0  <=>  v = -beta1 sig(s1,q1) - beta2 sig(s1,q2)", steps,
                 paper_expr=paper, derived_expr=derived)


@memo
def v1dot_axis_claim() -> Claim:
    V1 = r**2 / 2
    V1dot = sp.diff(V1, r) * M.reaching_law_rhs(r)
    target = -b1 * sp.Abs(r) ** (q1 + 1) - b2 * sp.Abs(r) ** (q2 + 1)
    lemma2_form = -(b1 * 2 ** ((q1 + 1) / 2) * V1 ** ((q1 + 1) / 2)
                    + b2 * 2 ** ((q2 + 1) / 2) * V1 ** ((q2 + 1) / 2))
    steps = [prove_branches(V1dot - target, (r,), "V1' = s1 s1' = -beta1|s1|^(q1+1) - "
                            "beta2|s1|^(q2+1) along (16) (one axis)"),
             prove_branches(target - lemma2_form, (r,), "= -(beta1 2^((q1+1)/2) V1^((q1+1)/2) + "
                            "beta2 2^((q2+1)/2) V1^((q2+1)/2)) with V1 = s1^2/2 (equality)")]
    return Claim("V1dot", "(19)-(20)", "Lyapunov derivative of the first surface, per axis",
                 "V1' = s1' s1 = -beta1|s1|^(q1+1) - beta2|s1|^(q2+1) <= -(beta1 2^((q1+1)/2) "
                 "V1^((q1+1)/2) + beta2 2^((q2+1)/2) V1^((q2+1)/2))",
                 "Per axis both relations are equalities (proved).", steps,
                 paper_expr=(sp.Eq(V1DOT, _disp(target), evaluate=False),
                             sp.Le(V1DOT, _lemma2_rhs(b1, b2, q1, q2, V1S), evaluate=False)),
                 derived_expr=(sp.Eq(V1DOT, _disp(target), evaluate=False),
                               sp.Eq(V1DOT, _lemma2_rhs(b1, b2, q1, q2, V1S), evaluate=False)))


def _lemma2_rhs(gain1, gain2, e1_, e2_, Vs: sp.Symbol) -> sp.Expr:
    """-(gain1 2^((e1+1)/2) V^((e1+1)/2) + gain2 2^((e2+1)/2) V^((e2+1)/2)): (20), (29)."""
    return -(gain1 * 2 ** ((e1_ + 1) / 2) * Vs ** ((e1_ + 1) / 2)
             + gain2 * 2 ** ((e2_ + 1) / 2) * Vs ** ((e2_ + 1) / 2))


def _power_mean_search(q_lo: float, q_hi: float, factor, statement: str, seed: int) -> Step:
    """Random search (today's slice) for sum_i |s_i|^(q+1) < factor(q) (sum_i s_i^2)^((q+1)/2);
    margin relative to the right side."""
    rng = random.Random(seed)
    pts = []
    for _ in range(4000):
        q = rng.uniform(q_lo, q_hi)
        x = [rng.uniform(-1, 1) * 10 ** rng.uniform(-3, 3) for _ in range(3)]
        pts.append({"q": q, "s": x})

    def margin(pt):
        x = np.asarray(pt["s"])
        rhs = factor(pt["q"]) * np.sum(x**2) ** ((pt["q"] + 1) / 2)
        return (np.sum(np.abs(x) ** (pt["q"] + 1)) - rhs) / rhs

    def recheck(pt):
        qq = sp.nsimplify(pt["q"])
        xs = [sp.nsimplify(c) for c in pt["s"]]
        lhs = sum(sp.Abs(c) ** (qq + 1) for c in xs)
        rhs = sp.nsimplify(factor(pt["q"])) * sum(c**2 for c in xs) ** ((qq + 1) / 2)
        return float(sp.N((lhs - rhs) / rhs, 30))

    return search_step(statement, margin, pts, domain={"q": [q_lo, q_hi],
                                                       "|s_i|": "[1e-3, 1e3] log-uniform",
                                                       "axes": 3},
                       method="random search (uniform q, log-uniform magnitudes, random signs)",
                       seed=seed, relative=True, recheck=recheck,
                       recheck_method="SymPy at 30 digits from the rationalised point")


@memo
def v1dot_vector_claim() -> Claim:
    """The paper writes (19)-(20) with the vector s1 and diagonal matrices; with V1 = |s1|^2/2
    the inequality needs sum_i |s_i|^(q+1) >= (sum s_i^2)^((q+1)/2), false for q > 1."""
    s = sp.symbols("s_x s_y s_z", real=True)
    qq = sp.Symbol("q", positive=True)
    gap = sum(sp.Abs(x) ** (qq + 1) for x in s) - sum(x**2 for x in s) ** ((qq + 1) / 2)
    pt = {s[0]: 1, s[1]: 1, s[2]: 1, qq: 2}
    steps = [refute_nonneg_at(gap, pt, "sum_i |s_i|^(q2+1) >= (sum_i s_i^2)^((q2+1)/2) for "
                              "q2 > 1 (needed for the beta2 term of (20) with V1 = |s1|^2/2)")]
    return Claim("V1dot-vector", "(19)-(20), vector form",
                 "Lyapunov derivative of the first surface, 3-axis form",
                 "V1 = s1^T s1/2, V1' <= -(beta1 2^((q1+1)/2) V1^((q1+1)/2) + beta2 2^((q2+1)/2) "
                 "V1^((q2+1)/2)) with diagonal gain matrices",
                 "With scalar gains the q2 term is false (counterexample at s1 = (1, 1, 1), "
                 "q2 = 2); the corrected form is claim V1dot-vector-corrected.", steps)


@memo
def v1dot_vector_corrected_claim() -> Claim:
    steps = [
        _power_mean_search(0.01, 0.99, lambda q: 1.0,
                           "sum_i |s_i|^(q1+1) >= (sum_i s_i^2)^((q1+1)/2) for 0 < q1 < 1", 0),
        _power_mean_search(1.01, 4.0, lambda q: 3 ** ((1 - q) / 2),
                           "sum_i |s_i|^(q2+1) >= 3^((1-q2)/2) (sum_i s_i^2)^((q2+1)/2) for "
                           "q2 > 1 (power-mean inequality)", 1),
    ]
    return Claim("V1dot-vector-corrected", "(19)-(20), vector form",
                 "Lyapunov derivative of the first surface, 3-axis form, corrected",
                 "V1 = s1^T s1/2, V1' <= -(beta1 2^((q1+1)/2) V1^((q1+1)/2) + beta2 2^((q2+1)/2) "
                 "V1^((q2+1)/2)) with diagonal gain matrices",
                 "With scalar gains the q1 term holds and the q2 term needs the factor "
                 "3^((1-q2)/2).  The time bound (18) holds per axis anyway: the axes are "
                 "decoupled (claim T1).", steps, statement="workbench", corrects="V1dot-vector",
                 derived_expr=_power_mean_forms())


def _power_mean_forms() -> tuple[sp.Basic, ...]:
    """The two power-mean inequalities of V1dot-vector-corrected (display)."""
    s = sp.symbols("s_x s_y s_z", real=True)
    lhs = {e: sum(sp.Abs(x) ** (e + 1) for x in s) for e in (q1, q2)}
    n2 = sum(x**2 for x in s)
    return (sp.GreaterThan(lhs[q1], n2 ** ((q1 + 1) / 2), evaluate=False),
            sp.GreaterThan(lhs[q2], 3 ** ((1 - q2) / 2) * n2 ** ((q2 + 1) / 2), evaluate=False))


def _report_search(search_id: str, starts: bool = False) -> Step:
    """One full-domain search of ``lgw.theory.mars.searches`` at the report's budget, as a
    step (``starts``: begin from the worst points of the larger FULL-budget run).  A search
    whose reduced dynamics assume the corrected law's exact cancellation is not run when the
    law in force does not cancel (its drift, computed from the law, is not 0): unproven."""
    from lgw.theory.mars import searches

    if search_id in NEEDS_EXACT_CANCELLATION and not M.s2_drift_vanishes("corrected"):
        pos, _ = M.s2_drift_branches("corrected")
        return Step(searches.STATEMENTS[search_id], Unproven(
            "not searched: the search's reduced loop takes s2' = -alpha1 sig(s2,g1) - alpha2 "
            "sig(s2,g2) (+ a_p) exactly, and the corrected law in force leaves the drift "
            f"{sp.sstr(pos)} (s1 = x > 0) in s2'"))
    run = searches.run_from_known if starts else searches.run
    return Step(searches.STATEMENTS[search_id], run(search_id, REPORT_SEARCH_BUDGET))


def _route_identity(gain1, gain2, e1_, e2_) -> tuple[Step, Step]:
    aV, bV = gain1 * 2 ** ((e1_ + 1) / 2), gain2 * 2 ** ((e2_ + 1) / 2)
    pV, gV = (e1_ + 1) / 2, (e2_ + 1) / 2
    printed = (1 / (gain1 * (1 - e1_) * 2 ** ((e1_ - 1) / 2))
               + 1 / (gain2 * (e2_ - 1) * 2 ** ((e2_ - 1) / 2)))
    s1 = _identity(sp.simplify(SP.polyakov_expr(aV, bV, pV, gV, 1) - printed),
                        "Lemma 2 (3) with k = 1 and the V-route constants equals the printed bound")
    s2 = _identity(SP._log_ratio(SP.exact_expr(aV, bV, pV, gV, 1),
                                      SP.exact_expr(gain1, gain2, e1_, e2_, 1)),
                        "T* is the same through V = s^2/2 and through |s| (route-invariant)")
    return s1, s2


def _decoupled_step(rhs_of, statement: str) -> Step:
    """Diagonal gains: the i-th component of the vector law depends on axis i only (the
    Jacobian's off-diagonal entries are identically 0, their sum of squares is the residual)."""
    xs = sp.symbols("x_x x_y x_z", real=True)
    comp = [rhs_of(xs[i], i) for i in range(3)]
    off = sum(sp.diff(comp[i], xs[j]) ** 2 for i in range(3) for j in range(3) if i != j)
    return _identity(off, statement)


@memo
def t1_claim() -> Claim:
    i1, _ = _route_identity(b1, b2, q1, q2)
    gb = [sp.symbols(f"beta1_{a} beta2_{a}", positive=True) for a in "xyz"]
    dec = _decoupled_step(lambda x, i: -gb[i][0] * sig(x, q1) - gb[i][1] * sig(x, q2),
                          "(16) with diagonal beta1, beta2 is decoupled: d s1i'/d s1j = 0 for "
                          "i != j, so the 3-axis time is the max over axes of the per-axis time")
    steps = [_lemma(v1dot_axis_claim(), "V1' along (16), per axis (equality)"),
             _lemma(SP.lemma2(), "Lemma 2: the settling bound (3)"), i1, dec]
    T18 = _bound_exprs()["T1 (18)"]
    return Claim("T1", "(18)", "Theorem 2: fixed-time convergence of the first surface",
                 "T1 <= 1/(beta1 (1-q1) 2^((q1-1)/2)) + 1/(beta2 (q2-1) 2^((q2-1)/2))",
                 "Holds per axis under (16).  Least upper bound: T1* = Gamma(m)Gamma(1-m)/"
                 "(beta1 (q2-q1)) (beta1/beta2)^m, m = (1-q1)/(q2-q1) (claim exact-bound).",
                 steps, searches=(_report_search("T1"),),
                 paper_expr=(sp.Le(T1S, T18, evaluate=False),),
                 derived_expr=(sp.Le(T1S, T1X, evaluate=False),
                               sp.Eq(T1X, SP.exact_expr(b1, b2, q1, q2, 1), evaluate=False),
                               sp.Le(T1X, T18, evaluate=False)))


# --- (22)-(29): the second surface and the guidance ---------------------------------------

@memo
def s2dot_claim() -> Claim:
    acc = sp.Symbol("a", real=True)
    s2dot = M.time_derivative(M.surface2(), acc)
    expected = acc + M.grav + M.am + _dbeta() * v
    steps = [prove_branches(s2dot - expected, (r,),
                            "s2' = s1'' + (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s1', "
                            "s1'' = a + g + a_m, s1' = v")]
    return Claim("s2dot", "(22)-(23)", "Derivative of the second surface",
                 "s2' = s1'' + beta1 q1 |s1|^(q1-1) s1' + beta2 q2 |s1|^(q2-1) s1'",
                 "Holds (s1 != 0).", steps)


@memo
def s2dot24_claim() -> Claim:
    acc = sp.Symbol("a", real=True)
    true = M.time_derivative(M.surface2(), acc)
    resid = true - _printed24(acc)
    pt = {**PT, r: sp.Integer(1), v: sp.Integer(1), acc: sp.Integer(0), M.grav: sp.Integer(0),
          M.am: sp.Integer(0)}
    steps = [identity_at(resid, pt, "(24) = true s2' (residual 0 for every state)")]
    return Claim("s2dot-24", "(24)", "Second-surface derivative with the command",
                 "s2' = a + g + a_m - beta1^2 q1|s1|^(2q1-1)sgn(s1) - beta2^2 q2|s1|^(2q2-1)"
                 "sgn(s1) - beta1 beta2 (q1+q2)|s1|^(q1+q2-1)sgn(s1)",
                 "(24) substitutes the reaching law (16) for s1' = v, which holds only on s2 = 0 "
                 "(claim s2dot-24-corrected).", steps,
                 paper_expr=(sp.Eq(S2DOT, _disp(_printed24(acc)), evaluate=False),))


def _printed24(acc: sp.Expr) -> sp.Expr:
    """Seed 000 (24) as printed (the paper's formula, judged as printed)."""
    return (acc + M.grav + M.am - b1**2 * q1 * sig(r, 2 * q1 - 1)
            - b2**2 * q2 * sig(r, 2 * q2 - 1) - b1 * b2 * (q1 + q2) * sig(r, q1 + q2 - 1))


@memo
def s2dot24_corrected_claim() -> Claim:
    acc = sp.Symbol("a", real=True)
    resid = M.time_derivative(M.surface2(), acc) - _printed24(acc)
    steps = [prove_branches(_surface_coords(resid - _dbeta() * M.surface2()), (r,),
                            "true s2' - printed (24) = (beta1 q1|s1|^(q1-1) + beta2 q2 "
                            "|s1|^(q2-1)) s2"),
             prove_branches(resid.subs(v, M.reaching_law_rhs(r)), (r,),
                            "on s2 = 0 (v given by (16)) the printed (24) is exact")]
    return Claim("s2dot-24-corrected", "(24)", "Second-surface derivative with the command, "
                 "corrected", "(24) as printed", "In general s2' = (24) + (beta1 q1|s1|^(q1-1) + "
                 "beta2 q2|s1|^(q2-1)) s2; on s2 = 0 it is (24).", steps,
                 paper_expr=(sp.Eq(S2DOT, _disp(_printed24(acc)), evaluate=False),),
                 derived_expr=(sp.Eq(S2DOT, _disp(_printed24(acc)) + _disp(_dbeta()) * S2,
                                     evaluate=False),),
                 statement="workbench", corrects="s2dot-24")


def _v_route_step(gain1, gain2, e1_, e2_, s: sp.Symbol, Vs: sp.Symbol, name: str) -> Step:
    """-gain1|s|^(e1+1) - gain2|s|^(e2+1) = Lemma 2's form in V = s^2/2 (equality, per axis)."""
    target = -gain1 * sp.Abs(s) ** (e1_ + 1) - gain2 * sp.Abs(s) ** (e2_ + 1)
    form = _lemma2_rhs(gain1, gain2, e1_, e2_, Vs).subs(Vs, s**2 / 2)
    return prove_branches(target - form, (s,), f"= -({sp.sstr(gain1)} 2^(({sp.sstr(e1_)}+1)/2) "
                          f"{name}^(({sp.sstr(e1_)}+1)/2) + ...) with {name} = s^2/2 (equality)")


def _branch_display(expr_rs2: sp.Expr) -> sp.Expr | None:
    """expr(r, S2) reduced on r = x > 0 and shown with |s1| for x (None if it is 0 there)."""
    x = sp.Symbol("x", positive=True)
    e = sp.simplify(sp.powsimp(sp.expand(expr_rs2.subs(r, x)), force=True))
    return None if e == 0 else _disp(e.subs(x, sp.Abs(S1)))


def _v2dot_residual(law: str, with_ap: bool = False) -> sp.Expr:
    cl = M.closed_loop(law)
    V2dot = cl.V2dot if with_ap else cl.V2dot.subs(ap, 0)
    s2 = M.surface2()
    target = -a1 * sp.Abs(s2) ** (g1 + 1) - a2 * sp.Abs(s2) ** (g2 + 1)
    if with_ap:
        target = target + s2 * ap
    return _surface_coords(V2dot - target)


@memo
def v2dot_claim(law: str) -> Claim:
    """(29) judged on the law: V2' - (29) is computed from the law's closed loop; it must
    vanish on every sign branch (a witness, drawn inside the gain hypotheses, refutes)."""
    resid = _v2dot_residual(law)
    paper = ("substituting (25) into (28): V2' = s2^T[-alpha1|s2|^g1 sgn(s2) - alpha2|s2|^g2 "
             "sgn(s2)] = -alpha1|s2|^(g1+1) - alpha2|s2|^(g2+1) <= -(alpha1 2^((g1+1)/2) "
             "V2^((g1+1)/2) + alpha2 2^((g2+1)/2) V2^((g2+1)/2))")
    law29 = -a1 * sp.Abs(S2) ** (g1 + 1) - a2 * sp.Abs(S2) ** (g2 + 1)
    paper_e = (sp.Eq(V2DOT, law29, evaluate=False),
               sp.Le(V2DOT, _lemma2_rhs(a1, a2, g1, g2, V2S), evaluate=False))
    steps = [prove_branches(resid, (r, S2), f"V2' = s2 s2' = -alpha1|s2|^(g1+1) - alpha2|s2|"
                            f"^(g2+1) under the {law} law (V2' from the law's closed loop)"),
             _v_route_step(a1, a2, g1, g2, S2, V2S, "V2")]
    extra = _branch_display(resid)
    remarks = ()
    if extra is not None:
        x = sp.Symbol("x", positive=True)
        remarks = (prove_nonneg(sp.simplify(sp.powsimp(sp.expand(resid.subs(r, x)),
                                                       force=True)),
                                "the extra term V2' - (29) is >= 0 on s1 > 0 (it destabilises "
                                "s2)"),)
    derived_e = (paper_e if extra is None else
                 (sp.Eq(V2DOT, law29 + extra, evaluate=False),))
    if law == "corrected":
        return Claim("V2dot-corrected", "(27)-(29)", "Lyapunov derivative of the second "
                     "surface, corrected law", paper,
                     "(29) computed for the corrected law (exact cancellation of s2').", steps,
                     law=law, paper_expr=paper_e, derived_expr=derived_e, remarks=remarks,
                     statement="workbench", corrects="V2dot-printed")
    return Claim("V2dot-printed", "(27)-(29)", "Lyapunov derivative of the second surface, "
                 "printed law (25)", paper,
                 "V2' computed from the printed law (25): V2' - (29) is shown (s1 > 0; the "
                 "extra term, if any, is why (29) fails off s2 = 0).", steps, law=law,
                 paper_expr=paper_e, derived_expr=derived_e, remarks=remarks)


@memo
def laws_agree_claim() -> Claim:
    diff = M.law_corrected() - M.law_printed()
    steps = [prove_branches(_surface_coords(diff + _dbeta() * M.surface2()), (r,),
                            "corrected - printed = -(beta1 q1|s1|^(q1-1) + "
                            "beta2 q2|s1|^(q2-1)) s2"),
             prove_branches(diff.subs(v, M.reaching_law_rhs(r)), (r,),
                            "hence the two laws agree on s2 = 0")]
    return Claim("laws-agree", "(25)", "The printed and the corrected guidance coincide on s2 = 0",
                 "(the paper has one law)", "corrected (25') = printed (25) - (beta1 q1 |s1|^(q1-1)"
                 " + beta2 q2|s1|^(q2-1)) s2", steps,
                 paper_expr=(sp.Eq(A_CMD, _disp(M.law_printed()), evaluate=False),),
                 derived_expr=(sp.Eq(A_CMD, _disp(M.law_corrected()), evaluate=False),
                               sp.Eq(A_CMD, _disp(M.law_printed()) - _disp(_dbeta()) * S2,
                                     evaluate=False)),
                 statement="workbench")


def _t2_printed_witness() -> Step:
    """The Fig. 6 case under the printed law: s2 at T2 (26), by two integrations."""
    g = EXAMPLE_GAINS
    T2 = float(polyakov_bound(g["alpha1"] * 2 ** ((g["g1"] + 1) / 2),
                              g["alpha2"] * 2 ** ((g["g2"] + 1) / 2),
                              (g["g1"] + 1) / 2, (g["g2"] + 1) / 2))
    tr = trajectory("printed", g, -8000.0, 0.0, 2 * T2)
    s2_at = float(np.interp(T2, tr["t"], tr["s2"]))
    # independent route: the surface-coordinate integration (events at the zeros)
    s2_0 = float(M.surfaces_numeric()[1](-8000.0, 0.0, g["beta1"], g["beta2"], g["q1"],
                                         g["q2"]))
    tr2 = surface_trajectory("printed", g, -8000.0, s2_0, 2 * T2, n_out=8001)
    s2_re = float(np.interp(T2, tr2["t"], tr2["s2"]))
    tol = 1.0  # m/s: "reached 0" allows 1 m/s, far above both integrators' error
    return witness_step("s2 = 0 by T2 (26) from s1x(0) = -8000 m, v(0) = 0 (the paper's Fig. 6 "
                        "case; gains EXAMPLE_GAINS)",
                        {"gains": g, "r0": -8000.0, "v0": 0.0, "T2 (26)": T2, "s2(T2)": s2_at,
                         "tolerance": tol},
                        tol - abs(s2_at), "LSODA rtol = atol = 1e-10 on the per-axis closed loop "
                        "in (r, v) (lgw.theory.mars.reduced.trajectory); margin 1 m/s - |s2(T2)|",
                        tol - abs(s2_re), "LSODA rtol 1e-11 in surface coordinates with events "
                        "at the zeros (lgw.theory.mars.reduced.surface_trajectory)",
                        domain={"case": "Fig. 6, s1x(0) = -8000 m"})


@memo
def t2_claim(law: str) -> Claim:
    """Theorem 3 judged on the law: the proof route of (26) rests on (29) for that law (claim
    V2dot-<law>) and Lemma 2; a falsification search of the statement itself runs beside it
    (the paper's Fig. 6 case flown by two integrators for the printed law; the full-domain
    search of lgw.theory.mars.searches for the corrected law)."""
    paper = ("T2 <= 1/(alpha1 (1-g1) 2^((g1-1)/2)) + 1/(alpha2 (g2-1) 2^((g2-1)/2)), "
             "independent of the initial state")
    T26 = sp.Le(T2S, _bound_exprs()["T2 (26)"], evaluate=False)
    i1, _ = _route_identity(a1, a2, g1, g2)
    steps = [_lemma(v2dot_claim(law), f"(29) under the {law} law"),
             _lemma(SP.lemma2(), "Lemma 2: the settling bound (3)"), i1]
    if law == "corrected":
        return Claim("T2-corrected", "(26)", "Theorem 3: fixed-time convergence of the second "
                     "surface, corrected law", paper,
                     "Holds for the corrected law; least upper bound T2* = Gamma(m)Gamma(1-m)/"
                     "(alpha1 (g2-g1)) (alpha1/alpha2)^m, m = (1-g1)/(g2-g1) (claim "
                     "exact-bound).", steps, law=law, searches=(_report_search("T2-corrected"),),
                     paper_expr=(T26,),
                     derived_expr=(sp.Le(T2S, T2X, evaluate=False),
                                   sp.Eq(T2X, SP.exact_expr(a1, a2, g1, g2, 1), evaluate=False),
                                   sp.Le(T2X, _bound_exprs()["T2 (26)"], evaluate=False)),
                     statement="workbench", corrects="T2-printed")
    return Claim("T2-printed", "(26)", "Theorem 3: fixed-time convergence of the second surface, "
                 "printed law (25)", paper,
                 "Judged on the printed law: the proof needs (29) for it (claim V2dot-printed); "
                 "the paper's Fig. 6 case is flown to T2 as a falsification.", steps, law=law,
                 searches=(_t2_printed_witness(),), paper_expr=(T26,))


# --- How T1 and T2 combine: the landing time ---------------------------------------------

def _composition_step() -> Step:
    t_s2, t_s1, T1_, T2_, t_land = sp.symbols("t_s2 t_s1 T1 T2 t_land", real=True)
    return prove_z3(sp.Le(t_land, T1_ + T2_),
                    [sp.Le(t_land, t_s2 + t_s1), sp.Le(t_s2, T2_), sp.Le(t_s1, T1_),
                     sp.Ge(t_s2, 0), sp.Ge(t_s1, 0)],
                    "landing time <= T2 + T1 per axis: s2 is at 0 by t_s2 <= T2 and stays; "
                    "from then s1 needs t_s1 <= T1 (uniform in s1(t_s2))")


@memo
def landing_claim() -> Claim:
    """The paper's rule for the whole mission, landing <= max{T1, T2}, judged for the law
    under which (18) and (26) both hold (the corrected law; under the printed law (26) fails
    already, claim T2-printed): a refutation there refutes the rule itself.  No proof: the
    paper's argument is invalid (remark); the full-domain falsification search decides."""
    paper_step = identity_at(_surface_coords(v) - M.reaching_law_rhs(r), {r: 0, S2: 1},
                             "s1 obeys (16) from t = 0 (the paper's reason for max{T1, T2}): "
                             "s1' - (16) = 0 for every state")
    return Claim("landing-time", "Part 1 (whole mission), Remark 1 tuning rule, (32)",
                 "How the two surfaces' times combine into the landing time",
                 "'for the whole mission, the maximum time is 74.5780 s' = max{T1, T2}; tune so "
                 "that max_i T1i <= tf and max_i T2i <= tf",
                 "The paper's argument for max{T1, T2} is invalid (s1 follows (16) only once "
                 "s2 = 0; remark).  The full-domain search over every gain and state in range "
                 "(corrected law, under which (18) and (26) hold) decides the rule.  The sound "
                 "bound is claim landing-time-corrected.", (), law="corrected",
                 searches=(_report_search("landing-time"),), remarks=(paper_step,),
                 paper_expr=(sp.Le(T_LAND, sp.Max(T1S, T2S), evaluate=False),))


@memo
def landing_corrected_claim() -> Claim:
    # The sound bound: s2 reaches 0 by T2 and stays (V2' <= 0), then s1 follows (16).
    s_res = _identity(
        _surface_coords(M.closed_loop("corrected").s2dot.subs(ap, 0)).subs(S2, 0),
        "s2 = 0 is invariant: s2' = 0 on s2 = 0 (corrected law)")
    steps = [_lemma(t2_claim("corrected"), "s2 reaches 0 within (26)"), s_res,
             _lemma(surface_claim(), "on s2 = 0, s1 obeys (16)"),
             _lemma(t1_claim(), "s1 reaches 0 within (18) under (16)"), _composition_step()]
    return Claim("landing-time-corrected", "Part 1 (whole mission), Remark 1 tuning rule",
                 "The landing-time bound: T2 + T1",
                 "'for the whole mission, the maximum time is 74.5780 s' = max{T1, T2}",
                 "The sound bound is T2 + T1 per axis (exact: T2* + T1*, lgw.theory.mars.bounds"
                 ".landing_time_bound).", steps, law="corrected",
                 paper_expr=(sp.Le(T_LAND, sp.Max(T1S, T2S), evaluate=False),),
                 derived_expr=(sp.Le(T_LAND, T1S + T2S, evaluate=False),
                               sp.Le(T_LAND, T1X + T2X, evaluate=False)),
                 statement="workbench", corrects="landing-time")


# --- Remark 1: minimum tf -------------------------------------------------------------------

@memo
def remark1_claim() -> Claim:
    a_max = THRUST_MAX_AXIS / M0
    printed = tf_min_printed(R0, V0, a_max, G_MARS)
    A, r0s, v0s, gs = sp.symbols("a_max r_0 v_0 g", real=True)
    a_max_q = sp.nsimplify(THRUST_MAX_AXIS) / sp.nsimplify(M0)
    table_y = {A: a_max_q, r0s: sp.nsimplify(R0[1]), v0s: sp.nsimplify(V0[1])}
    table_x = {A: a_max_q, v0s: sp.nsimplify(V0[0]), gs: sp.nsimplify(G_MARS[0])}
    steps = [
        refute_nonneg_at(v0s**2 - 2 * A * r0s, table_y,
                         "tf1 = (-v0 + sqrt(v0^2 - 2 a_max r0))/a_max is defined (v0^2 - 2 a_max "
                         f"r0 >= 0), Table I y axis, a_max = {THRUST_MAX_AXIS / 1e3:g} kN / "
                         f"{M0:g} kg"),
        refute_nonneg_at(-v0s / (A - gs), table_x,
                         "tf2 = -v0/(a_max - g) is a time (>= 0), Table I x axis"),
    ]
    return Claim("remark1", "Remark 1", "Least landing time under a thrust limit",
                 "tf >= max_i {tf1i, tf2i}, tf1i = (-v0i + sqrt(v0i^2 - 2 a_max r0i))/a_max, "
                 "tf2i = -v0i/(a_max - g_i)",
                 "Printed formulas hold only for r0 < 0 (tf1) and fail for v0 > 0 or z (tf2); "
                 "the corrected bound is claim remark1-corrected.", steps,
                 numbers={"printed_per_axis": printed.tolist(), "a_max": a_max})


@memo
def remark1_corrected_claim() -> Claim:
    a_max = THRUST_MAX_AXIS / M0
    derived = tf_min(R0, V0, a_max, G_MARS)
    A, gs = sp.symbols("a_max g", real=True)
    u, acc, d, tt, S = sp.symbols("u acc d t S", real=True)
    vv, dec = sp.symbols("v dec", real=True)
    gz = float(np.max(np.abs(G_MARS)))
    taylor = Cited("Taylor's theorem with integral remainder (any analysis text, e.g. Rudin, "
                   "Principles, Thm 5.15)", "|a_i| <= a_max gives distance-to-go >= d - u t - "
                   "acc t^2/2 and speed >= |v0| - dec t, acc = a_max + g.(toward target), "
                   "dec = a_max - sgn(v0) g_i",
                   (prove_arb(A - sp.Abs(gs), {A: (a_max,) * 2, gs: (gz,) * 2},
                              f"acc, dec > 0: a_max = {THRUST_MAX_AXIS / 1e3:g} kN / {M0:g} kg "
                              f"exceeds max_i |g_i| = {gz:g} m/s^2", strict=True,
                              recheck=lambda pt: pt["a_max"] - abs(pt["g"])),))
    steps = [
        Step("corrected bounds rest on integrating the acceleration bound twice", taylor),
        prove_z3(sp.Gt(d - u * tt - acc * tt**2 / 2, 0),
                 [sp.Gt(acc, 0), sp.Gt(d, 0), sp.Ge(tt, 0), sp.Ge(S, 0),
                  sp.Eq(S**2, u**2 + 2 * acc * d), sp.Lt(acc * tt, -u + S)],
                 "no |a_i| <= a_max reaches r_i = 0 before (-u + sqrt(u^2 + 2 acc |r0|))/acc: "
                 "the distance to go is still > 0 (S = the square root)"),
        prove_z3(sp.Gt(vv - dec * tt, 0), [sp.Gt(dec, 0), sp.Gt(vv, 0), sp.Ge(tt, 0),
                                           sp.Lt(dec * tt, vv)],
                 "nor stops before |v0|/(a_max - sgn(v0) g_i): the speed is still > 0"),
    ]
    return Claim("remark1-corrected", "Remark 1", "Least landing time under a thrust limit, "
                 "corrected", "tf >= max_i {tf1i, tf2i} (Remark 1 as printed)",
                 "Per-axis lower bound lgw.theory.mars.bounds.tf_min: (-u + sqrt(u^2 + 2 acc "
                 "|r0|))/acc and |v0|/(a_max - sgn(v0) g_i).  Use a_max = F_max/m_min for a "
                 "bound valid at every mass.", steps,
                 numbers={"derived_per_axis": derived.tolist(), "a_max": a_max},
                 statement="workbench", corrects="remark1")


def _essential_condition(exps: list[sp.Expr], hyps: list[sp.Basic]) -> sp.Basic:
    """And(e >= 0) without the exponents the hypotheses already make >= 0 (z3), reduced to
    an interval when one symbol is left (for the claim's text)."""
    from lgw.theory.provers import prove_z3

    keep = [e for e in exps
            if prove_z3(sp.GreaterThan(e, 0, evaluate=False), hyps, "implied").status
            != "proved"]
    if not keep:
        return sp.true
    syms = set().union(*(e.free_symbols for e in keep))
    if len(syms) == 1:
        (q,) = syms
        return sp.reduce_inequalities([sp.Ge(e, 0) for e in keep]
                                      + [h for h in hyps if h.free_symbols == {q}], q)
    return sp.And(*(sp.Ge(e, 0) for e in keep))


def command_exponents(law_expr: sp.Expr) -> list[sp.Expr]:
    """The exponent of every power of an absolute value and of every signed power sig(., e)
    in ``law_expr``, read from the expression: the command is bounded on bounded sets of
    states iff none is negative (a nonnegative power of a bounded quantity is bounded; a
    negative one of |s1| grows without bound as s1 -> 0)."""
    out = {p.exp for p in law_expr.atoms(sp.Pow) if isinstance(p.base, sp.Abs)}
    out |= {f.args[1] for f in law_expr.atoms(sig)}
    return sorted(out, key=sp.default_sort_key)


def _exponent_slope(law: str, gains: dict[str, float]) -> float:
    """d log|a| / d log s1 as s1 -> 0 (at s1 = 1e-8 and 1e-10, v = 1, g = a_m = 0) from the
    lambdified law the simulator runs: an independent, numeric reading of the command's
    leading power of |s1| (negative: the command grows without bound)."""
    f = M.law_numeric(law)
    args = [gains[k] for k in ("beta1", "beta2", "alpha1", "alpha2", "q1", "q2", "g1", "g2")]
    with np.errstate(all="ignore"):
        a1_, a2_ = (abs(float(f(x, 1.0, 0.0, 0.0, *args))) for x in (1e-8, 1e-10))
    if not (math.isfinite(a1_) and math.isfinite(a2_)) or a1_ == 0 or a2_ == 0:
        return -math.inf
    return math.log(a1_ / a2_) / math.log(1e-8 / 1e-10)


def _bounded_step(law: str, exps: list[sp.Expr], point: dict, statement: str) -> Step:
    """Every exponent >= 0 at the gain point (Arb on a point box); a negative one is a
    witness, re-checked by the numeric slope of the law's command near s1 = 0."""
    gains = {s_.name: float(val) for s_, val in point.items()}
    free = set().union(*(e.free_symbols for e in exps)) if exps else set()
    box = {s_: (float(val), float(val)) for s_, val in point.items() if s_ in free}
    full = {**{k: 1.0 for k in ("beta1", "beta2", "alpha1", "alpha2")}, **gains}
    return prove_arb(sp.Min(*exps) if len(exps) > 1 else exps[0], box, statement,
                     recheck=lambda pt: _exponent_slope(law, full),
                     recheck_method="the slope d log|a| / d log s1 of the lambdified command "
                                    "(the simulator's) between s1 = 1e-10 and 1e-8, v = 1")


# --- Bounded command ---------------------------------------------------------------------

@memo
def bounded_command_claim(law: str) -> Claim:
    if law == "corrected":
        acc = M.law(law).subs({M.grav: 0, M.am: 0})
        pt = {**PT, q1: sp.Rational(7, 10), v: sp.Integer(1)}
        x = sp.Symbol("x", positive=True)
        lim = sp.limit(acc.subs(pt).subs(r, x), x, 0, "+")
        a_lim = THRUST_MAX_AXIS / M0
        s_small = sp.Rational(1, 10**9)
        val = float(sp.N(acc.subs(pt).subs(r, s_small), 30))
        val2 = float(M.law_numeric("corrected")(1e-9, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.7,
                                                2.0, 0.5, 2.0))
        steps = [witness_step(
            "|a| stays below the thrust limit a_max = 50 kN / 1905 kg near s1 = 0",
            {"s1": "1e-9", "v": 1, "beta1": 1, "beta2": 1, "alpha1": 1, "alpha2": 1,
             "q1": "7/10", "q2": 2, "g1": "1/2", "g2": 2, "|a|": abs(val),
             "SymPy limit s1 -> 0+ of a": sp.sstr(lim)},
            a_lim - abs(val), "SymPy at 30 digits at s1 = 1e-9 (margin a_max - |a|); "
            f"SymPy limit s1 -> 0+ is {sp.sstr(lim)}", a_lim - abs(val2),
            "the lambdified law the simulator runs (lgw.theory.mars.mss.law_numeric)")]
        return Claim("bounded-command-corrected", "(25'), Part 1", "Bounded command, corrected "
                     "law", "no overlarge thrust command input if proper parameters are set",
                     "The corrected law contains -beta1 q1 |s1|^(q1-1) v: unbounded when s1 "
                     "crosses 0 while v != 0, whatever the gains (q1 < 1).  Trajectories that "
                     "reach s1 = 0 on s2 = 0 (v -> 0 with s1) keep it bounded for q1 >= 1/2.",
                     steps, law=law, statement="workbench")
    import z3
    from lgw.theory.provers import _to_z3, z3_check

    exps = command_exponents(M.law(law))
    qs = sorted(set().union(*(e.free_symbols for e in exps)), key=lambda s_: s_.name)
    cond = sp.And(*(sp.GreaterThan(e, 0, evaluate=False) for e in exps))
    hyps = [h for h in M.hypotheses() if h.free_symbols <= set(qs)]
    env: dict = {}
    solver = z3.Solver()
    solver.add(*(_to_z3(h, env) for h in hyps), _to_z3(cond, env))
    ans = z3_check(solver)
    exps_txt = ", ".join(sp.sstr(e) for e in exps)
    if ans == "sat":
        mdl = solver.model()
        point = {s_: sp.Rational(str(mdl.eval(env[s_], model_completion=True).as_fraction()))
                 for s_ in qs}
        step = _bounded_step(law, exps, point, "the gains z3 found within the hypotheses "
                             f"({', '.join(f'{k} = {val}' for k, val in point.items())}) make "
                             f"every exponent in the command >= 0 ({exps_txt})")
    else:  # no admissible gain set: refute with a sampled admissible one
        rng = random.Random(0)
        from lgw.theory.provers import _rational_point
        point = _rational_point(qs, rng, M.SAMPLE_RANGES)
        step = _bounded_step(law, exps, point, "some gain set within the hypotheses makes every "
                             f"exponent in the command >= 0 ({exps_txt}); z3: {ans} (none "
                             "exists); at the sampled admissible gains shown, one is negative")
    reduced = _essential_condition(exps, hyps)
    return Claim("bounded-command-printed", "(25), Part 1", "Bounded command, printed law",
                 "no overlarge thrust command input if proper parameters are set",
                 "Read from the law: the powers of |s1| and of the surfaces in the command "
                 f"have exponents {exps_txt}; the command is bounded on bounded sets of states "
                 f"iff all are >= 0, i.e. {sp.sstr(reduced)} within the hypotheses (judged per "
                 "gain set in bounded-command-printed@gains).", [step], law=law,
                 numbers={"exponents": [sp.sstr(e) for e in exps], "z3": ans,
                          "bounded iff": sp.sstr(reduced)})


# --- Theorem 4: disturbance, (36)-(45), (32) ------------------------------------------------

def _disturbance_product_step() -> Step:
    s_, a_, A_ = sp.symbols("s a_p a_max", real=True)
    return prove_z3(sp.Le(s_ * a_, A_ * sp.Abs(s_)), [sp.Le(a_, A_), sp.Ge(a_, -A_)],
                    "s2 a_p <= a_max |s2| whenever |a_p,i| <= a_max")


@memo
def v2dot_disturbed_claim(law: str) -> Claim:
    """(36) judged on the law: V2' - (29) - s2 a_p is computed from the law's closed loop
    under (30) and must vanish on every sign branch; then s2 a_p <= a_max |s2|."""
    resid = _v2dot_residual(law, with_ap=True)
    paper = ("(36): V2' = s2[-a_p - alpha1|s2|^g1 sgn - alpha2|s2|^g2 sgn] <= -alpha1|s2|^(g1+1)"
             " - alpha2|s2|^(g2+1) + a_max|s2|")
    steps = [prove_branches(resid, (r, S2), "V2' = -alpha1|s2|^(g1+1) - alpha2|s2|^(g2+1) "
                            f"+ s2 a_p under (30) and the {law} law (V2' from the law's closed "
                            "loop)"),
             _disturbance_product_step()]
    extra = _branch_display(resid)
    if law == "corrected":
        return Claim("V2dot-disturbed-corrected", "(33)-(36)", "V2' under disturbance, corrected "
                     "law", paper, "Holds per axis (the sign of a_p in (36) is a harmless slip: "
                     "V2' contains +s2 a_p).", steps, law=law, statement="workbench",
                     corrects="V2dot-disturbed-printed")
    return Claim("V2dot-disturbed-printed", "(33)-(36)", "V2' under disturbance, printed law",
                 paper, "V2' computed from the printed law (25) under (30)" + (
                     f": it exceeds (36)'s form by {sp.sstr(extra)} (s1 > 0)."
                     if extra is not None else "."), steps, law=law)


def _neighbourhood_steps(gain1, gain2, e1_, e2_, eta, theta, name: str) -> tuple[Step, ...]:
    """For V' <= -gain1|s|^(e1+1) - gain2|s|^(e2+1) + eta|s|: outside
    |s| <= min{(eta/((1-theta) gain1))^(1/e1), (eta/((1-theta) gain2))^(1/e2)},
    V' <= -theta (gain1|s|^(e1+1) + gain2|s|^(e2+1)) < 0; reached and never left."""
    x = sp.Symbol("x", positive=True)  # |s|
    bound = -gain1 * x ** (e1_ + 1) - gain2 * x ** (e2_ + 1) + eta * x
    target = -theta * (gain1 * x ** (e1_ + 1) + gain2 * x ** (e2_ + 1))
    gap = sp.expand(target - bound)
    Aq, Bq, tq, eq = sp.symbols("A B theta eta", real=True)
    om = sp.Symbol("omega", positive=True)  # 1 - theta > 0 for 0 < theta < 1
    thr1 = (eta / (om * gain1)) ** (1 / e1_)
    decrease = prove_nonneg(theta * (gain1 * x ** (e1_ + 1) + gain2 * x ** (e2_ + 1)),
                            f"theta > 0: on and outside the boundary the derivative of {name} "
                            "is < 0", strict=True)
    steps = (
        _identity(sp.simplify(gap - x * ((1 - theta) * (gain1 * x**e1_ + gain2 * x**e2_)
                                               - eta)),
                       f"-theta(...) - [bound on V'] = |{name}| ((1-theta)(A + B) - eta), "
                       f"A = {sp.sstr(gain1)}|{name}|^{sp.sstr(e1_)}, "
                       f"B = {sp.sstr(gain2)}|{name}|^{sp.sstr(e2_)}"),
        _identity(sp.simplify(gain1 * thr1**e1_ - eta / om),
                       "at the threshold (eta/((1-theta) gain1))^(1/e1), A = eta/(1-theta) "
                       "(omega = 1 - theta > 0; likewise for B)"),
        SP._increasing_power(e1_, "x -> x^e is increasing for e > 0: beyond its threshold, "
                             "A >= eta/(1-theta) (likewise B); beyond the min of the two "
                             "thresholds, one of them holds"),
        prove_z3(sp.Ge((1 - tq) * (Aq + Bq) - eq, 0),
                 [sp.Ge(Aq, 0), sp.Ge(Bq, 0), sp.Gt(tq, 0), sp.Lt(tq, 1),
                  sp.Or(sp.Ge(Aq * (1 - tq), eq), sp.Ge(Bq * (1 - tq), eq))],
                 "if A >= eta/(1-theta) or B >= eta/(1-theta), then (1-theta)(A+B) - eta >= 0: "
                 f"V' <= -theta (...) outside the neighbourhood of {name}"),
        decrease,
    )
    inv = Step(f"|{name}| <= the neighbourhood bound is reached and positively invariant",
               Cited(SP.INVARIANCE + "; " + SP.COMPARISON, "sublevel set with V' < 0 on its "
                     "boundary is invariant; outside it the comparison lemma bounds the time",
                     steps))
    return (*steps, inv)


def _t4(law: str, base: str) -> tuple[str, dict]:
    """Claim id and the statement fields of a Theorem 4 claim judged on ``law``: the paper's
    statement is about the printed law (25); the corrected law's is the workbench's."""
    if law == "printed":
        return base, {"law": "printed"}
    return f"{base}-corrected", {"law": "corrected", "statement": "workbench", "corrects": base}


@memo
def s2_neighborhood_claim(law: str = "corrected") -> Claim:
    cid, kw = _t4(law, "s2-neighborhood")
    steps = [_lemma(v2dot_disturbed_claim(law), f"(36) under the {law} law"),
             *_neighbourhood_steps(a1, a2, g1, g2, amax, th1, "s2")]
    remark = identity_at(sp.diff(amax * sp.Abs(S2), S2), {amax: 1, S2: 1},
                         "(37)-(38) apply Theorem 1 with eta = a_max|s2x|, which Theorem 1 "
                         "requires constant: d eta/d s2 = 0")
    return Claim(cid, "(37)-(39)", f"Neighbourhood of s2 under bounded disturbance, {law} law",
                 "|s2i| <= min{(a_max/((1-theta1)alpha1i))^(1/g1), (a_max/((1-theta1)alpha2i))"
                 "^(1/g2)}", f"Judged on the {law} law: from (36) for it by a direct proof (the "
                 "paper's use of Theorem 1 with a state-dependent eta is not valid as written, "
                 "the bound is).  Reached and never left.", steps, remarks=(remark,),
                 paper_expr=(sp.Le(sp.Abs(S2), _bound_exprs()["s2 nbhd (39)"], evaluate=False),),
                 derived_expr=(sp.Le(sp.Abs(S2), _bound_exprs()["s2 nbhd (39)"],
                                     evaluate=False),), **kw)


def _practical_time_identity(gain1, gain2, e1_, e2_, theta, eq: str) -> Step:
    return _identity(
        sp.simplify(SP.polyakov_expr(theta * gain1 * 2 ** ((e1_ + 1) / 2),
                                     theta * gain2 * 2 ** ((e2_ + 1) / 2),
                                     (e1_ + 1) / 2, (e2_ + 1) / 2, 1)
                    - (1 / (gain1 * theta * (1 - e1_) * 2 ** ((e1_ - 1) / 2))
                       + 1 / (gain2 * theta * (e2_ - 1) * 2 ** ((e2_ - 1) / 2)))),
        f"{eq} = Lemma 2 (3) with the gains -> theta x gains (V = s^2/2 route)")


@memo
def t2_practical_claim(law: str = "corrected") -> Claim:
    cid, kw = _t4(law, "T2-practical")
    steps = [_lemma(s2_neighborhood_claim(law), "s2 enters (39) and stays"),
             _practical_time_identity(a1, a2, g1, g2, th1, "(40)")]
    if law == "corrected":
        steps.append(_lemma(SP.exact_time_claim(), "the exact time T(V0)"))
    return Claim(cid, "(40)", f"Time for s2 to enter its neighbourhood, {law} law",
                 "T2i <= 1/(alpha1i theta1 (1-g1) 2^((g1-1)/2)) + 1/(alpha2i theta1 (g2-1) "
                 "2^((g2-1)/2))", f"Judged on the {law} law.  Sharper: (T2* - T2(M))/theta1, the "
                 "exact comparison time from infinity to the neighbourhood boundary M.", steps,
                 paper_expr=(sp.Le(T2S, _bound_exprs()["T2 practical (40)"], evaluate=False),),
                 derived_expr=(sp.Le(T2S, _bound_exprs()["T2 practical (40)"],
                                     evaluate=False),), **kw)


def _nbhd31() -> sp.Expr:
    """(31) with M_i, the s2 neighbourhood (39), kept as a symbol."""
    return sp.Min((MI / ((1 - th2) * b1)) ** (1 / q1), (MI / ((1 - th2) * b2)) ** (1 / q2))


@memo
def s1_neighborhood_claim(law: str = "corrected") -> Claim:
    cid, kw = _t4(law, "s1-neighborhood")
    resid = sp.diff(M.surface1(), r) * v - (M.reaching_law_rhs(r) + S2)
    Mi = sp.Symbol("M_i", positive=True)
    s_, z_ = sp.symbols("s_1 s_2", real=True)
    steps = [prove_branches(_surface_coords(resid), (r,), "(41): s1' = -beta1 sig(s1,q1) - "
                            "beta2 sig(s1,q2) + s2"),
             _lemma(s2_neighborhood_claim(law), "s2 enters (39) and never leaves"),
             prove_z3(sp.Le(s_ * z_, Mi * sp.Abs(s_)), [sp.Le(z_, Mi), sp.Ge(z_, -Mi)],
                      "once |s2| <= M_i for all later t (s2-neighborhood: never left), "
                      "s1 s2 <= M_i |s1|, so V1i' <= -beta1|s1|^(q1+1) - beta2|s1|^(q2+1) + "
                      "M_i|s1| (42)"),
             *_neighbourhood_steps(b1, b2, q1, q2, Mi, th2, "s1")]
    return Claim(cid, "(31), (41)-(44)", f"Landing-error neighbourhood, {law} law",
                 "|r_i| <= min{(M_i/((1-theta2)beta1i))^(1/q1), (M_i/((1-theta2)beta2i))^(1/q2)}",
                 f"Judged on the {law} law: holds after s2 has entered (39).", steps,
                 paper_expr=(sp.Le(sp.Abs(S1), _nbhd31(), evaluate=False),),
                 derived_expr=(sp.Le(sp.Abs(S1), _nbhd31(), evaluate=False),
                               sp.Eq(MI, _bound_exprs()["s2 nbhd (39)"], evaluate=False)), **kw)


@memo
def t1_practical_claim(law: str = "corrected") -> Claim:
    cid, kw = _t4(law, "T1-practical")
    steps = [_lemma(s1_neighborhood_claim(law), "s1 enters (31) and stays"),
             _practical_time_identity(b1, b2, q1, q2, th2, "(45)")]
    return Claim(cid, "(45)", f"Time for s1 to enter its neighbourhood, {law} law",
                 "T1i <= 1/(beta1i theta2 (1-q1) 2^((q1-1)/2)) + 1/(beta2i theta2 (q2-1) "
                 "2^((q2-1)/2))",
                 f"Judged on the {law} law: counted from the time s2 enters (39), not from "
                 "t = 0.", steps,
                 paper_expr=(sp.Le(T1S, _bound_exprs()["T1 practical (45)"], evaluate=False),),
                 derived_expr=(sp.Le(T1S, _bound_exprs()["T1 practical (45)"],
                                     evaluate=False),), **kw)


def _t3_paper_argument() -> Step:
    return identity_at(_surface_coords(v) - M.reaching_law_rhs(r), {r: 0, S2: 1},
                       "the paper's argument for max: s1 obeys the reaching law from t = 0, "
                       "i.e. s1' - (16) = 0 for every state (it is s2)")


@memo
def t3_claim() -> Claim:
    """(32) as printed: no proof (the paper's argument is invalid, remark); the full-domain
    search of the disturbed closed loop decides (judged for the corrected law, under which
    (39)-(45) hold, as for landing-time)."""
    return Claim("T3", "(32)", "Time to land in the neighbourhood under disturbance",
                 "T3i <= max{(40), (45)}",
                 "The paper's argument for max is invalid (remark).  The full-domain search "
                 "under the worst disturbance a_p = a_max sgn(s2) decides (starting from the "
                 "worst points of the larger run of docs/verify.md).  The sound bound is claim "
                 "T3-corrected.", (), law="corrected",
                 searches=(_report_search("T3", starts=True),), remarks=(_t3_paper_argument(),),
                 paper_expr=(sp.Le(T3S, sp.Max(sp.Symbol("T_(40)"), sp.Symbol("T_(45)")),
                                   evaluate=False),))


@memo
def t3_corrected_claim() -> Claim:
    t_s2, t_s1, T1_, T2_, t_land = sp.symbols("t_s2 t_s1 T45 T40 t_land", real=True)
    comp = prove_z3(sp.Le(t_land, T1_ + T2_),
                    [sp.Le(t_land, t_s2 + t_s1), sp.Le(t_s2, T2_), sp.Le(t_s1, T1_),
                     sp.Ge(t_s2, 0), sp.Ge(t_s1, 0)],
                    "time from t = 0 to (31) <= (40) + (45): s2 enters (39) by (40), then s1 "
                    "enters (31) within (45)")
    steps = [_lemma(t2_practical_claim("corrected"), "s2 enters (39) within (40)"),
             _lemma(t1_practical_claim("corrected"), "then s1 enters (31) within (45)"), comp]
    return Claim("T3-corrected", "(32)", "Time to land in the neighbourhood under disturbance, "
                 "corrected", "T3i <= max{(40), (45)}", "The sound bound is (40) + (45).", steps,
                 law="corrected", statement="workbench", corrects="T3",
                 paper_expr=(sp.Le(T3S, sp.Max(sp.Symbol("T_(40)"), sp.Symbol("T_(45)")),
                                   evaluate=False),),
                 derived_expr=(sp.Le(T3S, sp.Symbol("T_(40)") + sp.Symbol("T_(45)"),
                                     evaluate=False),))


# printed numbers of seed 000 (Part 1 and Part 2), and their rounding (4 decimals)
PRINTED = {"T1 (18)": 74.5780, "T2 (26)": 30.8217, "s2 nbhd (39)": 26.5257,
           "T2 practical (40)": 131.5173, "s1 nbhd (31)": 23.8472,
           "T1 practical (45)": 85.8610}
ROUND = 5e-5


@memo
def paper_numbers_claim() -> Claim:
    th1_, th2_ = sp.Rational(1, 5), sp.Rational(1, 10)
    P = {k: sp.nsimplify(v) for k, v in PRINTED.items()}
    steps = [_practical_time_identity(a1, a2, g1, g2, th1, "(40) = (26)/theta1"),
             _practical_time_identity(b1, b2, q1, q2, th2, "(45) = (18)/theta2"),
             identity_at(P["T2 practical (40)"] - P["T2 (26)"] / th1_, {},
                         "printed (40) = 131.5173 s equals printed (26)/theta1 = 30.8217/0.2 s",
                         tolerance=ROUND * (1 + 1 / float(th1_))),
             identity_at(P["T1 practical (45)"] - P["T1 (18)"] / th2_, {},
                         "printed (45) = 85.8610 s equals printed (18)/theta2 = 74.5780/0.1 s",
                         tolerance=ROUND * (1 + 1 / float(th2_)))]
    return Claim("paper-numbers", "Part 1-2 numbers", "Consistency of the paper's reported bounds",
                 "T1 <= 74.5780 s, T2 <= 30.8217 s (Part 1); (40) = 131.5173 s, (45) = 85.8610 s "
                 "with theta1 = 0.2, theta2 = 0.1 (Part 2)",
                 "With one gain set, (40) and (45) are (26)/theta1 = 154.1085 s and (18)/theta2 "
                 "= 745.78 s.  The printed numbers need different, unstated gains in Part 2; "
                 "they are not reference values.", steps,
                 numbers={"(26)/theta1": PRINTED["T2 (26)"] / 0.2,
                          "(18)/theta2": PRINTED["T1 (18)"] / 0.1})


# --- The model: plant (10)-(11), drag (12), mass (13)-(14), Hypothesis 1 and (47) -----------

@memo
def plant_claim() -> Claim:
    acc = sp.Symbol("a", real=True)
    steps = [_identity(M.time_derivative(v, acc, ap) - (acc + M.grav + M.am + ap),
                            "along (10)-(11), (30): s1'' = v' = a + g + a_m + a_p, as (23), (33)"),
             _identity(M.time_derivative(M.surface1(), acc) - v,
                            "s1' = r' = v (10), (15) with r_d = 0")]
    return Claim("plant", "(10)-(11), (23), (30), (33)", "The lander model as the laws use it",
                 "r' = v, v' = a + g + a_m (+ a_p); s1'' = v' = a + g + a_m (+ a_p)",
                 "Consistent: the symbolic time derivative used by every claim is (10)-(11) "
                 "with (30).", steps)


@memo
def drag_claim() -> Claim:
    vi, rz, Ai, m = sp.symbols("v_i r_z A_i m", real=True)
    a_m = -sp.Rational(699, 1000) * vi**2 * sp.exp(-sp.Rational(9, 10000) * rz) / (Ai * m)
    pt = {vi: -1, rz: 1000, Ai: 6, m: 1905}
    steps = [refute_nonneg_at(-a_m * vi, pt, "(12) is a drag: a_m,i v_i <= 0 (opposes the "
                              "motion) for every v_i (here v_i = -1 m/s, Table I area and mass)"),
             refute_nonneg_at(sp.diff(-a_m, Ai), {vi: 1, rz: 1000, Ai: 6, m: 1905},
                              "|a_m,i| grows with the cross-section A_i, as a drag does")]
    return Claim("drag-12", "(12)", "The Martian drag model as printed",
                 "a_m,i = -0.699 v_i^2 e^(-0.0009 r_z) / (A_i m)",
                 "Not a drag as printed: v_i^2 does not change sign with v_i (it pushes along "
                 "-i even when the lander moves that way) and it falls with the area.  The "
                 "simulator's default is the physical -(1/2) rho C_D A_i |v_i| v_i / m "
                 "(lgw.sim.mars.parameters); the laws cancel a_m whatever its model (plant).",
                 steps, scope="all-gains",
                 paper_expr=(sp.Eq(sp.Symbol("a_m,i"), a_m, evaluate=False),),
                 derived_expr=(sp.Eq(sp.Symbol("a_m,i"), -sp.Symbol("rho") * sp.Symbol("C_D")
                                     * Ai * sp.Abs(vi) * vi / (2 * m), evaluate=False),))


@memo
def mass_claim() -> Claim:
    Fx, Fy, Fz = sp.symbols("F_x F_y F_z", real=True)
    c, m = sp.symbols("c m", positive=True)
    norm = sp.sqrt(Fx**2 + Fy**2 + Fz**2)
    steps = [prove_nonneg(norm / c, "(13): m' = -|F|/c <= 0 (the mass never grows), c = Isp g_e "
                          "> 0"),
             _identity((sp.Matrix([Fx, Fy, Fz]) / m - sp.Matrix([Fx / m, Fy / m, Fz / m]))
                            .norm(), "(14): a = F/m per axis, so F_i = m a_i: the per-axis "
                            "thrust limit is |a_i| <= F_max/m")]
    return Claim("mass-13-14", "(13)-(14)", "Mass flow and thrust",
                 "m' = -|F|/c, c = Isp g_e; a = F/m",
                 "Consistent; the paper omits Isp (the workbench uses 225 s, Acikmese & Ploen "
                 "2007, lgw.theory.mars.parameters).  Because m <= m0, |F_i| <= m0 |a_i|: a "
                 "command within F_max/m0 is within the limit at every mass.", steps)


@memo
def hypothesis1_claim() -> Claim:
    t_ = sp.Symbol("t", real=True)
    amp = sp.Integer(20)
    norm47 = sp.sqrt(3) * amp * sp.Abs(sp.sin(t_))
    steps = [refute_nonneg_at(amp - norm47, {t_: sp.pi / 2},
                              "(47) satisfies Hypothesis 1's norm bound ||a_p|| <= a_pMAX = 20")]
    return Claim("hypothesis1-47", "Hypothesis 1, (47)", "The test disturbance against the "
                 "hypothesis it is meant to satisfy",
                 "||a_p|| <= a_pMAX (Hypothesis 1); a_p,i = 20 sin t, i = x, y, z (47); the "
                 "theorems are applied with a_pMAX = 20",
                 "(47) violates the norm bound with a_pMAX = 20 (||a_p|| = 20 sqrt 3 at "
                 "t = pi/2); the per-axis reading is claim hypothesis1-47-per-axis.",
                 steps, scope="scenario")


@memo
def hypothesis1_per_axis_claim() -> Claim:
    t_ = sp.Symbol("t", real=True)
    amp = sp.Integer(20)
    steps = [_identity(amp**2 - (amp * sp.sin(t_)) ** 2 - amp**2 * sp.cos(t_) ** 2,
                            "20^2 - (20 sin t)^2 = 20^2 cos^2 t"),
             prove_nonneg(amp**2 * sp.cos(t_) ** 2, "20^2 cos^2 t >= 0, so (47) a_p,i = 20 sin t "
                          "satisfies the per-axis bound |a_p,i| <= 20")]
    return Claim("hypothesis1-47-per-axis", "Hypothesis 1, (47)", "The test disturbance "
                 "against the per-axis hypothesis the derivation uses",
                 "||a_p|| <= a_pMAX (Hypothesis 1) with (47) and a_pMAX = 20",
                 "The per-axis derivation (37)-(44) only needs |a_p,i| <= a_pMAX, which (47) "
                 "satisfies.  The workbench reads a_max as the per-axis bound.", steps,
                 scope="scenario", statement="workbench", corrects="hypothesis1-47")


@memo
def remark2_claim() -> Claim:
    uu = sp.Symbol("u", positive=True)  # 1 - q1 (or 1 - g1), in (0, 1)
    ww = sp.Symbol("w", positive=True)  # q2 - 1 (or g2 - 1)
    f1 = 1 / (uu * 2 ** (-uu / 2))  # (18)'s first term times beta1: 1/((1-q1) 2^((q1-1)/2))
    f2 = 1 / (ww * 2 ** (ww / 2))
    steps = [_identity(sp.diff(f1, uu) + 2 ** (uu / 2) * (1 - uu * sp.log(2) / 2) / uu**2,
                            "d/du [2^(u/2)/u] = -2^(u/2)(1 - u ln2/2)/u^2, u = 1 - q1"),
             prove_arb(1 - uu * sp.log(2) / 2, {uu: (0.0, 1.0)},
                       "1 - u ln2/2 > 0 on u in [0, 1]: the q1 term of (18) falls as 1 - q1 "
                       "grows", strict=True),
             prove_nonneg(-sp.diff(f2, ww), "the q2 term of (18) falls as q2 - 1 grows",
                          strict=True)]
    return Claim("remark2", "Remark 2, (18), (26)", "Effect of the exponents on the time bounds",
                 "the convergence time is reduced if 1 - q1, 1 - p1, q2 - 1, p2 - 1 are large "
                 "(p1, p2 are g1, g2: a slip of the text); the peak thrust then grows",
                 "The bounds (18), (26) fall as 1 - q1 (1 - g1) and q2 - 1 (g2 - 1) grow, "
                 "term by term (proved).  The thrust statement needs simulation (not checked "
                 "here; see thrust-table1@gains).", steps)


@memo
def theta_effect_claim() -> Claim:
    """After (45): 'a large value of the disturbance upper bound a_pMAX leads to a wide
    neighborhood; large values of theta1 and theta2 shrink the neighborhood size, but increase
    the convergence time'.  Judged on (39) and (40) (the s1 ones behave alike)."""
    M39 = (amax / ((1 - th1) * a1)) ** (1 / g1)
    T40 = 1 / (a1 * th1 * (1 - g1) * 2 ** ((g1 - 1) / 2))  # the g1 term of (40)
    pt = {amax: 20, a1: 1, g1: sp.Rational(1, 2), th1: sp.Rational(1, 5)}
    om = sp.Symbol("omega", positive=True)  # 1 - theta1
    steps = [prove_nonneg(sp.diff(M39.subs(th1, 1 - om), amax),
                          "(39) grows with a_pMAX (its derivative is >= 0)"),
             refute_nonneg_at(-sp.diff(M39, th1), pt,
                              "(39) shrinks as theta1 grows: d(39)/d theta1 <= 0"),
             refute_nonneg_at(sp.diff(T40, th1), pt,
                              "(40) grows with theta1: d(40)/d theta1 >= 0")]
    return Claim("theta-effect", "(31), (32), (39), (40), text after (45)",
                 "Effect of a_pMAX, theta1, theta2 on the neighbourhoods and times",
                 "a large a_pMAX widens the neighbourhood; large theta1, theta2 shrink the "
                 "neighbourhood but increase the convergence time",
                 "Backwards for theta: the neighbourhoods (39), (31) grow with theta (the factor "
                 "1/(1-theta)) and the times (40), (45) fall with it (the factor 1/theta).  The "
                 "a_pMAX statement holds.", steps)


# --- Claims judged for a gain set -----------------------------------------------------------

def _point_box(vals: dict) -> dict:
    return {k: (float(x), float(x)) for k, x in vals.items()}


def _bound_exprs():
    """(18), (26), (39), (31) and (40), (45) as SymPy expressions of the per-axis gains."""
    T1 = (1 / (b1 * (1 - q1) * 2 ** ((q1 - 1) / 2)) + 1 / (b2 * (q2 - 1) * 2 ** ((q2 - 1) / 2)))
    T2 = (1 / (a1 * (1 - g1) * 2 ** ((g1 - 1) / 2)) + 1 / (a2 * (g2 - 1) * 2 ** ((g2 - 1) / 2)))
    Mx = sp.Min((amax / ((1 - th1) * a1)) ** (1 / g1), (amax / ((1 - th1) * a2)) ** (1 / g2))
    N = sp.Min((Mx / ((1 - th2) * b1)) ** (1 / q1), (Mx / ((1 - th2) * b2)) ** (1 / q2))
    return {"T1 (18)": T1, "T2 (26)": T2, "s2 nbhd (39)": Mx, "T2 practical (40)": T2 / th1,
            "s1 nbhd (31)": N, "T1 practical (45)": T1 / th2}


def _axis_point(g, i: int) -> dict:
    ax = g.axis(i)
    pt = {b1: ax["beta1"], b2: ax["beta2"], a1: ax["alpha1"], a2: ax["alpha2"], q1: ax["q1"],
          q2: ax["q2"], g1: ax["g1"], g2: ax["g2"]}
    if g.disturbance is not None:
        d = g.disturbance
        pt.update({amax: d.a_max, th1: d.theta1, th2: d.theta2})
    return pt


def _distinct_axes(g) -> list[int]:
    seen, out = [], []
    for i in range(3):
        key = tuple(sorted(g.axis(i).items()))
        if key not in seen:
            seen.append(key)
            out.append(i)
    return out


def _numbers_steps(g, keys: tuple[str, ...]) -> list[Step]:
    from lgw.theory.mars.bounds import axis_bounds

    ex = _bound_exprs()
    numpy_key = {"T1 (18)": "T1_polyakov", "T2 (26)": "T2_polyakov", "s2 nbhd (39)": "s2_bound",
                 "T2 practical (40)": "T2_practical", "s1 nbhd (31)": "s1_bound",
                 "T1 practical (45)": "T1_practical"}
    bounds = axis_bounds(g)
    steps = []
    for i in _distinct_axes(g):
        axn = "xyz"[i]
        for k in keys:
            printed = sp.nsimplify(PRINTED[k])
            expr = ROUND - sp.Abs(ex[k] - printed)
            steps.append(prove_arb(
                expr, _point_box({s_: x for s_, x in _axis_point(g, i).items()
                                  if s_ in expr.free_symbols}),
                f"these gains reproduce the printed {k} = {PRINTED[k]} on axis {axn} "
                f"(to the printed rounding {ROUND:g})",
                recheck=lambda pt, k=k, axn=axn: ROUND - abs(bounds[axn][numpy_key[k]]
                                                              - PRINTED[k])))
    return steps


def reproducing_gains(g) -> dict[str, float | None]:
    """Per axis, the beta1 (alpha1) that makes (18) (26) equal the printed 74.5780 s
    (30.8217 s) with this gain set's other gains and exponents: (18) is affine in 1/beta1, so
    beta1 = 1/(c1 (T - 1/(beta2 c2))), c1 = (1-q1) 2^((q1-1)/2), c2 = (q2-1) 2^((q2-1)/2);
    None when the beta2 term alone already exceeds the printed time."""
    out: dict[str, float | None] = {}
    for i in _distinct_axes(g):
        ax = g.axis(i)
        for name, (k2, e1_, e2_, T) in {
                "beta1": ("beta2", "q1", "q2", PRINTED["T1 (18)"]),
                "alpha1": ("alpha2", "g1", "g2", PRINTED["T2 (26)"])}.items():
            c1 = (1 - ax[e1_]) * 2 ** ((ax[e1_] - 1) / 2)
            c2 = (ax[e2_] - 1) * 2 ** ((ax[e2_] - 1) / 2)
            rest = T - 1 / (ax[k2] * c2)
            out[f"{name}_{'xyz'[i]}"] = 1 / (c1 * rest) if rest > 0 else None
    return out


def paper_numbers_gain_claims(g) -> list[Claim]:
    part1 = _numbers_steps(g, ("T1 (18)", "T2 (26)"))
    c1 = Claim("paper-numbers-part1@gains", "(18), (26), Part 1",
               "Do these gains reproduce Part 1's printed bounds?",
               "T1 <= 74.5780 s (18), T2 <= 30.8217 s (26)",
               "(18) and (26) evaluated for the gain set by Arb interval arithmetic and compared "
               "with the printed numbers to their rounding.  Numbers: the beta1, alpha1 that "
               "would reproduce them with this set's other gains and exponents.", part1,
               scope="gain-set", numbers={"reproducing_gains": reproducing_gains(g),
                                          **_bound_numbers(g, ("T1_polyakov", "T2_polyakov"))})
    if g.disturbance is None:
        part2 = [Step("the Part 2 numbers need a_max, theta1, theta2",
                      Unproven("the gain file has no [disturbance] table"))]
    else:
        part2 = _numbers_steps(g, ("s2 nbhd (39)", "T2 practical (40)", "s1 nbhd (31)",
                                   "T1 practical (45)"))
    c2 = Claim("paper-numbers-part2@gains", "(39), (40), (31), (45), Part 2",
               "Do these gains reproduce Part 2's printed neighbourhoods and times?",
               "(39) = 26.5257 m, (40) = 131.5173 s, (31) = 23.8472 m, (45) = 85.8610 s "
               "(theta1 = 0.2, theta2 = 0.1, a_pMAX = 20)",
               "Evaluated for the gain set and its [disturbance] table by Arb; no gain set can "
               "give both (26) = 30.8217 s and (40) = 131.5173 s with theta1 = 0.2 (claim "
               "paper-numbers).", part2, scope="gain-set",
               numbers=_bound_numbers(g, ("s2_bound", "T2_practical", "s1_bound",
                                          "T1_practical")) if g.disturbance else {})
    return [c1, c2]


def _bound_numbers(g, keys: tuple[str, ...]) -> dict[str, dict[str, float]]:
    """The gain set's bounds (lgw.theory.mars.bounds.axis_bounds) per axis: a claim's
    numbers."""
    from lgw.theory.mars.bounds import axis_bounds

    b = axis_bounds(g)
    return {k: {ax: float(b[ax][k]) for ax in b} for k in keys}


def _thrust_step(g, law: str, t_end: float, n_out: int) -> Step:
    """Per axis, the reduced closed loop from Table I (gravity and drag cancel exactly in the
    law, so r, v do not depend on them nor on the mass); the command a_i = law(r, v, g_i,
    a_m = 0) and |F_i| = m |a_i|.  Margin: F_max - m0 |a_i| (m <= m0, so a nonnegative
    margin is sound).  Re-check of a violation: the surface-coordinate integration and the
    SymPy law at 30 digits with the least mass the lander can have then: m0 at t = 0 (the
    mass is Table I's there), the dry mass m_dry later (m >= m_dry), so a negative re-checked
    margin is a sound violation."""
    from lgw.theory.mars.parameters import M_DRY

    f = M.law_numeric(law)
    pts, states, failed = [], {}, {}
    for i in range(3):
        ax = g.axis(i)
        args = [ax[k] for k in ("beta1", "beta2", "alpha1", "alpha2", "q1", "q2", "g1", "g2")]
        try:
            tr = trajectory(law, ax, float(R0[i]), float(V0[i]), t_end, n_out=n_out)
        except (RuntimeError, ArithmeticError) as e:  # stated in the domain: not searched
            failed["xyz"[i]] = f"{type(e).__name__}: {e}"
            continue
        with np.errstate(all="ignore"):
            acc = f(tr["r"], tr["v"], float(G_MARS[i]), 0.0, *args)
        states[i] = (tr, acc)
        for j in range(len(tr["t"])):
            pts.append({"axis": "xyz"[i], "t": float(tr["t"][j]), "r": float(tr["r"][j]),
                        "v": float(tr["v"][j]), "a": float(acc[j])})

    if not pts:
        return Step(f"|F_i(t)| <= {THRUST_MAX_AXIS:.0f} N along the Table I flight, {law} law",
                    Unproven(f"the reference integration failed on every axis: {failed}"))

    def margin(pt):
        a_ = pt["a"]
        return THRUST_MAX_AXIS - M0 * abs(a_) if math.isfinite(a_) else -math.inf

    def recheck(pt):
        i = "xyz".index(pt["axis"])
        ax = g.axis(i)
        s2_0 = float(M.surfaces_numeric()[1](float(R0[i]), float(V0[i]), ax["beta1"],
                                             ax["beta2"], ax["q1"], ax["q2"]))
        tr2 = surface_trajectory(law, ax, float(R0[i]), s2_0, max(pt["t"], 1e-9) * 1.0001 + 1e-9,
                                 n_out=2001)
        rr = float(np.interp(pt["t"], tr2["t"], tr2["r"]))
        vv = float(np.interp(pt["t"], tr2["t"], tr2["v"]))
        subs = {M.r: sp.Float(rr, 30), M.v: sp.Float(vv, 30), M.grav: sp.Float(G_MARS[i], 30),
                M.am: 0, **{getattr(M, k): sp.Float(val, 30) for k, val in ax.items()}}
        a_re = float(sp.N(M.law(law).subs(subs), 30))
        return THRUST_MAX_AXIS - (M0 if pt["t"] == 0.0 else M_DRY) * abs(a_re)

    return search_step(
        f"|F_i(t)| <= {THRUST_MAX_AXIS:.0f} N on every axis along the Table I flight, {law} law",
        margin, pts,
        domain={"scenario": "Table I r0, v0, m0 = 1905 kg", "t": [0.0, t_end],
                "grid": f"{n_out} points per axis",
                "a_m": "0 in the command (the laws cancel a_m, so r and v do not depend on "
                       "it; the command shifts by -a_m, ~0.03 m/s^2 at 100 m/s, 1.5 km with "
                       "the simulator's physical drag)",
                "axes": [a for a in "xyz" if a not in failed],
                **({"integration failed": failed} if failed else {})},
        method="reduced per-axis closed loop (LSODA 1e-10, lgw.theory.mars.reduced), margin "
               "F_max - m0 |a_i(t)| over the time grid",
        recheck=recheck, recheck_method="surface-coordinate integration and the SymPy law at "
        "30 digits, with the least possible mass (m0 at t = 0, else the dry mass 1505 kg; "
        "margin F_max - m |a_i|)")


def _thrust_numbers(step: Step) -> dict:
    """The peak command and its margin, from the thrust search (the claim's numbers)."""
    ev = step.evidence
    if not isinstance(ev, Search):
        return {}
    return {"least margin F_max - m0 |a_i| (N)": ev.best_margin,
            "at": {k: ev.best_point.get(k) for k in ("axis", "t", "a")}}


def thrust_gain_claims(g, t_end: float = 40.0, n_out: int = 2001) -> list[Claim]:
    out = []
    for law in ("printed", "corrected"):
        step = _thrust_step(g, law, t_end, n_out)
        out.append(Claim(
            f"thrust-table1-{law}@gains", "Part 1 (Fig. 2(c)), Part 3 (50 kN limit)",
            f"Command against the thrust limit on Table I, {law} law",
            "'the maximum value [of the command thrust] is less than 4 x 10^4 N ... no "
            "overlarge thrust command input if proper parameters are set'; thrust limit 50 kN "
            "per axis (Part 3)",
            f"The {law} law's command for this gain set on the paper's own scenario (Table I), "
            "against the stated 50 kN per-axis limit.", [step],
            law=law, scope="gain-set", numbers=_thrust_numbers(step),
            **({"statement": "workbench"} if law == "corrected" else {})))
    return out


def bounded_command_gain_claim(g) -> Claim:
    """bounded-command-printed for this gain set: every exponent of the printed law's command
    (read from the law) at the gain set's exponents, by Arb; a negative one is a witness."""
    exps = command_exponents(M.law("printed"))
    point = {s_: sp.nsimplify(getattr(g, s_.name))
             for s_ in sorted(set().union(*(e.free_symbols for e in exps)),
                              key=lambda x: x.name)}
    st = _bounded_step("printed", exps, point, "every exponent of a power in the printed law's "
                       f"command is >= 0 at this gain set ({', '.join(sp.sstr(e) for e in exps)})"
                       ": the command is bounded near s1 = 0")
    vals = {sp.sstr(e): float(e.subs(point)) for e in exps}
    return Claim("bounded-command-printed@gains", "(25)", "Printed law bounded near s1 = 0 for "
                 "these exponents", "no overlarge thrust command input if proper parameters "
                 "are set", "For this gain set's exponents (claim bounded-command-printed).",
                 [st], law="printed", scope="gain-set", numbers={"exponents": vals})


def hypotheses_gain_claim(g) -> Claim:
    if g.disturbance is None:
        steps = [Step("Theorem 4's hypotheses need a_max, theta1, theta2",
                      Unproven("the gain file has no [disturbance] table"))]
    else:
        A = sp.Symbol("a_max", positive=True)
        box = {A: (g.disturbance.a_max, g.disturbance.a_max)}
        steps = [prove_arb(A - 20, box, "the paper's test disturbance (47), 20 sin t per axis, "
                           "satisfies |a_p,i| <= a_max (the per-axis hypothesis (37)-(44) use)",
                           recheck=lambda pt: pt["a_max"] - 20.0),
                 prove_arb(A - 20 * sp.sqrt(3), box, "(47) satisfies Hypothesis 1 as printed, "
                           "||a_p|| <= a_max (max ||a_p|| = 20 sqrt 3 at t = pi/2)",
                           recheck=lambda pt: pt["a_max"] - 20.0 * math.sqrt(3.0))]
    return Claim("practical-hypotheses@gains", "Hypothesis 1, (47), Theorem 4",
                 "The practical bounds' hypotheses for this disturbance table",
                 "Theorem 4 under Hypothesis 1, tested with (47)",
                 "Whether the gain file's a_max covers the paper's own test disturbance (per "
                 "axis, and in norm as Hypothesis 1 is printed).", steps, scope="gain-set",
                 numbers={} if g.disturbance is None else {
                     "a_max": g.disturbance.a_max,
                     "a_max - 20 (per axis)": g.disturbance.a_max - 20.0,
                     "a_max - 20 sqrt 3 (norm)": g.disturbance.a_max - 20.0 * math.sqrt(3.0)})


def tuning_rule_gain_claim(g, tf: float = 30.0) -> Claim:
    from lgw.theory.mars.bounds import axis_bounds

    ex = _bound_exprs()
    bounds = axis_bounds(g)
    steps = []
    for i in _distinct_axes(g):
        axn = "xyz"[i]
        pt = _axis_point(g, i)
        for k, key in (("T1 (18)", "T1_polyakov"), ("T2 (26)", "T2_polyakov")):
            e = tf - ex[k]
            steps.append(prove_arb(e, _point_box({s_: x for s_, x in pt.items()
                                                  if s_ in e.free_symbols}),
                                   f"the tuning rule {k} <= tf = {tf:g} s on axis {axn}",
                                   recheck=lambda p, key=key, axn=axn: tf - bounds[axn][key]))
    return Claim("tuning-rule@gains", "(18), (26), Remark 1 tuning rule, Part 1 (tf = 30 s)",
                 "The paper's tuning rule for tf = 30 s",
                 "max_i (18)_i <= tf and max_i (26)_i <= tf, with Part 1's tf = 30 s",
                 "Judged for this gain set; note the rule itself does not bound the landing "
                 "time (claim landing-time: the sound bound is T1 + T2).", steps,
                 scope="gain-set", numbers=_bound_numbers(g, ("T1_polyakov", "T2_polyakov")))


def _gains_text(g) -> str:
    """A gain set as a memo key: every value of the file (the arrays, the disturbance and
    the ``extra`` tables the bounded laws read), as canonical JSON."""
    import json

    return json.dumps({**g.to_dict(), "extra": g.extra}, sort_keys=True, default=repr)


@memo(key=_gains_text)
def _gain_set_claims(g) -> tuple[Claim, ...]:
    # memoised per gain set (a report, its JSON and the checks judge the same set more than
    # once; each judgement flies the thrust scenarios): cleared with the module's caches
    from lgw.theory.mars import bounded_claims

    return (*paper_numbers_gain_claims(g), tuning_rule_gain_claim(g),
            bounded_command_gain_claim(g), *thrust_gain_claims(g), hypotheses_gain_claim(g),
            *bounded_claims.gain_set_claims(g))


def gain_set_claims(g) -> list[Claim]:
    """Every gain-dependent statement of seed 000 judged for the gain set ``g`` (a
    ``lgw.theory.mars.gains.Gains``): scope "gain-set"; the bounded laws' box bounds are judged
    for the file's ``[bounded]`` and ``[bounded-sat]`` tables."""
    return list(_gain_set_claims(g))


def general_claims() -> list[Claim]:
    """Every claim of seed 000 that holds or fails whatever the valid gains, in report order:
    each paper statement, followed by the workbench's correction of it where there is one."""
    se = _settling_exprs()
    return [SP.lemma1(), _with_exprs(SP.lemma2(), *se["lemma2"]),
            _with_exprs(SP.exact_bound_claim(), *se["exact-bound"]), SP.exact_time_claim(),
            SP.theorem1(), SP.theorem1_corrected(), plant_claim(), drag_claim(), mass_claim(),
            surface_claim(), v1dot_axis_claim(), v1dot_vector_claim(),
            v1dot_vector_corrected_claim(), t1_claim(), s2dot_claim(), s2dot24_claim(),
            s2dot24_corrected_claim(), v2dot_claim("printed"), v2dot_claim("corrected"),
            laws_agree_claim(), t2_claim("printed"), t2_claim("corrected"), landing_claim(),
            landing_corrected_claim(), remark1_claim(), remark1_corrected_claim(),
            remark2_claim(), bounded_command_claim("printed"),
            bounded_command_claim("corrected"), hypothesis1_claim(),
            hypothesis1_per_axis_claim(), v2dot_disturbed_claim("printed"),
            v2dot_disturbed_claim("corrected"), s2_neighborhood_claim("printed"),
            s2_neighborhood_claim("corrected"), t2_practical_claim("printed"),
            t2_practical_claim("corrected"), s1_neighborhood_claim("printed"),
            s1_neighborhood_claim("corrected"), t1_practical_claim("printed"),
            t1_practical_claim("corrected"), t3_claim(), t3_corrected_claim(),
            theta_effect_claim(), paper_numbers_claim()]


def all_claims(gains=None, comparison=None) -> list[Claim]:
    """Every claim of seed 000 in report order, then the workbench's own bounded laws
    (``lgw.theory.mars.bounded_claims``: beyond the paper); with a gain set, also the claims
    judged for it; then the claims on the paper's Part 1 comparison (``comparison``: the
    record of ``lgw compare mars`` the report layer passes in; without it they say so)."""
    from lgw.theory.mars import bounded_claims, scenario_claims

    return (general_claims() + list(bounded_claims.all_claims())
            + (gain_set_claims(gains) if gains is not None else [])
            + scenario_claims.comparison_claims(comparison))


