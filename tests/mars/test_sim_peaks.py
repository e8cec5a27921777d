"""Node peaks, stage peaks and the peak after arrival (lgw.sim.mars.batch).

Each is checked against an independent route: the stage peaks against the RK4 trial states
re-computed in numpy from the recorded nodes with the reference mode's closed loop
(``ClosedLoopRHS``, the numpy law), the peak after arrival against
``benchmarks/bench_tune.py``'s ``after_arrival_peaks`` on the recorded trajectory.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.campaign import table3_states
from lgw.sim.mars.disturbances import make_disturbance
from lgw.sim.mars.reference import ClosedLoopRHS, after_arrival, simulate_reference
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import LAND_POS_TOL, LAND_VEL_TOL, M0, R0, V0

G = default_gains()
ROOT = Path(__file__).resolve().parents[2]
DT = 0.05


def _bench_tune():
    spec = importlib.util.spec_from_file_location("bench_tune",
                                                  ROOT / "benchmarks" / "bench_tune.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def recorded():
    """Ten Table III states flown to t_max with RK4, trajectories recorded."""
    r0, v0, m0 = table3_states(10, seed=11)
    res = simulate_batch(r0, v0, m0, G, dt=DT, t_max=80.0, stop="t_max", record=True)
    return r0, v0, m0, res


def test_stage_peaks_bound_the_node_peaks_and_differ_somewhere(recorded) -> None:
    *_, res = recorded
    for node, stage in ((res.peak_thrust, res.peak_thrust_stages),
                        (res.peak_thrust_unsat, res.peak_thrust_unsat_stages)):
        assert np.all(np.isfinite(stage)) and np.all(stage >= node)
    # the corrected law without a limit: trial states near s1 = 0 ask for more than any node
    assert np.any(res.peak_thrust_unsat_stages > res.peak_thrust_unsat)


def test_stage_peaks_equal_the_numpy_rk4_trial_states(recorded) -> None:
    """Independent route: from each recorded node y (the kernel's own), RK4's trial states
    y + h/2 k1, y + h/2 k2, y + h k3 and the new node, with k from the numpy closed loop; the
    max |F_i| over them and the nodes is the kernel's stage peak, over the steps up to the
    one in which the case lands (the metrics stop at the outcome, stop="t_max" or not)."""
    r0, v0, m0, res = recorded
    dist = make_disturbance("none", len(res))
    tr = res.trajectory
    for i in range(3):
        rhs = ClosedLoopRHS(G, dist=dist, case=i, m0=float(m0[i]))
        ys = np.concatenate([tr["r"][i], tr["v"][i], tr["m"][i][:, None]], axis=1)
        n_nodes = int(np.sum(np.isfinite(ys[:, 0])))
        t_l = res.landing_time[i]
        # steps whose left node is at or before the landing (the metrics stop there)
        last = n_nodes - 1 if not np.isfinite(t_l) else min(int(np.floor(t_l / DT)) + 1,
                                                              n_nodes - 1)
        peak = np.zeros(3)
        for k in range(last):
            y = ys[k]
            k1 = rhs(k * DT, y)
            y2 = y + 0.5 * DT * k1
            k2 = rhs(k * DT + 0.5 * DT, y2)
            y3 = y + 0.5 * DT * k2
            k3 = rhs(k * DT + 0.5 * DT, y3)
            y4 = y + DT * k3
            for yy in (y, y2, y3, y4, ys[k + 1]):
                peak = np.maximum(peak, np.abs(rhs.force(yy)[1]))
        np.testing.assert_allclose(res.peak_thrust_unsat_stages[i], peak, rtol=1e-7)


def test_peak_after_arrival_equals_the_trajectory_route(recorded) -> None:
    *_, res = recorded
    tr = res.trajectory
    first, want = _bench_tune().after_arrival_peaks(tr["r"], tr["v"], tr["F"],
                                                    tol=(LAND_POS_TOL, LAND_VEL_TOL))
    assert np.all(first >= 0)  # every axis of these cases arrives
    np.testing.assert_array_equal(res.peak_thrust_after_arrival, want)
    # the reference's own helper, the same samples
    for i in range(len(res)):
        n = int(np.sum(np.isfinite(tr["r"][i, :, 0])))
        got = after_arrival(tr["r"][i, :n], tr["v"][i, :n], tr["F"][i, :n],
                            (LAND_POS_TOL, LAND_VEL_TOL))
        np.testing.assert_array_equal(got, want[i])


def test_peak_after_arrival_is_null_before_arrival_and_agrees_with_the_reference() -> None:
    """Table I to 20 s: no axis is in its band yet (NaN); to landing: every axis arrived and
    the batch and the reference (LSODA on a 1 ms grid) agree to a few percent."""
    short = simulate_batch(R0[None], V0[None], [M0], G, t_max=20.0)
    assert np.all(np.isnan(short.peak_thrust_after_arrival))
    a = simulate_batch(R0[None], V0[None], [M0], G, dt=0.01)
    b = simulate_reference(R0[None], V0[None], [M0], G)
    assert a.landed[0] and b.landed[0]
    assert np.all(np.isfinite(a.peak_thrust_after_arrival))
    np.testing.assert_allclose(a.peak_thrust_after_arrival, b.peak_thrust_after_arrival,
                               rtol=0.05)


def test_a_blown_up_command_is_never_a_peak_after_arrival() -> None:
    """Found by the million-state campaign: a state landed at t = 0 (|r|, |v| <= 0.1) with
    r_x = 9e-71 m, v_x = 2.6e-3 m/s asks for |s1|^(q1-1) v far beyond BLOWUP_ACCEL m0 there;
    the case ends at once, that command is never flown, and the peak after arrival is null,
    not that number (in every mode)."""
    r0 = np.array([[9.092454759081029e-71, 0.0, 0.0]])
    v0 = np.array([[0.002586392496802433, 0.0001090525739392657, 0.0]])
    m0 = [1505.037574524383]
    for res in (simulate_batch(r0, v0, m0, G), simulate_batch(r0, v0, m0, G, method="dopri5"),
                simulate_reference(r0, v0, m0, G)):
        assert res.landed[0] and res.landing_time[0] == 0.0
        assert np.isnan(res.peak_thrust_after_arrival[0, 0])
        assert np.all(res.peak_thrust_stages == 0.0)
