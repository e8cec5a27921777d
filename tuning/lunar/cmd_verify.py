"""Check seed 001's bounds (13), (18), (19), (21a) for a gain set's orbit loop:
``lgw verify lunar``.

The orbit loop of the gain set (``[orbit]``; default seed 001 Section 5's) flies the general
system (5) (``lgw.sim.lunar.general``: ||d|| = 0.5 m/s^2 constant, per-axis saturation of the
command at --thrust-max, RK4 --dt, --t-max s) from Hypothesis-drawn initial errors of the
envelope.  Margin = (bound - observed)/bound, < 0 violates.  Exit 0 holds (or not applicable),
1 violated (with the observed value, the bound, the state, the gains and a reproducing
``lgw verify`` command), 4 inconclusive.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from lgw.tuning import vocabulary as V
from lgw.tuning.verifying import Claim, Var, plan, verify_options

D_NORM = 0.5  # m/s^2, ||d|| of the general system (5) (chosen; lgw.sim.lunar.general)
TOL = "none: the integrals are trapezoidal sums on the RK4 grid; the re-check halves the step"
L2 = "L2 norm on [0, t-max]"
CLAIMS = {c.name: c for c in (
    Claim("V2_step_outside_band", "(13)", "orbit",
          "largest one-step rise of V2 (12) outside the chattering band ||z2|| <= 3 dt "
          "(d0e + D), over V2(0)", "0 (V2 does not increase, (13))", "",
          "no step with ||z2|| outside the chattering band: nothing to check", TOL),
    Claim("(18a)", "(18a)", "orbit", f"||lambda1|| ({L2})",
          "||B0 du|| / sqrt(2 f1bar) (lgw.theory.lunar.bounds.lambda_gain_bounds)", "",
          "the saturation never acted (||B0 du|| = 0): lambda1 stays 0, a check of 0 <= 0",
          TOL),
    Claim("(18b)", "(18b)", "orbit", f"||lambda2|| ({L2})",
          "||B0 du|| / sqrt(2 f2bar - 1) (lambda_gain_bounds)", "",
          "the saturation never acted (||B0 du|| = 0): lambda2 stays 0, a check of 0 <= 0",
          TOL),
    Claim("(19a)", "(19a)", "orbit", f"||z1||^2 ({L2})",
          "V2(0)/f1bar (lgw.theory.lunar.bounds.z_l2_bounds)", "",
          "the bound is not a positive number", TOL),
    Claim("(19b) derived", "(19b)", "orbit", f"||z2||^2 ({L2})",
          "V2(0)/(f2bar - f3) (z_l2_bounds, derived from (13))", "",
          "the bound is not a positive number", TOL),
    Claim("(19b) printed", "(19b) as printed", "orbit", f"||z2||^2 ({L2})",
          "V2(0)/f2bar (z_l2_bounds, printed=True)", "",
          "the bound is not a positive number", TOL),
    Claim("(21a)", "(21a)", "orbit", f"||x1|| ({L2})",
          "(sqrt(2 V2(0)) + ||B0 du||)/sqrt(2 f1bar) (lgw.theory.lunar.bounds."
          "transient_bounds)", "", "the bound is not a positive number", TOL),
)}
VARIABLES = (Var("x1", "m", "height error"), Var("x2x", "m/s", "velocity error"),
             Var("x2y", "m/s", "velocity error"), Var("x2z", "m/s", "velocity error"))


@dataclass(frozen=True)
class Options(verify_options("lgw.tuning.lunar.verify", CLAIMS, VARIABLES,
                             "x1=50.0,x2x=1.0,x2y=-2.0,x2z=0.5", {"ci": 16, "thorough": 120},
                             module=__name__)):
    SETTINGS: ClassVar = ("t_max", "dt", "thrust_max")

    t_max: float = V.t_max(5.0, "flight time per case", hi=600.0)
    dt: float = V.dt(0.02, 0.1, "RK4 step (the re-check flies at dt/2)")
    thrust_max: float = V.thrust_max(2000.0, "per-axis saturation of the orbit command u "
                                     "(1e9: effectively none)")

    def settings(self) -> dict[str, Any]:
        return {**super().settings(), "D": D_NORM}


__all__ = ["CLAIMS", "VARIABLES", "Options", "plan"]
