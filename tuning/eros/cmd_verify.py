"""Check seed 002's proven per-axis times for a gain set (FTSMC (19), sign switching, sampled at
0.01 s): ``lgw verify eros``.

Per claim, Hypothesis-driven simulations of the sampled-data loop from initial offsets of the
envelope (default: a tuned file's certificate envelope, else |e_i(0)| <= 10 m, |e_i'(0)| <=
0.5 m/s), each case against its own bound (``lgw.theory.eros.bounds.axis_time_bound``); a
tuned file's [certificate] promises (tracking time, control limit) are checked too.  Margin =
(bound - observed)/bound, < 0 violates.  Exit 0 holds (or not applicable), 1 violated (with the
observed value, the bound, the state, the gains and a reproducing ``lgw verify`` command), 4
inconclusive.
"""

from __future__ import annotations

from lgw.tuning.verifying import Claim, Var, plan, verify_options

TOL = "one sample dt = 0.01 s (an event between samples is seen at the next)"
REACH = "first sample with |s_i| <= 1e-3 m/s or a sign change of s_i"
TRACK = "first sample after which |e_i| <= 1 cm to the end of the run (never: inf)"
ON_SURFACE = "|s_i(0)| <= 1e-3 m/s: it starts on the sliding surface"
TRACKED = "|e_i(0)| <= 1 cm and |s_i(0)| <= 1e-3 m/s: it starts tracked"


def _mode(mode: str, eq: str, t_r: str, dbar: str) -> tuple[Claim, Claim]:
    """The reaching and reaching + sliding claims of one disturbance mode."""
    return (Claim(f"reaching-{mode}", f"(15)-(18), {eq}", mode, REACH,
                  f"t_r = {t_r} (lgw.theory.eros.bounds.axis_time_bound, {dbar})", "s",
                  ON_SURFACE, TOL),
            Claim(f"time-{mode}", f"(6),(18), {eq}", mode, TRACK,
                  f"t_r + t_s(e_max) of axis_time_bound ({dbar})", "s", TRACKED, TOL))


CLAIMS = {c.name: c for c in (
    *_mode("known", "D known", "|s0|/k", "dbar = 0"),
    *_mode("unknown", "|D| <= dbar", "|s0|/(k - dbar)", "dbar = 0.05 m/s^2"),
    Claim("certificate-time", "certificate", "certificate", TRACK,
          "the certificate's bound_t_total (lgw tune eros)", "s", TRACKED, TOL),
    Claim("certificate-u", "certificate", "certificate", "max |u_i| over the run",
          "the certificate's u_max = thrust-max / probe mass (lgw tune eros)", "m/s^2",
          "never: every case commands a control", ""),
)}
VARIABLES = (Var("ex", "m", "position error"), Var("ey", "m", "position error"),
             Var("ez", "m", "position error"), Var("vx", "m/s", "velocity error"),
             Var("vy", "m/s", "velocity error"), Var("vz", "m/s", "velocity error"),
             Var("phase", "rad", "phase of the disturbance"))


Options = verify_options("lgw.tuning.eros.verify", CLAIMS, VARIABLES,
                         "ex=5.0,ey=-3.0,ez=1.0,vx=0.1,vy=0.0,vz=-0.2,phase=1.0",
                         {"ci": 8, "thorough": 60}, module=__name__)

__all__ = ["CLAIMS", "VARIABLES", "Options", "plan"]
