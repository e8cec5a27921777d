"""Seed 002's plant: the rotating-frame dynamics (1)/(4) of a probe near 433 Eros, batched.

    r'' = -2 W x r' - W x (W x r) + g(r) + u + D(t),   W = (0, 0, OMEGA)

(the component form (4), checked against the vector form in claim dynamics-1), with OMEGA the
measured spin rate (lgw.theory.eros.parameters.OMEGA; the paper's 3.3118e-4 differs by 4e-5
relative).  Gravity: the two-mass-point model (2) as derived (attracting; the printed sign is
wrong, claim gravity-2) with the fitted masses and positions, or the polyhedral model of the
shape (Werner & Scheeres) as the reference "truth".  Arrays are (cases, 3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gravity import two_point_accel
from lgw.theory.eros.polyhedron import eros_accel
from lgw.theory.errors import ParameterError

GRAVITY_MODELS = ("two-point", "polyhedron", "none")


def rotating_terms(pos: np.ndarray, vel: np.ndarray, omega: float = P.OMEGA) -> np.ndarray:
    """Coriolis + centrifugal accelerations of (4): (2w y' + w^2 x, -2w x' + w^2 y, 0)."""
    out = np.empty_like(pos)
    out[..., 0] = 2 * omega * vel[..., 1] + omega**2 * pos[..., 0]
    out[..., 1] = -2 * omega * vel[..., 0] + omega**2 * pos[..., 1]
    out[..., 2] = 0.0
    return out


def gravity(pos: np.ndarray, model: str) -> np.ndarray:
    """Gravitational acceleration (m/s^2) at pos (..., 3)."""
    if model == "two-point":
        return two_point_accel(pos, P.TWO_POINT_P1, P.TWO_POINT_P2, *P.TWO_POINT_GM)
    if model == "polyhedron":
        flat = pos.reshape(-1, 3)
        return eros_accel(flat).reshape(pos.shape)
    if model == "none":
        return np.zeros_like(pos)
    raise ParameterError("gravity", model, "one of " + ", ".join(GRAVITY_MODELS))


@dataclass(frozen=True)
class Disturbance:
    """D_i(t) = amp sin(freq t + phase_i + case_phase) per axis (m/s^2); |D_i| <= amp.

    seed 002 leaves D ("modelling uncertainties") unspecified: chosen, see parameters."""

    amp: float = P.DIST_AMP
    freq: float = P.DIST_FREQ
    phase: tuple[float, float, float] = tuple(P.DIST_PHASE)

    def __call__(self, t: float, case_phase: np.ndarray) -> np.ndarray:
        ph = np.asarray(self.phase)[None, :] + case_phase[:, None]
        return self.amp * np.sin(self.freq * t + ph)


def accel(t: float, pos: np.ndarray, vel: np.ndarray, u: np.ndarray, dist: Disturbance,
          case_phase: np.ndarray, model: str) -> np.ndarray:
    """r'' of (4) for each case."""
    return rotating_terms(pos, vel) + gravity(pos, model) + u + dist(t, case_phase)
