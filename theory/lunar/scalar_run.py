"""A scalar instance of seed 001's general system (5) under the law (7)-(11), flown by SciPy:
the witness route for the transient L2 bounds (19)-(21).

The instance is ``lgw.theory.lunar.law.GeneralSystem`` with n1 = n2 = m = 1: f1 = the
vertical component of the law's orbit f1 = a_h (-1, seed 001 (22)), f2 = 0, B0 = -1 (any nonzero b:
B0 B0^+ = 1, the closed loop does not depend on it), K1 = K1_zz, F2 = f2bar of the orbit gains
in use, f3, q, d0e(0) of the same gains, a constant disturbance d = D (so ||d|| = D and the
paper's d^_0 = d0e - ||d|| is the constant-bound reading), no saturation (du = 0, so lambda = 0
and x1 = z1).  The right-hand side is the law's own closed loop (``GeneralSystem.rates``)
lambdified; the squared L2 norms are integrated as extra states.

The bounds (19)-(21) hold on every [0, t] with the truncated norms (they come from integrating
(13) on [0, t]); a run stops at its horizon or where |z2| falls to Z2_STOP on its way to the
first zero of z2, where the term d0e^2 z2/(||z2|| d0e + f3||z2||^2) of (7) jumps (claim
smooth-7) and the loop may slide on z2 = 0: the integrators never meet the discontinuity.
Fast route: RK45 (rtol 1e-8); independent route: DOP853 (rtol 1e-12,
atol 1e-14).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.lunar import bounds as B
from lgw.theory.lunar import law as L
from lgw.theory.lunar.gains import A_H, LoopGains
from lgw.theory.symbolic import LAMBDIFY_MODULES
from scipy.integrate import solve_ivp

Z2_STOP = 1e-6  # the run ends where |z2| falls to this (times max(1, |z2(0)|), m/s)
HORIZON = 20.0  # s, chosen: long against the loop's time constants 1/K1_zz, 1/f2bar (10 s, 1 s)
ROUTES = {"fast": dict(method="RK45", rtol=1e-8, atol=1e-10),
          "reference": dict(method="DOP853", rtol=1e-12, atol=1e-14)}


@dataclass(frozen=True)
class ScalarGains:
    """The scalar instance's constants (orbit loop, vertical axis)."""

    k1: float  # K1_zz = f1bar (F1 = f1 k1 f1 with f1 = -1)
    f2: float  # F2 = f2bar
    f3: float
    q: float
    d0e0: float


def scalar_gains(g: LoopGains) -> ScalarGains:
    """The scalar instance of the orbit loop ``g``: K1_zz, f2bar, f3, q, d0e(0)."""
    return ScalarGains(float((A_H @ g.K1 @ A_H.T)[0, 0]), g.f2bar, g.f3, g.q, g.d0e0)


@cache
def _rhs():
    """The closed loop of the scalar instance, lambdified: y' = rhs(y, k1, F2, f3, q, D) for
    y = (x1, x2, lambda1, lambda2, d0e, int z1^2, int z2^2); f1 is the vertical component of
    the law's orbit f1 (a_h)."""
    f1v = L.orbit_system().f1[0, 2]
    x1, x2 = sp.Symbol("x1_1", real=True), sp.Symbol("x2_1", real=True)
    k1, F2 = sp.Symbol("k1", positive=True), sp.Symbol("F2", positive=True)
    S = L.GeneralSystem(sp.Matrix([x1]), sp.Matrix([x2]), sp.Matrix([[f1v]]), sp.zeros(1, 1),
                        sp.Matrix([[-1]]), sp.Matrix([[k1]]), sp.Matrix([[F2]]),
                        name="scalar-orbit")
    Dv = sp.Symbol("Dval", real=True)
    z2 = (S.x2 - S.lam2 - S.p)[0]
    z1 = (S.x1 - S.lam1)[0]
    sub = {S.d[0]: Dv, S.du[0]: 0, S.Ddot: 0, S.D: Dv}
    r = S.rates
    states = [S.x1[0], S.x2[0], S.lam1[0], S.lam2[0], S.d0e]
    exprs = [sp.sympify(r[x]).subs(sub).subs(S.nz, sp.Abs(z2)) for x in states]
    exprs += [z1 ** 2, z2 ** 2]
    args = (states, k1, F2, S.f3, S.q, Dv)
    f = sp.lambdify(args, exprs, modules=LAMBDIFY_MODULES)
    fz2 = sp.lambdify(args, z2, modules=LAMBDIFY_MODULES)
    return f, fz2


def fly(g: ScalarGains, x1_0: float, x2_0: float, D: float, route: str = "fast",
        horizon: float = HORIZON) -> dict[str, float]:
    """Fly the scalar instance from x1(0), x2(0) (lambda(0) = 0, d0e(0) = g.d0e0) under the
    constant disturbance D to the horizon or the first zero of z2; the squared L2 norms of z1
    and z2 over [0, t_end] and the initial values (19)-(20) need."""
    f, fz2 = _rhs()
    p = (g.k1, g.f2, g.f3, g.q, D)
    y0 = [x1_0, x2_0, 0.0, 0.0, g.d0e0, 0.0, 0.0]
    z2_0 = float(fz2(y0[:5], *p))
    if z2_0 == 0.0:
        raise ValueError("z2(0) = 0: the law (7) is undefined there (claim smooth-7)")

    def rhs(_t, y):
        return f(y[:5], *p)

    # stop just before z2 reaches 0 from its initial side (the adaptive term jumps there, and
    # where the loop slides on z2 = 0 an integrator would crawl at ever smaller steps)
    level = math.copysign(Z2_STOP * max(1.0, abs(z2_0)), z2_0)

    def crossing(_t, y):
        return fz2(y[:5], *p) - level
    crossing.terminal = True
    sol = solve_ivp(rhs, (0.0, horizon), y0, events=crossing, **ROUTES[route])
    if sol.status < 0:
        raise RuntimeError(f"scalar instance: {sol.message}")
    y = sol.y[:, -1]
    if not np.all(np.isfinite(y)):
        raise ArithmeticError("scalar instance: non-finite state")
    return {"t_end": float(sol.t[-1]), "Z1": float(y[5]), "Z2": float(y[6]),
            "z1_0": float(x1_0), "z2_0": z2_0, "d0e_end": float(y[4])}


def v2_0(run: Mapping[str, float], g: ScalarGains, D: float, printed: bool) -> float:
    """V2(0) (``bounds.v2_initial``): (20) as printed (|z1(0)|^2/2 + |z2(0)|^2/2) or (12) at
    t = 0 (plus (d0e(0) - D)^2/(2q))."""
    return B.v2_initial(run["z1_0"], run["z2_0"], g.d0e0, D, g.q, printed=printed)


def bounds_19(run: Mapping[str, float], g: ScalarGains, D: float,
              printed: bool) -> tuple[float, float]:
    """(19a), (19b) (``bounds.z_l2_bounds``): the squared L2 bounds on z1, z2 over
    [0, t_end], as printed (with (20)'s V2(0) and V2(0)/f2bar) or derived (V2(0) of (12),
    V2(0)/(f2bar - f3bar))."""
    return B.z_l2_bounds(v2_0(run, g, D, printed), g.k1, g.f2, g.f3, printed=printed)


def _rel(bound: float, observed: float) -> float:
    return (bound - observed) / bound if bound > 0 else (-math.inf if observed > 0 else 0.0)


def margin_19(g: ScalarGains, point: Mapping[str, float], printed: bool,
              route: str = "fast") -> float:
    """min over (19a), (19b) of (bound - observed)/bound at ``point`` (x1_0, x2_0, D)."""
    run = fly(g, point["x1_0"], point["x2_0"], point["D"], route)
    b1, b2 = bounds_19(run, g, point["D"], printed)
    return min(_rel(b1, run["Z1"]), _rel(b2, run["Z2"]))


def margin_21a(g: ScalarGains, point: Mapping[str, float], printed: bool,
               route: str = "fast") -> float:
    """(21a) (``bounds.transient_bounds``) at ``point``: (bound - ||x1||)/bound, with du = 0
    (so ||B0 du|| = 0, lambda = 0 and x1 = z1)."""
    run = fly(g, point["x1_0"], point["x2_0"], point["D"], route)
    x1b, _ = B.transient_bounds(v2_0(run, g, point["D"], printed), 0.0, g.k1, g.f2, g.f3,
                                g.k1, printed=printed)
    return _rel(x1b, math.sqrt(run["Z1"]))


def observed(g: ScalarGains, point: Mapping[str, float], route: str = "reference") -> dict:
    """The run at ``point`` with the printed and derived bounds beside it (report numbers)."""
    run = fly(g, point["x1_0"], point["x2_0"], point["D"], route)
    bp = bounds_19(run, g, point["D"], True)
    bd = bounds_19(run, g, point["D"], False)
    return {**run, "(19a) printed": bp[0], "(19b) printed": bp[1], "(19a) derived": bd[0],
            "(19b) derived": bd[1], "ratio (19a) observed/printed": run["Z1"] / bp[0],
            "ratio (19b) observed/printed": run["Z2"] / bp[1]}
