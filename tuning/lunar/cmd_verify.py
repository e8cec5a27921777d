"""Check seed 001's bounds (13), (18), (19), (21a) for a gain set's orbit loop:
``lgw verify lunar``, and a tuned file's [certificate] promises (``lgw tune lunar``).

The orbit loop of the gain set (``[orbit]``; default seed 001 Section 5's) flies the general
system (5) (``lgw.sim.lunar.general``: ||d|| = 0.5 m/s^2 constant, per-axis saturation of the
command at --thrust-max, RK4 --dt, --t-max s) from Hypothesis-drawn initial errors of the
envelope.  A file written by ``lgw tune lunar`` also has its [certificate] promises checked
(``lgw.tuning.lunar.design.check_certificate``): the proven ones re-derived (the thrust
redundancy in exact arithmetic, the hypotheses, the (18) constants against linfnorm), the
sampled ones re-flown on a fresh campaign of --cert-cases cases (--cert-seed) over the
certificate's own envelope, a violation re-flown at half the step.  Margin = (bound -
observed)/bound, < 0 violates.  Exit 0 holds (or not applicable),
1 violated (with the observed value, the bound, the state, the gains and a reproducing
``lgw verify`` command), 4 inconclusive.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from lgw.tuning import vocabulary as V
from lgw.tuning.options import SEED, Integer
from lgw.tuning.spec import option
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
          "V2(0)/f2bar with the printed (20) V2(0) = |z1(0)|^2/2 + |z2(0)|^2/2 "
          "(lgw.theory.lunar.bounds.z_l2_bounds_printed)", "",
          "the bound is not a positive number", TOL),
    Claim("(21a)", "(21a)", "orbit", f"||x1|| ({L2})",
          "(sqrt(2 V2(0)) + ||B0 du||)/sqrt(2 f1bar) (lgw.theory.lunar.bounds."
          "transient_bounds)", "", "the bound is not a positive number", TOL),
    *(Claim(name, "certificate", "certificate", obs, bound, unit, "", kind="computed")
      for name, obs, bound, unit in (
          ("certificate-redundancy", "the nominal thrust T_d", "T_max T_a,min (exact "
           "rationals; lgw.tuning.lunar.design.redundancy)", "N"),
          ("certificate-hypotheses", "hypotheses of (13), (17b), (18) that fail on the "
           "orbit gains", "0", ""),
          ("certificate-l2-lambda1", "the L2 gain B0 du -> lambda1 (linfnorm)",
           "the certificate's lambda1_gain_18a", ""),
          ("certificate-l2-lambda2", "the L2 gain B0 du -> lambda2 (linfnorm)",
           "the certificate's lambda2_gain_18b", ""),
          ("certificate-completes", "cases of the certificate's envelope that do not "
           "complete", "0", ""),
          ("certificate-eh", "max |e_h(t_f)| over the campaign", "the certificate's eh_max_m",
           "m"),
          ("certificate-ev", "max |e_v(t_f)| over the campaign",
           "the certificate's ev_max_m_s", "m/s"),
          ("certificate-thrust", "max commanded thrust after the failure",
           "the certificate's thrust_max_N", "N"))),
)}
CERT_CLAIMS = tuple(c for c in CLAIMS if CLAIMS[c].kind == "computed")
VARIABLES = (Var("x1", "m", "height error"), Var("x2x", "m/s", "velocity error"),
             Var("x2y", "m/s", "velocity error"), Var("x2z", "m/s", "velocity error"))


@dataclass(frozen=True)
class Options(verify_options("lgw.tuning.lunar.verify", CLAIMS, VARIABLES,
                             "x1=50.0,x2x=1.0,x2y=-2.0,x2z=0.5", {"ci": 16, "thorough": 120},
                             module=__name__)):
    SETTINGS: ClassVar = ("t_max", "dt", "thrust_max", "cert_cases", "cert_seed")

    t_max: float = V.t_max(5.0, "flight time per case", hi=600.0)
    dt: float = V.dt(0.02, 0.1, "RK4 step (the re-check flies at dt/2)")
    thrust_max: float = V.thrust_max(2000.0, "per-axis saturation of the orbit command u "
                                     "(1e9: effectively none)")
    cert_cases: int = option("--cert-cases", Integer(1, 10_000, "cases"), 30,
                             "a tuned file's [certificate]: cases of the fresh campaign its "
                             "sampled promises are re-flown on (plus the envelope's nominal "
                             "case)", probe=3)
    cert_seed: int = option("--cert-seed", SEED, 12345, "a tuned file's [certificate]: seed "
                            "of that campaign (numpy SeedSequence)")

    def settings(self) -> dict[str, Any]:
        return {**super().settings(), "D": D_NORM}


__all__ = ["CLAIMS", "VARIABLES", "Options", "plan"]
