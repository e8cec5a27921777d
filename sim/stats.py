"""Campaign statistics that are never impossible (for every layer: ``lgw.tuning.stats`` re-exports
them): computed over the finite values of the cases
that count, with every other case counted apart, so a mean is always within [min, max] and no
blown-up case (inf, 1.7e308) hides in a maximum.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np


def finite_stats(values: Any, include: Any = None) -> dict[str, Any]:
    """``{n, min, mean, median, max, excluded}`` over the finite entries of ``values`` where
    ``include`` (a bool mask, default all) holds; ``excluded`` counts the rest (not included,
    or not finite).  With nothing to summarise every statistic is None."""
    v = np.asarray(values, float).ravel()
    mask = np.ones(v.shape, bool) if include is None else np.asarray(include, bool).ravel()
    ok = mask & np.isfinite(v)
    out: dict[str, Any] = {"n": int(ok.sum()), "excluded": int(v.size - ok.sum())}
    if not ok.any():
        return {**out, "min": None, "mean": None, "median": None, "max": None}
    x = v[ok]
    lo, hi = float(x.min()), float(x.max())
    mean = min(max(float(x.mean()), lo), hi)  # rounding may step a hair outside [lo, hi]
    return {**out, "min": lo, "mean": mean, "median": float(np.median(x)), "max": hi}


def outcome_counts(codes: Any, names: Mapping[int, str] | Any) -> dict[str, int]:
    """Cases per outcome name (codes index ``names``), every outcome listed."""
    codes = np.asarray(codes, int).ravel()
    names = list(names)
    return {n: int(np.sum(codes == i)) for i, n in enumerate(names)}
