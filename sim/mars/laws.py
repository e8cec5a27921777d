"""The registry of guidance laws the simulator runs, compiled from ``theory``'s SymPy expressions.

Every law is one SymPy expression for the commanded (thrust) acceleration a_i of one axis,
with leading arguments (r, v, grav, a_m, m) and then per-axis parameters.  The simulator never
re-types a law: ``numba_law`` lambdifies the expression to ``math``-module code (with common
subexpressions eliminated) and compiles it with ``numba.njit``; ``numpy_law`` uses the numpy
lambdification from ``theory`` (the reference mode and python-control interop use it).  A test
evaluates both against the SymPy expression with exact numbers at random points.

Registered laws:
  "corrected"       the workbench default: guidance derived from seed 000 (22) with s1' = v
                    (``lgw.theory.mars.mss.law_corrected``); proven bounds in
                    ``lgw.theory.mars.bounds``;
  "printed"         seed 000 (25) as printed (``lgw.theory.mars.mss.law_printed``);
  "super-twisting"  seed 000 (46), the STSMG baseline (``lgw.theory.mars.supertwisting``);
                    parameters B1, B2 of the paper, the gain set is ignored.

How to add a law (three steps):
  1. write its SymPy expression in ``theory`` (a function returning sp.Expr in the per-axis
     symbols r, v, grav, a_m of ``lgw.theory.mars.mss``, plus m and any parameter symbols);
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
from lgw.sim.codegen import lambdified_source, nb_sig, nb_sign
from lgw.sim.integrate import CALLEE_ONLY
from lgw.theory.errors import ParameterError
from lgw.theory.mars import mss as mss
from lgw.theory.mars import supertwisting as st
from lgw.theory.mars.gains import Gains
from lgw.theory.symbolic import sig

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
    """Add (or replace) a law in the registry; see the module docstring.

    The generated code is cached per ``LawSpec`` (and on disk per expression), so replacing a
    law needs no cache clearing: the new spec is a new key."""
    if not isinstance(spec, LawSpec):
        raise ParameterError("spec", type(spec).__name__, "must be a LawSpec")
    LAWS[spec.name] = spec


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


def share_powers(expr: sp.Expr) -> tuple[sp.Expr, list[sp.Expr]]:
    """Rewrite exp((q + k) ln|x|) -> exp(q ln|x|) |x|^k when exp(q ln|x|) also occurs (k a
    small nonzero integer): one exp per family instead of one per power (the corrected law's
    |s1|^(q1-1), |s1|^(q2-1) next to |s1|^q1, |s1|^q2: 6 -> 4 exp per axis).

    Exact for x != 0 (up to rounding: one division or multiplication instead of an exp); at
    x = 0 it gives 0 * inf = NaN where the original gives +-inf or 0, and |x|^-1 overflows for
    |x| < 1/DBL_MAX, so ``numba_law`` calls the unshared expression when |x| <= TINY.
    Returns the rewritten expression and the x of each rewritten family.
    """
    exps = [e for e in expr.atoms(_ex)
            if isinstance(e.args[0], sp.Mul) and any(isinstance(f, _ln) for f in e.args[0].args)]
    by_log: dict = {}
    for e in exps:
        lns = [f for f in e.args[0].args if isinstance(f, _ln)]
        if len(lns) != 1:
            continue
        by_log.setdefault(lns[0], []).append((sp.expand(e.args[0] / lns[0]), e))
    subs = {}
    for ln_, fam in by_log.items():
        def above(q, fam=fam):  # a power of the family q + k, k in {1, 2} (the kept one)
            for q0, e0 in fam:
                k = sp.simplify(q - q0)
                if k.is_Integer and int(k) in (-1, -2):
                    return e0, int(k)
            return None
        for q, e in sorted(fam, key=lambda qe: sp.default_sort_key(qe[0])):
            hit = above(q)
            while hit is not None and above(_exponent(hit[0], ln_)) is not None:
                up = above(_exponent(hit[0], ln_))  # chain q -> q+1 -> q+2: use the top
                hit = (up[0], hit[1] + up[1])
            if hit is not None:
                subs[e] = hit[0] * ln_.args[0] ** hit[1]
    bases = sorted({ln_.args[0] for ln_, fam in by_log.items()
                    if any(e in subs for _, e in fam)}, key=sp.default_sort_key)
    return expr.xreplace(subs), bases


def _exponent(e: sp.Expr, ln_: sp.Expr) -> sp.Expr:
    return sp.expand(e.args[0] / ln_)


# Below this |x| the shared powers are not used (|x|^-1 overflows; 0 * inf at x = 0).
TINY = 1e-300


# LLVM fast-math flags that keep NaN/inf semantics (no "nnan"/"ninf": the simulator must see the
# singular values): contraction to fma, reassociation, reciprocal, approximate libm calls.
FASTMATH = {"contract", "reassoc", "arcp", "nsz", "afn"}

_NB_MODULES = [{"sig": nb_sig, "sign": nb_sign, "Abs": abs, "sqrt": math.sqrt,
                "_ln": math.log, "_ex": math.exp}, "math"]


def law_args(spec: LawSpec) -> tuple[sp.Symbol, ...]:
    return LEAD_ARGS + spec.params


def python_law(name: str) -> Callable[..., float]:
    """The generated scalar code f(r, v, grav, a_m, m, *params) (plain Python + math)."""
    return _python_law(get_law(name))


@cache
def _python_law(spec: LawSpec) -> Callable[..., float]:
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


# The symbols of s2 (21) in the column order of ``surface_params``.
SURFACE_SYMBOLS = (mss.beta1, mss.beta2, mss.q1, mss.q2)


@cache
def _generated(spec: LawSpec, with_s2: bool) -> dict:
    """The generated scalar code behind ``numba_law`` / ``numba_law_s2``: the exact form
    (``explog``), the form at r = v = 0 (``origin_expr``), the ``share_powers`` form and its
    guard, each returning a, or (a, s2) with s2 of (21) computed in the same code (common
    subexpressions shared with the law) when with_s2.  Arguments: law_args, then the surface
    symbols the law does not have (``extra``, taken from surface_params)."""
    exprs = [spec.expr()] + ([mss.surface2()] if with_s2 else [])
    extra = _extra(spec, with_s2)
    args = law_args(spec) + extra

    def lam(es: list[sp.Expr]) -> Callable:
        return sp.lambdify(args, es[0] if len(es) == 1 else tuple(es), modules=_NB_MODULES,
                           cse=True)

    exact = [explog(e) for e in exprs]
    out = {"extra": extra, "exact": lam(exact),
           "origin": lam([explog(e.subs(mss.v, 0)) for e in exprs]), "shared": None}
    shared, bases = share_powers(sp.Tuple(*exact))
    if bases:
        guard = bases[0] if len(bases) == 1 else sp.Min(*bases)
        out["shared"] = lam(list(shared.args))
        out["guard"] = sp.lambdify(args, guard, modules=_NB_MODULES)
    return out


def python_law_origin(name: str) -> Callable[..., float]:
    """``python_law`` of ``origin_expr``: the law at r = v = 0, same arguments."""
    return _generated(get_law(name), False)["origin"]


def _extra(spec: LawSpec, with_s2: bool) -> tuple[sp.Symbol, ...]:
    return tuple(x for x in SURFACE_SYMBOLS if x not in spec.params) if with_s2 else ()


def law_source(spec: LawSpec, with_s2: bool) -> str:
    """Module source defining ``law``, the law compiled for one axis (see ``numba_law`` and
    ``numba_law_s2``): the generated forms of ``_generated`` as lambdify wrote them
    (``lgw.sim.codegen.lambdified_source``), each njit-compiled, and the branch between them."""
    gen = _generated(spec, with_s2)
    imports: set[str] = set()
    parts = []
    for key in ("exact", "origin", "shared", "guard"):
        if gen.get(key) is None:
            continue
        src, imp = lambdified_source(gen[key], f"_{key}")
        imports |= set(imp)
        # a part only ``law`` calls: no wrappers (lgw.sim.integrate.CALLEE_ONLY)
        opts = (f'error_model="numpy", {CALLEE_ONLY}'
                + (", fastmath=FASTMATH" if key != "guard" else ""))
        parts += [src, f"_{key} = numba.njit(_{key}, {opts})", ""]
    pars = ", ".join([f"P[i, {j}]" for j in range(len(spec.params))]
                     + [f"SP[i, {SURFACE_SYMBOLS.index(x)}]" for x in gen["extra"]])
    call = f"(r, v, grav, a_m, m, {pars})"
    fast = ""
    if gen["shared"] is not None:
        fast = f"    if abs(_guard{call}) > TINY:\n        return _shared{call}\n"
    parts.append(f"def law(r, v, grav, a_m, m, P, {'SP, ' if with_s2 else ''}i):\n"
                 f"{fast}"
                 f"    if r == 0.0 and v == 0.0:\n"
                 f"        return _origin{call}\n"
                 f"    return _exact{call}\n\n\n"
                 'law = numba.njit(law, error_model="numpy", inline="always")\n')
    fm = "{" + ", ".join(repr(f) for f in sorted(FASTMATH)) + "}"
    return "\n".join([*sorted(imports), f"TINY = {TINY!r}", f"FASTMATH = {fm}", "", *parts])


def law_key_parts(spec: LawSpec, with_s2: bool) -> list[str]:
    """What the generated law depends on: its expression, s2 and the symbols' order."""
    parts = [spec.name, sp.srepr(spec.expr()), sp.srepr(law_args(spec)), str(with_s2)]
    if with_s2:
        parts += [sp.srepr(mss.surface2()), sp.srepr(_extra(spec, with_s2))]
    return parts


def _law_module(name: str, with_s2: bool):
    from lgw.sim.mars import kernel
    if with_s2:
        return kernel.kernel_module(name)
    return kernel.law_module(name)


def numba_law(name: str) -> Callable[..., float]:
    """The law compiled for one axis: f(r, v, grav, a_m, m, P, i) with P[i] the axis's parameters.

    P and the row index are passed (not the row P[i]) because slicing in a numba prange loop
    reference-counts the parent array atomically, which costs more than the law itself.

    error_model="numpy": 0 ** (negative) and x/0 give inf (not an exception), so the corrected
    law at s1 = 0, v != 0 returns +-inf; the simulator saturates it (limits on) or flags the case.
    At r = v = 0 exactly (an axis at its equilibrium) the law is evaluated with v = 0 substituted
    symbolically (``origin_expr``): the limit along the solution, finite, instead of 0 * inf.
    Elsewhere the ``share_powers`` form is used where it is exact (|x| > TINY for each shared
    family), ``python_law`` otherwise.  Compiled from a generated module in the kernel cache
    (``lgw.sim.kernel_cache``).
    """
    return _law_module(name, False).law


def numba_law_s2(name: str) -> Callable[..., tuple[float, float]]:
    """The law and s2 (21) in one compiled function: f(r, v, grav, a_m, m, P, SP, i) -> (a, s2),
    SP = ``surface_params`` (used for the s2 symbols the law does not have).  The simulator
    needs s2 at every node; computing it with the law shares |r|^q1, |r|^q2 (and saves one
    ln and two exp per axis and node for the sliding-mode laws).  Same branches as numba_law.
    This is the very function the simulator's kernel calls (``lgw.sim.mars.kernel``)."""
    return _law_module(name, True).law


def numpy_law(name: str) -> Callable[..., np.ndarray]:
    """The law as numpy code: f(r, v, grav, a_m, m, P) with r, v (..., 3), m (...,) and P (3, k).

    Uses ``theory``'s own lambdification (lgw.theory.mars.mss.law_numeric for the sliding-mode laws,
    lgw.theory.mars.supertwisting.supertwisting_numeric for (46)) where it exists.
    """
    return _numpy_law(get_law(name))


@cache
def _numpy_law(spec: LawSpec) -> Callable[..., np.ndarray]:
    name = spec.name
    from lgw.theory.symbolic import LAMBDIFY_MODULES
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



# --- the bounded cascade law (lgw.theory.mars.bounded), gains from [bounded] --------
from lgw.theory.mars import bounded as _bounded  # noqa: E402  (kept with its one registration)

register_law(LawSpec(_bounded.NAME, _bounded.law_bounded, _bounded.PARAMS,
                     lambda g: _bounded.bounded_from_extra(g.extra).params(),
                     "bounded cascade: s = v + psi(r), finite continuous command, "
                     "proven time and command bounds; gains from the [bounded] table"))

# the saturated-cancellation variant (lgw.theory.mars.bounded.law_bounded_sat), gains
# from [bounded-sat]; its box bounds are lgw.theory.mars.bounded_sat.axis_box_bounds_sat.
from lgw.theory.mars import bounded_sat as _bounded_sat  # noqa: E402

register_law(LawSpec(_bounded_sat.NAME, _bounded.law_bounded_sat, _bounded.PARAMS_SAT,
                     lambda g: _bounded_sat.sat_from_extra(g.extra).params(),
                     "bounded cascade with saturated cancellation psi'(r) sat(v, psi(|r|) + w0) "
                     ": proven box bounds; gains from the [bounded-sat] table"))
