"""Seed 000: multiple-sliding-surface fixed-time guidance for Mars powered descent.

One axis i in {x, y, z} at a time: the paper's gains are diagonal and every term of (25) acts
per axis, so the 3-axis closed loop is three copies of this scalar one (the vector forms are
checked separately in ``lgw.theory.mars.claims``).

Symbols (per axis): r position, v velocity, grav gravity component g_i, am drag acceleration
a_m,i (12), ap lumped disturbance a_p,i (30).  The target is r_d = 0, v_d = 0 (seed 000 (23)).

Two versions of the guidance:

* ``law_printed``: seed 000, eq. (25) as printed.  It was obtained from (24), which replaces
  s1' by the reaching law (16); that only holds on s2 = 0.  Off the surface the true s2' differs
  by (beta1 q1 |s1|^(q1-1) + beta2 q2 |s1|^(q2-1)) s2, so V2' is not (29).
* ``law_corrected``: derived here from the exact s2' of (22) with s1' = v, so that s2' equals
  -alpha1 sig(s2, g1) - alpha2 sig(s2, g2) (+ a_p) identically and (26), (39), (40) follow.
  Its price: the term q1 |s1|^(q1-1) v is unbounded where s1 = 0 and v != 0.

Both are SymPy expressions; ``law_numeric`` lambdifies the same expressions for the simulator.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import sympy as sp
from lgw.theory.symbolic import LAMBDIFY_MODULES, memo, sig

LAWS = ("corrected", "printed")

# Per-axis state and environment symbols.
r, v, grav, am, ap = sp.symbols("r v grav a_m a_p", real=True)
# Gains (seed 000 (16), (25)): positive.  Exponent ranges are checked by lgw.theory.mars.gains.
beta1, beta2, alpha1, alpha2 = sp.symbols("beta1 beta2 alpha1 alpha2", positive=True)
q1, q2, g1, g2 = sp.symbols("q1 q2 g1 g2", positive=True)
GAIN_SYMBOLS = (beta1, beta2, alpha1, alpha2, q1, q2, g1, g2)
S2 = sp.Symbol("s_2", real=True)  # the second surface as a coordinate

# The hypotheses of (16) and (25) (seed 000: beta_i, alpha_i > 0, 0 < q1 < 1 < q2,
# 0 < g1 < 1 < g2), as the open ranges a witness sampler may draw from.  q2, g2 > 1 have no
# upper end in the paper; the sampler stops at 4 (a stated sub-range, as the full-domain
# searches of lgw.theory.mars.searches do).
SAMPLE_RANGES: dict[sp.Symbol, tuple[float, float]] = {
    beta1: (0.0, 3.0), beta2: (0.0, 3.0), alpha1: (0.0, 3.0), alpha2: (0.0, 3.0),
    q1: (0.0, 1.0), q2: (1.0, 4.0), g1: (0.0, 1.0), g2: (1.0, 4.0)}


def hypotheses() -> list[sp.Basic]:
    """The gain hypotheses of (16), (25) as SymPy relations (for z3)."""
    rel = {"gt": sp.StrictGreaterThan, "lt": sp.StrictLessThan}
    pairs = [(q1, "gt", 0), (q1, "lt", 1), (q2, "gt", 1), (g1, "gt", 0), (g1, "lt", 1),
             (g2, "gt", 1), *((x, "gt", 0) for x in (beta1, beta2, alpha1, alpha2))]
    # unevaluated: the symbols are declared positive, so SymPy would reduce q1 > 0 to True
    return [rel[op](x, c, evaluate=False) for x, op, c in pairs]


def surface1() -> sp.Expr:
    """Seed 000, eq. (15): s1 = r - r_d with r_d = 0."""
    return r


def reaching_law_rhs(s1: sp.Expr) -> sp.Expr:
    """Seed 000, eq. (16): s1' = -beta1 |s1|^q1 sgn(s1) - beta2 |s1|^q2 sgn(s1)."""
    return -beta1 * sig(s1, q1) - beta2 * sig(s1, q2)


def surface2() -> sp.Expr:
    """Seed 000, eq. (21): s2 = s1' + beta1 |s1|^q1 sgn(s1) + beta2 |s1|^q2 sgn(s1), s1' = v."""
    s1 = surface1()
    return v - reaching_law_rhs(s1)


def s2_symbol_law(s2: sp.Expr) -> sp.Expr:
    """The s2 reaching term of (25): -alpha1 |s2|^g1 sgn(s2) - alpha2 |s2|^g2 sgn(s2)."""
    return -alpha1 * sig(s2, g1) - alpha2 * sig(s2, g2)


def law_printed() -> sp.Expr:
    """Seed 000, eq. (25) as printed: the commanded acceleration a_i.

    a = -g - a_m + beta1^2 q1 |s1|^(2q1-1) sgn(s1) + beta2^2 q2 |s1|^(2q2-1) sgn(s1)
        + beta1 beta2 (q1 + q2) |s1|^(q1+q2-1) sgn(s1) - alpha1 |s2|^g1 sgn(s2)
        - alpha2 |s2|^g2 sgn(s2).
    Departure: none; for q1 < 1/2 the |s1|^(2q1-1) term is unbounded at s1 = 0 and for q1 = 1/2
    it is the discontinuous sgn(s1).
    """
    s1, s2 = surface1(), surface2()
    return (-grav - am
            + beta1**2 * q1 * sig(s1, 2 * q1 - 1) + beta2**2 * q2 * sig(s1, 2 * q2 - 1)
            + beta1 * beta2 * (q1 + q2) * sig(s1, q1 + q2 - 1)
            + s2_symbol_law(s2))


def law_corrected() -> sp.Expr:
    """Guidance that makes seed 000's Theorem 3 true: derived from (22) with s1' = v.

    a = -g - a_m - (beta1 q1 |s1|^(q1-1) + beta2 q2 |s1|^(q2-1)) v - alpha1 |s2|^g1 sgn(s2)
        - alpha2 |s2|^g2 sgn(s2).
    Departure from (25): the printed law evaluates the bracket at v = -beta1 sig(s1,q1)
    - beta2 sig(s1,q2) (the reaching law (16)), which equals v only on s2 = 0.  On s2 = 0 the
    two laws are identical (proved in ``lgw.theory.mars.claims``).
    """
    s1, s2 = surface1(), surface2()
    dbeta = beta1 * q1 * sp.Abs(s1) ** (q1 - 1) + beta2 * q2 * sp.Abs(s1) ** (q2 - 1)
    return -grav - am - dbeta * v + s2_symbol_law(s2)


def law(name: str) -> sp.Expr:
    if name == "printed":
        return law_printed()
    if name == "corrected":
        return law_corrected()
    raise ValueError(f"law must be one of {LAWS}, got {name!r}")


def time_derivative(expr: sp.Expr, accel: sp.Expr, disturbance: sp.Expr = sp.S.Zero) -> sp.Expr:
    """d/dt of expr(r, v) along seed 000's (10), (30): r' = v, v' = a + g + a_m + a_p."""
    vdot = accel + grav + am + disturbance
    return sp.diff(expr, r) * v + sp.diff(expr, v) * vdot


@dataclass(frozen=True)
class ClosedLoop:
    """Per-axis closed loop of one law, derived symbolically."""

    name: str
    accel: sp.Expr  # commanded acceleration a_i
    s1: sp.Expr
    s2: sp.Expr
    s2dot: sp.Expr  # along (30) with a_p
    V1: sp.Expr  # (19), one axis
    V2: sp.Expr  # (27), one axis
    V2dot: sp.Expr  # along (30) with a_p


@memo
def closed_loop(name: str) -> ClosedLoop:
    a = law(name)
    s1, s2 = surface1(), surface2()
    s2dot = time_derivative(s2, a, ap)
    V2 = s2**2 / 2
    return ClosedLoop(name, a, s1, s2, s2dot, s1**2 / 2, V2, time_derivative(V2, a, ap))


def in_surface_coords(expr: sp.Expr) -> sp.Expr:
    """expr(r, v) in (s1, s2) = (r, S2): v = S2 - beta1 sig(r,q1) - beta2 sig(r,q2)."""
    return expr.subs(v, S2 + reaching_law_rhs(r))


@memo
def s2_drift_branches(name: str) -> tuple[sp.Expr, sp.Expr]:
    """What the law leaves in s2' beyond the s2 reaching term, without disturbance:
    e(s1, s2) = s2' + alpha1 sig(s2,g1) + alpha2 sig(s2,g2) in surface coordinates, computed
    from the law's closed loop and reduced on s1 = x > 0 and s1 = -x < 0 (x positive).

    The corrected law gives (0, 0) (exact cancellation, claim V2dot-corrected); the printed
    law (25) gives +-(beta1 q1 x^(q1-1) + beta2 q2 x^(q2-1)) s2 (claim s2dot-24)."""
    cl = closed_loop(name)
    e = in_surface_coords(cl.s2dot.subs(ap, 0) - s2_symbol_law(surface2()))
    x = sp.Symbol("x", positive=True)
    out = []
    for sg in (1, -1):
        b = sp.powsimp(sp.expand(e.subs(r, sg * x)), force=True)
        out.append(sp.simplify(b))
    return out[0], out[1]


def s2_drift_vanishes(name: str) -> bool:
    """The law cancels s2' exactly (its drift is 0 on both branches)."""
    return all(b == 0 for b in s2_drift_branches(name))


@memo
def s2_drift_numeric(name: str) -> Callable[..., float] | None:
    """The drift e(s1, s2) of ``s2_drift_branches`` as a scalar function
    f(s1, s2, beta1, beta2, alpha1, alpha2, q1, q2, g1, g2) (plain floats), or None when it
    vanishes identically.  At s1 = 0 the surface derivative (22) is not defined (the paper
    takes it for s1 != 0); there the drift is taken as 0 (a set of measure zero).  Raises
    ValueError if the drift does not vanish with s2 (then s2 = 0 would not be invariant and
    the reduced loops of lgw.theory.mars.reduced do not apply)."""
    pos, neg = s2_drift_branches(name)
    if pos == 0 and neg == 0:
        return None
    if sp.simplify(pos.subs(S2, 0)) != 0 or sp.simplify(neg.subs(S2, 0)) != 0:
        raise ValueError(f"law {name}: the s2 drift does not vanish on s2 = 0")
    x = sp.Symbol("x", positive=True)
    s1 = sp.Symbol("s1", real=True)
    pw = sp.Piecewise((pos.subs(x, s1), s1 > 0), (neg.subs(x, -s1), s1 < 0), (0, True))
    return sp.lambdify((s1, S2, *GAIN_SYMBOLS), pw,
                       modules=[{"sig": lambda a, q: math.copysign(abs(a) ** q, a)}, "math"])


# --- Numeric law, generated from the same expressions ------------------------------------

LawFn = Callable[..., np.ndarray]
LAW_ARGS = (r, v, grav, am, *GAIN_SYMBOLS)


@memo
def law_numeric(name: str) -> LawFn:
    """The law ``name`` lambdified: f(r, v, grav, a_m, beta1, beta2, alpha1, alpha2, q1, q2,
    g1, g2) -> commanded acceleration, broadcasting over numpy arrays (e.g. (N, 3) states with
    (3,) gains).  This is what ``sim`` runs; a test checks it against the SymPy expression."""
    return sp.lambdify(LAW_ARGS, law(name), modules=LAMBDIFY_MODULES)


@memo
def surfaces_numeric() -> tuple[LawFn, LawFn]:
    """(s1, s2) of (15), (21) lambdified as f(r, v, beta1, beta2, q1, q2)."""
    args = (r, v, beta1, beta2, q1, q2)
    return (sp.lambdify(args, surface1(), modules=LAMBDIFY_MODULES),
            sp.lambdify(args, surface2(), modules=LAMBDIFY_MODULES))
