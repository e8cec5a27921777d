"""``lgw.sim.mars.arrival.after_arrival_peaks`` on a hand-made trajectory."""

from __future__ import annotations

import math

import numpy as np
import pytest
from lgw.sim.mars.arrival import after_arrival_peaks

NAN = math.nan


def _hand_made() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Two cases, six samples.  Case 0: x is in position at sample 1 but too fast (not in its
    band), enters at 2, spikes 700 N at 4 (after arrival; the 900 N before it does not count);
    y never arrives; z is in its band from sample 0 exactly on the edges (inclusive), -50 N
    there, NaN samples ignored.  Case 1 stopped after sample 2 (NaN), x arrives at 1."""
    r = np.full((2, 6, 3), NAN)
    v = np.full((2, 6, 3), NAN)
    F = np.full((2, 6, 3), NAN)  # noqa: N806
    r[0, :, 0] = [5, 0.05, 0.05, 0.0, -0.05, 0.02]
    v[0, :, 0] = [1, 0.5, 0.05, 0.0, 0.2, 0.0]
    F[0, :, 0] = [100, 900, 30, -40, -700, 10]
    r[0, :, 1] = 5.0
    v[0, :, 1] = 0.0
    F[0, :, 1] = 1e4
    r[0, :, 2] = [0.1, 0.1, 0.0, 0.0, 0.0, 0.0]
    v[0, :, 2] = [-0.1, 0.0, 0.0, 0.0, 0.0, 0.0]
    F[0, :, 2] = [-50, 20, NAN, NAN, 3, 3]
    r[1, :3, 0] = [3, 0.0, 0.01]
    v[1, :3, 0] = [2, 0.0, 0.0]
    F[1, :3, 0] = [9e3, 5, 6]
    r[1, :3, 1:] = 7.0
    v[1, :3, 1:] = 0.0
    F[1, :3, 1:] = 1.0
    return r, v, F


def test_after_arrival_by_hand() -> None:
    r, v, F = _hand_made()  # noqa: N806
    first, peak = after_arrival_peaks(r, v, F)
    assert first.tolist() == [[2, -1, 0], [1, -1, -1]]
    assert peak[0, 0] == 700.0 and math.isnan(peak[0, 1]) and peak[0, 2] == 50.0
    assert peak[1, 0] == 6.0 and np.isnan(peak[1, 1:]).all()
    # one case as (S, 3) gives the same as that case in a batch
    f0, p0 = after_arrival_peaks(r[0], v[0], F[0])
    assert f0.tolist() == [2, -1, 0] and p0[0] == 700.0 and p0[2] == 50.0
    # a wider band makes x arrive at sample 1 (|v| = 0.5), where the 900 N spike then counts
    _, wide = after_arrival_peaks(r, v, F, tol=(0.1, 0.5))
    assert wide[0, 0] == 900.0


def test_after_arrival_rejects_bad_shapes() -> None:
    with pytest.raises(ValueError, match="must all be"):
        after_arrival_peaks(np.zeros((2, 3)), np.zeros((2, 3)), np.zeros((3, 3)))
