"""Symbolic building blocks shared by the laws: the signed power sig(x, q) = |x|^q sgn(x).

Writing |x|^q sgn(x) as one function keeps SymPy's derivatives free of DiracDelta terms:
d/dx sig(x, q) = q |x|^(q-1) for x != 0 (seed 000 uses this in (22)).  Proofs split the real
line into x > 0 and x < 0 (``on_branch``), where sig is an ordinary power and SymPy can
simplify; x = 0 is handled by the claims that need it.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable, Hashable, Iterator, Mapping
from typing import Any

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


def memo(fn: Callable[..., Any] | None = None, *,
         key: Callable[..., Hashable] | None = None) -> Any:
    """``functools.cache`` whose store can be kept: ``cache_clear()`` as functools', and
    ``cache_store``, the dict of results, which ``kept_module_caches`` saves and puts back
    (a mutation check derives afresh without throwing away the unmutated derivation).
    ``@memo(key=f)`` stores under ``f(*args, **kwargs)`` instead of the arguments: for
    arguments that are not hashable but have a canonical form (a gain set's exact values)."""
    if fn is None:
        return lambda f: memo(f, key=key)
    store: dict[Any, Any] = {}
    kw_mark = object()

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        k = (key(*args, **kwargs) if key is not None else
             args if not kwargs else (*args, kw_mark, *kwargs.items()))
        try:
            return store[k]
        except KeyError:
            pass
        value = fn(*args, **kwargs)
        store[k] = value
        return value

    wrapper.cache_clear = store.clear  # type: ignore[attr-defined]
    wrapper.cache_store = store  # type: ignore[attr-defined]
    return wrapper


@contextlib.contextmanager
def kept_module_caches(modules: tuple[str, ...]) -> Iterator[None]:
    """Within: the named modules' memoised results may be cleared and re-derived at will
    (under a mutated law, say); after: every ``memo`` store holds exactly what it held before,
    and every other cache of those modules is cleared (nothing derived within survives)."""
    import sys

    saved = [(obj, dict(obj.cache_store)) for name in modules
             for obj in (vars(sys.modules[name]).values() if name in sys.modules else ())
             if isinstance(getattr(obj, "cache_store", None), dict)]
    try:
        yield
    finally:
        clear_module_caches(modules)
        for obj, store in saved:
            obj.cache_store.update(store)


def clear_module_caches(modules: tuple[str, ...]) -> None:
    """Forget every memoised result (``functools.cache``) of the named modules that are loaded:
    a changed law, bound or constant is then derived afresh (the mutation harnesses use it)."""
    import sys

    for name in modules:
        mod = sys.modules.get(name)
        for obj in vars(mod).values() if mod else ():
            if callable(getattr(obj, "cache_clear", None)):
                obj.cache_clear()
