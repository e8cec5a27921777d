"""Seed 001's law (7), (8), (10), (11) as generated code: lambdify of the SymPy expressions of
``lgw.theory.lunar.law`` (the expressions whose V2' is checked against (13)), batched over cases
by numpy broadcasting (every argument may be an array of shape (N,)).

The adaptive term of (7) is undefined at z2 = 0 (claim smooth-7); the generated code takes
||z2|| as an argument and the wrapper passes max(||z2||, 1e-150), which sets the term to 0 at
z2 = 0 exactly (the value of its numerator there).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.lunar import law as L

TINY = 1e-150  # nz^2 must stay a normal float: 1e-300 squared underflows to 0 (0/0)


@dataclass(frozen=True)
class GeneratedLaw:
    """Generated functions of one loop: p, z2, u_c, with their argument order."""

    args: tuple
    z2: object
    uc: object
    V2_part: object  # 1/2 |z1|^2 + 1/2 |z2|^2 (the d0e term is added by the caller)


def _lambdify(S: L.GeneralSystem, extra: tuple) -> GeneratedLaw:
    args = (*S.x1, *S.x2, *S.lam1, *S.lam2, S.d0e, *extra, S.f3, S.nz)
    z2 = sp.lambdify(args, list(S.z2), "numpy", cse=True)
    uc = sp.lambdify(args, list(S.uc), "numpy", cse=True)
    v2p = sp.lambdify(args, ((S.z1.T * S.z1)[0] + (S.z2.T * S.z2)[0]) / 2, "numpy", cse=True)
    return GeneratedLaw(tuple(str(a) for a in args), z2, uc, v2p)


@cache
def orbit_law() -> GeneratedLaw:
    """Orbit loop (22): args e_h, e_v1..3, lambda1_1, lambda2_1..3, d0e, m, K1 (9), F2 (9),
    f3, ||z2||."""
    S = L.orbit_system(full=True)
    return _lambdify(S, (sp.Symbol("m", positive=True), *S.K1, *S.F2))


@cache
def attitude_law() -> GeneratedLaw:
    """Attitude loop (27): args e_q1..3, e_w1..3, lambda1 (3), lambda2 (3), d0e, e_q0,
    f2 (3), J (3), K1 (9), F2 (9), f3, ||z2||."""
    S = L.attitude_system()
    eq0 = sp.Symbol("e_q0", real=True)
    J = sp.symbols("J_1:4", positive=True)
    return _lambdify(S, (eq0, *S.f2, *J, *S.K1, *S.F2))


def _call(f, *a):
    out = f(*a)
    return np.array([np.broadcast_to(np.asarray(o, dtype=float), np.shape(a[0])) for o in out])


def evaluate(gl: GeneratedLaw, x1, x2, lam1, lam2, d0e, extra) -> tuple[np.ndarray, ...]:
    """(u_c, z2, ||z2||, 1/2|z1|^2 + 1/2|z2|^2) for batched arrays (components first)."""
    base = (*x1, *x2, *lam1, *lam2, d0e, *extra)
    z2 = _call(gl.z2, *base, 0.0, 1.0)  # z2 does not depend on f3 or ||z2||
    nz = np.sqrt(np.sum(z2 * z2, axis=0))
    return z2, nz, base


def orbit_command(eh, ev, lam1, lam2, d0e, m, g) -> tuple[np.ndarray, ...]:
    """u_co of (7) for the orbit loop and its z2, ||z2||, V2 part; ``g`` is a dict of arrays
    K1 (3, 3, N), F2 (3, 3, N), f3 (N)."""
    gl = orbit_law()
    extra = (m, *g["K1"].reshape(9, -1), *g["F2"].reshape(9, -1))
    z2, nz, base = evaluate(gl, [eh], ev, [lam1], lam2, d0e, extra)
    nzs = np.maximum(nz, TINY)
    uc = _call(gl.uc, *base, g["f3"], nzs)
    v2 = np.asarray(gl.V2_part(*base, g["f3"], nzs), dtype=float)
    return uc, z2, nz, v2


def attitude_command(eq0, eq, ew, lam1, lam2, d0e, f2, J, g) -> tuple[np.ndarray, ...]:
    """M_c of (7) for the attitude loop (B0 = J^-1) and its z2, ||z2||, V2 part."""
    gl = attitude_law()
    extra = (eq0, *f2, *J, *g["K1"].reshape(9, -1), *g["F2"].reshape(9, -1))
    z2, nz, base = evaluate(gl, eq, ew, lam1, lam2, d0e, extra)
    nzs = np.maximum(nz, TINY)
    uc = _call(gl.uc, *base, g["f3"], nzs)
    v2 = np.asarray(gl.V2_part(*base, g["f3"], nzs), dtype=float)
    return uc, z2, nz, v2
