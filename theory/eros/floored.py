"""The FTSMC (19) as it is flown, floor included: per-axis time and command bounds, proven.

The law (``lgw.theory.eros.laws.control("ftsmc", "sign")``, the implemented form): per axis

    u = -(f + D_k - xdd) - e' G(e) - k sgn(s),   G(e) = alpha + beta r max(|e|, e_f)^(r - 1),
    s = e' + alpha e + beta sig(e)^r                                      (seed 002 (6), (19))

with r = p/q, e_f = ``e_floor``.  Without the floor the command is unbounded: e' |e|^(r-1) is
singular at e = 0, and from e(0) = 0, e'(0) = v0 != 0 the command is infinite at t = 0 (claim
singular-term).  The floor is what makes the command bounded, and it changes the dynamics
near e = 0, so the bounds of ``lgw.theory.eros.bounds`` (for the unfloored surface) are not
the flown law's.  Here the flown law is analysed exactly (continuous time, Filippov
solutions of the sign switch), on one axis, with |D - D_k| <= d (d = 0: D known, the paper's
(14); d = dbar: D unknown) and the drift f the controller cancels equal to the plant's (the
tracking scenario: the same two-point gravity and rotating terms in both).

The floored surface.  Phi(x) = integral_0^x r max(y, e_f)^(r-1) dy (x >= 0, odd extension):
Phi(x) = r e_f^(r-1) x for x <= e_f, x^r - (1 - r) e_f^r beyond; h(x) = alpha x + beta Phi(x),
sigma = e' + h(e).  Then, exactly,

    sigma' = e'' + e' G(e) = -k sgn(s) + (D - D_k),      |s - sigma| <= delta = beta (1-r) e_f^r

(1) Reaching.  Where |sigma| > delta, sgn(s) = sgn(sigma) and d|sigma|/dt <= -(k - d): the band
    |sigma| <= delta is reached by t_r = (|sigma0| - delta)^+ / (k - d) and never left.  So
    |sigma| <= S = max(|sigma0|, delta) throughout.
(1b) The paper's surface s.  Until s changes sign, sgn(s) = sgn(s0) and sigma moves against it
    at a rate >= k - d; s = sigma + beta (sig(e)^r - Phi(e)) has the sign of sigma once sigma
    is past -sgn(s0) delta, so s reaches 0 (or changes sign) by
    t_r(s) = (sgn(s0) sigma0 + delta)^+ / (k - d)  (``s_reach_time``; |s0|/(k - d) when e_f
    = 0, seed 002 (18)).
(2) Position.  d|e|/dt <= |sigma| - h(|e|): |e| <= E = max(|e0|, h^-1(S)).
(3) Tracking.  After t_r, d|e|/dt <= delta - h(|e|) < 0 wherever h(|e|) > delta: |e| falls from
    E to the tracking tolerance tol (when h(tol) > delta) within
    t_s = integral_tol^E dx / (h(x) - delta), and stays within tol.  t_track <= t_r + t_s.
(4) Velocity.  While sigma > delta (so s > 0): e'' = -k + (D - D_k) - G(e) e', so e' >= 0
    gives e'' < 0: e' <= max(e'0, 0); and e' > delta - h(e), so e' < 0 only with e > 0 and
    |e'| < h(e) - delta.  Symmetrically for sigma < -delta.  In the band, |e'| <=
    delta + h(|e|).  Hence on every reachable state |e'| G(e) <= max(|e'0| G(e_f),
    (h(|e|) + delta) G(|e|)).
(5) Command.  |u| <= F + k + max(|e'0| G(e_f), max_{0 <= x <= E} (h(x) + delta) G(x)), F a
    bound on |f + D_k - xdd| along the run (``drift_bound``).

Over an envelope |e0| <= e_max, |e'0| <= v_max (each axis), every quantity above grows with
|sigma0| <= v_max + h(e_max), |e0| and |e'0|, all largest at the corner e0 = e_max,
e'0 = v_max: the envelope's bound is the corner's (``envelope_bound``).

Evaluation.  Every number is an upper bound computed in Arb ball arithmetic (python-flint):
the two integrals and the maximum are sums over cells (a geometric grid) of the integrand or
the product at the cell's worst end (h increases, G and 1/(h - delta) decrease), and h^-1 is
bracketed by bisection on enclosures.  ``screen=True`` does the same in floats, for the
tuner's grid; what a certificate states is always the Arb result.

What is not covered: the zero-order hold of the 0.01 s sampled loop (the bound is for the
continuous-time law; the sampled loop is checked by simulation), and a plant whose drift
differs from the controller's (e.g. the polyhedral gravity: its difference is an unknown
disturbance to add to d).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from functools import cache
from typing import Any

import numpy as np
from lgw.theory.eros import parameters as P

CELLS = 400  # geometric cells per integral / maximum (the sum over-estimates by ~ ln(ratio)/CELLS)
SQRT3 = math.sqrt(3.0)


@dataclass(frozen=True)
class AxisBound:
    """Proven bounds of one axis from |e0|, |e'0| (module docstring); times in s, command in
    m/s^2.  ``inf`` where a hypothesis fails (k <= d, or h(tol) <= delta)."""

    e0: float
    ed0: float
    sigma0: float  # |sigma(0)|, m/s
    delta: float  # m/s, the floor's surface offset beta (1-r) e_f^r
    g_max: float  # 1/s, G(e_f)
    S: float  # m/s, bound on |sigma|
    E: float  # m, bound on |e|
    V: float  # m/s, bound on |e'|
    t_reach: float
    t_slide: float
    t_total: float
    ed_g: float  # m/s^2, bound on |e' G(e)|
    drift: float  # m/s^2, the F used
    k: float
    u: float  # m/s^2, bound on |u|
    tol: float  # m, tracking tolerance
    dm: float  # m/s^2, |D - D_k| bound

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


class _Arb:
    """Arb balls: ``up``/``low`` are floats outside the ball."""

    def num(self, x: float) -> Any:
        from flint import arb

        return arb(float(x))

    def up(self, x: Any) -> float:
        if not x.is_finite():
            return math.inf
        return math.nextafter(float(x.upper()), math.inf)

    def low(self, x: Any) -> float:
        if not x.is_finite():
            return -math.inf
        return math.nextafter(float(x.lower()), -math.inf)

    def pos(self, x: Any) -> bool:
        return bool(x > 0)


def _geometric(a: float, b: float, n: int) -> list[float]:
    """n + 1 points from a to b (0 < a < b), ratio constant; the ends exact."""
    pts = [a * (b / a) ** (j / n) for j in range(n + 1)]
    pts[0], pts[-1] = a, b
    return pts


def axis_bound(e0: float, ed0: float, gains: Any, *, dm: float = 0.0, drift: float = 0.0,
               tol: float = P.TRACK_TOL, cells: int = CELLS, screen: bool = False
               ) -> AxisBound:
    """The bounds of one axis from the signed initial offset e0 (m) and rate ed0 (m/s) for the
    FTSMC gains ``gains`` (alpha, beta, p, q, k, e_floor), disturbance mismatch ``dm`` and
    drift bound ``drift`` (m/s^2); see the module docstring for each step."""
    if screen:
        return _screen(e0, ed0, gains, dm, drift, tol, cells)
    A = _Arb()
    n = A.num
    alpha, beta, k = n(gains.alpha), n(gains.beta), n(gains.k)
    r = n(gains.p) / n(gains.q)
    ef = n(gains.e_floor)
    one = n(1.0)
    delta = beta * (one - r) * ef ** r
    g_max = alpha + beta * r * ef ** (r - one)

    def h(x: float) -> Any:
        x = n(x)
        if x <= gains.e_floor:
            return alpha * x + beta * r * ef ** (r - one) * x
        return alpha * x + beta * (x ** r - (one - r) * ef ** r)

    def G(x: float) -> Any:
        x = n(max(x, gains.e_floor))
        return alpha + beta * r * x ** (r - one)

    ae0, aed0 = abs(float(e0)), abs(float(ed0))
    sig0 = n(float(ed0)) + (h(ae0) if e0 >= 0 else -h(ae0))
    s0 = abs(sig0)
    S = s0 if A.up(s0) > A.up(delta) else delta
    rate = k - n(dm)
    t_reach = math.inf
    if A.pos(rate):
        reach = s0 - delta
        t_reach = A.up(reach / rate) if A.up(reach) > 0 else 0.0
    # E: the larger of |e0| and a point where h >= S (bisection on enclosures)
    hi = max(ae0, 1e-12)
    while not h(hi) >= S:
        hi *= 2.0
    lo = 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if h(mid) >= S:
            hi = mid
        else:
            lo = mid
    E = max(ae0, hi)
    # tracking: integral of 1/(h - delta) from tol to E, cells at their low end
    t_slide = 0.0
    if not A.pos(h(tol) - delta):
        t_slide = math.inf
    elif E > tol:
        pts = _geometric(tol, E, cells)
        acc = n(0.0)
        for a, b in zip(pts[:-1], pts[1:], strict=True):
            acc = acc + (n(b) - n(a)) / (h(a) - delta)
        t_slide = A.up(acc)
    # the command: max over [0, E] of (h + delta) G, cells at their worst ends
    best = (h(min(gains.e_floor, E)) + delta) * g_max
    worst = A.up(best)
    if E > gains.e_floor:
        pts = _geometric(gains.e_floor, E, cells)
        for a, b in zip(pts[:-1], pts[1:], strict=True):
            worst = max(worst, A.up((h(b) + delta) * G(a)))
    ed_g = max(A.up(n(aed0) * g_max), worst)
    V = max(aed0, A.up(h(E) + delta))
    u = A.up(n(drift) + k + n(ed_g))
    return AxisBound(ae0, aed0, A.up(s0), A.up(delta), A.up(g_max), A.up(S), E, V, t_reach,
                     t_slide, t_reach + t_slide if math.isfinite(t_reach) else math.inf,
                     ed_g, float(drift), float(gains.k), u, float(tol), float(dm))


def _screen(e0: float, ed0: float, g: Any, dm: float, drift: float, tol: float,
            cells: int) -> AxisBound:
    """``axis_bound`` in floats, vectorised (the tuner's grid; not a proof)."""
    r, ef = g.p / g.q, g.e_floor

    def h(x):
        x = np.asarray(x, float)
        return g.alpha * x + g.beta * np.where(x <= ef, r * ef ** (r - 1) * x,
                                               np.maximum(x, ef) ** r - (1 - r) * ef ** r)

    def G(x):
        return g.alpha + g.beta * r * np.maximum(np.asarray(x, float), ef) ** (r - 1)

    delta = g.beta * (1 - r) * ef ** r
    g_max = float(G(0.0))
    s0 = abs(ed0 + math.copysign(float(h(abs(e0))), e0))
    S = max(s0, delta)
    t_reach = max(s0 - delta, 0.0) / (g.k - dm) if g.k > dm else math.inf
    hi = max(abs(e0), 1e-12)
    while h(hi) < S:
        hi *= 2.0
    lo = 0.0
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if h(mid) >= S else (mid, hi)
    E = max(abs(e0), hi)
    if h(tol) <= delta:
        t_slide = math.inf
    elif E > tol:
        x = tol * (E / tol) ** (np.arange(cells + 1) / cells)
        t_slide = float(np.sum(np.diff(x) / (h(x[:-1]) - delta)))
    else:
        t_slide = 0.0
    worst = float((h(min(ef, E)) + delta) * g_max)
    if E > ef:
        x = ef * (E / ef) ** (np.arange(cells + 1) / cells)
        worst = max(worst, float(np.max((h(x[1:]) + delta) * G(x[:-1]))))
    ed_g = max(abs(ed0) * g_max, worst)
    V = max(abs(ed0), float(h(E)) + delta)
    return AxisBound(abs(e0), abs(ed0), s0, delta, g_max, S, E, V, t_reach, t_slide,
                     t_reach + t_slide, ed_g, drift, g.k, drift + g.k + ed_g, tol, dm)


@cache
def reference_extents(t_end: float = P.T_LAND, cells: int = 400) -> dict[str, Any]:
    """Upper bounds over t in [0, t_end] s of seed 002's reference (8)-(10) (exact cubic):
    per axis max |x_d|, |x_d'|, |x_d''|, and a lower bound of its least distance to each
    mass point of (2); Arb enclosures of the cubic on ``cells`` time cells."""
    from flint import arb
    from lgw.theory.eros.reference import coefficients

    coef = coefficients()
    ts = np.linspace(0.0, float(t_end), cells + 1)
    pos_max, vel_max, acc_max = [0.0] * 3, [0.0] * 3, [0.0] * 3
    dmin = [math.inf, math.inf]
    masses = (P.TWO_POINT_P1, P.TWO_POINT_P2)
    cs = [[arb(float(c)) for c in coef[i]] for i in range(3)]
    for a, b in zip(ts[:-1], ts[1:], strict=True):
        t = arb((a + b) / 2, (b - a) / 2 * (1 + 1e-9) + 1e-12)  # the cell as a ball
        pos = []
        for i in range(3):
            c0, c1, c2, c3 = cs[i]
            x = c0 + t * (c1 + t * (c2 + t * c3))
            pos.append(x)
            pos_max[i] = max(pos_max[i], _up(abs(x)))
            vel_max[i] = max(vel_max[i], _up(abs(c1 + t * (2 * c2 + 3 * t * c3))))
            acc_max[i] = max(acc_max[i], _up(abs(2 * c2 + 6 * c3 * t)))
        for j, pj in enumerate(masses):
            d2 = sum((pos[i] - arb(float(pj[i]))) ** 2 for i in range(3))
            dmin[j] = min(dmin[j], math.nextafter(math.sqrt(max(float(d2.lower()), 0.0)), 0.0)
                          * (1 - 1e-12))
    return {"pos_max": pos_max, "vel_max": vel_max, "acc_max": acc_max, "dmin": dmin,
            "t_end": float(t_end)}


def _up(x: Any) -> float:
    return math.nextafter(float(x.upper()), math.inf)


def s_reach_time(e0: float, ed0: float, gains: Any, dm: float = 0.0) -> float:
    """The time (s) by which the paper's surface s = e' + alpha e + beta sig(e)^r reaches 0
    (or changes sign) under the floored law, from e0 (m), ed0 (m/s): step (1b) of the module
    docstring; inf when k <= d."""
    if not gains.k > dm:
        return math.inf
    r, ef = gains.p / gains.q, gains.e_floor
    a = abs(e0)
    phi = r * ef ** (r - 1) * a if a <= ef else a ** r - (1 - r) * ef ** r
    sigma0 = ed0 + math.copysign(gains.alpha * a + gains.beta * phi, e0)
    s0 = ed0 + gains.alpha * e0 + gains.beta * math.copysign(a ** r, e0)
    if s0 == 0.0:
        return 0.0
    delta = gains.beta * (1 - r) * ef ** r
    return max(math.copysign(1.0, s0) * sigma0 + delta, 0.0) / (gains.k - dm)


def drift_bound(E: float, V: float, known_amp: float, t_end: float = P.T_LAND
                ) -> dict[str, float]:
    """An upper bound (m/s^2) on |f_i + D_k,i - xdd_i| along any run that stays within E (m)
    and V (m/s) of seed 002's reference (8)-(10) on [0, t_end] s, per axis: the rotating terms
    of (4) (2 w |v_j| + w^2 |x_i|), the fitted two-point gravity (2) (sum of G M_j / d_j^2, d_j
    the least distance from the reference to mass point j less sqrt(3) E), the disturbance the
    controller cancels (``known_amp``: its amplitude when D is known, 0 when not) and the
    reference acceleration (``reference_extents``); the closed form is inflated by 1e-9
    relative for its float rounding."""
    ext = reference_extents(float(t_end))
    d = [x - SQRT3 * E for x in ext["dmin"]]
    if min(d) <= 0:
        return {"drift": math.inf, "why": "the envelope reaches a mass point of (2)"}
    grav = sum(gm / dj ** 2 for gm, dj in zip(P.TWO_POINT_GM, d, strict=True))
    w = float(P.OMEGA)
    pm, vm = ext["pos_max"], ext["vel_max"]
    rot = [2 * w * (vm[1] + V) + w ** 2 * (pm[0] + E), 2 * w * (vm[0] + V) + w ** 2 * (pm[1] + E),
           0.0]
    per_axis = [rot[i] + grav + known_amp + ext["acc_max"][i] for i in range(3)]
    return {"drift": max(per_axis) * (1 + 1e-9), "gravity": grav, "rotating": max(rot),
            "reference_accel": max(ext["acc_max"]), "disturbance_cancelled": float(known_amp),
            "t_end": float(t_end)}


def envelope_bound(gains: Any, e_max: float, v_max: float, *, dm: float = 0.0,
                   known_amp: float = 0.0, tol: float = P.TRACK_TOL, screen: bool = False,
                   drift: float | None = None) -> dict[str, Any]:
    """The proven bounds over |e_i(0)| <= e_max, |e_i'(0)| <= v_max (every axis): the corner's
    ``axis_bound`` (module docstring: each bound grows with |sigma0|, |e0| and |e'0|), with
    the drift bound of ``drift_bound`` over the reachable E, V (iterated once: the drift does
    not enter E or V).  Returns the AxisBound fields, the drift's terms and ``how``."""
    first = axis_bound(e_max, v_max, gains, dm=dm, tol=tol, screen=screen)
    dr = {"drift": drift} if drift is not None else drift_bound(first.E, first.V, known_amp)
    b = axis_bound(e_max, v_max, gains, dm=dm, drift=dr["drift"], tol=tol, screen=screen)
    how = ("continuous-time floored FTSMC (19), sign switching, Filippov solutions: reaching "
           "on the floored surface, |e| and |e'| bounded on the reachable set, tracking time "
           "by an upper Riemann sum, command by a cellwise maximum; Arb ball arithmetic "
           "(lgw.theory.eros.floored)")
    return {**b.to_dict(), "drift_terms": dr, "how": how if not screen else "float screen"}


def hypotheses(gains: Any, dm: float = 0.0, tol: float = P.TRACK_TOL) -> dict[str, bool]:
    """What the bounds need: k > d (reaching) and h(tol) > delta (the band the floor leaves
    lies inside the tracking tolerance)."""
    r = gains.p / gains.q
    ef = gains.e_floor
    phi = r * ef ** (r - 1) * tol if tol <= ef else tol ** r - (1 - r) * ef ** r
    return {"k > d": gains.k > dm,
            "h(tol) > delta": gains.alpha * tol + gains.beta * phi
            > gains.beta * (1 - r) * ef ** r}
