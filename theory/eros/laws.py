"""Seed 002's surfaces and control laws as SymPy expressions: the one source of truth.

Per axis (seed 002 does x and says y, z "are calculated in the same way"): the tracking error
e = x_1 - x_d, its rate ed = x_2 - x_2d, and the closed loop (4) written in the error:

    e'' = f + u + D - xdd_ref,         f = 2 w x_4 + w^2 x_1 + g_x   (x axis of (4))

with f the known drift (Coriolis, centrifugal, model gravity), D the disturbance of (1) and
xdd_ref the reference acceleration (the paper's \\dot x_{2d}).  The simulator lambdifies the
expressions below (lgw.sim.eros.laws); tests check generated against symbolic.

Departures from the printed text, each named:
  * (e)^{p/q} is read as sig(e)^{p/q} = |e|^{p/q} sgn(e) (real for e < 0 whatever the parity
    of p, q; equal to the printed power for odd p, q);
  * the exponent of (16) and (19) as extracted, (p-1)/q, is read as p/q - 1, the exponent of
    (11) and (14) (claim printed-exponent-19 shows the extracted one breaks (17));
  * |e|^{p/q-1} is evaluated at max(|e|, e_floor) (it is unbounded at e = 0; claim
    singular-term);
  * the fuzzy distance (21) is defined for a linear surface c^T x; for the FTSM surface the
    workbench uses D_i = s_i / sqrt(1 + alpha^2), the distance of (e, ed) to the tangent line
    e' + alpha e = 0 (the surface far from e = 0), and D = sqrt(sum D_i^2) as in (22).
"""

from __future__ import annotations

import sympy as sp

# --- symbols ------------------------------------------------------------------------------
e, ed = sp.symbols("e e_d", real=True)  # tracking error (m) and its rate (m/s)
f = sp.Symbol("f", real=True)  # known drift of (4) on this axis (m/s^2)
Dist = sp.Symbol("D", real=True)  # the disturbance D of (1) (m/s^2)
Dk = sp.Symbol("D_k", real=True)  # the disturbance the equivalent control uses (D or 0)
xdd = sp.Symbol("xdd_ref", real=True)  # reference acceleration (m/s^2)
u = sp.Symbol("u", real=True)
s = sp.Symbol("s", real=True)  # a surface value as a coordinate
dist = sp.Symbol("d", nonnegative=True)  # the fuzzy distance D of (21)-(22)
alpha, beta, k, lam, phi, N, M = sp.symbols("alpha beta k lambda phi N M", positive=True)
r = sp.Symbol("r", positive=True)  # p/q in (0, 1)
p, q = sp.symbols("p q", positive=True, integer=True)
eps = sp.Symbol("e_floor", positive=True)  # m, floor of |e| in |e|^(r-1)

SWITCHES = ("sign", "tanh")
LAWS = ("pdsmc", "ftsmc", "fuzzy")


def sig(x: sp.Expr, a: sp.Expr) -> sp.Expr:
    """sig(x)^a = |x|^a sgn(x) (the real reading of the printed x^{p/q})."""
    return sp.Abs(x) ** a * sp.sign(x)


def surface_tsm() -> sp.Expr:
    """Terminal surface, seed 002 eq. (5): s = e' + beta e^{p/q}."""
    return ed + beta * sig(e, r)


def surface_ftsm() -> sp.Expr:
    """Fast terminal surface, seed 002 eq. (6): s = e' + alpha e + beta e^{p/q}."""
    return ed + alpha * e + beta * sig(e, r)


def surface_pd() -> sp.Expr:
    """The 'classic PD sliding mode' surface the paper compares with (not printed; the
    linear surface its name implies): s = e' + lambda e."""
    return ed + lam * e


def surface(law: str) -> sp.Expr:
    return surface_pd() if law == "pdsmc" else surface_ftsm()


def ds_de(law: str, floor: bool = False) -> sp.Expr:
    """ds/de for e != 0, differentiated from ``surface(law)``: (11)'s alpha + beta (p/q)
    |e|^{p/q - 1} for (6) (lambda for PD).  The surfaces are odd in e, so ds/de is even: it is
    the derivative on the branch e = E > 0, written in |e|.

    ``floor``: the implemented form, |e| replaced by max(|e|, e_floor)."""
    E = sp.Symbol("E", positive=True)
    d = sp.powsimp(sp.expand(sp.diff(surface(law).subs(e, E), E)), force=True)
    a = sp.Max(sp.Abs(e), eps) if floor else sp.Abs(e)
    return d.subs(E, a)


def sdot(law: str, control: sp.Expr) -> sp.Expr:
    """s' along the closed loop (4) for e != 0: ds/de e' + e'' with e'' = f + u + D - xdd.
    seed 002 eq. (11) (and (16) with u substituted)."""
    return ds_de(law) * ed + (f + control + Dist - xdd)


def u_eq(law: str, floor: bool = True) -> sp.Expr:
    """Equivalent control, seed 002 eq. (14): s' = 0 solved for u, with D replaced by D_k
    (D_k = D: the paper's known-D assumption; D_k = 0: D unknown and bounded)."""
    return -(f + Dk - xdd) - ed * ds_de(law, floor)


def u_switch(switch: str, sv: sp.Expr | None = None) -> sp.Expr:
    """Switching control, seed 002 eq. (18): -k sgn(s); or -k tanh(s / phi), the 'saturation
    function' of the paper's second set of runs, boundary-layer width phi (m/s)."""
    sv = s if sv is None else sv
    if switch == "sign":
        return -k * sp.sign(sv)
    if switch == "tanh":
        return -k * sp.tanh(sv / phi)
    raise ValueError(f"switch must be one of {SWITCHES}")


def fuzzy_weights(d: sp.Expr = dist) -> tuple[sp.Expr, sp.Expr]:
    """seed 002 eq. (22) (second of that number): a(D) = exp(-N D), b(D) = 1 - exp(-M D)."""
    return sp.exp(-N * d), 1 - sp.exp(-M * d)


def control(law: str, switch: str, floor: bool = True) -> sp.Expr:
    """The full control of one axis as a function of (e, ed, f, D_k, xdd_ref, d) and the gains:
    (13) u = u_eq + u_s for PD-SMC and FTSMC (= (19)); (20) u = a u_eq + b u_s for the fuzzy
    FTSMC.  The surface value enters through s = surface(law)."""
    us = u_switch(switch, surface(law))
    ue = u_eq(law, floor)
    if law == "fuzzy":
        a, b = fuzzy_weights()
        return a * ue + b * us
    return ue + us


def fuzzy_distance(s_axes: tuple[sp.Expr, sp.Expr, sp.Expr]) -> sp.Expr:
    """seed 002 eqs. (21)-(22): D = sqrt(sum D_i^2), D_i = s_i / sqrt(1 + alpha^2) (see the
    module note for the FTSM reading of (21))."""
    return sp.sqrt(sum(si**2 for si in s_axes)) / sp.sqrt(1 + alpha**2)


def rotating_frame_accel() -> tuple[tuple[sp.Expr, ...], tuple[sp.Expr, ...]]:
    """(printed (4), derived -2 W x v - W x (W x r)) with W = (0, 0, w): the rotating-frame
    terms of seed 002 eq. (1)/(4)."""
    w = sp.Symbol("omega", positive=True)
    x1, x2, x3, x4, x5, x6 = sp.symbols("x1:7", real=True)
    W = sp.Matrix([0, 0, w])
    rv, vv = sp.Matrix([x1, x3, x5]), sp.Matrix([x2, x4, x6])
    derived = -2 * W.cross(vv) - W.cross(W.cross(rv))
    printed = (2 * w * x4 + w**2 * x1, -2 * w * x2 + w**2 * x3, sp.Integer(0))
    return printed, tuple(derived)
