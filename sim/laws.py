"""The registry of guidance laws the simulator runs, compiled from ``theory``'s SymPy expressions.

Every law is one SymPy expression for the commanded (thrust) acceleration a_i of one axis,
with leading arguments (r, v, grav, a_m, m) and then per-axis parameters.  The simulator never
re-types a law: ``numba_law`` lambdifies the expression to ``math``-module code (with common
subexpressions eliminated) and compiles it with ``numba.njit``; ``numpy_law`` uses the numpy
lambdification from ``theory`` (the reference mode and python-control interop use it).  A test
evaluates both against the SymPy expression with exact numbers at random points.

Registered laws:
  "corrected"       the workbench default: guidance derived from seed 000 (22) with s1' = v
                    (``theory.mars_mss.law_corrected``); proven bounds in ``theory.mars_bounds``;
  "printed"         seed 000 (25) as printed (``theory.mars_mss.law_printed``);
  "super-twisting"  seed 000 (46), the STSMG baseline (``theory.mars_supertwisting``);
                    parameters B1, B2 of the paper, the gain set is ignored.

How to add a law (three steps):
  1. write its SymPy expression in ``theory`` (a function returning sp.Expr in the per-axis
     symbols r, v, grav, a_m of ``theory.mars_mss``, plus m and any parameter symbols);
  2. call ``register_law(LawSpec(name, expr_fn, params, param_values, description))`` here (or
     from your own module before simulating), where ``params`` are the parameter symbols in
     order and ``param_values(gains) -> (3, len(params))`` array gives their value per axis;
  3. ``simulate_batch(..., law=name)`` and ``lgw simulate mars --law name`` then run it; add it to
     the generated-vs-symbolic test in tests/test_sim_laws.py.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import numba
import numpy as np
import sympy as sp

from theory import mars_mss as mss
from theory import mars_supertwisting as st
from theory.errors import ParameterError
from theory.gains import Gains
from theory.symbolic import sig

# The leading per-axis arguments every law receives.
LEAD_ARGS = (mss.r, mss.v, mss.grav, mss.am, st.m)


@dataclass(frozen=True)
class LawSpec:
    """One registered law: its SymPy expression and how to get its parameters."""

    name: str
    expr: Callable[[], sp.Expr]
    params: tuple[sp.Symbol, ...]
    param_values: Callable[[Gains], np.ndarray]
    description: str


def _mss_params(g: Gains) -> np.ndarray:
    return np.column_stack([g.beta1, g.beta2, g.alpha1, g.alpha2,
                            np.full(3, g.q1), np.full(3, g.q2),
                            np.full(3, g.g1), np.full(3, g.g2)]).astype(float)


def _st_params(g: Gains) -> np.ndarray:
    del g  # (46) uses the paper's B1, B2, not the sliding-surface gains
    return np.column_stack([st.B1_PAPER, st.B2_PAPER]).astype(float)


LAWS: dict[str, LawSpec] = {}


def register_law(spec: LawSpec) -> None:
    """Add (or replace) a law in the registry; see the module docstring."""
    LAWS[spec.name] = spec
    # defined below; not yet at import
    for fn in ("python_law", "python_law_origin", "numba_law", "numpy_law"):
        if fn in globals():
            globals()[fn].cache_clear()


register_law(LawSpec("corrected", mss.law_corrected, mss.GAIN_SYMBOLS, _mss_params,
                     "guidance from (22) with s1' = v (workbench default, proven bounds)"))
register_law(LawSpec("printed", mss.law_printed, mss.GAIN_SYMBOLS, _mss_params,
                     "seed 000 eq. (25) as printed (exact only on s2 = 0)"))
register_law(LawSpec("super-twisting", st.law_supertwisting, st.ST_PARAMS, _st_params,
                     "seed 000 eq. (46), STSMG baseline, B1=(1200,1000,1000), "
                     "B2=(5500,5000,5000)"))


def get_law(name: str) -> LawSpec:
    if name not in LAWS:
        raise ParameterError("law", name, f"must be one of {', '.join(LAWS)}")
    return LAWS[name]


# --- numba building blocks the generated code calls ---------------------------------------

@numba.njit(cache=True, error_model="numpy")
def nb_sig(x: float, q: float) -> float:
    """sig(x, q) = |x|^q sgn(x), as ``theory.symbolic.np_sig`` (0 at 0; NaN for q < 0 at 0)."""
    s = 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)
    return s * abs(x) ** q


@numba.njit(cache=True, error_model="numpy")
def nb_sign(x: float) -> float:
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


class _ln(sp.Function):  # noqa: N801  unevaluated log, so SymPy cannot fold exp(q ln x) back
    nargs = 1


class _ex(sp.Function):  # noqa: N801  unevaluated exp
    nargs = 1


def explog(expr: sp.Expr) -> sp.Expr:
    """Rewrite sig(x, q) -> sgn(x) exp(q ln|x|) and |x|^q -> exp(q ln|x|) (q not an integer).

    Mathematically the same expression (with 0^q = exp(-inf q): 0 for q > 0, inf for q < 0,
    as the compiled pow gives); after common-subexpression elimination each ln|x| is computed
    once for all the powers of x, which roughly halves the cost of the law.
    """
    expr = expr.replace(sig, lambda x, q: sp.sign(x) * _ex(q * _ln(sp.Abs(x))))
    return expr.replace(
        lambda e: e.is_Pow and isinstance(e.base, sp.Abs) and not e.exp.is_Integer,
        lambda e: _ex(e.exp * _ln(e.base)))


# LLVM fast-math flags that keep NaN/inf semantics (no "nnan"/"ninf": the simulator must see the
# singular values): contraction to fma, reassociation, reciprocal, approximate libm calls.
FASTMATH = {"contract", "reassoc", "arcp", "nsz", "afn"}

_NB_MODULES = [{"sig": nb_sig, "sign": nb_sign, "Abs": abs, "sqrt": math.sqrt,
                "_ln": math.log, "_ex": math.exp}, "math"]


def law_args(spec: LawSpec) -> tuple[sp.Symbol, ...]:
    return LEAD_ARGS + spec.params


@cache
def python_law(name: str) -> Callable[..., float]:
    """The generated scalar code f(r, v, grav, a_m, m, *params) (plain Python + math)."""
    spec = get_law(name)
    return sp.lambdify(law_args(spec), explog(spec.expr()), modules=_NB_MODULES, cse=True)


def origin_expr(spec: LawSpec) -> sp.Expr:
    """The law on an axis at its equilibrium r = v = 0: the expression with v = 0 substituted.

    At r = v = 0 the singular terms of the registered laws are 0 * inf in floating point (the
    corrected law's beta1 q1 |s1|^(q1-1) v, (46)'s |s|^(-1/2) s').  Their value along the solution
    through that point is 0: the axis sits at its equilibrium (s1 = s2 = 0 for all t, v = 0
    identically), so the command is the limit along v = 0, i.e. the law with v := 0 (for the
    corrected law -g - a_m; for (46) -g).  r = 0 with v != 0 stays a genuine +-inf.
    """
    return spec.expr().subs(mss.v, 0)


@cache
def python_law_origin(name: str) -> Callable[..., float]:
    """``python_law`` of ``origin_expr``: the law at r = v = 0, same arguments."""
    spec = get_law(name)
    return sp.lambdify(law_args(spec), explog(origin_expr(spec)), modules=_NB_MODULES, cse=True)


@cache
def numba_law(name: str) -> Callable[..., float]:
    """The law compiled for one axis: f(r, v, grav, a_m, m, P, i) with P[i] the axis's parameters.

    P and the row index are passed (not the row P[i]) because slicing in a numba prange loop
    reference-counts the parent array atomically, which costs more than the law itself.

    error_model="numpy": 0 ** (negative) and x/0 give inf (not an exception), so the corrected
    law at s1 = 0, v != 0 returns +-inf; the simulator saturates it (limits on) or flags the case.
    At r = v = 0 exactly (an axis at its equilibrium) the law is evaluated with v = 0 substituted
    symbolically (``origin_expr``): the limit along the solution, finite, instead of 0 * inf.
    """
    spec = get_law(name)
    core = numba.njit(python_law(name), error_model="numpy", fastmath=FASTMATH)
    core0 = numba.njit(python_law_origin(name), error_model="numpy", fastmath=FASTMATH)
    k = len(spec.params)
    pars = ", ".join(f"P[i, {j}]" for j in range(k))
    src = (f"def law_p(r, v, grav, a_m, m, P, i):\n"
           f"    if r == 0.0 and v == 0.0:\n"
           f"        return core0(r, v, grav, a_m, m, {pars})\n"
           f"    return core(r, v, grav, a_m, m, {pars})\n")
    ns: dict = {"core": core, "core0": core0}
    exec(src, ns)  # noqa: S102  (source generated above from the registry, no user text)
    return numba.njit(ns["law_p"], error_model="numpy")


@cache
def numpy_law(name: str) -> Callable[..., np.ndarray]:
    """The law as numpy code: f(r, v, grav, a_m, m, P) with r, v (..., 3), m (...,) and P (3, k).

    Uses ``theory``'s own lambdification (theory.mars_mss.law_numeric for the sliding-mode laws,
    theory.mars_supertwisting.supertwisting_numeric for (46)) where it exists.
    """
    spec = get_law(name)
    from theory.symbolic import LAMBDIFY_MODULES
    modules = [{"sign": np.sign}] + LAMBDIFY_MODULES
    fn0 = sp.lambdify(law_args(spec), origin_expr(spec), modules=modules)

    def at_origin(a, r, v, grav, a_m, m, P):
        # axes exactly at r = v = 0: the limit along the solution (``origin_expr``), not 0 * inf
        r = np.asarray(r, float)
        v = np.asarray(v, float)
        at0 = (r == 0.0) & (v == 0.0)
        if not np.any(at0):
            return a
        a0 = fn0(r, v, grav, a_m, np.asarray(m, float)[..., None], *P.T)
        return np.where(at0, a0, a)

    if name in mss.LAWS:
        fn = mss.law_numeric(name)

        def f(r, v, grav, a_m, m, P):
            return at_origin(fn(r, v, grav, a_m, *P.T), r, v, grav, a_m, m, P)
        return f
    if name == "super-twisting":
        fn = st.supertwisting_numeric()
    else:
        fn = sp.lambdify(law_args(spec), spec.expr(), modules=modules)

    def g(r, v, grav, a_m, m, P):
        a = fn(r, v, grav, a_m, np.asarray(m, float)[..., None], *P.T)
        return at_origin(a, r, v, grav, a_m, m, P)
    return g


# --- the sliding variables, for diagnostics and the worst-case disturbance ----------------

@cache
def numba_s2() -> Callable[..., float]:
    """s2 of seed 000 (21) compiled: f(r, v, beta1, beta2, q1, q2)."""
    args = (mss.r, mss.v, mss.beta1, mss.beta2, mss.q1, mss.q2)
    return numba.njit(sp.lambdify(args, explog(mss.surface2()), modules=_NB_MODULES, cse=True),
                      error_model="numpy")


def surface_params(g: Gains) -> np.ndarray:
    """(3, 4) array [beta1, beta2, q1, q2] per axis for s2 (21)."""
    return np.column_stack([g.beta1, g.beta2, np.full(3, g.q1), np.full(3, g.q2)]).astype(float)
