"""Seed 000's bounds as numbers for a gain set: the one implementation every caller uses.

Per axis i, with V = s^2/2 the paper's route gives Lemma 2 with k = 1 and
  (a, b, p, g) = (beta1 2^((q1+1)/2), beta2 2^((q2+1)/2), (q1+1)/2, (q2+1)/2)   for s1, (18)
  (a, b, p, g) = (alpha1 2^((g1+1)/2), alpha2 2^((g2+1)/2), (g1+1)/2, (g2+1)/2) for s2, (26)
The exact bounds do not depend on that route (the same time in the variable |s|, with
(a, b, p, g) = (beta1, beta2, q1, q2)), which ``lgw.theory.mars.claims`` proves.

How the two surfaces' times combine is where the paper and the workbench part ways: the paper
takes max{T1, T2} for the whole landing (Part 1: "the maximum time is 74.5780 s", and (32)),
but s1 obeys (16) only after s2 has reached 0, so the sound bound is T2 + T1 (see claims).
"""

from __future__ import annotations

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import AXES
from lgw.theory.settling import exact_bound, polyakov_bound, settling_time


def _v_route(gain1: np.ndarray, gain2: np.ndarray, e1: float, e2: float):
    """(a, b, p, g) of Lemma 2 for V = s^2/2 under s' = -gain1 sig(s,e1) - gain2 sig(s,e2)."""
    return gain1 * 2 ** ((e1 + 1) / 2), gain2 * 2 ** ((e2 + 1) / 2), (e1 + 1) / 2, (e2 + 1) / 2


def t1_polyakov(g: Gains) -> np.ndarray:
    """Seed 000, eq. (18), per axis."""
    return polyakov_bound(*_v_route(g.beta1, g.beta2, g.q1, g.q2))


def t2_polyakov(g: Gains) -> np.ndarray:
    """Seed 000, eq. (26), per axis."""
    return polyakov_bound(*_v_route(g.alpha1, g.alpha2, g.g1, g.g2))


def t1_exact(g: Gains) -> np.ndarray:
    """Least upper bound of the time for (16) to bring s1 to 0 (not in seed 000)."""
    return exact_bound(g.beta1, g.beta2, g.q1, g.q2)


def t2_exact(g: Gains) -> np.ndarray:
    """Least upper bound of the time for s2' = -alpha1 sig(s2,g1) - alpha2 sig(s2,g2) to reach 0."""
    return exact_bound(g.alpha1, g.alpha2, g.g1, g.g2)


def reaching_time(s0: np.ndarray, gain1, gain2, e1: float, e2: float) -> np.ndarray:
    """Exact T(s0) for s' = -gain1 sig(s,e1) - gain2 sig(s,e2): seed 000 (16) from |s(0)| = s0."""
    return settling_time(np.abs(np.asarray(s0, float)), gain1, gain2, e1, e2)


def neighborhood(eta, gain1, gain2, e1: float, e2: float, theta: float) -> np.ndarray:
    """Seed 000, eqs. (38)/(39) and (44)/(31): |s| <= min{(eta/((1-theta) gain1))^(1/e1),
    (eta/((1-theta) gain2))^(1/e2)} for V' <= -gain1|s|^(e1+1) - gain2|s|^(e2+1) + eta|s|."""
    # one candidate may overflow to inf at the edge of the accepted range (e.g. q1 = 1e-300):
    # the minimum is then the other, finite one; check_evaluable rejects sets where both are
    with np.errstate(over="ignore"):
        return np.minimum((eta / ((1 - theta) * gain1)) ** (1 / e1),
                          (eta / ((1 - theta) * gain2)) ** (1 / e2))


def s2_bound(g: Gains) -> np.ndarray:
    """Seed 000, eq. (39): the neighborhood of s2 = 0 under |a_p,i| <= a_max (= M_i of (31))."""
    d = _need_disturbance(g)
    return neighborhood(d.a_max, g.alpha1, g.alpha2, g.g1, g.g2, d.theta1)


def s1_bound(g: Gains) -> np.ndarray:
    """Seed 000, eq. (31)/(44): the neighborhood of s1 = r = 0 (the landing error per axis)."""
    d = _need_disturbance(g)
    return neighborhood(s2_bound(g), g.beta1, g.beta2, g.q1, g.q2, d.theta2)


def _need_disturbance(g: Gains):
    if g.disturbance is None:
        raise ParameterError("disturbance", None, "a [disturbance] table (a_max, theta1, theta2) "
                             "is needed for the practical bounds")
    return g.disturbance


def practical_exact(gain1, gain2, e1, e2, theta, nbhd) -> np.ndarray:
    """Time to enter |s| <= nbhd when V' <= -theta (gain1|s|^(e1+1) + gain2|s|^(e2+1)) holds
    outside it (Theorem 1's (7)-(9)): (T* - T(nbhd))/theta.  Sharper than (6), and sound for the
    same reason: outside the neighborhood the comparison system is slower than the true one."""
    return (exact_bound(gain1, gain2, e1, e2) - settling_time(nbhd, gain1, gain2, e1, e2)) / theta


def axis_bounds(g: Gains) -> dict[str, dict[str, float]]:
    """Every bound of seed 000 for the gain set, per axis, plus the workbench's landing bounds.

    Keys (all seconds or metres):
      T1_polyakov (18), T1_exact, T2_polyakov (26), T2_exact,
      T_whole_paper: max{T1, T2}, the paper's "maximum time for the whole mission" (refuted),
      landing_time_bound: T2_exact + T1_exact, the workbench's sound bound without disturbance
        for the corrected law (the printed law (25) has no proven bound),
      landing_time_bound_polyakov: T2_polyakov + T1_polyakov (sound, looser);
    with a [disturbance] table also
      s2_bound (39), T2_practical (40), T2_practical_exact, s1_bound (31), T1_practical (45),
      T1_practical_exact, T3_paper (32 as printed: max of (40), (45)),
      v_bound: |v_i| <= beta1 s1^q1 + beta2 s1^q2 + s2 inside both neighborhoods,
      landing_time_bound_disturbed: T2_practical_exact + T1_practical_exact, the workbench's sound
        bound on the time to enter |r_i| <= s1_bound under |a_p,i| <= a_max (corrected law).
    """
    out: dict[str, np.ndarray] = {
        "T1_polyakov": t1_polyakov(g),
        "T1_exact": t1_exact(g),
        "T2_polyakov": t2_polyakov(g),
        "T2_exact": t2_exact(g),
    }
    out["T_whole_paper"] = np.maximum(out["T1_polyakov"], out["T2_polyakov"])
    out["landing_time_bound"] = out["T1_exact"] + out["T2_exact"]
    out["landing_time_bound_polyakov"] = out["T1_polyakov"] + out["T2_polyakov"]
    if g.disturbance is not None:
        d = g.disturbance
        m = s2_bound(g)
        n = s1_bound(g)
        out["s2_bound"] = m
        out["T2_practical"] = out["T2_polyakov"] / d.theta1
        out["T2_practical_exact"] = practical_exact(g.alpha1, g.alpha2, g.g1, g.g2, d.theta1, m)
        out["s1_bound"] = n
        out["T1_practical"] = out["T1_polyakov"] / d.theta2
        out["T1_practical_exact"] = practical_exact(g.beta1, g.beta2, g.q1, g.q2, d.theta2, n)
        out["T3_paper"] = np.maximum(out["T2_practical"], out["T1_practical"])
        out["v_bound"] = g.beta1 * n**g.q1 + g.beta2 * n**g.q2 + m
        out["landing_time_bound_disturbed"] = out["T2_practical_exact"] + out["T1_practical_exact"]
    return {ax: {k: float(val[i]) for k, val in out.items()} for i, ax in enumerate(AXES)}


# which of the user's parameters each bound depends on (for check_evaluable's error message)
_S1 = "beta1, beta2, q1, q2"
_S2 = "alpha1, alpha2, g1, g2"
_DIST = "[disturbance] a_max, theta1, theta2"
_DEPENDS = (
    (("T1_polyakov", "T1_exact"), _S1, "T1 (18) and T1_exact scale as 1/beta1, 1/beta2"),
    (("T2_polyakov", "T2_exact"), _S2, "T2 (26) and T2_exact scale as 1/alpha1, 1/alpha2"),
    (("T_whole_paper", "landing_time_bound", "landing_time_bound_polyakov"), f"{_S1}, {_S2}",
     "the landing-time bounds T1 + T2"),
    (("s2_bound", "T2_practical", "T2_practical_exact"), f"{_S2}, {_DIST}",
     "the neighbourhood (39) (a_max/((1 - theta1) alpha))^(1/g) and the time (40)"),
    (("s1_bound", "T1_practical", "T1_practical_exact", "T3_paper", "v_bound",
      "landing_time_bound_disturbed"), f"{_S1}, {_S2}, {_DIST}",
     "the neighbourhood (31)/(44), v_bound and the times (45), (32)"),
)


def check_evaluable(g: Gains) -> None:
    """Range check: every bound of ``axis_bounds`` is a finite double for ``g``.

    The gain hypotheses (``lgw.theory.mars.gains``) admit values for which the closed forms
    overflow: T1* ~ 1/beta1 is inf for beta1 = 1e-308, the neighbourhood (39) raises
    a_max/((1 - theta1) alpha1) to the power 1/g1.  Such a gain set is rejected here with a
    ParameterError naming the user's parameters behind the first bound that is not finite,
    instead of printing Infinity or raising OverflowError."""
    try:
        with np.errstate(all="ignore"):
            b = axis_bounds(g)
    except (OverflowError, ZeroDivisionError, ParameterError) as e:
        raise ParameterError(f"{_S1}, {_S2}", _gain_values(g, _S1 + ", " + _S2),
                             "the bounds (18), (26) cannot be evaluated in double precision "
                             f"for these values ({type(e).__name__}: {e})") from None
    for keys, names, what in _DEPENDS:
        bad = [(ax, k) for ax in AXES for k in keys if k in b[ax]
               and not (np.isfinite(b[ax][k]) and b[ax][k] >= 0)]
        if bad:
            ax, k = bad[0]
            raise ParameterError(names, _gain_values(g, names),
                                 f"the bound {k} on axis {ax} is {b[ax][k]!r}: {what}; the "
                                 "values must keep every bound a finite double (< 1.8e308)")


def _gain_values(g: Gains, names: str) -> dict[str, object]:
    out: dict[str, object] = {}
    for n in names.replace("[disturbance] ", "").split(", "):
        if g.disturbance is not None and n in ("a_max", "theta1", "theta2"):
            out[n] = getattr(g.disturbance, n)
        elif hasattr(g, n):
            v = getattr(g, n)
            out[n] = [float(x) for x in v] if isinstance(v, np.ndarray) else v
    return out


def landing_time_bound(g: Gains, disturbed: bool = False) -> float:
    """The workbench's sound landing-time bound over all axes (corrected law)."""
    key = "landing_time_bound_disturbed" if disturbed else "landing_time_bound"
    return max(b[key] for b in axis_bounds(g).values())


# --- Remark 1: the least flight time a thrust limit allows --------------------------------

def tf_min_printed(r0: np.ndarray, v0: np.ndarray, a_max: float, grav: np.ndarray) -> np.ndarray:
    """Seed 000, Remark 1 as printed: max over axes of
    tf1 = (-v0 + sqrt(v0^2 - 2 a_max r0))/a_max and tf2 = -v0/(a_max - g).
    NaN where the square root is of a negative number (r0 > 0 with small v0)."""
    with np.errstate(invalid="ignore"):
        tf1 = (-v0 + np.sqrt(v0**2 - 2 * a_max * r0)) / a_max
    tf2 = -v0 / (a_max - grav)
    return np.maximum(tf1, tf2)


def tf_min(r0: np.ndarray, v0: np.ndarray, a_max: float, grav: np.ndarray) -> np.ndarray:
    """A sound lower bound on the landing time of one axis with |a_i| <= a_max (corrected
    Remark 1 of seed 000).  Departures from the printed formulas:
      - position: reach r = 0 with the best acceleration toward the target, a_max plus the
        gravity component that points the same way; valid for either sign of r0
        (the printed tf1 is the r0 < 0, no-gravity case and is NaN for r0 > 0);
      - velocity: stop with the best acceleration against v0, a_max - sgn(v0) g_i
        (the printed -v0/(a_max - g) is negative for v0 > 0 and uses the wrong sign of g for
        v0 < 0 on the z axis).
    Pass a_max = F_max / m_min for a bound that holds whatever the mass."""
    r0, v0, grav = (np.asarray(x, float) for x in (r0, v0, grav))
    if not a_max > np.max(np.abs(grav)):
        raise ParameterError("a_max", a_max, f"must exceed |g| = {np.max(np.abs(grav))} m/s^2")
    toward = -np.sign(r0)  # direction of the target from the lander
    dist = np.abs(r0)
    u = v0 * toward  # speed toward the target
    acc = a_max + grav * toward  # best acceleration toward the target
    tf1 = np.where(dist > 0, (-u + np.sqrt(u**2 + 2 * acc * dist)) / acc, 0.0)
    dec = a_max - np.sign(v0) * grav  # best deceleration against v0
    tf2 = np.abs(v0) / dec
    return np.maximum(tf1, tf2)
