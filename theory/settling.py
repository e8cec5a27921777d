"""Settling-time bounds for V' <= -(a V^p + b V^g)^k (+ eta): seed 000, Lemma 1, Lemma 2, Theorem 1.

Two bounds for the same inequality:

* Polyakov's form, seed 000 eq. (3):  T <= 1/(a^k (1 - p k)) + 1/(b^k (g k - 1)).  It splits the
  integral at V = 1, so it is conservative and not invariant under rescaling V.
* The least upper bound, T* = int_0^oo dV / (a V^p + b V^g)^k
      = Gamma(m_p) Gamma(m_g) / (a^k Gamma(k) (g - p)) * (a/b)^m_p,
  m_p = (1 - k p)/(g - p), m_g = (k g - 1)/(g - p)   (Aldana-Lopez, Gomez-Gutierrez et al.,
  IJRNC 2019).  It is attained by V' = -(a V^p + b V^g)^k as V(0) -> infinity.
* The exact time from a given V0, T(V0) = int_0^V0 dV/(a V^p + b V^g)^k, which is a regularised
  incomplete Beta function (derived in ``lgw.theory.settling_proofs``).

The symbolic forms used by the proofs live in ``lgw.theory.settling_proofs``; the functions here are
the one numeric implementation that the CLI, reports, tuner and tests call, and a test checks
them against the symbolic forms and against quadrature.
"""

from __future__ import annotations

import numpy as np
from lgw.theory.errors import ParameterError
from numpy.typing import ArrayLike
from scipy import special


def _check(a: ArrayLike, b: ArrayLike, p: float, g: float, k: float) -> None:
    # range checks of the lemma's own symbols; a system's loader (e.g. lgw.theory.mars.gains)
    # rejects user values first, naming the user's parameters, so these guard direct callers
    if not np.all(np.isfinite(np.asarray(a, float))) or np.any(np.asarray(a) <= 0):
        raise ParameterError("a", a, "must be finite and > 0")
    if not np.all(np.isfinite(np.asarray(b, float))) or np.any(np.asarray(b) <= 0):
        raise ParameterError("b", b, "must be finite and > 0")
    if not all(np.isfinite(x) for x in (p, g, k)):
        raise ParameterError("p, g, k", (p, g, k), "must be finite")
    if not k > 0:
        raise ParameterError("k", k, "must be > 0")
    if not (p > 0 and p * k < 1):
        raise ParameterError("p", p, f"must satisfy 0 < p k < 1 (k = {k})")
    if not g * k > 1:
        raise ParameterError("g", g, f"must satisfy g k > 1 (k = {k})")


def lemma1_bound(a: ArrayLike, p: float, v0: ArrayLike) -> np.ndarray:
    """Seed 000, Lemma 1: T <= V0^(1-p) / (a (1-p)) for V' <= -a V^p, 0 < p < 1 (exact)."""
    if not 0 < p < 1:
        raise ParameterError("p", p, "must lie in (0, 1)")
    return np.asarray(v0, float) ** (1 - p) / (np.asarray(a, float) * (1 - p))


def polyakov_bound(a: ArrayLike, b: ArrayLike, p: float, g: float, k: float = 1.0) -> np.ndarray:
    """Seed 000, eq. (3) (Lemma 2): 1/(a^k (1 - p k)) + 1/(b^k (g k - 1))."""
    _check(a, b, p, g, k)
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    return a ** (-k) / (1 - p * k) + b ** (-k) / (g * k - 1)


def _beta_params(p: float, g: float, k: float) -> tuple[float, float, float]:
    d = g - p
    return d, (1 - k * p) / d, (k * g - 1) / d


def exact_bound(a: ArrayLike, b: ArrayLike, p: float, g: float, k: float = 1.0) -> np.ndarray:
    """Least upper bound T* of the settling time under Lemma 2's inequality (2) (seed 000).

    Not printed in seed 000, which gives only Polyakov's form (3); this is the supremum of
    int_0^V0 dV/(a V^p + b V^g)^k over V0 (Aldana-Lopez et al. 2019), evaluated in log space.
    """
    _check(a, b, p, g, k)
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    d, mp, mg = _beta_params(p, g, k)
    log_t = (special.gammaln(mp) + special.gammaln(mg) - special.gammaln(k) - np.log(d)
             - k * np.log(a) + mp * (np.log(a) - np.log(b)))
    return np.exp(log_t)


def settling_time(v0: ArrayLike, a: ArrayLike, b: ArrayLike, p: float, g: float,
                  k: float = 1.0) -> np.ndarray:
    """Exact time for V' = -(a V^p + b V^g)^k to bring V from v0 to 0.

    T(v0) = T* * I_u(m_p, m_g) with u = c v0^d / (1 + c v0^d), c = b/a, d = g - p, I the
    regularised incomplete Beta function; v0 = inf gives T*.  Used for the reaching law (16)
    with (a, b, p, g) = (beta1, beta2, q1, q2) and V = |s1|.
    """
    _check(a, b, p, g, k)
    v0 = np.asarray(v0, float)
    if np.any(v0 < 0) or np.any(np.isnan(v0)):
        raise ParameterError("v0", v0, "must be >= 0")
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    d, mp, mg = _beta_params(p, g, k)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        log_x = np.log(b) - np.log(a) + d * np.log(v0)  # log(c v0^d)
        # u = x/(1+x), 1-u = 1/(1+x); use the complement where u is close to 1.
        u = special.expit(log_x)
        one_minus_u = special.expit(-log_x)
        frac = np.where(u < 0.5, special.betainc(mp, mg, u), special.betaincc(mg, mp, one_minus_u))
    frac = np.where(v0 == 0, 0.0, frac)
    return exact_bound(a, b, p, g, k) * frac


def practical_neighborhood(a: ArrayLike, b: ArrayLike, p: float, g: float, k: float,
                           theta: float, eta: ArrayLike) -> np.ndarray:
    """Seed 000, eq. (5) (Theorem 1): V <= min{(eta/(a^k(1-theta^k)))^(1/(pk)),
    (eta/(b^k(1-theta^k)))^(1/(gk))}."""
    _check(a, b, p, g, k)
    if not 0 < theta < 1:
        raise ParameterError("theta", theta, "must lie in (0, 1)")
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    eta = np.asarray(eta, float)
    den = 1 - theta**k
    return np.minimum((eta / (a**k * den)) ** (1 / (p * k)), (eta / (b**k * den)) ** (1 / (g * k)))


def practical_polyakov_bound(a: ArrayLike, b: ArrayLike, p: float, g: float, k: float,
                             theta: float) -> np.ndarray:
    """Seed 000, eq. (6) (Theorem 1): 1/(a^k theta^k (1-pk)) + 1/(b^k theta^k (gk-1))."""
    if not 0 < theta < 1:
        raise ParameterError("theta", theta, "must lie in (0, 1)")
    return polyakov_bound(theta * np.asarray(a, float), theta * np.asarray(b, float), p, g, k)
