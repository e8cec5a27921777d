"""Settling and reaching times of seed 002's surfaces: one function per bound, used by the CLI,
the report, the tuner and the tests.  Times in seconds, errors in metres, s in m/s.

Derived (claims settling-tsm, settling-ftsm, reaching-*): with r = p/q in (0, 1),
  terminal surface (5), e' = -beta sig(e)^r:          t_s = |e0|^(1-r) / (beta (1-r))
  fast terminal (6), e' = -alpha e - beta sig(e)^r:   t_s = ln(1 + alpha |e0|^(1-r)/beta)
                                                            / (alpha (1-r))
  reaching, s' = D - k sgn(s), |D| <= dbar < k:      t_r <= |s0| / (k - dbar)
The printed (5) and (7) are these with p and q exchanged (negative for p < q).
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.optimize import brentq


def ts_tsm(e0, beta: float, r: float):
    """Sliding-phase settling time on the terminal surface (5), derived (s)."""
    return np.abs(e0) ** (1.0 - r) / (beta * (1.0 - r))


def _log1p(x):
    """log(1 + x) of an array or float (numpy), or of a SymPy expression."""
    return sp.log(1 + x) if isinstance(x, sp.Basic) else np.log1p(x)


def ts_tsm_printed(e0, beta: float, p: float, q: float):
    """The settling time printed after seed 002 eq. (5): p/(beta (p-q)) |e0|^((p-q)/p).
    (Also on SymPy symbols: the claims judge this function's formula.)"""
    return p / (beta * (p - q)) * abs(e0) ** ((p - q) / p)


def ts_ftsm(e0, alpha: float, beta: float, r: float):
    """Sliding-phase settling time on the fast terminal surface (6), derived (s)."""
    return np.log1p(alpha * np.abs(e0) ** (1.0 - r) / beta) / (alpha * (1.0 - r))


def ts_ftsm_printed(e0, alpha: float, beta: float, p: float, q: float):
    """Seed 002 eq. (7) as printed: p/(alpha(p-q)) (ln(alpha e0^((p-q)/p) + beta) - ln beta),
    evaluated as p/(alpha(p-q)) log1p(alpha e0^((p-q)/p)/beta) (the same number, without the
    cancellation of the two logarithms)."""
    return p / (alpha * (p - q)) * _log1p(alpha * abs(e0) ** ((p - q) / p) / beta)


def t_pd(e0, lam: float, tol: float):
    """PD surface s = e' + lam e: e = e0 exp(-lam t) never reaches 0; time to |e| <= tol."""
    return np.maximum(np.log(np.abs(e0) / tol), 0.0) / lam


def t_reach_sign(s0, k: float, dbar: float = 0.0):
    """Time to reach s = 0 under s' = D - k sgn(s), |D| <= dbar < k (bound; equality for
    D = 0, the known-D case of (14))."""
    if not k > dbar:
        raise ValueError("the reaching bound needs k > dbar")
    return np.abs(s0) / (k - dbar)


def s_band_tanh(k: float, phi: float, dbar: float):
    """With u_s = -k tanh(s/phi) and |D| <= dbar < k, s' s < 0 outside |s| <= phi artanh(dbar/k):
    the band the boundary layer leaves (m/s)."""
    return phi * np.arctanh(dbar / k)


def t_reach_tanh(s0, k: float, phi: float, dbar: float, s_band: float):
    """Time bound to enter |s| <= s_band (> s_band_tanh) under s' = D - k tanh(s/phi):
    (|s0| - s_band)/(k tanh(s_band/phi) - dbar), 0 if already inside."""
    rate = k * np.tanh(s_band / phi) - dbar
    if not rate > 0:
        raise ValueError("s_band must exceed phi artanh(dbar/k)")
    return np.maximum(np.abs(s0) - s_band, 0.0) / rate


def e_max_reaching(e0: float, s0: float, alpha: float, beta: float, r: float,
                   lam: float | None = None) -> float:
    """Bound on |e| during the reaching phase while |s| <= |s0|: e' = s - alpha e - beta sig(e)^r
    points inwards wherever alpha|e| + beta|e|^r > |s0|, so |e| <= max(|e0|, e*) with
    alpha e* + beta e*^r = |s0| (PD: lam e* = |s0|)."""
    s0 = abs(s0)
    if s0 == 0.0:
        return abs(e0)
    if lam is not None:
        return max(abs(e0), s0 / lam)
    estar = brentq(lambda x: alpha * x + beta * x**r - s0, 0.0, s0 / alpha + 1.0)
    return max(abs(e0), estar)


def axis_time_bound(e0: float, ed0: float, g, dbar: float = 0.0) -> dict[str, float]:
    """Reaching + sliding time bound of one axis of the FTSMC (known D: dbar = 0; unknown
    |D| <= dbar), continuous-time law with sign switching.  ``g``: lgw.theory.eros.gains.Gains."""
    r = g.p / g.q
    s0 = ed0 + g.alpha * e0 + g.beta * np.sign(e0) * abs(e0) ** r
    tr = float(t_reach_sign(s0, g.k, dbar))
    em = e_max_reaching(e0, s0, g.alpha, g.beta, r)
    ts = float(ts_ftsm(em, g.alpha, g.beta, r))
    return {"s0": float(s0), "t_reach": tr, "e_max_reaching": em, "t_slide": ts,
            "t_total": tr + ts}


def envelope_time_bound(g, e_max: float, v_max: float, dbar: float = 0.0) -> dict[str, float]:
    """Worst case of ``axis_time_bound`` over |e0| <= e_max, |ed0| <= v_max: |s0| is largest at
    the corner e0 = e_max, ed0 = v_max (s0 increasing in both), and t_total grows with |s0| and
    |e0|, so the corner is the worst case."""
    return axis_time_bound(e_max, v_max, g, dbar)
