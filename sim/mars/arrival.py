"""Thrust spikes after arrival, from a recorded trajectory.

An axis i *arrives* when it first enters its landing band |r_i| <= tol_r (m) and
|v_i| <= tol_v (m/s) (per axis, the band of seed 000's landing criterion after (14) applied to
one component; the default tolerances are ``lgw.theory.mars.parameters.LAND_POS_TOL`` and
``LAND_VEL_TOL``, 0.1 m and 0.1 m/s).  The *spike after arrival* of axis i is the peak |F_i| (N)
from that sample on, to the end of the record: a law whose command stays small once the axis is
on target has a small one; the corrected law's -(b1 q1 |s1|^(q1-1) + ...) v term (seed 000
(25) corrected, see ``lgw.theory.mars.mss``) can spike where s1 = r_i crosses 0 with v_i != 0.

Computed from the samples only (the RK4 nodes of ``simulate_batch(..., record=True)``, or any
other recorded trajectory): a spike between samples is not seen.  One implementation, used by
``lgw compare mars`` (``lgw.tuning.mars.compare``) and ``benchmarks/bench_tune.py``.
"""

from __future__ import annotations

import numpy as np
from lgw.theory.mars.parameters import LAND_POS_TOL, LAND_VEL_TOL


def after_arrival_peaks(r: np.ndarray, v: np.ndarray, F: np.ndarray,  # noqa: N803
                        tol: tuple[float, float] = (LAND_POS_TOL, LAND_VEL_TOL)
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Per case and axis: (first, peak).

    r, v, F: (N, S, 3) samples (m, m/s, N) of N cases at S common sample times, NaN after a
    case stopped (or (S, 3) for one case: the outputs then have shape (3,)).
    first: the sample index at which the axis first has |r_i| <= tol[0] and |v_i| <= tol[1]
    (-1 if never); peak: max |F_i| over the samples from ``first`` on (N; NaN samples ignored;
    NaN if the axis never arrives or no finite |F_i| is recorded from then on).
    """
    r, v, F = (np.asarray(x, float) for x in (r, v, F))  # noqa: N806
    if not r.shape == v.shape == F.shape or r.ndim not in (2, 3) or r.shape[-1] != 3:
        raise ValueError(f"r, v, F must all be (N, S, 3) or (S, 3), got {r.shape}, {v.shape}, "
                         f"{F.shape}")
    if r.ndim == 2:
        first, peak = after_arrival_peaks(r[None], v[None], F[None], tol)
        return first[0], peak[0]
    if r.shape[1] == 0:  # nothing recorded (a run that never started)
        return np.full(r.shape[::2], -1), np.full(r.shape[::2], np.nan)
    with np.errstate(invalid="ignore"):
        band = (np.abs(r) <= tol[0]) & (np.abs(v) <= tol[1])  # (N, S, 3); NaN -> False
    first = np.where(band.any(axis=1), np.argmax(band, axis=1), -1)
    n_s = r.shape[1]
    after = np.arange(n_s)[None, :, None] >= np.where(first < 0, n_s, first)[:, None, :]
    aF = np.where(after & np.isfinite(F), np.abs(F), -np.inf)  # noqa: N806
    peak = aF.max(axis=1)
    return first, np.where((first < 0) | ~np.isfinite(peak), np.nan, peak)
