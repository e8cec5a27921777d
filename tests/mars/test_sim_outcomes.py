"""Every case ends in exactly one outcome (lgw.sim.results), the same in RK4, dopri5 and the
reference mode for the same state; the reproductions of the input defects, one test per
defect class."""

from __future__ import annotations

import numpy as np
from lgw.sim.mars.batch import BLOWUP_ACCEL, OUTCOMES_USED, simulate_batch
from lgw.sim.mars.disturbances import make_disturbance
from lgw.sim.mars.reference import ClosedLoopRHS, simulate_reference
from lgw.sim.results import OUTCOMES, classify, counts
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import M0, M_DRY, R0, V0

G = default_gains()


def _names(res) -> list[str]:
    code, t = res.outcomes()
    assert len(code) == len(res) and np.all(np.isfinite(t) | (code == 1))
    return [OUTCOMES[k] for k in code]


def _physical(res, m_dry: float = M_DRY) -> None:
    """No impossible quantity: fuel within the load, mass at or above dry mass, peaks a thrust,
    the end state finite unless flagged."""
    load = res.m0 - m_dry
    assert np.all((res.fuel >= -1e-9) & (res.fuel <= load)), res.fuel
    assert np.all(res.y_end[:, 6] >= m_dry), res.y_end[:, 6]
    blow = BLOWUP_ACCEL * res.m0[:, None]
    assert np.all(res.peak_thrust <= blow) and np.all(res.peak_thrust_unsat <= blow)
    assert np.all(np.isfinite(res.y_end).all(axis=1) | res.nonfinite)


def test_same_outcome_in_every_integrator() -> None:
    r0 = np.array([R0, R0, [0.0, 1000.0, 1500.0]])
    v0 = np.array([V0, V0, [10.0, -15.0, -75.0]])
    m0 = np.array([M0, M_DRY + 60.0, M0])  # lands; runs dry first; r_x = 0 with v_x != 0
    want = ["landed", "propellant_exhausted", "command_blown_up"]
    runs = [simulate_batch(r0, v0, m0, G), simulate_batch(r0, v0, m0, G, method="dopri5"),
            simulate_reference(r0, v0, m0, G)]
    for res in runs:
        assert _names(res) == want, res.info["integrator"]
        _physical(res)
        # -inf on x at t = 0: blown up at once, and flagged as a non-finite value too
        assert res.nonfinite[2] and res.t_end[2] == 0.0 and res.fuel[2] == 0.0
    # a horizon too short to land: "horizon" at t_max in all three
    for res in (simulate_batch(r0[:1], v0[:1], m0[:1], G, t_max=10.0),
                simulate_batch(r0[:1], v0[:1], m0[:1], G, t_max=10.0, method="dopri5"),
                simulate_reference(r0[:1], v0[:1], m0[:1], G, t_max=10.0)):
        code, t = res.outcomes()
        assert OUTCOMES[code[0]] == "horizon" and t[0] == 10.0
    lim = simulate_batch(r0[:1], v0[:1], m0[:1], G, method="dopri5", max_steps=5)
    assert _names(lim) == ["step_limit"]


def test_tiny_position_blows_the_command_up_not_the_fuel() -> None:
    """r_x = 1e-100, v_x = 0 reported "fuel exhausted" after one step with 5.2e24 kg
    of fuel.  The command at t = 0 is finite (v_x = 0), a stage of the first step asks for
    |s1|^(q1-1) v ~ 1e38 N: blown up at the start, nothing impossible reported."""
    r0 = np.array([[1e-100, R0[1], R0[2]]])
    v0 = np.array([[0.0, V0[1], V0[2]]])
    for res in (simulate_batch(r0, v0, [M0], G),
                simulate_batch(r0, v0, [M0], G, method="dopri5"),
                simulate_reference(r0, v0, [M0], G)):
        assert _names(res) == ["command_blown_up"], res.info["integrator"]
        assert not res.fuel_exhausted[0] and not res.landed[0]
        _physical(res)
        code, t = res.outcomes()
        assert 0.0 <= t[0] < 1e-6 and res.fuel[0] < 1e-6


def test_huge_step_is_blown_up() -> None:
    """``--dt 100`` on Table I reported 1.7e10 kg of fuel.  The stages of a 100 s
    step ask for commands no thrust can give (or at a mass <= 0): blown up at t = 0."""
    res = simulate_batch(R0[None], V0[None], [M0], G, dt=100.0)
    assert _names(res) == ["command_blown_up"]
    _physical(res)
    assert res.t_end[0] == 0.0 and res.fuel[0] == 0.0 and res.y_end[0, 6] == M0


def test_z_axis_on_its_target_lands_in_every_mode() -> None:
    """The z0.csv: r_z = v_z = 0 went non-finite at 0.25 s (dopri5 0.55 s)."""
    r0 = np.array([[-200.0, 1400.0, 0.0]])
    v0 = np.array([[-15.0, -100.0, 0.0]])
    for res in (simulate_batch(r0, v0, [1905.0], G),
                simulate_batch(r0, v0, [1905.0], G, method="dopri5"),
                simulate_reference(r0, v0, [1905.0], G)):
        assert _names(res) == ["landed"] and not res.nonfinite[0]
        assert res.r_land[0, 2] == 0.0 and res.v_land[0, 2] == 0.0
        _physical(res)


def test_all_zero_state_lands_at_once_in_every_mode() -> None:
    """``--reference`` reported the all-zero state both landed and non-finite."""
    z = np.zeros((1, 3))
    for res in (simulate_batch(z, z, [M0], G), simulate_batch(z, z, [M0], G, method="dopri5"),
                simulate_reference(z, z, [M0], G)):
        assert _names(res) == ["landed"] and not res.nonfinite[0]
        assert res.landing_time[0] == 0.0 and res.fuel[0] == 0.0 and res.t_end[0] == 0.0
        _physical(res)


def test_peaks_are_the_node_maxima_not_the_stages() -> None:
    """The peak is the max of |F| over the step nodes up to landing (the states on the
    trajectory), recomputed independently from the recorded nodes with the numpy law and plant
    (lgw.sim.mars.reference.ClosedLoopRHS); the RK4 stages of this run go higher, so the test
    tells the two definitions apart."""
    dt = 0.05
    res = simulate_batch(R0[None], V0[None], [M0], G, record=True, dt=dt)
    assert res.landed[0]
    n = int(np.ceil(res.landing_time[0] / dt))  # the step that contains the landing
    y = np.concatenate([res.trajectory["r"][0], res.trajectory["v"][0],
                        res.trajectory["m"][0][:, None]], axis=1)[: n + 1]
    rhs = ClosedLoopRHS(G, dist=make_disturbance("none", 1))
    stages = [y]
    k1 = np.array([rhs(0.0, yy) for yy in y[:-1]])
    y2 = y[:-1] + 0.5 * dt * k1
    k2 = np.array([rhs(0.0, yy) for yy in y2])
    y3 = y[:-1] + 0.5 * dt * k2
    k3 = np.array([rhs(0.0, yy) for yy in y3])
    stages += [y2, y3, y[:-1] + dt * k3]
    peak = np.max(np.abs(np.concatenate([rhs.force(s)[0] for s in stages])), axis=0)
    node = np.max(np.abs(rhs.force(y)[0]), axis=0)
    # nodes up to the step before the landing step (the landing step's left node included)
    node = np.max(np.abs(rhs.force(y[:-1])[0]), axis=0)
    np.testing.assert_allclose(res.peak_thrust[0], node, rtol=1e-9)
    assert np.any(peak > node * (1 + 1e-6))  # the stages differ here: the test can fail


def test_times_and_precedence() -> None:
    res = simulate_batch(np.array([R0, R0]), np.array([V0, V0]), np.array([M0, M_DRY + 60.0]),
                         G)
    code, t = res.outcomes()
    assert t[0] == res.landing_time[0] and t[1] == res.t_end[1] < res.info["t_max"]
    # a case that landed and later ran dry (stop="t_max") counts as landed, once
    code, t = classify(landed=[True, False], fuel_exhausted=[True, True],
                       nonfinite=[True, True], step_limit=[False, True],
                       landing_time=[3.0, np.nan], t_end=[9.0, 9.0], stop_at_outcome=False)
    assert code.tolist() == [0, 1] and t[0] == 3.0 and np.isnan(t[1])
    assert counts(code, OUTCOMES_USED) == {
        "landed": 1, "crashed": 0, "below_surface": 0, "propellant_exhausted": 1,
        "command_blown_up": 0, "nonfinite": 0, "step_limit": 0, "horizon": 0}
    # a contact that is not a landing crashed at its contact time; below the surface at t = 0
    # comes first
    code, t = classify(landed=[False, True, False], fuel_exhausted=[True, False, False],
                       nonfinite=[False] * 3, step_limit=[False] * 3,
                       contact=[True, True, False], contact_time=[2.5, 1.0, np.nan],
                       below_surface=[False, False, True], landing_time=[np.nan, 1.0, np.nan],
                       t_end=[2.6, 1.0, 5.0], stop_at_outcome=False)
    assert [OUTCOMES[k] for k in code] == ["crashed", "landed", "below_surface"]
    assert t.tolist() == [2.5, 1.0, 0.0]
    # blown up before non-finite, step limit and horizon; after landing and running dry
    code, t = classify(landed=[False, False, True], fuel_exhausted=[False, True, False],
                       nonfinite=[True, False, False], step_limit=[True, False, False],
                       blown_up=[True, True, True], landing_time=[np.nan, np.nan, 1.0],
                       t_end=[2.0, 3.0, 4.0], stop_at_outcome=True)
    assert [OUTCOMES[k] for k in code] == ["command_blown_up", "propellant_exhausted",
                                           "landed"]
    assert t.tolist() == [2.0, 3.0, 1.0]
