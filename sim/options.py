"""Run options as small frozen objects: integration, stopping, thrust limit.

Each object validates its own ranges when built (``ParameterError`` naming the parameter) and,
being a frozen keyword-only dataclass, rejects a misspelled keyword (``TypeError``) and cannot
be changed after it is built (use ``dataclasses.replace``).  System-independent: the values a
system chooses (seed 000's dt, tolerances, dry mass) live in ``lgw.sim.<system>.parameters``
and its defaults objects (for Mars ``lgw.sim.mars.batch.INTEGRATION``, ``stopping_defaults``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from lgw.theory.errors import ParameterError

METHODS = ("rk4", "dopri5")
STOP_MODES = ("landing", "t_max")
LIMITS = ("axis", "norm")
# The finest relative tolerance the double-precision error estimate can honour.
RTOL_MIN = 1e-13


def positive(name: str, x: object, unit: str, allow_none: bool = False) -> None:
    """Raise ParameterError(name) unless x is a finite real number > 0 (or None if allowed)."""
    if x is None and allow_none:
        return
    ok = isinstance(x, int | float | np.integer | np.floating) and not isinstance(x, bool)
    if not (ok and math.isfinite(x) and x > 0):
        raise ParameterError(name, x, f"must be a finite number > 0 ({unit})")


def _one_of(name: str, x: object, valid: tuple[str, ...]) -> None:
    if x not in valid:
        raise ParameterError(name, x, f"must be one of {', '.join(valid)}")


@dataclass(frozen=True, kw_only=True)
class IntegrationOptions:
    """How each case is integrated (``lgw.sim.integrate``).

    method: "rk4" (classical RK4, fixed step dt) or "dopri5" (Dormand-Prince 5(4) with scipy
      RK45's error control rtol, atol; dt is the first step, max_step caps the step, a case
      needing more than max_steps attempts stops flagged ``step_limit``).
    dt, max_step in s; record=True keeps the trajectory (needs rk4: the fixed step grid).
    """

    method: str = "rk4"
    dt: float
    rtol: float
    atol: float
    max_step: float
    max_steps: int
    record: bool = False

    def __post_init__(self) -> None:
        _one_of("method", self.method, METHODS)
        positive("dt", self.dt, "s")
        if self.method == "dopri5":
            positive("rtol", self.rtol, "relative tolerance")
            if self.rtol < RTOL_MIN:
                raise ParameterError("rtol", self.rtol,
                                     f"must be >= {RTOL_MIN:g} (double precision)")
            positive("atol", self.atol, "absolute tolerance")
            positive("max_step", self.max_step, "s")
            if isinstance(self.max_steps, bool) or not isinstance(self.max_steps,
                                                                  int | np.integer) \
                    or self.max_steps < 1:
                raise ParameterError("max_steps", self.max_steps, "must be an integer >= 1")
            if self.record:
                raise ParameterError("record", self.record, "needs method='rk4' (the "
                                     "trajectory is recorded on the fixed step grid)")


@dataclass(frozen=True, kw_only=True)
class StoppingOptions:
    """When a case ends.

    stop="landing": at landing (|r| <= land_tol[0] m and |v| <= land_tol[1] m/s) or when the
      mass reaches m_dry (kg); stop="t_max": integrate to t_max (s) regardless, recording
      which came first.
    blowup_accel (m/s^2, > 0, may be inf; None: the system's default): a commanded
      acceleration above it ends the case as a blown-up command.  inf keeps only the
      non-finite test: for checks of the mathematical bounds with unlimited thrust, where a
      huge but finite command is part of the closed loop being checked.
    """

    stop: str = "landing"
    t_max: float
    land_tol: tuple[float, float]
    m_dry: float
    blowup_accel: float | None = None

    def __post_init__(self) -> None:
        _one_of("stop", self.stop, STOP_MODES)
        positive("t_max", self.t_max, "s")
        if not isinstance(self.land_tol, tuple | list | np.ndarray) or len(self.land_tol) != 2:
            raise ParameterError("land_tol", self.land_tol, "must be (position m, velocity m/s)")
        positive("land_tol[0]", self.land_tol[0], "m")
        positive("land_tol[1]", self.land_tol[1], "m/s")
        object.__setattr__(self, "land_tol", (float(self.land_tol[0]), float(self.land_tol[1])))
        positive("m_dry", self.m_dry, "kg")
        if self.blowup_accel is not None and not (float(self.blowup_accel) > 0):
            raise ParameterError("blowup_accel", self.blowup_accel, "must be > 0 (m/s^2; inf "
                                 "allowed) or None")

    def check_masses(self, m0: np.ndarray) -> None:
        """The dry mass must be below every initial mass."""
        if np.any(np.asarray(m0) <= self.m_dry):
            raise ParameterError("m_dry", self.m_dry, "must be < every initial mass m0 "
                                 f"(smallest m0 = {float(np.min(m0)):g} kg)")


@dataclass(frozen=True, kw_only=True)
class LimitOptions:
    """The thrust limit: None (unlimited), or thrust_limit N per axis (kind "axis": each
    |F_i|) or on the norm (kind "norm": |F|, direction kept)."""

    thrust_limit: float | None = None
    kind: str = "axis"

    def __post_init__(self) -> None:
        positive("thrust_limit", self.thrust_limit, "N", allow_none=True)
        _one_of("limit", self.kind, LIMITS)

    @property
    def code(self) -> int:
        """Kernel code: 0 unlimited, 1 per axis, 2 on the norm."""
        return 0 if self.thrust_limit is None else (1 if self.kind == "axis" else 2)

    @property
    def fmax(self) -> float:
        return math.inf if self.thrust_limit is None else float(self.thrust_limit)
