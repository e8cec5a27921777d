"""One notion of contact for every system (lgw.sim.results): the first crossing of the surface
ends the case at the crossing, located inside the step, as "landed" within the landing
tolerance and "crashed" otherwise, with the impact time, point and speed; a state that starts
below the surface is named as such (and refused by the command line)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from lgw.sim.integrate import _herm, _herm_first_under
from lgw.sim.results import (
    CONTACT,
    MEANINGS,
    OUTCOMES,
    contact_outcome,
    contact_record,
    names,
)

from tests.test_cli_conventions import assert_one_error, run_lgw

# the two states of the issue, from the Table I mass, default gains, no thrust limit: before,
# the first reached 116 m below the ground and was "landed" at 21.9 s, the second 233 m below
# and "propellant exhausted" at 14.3 s
ISSUE_R0 = np.array([[0.0, 0.0, 300.0], [100.0, 0.0, 500.0]])
ISSUE_V0 = np.array([[0.0, 0.0, -200.0], [300.0, 0.0, -300.0]])


def _mars():
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.reference import simulate_reference
    from lgw.theory.mars.gains import default_gains
    return simulate_batch, simulate_reference, default_gains()


def _names(res) -> list[str]:
    return [OUTCOMES[k] for k in res.outcomes()[0]]


def test_issue_states_crash_at_first_contact_cross_checked_with_solve_ivp() -> None:
    """RK4 (default step), dopri5 and the tight solve_ivp reference (a terminal event on the
    ground): each state crashes at its first crossing of r_z = 0, about 2 s in, with the same
    contact time and impact speed; the case ends there (never below the ground)."""
    sim, ref_sim, g = _mars()
    m0 = [1905.0, 1905.0]
    ref = ref_sim(ISSUE_R0, ISSUE_V0, m0, g)
    rk = sim(ISSUE_R0, ISSUE_V0, m0, g)
    dp = sim(ISSUE_R0, ISSUE_V0, m0, g, method="dopri5")
    for res, speed_rtol in ((ref, 0.0), (rk, 0.02), (dp, 0.005)):
        assert _names(res) == ["crashed", "crashed"], res.info["integrator"]
        code, t = res.outcomes()
        assert np.all((t > 1.5) & (t < 2.5)) and np.array_equal(t, res.contact_time)
        assert not res.landed.any() and not res.fuel_exhausted.any()
        # the case ends at the crossing: on the ground plane, never below it
        assert np.array_equal(res.t_end, res.contact_time)
        assert np.all(np.abs(res.y_end[:, 2]) < 1e-9) and np.all(res.min_altitude > -1e-9)
        assert np.all(np.abs(res.contact_point[:, 2]) < 1e-9)
        np.testing.assert_allclose(res.contact_time, ref.contact_time, atol=2e-4)
        np.testing.assert_allclose(res.impact_speed, ref.impact_speed, rtol=speed_rtol + 1e-12)
        np.testing.assert_allclose(res.contact_point[:, :2], ref.contact_point[:, :2],
                                   rtol=speed_rtol + 1e-9)
    # fast impacts: 87 and 205 m/s
    assert 80 < ref.impact_speed[0] < 95 and 195 < ref.impact_speed[1] < 215


def test_below_the_ground_at_start_is_named_in_every_integrator() -> None:
    sim, ref_sim, g = _mars()
    r0, v0 = np.array([[10.0, 0.0, -1.0]]), np.array([[0.0, 0.0, -5.0]])
    for res in (sim(r0, v0, [1905.0], g), sim(r0, v0, [1905.0], g, method="dopri5"),
                ref_sim(r0, v0, [1905.0], g)):
        assert _names(res) == ["below_surface"]
        assert res.outcomes()[1][0] == 0.0 and res.t_end[0] == 0.0 and res.fuel[0] == 0.0
        assert res.below_surface[0] and not res.contact[0]
    # observing the closed loop to t_max (the bound checks), it flies, and is still named
    obs = sim(r0, v0, [1905.0], g, stop="t_max", t_max=5.0)
    assert _names(obs) == ["below_surface"] and obs.t_end[0] == 5.0


def test_on_the_ground_descending_is_a_contact_at_once() -> None:
    sim, ref_sim, g = _mars()
    r0, v0 = np.array([[50.0, 0.0, 0.0]]), np.array([[0.0, 0.0, -5.0]])
    for res in (sim(r0, v0, [1905.0], g), ref_sim(r0, v0, [1905.0], g)):
        assert _names(res) == ["crashed"]
        assert res.contact_time[0] < 1e-9 and res.impact_speed[0] == pytest.approx(5.0)


def test_slow_contact_is_dated_at_its_crossing() -> None:
    """A vehicle that crosses the ground slower than the landing speed tolerance (a graze so
    far) and sinks deeper than the position tolerance: a contact, dated at the crossing, at
    the same time in RK4 and the reference."""
    sim, ref_sim, g = _mars()
    # 6.8 kN per axis cannot hold 1905 kg against Mars gravity (7.07 kN): the vehicle sinks,
    # crossing r_z = 0 at ~8 cm/s, and goes on sinking; x is far from its target
    r0, v0 = np.array([[400.0, 0.0, 0.02]]), np.array([[0.0, 0.0, -0.02]])
    kw = dict(thrust_limit=6800.0)
    rk = sim(r0, v0, [1905.0], g, dt=0.01, **kw)
    ref = ref_sim(r0, v0, [1905.0], g, **kw)
    assert _names(rk) == _names(ref) == ["crashed"]
    assert rk.contact_time[0] == pytest.approx(ref.contact_time[0], abs=0.02)
    assert rk.impact_speed[0] == pytest.approx(ref.impact_speed[0], rel=0.05, abs=0.01)


@settings(max_examples=300, deadline=None)
@given(p=st.lists(st.floats(-10, 10), min_size=4, max_size=4), h=st.floats(0.01, 2.0),
       level=st.floats(-5, 5), ab=st.tuples(st.floats(0, 1), st.floats(0, 1)))
def test_first_crossing_matches_dense_sampling(p, h, level, ab) -> None:
    """``_herm_first_under``: the first th in [a, b] where the interpolant is below the level,
    even when it dips below and comes back inside the step; 2.0 if there is none."""
    a, b = min(ab), max(ab)
    p0, d0, p1, d1 = p
    th = np.linspace(a, b, 20001)
    vals = np.array([_herm(p0, d0, p1, d1, h, x) for x in th])
    got = _herm_first_under(p0, d0, p1, d1, h, level, a, b)
    below = np.flatnonzero(vals < level - 1e-9)
    if got > 1.0:
        assert not below.size, (th[below[:1]], vals[below[:1]])
        return
    assert a <= got <= b and _herm(p0, d0, p1, d1, h, got) < level
    if below.size:  # nothing clearly below the level before it
        assert got <= th[below[0]] + 1e-12


def test_every_system_names_its_outcomes_from_the_shared_vocabulary() -> None:
    from lgw.sim.eros.batch import OUTCOMES as EROS
    from lgw.sim.lunar.outcomes import OUTCOMES as LUNAR
    from lgw.sim.mars.batch import OUTCOMES_USED as MARS
    for vocab in (MARS, LUNAR, EROS):
        assert set(vocab) <= set(OUTCOMES), set(vocab) - set(OUTCOMES)
    assert "crashed" in MARS and "crashed" in LUNAR and "below_surface" in LUNAR
    assert set(MEANINGS) == set(OUTCOMES) and set(CONTACT) <= set(OUTCOMES)
    with pytest.raises(ValueError, match="surface_contact"):
        names("landed", "surface_contact")


def test_contact_record_classifies_by_the_landing_tolerance() -> None:
    down = (0.0, 0.0, 1.0)  # outward normal of the ground plane
    soft = contact_record(3.0, (0.05, 0.0, 0.0), (0.0, 0.0, -0.08), down, (0.1, 0.1))
    assert soft.outcome == "landed" and soft.normal_speed == pytest.approx(0.08)
    hard = contact_record(3.0, (0.05, 0.0, 0.0), (0.0, 0.3, -0.08), down, (0.1, 0.1))
    assert hard.outcome == "crashed" and hard.speed == pytest.approx(np.hypot(0.3, 0.08))
    off = contact_record(3.0, (5.0, 0.0, 0.0), (0.0, 0.0, -0.01), down, (0.1, 0.1))
    assert off.outcome == "crashed"
    assert contact_outcome(0.0, 0.0, None) == "crashed"  # no landing criterion: a crash
    assert hard.to_dict()["impact_speed_mps"] == hard.speed


def test_simulate_mars_refuses_a_state_below_the_ground(tmp_path) -> None:
    f = tmp_path / "states.csv"
    f.write_text("rx,ry,rz,vx,vy,vz,m\n0,0,100,0,0,-10,1905\n0,0,-0.5,0,0,-10,1905\n")
    out = tmp_path / "out"
    r = run_lgw(["simulate", "mars", "--initial-states", str(f), "--out", str(out)])
    assert_one_error(r)
    assert "row 3" in r.stderr and "rz" in r.stderr and "below the ground" in r.stderr
    assert not out.exists()
