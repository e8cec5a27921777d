"""The bounded law with saturated cancellation: gains, box bounds, thrust bound.

The law (``lgw.theory.mars.bounded.law_bounded_sat``), per axis of seed 000's plant (10), (30):

  a = -g - a_m - psi'(r) sat(v, W(r)) - k(s),   s = v + psi(r),   W(r) = psi(|r|) + w0,
  sat(v, W) = max(-W, min(W, v)),   k(s) = k1 sig(s, e1) + k2 sig(s, e2),

with psi, psi' of ``bounded`` and a speed margin w0 > 0 (m/s).  Inside Omega = {|v| <= W(r)} it
is the bounded law, so s' = -k(s) + a_p exactly (claim ``bounded-derivative``); Omega is forward
invariant when k(w0) > a_max (claim ``bounded-sat-invariance``).  Outside Omega, v > W(r) (the
case v < -W(r) is symmetric): s = v + psi(r) > psi(|r|) + psi(r) + w0 >= w0 (psi is odd and
increasing), so

  v' = -psi'(r) W(r) - k(s) + a_p <= -D,   D = inf_{|x| <= R_out} psi'(x) W(x) + k(w0) - a_max > 0

(claim ``bounded-sat-outside``).  So the time outside is T_out <= (|v0| - w0)/D and |r| moves by
at most (v0^2 - w0^2)/(2 D) while outside (dr = v dt <= -v dv/D).  Once in Omega, |s| decreases
(s' = -k(s)); |r| grows only while |s| > psi(|r|), by at most (claim ``bounded-sat-growth``)

  G(y, S) = int_{psi(y)}^{S} (sigma - psi(y)) / (k1 sigma^e1) d sigma      (y = min |r| so far),

a closed form; the old route |r| <= psi^-1(S) is kept and the smaller is used.  The command
bound is psi'(r) W(r) + k(|s|) outside and psi'(r)|v| + k(|s|) inside, with |s| bounded per
phase.  Every quantity is computed by one function, ``axis_box_bounds_sat``, which the CLI, the
tuner, the report and the tests call.  The bounds are box-wise, not uniform: T_out and the
excursion grow with the box's largest |v0| (the law is not fixed-time from every state with a
bound independent of v0 on the outside phase; inside Omega it is, as the bounded law).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.mars import bounded as B
from lgw.theory.settling import settling_time

NAME = "bounded-sat"
TABLE = "bounded-sat"  # the TOML table of a gains file
AXIS_KEYS = B.AXIS_KEYS + ("w0",)
EXP_KEYS = B.EXP_KEYS


@dataclass(frozen=True)
class SatGains:
    """Gains of the saturated law: those of ``BoundedGains`` plus w0 (m/s) per axis."""

    c1: np.ndarray
    delta: np.ndarray
    c2: np.ndarray
    k1: np.ndarray
    k2: np.ndarray
    w0: np.ndarray
    p2: float
    e1: float
    e2: float

    def bounded(self) -> B.BoundedGains:
        return B.BoundedGains(self.c1, self.delta, self.c2, self.k1, self.k2, self.p2, self.e1,
                              self.e2)

    def to_dict(self) -> dict[str, Any]:
        out = self.bounded().to_dict()
        out["w0"] = [float(x) for x in self.w0]
        return {k: out[k] for k in AXIS_KEYS + EXP_KEYS}

    def params(self) -> np.ndarray:
        """(3, 9) parameter rows in the order of ``bounded.PARAMS_SAT``."""
        return np.column_stack([self.bounded().params(), self.w0]).astype(float)


def sat_gains_from_dict(d: dict[str, Any]) -> SatGains:
    """Validate a ``[bounded-sat]`` table: the keys of ``[bounded]`` (same ranges) and w0 > 0
    (m/s, number or list of three).  Errors name ``bounded-sat.KEY``."""
    if not isinstance(d, dict):
        raise ParameterError(TABLE, d, "must be a table [bounded-sat]")
    for key in d:
        if key not in AXIS_KEYS + EXP_KEYS:
            raise ParameterError(f"{TABLE}.{key}", d[key], "unknown key; valid keys are "
                                 + ", ".join(AXIS_KEYS + EXP_KEYS))
    if "w0" not in d:
        raise ParameterError(f"{TABLE}.w0", None, "missing; must be > 0 (m/s)")
    raw = d["w0"] if isinstance(d["w0"], list | tuple | np.ndarray) else [d["w0"]] * 3
    if len(raw) != 3:
        raise ParameterError(f"{TABLE}.w0", d["w0"], "a list must hold three values (x, y, z)")
    for x in raw:
        if isinstance(x, bool) or not isinstance(x, int | float | np.floating) \
                or not math.isfinite(float(x)) or float(x) <= 0:
            raise ParameterError(f"{TABLE}.w0", d["w0"], "must be finite numbers > 0 (m/s)")
    w = np.array([float(x) for x in raw])
    try:
        bg = B.bounded_gains_from_dict({k: x for k, x in d.items() if k != "w0"})
    except ParameterError as e:
        raise ParameterError(e.name.replace("bounded.", f"{TABLE}.", 1), e.value,
                             e.valid) from None
    return SatGains(bg.c1, bg.delta, bg.c2, bg.k1, bg.k2, w, bg.p2, bg.e1, bg.e2)


# Default gain set: the output of ``lgw tune mars --law bounded-sat --tf 60 --thrust-max 50000``
# on the default Table III + Table II envelope (docs/tuning.md): proven |F_i| <= 49.0 kN on the
# whole envelope, proven landing bound 57.4 s to the Euclidean landing ball (56.9 s to the
# per-axis box |r_i|, |v_i| <= 0.1 it was tuned against before the tuner's landing set was
# corrected to 0.1/sqrt(3) per axis).
DEFAULT_SAT: dict[str, Any] = {"c1": [3.576, 3.463, 3.249], "delta": [12.87, 12.02, 10.56],
                               "c2": [1e-9, 1e-9, 1e-9], "k1": [2.346, 1.95, 1.901],
                               "k2": [2.081e-06, 8.928e-05, 1.067e-07],
                               "w0": [5.339, 6.155, 5.408], "p2": 1.5, "e1": 0.4, "e2": 1.5}


def default_sat() -> SatGains:
    return sat_gains_from_dict(DEFAULT_SAT)


def sat_from_extra(extra: dict[str, Any] | None) -> SatGains:
    """The ``[bounded-sat]`` table of a gains file (kept in ``Gains.extra``), else the default."""
    if extra and TABLE in extra:
        return sat_gains_from_dict(extra[TABLE])
    return default_sat()


# --- numeric pieces -------------------------------------------------------------------------

def k_np(s: Any, sg: SatGains, i: int) -> np.ndarray:
    """k(s) = k1 s^e1 + k2 s^e2 for s >= 0 (m/s^2): the reaching term's magnitude."""
    s = np.abs(np.asarray(s, float))
    return sg.k1[i] * s**sg.e1 + sg.k2[i] * s**sg.e2


def _grid(R: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    lo_x = max(R * 1e-9, 1e-9)
    xs = np.concatenate([[0.0], np.geomspace(lo_x, max(R, 2 * lo_x), n)])
    return xs[:-1], xs[1:]


def _dpsi_range(sg: SatGains, i: int, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray,
                                                                          np.ndarray]:
    """Lower and upper bounds of psi' on cells [a, b] (c1 phi' nonincreasing, c2 p2 x^(p2-1)
    nondecreasing: claim ``bounded-psi-monotone``)."""
    d_ = sg.delta[i]
    dphi = lambda x: sg.c1[i] * (d_ + x / 2) * (d_ + x) ** -1.5  # noqa: E731
    dpow = lambda x: sg.c2[i] * sg.p2 * x ** (sg.p2 - 1)  # noqa: E731
    return dphi(b) + dpow(a), dphi(a) + dpow(b)


def inf_dpsi_w(sg: SatGains, i: int, R: float, n: int = 400) -> float:
    """A rigorous lower bound of inf_{0<=x<=R} psi'(x) W(x) (m/s^2), W = psi + w0, by cells:
    on [a, b] the product is >= psi'_lo(a, b) (psi(a) + w0) (both factors positive)."""
    a, b = _grid(R, n)
    lo, _ = _dpsi_range(sg, i, a, b)
    return float(np.min(lo * (B.psi_np(a, sg, i) + sg.w0[i])))


def sup_dpsi_speed(sg: SatGains, i: int, R: float, s_b: float | None = None,
                   n: int = 600) -> float:
    """A rigorous upper bound of sup_{0<=x<=R} psi'(x) min(W(x), s_b + psi(x)) (m/s^2) by
    cells (s_b = None: psi'(x) W(x)); W and psi increase."""
    a, b = _grid(R, n)
    _, hi = _dpsi_range(sg, i, a, b)
    speed = B.psi_np(b, sg, i) + sg.w0[i]
    if s_b is not None:
        speed = np.minimum(speed, s_b + B.psi_np(b, sg, i))
    return float(np.max(hi * speed))


def growth_bound(p: Any, S: Any, k1: float, e1: float) -> np.ndarray:
    """G = int_p^S (sigma - p)/(k1 sigma^e1) d sigma (m) for 0 <= p < S, else 0:
    (1/k1) [(S^(2-e1) - p^(2-e1))/(2-e1) - p (S^(1-e1) - p^(1-e1))/(1-e1)] (claim
    ``bounded-sat-growth``); it bounds the growth of |r| in Omega while |s| > psi(y) >= p."""
    p, S = np.asarray(p, float), np.asarray(S, float)
    q = np.minimum(p, S)
    g = ((S ** (2 - e1) - q ** (2 - e1)) / (2 - e1)
         - q * (S ** (1 - e1) - q ** (1 - e1)) / (1 - e1)) / k1
    return np.maximum(g, 0.0)


def radius_in_omega(sg: SatGains, i: int, R_in: float, S: float, n: int = 400) -> float:
    """Bound on |r(t)| in Omega (no disturbance) after entering it with |r| <= R_in, |s| <= S.

    With y = min |r| over [t_in, t] (at time tau): |r(t)| - y <= int (|s| - psi(y))^+ dt
    <= G(psi(y), sigma(tau)) (|s| decreases at rate k(|s|) >= k1 |s|^e1), and in Omega
    sigma <= |v| + psi(|r|) <= 2 psi(y) + w0.  So |r(t)| <= sup_{y <= R_in} y +
    G(psi(y), min(S, 2 psi(y) + w0)), bounded on cells [a, b] by b + G(psi(a), min(S,
    2 psi(b) + w0)) (G decreases in its first and increases in its second argument); the old
    route max(R_in, psi^-1(S)) is also valid and the smaller is returned."""
    crude = max(R_in, float(B.psi_inv_upper(S, sg.bounded(), i)))
    if R_in <= 0:
        return min(crude, float(growth_bound(0.0, min(S, float(sg.w0[i])), sg.k1[i], sg.e1)))
    a, b = _grid(R_in, n)
    cap = np.minimum(S, 2 * B.psi_np(b, sg, i) + sg.w0[i])
    g = growth_bound(B.psi_np(a, sg, i), cap, sg.k1[i], sg.e1)
    return min(crude, max(float(np.max(b + g)), R_in))


def axis_box_bounds_sat(sg: SatGains, i: int, box: B.AxisBox, *, a_max: float = 0.0,
                        theta1: float = 0.5, theta2: float = 0.5, pos_tol: float = 0.1,
                        vel_tol: float = 0.1) -> dict[str, float]:
    """Every bound of the saturated law for axis i from any initial state of ``box``:

      D      the outside deceleration bound, inf psi'W + k(w0) - a_max (m/s^2);
      T_out  time outside Omega, max(|v0| - w0)/D (s);
      R_out  bound on |r| while outside: r in [r_lo - dist_-, r_hi + dist_+],
             dist_+- = ((v0)+-^2 - w0^2)^+ / (2 D) (m);
      S_out  bound on |s| while outside, |v0| + psi(|r|) on each side (m/s);
      S_in   bound on |s| in Omega: at entry from outside s = w0 (toward the target) or
             2 psi(|r|) + w0 (overshooting side); from a start in Omega
             min(max |s0| over the corners, 2 psi(R0) + w0); with disturbance max(., s_nb);
      R_b    bound on |r(t)| for all t: max(R_out, ``radius_in_omega``) (psi^-1(S) with a_p);
      V_b    bound on |v(t)|: max(V0, min(W(R_b), S_in + psi(R_b)));
      u_b    bound on |a + g + a_m| for all t: max over the phases of psi' W + k(S_out)
             (outside) and psi' min(W, S_in + psi) + k(S_in) (inside), sups by cells;
      rho    landing radius (``bounded.landing_radius``);
      T_land max(T_out + T_s(S_entry), T_s(S_start)) + T_r(R_b -> rho) (s), T_s the exact
             settling time of s' = -k(s) (with a_p: Theorem 1's (T(S) - T(s_nb))/theta1).
    Raises ParameterError if k(w0) <= a_max (Omega is then not invariant)."""
    bg = sg.bounded()
    w0 = float(sg.w0[i])
    kw0 = float(k_np(w0, sg, i))
    if kw0 <= a_max:
        raise ParameterError(f"{TABLE}.w0", w0, f"k(w0) = {kw0:.3g} must exceed a_max = "
                             f"{a_max:g} m/s^2 (the invariance of Omega)")
    D0 = kw0 - a_max
    vp, vm = max(box.v_hi, 0.0), max(-box.v_lo, 0.0)  # largest speeds on each side
    R0 = max(abs(box.r_lo), abs(box.r_hi))
    V0 = max(vp, vm)
    # a state outside on the side v > 0 has psi(|r0|) + w0 < v0 <= vp, so |r0| < psi^-1(vp - w0)
    side = []  # (sign, speed, r0 range of the outside states on that side) when nonempty
    for sgn, spd in ((1.0, vp), (-1.0, vm)):
        if spd <= w0:
            continue
        rr = float(B.psi_inv_upper(spd - w0, bg, i))
        lo, hi = max(box.r_lo, -rr), min(box.r_hi, rr)
        if lo <= hi:
            side.append((sgn, spd, lo, hi))

    def excursion(D: float) -> list[float]:
        """per side: the largest |r| on the side the state moves to, while outside (m)."""
        out = []
        for sgn, spd, lo, hi in side:
            dist = (spd**2 - w0**2) / (2 * D)
            out.append(max(hi + dist, 0.0) if sgn > 0 else max(dist - lo, 0.0))
        return out

    far = [max(abs(lo), abs(hi)) for _, _, lo, hi in side]  # |r| on the other side is |r0|
    R1 = max([0.0, *excursion(D0), *far])
    D = D0 + inf_dpsi_w(sg, i, R1)  # valid on [0, R_exc] since R_exc <= R1
    exc = excursion(D)
    R_exc = max([0.0, *exc, *far])
    T_out = max([0.0] + [(spd - w0) / D for _, spd, _, _ in side])
    psi = lambda x: float(B.psi_np(max(x, 0.0), bg, i))  # noqa: E731
    # outside, |s| = |v| + psi(|r|) on the side v moves to (sgn r = sgn v), |v| - psi(|r|) < |v|
    # on the other (|v| <= |v0| decreases while outside)
    S_out = max([0.0] + [spd + psi(e) for (_, spd, _, _), e in zip(side, exc, strict=True)])
    S_entry = max([0.0] + [2 * psi(e) + w0 for e in exc])  # s = w0 on the toward side
    s_corner = [box.v_hi + float(B.psi_np(box.r_hi, bg, i)),
                box.v_lo + float(B.psi_np(box.r_lo, bg, i))]  # s increases in r and v
    S_start = min(max(abs(x) for x in s_corner), 2 * psi(R0) + w0)
    s_nb = float(B.s_neighborhood(a_max, bg, theta1)[i]) if a_max > 0 else 0.0
    S_in = max(S_entry, S_start, s_nb)
    R_out = max(R0, R_exc)
    if a_max > 0:
        R_b = max(R_out, float(B.psi_inv_upper(S_in, bg, i)))
    else:
        R_b = max(R_out, radius_in_omega(sg, i, R0, S_start),
                  radius_in_omega(sg, i, R_exc, S_entry) if side else 0.0)
    V_b = max(V0, min(psi(R_b) + w0, S_in + psi(R_b)))
    u_out = (sup_dpsi_speed(sg, i, R_out) + float(k_np(S_out, sg, i))) if S_out > 0 else 0.0
    u_in = sup_dpsi_speed(sg, i, R_b, S_in) + float(k_np(S_in, sg, i))
    rho = B.landing_radius(bg, i, pos_tol, vel_tol, s_nb, theta2 if a_max > 0 else 1.0)

    def t_s(S: float) -> float:
        k1_, k2_ = bg.k1[i], bg.k2[i]
        if a_max > 0:
            return float(max(settling_time(S, k1_, k2_, bg.e1, bg.e2)
                             - settling_time(s_nb, k1_, k2_, bg.e1, bg.e2), 0.0) / theta1)
        return float(settling_time(S, k1_, k2_, bg.e1, bg.e2))
    T_r = float(B.slide_time(R_b, rho, bg, i, theta2 if a_max > 0 else 1.0))
    T_s = max(T_out + t_s(S_entry) if T_out > 0 else 0.0, t_s(S_start))
    # r never crosses 0 (e.g. the altitude stays > 0) when every state starts at r0 > 0 with
    # s0 >= 0: s' = -k(s) keeps s >= 0 (all such states are in Omega: outside on the side
    # v < 0 needs s < -w0), so r' = s - psi(r) >= -psi(r) >= -psi'_max r: r >= r0 e^(-L t) > 0
    crosses = 0.0 if (box.r_lo > 0 and s_corner[1] >= 0 and a_max == 0) else 1.0
    return {"crosses_zero": crosses, "D": D, "T_out": T_out, "R_out": R_out, "S_out": S_out,
            "S": S_in, "S_entry": S_entry, "S_start": S_start, "s_nb": s_nb, "R_b": R_b, "V_b": V_b,
            "u_b": max(u_out, u_in), "rho": rho, "T_s": T_s, "T_r": T_r, "T_land": T_s + T_r}


def thrust_bound_sat(sg: SatGains, i: int, box: B.AxisBox, m_max: float, grav_i: float,
                     drag_force_coef: float, **kw: Any) -> float:
    """A proven bound on |F_i| (N) for all t >= 0 from every state of ``box``:
    m_max (|g_i| + u_b) + drag_force_coef V_b^2 (as ``bounded.thrust_bound``)."""
    d = axis_box_bounds_sat(sg, i, box, **kw)
    return float(m_max * (abs(grav_i) + d["u_b"]) + drag_force_coef * d["V_b"] ** 2)


def global_time_bound_sat(sg: SatGains, i: int, v_max: float, pos_tol: float = 0.1,
                          vel_tol: float = 0.1) -> float:
    """The time bound from every state with |v0| <= v_max (any r0): T_out + T_s* + the sliding
    phase from any r (``bounded.slide_time_global``): not uniform in v0 (T_out grows with it)."""
    bg = sg.bounded()
    D = float(k_np(sg.w0[i], sg, i))
    t_out = max(v_max - float(sg.w0[i]), 0.0) / D
    rho = B.landing_radius(bg, i, pos_tol, vel_tol)
    return t_out + float(B.reach_time_global(bg)[i]) + B.slide_time_global(rho, bg, i)

