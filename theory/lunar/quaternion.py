"""Scalar-first unit quaternions as SymPy expressions (seed 001 Section 4, attitude).

Convention (seed 001, after [9], [10]): Q = [q0, q^T]^T from F_H to F_B, Hamilton product,
kinematics Q' = Q (x) [0, omega] / 2 with omega in F_B.  ``dcm(Q)`` is the matrix L that maps
coordinates in the "from" frame to the "to" frame (v_B = L v_H), the paper's L_BH and L(e_Q).
"""

from __future__ import annotations

import sympy as sp
from lgw.theory.lunar.law import skew


def qmul(a: sp.Matrix, b: sp.Matrix) -> sp.Matrix:
    """Hamilton product a (x) b of scalar-first quaternions."""
    a0, av = a[0], sp.Matrix(a[1:])
    b0, bv = b[0], sp.Matrix(b[1:])
    return sp.Matrix([a0 * b0 - (av.T * bv)[0], *(a0 * bv + b0 * av + av.cross(bv))])


def conj(a: sp.Matrix) -> sp.Matrix:
    return sp.Matrix([a[0], -a[1], -a[2], -a[3]])


def dcm(q: sp.Matrix) -> sp.Matrix:
    """L(q) = (q0^2 - q^T q) I + 2 q q^T - 2 q0 S(q): coordinates in the from-frame to the
    to-frame for a unit q (the transpose of the active rotation matrix)."""
    q0, qv = q[0], sp.Matrix(q[1:])
    return (q0 ** 2 - (qv.T * qv)[0]) * sp.eye(3) + 2 * qv * qv.T - 2 * q0 * skew(qv)


def unit_constraint(q: sp.Matrix) -> sp.Expr:
    return sum(x ** 2 for x in q) - 1


def reduce_unit(expr: sp.Expr, q: sp.Matrix) -> sp.Expr:
    """The remainder of a polynomial modulo |q|^2 - 1 (Groebner reduction): zero means the
    identity holds on unit quaternions."""
    return sp.reduced(sp.expand(expr), [unit_constraint(q)], *q)[1]
