"""Provers that make evidence (``lgw.theory.evidence``).

Each returns a ``Step`` whose status is computed from the evidence it carries; nothing here
(or anywhere) writes a status by hand:
  prove_identity / identity_at     SymPy residual (kept); at a stated exact point as well
  prove_nonneg / refute_nonneg_at  SymPy assumptions (None is unproven); a negative exact value
  prove_z3                         z3 on a polynomial form (hypotheses => goal), query kept
  prove_arb                        Arb (python-flint) enclosure over a stated box, box kept
  search_step / witness_step       falsification over a stated domain and budget
``run_search`` is the one place where today's slice searches run; the full-domain engine
(``lgw.theory.falsify``) replaces it there.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp
from lgw.theory.evidence import Identity, Inequality, Search, Step, Witness
from lgw.theory.symbolic import LAMBDIFY_MODULES


def _rational_point(symbols: Iterable[sp.Symbol], rng: random.Random,
                    ranges: Mapping[sp.Symbol, tuple[float, float]]) -> dict:
    """An exact rational point with every coordinate strictly inside its range: ``ranges``
    holds the hypotheses of the statement under test (e.g. 0 < q1 < 1 < q2), so a witness is
    never drawn where the statement does not claim anything.  Symbols without a range: (0.1,
    3) if positive, else (-3, 3) without 0."""
    pt = {}
    for s in symbols:
        lo, hi = ranges.get(s, (0.1, 3.0) if s.is_positive else (-3.0, 3.0))
        for _ in range(100):
            x = sp.Rational(round(rng.uniform(lo, hi), 3)).limit_denominator(1000)
            if lo < x < hi and x != 0:
                break
        else:  # a range narrower than the rounding: its midpoint, exactly
            x = (sp.nsimplify(lo) + sp.nsimplify(hi)) / 2
        pt[s] = x
    return pt


def in_ranges(point: Mapping[sp.Symbol, Any], ranges: Mapping[sp.Symbol, tuple[float, float]]
              ) -> bool:
    """Every coordinate of ``point`` strictly inside its range (the hypotheses)."""
    return all(lo < point[s] < hi for s, (lo, hi) in ranges.items() if s in point)


def identity_evidence(expr: sp.Expr, *, method: str = "sympy.simplify", samples: int = 8,
                      seed: int = 0, ranges: Mapping[sp.Symbol, tuple[float, float]] | None = None,
                      simplified: sp.Expr | None = None) -> Identity:
    """Evidence for ``expr == 0`` identically: the residual after ``sp.simplify`` (or the
    given ``simplified`` form); if it is not 0, a search for an exact rational point where it
    is nonzero (evaluated at 30 digits and re-checked at 60): a refutation needs both.
    ``ranges``: the open interval of each symbol the statement's hypotheses allow (the
    sampler draws only there)."""
    ranges = ranges or {}
    simp = sp.simplify(expr) if simplified is None else simplified
    if simp == 0:
        return Identity(sp.Integer(0), method)
    rng = random.Random(seed)
    syms = sorted(expr.free_symbols, key=lambda s: s.name)
    for _ in range(samples):
        pt = _rational_point(syms, rng, ranges)
        val = sp.N(expr.subs(pt), 30)
        if val.is_number and val.is_real and abs(val) > 1e-20:
            val60 = sp.N(expr.subs(pt), 60)
            w = Witness({str(k): str(v) for k, v in pt.items()}, -abs(float(val)),
                        "residual at an exact rational point (30 digits)",
                        -abs(float(val60)) if val60.is_real else None,
                        "the same residual at 60 digits", seed)
            return Identity(simp, method, w)
    return Identity(simp, method)


def prove_identity(expr: sp.Expr, statement: str, **kw) -> Step:
    """A step asserting ``expr == 0`` identically (see ``identity_evidence``)."""
    return Step(statement, identity_evidence(expr, **kw), sp.Eq(expr, 0, evaluate=False))


def prove_nonneg(expr: sp.Expr, statement: str, *, strict: bool = False) -> Step:
    """A step asserting ``expr >= 0`` (> 0 if strict) under the symbols' assumptions, by
    SymPy's assumption system (True proves, None is unproven, False is not a witness by
    itself: it says the assumptions admit a negative value, so it stays unproven unless a
    point is supplied by a search)."""
    e = sp.simplify(expr)
    ans = e.is_positive if strict else e.is_nonnegative
    rel = _relation(expr, strict)
    return Step(statement, Inequality(e, "sympy", answer=ans, strict=strict), rel)


def _relation(expr: sp.Expr, strict: bool) -> sp.Basic:
    """``expr > 0`` or ``expr >= 0``, unevaluated (kept for rendering)."""
    return (sp.StrictGreaterThan if strict else sp.GreaterThan)(expr, 0, evaluate=False)


# --- exact points ------------------------------------------------------------------------

def _float_at(expr: sp.Expr, point: Mapping[sp.Symbol, Any]) -> float:
    """``expr`` at ``point`` by plain floating point (lambdify with numpy): the independent
    route against which an exact SymPy evaluation is re-checked."""
    syms = sorted(expr.free_symbols, key=lambda s: s.name)
    f = sp.lambdify(syms, expr, modules=LAMBDIFY_MODULES)
    with np.errstate(all="ignore"):
        return float(np.real_if_close(f(*(float(point[s]) for s in syms))))


def _exact_at(expr: sp.Expr, point: Mapping[sp.Symbol, Any], digits: int = 30) -> float:
    val = sp.N(sp.sympify(expr).subs({k: sp.nsimplify(v) for k, v in point.items()}), digits)
    if not (val.is_number and val.is_real):
        raise ValueError(f"{sp.sstr(expr)} is not a real number at {dict(point)}")
    return float(val)


def identity_at(expr: sp.Expr, point: Mapping[sp.Symbol, Any], statement: str, *,
                tolerance: float = 0.0, method: str = "sympy.simplify") -> Step:
    """A step asserting ``expr == 0`` identically, judged at a stated point as well: if the
    residual at ``point`` exceeds ``tolerance`` in size (SymPy at 30 digits from exact
    rationals), re-checked by floating point, the point is a witness and the identity is
    refuted.  ``tolerance`` covers rounding of printed numbers (0 for exact identities)."""
    simp = sp.simplify(expr)
    if simp == 0:
        return Step(statement, Identity(sp.Integer(0), method), sp.Eq(expr, 0, evaluate=False))
    m = tolerance - abs(_exact_at(expr, point))
    m2 = tolerance - abs(_float_at(expr, point)) if expr.free_symbols else m
    w = Witness({str(k): sp.sstr(sp.nsimplify(v)) for k, v in point.items()}, m,
                "residual at an exact point (SymPy, 30 digits)"
                + (f", less the rounding tolerance {tolerance:g}" if tolerance else ""),
                m2, "the same residual in floating point (numpy)" if expr.free_symbols
                else "exact rational arithmetic (no free symbols)")
    return Step(statement, Identity(simp, method, w), sp.Eq(expr, 0, evaluate=False))


def refute_nonneg_at(expr: sp.Expr, point: Mapping[sp.Symbol, Any], statement: str, *,
                     strict: bool = False) -> Step:
    """A step asserting ``expr >= 0`` (> 0 if strict) for all symbol values, judged by SymPy's
    assumptions and at the stated ``point``: a negative value there (exact, re-checked in
    floating point) is a witness; otherwise SymPy's answer stands (None is unproven)."""
    e = sp.simplify(expr)
    ans = e.is_positive if strict else e.is_nonnegative
    val = _exact_at(expr, point)
    val2 = _float_at(expr, point) if expr.free_symbols else val
    # margin: the value itself (a strict claim is also violated by 0: margin -0 is not < 0,
    # so a strict refutation needs a negative value too)
    w = Witness({str(k): sp.sstr(sp.nsimplify(v)) for k, v in point.items()}, val,
                "value at an exact point (SymPy, 30 digits)", val2,
                "the same expression in floating point (numpy)") if val < 0 else None
    rel = _relation(expr, strict)
    return Step(statement, Inequality(e, "sympy", answer=ans, strict=strict, counter=w), rel)


# --- z3 on polynomial forms ----------------------------------------------------------------

def z3_check(solver) -> str:
    """``solver.check()`` as "sat", "unsat" or "unknown".  z3 catches Ctrl-C during a check
    itself and answers "unknown" (reason "interrupted from keyboard"; a timeout's reason is
    "timeout" or "canceled" and stays "unknown"): that answer is raised as the
    KeyboardInterrupt it was, never taken for an unproven step of a run that goes on and
    exits 0."""
    ans = str(solver.check())
    if ans == "unknown" and "keyboard" in solver.reason_unknown():
        raise KeyboardInterrupt
    return ans


def _to_z3(e: sp.Basic, env: dict):
    import z3

    if isinstance(e, sp.Symbol):
        if e not in env:
            env[e] = z3.Real(e.name)
        return env[e]
    if e.is_Rational:
        return z3.RealVal(str(e.p)) / z3.RealVal(str(e.q)) if e.q != 1 else z3.RealVal(str(e.p))
    if isinstance(e, sp.Add):
        return z3.Sum([_to_z3(a, env) for a in e.args])
    if isinstance(e, sp.Mul):
        out = _to_z3(e.args[0], env)
        for a in e.args[1:]:
            out = out * _to_z3(a, env)
        return out
    if isinstance(e, sp.Pow) and e.exp.is_Integer and e.exp > 0:
        base = _to_z3(e.base, env)
        out = base
        for _ in range(int(e.exp) - 1):
            out = out * base
        return out
    if isinstance(e, sp.Abs):
        x = _to_z3(e.args[0], env)
        return z3.If(x >= 0, x, -x)
    rel = {sp.GreaterThan: lambda a, b: a >= b, sp.StrictGreaterThan: lambda a, b: a > b,
           sp.LessThan: lambda a, b: a <= b, sp.StrictLessThan: lambda a, b: a < b,
           sp.Equality: lambda a, b: a == b}
    for cls, op in rel.items():
        if isinstance(e, cls):
            return op(_to_z3(e.lhs, env), _to_z3(e.rhs, env))
    if isinstance(e, sp.And):
        return z3.And(*[_to_z3(a, env) for a in e.args])
    if isinstance(e, sp.Or):
        return z3.Or(*[_to_z3(a, env) for a in e.args])
    if isinstance(e, sp.Not):
        return z3.Not(_to_z3(e.args[0], env))
    if isinstance(e, sp.Implies):
        return z3.Implies(_to_z3(e.args[0], env), _to_z3(e.args[1], env))
    if isinstance(e, sp.Equivalent):
        return _to_z3(e.args[0], env) == _to_z3(e.args[1], env)
    raise TypeError(f"not a polynomial form z3 can take: {sp.sstr(e)}")


def prove_z3(goal: sp.Basic, hypotheses: Iterable[sp.Basic], statement: str, *,
             timeout_ms: int = 20_000) -> Step:
    """A step asserting ``hypotheses => goal`` over the reals, decided by z3 on the polynomial
    form (nonlinear real arithmetic; ``Abs`` becomes an if-then-else).  z3 is asked for a
    model of ``hypotheses and not goal``: "unsat" proves; "sat" gives a model, kept as a
    witness once SymPy re-checks it exactly; "unknown" is unproven.  The SMT-LIB query is the
    certificate kept with the step."""
    import z3

    hyps = list(hypotheses)
    env: dict = {}
    s = z3.Solver()
    s.set("timeout", timeout_ms)
    zh = [_to_z3(h, env) for h in hyps]
    zg = _to_z3(goal, env)
    s.add(*zh)
    s.add(z3.Not(zg))
    ans = z3_check(s)
    # the SMT-LIB query, written from the assertions (s.sexpr() also prints solver state
    # that depends on earlier z3 calls in the process, which would make reports unstable)
    query = "\n".join([f"(declare-fun {sym.name} () Real)"
                       for sym in sorted(env, key=lambda q: q.name)]
                      + [f"(assert {a.sexpr()})" for a in s.assertions()] + ["(check-sat)"])
    counter = None
    margin_expr = None  # the goal as "margin >= 0"
    if isinstance(goal, sp.GreaterThan | sp.StrictGreaterThan):
        margin_expr = goal.lhs - goal.rhs
    elif isinstance(goal, sp.LessThan | sp.StrictLessThan):
        margin_expr = goal.rhs - goal.lhs
    if ans == "sat" and margin_expr is not None:
        mdl = s.model()
        pt = {}
        for sym, zv in env.items():
            val = mdl.eval(zv, model_completion=True)
            pt[sym] = sp.Rational(val.as_fraction().numerator, val.as_fraction().denominator) \
                if z3.is_rational_value(val) else sp.nsimplify(float(val.as_decimal(20)
                                                                      .rstrip("?")))
        holds = [bool(sp.sympify(h).subs(pt)) for h in hyps]
        m = float(margin_expr.subs(pt))
        counter = Witness({str(k): sp.sstr(v) for k, v in pt.items()}, m, "z3 model",
                          m if all(holds) and not bool(goal.subs(pt)) else None,
                          "SymPy: hypotheses hold and the goal fails at the model, exactly")
    expr = margin_expr if margin_expr is not None else sp.Integer(0)
    rel = sp.Implies(sp.And(*hyps), goal) if hyps else goal
    strict = isinstance(goal, sp.StrictGreaterThan | sp.StrictLessThan)
    return Step(statement, Inequality(expr, "z3", answer=ans, certificate=query, strict=strict,
                                      counter=counter), rel)


# --- Arb interval enclosures ---------------------------------------------------------------

def _arb_eval(e: sp.Basic, env: Mapping[sp.Symbol, Any]):
    from flint import arb

    if isinstance(e, sp.Symbol):
        return env[e]
    if e.is_Integer:
        return arb(int(e))
    if e.is_Rational:
        return arb(int(e.p)) / int(e.q)
    if e.is_Float:
        return arb(float(e))
    if e is sp.pi:
        return arb.pi()
    if isinstance(e, sp.Add):
        out = arb(0)
        for a in e.args:
            out = out + _arb_eval(a, env)
        return out
    if isinstance(e, sp.Mul):
        out = arb(1)
        for a in e.args:
            out = out * _arb_eval(a, env)
        return out
    if isinstance(e, sp.Pow):
        b, x = _arb_eval(e.base, env), e.exp
        if x.is_Integer:
            return b ** int(x)
        return b ** _arb_eval(x, env)
    fns = {sp.exp: "exp", sp.log: "log", sp.gamma: "gamma", sp.sin: "sin", sp.cos: "cos",
           sp.Abs: "__abs__"}
    for cls, name in fns.items():
        if isinstance(e, cls):
            return getattr(_arb_eval(e.args[0], env), name)()
    if isinstance(e, sp.Min | sp.Max):
        vals = [_arb_eval(a, env) for a in e.args]
        out = vals[0]
        for v_ in vals[1:]:
            out = out.min(v_) if isinstance(e, sp.Min) else out.max(v_)
        return out
    raise TypeError(f"no Arb enclosure for {sp.sstr(e)}")


def arb_enclosure(expr: sp.Expr, box: Mapping[sp.Symbol, tuple[float, float]], *,
                  splits: int = 0) -> tuple[float, float]:
    """Rigorous enclosure [lo, hi] of ``expr`` over ``box`` by Arb interval arithmetic,
    bisecting every box ``splits`` times along its widest side (2**splits leaves).
    A degenerate side (lo == hi) is the exact binary value of that float."""
    from flint import arb

    boxes = [dict(box)]
    for _ in range(splits):
        nxt = []
        for b in boxes:
            s = max(b, key=lambda k: b[k][1] - b[k][0])
            lo, hi = b[s]
            mid = (lo + hi) / 2
            nxt += [{**b, s: (lo, mid)}, {**b, s: (mid, hi)}]
        boxes = nxt
    lo_all, hi_all = float("inf"), float("-inf")
    for b in boxes:
        env = {}
        for s, (lo, hi) in b.items():
            lo_, hi_ = arb(lo), arb(hi)
            env[s] = lo_.union(hi_) if lo != hi else lo_
        val = _arb_eval(expr, env)
        lo_all = min(lo_all, float(val.lower()))
        hi_all = max(hi_all, float(val.upper()))
    return lo_all, hi_all


def prove_arb(expr: sp.Expr, box: Mapping[sp.Symbol, tuple[float, float]], statement: str, *,
              strict: bool = False, splits: int = 0,
              recheck: Callable[[Mapping[str, float]], float] | None = None,
              recheck_method: str = "the numpy implementation of the same quantity") -> Step:
    """A step asserting ``expr >= 0`` (> 0 if strict) on ``box``, by an Arb enclosure (the
    box is kept).  If the enclosure lies wholly below 0 on a box that is a single point, the
    point is a witness; ``recheck`` (a different route, e.g. the numpy implementation the
    CLI uses) must confirm it."""
    lo, hi = arb_enclosure(expr, box, splits=splits)
    counter = None
    point = all(a == b for a, b in box.values())
    if hi < 0 and point:
        pt = {str(k): v[0] for k, v in box.items()}
        counter = Witness(pt, hi, "Arb enclosure at the point (upper end)",
                          recheck(pt) if recheck else None, recheck_method if recheck else "")
    rel = _relation(expr, strict)
    return Step(statement, Inequality(expr, "arb", box={str(k): v for k, v in box.items()},
                                      lower=lo, strict=strict, counter=counter,
                                      certificate={"enclosure": [lo, hi], "splits": splits}),
                rel)


# --- searches (today's slices; the full-domain engine swaps in here) ------------------------

@dataclass(frozen=True)
class SearchResult:
    """What a falsification run returns: the margins it saw and where the smallest was."""

    evaluations: int
    best_margin: float
    best_point: Mapping[str, Any]


def run_search(margin: Callable[[Mapping[str, Any]], float],
               points: Iterable[Mapping[str, Any]]) -> SearchResult:
    """Evaluate ``margin`` (bound minus observed; < 0 violates) at every point of a stated
    list.  This is the one place the lead swaps for ``lgw.theory.falsify`` (a global search
    over the whole domain with local refinement): callers pass the domain and the margin."""
    best, best_pt, n = math.inf, {}, 0
    for pt in points:
        m = float(margin(pt))
        n += 1
        if m < best:
            best, best_pt = m, dict(pt)
    return SearchResult(n, best, best_pt)


def search_step(statement: str, margin: Callable[[Mapping[str, Any]], float],
                points: Iterable[Mapping[str, Any]], *, domain: Mapping[str, Any],
                method: str, seed: int | None = None, relative: bool = False,
                recheck: Callable[[Mapping[str, Any]], float] | None = None,
                recheck_method: str = "", tolerance: float = 0.0, budget: str = "") -> Step:
    """A step that rests on a falsification search: ``checked`` with the best margin over the
    stated domain and budget (if it clears ``tolerance``), or ``refuted`` when the best point
    has a negative margin that ``recheck`` (an independent route) confirms."""
    res = run_search(margin, points)
    counter = None
    if res.best_margin < 0:
        rechecked, how = None, recheck_method
        if recheck is not None:
            try:
                rechecked = float(recheck(res.best_point))
            except (ArithmeticError, ValueError) as e:  # not evaluable in double precision
                how = f"{recheck_method} (could not be evaluated: {type(e).__name__}: {e})"
        counter = Witness(res.best_point, res.best_margin, method, rechecked, how, seed)
    return Step(statement, Search(dict(domain), method, res.evaluations, res.best_margin,
                                  res.best_point, seed, counter, relative, tolerance,
                                  budget or f"{res.evaluations} points, each evaluated once"))


def witness_step(statement: str, point: Mapping[str, Any], margin: float, method: str,
                 rechecked: float | None, recheck_method: str, *,
                 domain: Mapping[str, Any] | None = None) -> Step:
    """A counterexample located by construction (one evaluation at a stated point), as Search
    evidence: refuted iff both margins are negative."""
    w = Witness(dict(point), margin, method, rechecked, recheck_method)
    return Step(statement, Search(dict(domain or {k: "given" for k in point}), method, 1,
                                  margin, dict(point), None, w,
                                  budget="one evaluation at the stated point"))
