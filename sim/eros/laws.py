"""Seed 002's six controllers as generated numpy code, from ``lgw.theory.eros.laws``.

The six variants: law in ("pdsmc", "ftsmc", "fuzzy") x switch in ("sign", "tanh").  Each is the
SymPy expression ``lgw.theory.eros.laws.control(law, switch)`` (with the |e| floor), lambdified
once (numpy, common subexpressions eliminated) and evaluated on arrays of any shape, e.g.
(cases, 3 axes).  The fuzzy distance D of (21)-(22) is the lambdified
``fuzzy_distance`` of the three axes' surface values.  tests/eros/test_sim_laws.py evaluates the
generated code against the SymPy expressions with exact numbers.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import sympy as sp
from lgw.theory.eros import laws as L
from lgw.theory.eros.gains import Gains

VARIANTS = tuple((law, sw) for law in L.LAWS for sw in L.SWITCHES)
STATE_ARGS = (L.e, L.ed, L.f, L.Dk, L.xdd, L.dist)
GAIN_ARGS = (L.alpha, L.beta, L.r, L.k, L.lam, L.N, L.M, L.phi, L.eps)


def variant_name(law: str, switch: str) -> str:
    return f"{law}-{switch}"


def parse_variant(name: str) -> tuple[str, str]:
    from lgw.theory.errors import ParameterError

    for law, sw in VARIANTS:
        if name == variant_name(law, sw):
            return law, sw
    raise ParameterError("--law", name, "one of " + ", ".join(variant_name(*v) for v in VARIANTS))


def gain_values(g: Gains) -> tuple[float, ...]:
    """The values of GAIN_ARGS for a gain set (the order of the generated functions)."""
    return (g.alpha, g.beta, g.r, g.k, g.lam, g.N, g.M, g.phi, g.e_floor)


@cache
def control_fn(law: str, switch: str):
    """u(e, ed, f, D_k, xdd_ref, d, *gains) for one axis, numpy-vectorised."""
    return sp.lambdify(STATE_ARGS + GAIN_ARGS, L.control(law, switch, floor=True), "numpy",
                       cse=True)


@cache
def surface_fn(law: str):
    return sp.lambdify((L.e, L.ed) + GAIN_ARGS, L.surface(law), "numpy")


@cache
def distance_fn():
    s1, s2, s3 = sp.symbols("s1:4", real=True)
    return sp.lambdify((s1, s2, s3, L.alpha), L.fuzzy_distance((s1, s2, s3)), "numpy")


def evaluate(law: str, switch: str, e, ed, f, Dk, xdd, g: Gains) -> tuple[np.ndarray, np.ndarray]:
    """Control u and surface s for arrays (..., 3) of the per-axis inputs (generated code)."""
    gv = gain_values(g)
    s = np.asarray(surface_fn(law)(e, ed, *gv), dtype=float)
    s = np.broadcast_to(s, np.shape(e))
    if law == "fuzzy":
        d = distance_fn()(s[..., 0], s[..., 1], s[..., 2], g.alpha)[..., None]
    else:
        d = np.zeros(np.shape(e)[:-1] + (1,))
    u = np.asarray(control_fn(law, switch)(e, ed, f, Dk, xdd, d, *gv), dtype=float)
    return np.broadcast_to(u, np.shape(e)).copy(), s


def fuzzy_weights(s: np.ndarray, g: Gains) -> tuple[np.ndarray, np.ndarray]:
    """a(D), b(D) of (22) for surface values s (..., 3) (for plots / records)."""
    d = distance_fn()(s[..., 0], s[..., 1], s[..., 2], g.alpha)
    a, b = L.fuzzy_weights()
    fa = sp.lambdify((L.dist, L.N), a, "numpy")
    fb = sp.lambdify((L.dist, L.M), b, "numpy")
    return fa(d, g.N), fb(d, g.M)
