"""Convergence of seed 001's simulated numbers, measured on every run that quotes them.

A number is converged when the same run at a refined step agrees with it:

    |x(dt) - x(dt / refine)| <= RTOL * max(|x(dt / refine)|, floor)

``RTOL`` = 1 %; ``floor`` is the quantity's absolute scale below which a relative difference
means nothing, listed in ``QUOTED`` with the unit of the quantity: RTOL x floor is the absolute
tolerance of a number near zero (1 mm for a final height error of 0.3 mm, 1 mm/s, 10 N,
10 ms).  Every number ``lgw simulate lunar``, ``lgw compare lunar`` and ``lgw report lunar``
quote for a single case goes through ``check`` and is flagged in the output and the JSON when
it fails.

Why a check is needed here: the orbit law (7) is not continuous at z2 = 0 (claim smooth-7), so
the loop slides on z2 = 0 after the initial transient and a fixed step chatters about it; the
error of the final numbers falls roughly like sqrt(dt), and some quantities (the peak of the
chattering command, the saturated time of a chattering thrust) converge slowly or not at all.
The step ``lgw.sim.lunar.parameters.DT`` is chosen so that the Section 5 numbers pass.

One mechanism for every system: each quantity's tolerance is a ``lgw.sim.convergence.Tol``
(1 % of the refined value, at least of the floor) and every comparison is the shared
``compare_cases`` record, which decides ``converged``; what is lunar's own is the list of
quoted quantities, their floors, and the dt/4 rule of a single run (dt/2 in campaigns).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from lgw.sim import convergence as SC

RTOL = SC.RTOL  # the shared tolerance (1 %)
REFINE = 4  # single runs: the default step against dt / 4
REFINE_CAMPAIGN = 2  # campaigns: a subset re-flown at dt / 2

# quantity -> (unit, absolute floor): the numbers of ``lgw.sim.lunar.scenario.summarize`` that
# the commands quote for a single case
QUOTED: dict[str, tuple[str, float]] = {
    "eh_final_m": ("m", 0.1),  # 1 mm
    "ev_final_norm_m_s": ("m/s", 0.1),  # 1 mm/s
    "max_abs_eh_m": ("m", 0.1),
    "max_abs_eh_after_failure_m": ("m", 0.1),
    "thrust_cmd_max_after_failure_N": ("N", 1000.0),  # 10 N
    "orbit_saturated_s": ("s", 1.0),  # 10 ms
    "orbit_saturated_after_failure_s": ("s", 1.0),
    "torque_saturated_initial_s": ("s", 1.0),
    "torque_saturation_end_s": ("s", 1.0),
    "d0e_orbit_final": ("m/s^2", 1e-3),
    "d0e_attitude_final": ("rad/s^2", 1e-5),
    "min_abs_eq0": ("1", 0.1),  # 1e-3
    "B0du_orbit_L2": ("m/s^2 s^0.5", 1.0),
    "B0du_attitude_L2": ("rad/s^2 s^0.5", 1.0),
    "lambda1_orbit_L2": ("m s^0.5", 1.0),
    "lambda2_orbit_L2": ("m/s s^0.5", 1.0),
    "lambda1_attitude_L2": ("s^0.5", 0.1),
    "lambda2_attitude_L2": ("rad/s s^0.5", 0.1),
}


def tolerance(floor: float) -> SC.Tol:
    """The shared tolerance of a lunar quantity: 1 % of the refined run's value, or of the
    quantity's floor near zero (``lgw.sim.convergence.Tol`` relative to the check)."""
    return SC.Tol(RTOL, 0.0, floor, "check")


@dataclass(frozen=True)
class Check:
    """One number at the default step and at the refined step."""

    name: str
    unit: str
    value: float
    refined: float
    floor: float

    @property
    def tol(self) -> SC.Tol:
        return tolerance(self.floor)

    @property
    def difference(self) -> float:
        """|x(dt) - x(dt/refine)| / max(|x(dt/refine)|, floor)."""
        return self.tol.difference(self.value, self.refined)

    @property
    def converged(self) -> bool:
        return self.tol.ok(self.value, self.refined)

    def to_dict(self) -> dict[str, Any]:
        return {"value": _num(self.value), "refined": _num(self.refined), "unit": self.unit,
                "floor": self.floor, "difference": _num(self.difference),
                "converged": self.converged}


def _num(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


@dataclass(frozen=True)
class Convergence:
    """The checks of one run: ``dt`` and the refined step, per quantity; the outcome class at
    both steps must also agree.  ``record`` is the shared ``lgw.sim.convergence``
    ConvergenceRecord of the same comparison (one case), which decides ``converged``."""

    dt: float
    refined_dt: float
    checks: tuple[Check, ...]
    outcome: str
    refined_outcome: str
    record: SC.ConvergenceRecord = field(compare=False, repr=False)

    @property
    def unconverged(self) -> list[Check]:
        if self.outcome != self.refined_outcome:  # numbers of another outcome: not compared
            return [c for c in self.checks if not c.converged]
        bad = {m.name for m in self.record.metrics.values() if m.unconverged}
        return [c for c in self.checks if c.name in bad]

    @property
    def converged(self) -> bool:
        return self.record.converged

    def flags(self, label: str = "") -> list[str]:
        """One warning line per unconverged number (empty when converged)."""
        pre = f"{label}: " if label else ""
        out = []
        if self.outcome != self.refined_outcome:
            out.append(f"{pre}UNCONVERGED outcome {self.outcome} at dt = {self.dt:g} s but "
                       f"{self.refined_outcome} at dt = {self.refined_dt:g} s: not converged")
        for c in self.unconverged:
            out.append(f"{pre}UNCONVERGED {c.name} = {c.value:.6g} {c.unit} at dt = {self.dt:g} s, "
                       f"{c.refined:.6g} at dt = {self.refined_dt:g} s: differs by "
                       f"{100 * c.difference:.3g} % (> {100 * RTOL:g} %): not converged")
        return out

    def to_dict(self) -> dict[str, Any]:
        # the shared record's keys (how, base, check, cases, cases_checked, metrics, ...) as
        # every system prints them, then seed 001's own: the steps and each quoted number
        return {**self.record.to_dict(), "dt": self.dt, "refined_dt": self.refined_dt, "rtol": RTOL,
                "criterion": "|x(dt) - x(dt/k)| <= rtol max(|x(dt/k)|, floor)",
                "converged": self.converged, "outcome": self.outcome,
                "refined_outcome": self.refined_outcome,
                "numbers": {c.name: c.to_dict() for c in self.checks}}


def compare(numbers: Mapping[str, Any], refined: Mapping[str, Any], dt: float,
            refined_dt: float, outcome: str, refined_outcome: str,
            quoted: Mapping[str, tuple[str, float]] = QUOTED) -> Convergence:
    """The checks of the quoted numbers present in both summaries, through the shared
    ``lgw.sim.convergence.compare_cases`` (one case, step halving or dt/4)."""
    checks = tuple(Check(k, unit, float(numbers[k]), float(refined[k]), floor)
                   for k, (unit, floor) in quoted.items()
                   if k in numbers and k in refined and numbers[k] is not None
                   and refined[k] is not None)
    rec = SC.compare_cases(
        [{"outcome": outcome, **{c.name: c.value for c in checks}}],
        [{"outcome": refined_outcome, **{c.name: c.refined for c in checks}}],
        {c.name: c.tol for c in checks}, how="step refinement",
        base_label=f"RK4 dt = {dt:g} s", check_label=f"RK4 dt = {refined_dt:g} s")
    return Convergence(dt, refined_dt, checks, outcome, refined_outcome, rec)


def check(fly: Callable[[float], tuple[Mapping[str, Any], str]], dt: float,
          refine: int = REFINE, numbers: tuple[Mapping[str, Any], str] | None = None
          ) -> Convergence:
    """Fly ``fly(dt)`` (-> (summary numbers, outcome name)) at dt (unless given as
    ``numbers``) and at dt / refine, and compare the quoted numbers."""
    a, oa = numbers if numbers is not None else fly(dt)
    b, ob = fly(dt / refine)
    return compare(a, b, dt, dt / refine, oa, ob)
