"""Seed 001's adaptive backstepping law as SymPy expressions: the one source of truth.

The general system (5) x1' = f1(x1) x2, x2' = f2 + d + B0 u, the command (7), the update law
(8), the transformation (9)-(10) and the virtual states (11), built for explicit dimensions
(n1, n2, m).  The same expressions give the Lyapunov derivative that ``claims`` checks against
(13) and, through ``lgw.sim.lunar.laws`` (lambdify), the code the simulator runs.

Reconstruction of the garbled (7) (seed 001, eq. (7)):

    u_c = -B0^+ ( F2 (x2 - p) + f1^T x1 + f2 - p' + d0e^2 z2 / (||z2|| d0e + f3 ||z2||^2) )

where p' is the true time derivative of p = -K1 f1^T x1 (10) along (5a) (it involves only x1's
derivative f1 x2, so it is computable without d).  The last term is written
``Phi = d0e^2 z2 / (||z2|| (d0e + f3 ||z2||))``; it is undefined at z2 = 0 (claim smooth-7).

``nz`` is a positive symbol standing for ||z2||: V2 (12) does not contain ||z2||, so it is never
differentiated; comparisons substitute nz = sqrt(z2^T z2) (``norm_subs``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import sympy as sp


def vec(name: str, n: int, **assumptions) -> sp.Matrix:
    return sp.Matrix(sp.symbols(f"{name}_1:{n + 1}", **assumptions)) if n > 1 else \
        sp.Matrix([sp.Symbol(f"{name}_1", **assumptions)])


def skew(a: sp.Matrix) -> sp.Matrix:
    """S(a): the cross-product matrix, S(a) b = a x b (seed 001 (27))."""
    return sp.Matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


@dataclass(frozen=True)
class GeneralSystem:
    """System (5) with the law (7)-(11) for explicit dimensions.

    f1 (n1 x n2) may depend on x1 and on auxiliary symbols listed in ``aux`` with their time
    derivatives (e.g. the scalar part eq0 of the attitude error, whose derivative follows from
    (27a)).  ``D`` is the bound on ||d|| that d0e estimates; it is treated as a state with
    derivative ``Ddot`` so that the derivation shows what a time-varying ||d|| adds (the
    paper's d^_0 = d0e - ||d|| in (12))."""

    x1: sp.Matrix
    x2: sp.Matrix
    f1: sp.Matrix
    f2: sp.Matrix
    B0: sp.Matrix
    K1: sp.Matrix
    F2: sp.Matrix
    aux: dict = field(default_factory=dict)
    name: str = "general"

    # --- symbols shared by every instance ---
    @cached_property
    def n1(self) -> int:
        return self.x1.shape[0]

    @cached_property
    def n2(self) -> int:
        return self.x2.shape[0]

    @cached_property
    def m(self) -> int:
        return self.B0.shape[1]

    @cached_property
    def lam1(self) -> sp.Matrix:
        return vec("lambda1", self.n1, real=True)

    @cached_property
    def lam2(self) -> sp.Matrix:
        return vec("lambda2", self.n2, real=True)

    @cached_property
    def d(self) -> sp.Matrix:
        return vec("d", self.n2, real=True)

    @cached_property
    def du(self) -> sp.Matrix:
        return vec("Du", self.m, real=True)

    d0e = sp.Symbol("d_0e", nonnegative=True)
    f3 = sp.Symbol("f3", positive=True)
    q = sp.Symbol("q", positive=True)
    D = sp.Symbol("D", nonnegative=True)
    Ddot = sp.Symbol("Ddot", real=True)
    nz = sp.Symbol("nz", positive=True)  # ||z2||

    # --- the law ---
    @cached_property
    def F1(self) -> sp.Matrix:
        """F1 := f1 K1 f1^T (seed 001 (10))."""
        return self.f1 * self.K1 * self.f1.T

    @cached_property
    def p(self) -> sp.Matrix:
        """Virtual control p = -K1 f1^T x1 (seed 001 (10))."""
        return -self.K1 * self.f1.T * self.x1

    def dt_kinematic(self, expr: sp.Matrix) -> sp.Matrix:
        """Time derivative of an expression of (x1, aux) along (5a): x1' = f1 x2."""
        rates = {s: r for s, r in zip(self.x1, self.f1 * self.x2, strict=True)}
        rates.update(self.aux)
        return sum((expr.diff(s) * r for s, r in rates.items()), sp.zeros(*expr.shape))

    @cached_property
    def pdot(self) -> sp.Matrix:
        return self.dt_kinematic(self.p)

    @cached_property
    def z1(self) -> sp.Matrix:
        return self.x1 - self.lam1  # (9a)

    @cached_property
    def z2(self) -> sp.Matrix:
        return self.x2 - self.lam2 - self.p  # (9b)

    @cached_property
    def Phi(self) -> sp.Matrix:
        """The adaptive term of (7): d0e^2 z2 / (||z2|| d0e + f3 ||z2||^2)."""
        return self.d0e ** 2 * self.z2 / (self.nz * self.d0e + self.f3 * self.nz ** 2)

    @cached_property
    def B0pinv(self) -> sp.Matrix:
        return sp.simplify(self.B0.pinv())

    @cached_property
    def uc(self) -> sp.Matrix:
        """Command (7)."""
        inner = (self.F2 * (self.x2 - self.p) + self.f1.T * self.x1 + self.f2 - self.pdot
                 + self.Phi)
        return -self.B0pinv * inner

    # --- closed loop ---
    @cached_property
    def rates(self) -> dict:
        """State -> time derivative along (5) with u = u_c + Du, (8), (11)."""
        x1dot = self.f1 * self.x2
        x2dot = self.f2 + self.d + self.B0 * (self.uc + self.du)
        l1dot = -self.F1 * self.lam1 + self.f1 * self.lam2  # (11a)
        l2dot = -self.F2 * self.lam2 - self.f1.T * self.lam1 + self.B0 * self.du  # (11b)
        r = {}
        for xs, dx in ((self.x1, x1dot), (self.x2, x2dot), (self.lam1, l1dot),
                       (self.lam2, l2dot)):
            r.update(zip(xs, dx, strict=True))
        r[self.d0e] = self.q * self.nz  # (8)
        r[self.D] = self.Ddot
        r.update(self.aux)
        return r

    @cached_property
    def V2(self) -> sp.Expr:
        """(12) with d^_0 = d0e - D."""
        return ((self.z1.T * self.z1)[0] + (self.z2.T * self.z2)[0]) / 2 \
            + (self.d0e - self.D) ** 2 / (2 * self.q)

    @cached_property
    def V2dot(self) -> sp.Expr:
        """dV2/dt along the closed loop, by the chain rule over every state."""
        return sum(sp.diff(self.V2, s) * r for s, r in self.rates.items())

    @cached_property
    def V2dot_z(self) -> sp.Expr:
        """V2' in (x1, z2, lambda, ...) coordinates (``in_z``), computed once per instance."""
        return self.in_z(self.V2dot)

    @cached_property
    def z2s(self) -> sp.Matrix:
        return vec("z2", self.n2, real=True)

    def in_z(self, expr: sp.Expr) -> sp.Expr:
        """Write an expression in (x1, z2, lambda, ...) coordinates: x2 = z2 + lambda2 + p."""
        return expr.subs(dict(zip(self.x2, self.z2s + self.lam2 + self.p, strict=True)),
                         simultaneous=True)

    def norm_subs(self, expr: sp.Expr) -> sp.Expr:
        return expr.subs(self.nz, sp.sqrt((self.z2s.T * self.z2s)[0]))

    def remainder_13(self) -> sp.Expr:
        """The exact remainder of (13) the derivation should produce, in z coordinates:
        V2' = -z1^T F1 z1 - z2^T F2 z2 + [z2^T d - D ||z2||] + f3 d0e ||z2||^2/(d0e + f3||z2||)
              - (d0e - D) D'/q."""
        z1, z2 = self.z1, self.z2s
        return (-(z1.T * self.F1 * z1)[0] - (z2.T * self.F2 * z2)[0]
                + (z2.T * self.d)[0] - self.D * self.nz
                + self.f3 * self.d0e * self.nz ** 2 / (self.d0e + self.f3 * self.nz)
                - (self.d0e - self.D) * self.Ddot / self.q)


# --- instances --------------------------------------------------------------------------

def scalar_system() -> GeneralSystem:
    """n1 = n2 = m = 1 with f1(x1), f2(x1, x2) unspecified smooth functions, B0 = b != 0."""
    x1, x2 = sp.Symbol("x1_1", real=True), sp.Symbol("x2_1", real=True)
    b, k1, F2 = sp.Symbol("b", nonzero=True, real=True), sp.Symbol("k1", positive=True), \
        sp.Symbol("F2", positive=True)
    f1 = sp.Function("f1")(x1)
    f2 = sp.Function("f2")(x1, x2)
    return GeneralSystem(sp.Matrix([x1]), sp.Matrix([x2]), sp.Matrix([[f1]]), sp.Matrix([f2]),
                         sp.Matrix([[b]]), sp.Matrix([[k1]]), sp.Matrix([[F2]]), name="scalar")


def diag_symbols(name: str, n: int = 3, **assumptions) -> sp.Matrix:
    return sp.diag(*sp.symbols(f"{name}_1:{n + 1}", **assumptions))


def orbit_system(full: bool = False) -> GeneralSystem:
    """Seed 001 (22): x1 = e_h, x2 = e_v, f1 = a_h = [0, 0, -1], f2 = 0, B0 = -I/m.

    K1, F2 diagonal (positive symbols) by default; ``full`` makes them general 3x3 symbol
    matrices (the form the simulator's generated code takes)."""
    eh = sp.Matrix([sp.Symbol("e_h", real=True)])
    ev = sp.Matrix(sp.symbols("e_v1:4", real=True))
    mass = sp.Symbol("m", positive=True)
    if full:
        K1 = sp.Matrix(3, 3, sp.symbols("K1_1:10", real=True))
        F2 = sp.Matrix(3, 3, sp.symbols("F2_1:10", real=True))
    else:
        K1, F2 = diag_symbols("k", positive=True), diag_symbols("F2d", positive=True)
    return GeneralSystem(eh, ev, sp.Matrix([[0, 0, -1]]), sp.zeros(3, 1), -sp.eye(3) / mass,
                         K1, F2, name="orbit")


def attitude_symbols():
    eq = sp.Matrix(sp.symbols("e_q1:4", real=True))
    ew = sp.Matrix(sp.symbols("e_w1:4", real=True))
    eq0 = sp.Symbol("e_q0", real=True)
    return eq0, eq, ew


def attitude_system(f2: sp.Matrix | None = None) -> GeneralSystem:
    """Seed 001 (27): x1 = e_q, x2 = e_omega, f1 = (eq0 I + S(eq))/2, B0 = J^-1, u = M.

    eq0 is an auxiliary state with eq0' = -eq^T e_omega / 2 (the scalar row of the error
    kinematics, seed 001 (27a) before its vector part).  f2 is the vector of symbols
    f2_1..3: the plant computes it (it is the known part of (27b)), the law cancels it."""
    eq0, eq, ew = attitude_symbols()
    f1 = (eq0 * sp.eye(3) + skew(eq)) / 2
    if f2 is None:
        f2 = sp.Matrix(sp.symbols("f2_1:4", real=True))
    J = diag_symbols("J", positive=True)
    return GeneralSystem(eq, ew, f1, f2, J.inv(), sp.Matrix(3, 3, sp.symbols("K1_1:10",
                         real=True)), sp.Matrix(3, 3, sp.symbols("F2_1:10", real=True)),
                         aux={eq0: -(eq.T * ew)[0] / 2}, name="attitude")


def underactuated_system() -> GeneralSystem:
    """n1 = 1, n2 = 2, m = 1: B0 has rank 1 < n2, so B0 B0^+ != I (a hypothesis of (13))."""
    x1 = sp.Matrix([sp.Symbol("x1_1", real=True)])
    x2 = sp.Matrix(sp.symbols("x2_1:3", real=True))
    b1, b2 = sp.symbols("b1 b2", positive=True)
    return GeneralSystem(x1, x2, sp.Matrix([[1, 1]]), sp.zeros(2, 1), sp.Matrix([[b1], [b2]]),
                         sp.eye(2), sp.diag(*sp.symbols("F2d_1:3", positive=True)),
                         name="underactuated")
