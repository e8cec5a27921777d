"""Symbolic building blocks shared by the laws: the signed power sig(x, q) = |x|^q sgn(x).

Writing |x|^q sgn(x) as one function keeps SymPy's derivatives free of DiracDelta terms:
d/dx sig(x, q) = q |x|^(q-1) for x != 0 (seed 000 uses this in (22)).  Proofs split the real
line into x > 0 and x < 0 (``on_branch``), where sig is an ordinary power and SymPy can
simplify; x = 0 is handled by the claims that need it.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy as sp


class sig(sp.Function):  # noqa: N801  (SymPy function names are lower case)
    """sig(x, q) = |x|^q sgn(x)."""

    nargs = 2

    def fdiff(self, argindex: int = 1) -> sp.Expr:
        x, q = self.args
        if argindex == 1:
            return q * sp.Abs(x) ** (q - 1)
        if argindex == 2:
            return self * sp.log(sp.Abs(x))
        raise sp.ArgumentIndexError(self, argindex)

    @classmethod
    def eval(cls, x: sp.Expr, q: sp.Expr) -> sp.Expr | None:
        if x.is_zero and q.is_positive:
            return sp.S.Zero
        if x.is_positive:
            return x**q
        if x.is_negative:
            return -((-x) ** q)
        return None


def np_sig(x: np.ndarray, q: np.ndarray | float) -> np.ndarray:
    """Numeric sig: |x|^q sgn(x), with sig(0, q) = 0 for q > 0 (the limit)."""
    return np.sign(x) * np.abs(x) ** q


LAMBDIFY_MODULES = [{"sig": np_sig}, "numpy"]


def positive_symbols(names: str) -> tuple[sp.Symbol, ...]:
    return sp.symbols(names, positive=True)


def on_branch(expr: sp.Expr, signs: Mapping[sp.Symbol, int]) -> tuple[sp.Expr, dict]:
    """Substitute each real symbol x by sign * x_pos with x_pos > 0.

    Returns the expression on that branch and the map from the original symbols to the positive
    ones, so that sig and Abs reduce to plain powers SymPy can simplify.
    """
    subs = {}
    for s, sgn in signs.items():
        xp = sp.Symbol(f"{s.name}_abs", positive=True)
        subs[s] = sgn * xp
    return sp.powsimp(sp.expand(expr.subs(subs)), force=False), subs


def clear_module_caches(modules: tuple[str, ...]) -> None:
    """Forget every memoised result (``functools.cache``) of the named modules that are loaded:
    a changed law, bound or constant is then derived afresh (the mutation harnesses use it)."""
    import sys

    for name in modules:
        mod = sys.modules.get(name)
        for obj in vars(mod).values() if mod else ():
            if callable(getattr(obj, "cache_clear", None)):
                obj.cache_clear()
