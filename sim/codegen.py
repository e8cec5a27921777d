"""SymPy -> numba code generation, as module source text (so it can be cached on disk).

Two generators, both giving the source of a plain Python function plus the import lines its
names need; ``lgw.sim.kernel_cache`` writes them into a real module and compiles them with
``numba.njit(cache=True)``:

* ``lambdified_source``: the source of a ``sympy.lambdify`` function (scalar laws; the Mars
  per-axis laws use it, with their own explog / share_powers rewriting in
  ``lgw.sim.mars.laws``), renamed, with its globals turned into imports.  The text is exactly
  what lambdify executes, so the compiled arithmetic is the same as lambdify + njit.
* ``vector_source``: laws whose expression couples components (quaternion kinematics,
  Coriolis terms): inputs are vectors / matrices of symbols, passed as 1-d / 2-d arrays and
  unpacked by index; outputs (a scalar, a vector or a matrix) are written into a preallocated
  ``out`` array (no allocation per call), with common subexpressions eliminated over all
  components together.

``compile_source`` compiles such a source in memory (tests, one-off use); the simulator uses
the cached module instead.
"""

from __future__ import annotations

import builtins
import inspect
import keyword
import math
import re
from collections.abc import Callable, Sequence
from typing import Any

import numba
import numpy as np
import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

# Builtins the generated code may name directly.
_BUILTINS = {"abs", "min", "max", "float", "int", "range", "pow"}


def import_line(alias: str, obj: Any) -> str:
    """An import (or assignment) that binds ``alias`` to ``obj`` in a generated module."""
    if isinstance(obj, int | float):
        return f"{alias} = {obj!r}"
    mod = getattr(obj, "__module__", None)
    name = getattr(obj, "__name__", None)
    if mod == "builtins" or (mod is None and name in _BUILTINS):
        return f"{alias} = {name}" if alias != name else ""
    if mod is None or name is None:
        raise ValueError(f"cannot import {alias} = {obj!r} in a generated module")
    return f"from {mod} import {name}" + (f" as {alias}" if alias != name else "")


def _code_names(code) -> set[str]:
    names = set(code.co_names)
    for c in code.co_consts:
        if inspect.iscode(c):
            names |= _code_names(c)
    return names


def lambdified_source(fn: Callable, name: str) -> tuple[str, list[str]]:
    """(source of the lambdify-generated ``fn`` as ``def name(...)``, import lines of the
    globals it uses)."""
    src = inspect.getsource(fn)
    src = re.sub(r"^def _lambdifygenerated\(", f"def {name}(", src, count=1)
    glb = fn.__globals__
    lines = []
    for n in sorted(_code_names(fn.__code__)):
        if n in glb:
            line = import_line(n, glb[n])
            if line:
                lines.append(line)
        elif n not in _BUILTINS and not hasattr(builtins, n):
            raise ValueError(f"generated code names {n!r}, which is not in its namespace")
    return src, lines


# --- vector / matrix laws -----------------------------------------------------------------

@numba.njit(cache=True, error_model="numpy")
def nb_sign(x: float) -> float:
    """sign(x) (0 at 0), as SymPy's sign."""
    return 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)


@numba.njit(cache=True, error_model="numpy")
def nb_sig(x: float, q: float) -> float:
    """sig(x, q) = |x|^q sgn(x) (``lgw.theory.symbolic.sig``; 0 at 0)."""
    s = 1.0 if x > 0 else (-1.0 if x < 0 else 0.0)
    return s * abs(x) ** q


class _Printer(PythonCodePrinter):
    """Python code for numba: math-module functions, sign and sig as compiled helpers."""

    def __init__(self) -> None:
        super().__init__({"fully_qualified_modules": False, "inline": True,
                          "allow_unknown_functions": False})

    def _print_sign(self, e):
        return f"nb_sign({self._print(e.args[0])})"

    def _print_Abs(self, e):
        return f"abs({self._print(e.args[0])})"

    def _print_Function(self, e):
        if type(e).__name__ == "sig":
            return f"nb_sig({self._print(e.args[0])}, {self._print(e.args[1])})"
        return super()._print_Function(e)


VECTOR_IMPORTS = ("import math", "from math import *  # noqa: F403",
                  "from lgw.sim.codegen import nb_sig, nb_sign")


def _arg_name(s: sp.Symbol, used: set[str]) -> str:
    base = re.sub(r"\W", "_", str(s)) or "x"
    if base[0].isdigit() or keyword.iskeyword(base):
        base = "s_" + base
    n = base
    k = 1
    while n in used:
        n = f"{base}_{k}"
        k += 1
    used.add(n)
    return n


Arg = sp.Symbol | sp.MatrixBase | Sequence[sp.Symbol]


def vector_source(name: str, args: Sequence[tuple[str, Arg]], expr: sp.Expr | sp.MatrixBase
                  | Sequence[sp.Expr]) -> str:
    """Source of ``def name(<args>, out)`` writing ``expr`` into ``out``.

    args: (argument name, a symbol (a float argument) or a vector / matrix of symbols (an
    array argument of that shape, read by index)); expr: a scalar (out has shape (1,)), a
    sequence or column / row vector (out (n,)) or a matrix (out (n, m)).  Common
    subexpressions are eliminated over all the components together.
    """
    used = {a for a, _ in args} | {"out"}
    lines = []
    subs: dict[sp.Symbol, sp.Symbol] = {}
    for aname, a in args:
        if isinstance(a, sp.Symbol):
            subs[a] = sp.Symbol(aname)
            continue
        m = sp.Matrix(a)
        vec = m.shape[1] == 1 or m.shape[0] == 1
        for idx in np.ndindex(*m.shape):
            s = m[idx]
            if not isinstance(s, sp.Symbol):
                raise ValueError(f"argument {aname}: entries must be symbols, got {s}")
            local = _arg_name(s, used)
            subs[s] = sp.Symbol(local)
            k = max(idx) if vec else None
            lines.append(f"    {local} = {aname}[{k if vec else ', '.join(map(str, idx))}]")
    if isinstance(expr, sp.MatrixBase):
        m = sp.Matrix(expr)
        vec = m.shape[1] == 1 or m.shape[0] == 1
        comps = [(f"{max(idx)}" if vec else ", ".join(map(str, idx)), m[idx])
                 for idx in np.ndindex(*m.shape)]
    elif isinstance(expr, sp.Expr):
        comps = [("0", expr)]
    else:
        comps = [(str(k), sp.sympify(e)) for k, e in enumerate(expr)]
    exprs = [sp.sympify(e).xreplace(subs) for _, e in comps]
    free = set().union(*(e.free_symbols for e in exprs)) - set(subs.values())
    if free:
        raise ValueError(f"{name}: symbols {sorted(map(str, free))} are not arguments")
    tmp = sp.numbered_symbols("_x")
    reps, reduced = sp.cse(exprs, symbols=tmp)
    pr = _Printer()
    for s, e in reps:
        lines.append(f"    {s} = {pr.doprint(e)}")
    for (k, _), e in zip(comps, reduced, strict=True):
        lines.append(f"    out[{k}] = {pr.doprint(e)}")
    lines.append("    return out")
    sig = ", ".join([a for a, _ in args] + ["out"])
    return f"def {name}({sig}):\n" + "\n".join(lines) + "\n"


def compile_source(source: str, name: str, imports: Sequence[str] = VECTOR_IMPORTS,
                   **njit_options: Any) -> Callable:
    """Compile a generated function in memory (no disk cache): for tests and one-off use."""
    ns: dict[str, Any] = {"math": math, "np": np, "numba": numba}
    exec("\n".join(imports), ns)  # noqa: S102  (our own import lines)
    exec(source, ns)  # noqa: S102  (source generated from SymPy expressions, no user text)
    return numba.njit(ns[name], error_model="numpy", **njit_options)


def module_source(functions: Sequence[tuple[str, str]], imports: Sequence[str] = VECTOR_IMPORTS,
                  fastmath: bool = False) -> str:
    """A module holding generated functions [(name, source)], each compiled with
    ``numba.njit(cache=True, error_model="numpy")``: write it with
    ``lgw.sim.kernel_cache.load_module`` to get machine code that persists between runs."""
    opts = 'cache=True, error_model="numpy"' + (", fastmath=True" if fastmath else "")
    body = []
    for name, src in functions:
        body += [src, f"{name} = numba.njit({name}, {opts})", ""]
    return "\n".join(["# generated by lgw.sim.codegen: do not edit (a cache entry)",
                      "import numba", *imports, "", *body])
