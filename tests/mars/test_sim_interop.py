"""The closed loop as a python-control nlsys reproduces the simulators."""

from __future__ import annotations

import control
import numpy as np
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.interop import closed_loop_nlsys, initial_state
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import M0, R0, V0


def test_nlsys_matches_batch_at_landing() -> None:
    g = default_gains()
    b = simulate_batch(R0[None], V0[None], [M0], g)
    sys = closed_loop_nlsys(g)
    assert sys.nstates == 7 and sys.ninputs == 3 and sys.noutputs == 10
    T = np.linspace(0.0, b.landing_time[0], 501)
    resp = control.input_output_response(sys, T, U=0, X0=initial_state(),
                                         solve_ivp_method="LSODA",
                                         solve_ivp_kwargs={"rtol": 1e-10, "atol": 1e-10})
    x_end = resp.states[:, -1]
    np.testing.assert_allclose(x_end[:3], b.r_land[0], atol=1e-3)
    assert abs((M0 - x_end[6]) - b.fuel[0]) < 0.01
    # the input is an extra disturbance acceleration on v' only
    x = initial_state()
    u = np.array([0.3, -0.2, 0.1])
    d = sys._rhs(0.0, x, u) - sys._rhs(0.0, x, np.zeros(3))
    np.testing.assert_allclose(d, np.concatenate([np.zeros(3), u, [0.0]]), atol=1e-12)
