"""Peak thrust over the limit: a fixed-step spike is told from a real peak by refinement.

The shipped tf = 90 s gains fly Table II case 281 (seed 777001) with a 121 kN spike at
dt = 0.05 s, one step after the x axis arrives at s1 ~ 0 (the singular term b1 q1 |s1|^(q1-1) v
sampled at a node near s1 = 0); at smaller steps the peak is 8.7 kN.  ``refine_over_limit`` must
remove that spike and must keep a peak that is real (the reaching phase, which does not move
with dt)."""

from __future__ import annotations

import numpy as np
import pytest
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.campaign import table2_states
from lgw.theory.mars.gains import load_gains
from lgw.tuning.mars.compare import TUNED_DEFAULT
from lgw.tuning.mars.design import (
    REFINE_FACTORS,
    Request,
    _simulate,
    limit_measure,
    refine_over_limit,
)

SPIKE_SEED, SPIKE_CASE = 777001, 281


@pytest.fixture(scope="module")
def spike_case() -> tuple[np.ndarray, object]:
    r0, v0, m0 = table2_states(300, seed=SPIKE_SEED)
    k = SPIKE_CASE
    x = np.column_stack([r0[k:k + 1], v0[k:k + 1], m0[k:k + 1]])
    return x, load_gains(TUNED_DEFAULT)


def _fly(x: np.ndarray, g: object, req: Request, dt: float):
    return _simulate(x, g, req, req.tf * 1.05 + 1.0, seed=0, dt=dt)


def test_spike_is_removed_and_replaced_by_the_converged_peak(spike_case) -> None:
    x, g = spike_case
    req = Request(tf=90.0, thrust_max=50_000.0)
    coarse = _fly(x, g, req, 0.05)
    m_coarse = limit_measure(coarse.peak_thrust_unsat, coarse.nonfinite, "axis")[0]
    # the phenomenon itself (if a sim change removes it, this test has nothing to check)
    assert m_coarse > req.thrust_max and coarse.time_saturated[0] > 0
    res, info = refine_over_limit(x, coarse, g, req, req.tf * 1.05 + 1.0, seed=0)
    assert info["over_limit"] == 1 and info["artifacts"] == 1 and info["confirmed"] == 0
    assert res.info["replaced"] == [0] and res.dt == coarse.dt
    m_ref = limit_measure(res.peak_thrust_unsat, res.nonfinite, "axis")[0]
    assert m_ref < 0.5 * req.thrust_max and res.time_saturated[0] == 0
    # independent: a much finer step gives the same peak (the reaching-phase maximum)
    fine = _fly(x, g, req, 0.05 / 40)
    m_fine = limit_measure(fine.peak_thrust_unsat, fine.nonfinite, "axis")[0]
    assert m_ref == pytest.approx(m_fine, rel=0.02)
    assert res.landing_time[0] == pytest.approx(fine.landing_time[0], abs=0.01)


def test_real_peak_over_the_limit_is_kept(spike_case) -> None:
    """With a 10 kN limit the z axis's 16 kN reaching-phase peak is real at every dt."""
    x, g = spike_case
    req = Request(tf=90.0, thrust_max=10_000.0)
    coarse = _fly(x, g, req, 0.05)
    res, info = refine_over_limit(x, coarse, g, req, req.tf * 1.05 + 1.0, seed=0)
    assert info["over_limit"] == 1 and info["artifacts"] == 0 and info["confirmed"] == 1
    assert res.equal(coarse)
    fine = _fly(x, g, req, 0.05 / REFINE_FACTORS[-1])
    assert fine.time_saturated[0] > 0


def test_with_rows_replaces_only_the_given_cases(spike_case) -> None:
    x, g = spike_case
    xs = np.repeat(x, 3, axis=0)
    xs[1, 2] += 50.0
    a = simulate_batch(xs[:, :3], xs[:, 3:6], xs[:, 6], g, dt=0.05, t_max=95.0)
    b = simulate_batch(xs[1:2, :3], xs[1:2, 3:6], xs[1:2, 6], g, dt=0.01, t_max=95.0)
    c = a.with_rows(np.array([1]), b)
    assert c.landing_time[1] == b.landing_time[0]
    assert c.landing_time[0] == a.landing_time[0] and c.landing_time[2] == a.landing_time[2]
    np.testing.assert_array_equal(c.peak_thrust[1], b.peak_thrust[0])
    assert a.info.get("replaced") is None  # the original is untouched
    with pytest.raises(ValueError, match="2 indices for 1 cases"):
        a.with_rows(np.array([0, 1]), b)
