"""Provers that make evidence (``lgw.theory.evidence``): SymPy identities and inequalities.

Each returns a ``Step`` whose status is computed from the evidence it carries; nothing here
(or anywhere) writes a status by hand.  More provers (z3, Arb enclosures, SOS) and the
falsification engine sit beside this module.
"""

from __future__ import annotations

import random
from collections.abc import Iterable, Mapping

import sympy as sp
from lgw.theory.evidence import Identity, Inequality, Step, Witness


def _rational_point(symbols: Iterable[sp.Symbol], rng: random.Random,
                    ranges: Mapping[sp.Symbol, tuple[float, float]]) -> dict:
    pt = {}
    for s in symbols:
        lo, hi = ranges.get(s, (0.1, 3.0) if s.is_positive else (-3.0, 3.0))
        pt[s] = sp.Rational(round(rng.uniform(lo, hi), 3)).limit_denominator(1000)
        if pt[s] == 0:
            pt[s] = sp.Rational(1, 7)
    return pt


def identity_evidence(expr: sp.Expr, *, method: str = "sympy.simplify", samples: int = 8,
                      seed: int = 0, ranges: Mapping[sp.Symbol, tuple[float, float]] | None = None,
                      simplified: sp.Expr | None = None) -> Identity:
    """Evidence for ``expr == 0`` identically: the residual after ``sp.simplify`` (or the
    given ``simplified`` form); if it is not 0, a search for an exact rational point where it
    is nonzero (evaluated at 30 digits and re-checked at 60): a refutation needs both."""
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
    rel = sp.StrictGreaterThan(expr, 0) if strict else sp.GreaterThan(expr, 0)
    return Step(statement, Inequality(e, "sympy", answer=ans, strict=strict), rel)
