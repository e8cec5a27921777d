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

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.symbolic import LAMBDIFY_MODULES, sig

LAWS = ("corrected", "printed")

# Per-axis state and environment symbols.
r, v, grav, am, ap = sp.symbols("r v grav a_m a_p", real=True)
# Gains (seed 000 (16), (25)): positive.  Exponent ranges are checked by lgw.theory.mars.gains.
beta1, beta2, alpha1, alpha2 = sp.symbols("beta1 beta2 alpha1 alpha2", positive=True)
q1, q2, g1, g2 = sp.symbols("q1 q2 g1 g2", positive=True)
GAIN_SYMBOLS = (beta1, beta2, alpha1, alpha2, q1, q2, g1, g2)


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


@cache
def closed_loop(name: str) -> ClosedLoop:
    a = law(name)
    s1, s2 = surface1(), surface2()
    s2dot = time_derivative(s2, a, ap)
    V2 = s2**2 / 2
    return ClosedLoop(name, a, s1, s2, s2dot, s1**2 / 2, V2, time_derivative(V2, a, ap))


# --- Numeric law, generated from the same expressions ------------------------------------

LawFn = Callable[..., np.ndarray]
LAW_ARGS = (r, v, grav, am, *GAIN_SYMBOLS)


@cache
def law_numeric(name: str) -> LawFn:
    """The law ``name`` lambdified: f(r, v, grav, a_m, beta1, beta2, alpha1, alpha2, q1, q2,
    g1, g2) -> commanded acceleration, broadcasting over numpy arrays (e.g. (N, 3) states with
    (3,) gains).  This is what ``sim`` runs; a test checks it against the SymPy expression."""
    return sp.lambdify(LAW_ARGS, law(name), modules=LAMBDIFY_MODULES)


@cache
def surfaces_numeric() -> tuple[LawFn, LawFn]:
    """(s1, s2) of (15), (21) lambdified as f(r, v, beta1, beta2, q1, q2)."""
    args = (r, v, beta1, beta2, q1, q2)
    return (sp.lambdify(args, surface1(), modules=LAMBDIFY_MODULES),
            sp.lambdify(args, surface2(), modules=LAMBDIFY_MODULES))
