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


# --- the plant and the law as separate blocks ---------------------------------------------
#
#     P = plant()                       states = inputs of the law: [r, v, m]
#     C = law(default_gains())          gains as params: beta1_x ... alpha2_z, q1, q2, g1, g2
#     loop = control.interconnect([P, C], inputs=["apx", "apy", "apz"], outputs=STATES)
#     resp = control.input_output_response(loop, T, U=0, X0=initial_state(),
#                                          params={"q1": 0.62})   # another gain, same blocks
#
# The signal names connect the two blocks: the law reads rx ... m and commands Fx, Fy, Fz; the
# plant reads Fx, Fy, Fz and the disturbance apx, apy, apz.

FORCES = ("Fx", "Fy", "Fz")


def gain_params(gains: Gains) -> dict[str, float]:
    """A gain set as python-control params: one float per name (per-axis gains as
    ``<gain>_<axis>``)."""
    from lgw.theory.mars.gains import AXIS_GAINS, EXPONENTS

    out = {f"{k}_{a}": float(getattr(gains, k)[i]) for k in AXIS_GAINS
           for i, a in enumerate("xyz")}
    out.update({k: float(getattr(gains, k)) for k in EXPONENTS})
    return out


def gains_of(params: dict[str, float], base: Gains) -> Gains:
    """The gain set of ``params`` (names of ``gain_params``; absent ones from ``base``),
    validated by the gains loader (a bad value is a ParameterError naming the gain)."""
    from lgw.theory.mars.gains import AXIS_GAINS, EXPONENTS, gains_from_dict

    d = base.to_dict()
    for k in AXIS_GAINS:
        d["gains"][k] = [float(params.get(f"{k}_{a}", d["gains"][k][i]))
                         for i, a in enumerate("xyz")]
    for k in EXPONENTS:
        d["gains"][k] = float(params.get(k, d["gains"][k]))
    return gains_from_dict(d)


def plant(*, drag: str = "physical", isp: float = ISP, name: str = "mars_plant"
          ) -> control.NonlinearIOSystem:
    """Seed 000's plant (10)-(14) (``lgw.sim.mars.plant.plant_rhs``): states and outputs
    [r (m), v (m/s), m (kg)], inputs the thrust F (N, after any limit) and the disturbance
    acceleration a_p (m/s^2); params ``isp`` (s)."""
    from lgw.sim.mars.plant import check_drag, plant_rhs

    check_drag(drag)

    def updfcn(t, x, u, params):
        u = np.asarray(u, float)
        return plant_rhs(t, np.asarray(x, float), u[:3], drag=drag,
                         isp=float(params.get("isp", isp)), disturbance_accel=u[3:])

    return control.nlsys(updfcn, lambda t, x, u, params: np.asarray(x, float),
                         inputs=FORCES + INPUTS, outputs=STATES, states=STATES, name=name,
                         params={"isp": float(isp)})


def law(gains: Gains, *, law: str = "corrected", thrust_limit: float | None = None,
        limit: str = "axis", guidance_drag: str = "physical", name: str = "mars_law"
        ) -> control.NonlinearIOSystem:
    """The guidance law ``law`` (the generated numpy code of ``theory``'s expression, as the
    reference simulator flies it) as a static block: inputs [r, v, m], outputs the commanded
    thrust F (N) after the limit; the gains are params (``gain_params``), so one block serves
    every gain set: ``params={"beta1_x": 3.0}`` in ``input_output_response``."""
    from lgw.sim.mars.disturbances import make_disturbance

    cache: dict[tuple, ClosedLoopRHS] = {}

    def rhs_for(params: dict[str, float]) -> ClosedLoopRHS:
        key = tuple(sorted(params.items()))
        if key not in cache:
            cache.clear()
            cache[key] = ClosedLoopRHS(gains_of(params, gains), law=law,
                                       dist=make_disturbance("none", 1), case=0,
                                       thrust_limit=thrust_limit, limit=limit,
                                       guidance_drag=guidance_drag)
        return cache[key]

    def outfcn(t, x, u, params):
        y = np.asarray(u, float)
        if not y[6] > 0.0:  # no vehicle: python-control's first pass through an
            return np.zeros(3)  # interconnection evaluates the blocks at zero inputs
        return rhs_for(params).force(y)[0]

    return control.nlsys(None, outfcn, inputs=STATES, outputs=FORCES, name=name,
                         params=gain_params(gains))


def closed_loop(gains: Gains, **kw) -> control.InterconnectedSystem:
    """``plant()`` and ``law(gains)`` interconnected by signal name; input a_p, outputs the
    states.  ``kw``: the law's keywords (``law``, ``thrust_limit``, ``limit``,
    ``guidance_drag``)."""
    return control.interconnect([plant(drag=kw.get("guidance_drag", "physical")),
                                 law(gains, **kw)], inputs=list(INPUTS),
                                outputs=list(STATES), name="mars_loop")
