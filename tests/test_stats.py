"""Campaign statistics: the mean lies within [min, max], non-finite and excluded cases are
counted apart, never inside a statistic."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from lgw.tuning.stats import finite_stats, outcome_counts


@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), max_size=50),
       st.integers(0, 2**32 - 1))
def test_stats_are_possible(vals, seed):
    rng = np.random.default_rng(seed)
    mask = rng.random(len(vals)) < 0.7
    s = finite_stats(vals, mask)
    v = np.asarray(vals, float)
    ok = mask & np.isfinite(v)
    assert s["n"] == ok.sum() and s["excluded"] == len(vals) - ok.sum()
    if s["n"]:
        assert s["min"] <= s["mean"] <= s["max"] and s["min"] <= s["median"] <= s["max"]
        assert np.isfinite([s["min"], s["max"]]).all()
    else:
        assert s["mean"] is None and s["max"] is None


def test_a_blown_up_case_is_not_the_maximum():
    s = finite_stats([1.0, 2.0, np.inf, 1.7e308], [True, True, True, False])
    assert s == {"n": 2, "excluded": 2, "min": 1.0, "mean": 1.5, "median": 1.5, "max": 2.0}
    assert outcome_counts([0, 2, 2], ["a", "b", "c"]) == {"a": 1, "b": 0, "c": 2}


def test_eros_campaign_table_counts_blown_up_cases_apart():
    """The eros Table 2 analogue showed "peak inf / 1.7e308", a mean above the maximum: its
    statistics are over the tracked and horizon cases' finite values, the rest counted in
    ``outcomes``."""
    from lgw.sim.eros.batch import OUTCOMES
    from lgw.sim.eros.campaign import SUMMARY_KEYS, table

    code = np.array([OUTCOMES.index(o) for o in ("tracked", "horizon", "nonfinite",
                                                  "crashed")])
    d = {k: np.array([1.0, 3.0, np.inf, 1.7e308]) for k in SUMMARY_KEYS}
    d.update(outcome=code, nonfinite=np.array([False, False, True, False]))
    row = table({"ftsmc-sign": d})[0]
    for k in SUMMARY_KEYS:
        assert row[f"{k}_mean"] == 2.0 and row[f"{k}_max"] == 3.0 and row[f"{k}_n"] == 2
    assert row["outcomes"]["nonfinite"] == 1 and row["outcomes"]["crashed"] == 1
    empty = table({"x": {**d, "outcome": np.full(4, OUTCOMES.index("nonfinite"))}})[0]
    assert empty["iae_mean"] is None and empty["iae_n"] == 0
