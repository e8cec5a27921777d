"""Seed 000's baseline: the super-twisting sliding-mode guidance (STSMG), eq. (46).

The extraction of (46) is garbled ("a = -1/m { B1/2 |s|^(-1/2) s' + B2 sgn(s) } - g" spread over
three lines).  We read it as the *differentiated* super-twisting algorithm applied to s = r
(seed 000: "s = [sx sy sz] is the position"), per axis i:

    a_i = -(1/m) [ (B1_i / 2) |s_i|^(-1/2) s_i' + B2_i sgn(s_i) ] - g_i,   s_i = r_i, s_i' = v_i.

Reasoning: the super-twisting input u = -k1 |s|^(1/2) sgn(s) + w, w' = -k2 sgn(s) has derivative
u' = -(k1/2) |s|^(-1/2) s' - k2 sgn(s), which is the bracket of (46); B1, B2 are forces (N), so
dividing by m gives an acceleration, and -g cancels gravity.  Gains of seed 000:
B1 = (1200, 1000, 1000), B2 = (5500, 5000, 5000).  As printed, (46) does not cancel drag (no a_m
term), and the simulator keeps it that way.  The term |s|^(-1/2) s' is unbounded at s = 0 with
s' != 0, like the corrected law's |s1|^(q1-1) v (see ``lgw.theory.mars.mss``).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.mars.mss import am, grav, r, v
from lgw.theory.symbolic import LAMBDIFY_MODULES

B1_PAPER = np.array([1200.0, 1000.0, 1000.0])  # N, seed 000 Part 1
B2_PAPER = np.array([5500.0, 5000.0, 5000.0])  # N, seed 000 Part 1

m = sp.Symbol("m", positive=True)
B1, B2 = sp.symbols("B1 B2", positive=True)
ST_PARAMS = (B1, B2)
# Same leading arguments as lgw.theory.mars.mss.law_numeric plus the mass: (r, v, grav, a_m, m,
# ...).
ST_ARGS = (r, v, grav, am, m, B1, B2)


def law_supertwisting() -> sp.Expr:
    """Seed 000, eq. (46) per axis (reading above); a_m is an argument but does not appear."""
    s, sdot = r, v
    return -(B1 / 2 * sp.Abs(s) ** sp.Rational(-1, 2) * sdot + B2 * sp.sign(s)) / m - grav


@cache
def supertwisting_numeric() -> Callable[..., np.ndarray]:
    """(46) lambdified: f(r, v, grav, a_m, m, B1, B2), broadcasting over numpy arrays."""
    return sp.lambdify(ST_ARGS, law_supertwisting(), modules=LAMBDIFY_MODULES)
