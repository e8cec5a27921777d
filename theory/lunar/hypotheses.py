"""Seed 001's gain hypotheses, checked on the gain set in use, exactly.

The derivations of (13), (17)-(21) divide by, or need the sign of, f2bar - f3bar, f2bar - 1/2
and f1bar (seed 001, below (7), (13) and (17b)).  These are properties of a gain set, so they
are checked on the gains the report is made for, never proved by declaring a symbol positive:
each gain (a TOML number) is read as the exact rational of its decimal text, lambda_min of a
symmetric gain matrix is the smallest real root of its characteristic polynomial (an exact
algebraic number, SymPy ``real_roots``), and the sign of the difference is SymPy's exact
decision on that number (``prove_nonneg``: True proves, anything else is unproven).  A failed
hypothesis leaves the derivation that needs it unproven for these gains (it does not refute
the bound: the derivation just does not apply), so no witness is attached.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp
from lgw.theory.evidence import Step
from lgw.theory.lunar.gains import A_H, LoopGains
from lgw.theory.provers import prove_nonneg


def exact(x: float) -> sp.Rational:
    """The exact rational of a gain's decimal text (0.25 -> 1/4, 0.1 -> 1/10)."""
    return sp.Rational(repr(float(x)))


def exact_matrix(M: np.ndarray) -> sp.Matrix:
    return sp.Matrix(M.shape[0], M.shape[1], [exact(v) for v in np.asarray(M).ravel()])


def lambda_min_exact(M: np.ndarray) -> sp.Expr:
    """lambda_min of the symmetric part of ``M``, exactly: the smallest real root of the
    characteristic polynomial of the rational matrix (seed 001: f2bar, below (7))."""
    A = exact_matrix(M)
    S = (A + A.T) / 2
    lam = sp.Symbol("lambda")
    roots = sp.Poly(S.charpoly(lam).as_expr(), lam).real_roots()
    return min(roots, key=lambda r: sp.N(r, 30))


@dataclass(frozen=True)
class LoopQuantities:
    """The exact gain quantities of one loop that the derivations use."""

    loop: str
    f1bar: sp.Expr  # orbit: a_h K1 a_h^T = K1_zz; attitude: lambda_min(sym K1) (times eq0^2/4)
    f2bar: sp.Expr
    f3: sp.Expr
    q: sp.Expr
    d0e0: sp.Expr

    def numbers(self) -> dict[str, float]:
        return {f"{self.loop}.f1bar": float(self.f1bar), f"{self.loop}.f2bar": float(self.f2bar),
                f"{self.loop}.f2bar-f3": float(self.f2bar - self.f3),
                f"{self.loop}.f2bar-1/2": float(self.f2bar - sp.Rational(1, 2))}


def quantities(loop: str, g: LoopGains) -> LoopQuantities:
    """Exact f1bar, f2bar, f3, q, d0e(0) of ``g`` (``loop``: "orbit" or "attitude").  For the
    attitude loop f1bar here is lambda_min(sym K1): F1's minimum eigenvalue is that times
    eq0^2/4 (claim attitude-F1-bound)."""
    if loop == "orbit":
        f1 = (exact_matrix(A_H) * exact_matrix(g.K1) * exact_matrix(A_H).T)[0, 0]
    else:
        f1 = lambda_min_exact(g.K1)
    return LoopQuantities(loop, f1, lambda_min_exact(g.F2), exact(g.f3), exact(g.q),
                          exact(g.d0e0))


def _positive(expr: sp.Expr, statement: str) -> Step:
    """``expr > 0`` for an exact number: SymPy's exact sign (False or None: unproven)."""
    return prove_nonneg(expr, statement, strict=True)


def f2bar_minus_f3(Q: LoopQuantities) -> Step:
    """Hypothesis of (13) (seed 001, below (13)): f2bar > f3bar > 0."""
    return _positive(Q.f2bar - Q.f3, f"{Q.loop}: f2bar - f3bar = {float(Q.f2bar):.6g} - "
                     f"{float(Q.f3):.6g} > 0 (hypothesis of (13); exact on the gains in use)")


def f2bar_minus_half(Q: LoopQuantities) -> Step:
    """Hypothesis of (17b)-(18b) (seed 001, below (17b)): f2bar > 1/2."""
    return _positive(Q.f2bar - sp.Rational(1, 2), f"{Q.loop}: f2bar - 1/2 = "
                     f"{float(Q.f2bar):.6g} - 1/2 > 0 (hypothesis of (17b), (18b); exact on "
                     "the gains in use)")


def f1bar_positive(Q: LoopQuantities) -> Step:
    """F1 positive definite (seed 001 (10)): orbit K1_zz > 0; attitude lambda_min(sym K1) > 0
    (then F1 is positive definite wherever eq0 != 0, claim attitude-F1-bound)."""
    what = ("f1bar = a_h K1 a_h^T = K1_zz" if Q.loop == "orbit" else
            "lambda_min(sym K1) (F1 >= lambda_min(sym K1) eq0^2/4)")
    return _positive(Q.f1bar, f"{Q.loop}: {what} = {float(Q.f1bar):.6g} > 0 (hypothesis of "
                     "(10); exact on the gains in use)")
