"""Hypothesis strategies and property helpers for seed 000 (``lgw.testing.mars``).

Gain sets respect the hypotheses of the theorems (lgw.theory.mars.gains): 0 < q1 < 1 < q2 (q1
in (0.5, 1) for simulation: the corrected law's |s1|^(2 q1 - 1) term is singular below),
0 < g1 < 1 < g2, exponents q2, g2 in (1, 3), each kept 0.01 inside its open range (at the
ends the bounds diverge: T ~ 1/(1 - g1), 1/(g2 - 1)); per-axis gains log-uniform over several
decades; the disturbance a_max > 0, theta1, theta2 in (0, 1).  Initial states go from 1e-6 m
to 1e5 m and from 1e-6 m/s to 1e3 m/s with exact zeros and both signs; a batch of states is
one (N, 3) array (hypothesis.extra.numpy) so one example is one batched simulation.

The helpers return ``lgw.tuning.verifying.ClaimResult`` records, the rows ``lgw verify mars``
prints.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from lgw.testing import checker
from lgw.theory.mars.gains import Gains, gains_from_dict


def log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    """10^u, u uniform in [log10 lo, log10 hi] (shrinks towards lo)."""
    return st.floats(np.log10(lo), np.log10(hi)).map(lambda u: float(10.0**u))


def open_interval(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, exclude_min=True, exclude_max=True)


def per_axis(s: st.SearchStrategy[float]) -> st.SearchStrategy[Any]:
    """One value for all axes or a list of three."""
    return st.one_of(s, st.lists(s, min_size=3, max_size=3))


@st.composite
def gain_dicts(draw, *, disturbance: bool = True, sim: bool = True) -> dict[str, Any]:
    """A {"gains": ..., "disturbance": ...} dict as gains_from_dict reads it."""
    q1 = draw(st.floats(0.51 if sim else 0.01, 0.99))
    gains = {
        "beta1": draw(per_axis(log_uniform(0.1, 5.0))),
        "beta2": draw(per_axis(log_uniform(1e-5, 1e-2))),
        "alpha1": draw(per_axis(log_uniform(0.1, 5.0))),
        "alpha2": draw(per_axis(log_uniform(1e-6, 1e-2))),
        "q1": q1,
        "q2": draw(st.floats(1.01, 2.99)),
        "g1": draw(st.floats(0.01, 0.99)),
        "g2": draw(st.floats(1.01, 2.99)),
    }
    out: dict[str, Any] = {"gains": gains}
    if disturbance:
        out["disturbance"] = {"a_max": draw(log_uniform(0.1, 20.0)),
                              "theta1": draw(open_interval(0.05, 0.95)),
                              "theta2": draw(open_interval(0.05, 0.95))}
    return out


def gain_sets(**kw) -> st.SearchStrategy[Gains]:
    return gain_dicts(**kw).map(gains_from_dict)


def signed_magnitude(lo: float, hi: float) -> st.SearchStrategy[float]:
    """0, or +-10^u with u uniform in [log10 lo, log10 hi]."""
    return st.one_of(st.just(0.0), st.tuples(st.sampled_from([-1.0, 1.0]), log_uniform(lo, hi))
                     .map(lambda t: t[0] * t[1]))


positions = signed_magnitude(1e-6, 1e5)  # m
velocities = signed_magnitude(1e-6, 1e3)  # m/s
# The simulator cannot start at r_i = 0 exactly: the corrected law's |s1|^(q1-1) v is 0 * inf
# there and lgw.sim.mars.batch flags the case nonfinite at t = 0 (even with v = 0), so simulated
# batches draw positions without exact zeros (velocities keep them).
sim_positions = st.tuples(st.sampled_from([1.0, -1.0]), log_uniform(1e-6, 1e5)).map(
    lambda t: t[0] * t[1])

# The reduced per-axis loop has no such limits: surfaces over the whole range the searches use
# (lgw.theory.mars.searches), where |s2(0)| large is the regime in which the landing time
# approaches T2* + T1*.
surfaces = signed_magnitude(1e-3, 1e9)
nonzero_surfaces = st.tuples(st.sampled_from([1.0, -1.0]), log_uniform(1e-3, 1e9)).map(
    lambda t: t[0] * t[1])


def state_batches(n_min: int = 1, n_max: int = 4) -> st.SearchStrategy[tuple[np.ndarray,
                                                                                np.ndarray]]:
    """(r0, v0), each (N, 3), N in [n_min, n_max] (positions without exact zeros)."""
    return st.integers(n_min, n_max).flatmap(lambda n: st.tuples(
        hnp.arrays(np.float64, (n, 3), elements=sim_positions),
        hnp.arrays(np.float64, (n, 3), elements=velocities)))


# --- property helpers: the records lgw verify mars prints -------------------------------

check_bounds = checker("mars")


def check_landing_within_bound(gains=None, **options) -> list:
    """The landing-time claim alone (T2* + T1*, or the certificate's promise)."""
    return check_bounds(gains, claims=("landing-T2+T1",), **options)
