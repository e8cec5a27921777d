"""The batched RK4 simulator: cross-checked against the tight solve_ivp reference and against
independent routes (mass loss vs the integral of |F|/c)."""

from __future__ import annotations

import numpy as np
import pytest
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.campaign import table2_states, table3_states
from lgw.sim.mars.disturbances import make_disturbance
from lgw.sim.mars.plant import exhaust_velocity
from lgw.sim.mars.reference import simulate_reference
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import M0, M_DRY, R0, V0

G = default_gains()
# Tolerances of the fast integrator (dt = 0.05 s) against the reference (LSODA 1e-10):
T_TOL = 1e-3  # s, landing time (the workbench target is 0.01 s)
R_TOL = 1e-3  # m, landing position (target 1 cm)
FUEL_TOL = 0.1  # kg; RK4 chatter on an axis already at s ~ 0 burns ~0.05 kg extra
# Velocity at landing: an axis that converged early sits in RK4's chatter around s = 0, whose
# level at dt = 0.05 s is ~1e-2 m/s on s2 (lgw.sim.mars.parameters); the reference sits at ~1e-10.
V_TOL = 1e-2  # m/s


def _agree(b, r, t_tol=T_TOL, r_tol=R_TOL, fuel_tol=FUEL_TOL, v_tol=V_TOL) -> None:
    np.testing.assert_array_equal(b.landed, r.landed)
    np.testing.assert_allclose(b.landing_time, r.landing_time, atol=t_tol)
    np.testing.assert_allclose(b.r_land, r.r_land, atol=r_tol)
    np.testing.assert_allclose(b.v_land, r.v_land, atol=v_tol)
    np.testing.assert_allclose(b.fuel, r.fuel, atol=fuel_tol)


def test_table1_matches_reference_and_documented_numbers() -> None:
    kw = dict(drag="none")
    b = simulate_batch(R0[None], V0[None], [M0], G, **kw)
    r = simulate_reference(R0[None], V0[None], [M0], G, **kw)
    _agree(b, r, t_tol=1e-5, r_tol=1e-6, fuel_tol=1e-4)
    # lgw.theory.mars.parameters.DEFAULT_GAINS: lands in 27.4 s, peak 32.4 kN (y), 235 kg
    assert b.landed[0] and b.landing_time[0] == pytest.approx(27.39, abs=0.01)
    assert b.peak_thrust[0, 1] == pytest.approx(32.4e3, rel=0.01)
    assert np.argmax(b.peak_thrust[0]) == 1
    assert b.fuel[0] == pytest.approx(235.0, abs=0.5)
    np.testing.assert_allclose(b.peak_thrust, r.peak_thrust, rtol=1e-3)
    np.testing.assert_allclose(b.t_s1, r.t_s1, atol=0.01, equal_nan=True)
    assert b.eps == 0.05 and b.dt == 0.05
    assert not b.ground_contact[0] and not b.nonfinite[0]


def test_random_cases_match_reference() -> None:
    r0, v0, m0 = table2_states(3, seed=11)
    _agree(simulate_batch(r0, v0, m0, G), simulate_reference(r0, v0, m0, G))
    r0, v0, m0 = table3_states(2, seed=0)  # includes a stiff case (s1x ~ 0 early)
    kw = dict(thrust_limit=50e3)
    _agree(simulate_batch(r0, v0, m0, G, **kw), simulate_reference(r0, v0, m0, G, **kw))


def test_disturbed_and_limited_cases_match_reference() -> None:
    r0, v0, m0 = table2_states(2, seed=5)
    for dist in ("sin", "random"):
        kw = dict(disturbance=dist, dist_amplitude=0.5, land_tol=(0.5, 0.5), seed=3)
        _agree(simulate_batch(r0, v0, m0, G, **kw), simulate_reference(r0, v0, m0, G, **kw),
               t_tol=0.01, r_tol=0.01, fuel_tol=0.2)
    kw = dict(thrust_limit=30e3, limit="norm")
    b = simulate_batch(r0, v0, m0, G, **kw)
    r = simulate_reference(r0, v0, m0, G, **kw)
    _agree(b, r, t_tol=0.01, r_tol=0.01, fuel_tol=0.1)
    assert np.all(b.time_saturated > 0)
    np.testing.assert_allclose(b.time_saturated, r.time_saturated, atol=0.06)
    assert np.all(np.linalg.norm(b.peak_thrust, axis=1) <= np.sqrt(3) * 30e3)
    assert np.all(b.peak_thrust <= 30e3 + 1e-6)


def test_mass_loss_equals_integral_of_thrust_over_c() -> None:
    b = simulate_batch(R0[None], V0[None], [M0], G, record=True, dt=0.01)
    tr = b.trajectory
    t, f = tr["t"], tr["F"][0]
    keep = t <= b.landing_time[0]
    fn = np.linalg.norm(f[keep], axis=1)
    burned = np.trapezoid(fn, t[keep]) / exhaust_velocity()
    m_last = tr["m"][0][keep][-1]
    assert M0 - m_last == pytest.approx(burned, rel=1e-5)
    assert b.fuel[0] == pytest.approx(M0 - m_last, abs=0.1)


def test_printed_law_does_not_land_in_80s() -> None:
    b = simulate_batch(R0[None], V0[None], [M0], G, law="printed", t_max=80.0, drag="none")
    assert not b.landed[0] and np.isnan(b.landing_time[0])


def test_nonfinite_is_flagged_not_dropped() -> None:
    """r_x = 0 exactly with v_x != 0: the corrected law commands -inf on x (batch and
    reference alike)."""
    r0 = np.array([[0.0, 1000.0, 1500.0], list(R0)])
    v0 = np.array([[10.0, -15.0, -75.0], list(V0)])
    for sim in (simulate_batch, simulate_reference):
        b = simulate_batch(r0, v0, [M0, M0], G) if sim is simulate_batch else sim(
            r0, v0, [M0, M0], G)
        assert b.nonfinite[0] and not b.landed[0] and not b.nonfinite[1] and b.landed[1]
        assert b.t_end[0] == 0.0
        lim = sim(r0, v0, [M0, M0], G, thrust_limit=50e3)
        assert not lim.nonfinite[0] and lim.landed[0]  # saturated instead
        assert lim.peak_thrust_unsat[0, 0] == np.inf and lim.peak_thrust[0, 0] == 50e3


@pytest.mark.parametrize("law", ["corrected", "super-twisting"])
def test_axis_at_its_equilibrium_is_not_singular(law: str) -> None:
    """r_x = v_x = 0 exactly (x already at the target): the singular term is 0 there (the
    law's limit along the solution), x stays at 0 and the case flies, batch and reference."""
    r0 = np.array([[0.0, 1000.0, 1500.0], [0.0, 0.0, 1500.0]])
    v0 = np.array([[0.0, -15.0, -75.0], [0.0, 0.0, -75.0]])
    kw = dict(law=law) if law == "corrected" else dict(law=law, t_max=5.0, stop="t_max")
    b = simulate_batch(r0, v0, [M0, M0], G, **kw)
    r = simulate_reference(r0, v0, [M0, M0], G, **kw)
    for res in (b, r):
        assert not res.nonfinite.any()
        np.testing.assert_array_equal(res.y_end[:, [0, 3]], 0.0)
    if law == "corrected":
        assert b.landed.all()
        _agree(b, r)
    else:
        np.testing.assert_allclose(b.y_end, r.y_end, rtol=1e-6, atol=1e-6)
        np.testing.assert_array_equal(b.y_end[1, [0, 1, 3, 4]], 0.0)


def test_dry_mass_stops_the_case() -> None:
    """m reaching m_dry stops the case (located inside the step), flagged fuel_exhausted and
    not landed; batch and reference agree."""
    b = simulate_batch(R0[None], V0[None], [M0], G)
    assert b.landed[0] and not b.fuel_exhausted[0] and b.info["m_dry"] == M_DRY
    # a 5 kg budget on Table I: dry after ~0.28 s
    kw = dict(m_dry=M0 - 5.0)
    b = simulate_batch(R0[None], V0[None], [M0], G, **kw)
    r = simulate_reference(R0[None], V0[None], [M0], G, **kw)
    for res in (b, r):
        assert res.fuel_exhausted[0] and not res.landed[0] and not res.nonfinite[0]
        assert np.isnan(res.landing_time[0]) and np.all(np.isnan(res.r_land[0]))
        assert res.fuel[0] == pytest.approx(5.0, abs=1e-9)
        assert res.y_end[0, 6] == pytest.approx(M0 - 5.0, abs=1e-9)
    assert b.t_end[0] == pytest.approx(r.t_end[0], abs=1e-6) and 0 < b.t_end[0] < b.dt * 10
    np.testing.assert_allclose(b.y_end, r.y_end, atol=1e-5)
    # running dry 0.05 s before touchdown (231.44 kg at landing): not landed, stops there
    kw = dict(m_dry=M0 - 231.3)
    b = simulate_batch(R0[None], V0[None], [M0], G, **kw)
    r = simulate_reference(R0[None], V0[None], [M0], G, **kw)
    for res in (b, r):
        assert res.fuel_exhausted[0] and not res.landed[0]
        assert res.fuel[0] == pytest.approx(231.3, abs=1e-9)
    assert b.t_end[0] == pytest.approx(r.t_end[0], abs=1e-5)
    assert b.t_end[0] < 27.39 and not b.t_end[0] % b.dt == 0.0  # inside a step
    # stop="t_max" observes the closed loop past m_dry (as past landing); the flags still say
    # which came first: dry at 0.28 s, so not landed although the state reaches the target
    kw = dict(m_dry=M0 - 5.0, stop="t_max", t_max=40.0)
    b = simulate_batch(R0[None], V0[None], [M0], G, **kw)
    r = simulate_reference(R0[None], V0[None], [M0], G, **kw)
    for res in (b, r):
        assert res.fuel_exhausted[0] and not res.landed[0] and res.t_end[0] == 40.0
        assert res.fuel[0] == pytest.approx(5.0, abs=1e-9)
        assert np.linalg.norm(res.y_end[0, :3]) < 0.1 and res.y_end[0, 6] < M0 - 200
        assert res.min_altitude[0] > 1400  # metrics up to the dry point
    # hovering after landing runs dry at ~90 s: landed and exhausted
    b = simulate_batch(R0[None], V0[None], [M0], G, stop="t_max", t_max=100.0)
    assert b.landed[0] and b.fuel_exhausted[0] and b.y_end[0, 6] < M_DRY
    assert b.fuel[0] == pytest.approx(231.4, abs=0.1)  # fuel at landing, as before


def test_chunking_and_threads_do_not_change_results() -> None:
    r0, v0, m0 = table2_states(7, seed=3)
    kw = dict(disturbance="random", seed=9)
    a = simulate_batch(r0, v0, m0, G, **kw)
    b = simulate_batch(r0, v0, m0, G, chunk=3, **kw)
    assert a.equal(b)
    # case 5 alone, placed at its campaign index, sees the same disturbance
    c = simulate_batch(r0[5:6], v0[5:6], m0[5:6], G, case_offset=5, **kw)
    np.testing.assert_array_equal(c.y_end[0], a.y_end[5])
    np.testing.assert_array_equal(c.t_s2[0], a.t_s2[5])
    d = simulate_batch(r0, v0, m0, G, parallel=False, **kw)
    assert a.equal(d)


def test_random_disturbance_is_bounded_and_seeded() -> None:
    d = make_disturbance("random", 20, amplitude=3.0, seed=1)
    np.testing.assert_allclose(d.coef.sum(axis=2), 3.0)
    t = np.linspace(0, 100, 2001)
    for j in range(20):
        a = np.array([d.accel(tt, None, j) for tt in t])
        assert np.abs(a).max() <= 3.0 + 1e-12
    d2 = make_disturbance("random", 5, amplitude=3.0, seed=1, case_offset=15)
    np.testing.assert_array_equal(d2.omega, d.omega[15:])


def test_worst_case_disturbance_neighborhood_is_invariant() -> None:
    """a_p = -a_max sgn(s2) (Theorem 3 of seed 000): once |s2_i| is inside (39)'s neighborhood
    it stays there (up to the RK4 chatter floor, ~1e-2 m/s at dt = 0.05 s)."""
    from lgw.theory.mars.bounds import axis_bounds
    from lgw.theory.mars.gains import Disturbance
    from lgw.theory.mars.mss import surfaces_numeric

    amax = 0.2
    g = G.with_disturbance(Disturbance(amax, 0.2, 0.1))
    bound = axis_bounds(g)["x"]["s2_bound"]
    b = simulate_batch(R0[None], V0[None], [M0], g, disturbance="worst", dist_amplitude=amax,
                       stop="t_max", t_max=60.0, record=True, drag="none")
    assert not b.nonfinite[0]
    tr = b.trajectory
    s2 = surfaces_numeric()[1](tr["r"][0], tr["v"][0], g.beta1, g.beta2, g.q1, g.q2)
    for ax in range(3):
        inside = np.flatnonzero(np.abs(s2[:, ax]) <= bound)
        assert inside.size, "s2 never reached the neighborhood"
        assert np.abs(s2[inside[0]:, ax]).max() <= bound + 0.02


@pytest.mark.parametrize("kw,name", [
    (dict(dt=0.0), "dt"), (dict(dt=-1.0), "dt"), (dict(law="pd"), "law"),
    (dict(disturbance="gust"), "disturbance"), (dict(thrust_limit=-5.0), "thrust_limit"),
    (dict(limit="box"), "limit"), (dict(eps=0.0), "eps"), (dict(drag="x"), "drag"),
    (dict(isp=0.0), "isp"), (dict(land_tol=(0.1, -1)), "land_tol"), (dict(t_max=0.0), "t_max"),
    (dict(dist_amplitude=-1.0, disturbance="sin"), "dist_amplitude"),
    (dict(m_dry=0.0), "m_dry"), (dict(m_dry=-5.0), "m_dry"), (dict(m_dry=float("nan")), "m_dry"),
    (dict(m_dry=M0), "m_dry"), (dict(m_dry=M0 + 1.0), "m_dry"), (dict(m_dry="x"), "m_dry"),
])
def test_bad_options_raise_parameter_error(kw, name) -> None:
    with pytest.raises(ParameterError) as e:
        simulate_batch(R0[None], V0[None], [M0], G, **kw)
    assert e.value.name.startswith(name)


def test_bad_states() -> None:
    with pytest.raises(ParameterError):
        simulate_batch(np.zeros((2, 2)), np.zeros((2, 3)), [1.0, 1.0], G)
    with pytest.raises(ParameterError):
        simulate_batch(R0[None], V0[None], [-1.0], G)
    with pytest.raises(ParameterError):
        simulate_batch(np.array([[np.nan, 0, 0]]), V0[None], [M0], G)


def test_option_objects_give_the_keyword_results() -> None:
    """``simulate`` with option objects is what ``simulate_batch``'s keywords build."""
    from dataclasses import replace

    from lgw.sim.mars.batch import INTEGRATION, simulate, stopping_defaults
    from lgw.sim.options import LimitOptions

    r0, v0, m0 = table3_states(6, seed=4)
    kw = dict(method="dopri5", thrust_limit=50_000.0, limit="norm", stop="t_max", t_max=60.0,
              land_tol=(0.2, 0.3))
    a = simulate_batch(r0, v0, m0, G, **kw)
    b = simulate(r0, v0, m0, G, integration=replace(INTEGRATION, method="dopri5"),
                 stopping=stopping_defaults(stop="t_max", t_max=60.0, land_tol=(0.2, 0.3)),
                 limits=LimitOptions(thrust_limit=50_000.0, kind="norm"))
    assert a.equal(b)
    assert b.info["integrator"].startswith("Dormand-Prince") and b.info["limit"] == "norm"
    with pytest.raises(ParameterError, match="m_dry"):
        simulate(r0, v0, m0, G, stopping=stopping_defaults(m_dry=float(m0.min())))


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_axis_at_rest_on_its_target_stays_there(axis: int) -> None:
    """The reproduction: one axis exactly at r = v = 0 (on z the command is -g, and
    (m a)/m + g is an ulp off 0, which drifted v_z into the singular |s1|^(q1-1) v): RK4,
    dopri5 and the reference all land, and that axis stays exactly at rest."""
    r0 = np.array([-200.0, 1400.0, 900.0])
    v0 = np.array([-15.0, -100.0, -40.0])
    r0[axis] = v0[axis] = 0.0
    runs = [simulate_batch(r0[None], v0[None], [M0], G),
            simulate_batch(r0[None], v0[None], [M0], G, method="dopri5"),
            simulate_reference(r0[None], v0[None], [M0], G)]
    for res in runs:
        assert res.landed[0] and not res.nonfinite[0] and not res.fuel_exhausted[0]
        assert res.r_land[0, axis] == 0.0 and res.v_land[0, axis] == 0.0
        assert res.y_end[0, axis] == 0.0 and res.y_end[0, 3 + axis] == 0.0
    np.testing.assert_allclose(runs[0].landing_time, runs[2].landing_time, atol=T_TOL)
    np.testing.assert_allclose(runs[1].landing_time, runs[2].landing_time, atol=10 * T_TOL)


@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_fuel_never_exceeds_the_load(method: str) -> None:
    """Running dry ends with exactly m_dry and fuel m0 - m_dry, also when a blown-up stage
    command makes the step's interpolant wild (r_x = 1e-100, v_x = 0 reported
    5.2e24 kg of fuel and a negative mass)."""
    r0 = np.array([R0, [1e-100, R0[1], R0[2]]])
    v0 = np.array([V0, [0.0, V0[1], V0[2]]])
    m0 = np.array([M_DRY + 3.0, M0])
    b = simulate_batch(r0, v0, m0, G, method=method)
    assert b.fuel_exhausted[0] and b.fuel[0] == 3.0 and b.y_end[0, 6] == M_DRY
    assert b.fuel_exhausted[1] or b.nonfinite[1] or b.landed[1] or b.blown_up[1]
    assert np.all(b.fuel <= m0 - M_DRY) and np.all(b.y_end[:, 6] >= M_DRY)
