"""Seed 000's claims, derived from the law and checked: each ends with a verdict and evidence.

Everything here is derived from the SymPy expressions of ``lgw.theory.mars.mss``; no printed
formula is taken as true.  ``all_claims()`` lists every claim in report order.
"""

from __future__ import annotations

import itertools
import random
from functools import cache

import numpy as np
import sympy as sp
from lgw.theory import settling_proofs as SP
from lgw.theory.claims import Claim, Step, combine, numeric_search, prove_nonneg, prove_zero
from lgw.theory.mars import mss as M
from lgw.theory.mars.bounds import tf_min, tf_min_printed
from lgw.theory.mars.parameters import G_MARS, M0, R0, THRUST_MAX_AXIS, V0
from lgw.theory.mars.reduced import surface_trajectory, trajectory
from lgw.theory.settling import polyakov_bound
from lgw.theory.symbolic import sig

r, v, ap = M.r, M.v, M.ap
b1, b2, a1, a2 = M.beta1, M.beta2, M.alpha1, M.alpha2
q1, q2, g1, g2 = M.q1, M.q2, M.g1, M.g2
S2 = sp.Symbol("s_2", real=True)  # the second surface as a coordinate
amax = sp.Symbol("a_max", positive=True)
th1, th2 = sp.symbols("theta_1 theta_2", positive=True)

# A concrete gain set for counterexamples that need a trajectory (the example of issue 2).
EXAMPLE_GAINS = {"beta1": 0.2, "beta2": 0.05, "alpha1": 0.5, "alpha2": 0.1,
                 "q1": 0.7, "q2": 1.3, "g1": 0.7, "g2": 1.3}
# Rational points for symbolic counterexamples (exact arithmetic).
PT = {b1: sp.Integer(1), b2: sp.Integer(1), a1: sp.Integer(1), a2: sp.Integer(1),
      q1: sp.Rational(1, 2), q2: sp.Integer(2), g1: sp.Rational(1, 2), g2: sp.Integer(2)}


def _surface_coords(expr: sp.Expr) -> sp.Expr:
    """Write expr(r, v) in (s1, s2) = (r, S2): v = S2 - beta1 sig(r,q1) - beta2 sig(r,q2)."""
    return expr.subs(v, S2 + M.reaching_law_rhs(r))


def prove_branches(expr: sp.Expr, reals: tuple[sp.Symbol, ...], statement: str) -> Step:
    """expr == 0 on every sign branch of the real symbols (x = 0 excluded: measure zero, and
    the surfaces' derivatives are taken for x != 0 as in seed 000 (22))."""
    for signs in itertools.product((1, -1), repeat=len(reals)):
        pairs = list(zip(reals, signs, strict=True))
        subs = {s: sg * sp.Symbol(f"{s.name}_abs", positive=True) for s, sg in pairs}
        e = sp.expand(expr.subs(subs))
        st = prove_zero(sp.powsimp(e, force=True), statement)
        if st.status != "proved":
            st.detail = f"branch signs { {s.name: sg for s, sg in pairs} }: " + st.detail
            return st
    return Step(statement, "SymPy simplify on each sign branch of " +
                ", ".join(s.name for s in reals), "proved", "residual = 0 on every branch")


def _dbeta() -> sp.Expr:
    """d/ds1 (beta1 sig(s1,q1) + beta2 sig(s1,q2)) = beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)."""
    return b1 * q1 * sp.Abs(r) ** (q1 - 1) + b2 * q2 * sp.Abs(r) ** (q2 - 1)


def _at(expr: sp.Expr, pt: dict) -> sp.Expr:
    return sp.nsimplify(sp.N(expr.subs(pt), 30), rational=False)


# --- (15), (16), (19)-(20), (18) ---------------------------------------------------------

@cache
def surface_claim() -> Claim:
    steps = [prove_zero(M.surface2().subs(v, M.reaching_law_rhs(r)),
                        "s2 of (21) vanishes exactly when s1' = v obeys the reaching law (16)")]
    return Claim("surface2", "(15), (16), (21)", "The second surface encodes the reaching law",
                 "once s2 = 0 the first reaching law (16) is established automatically",
                 "s2 = 0  <=>  v = -beta1 sig(s1,q1) - beta2 sig(s1,q2)", steps, combine(steps),
                 "identity")


@cache
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
                 "Per axis both relations are equalities (proved).", steps, combine(steps),
                 "identities on both sign branches of s1")


@cache
def v1dot_vector_claim() -> Claim:
    """The paper writes (19)-(20) with the vector s1 and diagonal matrices; with V1 = |s1|^2/2
    the inequality needs sum_i |s_i|^(q+1) >= (sum s_i^2)^((q+1)/2), true for q < 1 and false
    for q > 1."""
    s = [sp.Integer(1)] * 3
    V1 = sum(x**2 for x in s) / 2
    pt = dict(PT)
    lhs = -sum(pt[b1] * abs(x) ** (pt[q1] + 1) + pt[b2] * abs(x) ** (pt[q2] + 1) for x in s)
    rhs = -(pt[b1] * 2 ** ((pt[q1] + 1) / 2) * V1 ** ((pt[q1] + 1) / 2)
            + pt[b2] * 2 ** ((pt[q2] + 1) / 2) * V1 ** ((pt[q2] + 1) / 2))
    v1dot, claimed = str(sp.nsimplify(lhs)), str(sp.N(rhs, 10))
    ce = {"s1": [1, 1, 1], "beta1": 1, "beta2": 1, "q1": "1/2", "q2": 2,
          "V1'": v1dot, "claimed upper bound": claimed}
    fails = bool(lhs > rhs)

    def check_q(q_lo: float, q_hi: float, factor) -> callable:
        def check(rng: random.Random):
            q = rng.uniform(q_lo, q_hi)
            x = np.array([rng.uniform(-1, 1) * 10 ** rng.uniform(-3, 3) for _ in range(3)])
            lhs_ = np.sum(np.abs(x) ** (q + 1))
            rhs_ = factor(q) * np.sum(x**2) ** ((q + 1) / 2)
            return lhs_ >= rhs_ * (1 - 1e-12), {"q": q, "s": x.tolist()}
        return check

    steps = [
        Step("sum_i |s_i|^(q2+1) >= (sum_i s_i^2)^((q2+1)/2) for q2 > 1",
             "exact evaluation at a rational point", "refuted" if fails else "unproven",
             f"V1' = {v1dot} > {claimed} at {ce}"),
        numeric_search(check_q(0.01, 0.99, lambda q: 1.0),
                       "sum_i |s_i|^(q1+1) >= (sum_i s_i^2)^((q1+1)/2) for 0 < q1 < 1",
                       "random search, log-uniform magnitudes", "q in (0,1), |s_i| in "
                       "[1e-3, 1e3], 3 axes", 4000),
        numeric_search(check_q(1.01, 4.0, lambda q: 3 ** ((1 - q) / 2)),
                       "sum_i |s_i|^(q2+1) >= 3^((1-q2)/2) (sum_i s_i^2)^((q2+1)/2) for q2 > 1 "
                       "(power-mean inequality)", "random search, log-uniform magnitudes",
                       "q in (1,4), |s_i| in [1e-3, 1e3], 3 axes", 4000),
    ]
    return Claim("V1dot-vector", "(19)-(20), vector form",
                 "Lyapunov derivative of the first surface, 3-axis form",
                 "V1 = s1^T s1/2, V1' <= -(beta1 2^((q1+1)/2) V1^((q1+1)/2) + beta2 2^((q2+1)/2) "
                 "V1^((q2+1)/2)) with diagonal gain matrices",
                 "With matrices the right side is not a scalar; with scalar gains the q2 term is "
                 "false (counterexample) and needs the factor 3^((1-q2)/2).  The time bound (18) "
                 "still holds per axis because the axes are decoupled (claim T1).",
                 steps, "refuted", "counterexample at s1 = (1, 1, 1)", counterexample=ce)


def _route_identity(gain1, gain2, e1_, e2_) -> tuple[Step, Step]:
    aV, bV = gain1 * 2 ** ((e1_ + 1) / 2), gain2 * 2 ** ((e2_ + 1) / 2)
    pV, gV = (e1_ + 1) / 2, (e2_ + 1) / 2
    printed = (1 / (gain1 * (1 - e1_) * 2 ** ((e1_ - 1) / 2))
               + 1 / (gain2 * (e2_ - 1) * 2 ** ((e2_ - 1) / 2)))
    s1 = prove_zero(sp.simplify(SP.polyakov_expr(aV, bV, pV, gV, 1) - printed),
                    "Lemma 2 (3) with k = 1 and the V-route constants equals the printed bound")
    s2 = prove_zero(SP._log_ratio(SP.exact_expr(aV, bV, pV, gV, 1),
                                  SP.exact_expr(gain1, gain2, e1_, e2_, 1)),
                    "T* is the same through V = s^2/2 and through |s| (route-invariant)")
    return s1, s2


@cache
def t1_claim() -> Claim:
    i1, i2 = _route_identity(b1, b2, q1, q2)
    steps = [Step("V1' per axis satisfies Lemma 2's (2) with k = 1", "claim V1dot", "proved"),
             Step("Lemma 2's bound (3) and the exact T*", "claims lemma2, exact-bound", "proved"),
             i1, i2,
             Step("the three axes are decoupled under (16), so the 3-axis time is the max over "
                  "axes of the per-axis bound", "structure of (16) (diagonal gains)", "proved")]
    return Claim("T1", "(18)", "Theorem 2: fixed-time convergence of the first surface",
                 "T1 <= 1/(beta1 (1-q1) 2^((q1-1)/2)) + 1/(beta2 (q2-1) 2^((q2-1)/2))",
                 "Holds per axis under (16).  Least upper bound: T1* = Gamma(m)Gamma(1-m)/"
                 "(beta1 (q2-q1)) (beta1/beta2)^m, m = (1-q1)/(q2-q1).",
                 steps, combine(steps), "symbolic identities + Lemma 2")


# --- (22)-(29): the second surface and the guidance ---------------------------------------

@cache
def s2dot_claim() -> Claim:
    acc = sp.Symbol("a", real=True)
    s2dot = M.time_derivative(M.surface2(), acc)
    expected = acc + M.grav + M.am + _dbeta() * v
    steps = [prove_branches(s2dot - expected, (r,),
                            "s2' = s1'' + (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s1', "
                            "s1'' = a + g + a_m, s1' = v")]
    return Claim("s2dot", "(22)-(23)", "Derivative of the second surface",
                 "s2' = s1'' + beta1 q1 |s1|^(q1-1) s1' + beta2 q2 |s1|^(q2-1) s1'",
                 "Holds (s1 != 0).", steps, combine(steps), "symbolic derivative")


@cache
def s2dot24_claim() -> Claim:
    acc = sp.Symbol("a", real=True)
    true = M.time_derivative(M.surface2(), acc)
    printed = (acc + M.grav + M.am - b1**2 * q1 * sig(r, 2 * q1 - 1)
               - b2**2 * q2 * sig(r, 2 * q2 - 1) - b1 * b2 * (q1 + q2) * sig(r, q1 + q2 - 1))
    resid = true - printed
    s_res = prove_branches(_surface_coords(resid - _dbeta() * M.surface2()), (r,),
                           "true s2' - printed (24) = (beta1 q1|s1|^(q1-1) + beta2 q2 "
                           "|s1|^(q2-1)) s2")
    pt = {**PT, r: sp.Integer(1), v: sp.Integer(1)}
    val = _at(resid, pt)
    ce = {"s1": 1, "v": 1, "beta1": 1, "beta2": 1, "q1": "1/2", "q2": 2,
          "s2": str(_at(M.surface2(), pt)), "true s2' - printed (24)": str(val)}
    steps = [s_res, Step("(24) = true s2'", "exact evaluation", "refuted" if val != 0 else
                         "unproven", str(ce)),
             prove_branches(resid.subs(v, M.reaching_law_rhs(r)), (r,),
                            "on s2 = 0 (v given by (16)) the printed (24) is exact")]
    return Claim("s2dot-24", "(24)", "Second-surface derivative with the command",
                 "s2' = a + g + a_m - beta1^2 q1|s1|^(2q1-1)sgn(s1) - beta2^2 q2|s1|^(2q2-1)"
                 "sgn(s1) - beta1 beta2 (q1+q2)|s1|^(q1+q2-1)sgn(s1)",
                 "(24) substitutes the reaching law (16) for s1' = v, which holds only on s2 = 0.  "
                 "In general s2' = (24) + (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s2.",
                 steps, "refuted", "counterexample off the surface", counterexample=ce)


def _v2dot_residual(law: str, with_ap: bool = False) -> sp.Expr:
    cl = M.closed_loop(law)
    V2dot = cl.V2dot if with_ap else cl.V2dot.subs(ap, 0)
    s2 = M.surface2()
    target = -a1 * sp.Abs(s2) ** (g1 + 1) - a2 * sp.Abs(s2) ** (g2 + 1)
    if with_ap:
        target = target + s2 * ap
    return _surface_coords(V2dot - target)


@cache
def v2dot_claim(law: str) -> Claim:
    resid = _v2dot_residual(law)
    paper = ("substituting (25) into (28): V2' = s2^T[-alpha1|s2|^g1 sgn(s2) - alpha2|s2|^g2 "
             "sgn(s2)] = -alpha1|s2|^(g1+1) - alpha2|s2|^(g2+1) <= -(alpha1 2^((g1+1)/2) "
             "V2^((g1+1)/2) + alpha2 2^((g2+1)/2) V2^((g2+1)/2))")
    if law == "corrected":
        steps = [prove_branches(resid, (r, S2), "V2' = s2 s2' = -alpha1|s2|^(g1+1) - "
                                "alpha2|s2|^(g2+1) under the corrected law")]
        return Claim("V2dot-corrected", "(27)-(29)", "Lyapunov derivative of the second "
                     "surface, corrected law", paper,
                     "Holds exactly for the corrected law (exact cancellation of s2').",
                     steps, combine(steps), "identity on the four sign branches", law=law)
    extra = _surface_coords(_dbeta()) * S2**2
    steps = [prove_branches(resid - extra, (r, S2), "V2' - (29) = (beta1 q1|s1|^(q1-1) + "
                            "beta2 q2|s1|^(q2-1)) s2^2 under the printed law (25)"),
             prove_nonneg(_dbeta().subs(r, sp.Symbol("x", positive=True)) * S2**2,
                          "the extra term is >= 0 (it destabilises s2)")]
    pt = {**PT, r: sp.Integer(1), S2: sp.Integer(1)}
    val = _at(resid, pt)
    ce = {"s1": 1, "s2": 1, "beta1": 1, "beta2": 1, "q1": "1/2", "q2": 2, "alpha1": 1,
          "alpha2": 1, "g1": "1/2", "g2": 2, "V2' - (29)": str(val)}
    steps.append(Step("V2' = (29) under (25)", "exact evaluation", "refuted", str(ce)))
    return Claim("V2dot-printed", "(27)-(29)", "Lyapunov derivative of the second surface, "
                 "printed law (25)", paper,
                 "False off s2 = 0: V2' = (29) + (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s2^2, "
                 "the extra term is positive and unbounded near s1 = 0.",
                 steps, "refuted", "counterexample", law=law, counterexample=ce)


@cache
def laws_agree_claim() -> Claim:
    diff = M.law_corrected() - M.law_printed()
    steps = [prove_branches(_surface_coords(diff + _dbeta() * M.surface2()), (r,),
                            "corrected - printed = -(beta1 q1|s1|^(q1-1) + "
                            "beta2 q2|s1|^(q2-1)) s2"),
             prove_branches(diff.subs(v, M.reaching_law_rhs(r)), (r,),
                            "hence the two laws agree on s2 = 0")]
    return Claim("laws-agree", "(25)", "The printed and the corrected guidance coincide on s2 = 0",
                 "(the paper has one law)", "corrected (25') = printed (25) - (beta1 q1 |s1|^(q1-1)"
                 " + beta2 q2|s1|^(q2-1)) s2", steps, combine(steps), "identities")


@cache
def t2_claim(law: str) -> Claim:
    paper = ("T2 <= 1/(alpha1 (1-g1) 2^((g1-1)/2)) + 1/(alpha2 (g2-1) 2^((g2-1)/2)), "
             "independent of the initial state")
    if law == "corrected":
        i1, i2 = _route_identity(a1, a2, g1, g2)
        steps = [Step("V2' satisfies Lemma 2's (2) per axis", "claim V2dot-corrected", "proved"),
                 Step("Lemma 2 (3) and T*", "claims lemma2, exact-bound", "proved"), i1, i2]
        return Claim("T2-corrected", "(26)", "Theorem 3: fixed-time convergence of the second "
                     "surface, corrected law", paper,
                     "Holds for the corrected law; least upper bound T2* = Gamma(m)Gamma(1-m)/"
                     "(alpha1 (g2-g1)) (alpha1/alpha2)^m, m = (1-g1)/(g2-g1).",
                     steps, combine(steps), "symbolic", law=law)
    g = EXAMPLE_GAINS
    T2 = float(polyakov_bound(g["alpha1"] * 2 ** ((g["g1"] + 1) / 2),
                              g["alpha2"] * 2 ** ((g["g2"] + 1) / 2),
                              (g["g1"] + 1) / 2, (g["g2"] + 1) / 2))
    tr = trajectory("printed", g, -8000.0, 0.0, 2 * T2)
    idx = int(np.searchsorted(tr["t"], T2))
    s2_at = float(tr["s2"][idx])
    ce = {"gains": g, "r0": -8000.0, "v0": 0.0, "T2 (26)": T2, "s2(T2)": s2_at,
          "method": "LSODA rtol = atol = 1e-10 on the per-axis closed loop "
                    "(lgw.theory.mars.reduced)"}
    ok = abs(s2_at) > 1.0
    steps = [Step("V2' obeys Lemma 2's (2)", "claim V2dot-printed", "refuted",
                  "extra term (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s2^2 >= 0"),
             Step("s2 = 0 by T2 from s1x(0) = -8000 m, v(0) = 0 (the paper's Fig. 6 case)",
                  "reference integration", "refuted" if ok else "unproven", str(ce))]
    return Claim("T2-printed", "(26)", "Theorem 3: fixed-time convergence of the second surface, "
                 "printed law (25)", paper,
                 "False for the printed law: s2 is still far from 0 at T2.", steps,
                 "refuted" if ok else "unproven", "trajectory counterexample", law=law,
                 counterexample=ce if ok else None)


# --- How T1 and T2 combine: the landing time ---------------------------------------------

def _landing_time_reduced(gd: dict, s1_0: float, s2_0: float, t_end: float) -> float:
    tr = surface_trajectory("corrected", gd, s1_0, s2_0, t_end, n_out=8001)
    out = np.where((np.abs(tr["s1"]) > 1e-6) | (np.abs(tr["s2"]) > 1e-6))[0]
    return float(tr["t"][out[-1]]) if len(out) else 0.0


@cache
def landing_claim() -> Claim:
    # The sound bound: s2 reaches 0 by T2 and stays (V2' <= 0), then s1 follows (16).
    s_res = prove_zero(_surface_coords(M.closed_loop("corrected").s2dot.subs(ap, 0)).subs(S2, 0),
                       "s2 = 0 is invariant: s2' = 0 on s2 = 0 (corrected law)")
    steps_sound = [
        Step("s2 reaches 0 within T2 (26) / T2*", "claim T2-corrected", "proved"), s_res,
        Step("from then on s1 obeys (16) from s1(T2), whatever its value, and reaches 0 within "
             "T1 (18) / T1*, a bound uniform in s1(T2)", "claims surface2, T1", "proved"),
        Step("landing time <= T2 + T1 per axis (max over axes)", "composition of the above",
             "proved")]
    # The paper's conclusion max{T1, T2}: search for a violation.
    rng = random.Random(0)
    worst = (0.0, None)
    n = 0
    for _ in range(3):
        gd = {"beta1": 10 ** rng.uniform(-1, 0.5), "beta2": 10 ** rng.uniform(-2, -0.5),
              "q1": rng.uniform(0.55, 0.9), "q2": rng.uniform(1.1, 1.9),
              "g1": rng.uniform(0.55, 0.9), "g2": rng.uniform(1.1, 1.9)}
        # balance the two surfaces so that max{T1, T2} is as small as the sum allows
        gd["alpha1"], gd["alpha2"] = gd["beta1"], gd["beta2"]
        gd["g1"], gd["g2"] = gd["q1"], gd["q2"]
        bound = float(polyakov_bound(gd["beta1"] * 2 ** ((gd["q1"] + 1) / 2),
                                     gd["beta2"] * 2 ** ((gd["q2"] + 1) / 2),
                                     (gd["q1"] + 1) / 2, (gd["q2"] + 1) / 2))
        for s1_0, s2_0 in ((1e3, 1e6), (1e5, 1e3), (10.0, 1e8), (-1e4, 1e4)):
            t_land = _landing_time_reduced(gd, s1_0, s2_0, 1.5 * bound)
            n += 1
            if t_land / bound > worst[0]:
                worst = (t_land / bound, {"gains": gd, "s1_0": s1_0, "s2_0": s2_0,
                                          "landing_time": t_land, "max(T1,T2)": bound})
    paper_step = Step("s1 obeys (16) from t = 0, so the whole landing takes max{T1, T2}",
                      "exact evaluation", "refuted",
                      "s1' = -beta1 sig(s1,q1) - beta2 sig(s1,q2) + s2 (42): (16) fails while "
                      "s2 != 0, e.g. s1 = 0, s2 = 1 gives s1' = 1")
    search = Step("no initial state lands later than max{T1, T2}", "reference integration of "
                  "the per-axis closed loop over random balanced gain sets and extreme states",
                  "checked", f"{n} cases, worst landing time / max(T1,T2) = {worst[0]:.3f} at "
                  f"{worst[1]}")
    steps = steps_sound + [paper_step, search]
    return Claim("landing-time", "Part 1 (whole mission), Remark 1 tuning rule, (32)",
                 "How the two surfaces' times combine into the landing time",
                 "'for the whole mission, the maximum time is 74.5780 s' = max{T1, T2}; tune so "
                 "that max_i T1i <= tf and max_i T2i <= tf",
                 "The sound bound is T2 + T1 per axis (proved; exact: T2* + T1*).  The paper's "
                 "argument for max{T1, T2} is invalid (s1 follows (16) only once s2 = 0); the "
                 "conclusion itself is unproven: no violation was found.",
                 steps, "unproven", "sum proved; paper's step refuted; max not violated in "
                 "the search", law="corrected",
                 numbers={"search_worst_ratio": worst[0], "search_cases": n})


# --- Remark 1: minimum tf -------------------------------------------------------------------

@cache
def remark1_claim() -> Claim:
    a_max = THRUST_MAX_AXIS / M0
    printed = tf_min_printed(R0, V0, a_max, G_MARS)
    derived = tf_min(R0, V0, a_max, G_MARS)
    ce = {"axis": "y (Table I)", "r0": float(R0[1]), "v0": float(V0[1]), "a_max": a_max,
          "v0^2 - 2 a_max r0": float(V0[1] ** 2 - 2 * a_max * R0[1]),
          "printed tf": float(printed[1])}
    steps = [
        Step("tf1 = (-v0 + sqrt(v0^2 - 2 a_max r0))/a_max is the least time to reach r = 0",
             "exact evaluation", "refuted", f"undefined for r0 > 0: {ce}"),
        Step("tf2 = -v0/(a_max - g) is the least time to stop", "exact evaluation", "refuted",
             "negative for v0 > 0 (Table I x axis: v0 = 100 m/s gives "
             f"{-V0[0] / (a_max - G_MARS[0]):.3f} s); for v0 < 0 on z it divides by "
             "a_max + 3.7114 where only a_max - 3.7114 is available against gravity"),
        Step("corrected: with u the speed toward the target and acc = a_max + g.(direction to "
             "target), no |a_i| <= a_max reaches r_i = 0 before (-u + sqrt(u^2 + 2 acc |r0|))"
             "/acc, nor stops before |v0|/(a_max - sgn(v0) g_i)",
             "elementary: integrate the acceleration bound twice (monotone in t)", "proved"),
    ]
    return Claim("remark1", "Remark 1", "Least landing time under a thrust limit",
                 "tf >= max_i {tf1i, tf2i}, tf1i = (-v0i + sqrt(v0i^2 - 2 a_max r0i))/a_max, "
                 "tf2i = -v0i/(a_max - g_i)",
                 "Printed formulas hold only for r0 < 0 (tf1) and fail for v0 > 0 or z (tf2); "
                 "corrected per-axis lower bound in lgw.theory.mars.bounds.tf_min.  Use a_max = "
                 "F_max/m_min for a bound valid at every mass.", steps, "refuted",
                 "counterexample: Table I y axis", counterexample=ce,
                 numbers={"printed_per_axis": printed.tolist(), "derived_per_axis":
                          derived.tolist(), "a_max": a_max})


# --- Bounded command ---------------------------------------------------------------------

@cache
def bounded_command_claim(law: str) -> Claim:
    x = sp.Symbol("x", positive=True)
    acc = M.law(law).subs({M.grav: 0, M.am: 0})
    if law == "corrected":
        lim = sp.limit(acc.subs({r: x, v: 1}).subs({q1: sp.Rational(7, 10), **{
            k: val for k, val in PT.items() if k not in (q1,)}}), x, 0, "+")
        ce = {"s1": "0+", "v": 1, "q1": "7/10", "limit of |a|": str(lim)}
        steps = [Step("|a| bounded near s1 = 0", "SymPy limit s1 -> 0+ at v = 1", "refuted"
                      if lim in (sp.oo, -sp.oo) else "unproven", str(ce))]
        return Claim("bounded-command-corrected", "(25'), Part 1", "Bounded command, corrected "
                     "law", "no overlarge thrust command input if proper parameters are set",
                     "The corrected law contains -beta1 q1 |s1|^(q1-1) v: unbounded when s1 "
                     "crosses 0 while v != 0, whatever the gains (q1 < 1).  Trajectories that "
                     "reach s1 = 0 on s2 = 0 (v -> 0 with s1) keep it bounded for q1 >= 1/2.",
                     steps, "refuted" if lim in (sp.oo, -sp.oo) else "unproven",
                     "limit", law=law, counterexample=ce)
    e = sp.Symbol("e", positive=True)  # q2 = 1 + e
    steps = [
        prove_nonneg(sp.Min(q1 + (1 + e) - 1, 2 * (1 + e) - 1),
                     "q1 + q2 - 1 > 0 and 2 q2 - 1 > 0 for q2 > 1, q1 > 0 (those terms vanish "
                     "at s1 = 0)"),
        Step("2 q1 - 1 >= 0 iff q1 >= 1/2: the |s1|^(2q1-1) term is bounded near s1 = 0 iff "
             "q1 >= 1/2 (discontinuous at q1 = 1/2, unbounded below)", "exponent sign", "proved"),
    ]
    return Claim("bounded-command-printed", "(25), Part 1", "Bounded command, printed law",
                 "no overlarge thrust command input if proper parameters are set",
                 "The printed law is bounded on bounded sets iff q1 >= 1/2 (continuous iff "
                 "q1 > 1/2).  For q1 <= 1/2 the workbench warns.", steps, combine(steps),
                 "exponents", law=law)


# --- Theorem 4: disturbance, (36)-(45), (32) ------------------------------------------------

@cache
def v2dot_disturbed_claim(law: str) -> Claim:
    resid = _v2dot_residual(law, with_ap=True)
    paper = ("(36): V2' = s2[-a_p - alpha1|s2|^g1 sgn - alpha2|s2|^g2 sgn] <= -alpha1|s2|^(g1+1)"
             " - alpha2|s2|^(g2+1) + a_max|s2|")
    if law == "corrected":
        steps = [prove_branches(resid, (r, S2), "V2' = -alpha1|s2|^(g1+1) - alpha2|s2|^(g2+1) "
                                "+ s2 a_p under (30) and the corrected law"),
                 Step("s2 a_p <= a_max |s2| for |a_p,i| <= a_max", "elementary", "proved")]
        return Claim("V2dot-disturbed-corrected", "(33)-(36)", "V2' under disturbance, corrected "
                     "law", paper, "Holds per axis (the sign of a_p in (36) is a harmless slip: "
                     "V2' contains +s2 a_p).", steps, combine(steps), "identity", law=law)
    steps = [Step("(36) under (25)", "claim V2dot-printed", "refuted",
                  "the extra term (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s2^2 remains")]
    return Claim("V2dot-disturbed-printed", "(33)-(36)", "V2' under disturbance, printed law",
                 paper, "False for the printed law (same extra term as (29)).", steps, "refuted",
                 "see V2dot-printed", law=law, counterexample=v2dot_claim("printed").counterexample)


@cache
def s2_neighborhood_claim() -> Claim:
    x = sp.Symbol("x", positive=True)  # |s2|
    # If (1-theta) alpha1 x^g1 >= a_max then V2' <= -theta(...): pure algebra on the bound.
    bound = -a1 * x ** (g1 + 1) - a2 * x ** (g2 + 1) + amax * x
    target = -th1 * (a1 * x ** (g1 + 1) + a2 * x ** (g2 + 1))
    gap = sp.expand(target - bound)  # = x ((1-theta)(alpha1 x^g1 + alpha2 x^g2) - a_max)
    steps = [
        prove_zero(sp.simplify(gap - x * ((1 - th1) * (a1 * x**g1 + a2 * x**g2) - amax)),
                   "-theta1(...) - [(36) bound] = |s2| ((1-theta1)(alpha1|s2|^g1 + "
                   "alpha2|s2|^g2) - a_max)"),
        Step("for |s2| >= min{(a_max/((1-theta1)alpha1))^(1/g1), (a_max/((1-theta1)alpha2))"
             "^(1/g2)} the bracket is >= 0, so V2' <= -theta1(alpha1|s2|^(g1+1) + alpha2|s2|"
             "^(g2+1))", "elementary: one of the two terms alone reaches a_max", "proved"),
        Step("on |s2| = M the derivative is < 0, so |s2| <= M is forward invariant (never left)",
             "previous step with theta1 > 0", "proved"),
    ]
    remark = Step("(37)-(38) apply Theorem 1 with eta = a_max|s2x|, which is not constant as "
                  "Theorem 1 requires", "hypothesis check", "refuted",
                  "eta depends on the state; the conclusion (39) holds by the direct argument")
    return Claim("s2-neighborhood", "(37)-(39)", "Neighbourhood of s2 under bounded disturbance",
                 "|s2i| <= min{(a_max/((1-theta1)alpha1i))^(1/g1), (a_max/((1-theta1)alpha2i))"
                 "^(1/g2)}", "Holds for the corrected law (direct proof; the paper's use of "
                 "Theorem 1 with a state-dependent eta is not valid as written, the bound is).  "
                 "Reached and never left.", steps, combine(steps),
                 "direct argument; the paper's route has an invalid step", law="corrected",
                 remarks=[remark])


@cache
def t2_practical_claim() -> Claim:
    steps = [Step("outside (39), V2' <= -theta1(alpha1|s2|^(g1+1) + alpha2|s2|^(g2+1))",
                  "claim s2-neighborhood", "proved"),
             prove_zero(sp.simplify(SP.polyakov_expr(th1 * a1 * 2 ** ((g1 + 1) / 2),
                                                     th1 * a2 * 2 ** ((g2 + 1) / 2),
                                                     (g1 + 1) / 2, (g2 + 1) / 2, 1)
                                    - (1 / (a1 * th1 * (1 - g1) * 2 ** ((g1 - 1) / 2))
                                       + 1 / (a2 * th1 * (g2 - 1) * 2 ** ((g2 - 1) / 2)))),
                        "(40) = Lemma 2 (3) with alpha -> theta1 alpha = (26)/theta1"),
             Step("sharper: (T2* - T2(M))/theta1, the exact comparison time from infinity to the "
                  "neighbourhood boundary M", "claims exact-bound, exact-time", "proved")]
    return Claim("T2-practical", "(40)", "Time for s2 to enter its neighbourhood",
                 "T2i <= 1/(alpha1i theta1 (1-g1) 2^((g1-1)/2)) + 1/(alpha2i theta1 (g2-1) "
                 "2^((g2-1)/2))", "Holds (corrected law).", steps, combine(steps), "symbolic",
                 law="corrected")


@cache
def s1_neighborhood_claim() -> Claim:
    resid = sp.diff(M.surface1(), r) * v - (M.reaching_law_rhs(r) + S2)
    steps = [prove_branches(_surface_coords(resid), (r,), "(41): s1' = -beta1 sig(s1,q1) - "
                            "beta2 sig(s1,q2) + s2"),
             Step("once |s2| <= M_i for all later t (claim s2-neighborhood: never left), "
                  "V1i' <= -beta1|s1|^(q1+1) - beta2|s1|^(q2+1) + M_i|s1| (42)",
                  "elementary: s1 s2 <= M_i |s1|", "proved"),
             Step("the argument of claim s2-neighborhood with (beta, q, M_i, theta2) gives "
                  "(44)/(31), "
                  "reached and never left", "claim s2-neighborhood", "proved")]
    return Claim("s1-neighborhood", "(31), (41)-(44)", "Landing-error neighbourhood",
                 "|r_i| <= min{(M_i/((1-theta2)beta1i))^(1/q1), (M_i/((1-theta2)beta2i))^(1/q2)}",
                 "Holds after s2 has entered (39) (corrected law).", steps, combine(steps),
                 "symbolic + direct argument", law="corrected")


@cache
def t1_practical_claim() -> Claim:
    steps = [Step("outside (31), once s2 is in (39): V1' <= -theta2(beta1|s1|^(q1+1) + "
                  "beta2|s1|^(q2+1))", "claim s1-neighborhood", "proved"),
             Step("(45) = (18)/theta2 by Lemma 2 with beta -> theta2 beta", "as in T2-practical",
                  "proved")]
    return Claim("T1-practical", "(45)", "Time for s1 to enter its neighbourhood",
                 "T1i <= 1/(beta1i theta2 (1-q1) 2^((q1-1)/2)) + 1/(beta2i theta2 (q2-1) "
                 "2^((q2-1)/2))",
                 "Holds, counted from the time s2 enters (39), not from t = 0.", steps,
                 combine(steps), "symbolic", law="corrected")


@cache
def t3_claim() -> Claim:
    steps = [Step("T3i = max{T1i, T2i} bounds the time from t = 0 to (31)", "argument check",
                  "refuted", "(45) starts when s2 is inside (39), which takes up to (40); "
                  "before that s1 is driven by an s2 of any size"),
             Step("time from t = 0 to (31) <= (40) + (45) (exact: T2_practical_exact + "
                  "T1_practical_exact)", "claims T2-practical, T1-practical", "proved")]
    return Claim("T3", "(32)", "Time to land in the neighbourhood under disturbance",
                 "T3i <= max{(40), (45)}",
                 "The sound bound is (40) + (45); the paper's max is unproven (its argument is "
                 "invalid; no counterexample searched beyond landing-time).", steps, "unproven",
                 "sum proved, max unproven", law="corrected")


@cache
def paper_numbers_claim() -> Claim:
    t1, t2 = 74.5780, 30.8217  # Part 1
    t2p, t1p = 131.5173, 85.8610  # Part 2, theta1 = 0.2, theta2 = 0.1
    ce = {"(26) Part 1": t2, "(40) Part 2": t2p, "(26)/theta1": t2 / 0.2,
          "(18) Part 1": t1, "(45) Part 2": t1p, "(18)/theta2": t1 / 0.1}
    steps = [prove_zero(sp.Integer(0), "(40) = (26)/theta1 and (45) = (18)/theta2 identically "
                        "(claims T2-practical, T1-practical)"),
             Step("reported (40) = 131.5173 s equals (26)/theta1 = 154.1085 s", "arithmetic",
                  "refuted", str(ce))]
    return Claim("paper-numbers", "Part 1-2 numbers", "Consistency of the paper's reported bounds",
                 "T1 <= 74.5780 s, T2 <= 30.8217 s (Part 1); (40) = 131.5173 s, (45) = 85.8610 s "
                 "with theta1 = 0.2, theta2 = 0.1 (Part 2)",
                 "With one gain set, (40) and (45) are (26)/theta1 = 154.1085 s and (18)/theta2 "
                 "= 745.78 s.  The printed numbers need different, unstated gains in Part 2; "
                 "they are not reference values.", steps, "refuted", "arithmetic",
                 counterexample=ce)


def all_claims() -> list[Claim]:
    """Every claim of seed 000 in report order."""
    claims = [SP.lemma1(), SP.lemma2(), SP.exact_bound_claim(), SP.exact_time_claim(),
              SP.theorem1(), surface_claim(), v1dot_axis_claim(), v1dot_vector_claim(),
              t1_claim(), s2dot_claim(), s2dot24_claim(), v2dot_claim("printed"),
              v2dot_claim("corrected"), laws_agree_claim(), t2_claim("printed"),
              t2_claim("corrected"), landing_claim(), remark1_claim(),
              bounded_command_claim("printed"), bounded_command_claim("corrected"),
              v2dot_disturbed_claim("printed"), v2dot_disturbed_claim("corrected"),
              s2_neighborhood_claim(), t2_practical_claim(), s1_neighborhood_claim(),
              t1_practical_claim(), t3_claim(), paper_numbers_claim()]
    return claims

