"""Hypothesis strategies and property helpers for seed 002 (``lgw.testing.eros``).

Gain sets respect the hypotheses of lgw.theory.eros.gains (alpha, beta, k, lam, N, M, phi,
e_floor > 0; integers 0 < p < q, odd as seed 002 asks after (5)); the switching gain k is drawn
above the modelled disturbance bound DIST_AMP = 0.05 m/s^2 (the reaching bound |s0|/(k - dbar)
needs k > dbar).  Initial states are the Monte Carlo envelope of ``lgw simulate eros --cases``:
position errors |e_i(0)| <= MC_POS = 10 m, velocity errors |e_i'(0)| <= MC_VEL = 0.5 m/s, and a
disturbance phase in [0, 2 pi) per case; a batch is one (e0 (N, 3), ed0 (N, 3), phase (N,))
triple so that one example is one batched simulation.

The helpers return ``lgw.tuning.verifying.ClaimResult`` records, the rows ``lgw verify eros``
prints.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from lgw.testing import checker
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains, gains_from_dict


def log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    """10^u, u uniform in [log10 lo, log10 hi] (shrinks towards lo)."""
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda u: float(10.0**u))


@st.composite
def gain_dicts(draw) -> dict[str, Any]:
    """A {"gains": ...} dict as lgw.theory.eros.gains.gains_from_dict reads it."""
    q = draw(st.sampled_from([3, 5, 7, 9]))
    p = draw(st.sampled_from([x for x in range(1, q, 2)]))
    return {"gains": {"alpha": draw(log_uniform(0.1, 5.0)), "beta": draw(log_uniform(0.1, 5.0)),
                      "p": p, "q": q, "k": draw(log_uniform(0.2, 5.0)),
                      "lam": draw(log_uniform(0.1, 5.0)), "N": draw(log_uniform(0.5, 10.0)),
                      "M": draw(log_uniform(0.5, 10.0)), "phi": draw(log_uniform(0.01, 0.5)),
                      "e_floor": draw(log_uniform(1e-6, 1e-3))}}


def gain_sets() -> st.SearchStrategy[Gains]:
    return gain_dicts().map(gains_from_dict)


def state_batches(n_min: int = 1, n_max: int = 16, e_max: float = P.MC_POS,
                  v_max: float = P.MC_VEL) -> st.SearchStrategy[tuple[np.ndarray, ...]]:
    """(e0 (N, 3) m, ed0 (N, 3) m/s, phase (N,) rad), N in [n_min, n_max], over the envelope
    |e0_i| <= e_max, |ed0_i| <= v_max (shrinks towards 0 errors and few cases)."""
    el = st.floats(-e_max, e_max, allow_nan=False)
    vl = st.floats(-v_max, v_max, allow_nan=False)
    ph = st.floats(0.0, 2 * math.pi, exclude_max=True)
    return st.integers(n_min, n_max).flatmap(lambda n: st.tuples(
        hnp.arrays(np.float64, (n, 3), elements=el), hnp.arrays(np.float64, (n, 3), elements=vl),
        hnp.arrays(np.float64, (n,), elements=ph)))


# --- property helpers: the records lgw verify eros prints -------------------------------

check_bounds = checker("eros")


def check_tracking_within_bound(gains=None, **options) -> list:
    """The reaching + sliding time claims alone (known and unknown disturbance)."""
    return check_bounds(gains, claims=("time-known", "time-unknown"), **options)
