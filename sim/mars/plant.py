"""Seed 000's plant, eqs. (10)-(14), and the Martian drag models of eq. (12).

State of one case: y = [r_x, r_y, r_z, v_x, v_y, v_z, m] in the landing-site frame (x
crossrange, y downrange, z altitude).  With thrust force F (N):
  r' = v                                   (10)
  v' = F/m + g + a_m(r, v, m) + a_p        (11), (14), with the lumped disturbance a_p of (30)
  m' = -|F| / c,  c = Isp g_e              (13)
These numpy functions are the readable statement of the plant (used by ``lgw.sim.mars.reference``,
``lgw.sim.mars.interop`` and open-loop replays); ``lgw.sim.mars.batch`` compiles the same equations
with numba,
and a test checks the two against each other.
"""

from __future__ import annotations

import numpy as np
from lgw.sim.mars.parameters import (
    CD_LANDER,
    DRAG_MODELS,
    H_MARS,
    PRINTED_DRAG_COEF,
    PRINTED_DRAG_DECAY,
    RHO0_MARS,
)
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import AREA, G_EARTH, G_MARS, ISP


def check_drag(model: str, name: str = "drag") -> str:
    if model not in DRAG_MODELS:
        raise ParameterError(name, model, f"must be one of {', '.join(DRAG_MODELS)}")
    return model


def drag_accel(r: np.ndarray, v: np.ndarray, m: np.ndarray | float,
               model: str = "physical") -> np.ndarray:
    """Drag acceleration a_m (m/s^2), broadcasting over leading axes of r, v (..., 3).

    model="physical" (default): a_m,i = -(1/2) rho0 exp(-r_z/H) C_D A_i |v_i| v_i / m, with
      rho0, H, C_D from ``lgw.sim.mars.parameters`` -- opposes each velocity component.
    model="printed": seed 000, eq. (12) as printed, a_m,i = -0.699 v_i^2 exp(-0.0009 r_z)/(A_i m)
      (always along -axis, divides by the area, 1.1 km scale height; kept for comparison).
    model="none": zero.
    """
    check_drag(model)
    r = np.asarray(r, float)
    v = np.asarray(v, float)
    m = np.asarray(m, float)[..., None]
    rz = r[..., 2:3]
    if model == "none":
        return np.zeros_like(v)
    if model == "physical":
        return -0.5 * RHO0_MARS * np.exp(-rz / H_MARS) * CD_LANDER * AREA * np.abs(v) * v / m
    return -PRINTED_DRAG_COEF * v**2 * np.exp(-PRINTED_DRAG_DECAY * rz) / (AREA * m)


def exhaust_velocity(isp: float = ISP) -> float:
    """c = Isp g_e of seed 000, eq. (13)."""
    if not (np.isfinite(isp) and isp > 0):
        raise ParameterError("isp", isp, "must be a finite number > 0 (s)")
    return float(isp) * G_EARTH


def plant_rhs(t: float, state: np.ndarray, force: np.ndarray, *, drag: str = "physical",
              isp: float = ISP, disturbance_accel: np.ndarray | None = None) -> np.ndarray:
    """dy/dt of seed 000 (10), (11), (13), (14) for one case and a given thrust force F (N).

    ``state`` = [r(3), v(3), m]; ``disturbance_accel`` is a_p (m/s^2, 3 values) or None.
    ``t`` is unused by the plant itself (kept for solve_ivp-style callers).
    """
    del t
    y = np.asarray(state, float)
    f = np.asarray(force, float)
    r, v, m = y[:3], y[3:6], y[6]
    acc = f / m + G_MARS + drag_accel(r, v, m, drag)
    if disturbance_accel is not None:
        acc = acc + np.asarray(disturbance_accel, float)
    return np.concatenate([v, acc, [-np.sqrt(f @ f) / exhaust_velocity(isp)]])


def saturate(force_unsat: np.ndarray, thrust_limit: float | None, limit: str = "axis"
             ) -> np.ndarray:
    """The commanded force after the thrust limit (..., 3).

    limit="axis": each |F_i| <= thrust_limit (seed 000, Part 3: 50 kN per axis);
    limit="norm": |F| <= thrust_limit, direction kept.  An infinite component (the corrected
    law's |s1|^(q1-1) v at s1 = 0) saturates to the limit along that component's sign; NaN stays
    NaN so the case is flagged.
    """
    f = np.asarray(force_unsat, float)
    if thrust_limit is None:
        return f
    if limit == "axis":
        return np.clip(f, -thrust_limit, thrust_limit)
    inf = np.isinf(f)
    any_inf = np.any(inf, axis=-1, keepdims=True)
    if np.any(inf):
        f = np.where(any_inf, np.where(inf, np.sign(f), 0.0), f)
    n = np.linalg.norm(f, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = np.where((n > thrust_limit) | any_inf, thrust_limit / n, 1.0)
    return f * scale
