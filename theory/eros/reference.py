"""The cubic landing reference of seed 002, eqs. (8)-(10): exact coefficients and checks.

x_d(t) = c0 + c1 t + c2 t^2 + c3 t^3 with x_d(0) = r0, x_d'(0) = v0, x_d(T) = rf, x_d'(T) = vf
(the boundary conditions (9), Table 1).  Solved here exactly in rationals from the printed
decimal boundary values; the printed (9)-(10) coefficients are 3-digit roundings.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.eros.parameters import CUBIC_PRINTED, R0, RF, T_LAND, V0, VF

t = sp.Symbol("t", nonnegative=True)
AXES = ("x", "y", "z")


def _rat(x: float) -> sp.Rational:
    return sp.Rational(repr(float(x)))


@cache
def exact_coefficients() -> tuple[tuple[sp.Rational, ...], ...]:
    """(c0..c3) per axis solving (9) exactly (SymPy linear solve in rationals)."""
    c = sp.symbols("c0:4")
    xd = sum(ci * t**i for i, ci in enumerate(c))
    T = _rat(T_LAND)
    out = []
    for i in range(3):
        eqs = [xd.subs(t, 0) - _rat(R0[i]), sp.diff(xd, t).subs(t, 0) - _rat(V0[i]),
               xd.subs(t, T) - _rat(RF[i]), sp.diff(xd, t).subs(t, T) - _rat(VF[i])]
        sol = sp.solve(eqs, c, dict=True)[0]
        out.append(tuple(sp.nsimplify(sol[ci]) for ci in c))
    return tuple(out)


def coefficients(printed: bool = False) -> np.ndarray:
    """3 x 4 array of coefficients (float): exact (default) or as printed in (9)-(10)."""
    if printed:
        return CUBIC_PRINTED.copy()
    return np.array([[float(x) for x in row] for row in exact_coefficients()])


def evaluate(coef: np.ndarray, tt) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity, acceleration of the reference at times tt: arrays (3, len(tt))
    (or (3,) for a scalar)."""
    tt = np.asarray(tt, dtype=float)
    c0, c1, c2, c3 = (coef[:, i].reshape((3,) + (1,) * tt.ndim) for i in range(4))
    pos = c0 + c1 * tt + c2 * tt**2 + c3 * tt**3
    vel = c1 + 2 * c2 * tt + 3 * c3 * tt**2
    acc = 2 * c2 + 6 * c3 * tt
    return pos, vel, acc


def endpoint_miss() -> dict[str, list[float]]:
    """Position and velocity of the printed-coefficient reference at T minus the targets, and
    the exact one's (which is 0), per axis."""
    pr, vr, _ = evaluate(coefficients(True), T_LAND)
    return {"position_m": (pr - RF).tolist(), "velocity_m_s": (vr - VF).tolist()}


def velocity_roots() -> list[list[float]]:
    """Real roots of x_d'(t) per axis (exact cubic): where the reference turns."""
    out = []
    for row in exact_coefficients():
        xd = sum(ci * t**i for i, ci in enumerate(row))
        roots = sp.Poly(sp.diff(xd, t), t).real_roots()
        out.append([float(x) for x in roots])
    return out
