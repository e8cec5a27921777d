"""Hypothesis strategies and property helpers for seed 001 (``lgw.testing.lunar``).

Orbit-loop gain sets respect the hypotheses of lgw.theory.lunar.gains (K1 = k I with
F1 = K1_zz > 0; F2 diagonal with every entry > 1/2 so f2bar > 1/2; 0 < f3 < f2bar; q > 0;
d0e(0) = 0), as ``lgw.tuning.lunar.verify.random_loop_gains`` draws them.  Initial errors are
the default envelope of ``lgw verify lunar``: height error x1(0) in [-100, 100] m, velocity
error x2(0) in [-5, 5]^3 m/s; a batch is one (x1_0 (N,), x2_0 (N, 3)) pair so that one
example is one batched flight of the general system (5).

The helpers return ``lgw.tuning.verifying.ClaimResult`` records, the rows
``lgw verify lunar`` prints.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp
from lgw.testing import checker
from lgw.theory.lunar.gains import LoopGains, make_loop

X1_MAX = 100.0  # m, |x1(0)|
X2_MAX = 5.0  # m/s, |x2_i(0)|


@st.composite
def orbit_gain_dicts(draw) -> dict[str, Any]:
    """An [orbit] table as lgw.theory.lunar.gains.make_loop reads it."""
    k = draw(st.floats(0.05, 1.0))
    F2 = [draw(st.floats(0.6, 5.0)) for _ in range(3)]
    return {"K1": [k, k, k], "F2": F2, "f3": draw(st.floats(0.05, 0.95)) * min(F2),
            "d0e0": 0.0, "q": draw(st.floats(0.005, 1.0))}


def orbit_gains() -> st.SearchStrategy[LoopGains]:
    return orbit_gain_dicts().map(lambda d: make_loop("orbit", d))


def state_batches(n_min: int = 1, n_max: int = 8, x1_max: float = X1_MAX,
                  x2_max: float = X2_MAX) -> st.SearchStrategy[tuple[np.ndarray, np.ndarray]]:
    """(x1_0 (N,) m, x2_0 (N, 3) m/s), N in [n_min, n_max] (shrinks to 0 errors, few cases)."""
    a = st.floats(-x1_max, x1_max, allow_nan=False)
    b = st.floats(-x2_max, x2_max, allow_nan=False)
    return st.integers(n_min, n_max).flatmap(lambda n: st.tuples(
        hnp.arrays(np.float64, (n,), elements=a), hnp.arrays(np.float64, (n, 3), elements=b)))


# --- property helpers: the records lgw verify lunar prints -------------------------------

check_bounds = checker("lunar")


def check_l2_bounds(gains=None, **options) -> list:
    """The L2-gain claims (18a), (18b), (19a), (19b) derived and (21a) alone."""
    return check_bounds(gains, claims=("(18a)", "(18b)", "(19a)", "(19b) derived", "(21a)"),
                        **options)
