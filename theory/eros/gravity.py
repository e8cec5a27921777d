"""The two-mass-point gravity of seed 002 eq. (2): potential, its gradient (derived) and the
gradient as printed, plus a vectorised evaluator generated from the derived gradient.

U = G M1 / |r - r1| + G M2 / |r - r2| (attraction: g = grad U points at the masses).  The
printed (2) writes U without G and g_x = +G M1 (x - x1)/r1^3 + ..., which is minus the gradient
(a repulsive field); see claim gravity-2.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import sympy as sp

x, y, z = sp.symbols("x y z", real=True)
x1, y1, z1, x2, y2, z2 = sp.symbols("x_1 y_1 z_1 x_2 y_2 z_2", real=True)
Gs, M1, M2 = sp.symbols("G M_1 M_2", positive=True)


def _rho(a, b, c):
    return sp.sqrt((x - a) ** 2 + (y - b) ** 2 + (z - c) ** 2)


def potential() -> sp.Expr:
    """U of (2) with the G the text says it carries (the extracted U omits it)."""
    return Gs * M1 / _rho(x1, y1, z1) + Gs * M2 / _rho(x2, y2, z2)


def potential_printed() -> sp.Expr:
    """U as printed (extracted) in (2): M1/r1 + M2/r2."""
    return M1 / _rho(x1, y1, z1) + M2 / _rho(x2, y2, z2)


def gradient() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """g = grad U, derived."""
    U = potential()
    return tuple(sp.diff(U, v) for v in (x, y, z))


def gradient_printed() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """g as printed in (2): + G M_i (x - x_i) / r_i^3 summed (power 1.5 of the squared norm)."""
    out = []
    for v, a, b in ((x, x1, x2), (y, y1, y2), (z, z1, z2)):
        r1sq = (x - x1) ** 2 + (y - y1) ** 2 + (z - z1) ** 2
        r2sq = (x - x2) ** 2 + (y - y2) ** 2 + (z - z2) ** 2
        out.append(Gs * M1 * (v - a) / r1sq ** sp.Rational(3, 2)
                   + Gs * M2 * (v - b) / r2sq ** sp.Rational(3, 2))
    return tuple(out)


@cache
def _generated():
    args = (x, y, z, x1, y1, z1, x2, y2, z2, Gs, M1, M2)
    return sp.lambdify(args, sp.Matrix(gradient()), "numpy", cse=True)


def two_point_accel(pos: np.ndarray, p1, p2, gm1: float, gm2: float) -> np.ndarray:
    """Acceleration (m/s^2) of the derived (2) at positions ``pos`` (..., 3) in the body frame;
    ``gm_i`` = G M_i (m^3/s^2), ``p_i`` the mass-point positions (m).  Generated from
    ``gradient()`` (lambdify), vectorised over the leading axes."""
    pos = np.asarray(pos, dtype=float)
    fn = _generated()
    out = fn(pos[..., 0], pos[..., 1], pos[..., 2], *p1, *p2, 1.0, gm1, gm2)
    return np.stack([np.broadcast_to(np.asarray(out[i, 0]), pos.shape[:-1]) for i in range(3)],
                    axis=-1)
