"""Integrating a Lyapunov comparison inequality, by SymPy, into L2 bounds (seed 001 (17)-(19)).

A comparison inequality V' <= -sum_k a_k X_k + sum_j b_j W_j (X_k = |x_k|^2, W_j = |w_j|^2, the
gains' coefficients a_k) is written as the equation V' = -sum a_k X_k + sum b_j W_j - sigma with
a slack sigma(t) >= 0 and integrated from 0 to t by ``sympy.integrate`` (the fundamental theorem
for the derivative, linearity for the rest).  The integrated equation is re-checked by
differentiating it back.  Solving it for the integral of X_k (``sympy.solve``) and dropping the
terms that are nonnegative (V(t) >= 0, the other integrals, the slack) gives the derived upper
bound; that step, "hypotheses => a_k int X_k <= a_k (bound)", is decided by z3 with the
hypotheses a_i > 0 written out (they are gain properties, checked on the gains in use by
``lgw.theory.lunar.hypotheses``, never assumed by declaring a symbol positive).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import sympy as sp
from lgw.theory.evidence import Step
from lgw.theory.provers import identity_evidence, prove_z3

s_, t_ = sp.symbols("s t", nonnegative=True)
V = sp.Function("V")
SIGMA = sp.Function("sigma")


@dataclass(frozen=True)
class Integrated:
    """The integrated comparison inequality and the bound derived for each decaying term."""

    equation: sp.Eq  # V(t) - V(0) = int_0^t (rate) ds, with V(0) = v0
    bounds: Mapping[str, sp.Expr]  # name -> the derived upper bound of int_0^t X_name
    integrals: Mapping[str, sp.Expr]  # name -> the symbol standing for int_0^t X_name
    check: Step  # the integrated equation differentiated back
    proofs: Mapping[str, Step]  # name -> z3: hypotheses => a_k int X_k <= a_k bound


def integrate_comparison(decay: Mapping[str, sp.Expr], forcing: Mapping[str, sp.Expr],
                         v0: sp.Expr, label: str) -> Integrated:
    """Integrate V' = -sum_k decay[k] X_k + sum_j forcing[j] W_j - sigma from 0 to t.

    ``decay``, ``forcing``: coefficient expressions in gain symbols (polynomial: z3 takes
    them); ``v0``: V(0) (an expression or 0).  Returns the equation, each derived bound and
    the steps that check them (see the module docstring)."""
    X = {k: sp.Function(f"X_{k}") for k in decay}
    W = {j: sp.Function(f"W_{j}") for j in forcing}
    rate = (-sum(a * X[k](s_) for k, a in decay.items())
            + sum(b * W[j](s_) for j, b in forcing.items()) - SIGMA(s_))
    lhs = sp.integrate(sp.Derivative(V(s_), s_), (s_, 0, t_))
    rhs = sp.simplify(sp.expand(sp.Integral(rate, (s_, 0, t_))))
    eq = sp.Eq(lhs.subs(V(0), v0), rhs)
    # re-check: d/dt (lhs - rhs) is V'(t) - rate(t), so the integrated equation is the
    # integral of the comparison equation (and both vanish at t = 0)
    back = sp.diff(lhs - rhs, t_) - (sp.Derivative(V(t_), t_) - rate.subs(s_, t_))
    check = Step(f"{label}: the integrated equation differentiated back is the comparison "
                 "equation (and both sides vanish at t = 0)",
                 identity_evidence(sp.simplify(back.doit()) + (lhs - rhs).subs(t_, 0).doit()))
    # plain symbols for the integrals and V(t) (z3 takes polynomials in symbols)
    ints = {k: sp.Symbol(f"I_{k}", real=True) for k in decay}
    jnts = {j: sp.Symbol(f"J_{j}", real=True) for j in forcing}
    Vt, Is = sp.Symbol("V_t", real=True), sp.Symbol("I_sigma", real=True)
    ren = {sp.Integral(X[k](s_), (s_, 0, t_)): ints[k] for k in decay}
    ren.update({sp.Integral(W[j](s_), (s_, 0, t_)): jnts[j] for j in forcing})
    ren.update({sp.Integral(SIGMA(s_), (s_, 0, t_)): Is, V(t_): Vt})
    eq_plain = sp.Eq(eq.lhs.xreplace(ren), eq.rhs.xreplace(ren))
    bounds, proofs = {}, {}
    for k, a in decay.items():
        sol = sp.solve(eq_plain, ints[k])
        if len(sol) != 1:
            raise ValueError(f"{label}: cannot solve the integrated equation for int X_{k}")
        dropped = {Vt: 0, Is: 0, **{ints[i]: 0 for i in decay if i != k}}
        bound = sp.simplify(sol[0].subs(dropped))
        bounds[k] = bound
        hyps = [sp.Gt(ai, 0) for ai in decay.values()] + [sp.Ge(Vt, 0), sp.Ge(Is, 0)]
        hyps += [sp.Ge(ints[i], 0) for i in decay] + [sp.Ge(jnts[j], 0) for j in forcing]
        hyps += [sp.Ge(sp.sympify(b), 0) for b in forcing.values()
                 if sp.sympify(b).free_symbols]
        hyps.append(sp.Eq(sp.expand(eq_plain.lhs - eq_plain.rhs), 0))
        if any(h in (sp.true, sp.false) for h in hyps):
            raise ValueError(f"{label}: a hypothesis reduced to a constant: the coefficients "
                             "must be real symbols whose signs are stated, not assumed")
        goal = sp.Le(sp.expand(a * ints[k]), sp.expand(sp.cancel(a * bound)))
        proofs[k] = prove_z3(goal, hyps, f"{label}: ({sp.sstr(a)}) int_0^t |{k}|^2 <= "
                             f"{sp.sstr(sp.expand(sp.cancel(a * bound)))}, given "
                             + ", ".join(f"{sp.sstr(ai)} > 0" for ai in decay.values())
                             + " (gain hypotheses), V(t) >= 0, sigma >= 0 and the integrated "
                             "equation; divided by " + sp.sstr(a) + " > 0: int_0^t |" + k
                             + "|^2 <= " + sp.sstr(bound))
    return Integrated(eq, bounds, ints, check, proofs)
