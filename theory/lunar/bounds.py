"""Seed 001's bounds as functions of the gains: one implementation used by the CLI, the report,
the simulator checks and the tests.

Norms ||.|| of signals are L2 norms over [0, t] (the horizon of the run): the derivation of
(18), (19) integrates (17b), (13) from 0 to t, so every bound holds for each finite t with the
truncated norms, and on [0, inf) only when the right-hand side is finite (claim L2-finite).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp
from lgw.theory.errors import MissingDependency
from lgw.theory.lunar.gains import A_H, LoopGains


def _sqrt(x: Any) -> Any:
    """sqrt of a float, or of a SymPy expression (the claims evaluate the same bound functions
    on symbols, so that the printed and derived forms they judge are these functions)."""
    return sp.sqrt(x) if isinstance(x, sp.Basic) else math.sqrt(x)


def _sumsq(v: Any) -> Any:
    """|v|^2 of a vector (float), or of a SymPy scalar / list of SymPy scalars."""
    if isinstance(v, sp.Basic):
        return v ** 2
    a = np.atleast_1d(np.asarray(v))
    if a.dtype == object:
        return sum(x ** 2 for x in a)
    return float(np.dot(a, a))


def f1bar_orbit(g: LoopGains) -> float:
    """Minimum eigenvalue of F1 = a_h K1 a_h^T = K1_zz (seed 001 (10), (22))."""
    return float((A_H @ g.K1 @ A_H.T)[0, 0])


def f1_attitude(eq: np.ndarray) -> np.ndarray:
    """f1 = (eq0 I + S(eq)) / 2 of seed 001 (27a); eq = [eq0, eq1, eq2, eq3]."""
    e0, v = eq[0], np.asarray(eq[1:], dtype=float)
    S = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return 0.5 * (e0 * np.eye(3) + S)


def f1bar_attitude(g: LoopGains, eq0_min: float) -> float:
    """A lower bound on the minimum eigenvalue of F1 = f1 K1 f1^T over unit error quaternions
    with |eq0| >= eq0_min: lambda_min(sym K1) * eq0_min^2 / 4, since f1 f1^T = (I - eq eq^T)/4
    has minimum eigenvalue eq0^2 / 4 (claim attitude-F1); exact for K1 = k I."""
    k1 = float(np.linalg.eigvalsh(0.5 * (g.K1 + g.K1.T)).min())
    return k1 * eq0_min ** 2 / 4.0


def lambda_gain_bounds(f1bar: float, f2bar: float) -> tuple[float, float]:
    """(18a), (18b): ||lambda1|| <= ||B0 du|| / sqrt(2 f1bar),
    ||lambda2|| <= ||B0 du|| / sqrt(2 f2bar - 1) (L2 norms, lambda(0) = 0).  As printed, and
    what integrating (17b) gives (claim L2-18).  A numeric f1bar = 0 (the attitude error at 180
    degrees, claim attitude-F1) gives an infinite (18a) constant: the bound says nothing."""
    numeric_zero = not isinstance(f1bar, sp.Basic) and f1bar == 0
    return (math.inf if numeric_zero else 1 / _sqrt(2 * f1bar)), 1 / _sqrt(2 * f2bar - 1)


def v2_initial(z1_0: np.ndarray, z2_0: np.ndarray, d0e0: float = 0.0, D: float = 0.0,
               q: float = 1.0, printed: bool = False) -> float:
    """V2(0) of (12): 1/2 |z1(0)|^2 + 1/2 |z2(0)|^2 + (d0e(0) - D)^2 / (2 q).

    The printed (20) omits the last term (``printed=True`` reproduces it); (12) at t = 0 has
    it, and it is what integrating (13) needs.  D is the bound on ||d|| that d0e estimates."""
    v = _sumsq(z1_0) / 2 + _sumsq(z2_0) / 2
    return v if printed else v + (d0e0 - D) ** 2 / (2 * q)


def z_l2_bounds(v20: float, f1bar: float, f2bar: float, f3: float,
                printed: bool = False) -> tuple[float, float]:
    """(19): squared L2 norms ||z1||^2 <= V2(0)/f1bar, ||z2||^2 <= V2(0)/(f2bar - f3).

    Integrating (13) gives f2bar - f3 in (19b); the printed (19b) has f2bar, which (13) does
    not imply (``printed=True`` reproduces it)."""
    return v20 / f1bar, v20 / (f2bar if printed else f2bar - f3)


def z_l2_bounds_printed(z1_0: np.ndarray, z2_0: np.ndarray, f1bar: float,
                        f2bar: float) -> tuple[float, float]:
    """(19)-(20) exactly as printed: (V2(0)/f1bar, V2(0)/f2bar) with the printed (20)
    V2(0) = |z1(0)|^2/2 + |z2(0)|^2/2 (no (d0e(0) - D)^2/(2q) term, and f2bar where (13) gives
    f2bar - f3bar).  The bound claim L2-19-20 refutes (a scalar instance exceeds it); it is
    the one a "(19b) as printed" row must use."""
    return z_l2_bounds(v2_initial(z1_0, z2_0, printed=True), f1bar, f2bar, 0.0, printed=True)


def transient_bounds(v20: float, w_l2: float, f1bar: float, f2bar: float, f3: float,
                     k1f1_norm: float, printed: bool = False) -> tuple[float, float]:
    """(21): L2 bounds on x1 and x2 from x1 = z1 + lambda1, x2 = z2 + lambda2 + p (Minkowski).

    (21a) ||x1|| <= (sqrt(2 V2(0)) + ||B0 du||) / sqrt(2 f1bar)
    (21b) ||x2|| <= sqrt(V2(0)/(f2bar - f3)) + ||B0 du||/sqrt(2 c2) + ||K1 f1^T|| ||x1||,
    with the undefined c2bar of the paper read as f2bar - 1/2 (so that 1/sqrt(2 c2) is the
    constant of (18b)), A1 read as -K1 (from z2(0) in (20) and p of (10)), ||K1 f1^T|| the
    supremum over the run of its spectral norm and ||x1|| the bound (21a).  ``printed=True``
    uses the printed 1/sqrt(f2bar) in the first term."""
    x1b = (_sqrt(2 * v20) + w_l2) / _sqrt(2 * f1bar)
    first = _sqrt(v20 / (f2bar if printed else f2bar - f3))
    x2b = first + w_l2 / _sqrt(2 * (f2bar - sp.Rational(1, 2) if isinstance(f2bar, sp.Basic)
                                    else f2bar - 0.5)) + k1f1_norm * x1b
    return x1b, x2b


def filter_matrices(F1: np.ndarray, f1: np.ndarray, F2: np.ndarray):
    """State-space form of the virtual-state filter (11) with input w = B0 du:
    [l1; l2]' = A [l1; l2] + B w, outputs l1 and l2."""
    n1, n2 = f1.shape
    A = np.block([[-F1, f1], [-f1.T, -F2]])
    B = np.vstack([np.zeros((n1, n2)), np.eye(n2)])
    C1 = np.hstack([np.eye(n1), np.zeros((n1, n2))])
    C2 = np.hstack([np.zeros((n2, n1)), np.eye(n2)])
    return A, B, C1, C2


def hinf_gains(F1: np.ndarray, f1: np.ndarray, F2: np.ndarray) -> dict[str, float]:
    """True L2 gains (H-infinity norms) of the frozen filter (11) from B0 du to lambda1 and to
    lambda2, by python-control (``linfnorm``, SLICOT AB13DD), and by an independent dense
    frequency sweep of the largest singular value (a lower bound on each norm)."""
    import control

    A, B, C1, C2 = filter_matrices(F1, f1, F2)
    out: dict[str, float] = {}
    for name, C in (("lambda1", C1), ("lambda2", C2)):
        sys = control.ss(A, B, C, np.zeros((C.shape[0], B.shape[1])))
        try:
            gam, wpk = control.linfnorm(sys, tol=1e-10)
        except control.ControlSlycot as exc:
            raise MissingDependency("slycot", "python-control's H-infinity norm (linfnorm, "
                                    "SLICOT AB13DD)") from exc
        w = np.concatenate([[0.0], np.logspace(-5, 4, 4000)])
        I = np.eye(A.shape[0])
        sweep = max(np.linalg.svd(C @ np.linalg.solve(1j * wi * I - A, B),
                                  compute_uv=False)[0] for wi in w)
        out[f"{name}_hinf"] = float(gam)
        out[f"{name}_peak_rad_s"] = float(wpk)
        out[f"{name}_sweep"] = float(sweep)
    return out


@dataclass(frozen=True)
class LoopBounds:
    f1bar: float
    f2bar: float
    lambda1_gain: float  # (18a) constant
    lambda2_gain: float  # (18b) constant
    hinf: dict

    def to_dict(self) -> dict:
        return {"f1bar": self.f1bar, "f2bar": self.f2bar, "lambda1_gain_18a": self.lambda1_gain,
                "lambda2_gain_18b": self.lambda2_gain, **self.hinf}


def orbit_bounds(g: LoopGains) -> LoopBounds:
    """(18) and the true filter gains for the orbit loop (f1 = a_h: the filter is LTI)."""
    f1b = f1bar_orbit(g)
    F1 = A_H @ g.K1 @ A_H.T
    return LoopBounds(f1b, g.f2bar, *lambda_gain_bounds(f1b, g.f2bar),
                      hinf_gains(F1, A_H, g.F2))


def attitude_bounds(g: LoopGains, eq0_min: float = 1.0) -> LoopBounds:
    """(18) with f1bar for |eq0| >= eq0_min, and the true gains of the filter frozen at
    e_Q = [eq0_min, sqrt(1 - eq0_min^2), 0, 0] (the filter is time-varying through f1(e_q);
    the frozen gain is the LTI gain at that error, not the gain of the time-varying filter)."""
    f1b = f1bar_attitude(g, eq0_min)
    eq = np.array([eq0_min, math.sqrt(max(0.0, 1.0 - eq0_min ** 2)), 0.0, 0.0])
    f1 = f1_attitude(eq)
    F1 = f1 @ g.K1 @ f1.T
    return LoopBounds(f1b, g.f2bar, *lambda_gain_bounds(f1b, g.f2bar),
                      hinf_gains(F1, f1, g.F2))
