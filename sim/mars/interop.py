"""Seed 000's closed loop as a python-control nonlinear I/O system (``control.nlsys``).

States x = [r_x, r_y, r_z, v_x, v_y, v_z, m] (seed 000 (10)-(14)); inputs u = an extra
disturbance acceleration a_p (3, m/s^2, added to the selected built-in disturbance); outputs
y = [x (7), F (3)] with F the commanded thrust after the limit.  The update function is
``lgw.sim.mars.reference.ClosedLoopRHS``: the law from ``theory``'s numpy lambdification and the
numpy
plant of ``lgw.sim.mars.plant``, so python-control users simulate exactly what the reference mode
does.

    sys = closed_loop_nlsys(default_gains())
    resp = control.input_output_response(sys, T, U=0, X0=initial_state())
"""

from __future__ import annotations

import control
import numpy as np
from lgw.sim.mars.disturbances import make_disturbance
from lgw.sim.mars.reference import ClosedLoopRHS
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import ISP, M0, R0, V0

STATES = ("rx", "ry", "rz", "vx", "vy", "vz", "m")
INPUTS = ("apx", "apy", "apz")
OUTPUTS = STATES + ("Fx", "Fy", "Fz")


def initial_state(r0: np.ndarray = R0, v0: np.ndarray = V0, m0: float = M0) -> np.ndarray:
    return np.concatenate([np.asarray(r0, float), np.asarray(v0, float), [float(m0)]])


def closed_loop_nlsys(gains: Gains, *, law: str = "corrected", disturbance: str = "none",
                      dist_amplitude: float | None = None, seed: int = 0,
                      thrust_limit: float | None = None, limit: str = "axis",
                      drag: str = "physical", guidance_drag: str | None = None,
                      isp: float = ISP, name: str = "mars_closed_loop"
                      ) -> control.NonlinearIOSystem:
    """The closed loop of ``law`` on the Mars plant as ``control.nlsys`` (see module doc)."""
    dist = make_disturbance(disturbance, 1, amplitude=dist_amplitude, seed=seed)
    rhs = ClosedLoopRHS(gains, law=law, dist=dist, case=0, thrust_limit=thrust_limit,
                        limit=limit, drag=drag, guidance_drag=guidance_drag, isp=isp)

    def updfcn(t, x, u, params):
        return rhs(t, np.asarray(x, float), ap_extra=np.asarray(u, float))

    def outfcn(t, x, u, params):
        f, _ = rhs.force(np.asarray(x, float))
        return np.concatenate([x, f])

    return control.nlsys(updfcn, outfcn, inputs=INPUTS, outputs=OUTPUTS, states=STATES,
                         name=name)
