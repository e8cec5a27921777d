"""Seed 002's plant and law as python-control nonlinear I/O blocks (``control.nlsys``).

Seed 002's control is sampled ("sampling time 0.01 s"): the law reads the state at t_k and its
command is held (zero-order hold) until t_k + dt.  So the blocks come in two timebases:

    plant(dt=0.01)   the plant sampled with the hold: x_{k+1} from x_k under constant u_k,
                     by ``n_sub`` classical RK4 steps with the continuous disturbance D(t) at
                     the stage times (as ``lgw.sim.eros.batch``), discrete-time;
    law(g, dt=0.01)  the law evaluated at the samples, discrete-time (static);
    plant(), law(g)  the continuous-time plant (1)/(4) and the law evaluated continuously.

    loop = closed_loop(default_gains())   # control.interconnect([P, C]) by signal name
    resp = control.input_output_response(loop, T, X0=initial_state(), params={"k": 2.5})

Plant: states and outputs the position and velocity in the rotating body frame (m, m/s),
input the control acceleration u (m/s^2); gravity two-point, polyhedron or none, and the
disturbance D (known or unknown to the law, or none).  Law: inputs position and velocity,
output u; the gains (alpha, beta, p, q, k, lam, N, M, phi, e_floor) are params.
"""

from __future__ import annotations

from typing import Any

import control
import numpy as np
from lgw.sim.eros import plant as PL
from lgw.sim.eros.batch import SimOptions, _controller, _ref_coef
from lgw.sim.eros.batch import initial_state as _initial_state
from lgw.theory.eros.gains import Gains, gains_from_dict

STATES = ("x", "y", "z", "vx", "vy", "vz")
CONTROLS = ("ux", "uy", "uz")
GAIN_KEYS = ("alpha", "beta", "p", "q", "k", "lam", "N", "M", "phi", "e_floor")


def gain_params(g: Gains) -> dict[str, float]:
    return {k: float(getattr(g, k)) for k in GAIN_KEYS}


def gains_of(params: dict[str, Any], base: Gains) -> Gains:
    """The gain set of ``params`` (absent keys from ``base``), validated by the loader."""
    return gains_from_dict({"gains": {k: params.get(k, getattr(base, k)) for k in GAIN_KEYS}})


def initial_state(e0: Any = None, ed0: Any = None, opts: SimOptions | None = None
                  ) -> np.ndarray:
    """Position and velocity at t0: the reference plus the errors (default: the scenario's)."""
    from lgw.theory.eros import parameters as P

    opts = SimOptions() if opts is None else opts
    e0 = P.SCENARIO_OFFSET if e0 is None else np.asarray(e0, float)
    ed0 = P.SCENARIO_VOFFSET if ed0 is None else np.asarray(ed0, float)
    pos, vel = _initial_state(e0[None], ed0[None], opts)
    return np.concatenate([pos[0], vel[0]])


def _accel(opts: SimOptions, t: float, p: np.ndarray, v: np.ndarray, u: np.ndarray,
           phase: np.ndarray) -> np.ndarray:
    if opts.disturbance == "none":
        return PL.rotating_terms(p, v) + PL.gravity(p, opts.gravity) + u
    return PL.accel(t, p, v, u, opts.dist, phase, opts.gravity)


def plant(opts: SimOptions | None = None, *, dt: float | None = None, case_phase: float = 0.0,
          name: str = "eros_plant") -> control.NonlinearIOSystem:
    """Seed 002's plant (see the module docstring); ``opts``: gravity, disturbance and, for
    the sampled form, ``n_sub``; ``dt``: None (continuous) or the sampling time (s)."""
    opts = SimOptions() if opts is None else opts
    phase = np.array([float(case_phase)])

    def deriv(t, x, u):
        p, v = x[None, :3], x[None, 3:]
        return np.concatenate([v[0], _accel(opts, t, p, v, u[None], phase)[0]])

    def updfcn(t, x, u, params):
        x, u = np.asarray(x, float), np.asarray(u, float)
        if dt is None:
            return deriv(t, x, u)
        h = dt / opts.n_sub
        for j in range(opts.n_sub):  # RK4 with u held, as lgw.sim.eros.batch
            tj = t + j * h
            k1 = deriv(tj, x, u)
            k2 = deriv(tj + h / 2, x + h / 2 * k1, u)
            k3 = deriv(tj + h / 2, x + h / 2 * k2, u)
            k4 = deriv(tj + h, x + h * k3, u)
            x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        return x

    return control.nlsys(updfcn, lambda t, x, u, params: np.asarray(x, float), inputs=CONTROLS,
                         outputs=STATES, states=STATES, name=name,
                         dt=0 if dt is None else dt)


def law(g: Gains, opts: SimOptions | None = None, *, dt: float | None = None,
        case_phase: float = 0.0, name: str = "eros_law") -> control.NonlinearIOSystem:
    """The controller ``opts.law``-``opts.switch`` (the generated code of ``theory``'s
    expression, as the simulator flies it) on the reference (8)-(10) (``opts.reference``),
    with D in u_eq when ``opts.disturbance`` is "known"; a static block, gains as params."""
    opts = SimOptions() if opts is None else opts
    coef = _ref_coef(opts)
    phase = np.array([float(case_phase)])
    cache: dict[tuple, Gains] = {}

    def outfcn(t, x, u, params):
        key = tuple(sorted(params.items()))
        if key not in cache:
            cache.clear()
            cache[key] = gains_of(params, g)
        y = np.asarray(u, float)
        with np.errstate(all="ignore"):
            cmd, _, _, _ = _controller(opts, cache[key], coef, t, y[None, :3], y[None, 3:],
                                       phase)
        return cmd[0]

    return control.nlsys(None, outfcn, inputs=STATES, outputs=CONTROLS, name=name,
                         params=gain_params(g), dt=0 if dt is None else dt)


def closed_loop(g: Gains, opts: SimOptions | None = None, *, sampled: bool = True,
                case_phase: float = 0.0) -> control.InterconnectedSystem:
    """``plant`` and ``law`` interconnected by signal name, sampled at ``opts.dt`` (the
    paper's sampled-data loop) or continuous; outputs position and velocity."""
    opts = SimOptions() if opts is None else opts
    dt = opts.dt if sampled else None
    return control.interconnect([plant(opts, dt=dt, case_phase=case_phase),
                                 law(g, opts, dt=dt, case_phase=case_phase)],
                                inputs=[], outputs=list(STATES), name="eros_loop")
