"""python-control interop of every system: the plant and the law as separate ``control.nlsys``
blocks with the gains as params, interconnected by signal name, against the workbench's own
simulator on the same case.

* mars: ``input_output_response`` (DOP853, rtol = atol = 1e-10) over 5 s against
  ``simulate_batch`` (the compiled RK4, dt = 0.01 s): within 1e-6 m, 1e-6 m/s, 1e-5 kg
  (measured: ~1e-9 m, ~2e-10 m/s, 5e-8 kg);
* lunar: over 0.5 s against ``rk4_batch`` (the compiled RK4, dt = 0.01 s): within 1e-6 m,
  1e-6 m/s and 1e-6 on every other state (measured: 5e-10 m, 8e-12 m/s, 6e-8; at 3 s:
  3e-5 m, 6e-5 m/s, the RK4 step's error);
* eros: the sampled-data loop (discrete blocks, dt = 0.01 s, the paper's sampling) over 2 s
  against ``simulate`` (the compiled kernel, same zero-order hold and RK4 substeps): within
  1e-9 m (measured: 0).

Each also shows the params are the gains: a changed gain in ``params`` changes the response
exactly as a block built from the changed gain set does.
"""

from __future__ import annotations

from dataclasses import replace

import control
import numpy as np
import pytest


def test_mars_plant_and_law_interconnected_match_the_simulator():
    from lgw.sim.mars import interop as I
    from lgw.sim.mars.batch import simulate_batch
    from lgw.theory.mars.gains import default_gains
    from lgw.theory.mars.parameters import M0, R0, V0

    g = default_gains()
    P, C = I.plant(), I.law(g)
    assert P.nstates == 7 and C.nstates == 0 and set(C.params) >= {"beta1_x", "q1", "g2"}
    loop = I.closed_loop(g)
    T = np.linspace(0.0, 5.0, 51)
    kw = dict(solve_ivp_method="DOP853", solve_ivp_kwargs={"rtol": 1e-10, "atol": 1e-10})
    resp = control.input_output_response(loop, T, U=0, X0=I.initial_state(), **kw)
    b = simulate_batch(R0[None], V0[None], [M0], g, t_max=5.0, stop="t_max", dt=0.01)
    diff = np.abs(resp.states[:, -1] - b.y_end[0])
    print(f"\nmars, 5 s: |dr| {diff[:3].max():.2e} m, |dv| {diff[3:6].max():.2e} m/s, "
          f"|dm| {diff[6]:.2e} kg")
    assert diff[:3].max() < 1e-6 and diff[3:6].max() < 1e-6 and diff[6] < 1e-5
    # a gain through params = a law built from that gain set
    p = {"q1": 0.62, "beta1_y": 3.0}
    moved = control.input_output_response(loop, T, U=0, X0=I.initial_state(), params=p, **kw)
    d = g.to_dict()
    d["gains"]["q1"], d["gains"]["beta1"][1] = 0.62, 3.0
    from lgw.theory.mars.gains import gains_from_dict

    rebuilt = control.input_output_response(I.closed_loop(gains_from_dict(d)), T, U=0,
                                            X0=I.initial_state(), **kw)
    assert np.abs(moved.states[:, -1] - resp.states[:, -1]).max() > 1.0
    np.testing.assert_allclose(moved.states, rebuilt.states, rtol=0, atol=1e-9)


def test_lunar_plant_and_law_interconnected_match_the_simulator():
    from lgw.sim.lunar import interop as I
    from lgw.sim.lunar.batch import rk4_batch
    from lgw.sim.lunar.closed_loop import RunOptions, make_context
    from lgw.sim.lunar.reference import reference
    from lgw.theory.lunar.gains import paper_gains

    g, ref = paper_gains(), reference()
    opts = RunOptions(t_end=0.5, dt=0.01)
    P, C = I.plant(), I.law(g, opts, ref=ref)
    assert P.nstates == 14 and C.nstates == 16 and "orbit_K1_22" in C.params
    loop = I.closed_loop(g, opts, ref=ref)
    x0 = I.initial_state(g, ref)
    kw = dict(solve_ivp_method="DOP853", solve_ivp_kwargs={"rtol": 1e-9, "atol": 1e-9})
    resp = control.input_output_response(loop, np.linspace(0.0, 0.5, 6), X0=x0, **kw)
    b = rk4_batch(make_context(ref, [g], opts), I.from_blocks(x0)[:, None], record_every=1)
    assert b.t[-1] == pytest.approx(0.5)
    xe, xi = b.X[-1][:, 0], I.from_blocks(resp.states[:, -1])
    dr, dv, rest = (np.abs(xe - xi)[[0]], np.abs(xe - xi)[3:6],
                    np.abs(xe - xi)[np.r_[1, 2, 6:30]])
    print(f"\nlunar, 0.5 s: |dr| {dr.max():.2e} m, |dv| {dv.max():.2e} m/s, others "
          f"{rest.max():.2e}")
    assert dr.max() < 1e-6 and dv.max() < 1e-6 and rest.max() < 1e-6
    moved = control.input_output_response(loop, np.linspace(0.0, 0.5, 6), X0=x0,
                                          params={"orbit_q": 0.5, "attitude_F2_00": 8.0},
                                          **kw)
    assert np.abs(I.from_blocks(moved.states[:, -1]) - xi).max() > 1e-6


def test_eros_sampled_plant_and_law_reproduce_the_simulator():
    from lgw.sim.eros import interop as I
    from lgw.sim.eros.batch import SimOptions, simulate
    from lgw.theory.eros import parameters as P
    from lgw.theory.eros.gains import default_gains

    g = default_gains()
    opts = SimOptions(law="fuzzy", switch="sign", t_final=2.0)
    P_, C = I.plant(opts, dt=opts.dt), I.law(g, opts, dt=opts.dt)
    assert P_.dt == C.dt == opts.dt and set(C.params) == set(I.GAIN_KEYS)
    loop = I.closed_loop(g, opts)
    T = np.arange(201) * opts.dt
    resp = control.input_output_response(loop, T, X0=I.initial_state(opts=opts))
    res = simulate(P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], g, opts)
    diff = np.abs(resp.states[:, -1] - np.concatenate([res.pos[0], res.vel[0]]))
    print(f"\neros, 2 s sampled at 0.01 s: |dx| {diff[:3].max():.2e} m, |dv| "
          f"{diff[3:].max():.2e} m/s")
    assert diff.max() < 1e-9
    moved = control.input_output_response(loop, T, X0=I.initial_state(opts=opts),
                                          params={"k": 2.5})
    res2 = simulate(P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], g.replace(k=2.5), opts)
    np.testing.assert_allclose(moved.states[:, -1], np.concatenate([res2.pos[0],
                                                                    res2.vel[0]]), atol=1e-9)
    assert np.abs(moved.states[:, -1] - resp.states[:, -1]).max() > 1e-6
    # the continuous-time blocks: the same loop without the hold differs by O(dt)
    cont = control.input_output_response(I.closed_loop(g, replace(opts, switch="tanh"),
                                                       sampled=False),
                                         np.linspace(0.0, 2.0, 21),
                                         X0=I.initial_state(opts=opts),
                                         solve_ivp_method="LSODA")
    assert np.all(np.isfinite(cont.states))


def test_every_system_names_its_interop_module():
    """Each registered System's interop module defines plant() and law(gains)."""
    import importlib

    from lgw.tuning.system import all_systems

    for s in all_systems():
        mod = importlib.import_module(s.interop)
        assert callable(mod.plant) and callable(mod.law) and callable(mod.closed_loop), s.name
