"""A third guidance law for seed 000's plant: bounded on bounded sets, with explicit time bounds.

Why: the printed law (25) has a bounded command but no valid proof; the corrected law
has a proof but its command -(b1 q1 |s1|^(q1-1) + b2 q2 |s1|^(q2-1)) v is unbounded wherever s1
crosses 0 with v != 0.  This law keeps a fixed-time sliding loop and removes the singularity by
putting it in a cascade (per axis i, plant r'' = a + g + a_m + a_p of seed 000 (10), (11), (30)):

  velocity reference   v_ref(r) = -psi(r),
      psi(r) = c1 r / sqrt(delta + |r|) + c2 sig(r, p2),      c1, delta, c2 > 0, p2 > 1;
  sliding variable     s = v + psi(r);
  command              a = -g - a_m - psi'(r) v - k1 sig(s, e1) - k2 sig(s, e2),
                       k1, k2 > 0, 0 < e1 < 1 < e2,
      psi'(r) = c1 (delta + |r|/2) (delta + |r|)^(-3/2) + c2 p2 |r|^(p2-1).

Closed loop: s' = -k1 sig(s, e1) - k2 sig(s, e2) + a_p exactly (``closed_loop_sdot``), so s
reaches 0 in the fixed time of ``lgw.theory.settling`` (exact, Aldana-Lopez et al. 2019); on
s = 0, r' = -psi(r).  psi is C^1 with 0 < psi' <= c1/sqrt(delta) + c2 p2 |r|^(p2-1): no negative
power of |r| or |s| multiplies anything, so the command is finite and continuous on R^2.

Where it comes from.  The reference is a smoothed braking curve: for |r| >> delta,
psi ~ c1 sqrt|r| (v = sqrt(2 a r), constant deceleration c1^2/2 on s = 0), and near r = 0 it is
linear with slope c1/sqrt(delta), as in the proximate time-optimal servo (PTOS: Workman 1987;
Franklin, Powell & Workman, Digital Control of Dynamic Systems, 3rd ed., 1998, sec. 14.3).  The
c2 sig(r, p2) term makes the sliding phase fixed-time (Polyakov, IEEE TAC 57(8), 2012): the time
from any r is bounded by ``slide_time_global``.  The velocity loop is the fixed-time reaching law
of seed 000 (16) applied to s (backstepping with exact cancellation of d v_ref/dt = -psi'(r) v,
which is bounded because psi' is).  The r-loop converges exponentially near 0 (rate
c1/sqrt(delta)) rather than in finite time, so the landing guarantee is *practical*: the time
bound is to the landing set |r| <= rho, |v| <= psi(rho) with rho <= 0.1 m (``landing_radius``),
which is what the landing criterion asks; the exact arrival at r = 0 is not claimed.

The gains live in their own frozen ``BoundedGains`` (TOML table ``[bounded]``), since seed 000's
``[gains]`` table has no place for them; ``DEFAULT_BOUNDED`` is the documented default.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
import sympy as sp
from lgw.theory.errors import ParameterError
from lgw.theory.mars.mss import am, ap, grav, r, v
from lgw.theory.settling import exact_bound, settling_time
from lgw.theory.symbolic import sig

NAME = "bounded"

# Gains (per axis; exponents shared).  Units: c1 m^(1/2)/s, delta m, c2 m^(1-p2)/s, k1 m^(1-e1)
# s^(e1-2), k2 m^(1-e2) s^(e2-2).
c1, delta, c2, k1, k2 = sp.symbols("c_1 delta c_2 k_1 k_2", positive=True)
p2, e1, e2 = sp.symbols("p_2 e_1 e_2", positive=True)
PARAMS = (c1, delta, c2, p2, k1, k2, e1, e2)
AXIS_KEYS = ("c1", "delta", "c2", "k1", "k2")
EXP_KEYS = ("p2", "e1", "e2")
S = sp.Symbol("s", real=True)  # the sliding variable as a coordinate


def psi() -> sp.Expr:
    """The reference speed toward the target, psi(r) = c1 r (delta+|r|)^(-1/2) + c2 sig(r, p2)."""
    return c1 * r / sp.sqrt(delta + sp.Abs(r)) + c2 * sig(r, p2)


def dpsi() -> sp.Expr:
    """psi'(r) written without sgn(r) r products (claim ``bounded-dpsi`` checks it is d psi/dr)."""
    return (c1 * (delta + sp.Abs(r) / 2) * (delta + sp.Abs(r)) ** sp.Rational(-3, 2)
            + c2 * p2 * sp.Abs(r) ** (p2 - 1))


def surface() -> sp.Expr:
    """s = v - v_ref(r) = v + psi(r)."""
    return v + psi()


def reaching(s: sp.Expr) -> sp.Expr:
    """The fixed-time reaching term of seed 000 (16), applied to s: -k1 sig(s,e1) - k2 sig(s,e2)."""
    return -k1 * sig(s, e1) - k2 * sig(s, e2)


def law_bounded() -> sp.Expr:
    """The commanded acceleration a_i: -g - a_m - psi'(r) v - k1 sig(s,e1) - k2 sig(s,e2)."""
    return -grav - am - dpsi() * v + reaching(surface())


def closed_loop_sdot(accel: sp.Expr | None = None) -> sp.Expr:
    """s' along seed 000 (10), (30), r' = v, v' = a + g + a_m + a_p, with psi'(r) = ``dpsi``."""
    a = law_bounded() if accel is None else accel
    return dpsi() * v + (a + grav + am + ap)


# --- gains ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class BoundedGains:
    """Gains of the bounded law, per axis (3,) except the exponents."""

    c1: np.ndarray
    delta: np.ndarray
    c2: np.ndarray
    k1: np.ndarray
    k2: np.ndarray
    p2: float
    e1: float
    e2: float

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {k: [float(x) for x in getattr(self, k)] for k in AXIS_KEYS}
        out.update({k: float(getattr(self, k)) for k in EXP_KEYS})
        return out

    def params(self) -> np.ndarray:
        """(3, 8) parameter rows in the order of ``PARAMS``."""
        return np.column_stack([self.c1, self.delta, self.c2, np.full(3, self.p2), self.k1,
                                self.k2, np.full(3, self.e1), np.full(3, self.e2)]).astype(float)

    def slope0(self) -> np.ndarray:
        """psi'(0) = c1/sqrt(delta) (1/s): the r-loop's rate near the target."""
        return self.c1 / np.sqrt(self.delta)


def _num(name: str, x: Any) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float | np.floating):
        raise ParameterError(f"bounded.{name}", x, "must be a number")
    x = float(x)
    if not math.isfinite(x):
        raise ParameterError(f"bounded.{name}", x, "must be finite")
    return x


def bounded_gains_from_dict(d: dict[str, Any]) -> BoundedGains:
    """Validate a ``[bounded]`` table: c1, delta, c2, k1, k2 > 0 (number or list of three),
    p2 > 1, 0 < e1 < 1 < e2 (the hypotheses of the time bounds)."""
    for key in d:
        if key not in AXIS_KEYS + EXP_KEYS:
            raise ParameterError(f"bounded.{key}", d[key], "unknown key; valid keys are "
                                 + ", ".join(AXIS_KEYS + EXP_KEYS))
    vals: dict[str, Any] = {}
    for k in AXIS_KEYS:
        if k not in d:
            raise ParameterError(f"bounded.{k}", None, "missing; must be > 0")
        raw = d[k] if isinstance(d[k], list | tuple | np.ndarray) else [d[k]] * 3
        if len(raw) != 3:
            raise ParameterError(f"bounded.{k}", d[k], "a list must hold three values (x, y, z)")
        arr = np.array([_num(k, x) for x in raw])
        if np.any(arr <= 0):
            raise ParameterError(f"bounded.{k}", d[k], "must be > 0")
        vals[k] = arr
    rng = {"p2": (lambda x: x > 1, "must be > 1"),
           "e1": (lambda x: 0 < x < 1, "must lie in (0, 1)"),
           "e2": (lambda x: x > 1, "must be > 1")}
    for k in EXP_KEYS:
        if k not in d:
            raise ParameterError(f"bounded.{k}", None, "missing; " + rng[k][1])
        x = _num(k, d[k])
        if not rng[k][0](x):
            raise ParameterError(f"bounded.{k}", x, rng[k][1])
        vals[k] = x
    return BoundedGains(**vals)


# Default gain set: the output of ``lgw tune mars --law bounded --tf 101.6 --thrust-max 50000``
# on the default Table III + Table II envelope (the nearest tf its proven bound meets; see
# docs/tuning.md): proven |F_i| <= 49.0 kN on the whole envelope, proven landing bound 104.9 s
# to the Euclidean landing ball (101.5 s to the per-axis box |r_i|, |v_i| <= 0.1 it was tuned
# against before the tuner's landing set was corrected to 0.1/sqrt(3) per axis).
DEFAULT_BOUNDED = {"c1": [2.311, 2.243, 2.013], "delta": [112.6, 185.8, 96.2],
                   "c2": [1e-9, 1e-9, 1e-9], "k1": [2.498, 2.797, 2.153],
                   "k2": [1.607e-05, 1.912e-05, 6.66e-05], "p2": 1.5, "e1": 0.2, "e2": 1.5}


def default_bounded() -> BoundedGains:
    return bounded_gains_from_dict(DEFAULT_BOUNDED)


def bounded_from_extra(extra: dict[str, Any] | None) -> BoundedGains:
    """The ``[bounded]`` table of a gains file (kept in ``Gains.extra``), else the default."""
    if extra and "bounded" in extra:
        t = extra["bounded"]
        if not isinstance(t, dict):
            raise ParameterError("bounded", t, "must be a table [bounded]")
        return bounded_gains_from_dict(t)
    return default_bounded()


# --- numeric forms (the one implementation the CLI, tuner and tests call) -------------------

def psi_np(x: np.ndarray, bg: BoundedGains, i: int | slice = slice(None)) -> np.ndarray:
    """psi(x) for axis i (x >= 0 or any sign), m/s."""
    x = np.asarray(x, float)
    c1_, d_, c2_ = bg.c1[i], bg.delta[i], bg.c2[i]
    return c1_ * x / np.sqrt(d_ + np.abs(x)) + c2_ * np.sign(x) * np.abs(x) ** bg.p2


def psi_inv_upper(y: np.ndarray, bg: BoundedGains, i: int) -> np.ndarray:
    """An upper bound of psi^(-1)(y), y >= 0, on axis i: the root of c1 x/sqrt(delta + x) = y,
    x = (y^2 + sqrt(y^4 + 4 c1^2 delta y^2)) / (2 c1^2), which is >= psi^(-1)(y) because
    psi >= c1 x/sqrt(delta + x) on x >= 0 (claim ``bounded-psi-monotone``)."""
    y = np.abs(np.asarray(y, float))
    c = bg.c1[i]
    return (y**2 + np.sqrt(y**4 + 4 * c**2 * bg.delta[i] * y**2)) / (2 * c**2)


def slide_primitive(x: np.ndarray, d: np.ndarray) -> np.ndarray:
    """F(x) = 2 sqrt(d+x) + sqrt(d) ln(x / (sqrt(d+x) + sqrt(d))^2), x > 0: an antiderivative of
    sqrt(d+x)/x (claim ``bounded-slide-time``); written without the cancelling difference
    sqrt(d+x) - sqrt(d) = x/(sqrt(d+x) + sqrt(d))."""
    x = np.asarray(x, float)
    sd = np.sqrt(d)
    return 2 * np.sqrt(d + x) + sd * (np.log(x) - 2 * np.log(np.sqrt(d + x) + sd))


def slide_time(x0: np.ndarray, x1: np.ndarray, bg: BoundedGains, i: int,
               theta: float = 1.0) -> np.ndarray:
    """Upper bound on the time for |r| to go from x0 down to x1 (0 < x1) when
    d|r|/dt <= -theta psi(|r|): int_x1^x0 dx/(theta c1 phi(x)) = (F(x0) - F(x1))/(theta c1)
    (the c2 term only shortens it); 0 when x0 <= x1."""
    x0, x1 = np.asarray(x0, float), np.asarray(x1, float)
    t = (slide_primitive(np.maximum(x0, x1), bg.delta[i]) - slide_primitive(x1, bg.delta[i]))
    return t / (theta * bg.c1[i])


def slide_time_global(x1: float, bg: BoundedGains, i: int) -> float:
    """A bound on the sliding-phase time from *any* r to |r| <= x1 (fixed time):
    int_x1^oo dx/(c1 phi + c2 x^p2) <= (F(X) - F(x1))/c1 + X^(1-p2)/(c2 (p2-1)) for every
    X >= x1; the least over a log grid of X is returned (each is a valid bound)."""
    xs = x1 * np.logspace(0, 16, 801)
    vals = (slide_time(xs, np.full_like(xs, x1), bg, i)
            + xs ** (1 - bg.p2) / (bg.c2[i] * (bg.p2 - 1)))
    return float(np.min(vals))


def landing_radius(bg: BoundedGains, i: int, pos_tol: float = 0.1, vel_tol: float = 0.1,
                   s_nb: float = 0.0, theta2: float = 1.0) -> float:
    """rho: the radius of |r| the r-loop is driven into, with |r| <= rho <= pos_tol and
    |v| <= psi(rho) + s_nb <= vel_tol there (a landing inside the criterion).  Without
    disturbance rho = min(pos_tol, psi^(-1)(vel_tol)); with |s| <= s_nb the r-loop's practical
    neighbourhood psi(|r|) <= s_nb/(1-theta2) must fit inside it (else ParameterError)."""
    if s_nb >= vel_tol:
        raise ParameterError("s_nb", s_nb, f"must be < the velocity tolerance {vel_tol} m/s")
    rho = min(pos_tol, float(psi_inv_upper(vel_tol - s_nb, bg, i)))
    while psi_np(rho, bg, i) + s_nb > vel_tol:  # psi_inv_upper is an upper end: step inside
        rho *= 0.999
    if s_nb > 0:
        r_nb = float(psi_inv_upper(s_nb / (1 - theta2), bg, i))
        if r_nb > rho:
            raise ParameterError("a_max", s_nb, "the disturbance's sliding neighbourhood "
                                 f"|r| <= {r_nb:.3g} m does not fit in the landing set")
    return rho


def s_neighborhood(a_max: float, bg: BoundedGains, theta1: float) -> np.ndarray:
    """|s| <= s_nb per axis under |a_p,i| <= a_max: the larger root-free bound of seed 000 (39)
    applied to s, min{(a_max/((1-theta1) k1))^(1/e1), (a_max/((1-theta1) k2))^(1/e2)}."""
    return np.minimum((a_max / ((1 - theta1) * bg.k1)) ** (1 / bg.e1),
                      (a_max / ((1 - theta1) * bg.k2)) ** (1 / bg.e2))


def reach_time(s0: np.ndarray, bg: BoundedGains, i: int) -> np.ndarray:
    """Exact time for s' = -k1 sig(s,e1) - k2 sig(s,e2) to bring |s| from s0 to 0."""
    return settling_time(np.abs(np.asarray(s0, float)), bg.k1[i], bg.k2[i], bg.e1, bg.e2)


def reach_time_global(bg: BoundedGains) -> np.ndarray:
    """T_s* = sup over s0 of ``reach_time`` (exact Gamma closed form), per axis."""
    return exact_bound(bg.k1, bg.k2, bg.e1, bg.e2)


# --- bounds over a box of initial states ----------------------------------------------------

@dataclass(frozen=True)
class AxisBox:
    """Initial states of one axis: r0 in [r_lo, r_hi] m, v0 in [v_lo, v_hi] m/s."""

    r_lo: float
    r_hi: float
    v_lo: float
    v_hi: float


def _cells_sup(bg: BoundedGains, i: int, R: float, s_b: float, v_b: float,
               n: int = 600) -> float:
    """A rigorous upper bound of sup_{0<=x<=R} psi'(x) min(v_b, s_b + psi(x)) (1/s * m/s).

    On each cell [x_j, x_j+1] of a grid (0 and a log grid up to R): c1 phi' decreases,
    c2 p2 x^(p2-1) and psi increase (claim ``bounded-psi-monotone``), so the product is at most
    (c1 phi'(x_j) + c2 p2 x_j+1^(p2-1)) min(v_b, s_b + psi(x_j+1))."""
    if R <= 0:
        return float(bg.slope0()[i] * min(v_b, s_b))
    lo_x = max(R * 1e-9, 1e-9)
    xs = np.concatenate([[0.0], np.geomspace(lo_x, R, n)])
    a, b = xs[:-1], xs[1:]
    d_ = bg.delta[i]
    dphi = bg.c1[i] * (d_ + a / 2) * (d_ + a) ** -1.5
    dpow = bg.c2[i] * bg.p2 * b ** (bg.p2 - 1)
    return float(np.max((dphi + dpow) * np.minimum(v_b, s_b + psi_np(b, bg, i))))


def axis_box_bounds(bg: BoundedGains, i: int, box: AxisBox, *, a_max: float = 0.0,
                    theta1: float = 0.5, theta2: float = 0.5, pos_tol: float = 0.1,
                    vel_tol: float = 0.1) -> dict[str, float]:
    """Every bound of the bounded law for axis i from any initial state of ``box``:

      S      max |s(0)| over the box (s increases in r and v: attained at a corner);
      s_nb   the disturbance's neighbourhood of s = 0 (0 without disturbance);
      R_b    bound on |r(t)| for all t >= 0: max(|r0|max, psi^(-1)(max(S, s_nb)));
      V_b    bound on |v(t)|: max(|v0|max, psi(R_b) + s_nb);
      u_b    bound on |a + g + a_m| = |-psi' v - k1 sig(s,e1) - k2 sig(s,e2)| for all t:
             sup_x psi'(x) min(V_b, S_b + psi(x)) + k1 S_b^e1 + k2 S_b^e2 (S_b = max(S, s_nb));
      rho    the landing radius (``landing_radius``); T_s the time for s to reach 0 (its
             neighbourhood with disturbance); T_r the sliding-phase time from R_b to rho;
      T_land = T_s + T_r, the proven bound on the time to reach |r| <= rho, |v| <= psi(rho)+s_nb
             on this axis (and stay), from every state of the box.
    Proofs: claims ``bounded-invariants`` and ``bounded-time`` of ``bounded_claims``."""
    s_corner = np.array([box.v_hi + psi_np(box.r_hi, bg, i), box.v_lo + psi_np(box.r_lo, bg, i)])
    S_ = float(np.max(np.abs(s_corner)))
    R0 = max(abs(box.r_lo), abs(box.r_hi))
    V0 = max(abs(box.v_lo), abs(box.v_hi))
    s_nb = float(s_neighborhood(a_max, bg, theta1)[i]) if a_max > 0 else 0.0
    s_b = max(S_, s_nb)
    R_b = max(R0, float(psi_inv_upper(s_b, bg, i)))
    V_b = max(V0, float(psi_np(R_b, bg, i)) + s_nb)
    u_b = (_cells_sup(bg, i, R_b, s_b, V_b) + bg.k1[i] * s_b**bg.e1 + bg.k2[i] * s_b**bg.e2)
    rho = landing_radius(bg, i, pos_tol, vel_tol, s_nb, theta2 if a_max > 0 else 1.0)
    if a_max > 0:
        k1_, k2_ = bg.k1[i], bg.k2[i]
        T_s = float(max(settling_time(S_, k1_, k2_, bg.e1, bg.e2)
                        - settling_time(s_nb, k1_, k2_, bg.e1, bg.e2), 0.0) / theta1)
        T_r = float(slide_time(R_b, rho, bg, i, theta2))
    else:
        T_s = float(reach_time(S_, bg, i))
        T_r = float(slide_time(R_b, rho, bg, i))
    return {"S": S_, "s_nb": s_nb, "R_b": R_b, "V_b": V_b, "u_b": float(u_b), "rho": rho,
            "T_s": T_s, "T_r": T_r, "T_land": T_s + T_r}


def global_time_bound(bg: BoundedGains, i: int, pos_tol: float = 0.1,
                      vel_tol: float = 0.1) -> float:
    """Fixed-time bound from *every* initial state (no disturbance): T_s* + sliding bound."""
    rho = landing_radius(bg, i, pos_tol, vel_tol)
    return float(reach_time_global(bg)[i]) + slide_time_global(rho, bg, i)


@cache
def law_expr() -> sp.Expr:
    return law_bounded()


def thrust_bound(bg: BoundedGains, i: int, box: AxisBox, m_max: float, grav_i: float,
                 drag_force_coef: float, **kw: Any) -> float:
    """A proven bound on |F_i| = m |a_i| (N) for all t >= 0 from every state of ``box``:
    m_max (|g_i| + u_b) + drag_force_coef V_b^2, where a_i = -g_i - a_m,i + u and
    m |a_m,i| <= drag_force_coef v_i^2 (the caller's drag model, e.g. (1/2) rho0 C_D A_i times
    the density factor on r_z >= -0.1 m); m <= m_max because the mass only decreases (13)."""
    d = axis_box_bounds(bg, i, box, **kw)
    return float(m_max * (abs(grav_i) + d["u_b"]) + drag_force_coef * d["V_b"] ** 2)


# --- a variant not yet certified: saturated cancellation -------------
w0 = sp.Symbol("w_0", positive=True)  # m/s, the speed margin of the saturation
PARAMS_SAT = PARAMS + (w0,)


def sat_limit() -> sp.Expr:
    """W(r) = psi(|r|) + w0: the speed up to which psi'(r) v is cancelled exactly."""
    return psi().subs(r, sp.Abs(r)) + w0


def law_bounded_sat() -> sp.Expr:
    """a = -g - a_m - psi'(r) sat(v, W(r)) - k1 sig(s,e1) - k2 sig(s,e2), sat(v, W) =
    max(-W, min(W, v)).

    Where |v| <= W(r) it is ``law_bounded`` (s' = -k(s) + a_p exactly); outside, the
    cancellation is capped at psi'(r) W(r), which removes the psi'(r)|v| term that limits
    psi'(0) (and so the terminal rate) for ``law_bounded``.  Proven here (claim
    ``bounded-sat-invariance``): {|v| <= W(r)} is forward invariant when k(w0) > a_max, and
    outside it |v| decreases at a rate >= k(w0) - a_max.  Not yet derived: a time and command
    bound over a box that is tight enough to tune with (the crude one goes through
    R0 + V0 T_out); so it is not registered as a law and has no tuner."""
    W = sat_limit()
    return -grav - am - dpsi() * sp.Max(-W, sp.Min(W, v)) + reaching(surface())
