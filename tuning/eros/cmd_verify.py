"""Check seed 002's proven per-axis times for a gain set (FTSMC (19), sign switching, sampled at
0.01 s), or the whole descent to touchdown: ``lgw verify eros``.

``--scenario tracking`` (default): per claim, Hypothesis-driven simulations of the sampled-data
loop from initial offsets of the envelope (default: a tuned file's certificate envelope, else
|e_i(0)| <= 10 m, |e_i'(0)| <= 0.5 m/s), each case against its own bound
(``lgw.theory.eros.bounds.axis_time_bound``); a tuned file's [certificate] promises (tracking
time, control limit) are flown from the states of its envelope, and those it says are proven
are proven again (``lgw.theory.eros.floored``, Arb).  ``--scenario descent``: the whole descent
(``lgw.sim.eros.descent``) over a campaign of ``dispersions`` (--cases, --descent-seed): every
case must touch down at or below the landing speed (a tuned descent file's land_speed, else
0.5 m/s); the worst violating case is re-flown by ``reference_solve_descent``.  Margin =
(bound - observed)/bound, < 0 violates.  Exit 0 holds (or not applicable), 1 violated (with the
observed value, the bound, the state or case, the gains and a reproducing ``lgw verify``
command), 4 inconclusive.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from lgw.tuning import vocabulary as V
from lgw.tuning.options import SEED, Integer, choice
from lgw.tuning.spec import option
from lgw.tuning.verifying import Claim, Var, plan, verify_options

TOL = "one sample dt = 0.01 s (an event between samples is seen at the next)"
REACH = "first sample with |s_i| <= 1e-3 m/s or a sign change of s_i"
TRACK = "first sample after which |e_i| <= 1 cm to the end of the run (never: inf)"
ON_SURFACE = "|s_i(0)| <= 1e-3 m/s: it starts on the sliding surface"
TRACKED = "|e_i(0)| <= 1 cm and |s_i(0)| <= 1e-3 m/s: it starts tracked"


def _mode(mode: str, eq: str, t_r: str, dbar: str) -> tuple[Claim, Claim]:
    """The reaching and reaching + sliding claims of one disturbance mode."""
    return (Claim(f"reaching-{mode}", f"(15)-(18), {eq}", mode, REACH,
                  f"t_r = {t_r}, the floored law's (lgw.theory.eros.floored.s_reach_time, "
                  f"{dbar}; |s0|/(k - dbar) without the floor)", "s", ON_SURFACE, TOL),
            Claim(f"time-{mode}", f"(6),(18), {eq}", mode, TRACK,
                  f"reaching + tracking time of the floored law (lgw.theory.eros.floored."
                  f"axis_bound, {dbar})", "s", TRACKED, TOL))


CLAIMS = {c.name: c for c in (
    *_mode("known", "D known", "(sgn(s0) sigma0 + delta)^+/k", "dbar = 0"),
    *_mode("unknown", "|D| <= dbar", "(sgn(s0) sigma0 + delta)^+/(k - dbar)",
           "dbar = 0.05 m/s^2"),
    Claim("certificate-time", "certificate", "certificate", TRACK,
          "the certificate's bound_t_total (lgw tune eros)", "s", TRACKED, TOL),
    Claim("certificate-u", "certificate", "certificate", "max |u_i| over the run",
          "the certificate's u_max = thrust-max / probe mass (lgw tune eros)", "m/s^2",
          "never: every case commands a control", ""),
    Claim("certificate-time-proof", "certificate", "certificate",
          "the proven tracking time of the floored law (19) over the certificate's envelope "
          "(lgw.theory.eros.floored, Arb)", "the certificate's bound_t_total", "s", "",
          kind="computed"),
    Claim("certificate-u-proof", "certificate", "certificate",
          "the proven bound on |u_i| of the floored law (19) over the certificate's envelope "
          "(lgw.theory.eros.floored, Arb)", "the certificate's u_max", "m/s^2", "",
          kind="computed"),
    Claim("descent-landing", "descent", "descent",
          "the largest touchdown speed over the descent campaign (inf: a case that never "
          "touched down)", "the landing speed (a tuned descent file's land_speed, else "
          "0.5 m/s)", "m/s", "", kind="computed"),
)}
TRACKING_CLAIMS = tuple(c for c in CLAIMS if CLAIMS[c].group != "descent")
SCENARIOS = ("tracking", "descent")
VARIABLES = (Var("ex", "m", "position error"), Var("ey", "m", "position error"),
             Var("ez", "m", "position error"), Var("vx", "m/s", "velocity error"),
             Var("vy", "m/s", "velocity error"), Var("vz", "m/s", "velocity error"),
             Var("phase", "rad", "phase of the disturbance"))


@dataclass(frozen=True)
class Options(verify_options("lgw.tuning.eros.verify", CLAIMS, VARIABLES,
                             "ex=5.0,ey=-3.0,ez=1.0,vx=0.1,vy=0.0,vz=-0.2,phase=1.0",
                             {"ci": 8, "thorough": 60}, module=__name__)):
    SETTINGS: ClassVar = ("scenario", "cases", "descent_seed", "case")

    scenario: str = option("--scenario", choice(SCENARIOS), "tracking",
                           "tracking: the paper's tracking loop (Hypothesis over the "
                           "envelope); descent: the whole descent to touchdown (a campaign of "
                           "dispersions)")
    cases: int = V.cases(30, "descent: cases of the campaign (dispersions of the start: "
                         "|e_i(0)| <= 10 m, |e_i'(0)| <= 1 cm/s, reflectivity, phase, "
                         "navigation ids)")
    descent_seed: int = option("--descent-seed", SEED, 3, "descent: seed of the campaign "
                               "(numpy SeedSequence; the navigation errors' too)")
    case: int | None = option("--case", Integer(0, 10**7, "case"), None,
                              "descent: fly only this case of the campaign (how a failure is "
                              "reproduced)", probe=0)

    def check(self) -> None:
        super().check()
        from lgw.theory.errors import ParameterError

        descent = self.scenario == "descent"
        for name in ("cases", "descent_seed", "case"):
            self.refuse_unless(descent, name, "only applies with --scenario descent")
        if self.case is not None and self.case >= self.cases:
            raise ParameterError("--case", self.case, f"must be < --cases = {self.cases}")
        self.refuse_unless(not descent, "witness", "the descent's claim is judged over its "
                           "campaign: reproduce a case with --case")

    def settings(self) -> dict[str, Any]:
        return {"scenario": self.scenario, "cases": self.cases,
                "descent_seed": self.descent_seed, "case": self.case}

__all__ = ["CLAIMS", "VARIABLES", "Options", "plan"]
