"""Falsification searches for seed 000's quantitative claims on the reduced per-axis dynamics.

Every problem here is a margin (bound minus observed, relative to the bound; < 0 violates) over
the whole valid range of one axis' gains and exponents and of the initial surfaces, minimised by
``lgw.theory.falsify``.  The per-axis reduction is exact for these claims: the axes decouple,
g and a_m cancel exactly in the law (claims V2dot-corrected, s2dot), and in surface coordinates
the closed loop of the corrected law is (``lgw.theory.mars.reduced``)

    s1' = s2 - f1(s1),  f1(s) = beta1 sig(s,q1) + beta2 sig(s,q2)          seed 000 (41)
    s2' = -f2(s2) + a_p,  f2(s) = alpha1 sig(s,g1) + alpha2 sig(s,g2)     (25'), (33)

(the printed law (25) adds (beta1 q1|s1|^(q1-1) + beta2 q2|s1|^(q2-1)) s2 to s2', claim
s2dot-24).  The bounds come from ``lgw.theory.mars.bounds`` at every evaluation, so editing a
bound there changes what these searches test.

The box (one axis; "the valid range" with stated ends, the open ends of the hypotheses can only
be approached): beta1, beta2, alpha1, alpha2 log-uniform in [1e-3, 1e2]; q1, g1 in
[0.02, 0.98]; q2, g2 in [1.02, 4]; s1(0), s2(0) of either sign with magnitudes log-uniform in
[1e-3, 1e9] (m, m/s); with disturbance a_max log-uniform in [1e-3, 1e2] m/s^2, theta1, theta2
in [0.02, 0.98].

Disturbance model ("worst case"): a_p = a_max sgn(s2), which by the comparison principle makes
|s2(t)| the largest any |a_p| <= a_max allows at every t, and whose s2 never changes sign; for
the conditional claims (31)/(45) ("once s2 is in (39)") the adversary is the constant s2 = M
sgn(s1), the worst the hypothesis |s2| <= M admits.

Routes: each problem has a fast route (closed form, quadrature or a moderate-tolerance ODE) for
the search and an independent re-check (tight LSODA integration, quadrature, or the SymPy
closed loop of ``lgw.theory.mars.mss``) for the witness.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
import sympy as sp
from lgw.theory.evidence import Search, Step
from lgw.theory.falsify import Budget, Dim, Problem, falsify
from lgw.theory.mars import bounds as B
from lgw.theory.mars import mss as M
from lgw.theory.mars.gains import Gains, gains_from_dict
from lgw.theory.mars.reduced import surface_trajectory, trajectory
from lgw.theory.settling import exact_bound
from lgw.theory.symbolic import LAMBDIFY_MODULES, memo
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

GAIN_DIMS = (Dim("beta1", 1e-3, 1e2, "log"), Dim("beta2", 1e-3, 1e2, "log"),
             Dim("alpha1", 1e-3, 1e2, "log"), Dim("alpha2", 1e-3, 1e2, "log"),
             Dim("q1", 0.02, 0.98), Dim("q2", 1.02, 4.0),
             Dim("g1", 0.02, 0.98), Dim("g2", 1.02, 4.0))
STATE_DIMS = (Dim("s1_0", 1e-3, 1e9, "signed-log"), Dim("s2_0", 1e-3, 1e9, "signed-log"))
DIST_DIMS = (Dim("a_max", 1e-3, 1e2, "log"), Dim("theta1", 0.02, 0.98),
             Dim("theta2", 0.02, 0.98))
GAIN_KEYS = tuple(d.name for d in GAIN_DIMS)

# The budget of the full-domain searches (popsize x dims per DE generation).
FULL = Budget(popsize=8, maxiter=25, local_evals=150, seed=0)


def gains_of(p: Mapping[str, float]) -> Gains:
    """The (validated) gain set of a search point: the same gains on every axis."""
    d: dict = {"gains": {k: float(p[k]) for k in GAIN_KEYS}}
    if "a_max" in p:
        d["disturbance"] = {k: float(p[k]) for k in ("a_max", "theta1", "theta2")}
    return gains_from_dict(d)


def bound(p: Mapping[str, float], key: str) -> float:
    """``lgw.theory.mars.bounds.axis_bounds`` at the point (axis x), key as there."""
    return B.axis_bounds(gains_of(p))["x"][key]


RHS_CAP = 20_000  # right-side evaluations per fast-route integration (then: a failed evaluation)


def _capped(rhs, cap: int = RHS_CAP):
    """rhs that raises RuntimeError after ``cap`` calls: a stiff corner of the box costs a
    counted failed evaluation, not the whole budget."""
    n = [0]

    def f(t, y):
        n[0] += 1
        if n[0] > cap:
            raise RuntimeError(f"fast route exceeded {cap} right-side evaluations")
        return rhs(t, y)
    return f


def _sig(x: float, q: float) -> float:
    return math.copysign(abs(x) ** q, x)


def _f(s: float, k1: float, k2: float, e1: float, e2: float) -> float:
    return k1 * _sig(s, e1) + k2 * _sig(s, e2)


def quad_time(lo: float, hi: float, k1: float, k2: float, e1: float, e2: float,
              push: float = 0.0) -> float:
    """int_lo^hi dx / (k1 x^e1 + k2 x^e2 - push) by quadrature in log x (0 <= lo < hi); the
    denominator must stay > 0 on (lo, hi].  Independent of the incomplete-Beta closed form."""
    if hi <= lo:
        return 0.0

    def g(y: float) -> float:  # x dy-form: 1/(k1 x^(e1-1) + k2 x^(e2-1) - push/x), x = e^y
        u1, u2 = (e1 - 1) * y, (e2 - 1) * y
        if max(u1, u2) > 700.0:
            return 0.0
        den = k1 * math.exp(u1) + k2 * math.exp(u2) - (push * math.exp(-y) if push else 0.0)
        return 1.0 / den

    y_hi = math.log(hi)
    y_lo = math.log(lo) if lo > 0 else -math.inf
    y_pk = math.log(k1 / k2) / (e2 - e1)  # where the two terms are equal
    pts = sorted({min(max(y_pk, y_lo), y_hi), y_hi})
    total = 0.0
    a = y_lo
    for b in pts:
        if b > a:
            val, _ = quad(g, a, b, limit=400, epsabs=0.0, epsrel=1e-11)
            total += val
        a = max(a, b)
    return total


# --- (18), (26), T1*, T2*: the reaching law alone ------------------------------------------

def _reaching_problem(name: str, key: str, surface: str, scale: float = 1.0) -> Problem:
    """Time for s' = -f(s) from |s(0)| to 0 against ``key`` (T1_polyakov, T1_exact, ...)."""
    k = ("beta1", "beta2", "q1", "q2") if surface == "s1" else ("alpha1", "alpha2", "g1", "g2")
    dims = tuple(d for d in GAIN_DIMS if d.name in k) + (Dim("s0", 1e-3, 1e12, "log"),)
    rest = {d.name: 1.0 if d.scale == "log" else (d.lo + d.hi) / 2 for d in GAIN_DIMS
            if d.name not in k}

    def margin(p):
        t_b = bound({**rest, **p}, key) * scale
        t = float(B.reaching_time(np.array([p["s0"]]), *(p[x] for x in k))[0])
        return (t_b - t) / t_b

    def recheck(p):
        t_b = bound({**rest, **p}, key) * scale
        return (t_b - quad_time(0.0, p["s0"], *(p[x] for x in k))) / t_b

    return Problem(name, dims, margin, recheck,
                   route="exact time T(s0) (incomplete Beta, lgw.theory.settling)",
                   recheck_method="adaptive quadrature of int_0^s0 ds/f(s) in log s "
                                  "(scipy quad, rtol 1e-11)", fixed=rest)


# --- the landing time: s2 to 0, then s1 by (16) -------------------------------------------

def landing_time_fast(p: Mapping[str, float]) -> float:
    """Exact landing time of the reduced corrected loop (no disturbance): T(|s2(0)|) for s2,
    plus T(|s1(T2)|) of (16) for s1, s1(T2) from integrating (41) with |s2| as the
    independent variable (y = ln|s2|, LSODA rtol 1e-9), where s2's own time is exact."""
    a1, a2, g1, g2 = p["alpha1"], p["alpha2"], p["g1"], p["g2"]
    b1, b2, q1, q2 = p["beta1"], p["beta2"], p["q1"], p["q2"]
    s1, s2 = p["s1_0"], p["s2_0"]
    t2 = float(B.reaching_time(np.array([s2]), a1, a2, g1, g2)[0])
    if s2 != 0.0:
        sg = math.copysign(1.0, s2)

        def rhs(y, x):
            sig_ = math.exp(y)
            return [-sig_ * (sg * sig_ - _f(x[0], b1, b2, q1, q2))
                    / (a1 * sig_**g1 + a2 * sig_**g2)]

        # stop where the rest of s2's approach takes < 1e-10 of its time (or at 1e-300)
        y_end = max(math.log(1e-10 * t2 * a1 * (1 - g1)) / (1 - g1), -690.0)
        y0 = math.log(abs(s2))
        if y_end < y0:
            sol = None
            for method in ("LSODA", "Radau"):  # Radau where LSODA gives up (s1 stuck at 0)
                try:
                    sol = solve_ivp(_capped(rhs), (y0, y_end), [s1], method=method, rtol=1e-9,
                                    atol=1e-12)
                except RuntimeError:
                    continue
                if sol.success:
                    break
            if sol is None or not sol.success:
                raise RuntimeError("landing fast route: LSODA and Radau failed")
            s1 = float(sol.y[0, -1])
    t1 = float(B.reaching_time(np.array([s1]), b1, b2, q1, q2)[0])
    return t2 + t1


def landing_time_reference(p: Mapping[str, float]) -> float:
    """The same landing time from ``lgw.theory.mars.reduced.surface_trajectory`` (time
    domain, (s1, w2) coordinates, LSODA rtol 1e-11, terminal events): the last grid node with
    s1 or s2 nonzero, plus one grid step (the true time is within that step, so this errs on
    the long side by at most one step: a re-checked violation is not made by the grid)."""
    # horizon: 1.05 (T2* + T1*) from lgw.theory.settling directly (the proven supremum; not
    # from lgw.theory.mars.bounds, which a test may have edited)
    t_guess = 1.05 * _sum_star(p) + 1e-9
    gd = {k: p[k] for k in GAIN_KEYS}
    tr = surface_trajectory("corrected", gd, p["s1_0"], p["s2_0"], t_guess, n_out=40001)
    nz = np.flatnonzero((tr["s1"] != 0.0) | (tr["s2"] != 0.0))
    if len(nz) == len(tr["t"]):
        return math.inf
    h = tr["t"][1] - tr["t"][0]
    return float(tr["t"][nz[-1]]) + h if len(nz) else 0.0


def _landing_problem(name: str, bound_fn: Callable[[Mapping[str, float]], float],
                     dims=GAIN_DIMS + STATE_DIMS, fixed=None) -> Problem:
    def margin(p):
        b = bound_fn(p)
        return (b - landing_time_fast(p)) / b

    def recheck(p):
        b = bound_fn(p)
        # the reference can only shorten the observed time by < one grid step; for a witness
        # take its *shortest* admissible landing time (the node before the last nonzero one)
        t = landing_time_reference(p)
        h = 1.05 * _sum_star(p) / 40000
        return (b - (t - 2 * h)) / b

    return Problem(name, dims, margin, recheck,
                   route="exact s2 time + (41) integrated in ln|s2| (LSODA 1e-9) + exact (16) "
                         "time of s1",
                   recheck_method="lgw.theory.mars.reduced.surface_trajectory (time domain, "
                                  "LSODA rtol 1e-11, events at s2 = 0 and s1 = 0), shortest "
                                  "time the 40001-node grid allows",
                   fixed=dict(fixed or {}))


def _sum_star(p) -> float:
    return float(exact_bound(p["alpha1"], p["alpha2"], p["g1"], p["g2"])
                 + exact_bound(p["beta1"], p["beta2"], p["q1"], p["q2"]))


def _max_paper(p):
    return max(bound(p, "T1_polyakov"), bound(p, "T2_polyakov"))


def _max_exact(p):
    return max(bound(p, "T1_exact"), bound(p, "T2_exact"))


def _sum_exact(p):
    return bound(p, "landing_time_bound")


# --- the printed law (25): s2 by T2 (26)? ---------------------------------------------------

def printed_s2_at(p: Mapping[str, float], t_end: float) -> tuple[float, float]:
    """(t_hit, |s2(t_end)|) for the printed law's reduced loop: the time s2 reaches 0 (inf if
    not by t_end) and |s2| at t_end.  (s1, w2 = sig(s2, 1-g1)) coordinates, RK45 rtol 1e-8 with
    a terminal event at w2 = 0 (w2 reaches 0 transversally, as in lgw.theory.mars.reduced).
    The law's drift in s2' is computed from the law (``mss.s2_drift_numeric``)."""
    a1, a2, g1, g2 = p["alpha1"], p["alpha2"], p["g1"], p["g2"]
    b1, b2, q1, q2 = p["beta1"], p["beta2"], p["q1"], p["q2"]
    s2_0 = p["s2_0"]
    if s2_0 == 0.0:
        return 0.0, 0.0
    sg = math.copysign(1.0, s2_0)
    drift = M.s2_drift_numeric("printed")
    gargs = tuple(float(p[k]) for k in GAIN_KEYS)

    def rhs(t, y):
        x1, w2 = y
        z2 = sg * abs(w2) ** (1 / (1 - g1))
        d1 = z2 - _f(x1, b1, b2, q1, q2)
        dw = (1 - g1) * (-a1 * sg - a2 * sg * abs(z2) ** (g2 - g1))
        if drift is not None and z2 != 0.0:
            dw += (1 - g1) * abs(z2) ** (-g1) * drift(x1, z2, *gargs)
        return [d1, dw]

    def hit(t, y):
        return y[1]
    hit.terminal = True
    sol = solve_ivp(_capped(rhs), (0.0, t_end), [p["s1_0"], _sig(s2_0, 1 - g1)],
                    method="RK45", rtol=1e-8, atol=1e-10, events=hit)
    if sol.status < 0:
        raise RuntimeError(sol.message)
    if sol.t_events[0].size:
        return float(sol.t_events[0][0]), 0.0
    return math.inf, abs(float(sol.y[1, -1])) ** (1 / (1 - g1))


def _printed_problem(name: str = "T2-printed") -> Problem:
    def t2(p):
        return bound(p, "T2_polyakov")

    def margin(p):
        tb = t2(p)
        t_hit, s2_end = printed_s2_at(p, tb)
        if math.isfinite(t_hit):
            return (tb - t_hit) / tb
        # not at 0 by T2: violated by the relative size of what is left (>= 1e-6: not a
        # solver's crumb)
        left = s2_end / (1.0 + abs(p["s2_0"]))
        return -left if left > 1e-6 else 0.0

    def recheck(p):
        tb = t2(p)
        gd = {k: p[k] for k in GAIN_KEYS}
        r0 = p["s1_0"]
        v0 = p["s2_0"] - _f(r0, gd["beta1"], gd["beta2"], gd["q1"], gd["q2"])
        tr = trajectory("printed", gd, r0, v0, tb, n_out=2001)
        tol = 1e-6 * (1.0 + abs(p["s2_0"]))
        at0 = np.flatnonzero(np.abs(tr["s2"]) <= tol)
        if at0.size:
            return (tb - float(tr["t"][at0[0]])) / tb
        return -abs(float(tr["s2"][-1])) / (1.0 + abs(p["s2_0"]))

    return Problem(name, GAIN_DIMS + STATE_DIMS, margin, recheck,
                   route="printed law (25) reduced to (s1, sig(s2,1-g1)), RK45 rtol 1e-8, "
                         "event at s2 = 0",
                   recheck_method="lgw.theory.mars.reduced.trajectory: the SymPy law (25) in "
                                  "(r, v), LSODA rtol = atol = 1e-10; s2 not within 1e-6 "
                                  "(1 + |s2(0)|) of 0 on [0, T2]")


# --- (39), (40): s2 under the worst disturbance --------------------------------------------

def _root(k1, k2, e1, e2, c) -> float:
    """x > 0 with k1 x^e1 + k2 x^e2 = c (the equilibrium of a constant push c)."""
    hi = 1.0
    while k1 * hi**e1 + k2 * hi**e2 < c:
        hi *= 2.0
    lo = hi
    while k1 * lo**e1 + k2 * lo**e2 > c and lo > 1e-300:
        lo /= 2.0
    return brentq(lambda x: k1 * x**e1 + k2 * x**e2 - c, lo, hi, xtol=1e-300, rtol=1e-14)


DIST_GAIN = GAIN_DIMS + DIST_DIMS
REPRESENTABLE = (1e-250, 1e250)


def representable(p: Mapping[str, float]) -> bool:
    """The bands (39), (31) of the point are ordinary floats.  With g1 or q1 near 0 the
    powers 1/g1, 1/q1 of (39)/(31) under- or overflow (a band of 1e-1070 m is computed as 0,
    which no trajectory can enter): such points are outside what float64 can decide, and are
    counted as such by the engine, not as violations."""
    b = B.axis_bounds(gains_of(p))["x"]
    lo, hi = REPRESENTABLE
    return all(lo < b[k] < hi for k in ("s2_bound", "s1_bound"))


RESOLVABLE = 1e-6  # m, m/s


def resolvable(p: Mapping[str, float]) -> bool:
    """For the entry times: both bands >= 1e-6 (m, m/s).  With q1, g1 near 0 the bands reach
    1e-100 and below; whether a float64 integration from |s| ~ 1e9 enters such a band is
    decided by the integrator's tolerances, not by the loop (both routes then report 'never
    entered'), so these points are counted as outside what can be decided."""
    b = B.axis_bounds(gains_of(p))["x"]
    return all(RESOLVABLE <= b[k] < REPRESENTABLE[1] for k in ("s2_bound", "s1_bound"))


@memo
def _s2dot_numeric():
    """s2' of the SymPy closed loop (corrected law, disturbance a_p) as a function of
    (s1, s2, a_p, gains): an independent route to the band's invariance."""
    s2 = sp.Symbol("s2", real=True)
    e = M.closed_loop("corrected").s2dot.subs(M.v, s2 + M.reaching_law_rhs(M.r))
    f = sp.lambdify((M.r, s2, M.ap, *M.GAIN_SYMBOLS), e, LAMBDIFY_MODULES)
    return lambda *a: float(f(*a))


def _s2_band_problem(scale: float = 1.0) -> Problem:
    def margin(p):
        m = bound(p, "s2_bound") * scale
        m_eq = _root(p["alpha1"], p["alpha2"], p["g1"], p["g2"], p["a_max"])
        return (m - m_eq) / m

    def recheck(p):
        m = bound(p, "s2_bound") * scale
        f = _s2dot_numeric()
        rate = f(1.0, m, p["a_max"], *(p[k] for k in GAIN_KEYS))  # a_p = a_max sgn(s2), s2 = M
        return -rate / p["a_max"]  # < 0: pushed out of the band at its edge

    return Problem("s2-neighborhood", DIST_GAIN, margin, recheck, valid=representable,
                   route="equilibrium of s2' = -f2(s2) + a_max (brentq): the sup of |s2| "
                         "under |a_p| <= a_max once inside",
                   recheck_method="sign of s2' of the SymPy closed loop (lgw.theory.mars.mss, "
                                  "corrected law) at s2 = M with a_p = a_max: outward > 0")


def _t2_practical_problem(key: str, scale: float = 1.0) -> Problem:
    dims = DIST_GAIN + (Dim("s2_0", 1e-3, 1e12, "log"),)

    def observed(p) -> float:
        m = bound(p, "s2_bound")
        if p["a_max"] >= p["alpha1"] * m ** p["g1"] + p["alpha2"] * m ** p["g2"]:
            return math.inf  # the band is never entered from outside
        return quad_time(m, p["s2_0"], p["alpha1"], p["alpha2"], p["g1"], p["g2"], p["a_max"])

    def margin(p):
        tb = bound(p, key) * scale
        t = observed(p)
        return max((tb - t) / tb, -1.0) if math.isfinite(t) else -1.0

    def recheck(p):
        tb = bound(p, key) * scale
        m = bound(p, "s2_bound")
        a1, a2, g1, g2, am = (p[k] for k in ("alpha1", "alpha2", "g1", "g2", "a_max"))
        if p["s2_0"] <= m:
            return 1.0

        def ev(t, y):
            return y[0] - m
        ev.terminal = True
        sol = solve_ivp(lambda t, y: [-a1 * y[0] ** g1 - a2 * y[0] ** g2 + am],
                        (0.0, 2.0 * tb), [p["s2_0"]], method="LSODA", rtol=1e-11,
                        atol=1e-12 * m, events=ev)
        t = float(sol.t_events[0][0]) if sol.t_events[0].size else math.inf
        return max((tb - t) / tb, -1.0) if math.isfinite(t) else -1.0

    return Problem("T2-practical", dims, margin, recheck, valid=resolvable,
                   route="entry time into (39) under a_p = a_max sgn(s2): quadrature of "
                         "ds/(f2(s) - a_max) from M to s2(0)",
                   recheck_method="LSODA (rtol 1e-11) on s2' = -f2(s2) + a_max, event at M")


# --- (31), (45): s1 once s2 is in (39) ----------------------------------------------------

def _s1_band_problem(scale: float = 1.0) -> Problem:
    def margin(p):
        n = bound(p, "s1_bound") * scale
        m = bound(p, "s2_bound")
        n_eq = _root(p["beta1"], p["beta2"], p["q1"], p["q2"], m)
        return (n - n_eq) / n

    def recheck(p):
        n = bound(p, "s1_bound") * scale
        m = bound(p, "s2_bound")
        s1dot = float(M.reaching_law_rhs(M.r).subs({M.r: n, M.beta1: p["beta1"],
                                                     M.beta2: p["beta2"], M.q1: p["q1"],
                                                     M.q2: p["q2"]})) + m
        return -s1dot / m

    return Problem("s1-neighborhood", DIST_GAIN, margin, recheck, valid=representable,
                   route="equilibrium of s1' = M - f1(s1) (brentq), M the (39) bound",
                   recheck_method="sign of s1' = (16) + M at s1 = N, (16) from the SymPy "
                                  "reaching law (lgw.theory.mars.mss)")


def _t1_practical_problem(key: str, scale: float = 1.0) -> Problem:
    dims = DIST_GAIN + (Dim("s1_e", 1e-3, 1e12, "log"),)

    def margin(p):
        tb = bound(p, key) * scale
        n, m = bound(p, "s1_bound"), bound(p, "s2_bound")
        if m >= p["beta1"] * n ** p["q1"] + p["beta2"] * n ** p["q2"]:
            return -1.0
        t = quad_time(n, p["s1_e"], p["beta1"], p["beta2"], p["q1"], p["q2"], m)
        return max((tb - t) / tb, -1.0)

    def recheck(p):
        tb = bound(p, key) * scale
        n, m = bound(p, "s1_bound"), bound(p, "s2_bound")
        b1, b2, q1, q2 = (p[k] for k in ("beta1", "beta2", "q1", "q2"))
        if p["s1_e"] <= n:
            return 1.0

        def ev(t, y):
            return y[0] - n
        ev.terminal = True
        sol = solve_ivp(lambda t, y: [m - b1 * y[0] ** q1 - b2 * y[0] ** q2], (0.0, 2.0 * tb),
                        [p["s1_e"]], method="LSODA", rtol=1e-11, atol=1e-12 * n, events=ev)
        t = float(sol.t_events[0][0]) if sol.t_events[0].size else math.inf
        return max((tb - t) / tb, -1.0) if math.isfinite(t) else -1.0

    return Problem("T1-practical", dims, margin, recheck, valid=resolvable,
                   route="entry time of s1 into (31) from s1 at s2's entry into (39), s2 = M "
                         "sgn(s1) (the worst (39) admits): quadrature",
                   recheck_method="LSODA (rtol 1e-11) on s1' = M - f1(s1), event at N")


# --- T3 (32) and the sound sum (40) + (45) under the worst disturbance, from t = 0 --------

def disturbed_entry_time(p: Mapping[str, float], t_end: float, rtol: float = 1e-8,
                         method: str = "LSODA", cap: int = RHS_CAP) -> float:
    """First time after s2 has entered (39) that |s1| <= (31), from t = 0, under a_p = a_max
    sgn(s2) (s2 keeps its sign; no non-Lipschitz point is crossed by s2).  inf if not by
    t_end.  Raw (s1, s2) coordinates, events at |s2| = M and then |s1| = N."""
    a1, a2, g1, g2 = p["alpha1"], p["alpha2"], p["g1"], p["g2"]
    b1, b2, q1, q2 = p["beta1"], p["beta2"], p["q1"], p["q2"]
    am = p["a_max"]
    m, n = bound(p, "s2_bound"), bound(p, "s1_bound")
    sg = math.copysign(1.0, p["s2_0"])

    def rhs0(t, y):
        return [y[1] - _f(y[0], b1, b2, q1, q2), -_f(y[1], a1, a2, g1, g2) + am * sg]
    rhs = _capped(rhs0, cap)

    y0 = [p["s1_0"], p["s2_0"]]
    # absolute tolerances well inside the bands, which can be far below 1 (a band of 1e-10
    # with atol 1e-10 is an event the solver cannot see)
    atol = [min(1e-10 * (1 + abs(y0[0])), 1e-4 * n), min(1e-10 * (1 + abs(y0[1])), 1e-4 * m)]
    t0 = 0.0
    if abs(y0[1]) > m:
        def in2(t, y):
            return abs(y[1]) - m
        in2.terminal = True
        sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, events=in2)
        if not sol.t_events[0].size:
            return math.inf
        t0, y0 = float(sol.t_events[0][0]), list(sol.y_events[0][0])
    if abs(y0[0]) <= n:
        return t0

    def in1(t, y):
        return abs(y[0]) - n
    in1.terminal = True
    sol = solve_ivp(rhs, (t0, t_end), y0, method=method, rtol=rtol, atol=atol, events=in1)
    return float(sol.t_events[0][0]) if sol.t_events[0].size else math.inf


def _disturbed_landing_problem(name: str, bound_fn) -> Problem:
    def run(p, rtol, method):
        tb = bound_fn(p)
        t = disturbed_entry_time(p, 1.2 * tb, rtol=rtol, method=method,
                                 cap=RHS_CAP if method == "LSODA" else 50 * RHS_CAP)
        return max((tb - t) / tb, -1.0) if math.isfinite(t) else -0.2

    return Problem(name, DIST_GAIN + STATE_DIMS, lambda p: run(p, 1e-8, "LSODA"),
                   lambda p: run(p, 1e-10, "Radau"), valid=resolvable, confirm_negatives=True,
                   route="(s1, s2) under a_p = a_max sgn(s2), LSODA rtol 1e-8, events at (39) "
                         "then (31)",
                   recheck_method="the same loop with Radau (implicit Runge-Kutta) rtol 1e-10")


def _t3_paper(p):
    return bound(p, "T3_paper")


def _t3_sum(p):
    return bound(p, "landing_time_bound_disturbed")


# --- registry ------------------------------------------------------------------------------

def problems() -> dict[str, tuple[str, Problem]]:
    """Search id -> (claim id of lgw.theory.mars.claims, problem), on the full valid domain."""
    return {
        "T1": ("T1", _reaching_problem("T1 (18)", "T1_polyakov", "s1")),
        "T1*": ("exact-bound", _reaching_problem("T1*", "T1_exact", "s1")),
        "T2-corrected": ("T2-corrected", _reaching_problem("T2 (26)", "T2_polyakov", "s2")),
        "T2*": ("exact-bound", _reaching_problem("T2*", "T2_exact", "s2")),
        "T2-printed": ("T2-printed", _printed_problem()),
        "landing-time": ("landing-time", _landing_problem("max{T1 (18), T2 (26)}",
                                                          _max_paper)),
        "landing-max-exact": ("landing-time", _landing_problem("max{T1*, T2*}", _max_exact)),
        "landing-sum": ("landing-time", _landing_problem("T1* + T2*", _sum_exact)),
        "s2-neighborhood": ("s2-neighborhood", _s2_band_problem()),
        "T2-practical": ("T2-practical", _t2_practical_problem("T2_practical")),
        "T2-practical-exact": ("T2-practical", _t2_practical_problem("T2_practical_exact")),
        "s1-neighborhood": ("s1-neighborhood", _s1_band_problem()),
        "T1-practical": ("T1-practical", _t1_practical_problem("T1_practical")),
        "T1-practical-exact": ("T1-practical", _t1_practical_problem("T1_practical_exact")),
        "T3": ("T3", _disturbed_landing_problem("max{(40), (45)} (32)", _t3_paper)),
        "T3-sum": ("T3", _disturbed_landing_problem("(40) + (45) exact", _t3_sum)),
    }


# The search that decides each claim's statement as the paper prints it (the others are
# the workbench's sharper or sound variants, exposed by search_steps()).
PAPER_SEARCH = {"T1": "T1", "exact-bound": "T1*", "T2-corrected": "T2-corrected",
                "T2-printed": "T2-printed", "landing-time": "landing-time",
                "s2-neighborhood": "s2-neighborhood", "T2-practical": "T2-practical",
                "s1-neighborhood": "s1-neighborhood", "T1-practical": "T1-practical",
                "T3": "T3"}

STATEMENTS = {
    "T1": "no initial s1 takes longer than (18) to reach 0 under (16)",
    "T1*": "no initial s1 takes longer than T1* to reach 0 under (16)",
    "T2-corrected": "no initial s2 takes longer than (26) to reach 0 (corrected law)",
    "T2*": "no initial s2 takes longer than T2* to reach 0 (corrected law)",
    "T2-printed": "under the printed law (25) s2 reaches 0 within (26) from every state",
    "landing-time": "no initial state lands later than max{T1 (18), T2 (26)} (the paper)",
    "landing-max-exact": "no initial state lands later than max{T1*, T2*}",
    "landing-sum": "no initial state lands later than T1* + T2* (the workbench's bound)",
    "s2-neighborhood": "|s2| never exceeds (39) once inside, whatever |a_p| <= a_max",
    "T2-practical": "|s2| enters (39) within (40) under the worst |a_p| <= a_max",
    "T2-practical-exact": "|s2| enters (39) within T2_practical_exact under the worst a_p",
    "s1-neighborhood": "|s1| never exceeds (31) once inside, while |s2| <= (39)",
    "T1-practical": "|s1| enters (31) within (45) of s2 entering (39)",
    "T1-practical-exact": "|s1| enters (31) within T1_practical_exact of s2 entering (39)",
    "T3": "|s1| enters (31) within max{(40), (45)} (32) from t = 0 (the paper)",
    "T3-sum": "|s1| enters (31) within (40) + (45) (exact) from t = 0 (the workbench's bound)",
}


@memo
def run(search_id: str, budget: Budget = FULL) -> Search:
    """The falsification run of one search (cached per budget)."""
    return falsify(problems()[search_id][1], budget)


# The worst points the FULL-budget runs found (docs/verify.md, "Measured: the full-domain
# searches"), as starting points for a re-run at a smaller budget: the optimiser begins where
# the larger run ended (``falsify``'s ``starts``).  They are only where the search starts:
# every margin is computed again from the bounds and the dynamics in force, and a witness is
# re-checked by the independent route as always.
KNOWN_STARTS: dict[str, tuple[dict[str, float], ...]] = {
    "T3": ({"beta1": 0.1, "beta2": 0.08, "alpha1": 3.0, "alpha2": 0.9, "q1": 0.6, "q2": 4.0,
            "g1": 0.4, "g2": 1.08, "a_max": 0.01, "theta1": 0.66, "theta2": 0.98,
            "s1_0": -2000.0, "s2_0": -1e8},),
}


@memo
def run_from_known(search_id: str, budget: Budget = FULL) -> Search:
    """``run`` started from the worst points of the FULL-budget run (``KNOWN_STARTS``)."""
    return falsify(problems()[search_id][1], budget, starts=KNOWN_STARTS.get(search_id, ()))


def search_steps(budget: Budget = FULL) -> dict[str, Step]:
    """Every search as a Step, keyed by search id (see ``problems``)."""
    return {sid: Step(STATEMENTS[sid], run(sid, budget)) for sid in problems()}


def full_domain_steps(budget: Budget = FULL) -> dict[str, Step]:
    """The full-domain search Step for each claim id of ``lgw.theory.mars.claims`` (the
    search of the claim as printed; ``search_steps`` has the sound variants too)."""
    return {cid: Step(STATEMENTS[sid], run(sid, budget)) for cid, sid in PAPER_SEARCH.items()}
