"""Check seed 000's proven bounds for a gain set (corrected law): ``lgw verify mars``.

Per claim, Hypothesis-driven simulations of the 3-axis plant (RK4, no drag, no thrust limit:
the plant of the bounds) from initial states of the envelope (default: a tuned file's
certificate envelope, else seed 000's Table III box and Table II dispersion), and a
falsification search on the exact reduced per-axis loop over the same states.  Margin =
(bound - observed)/bound, < 0 violates.  Exit 0 holds (or not applicable), 1 violated (with
the observed value, the bound, the state, the gains and a reproducing ``lgw verify`` command),
4 inconclusive (too few informative cases, too many excluded, or an unconfirmed violation).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from lgw.tuning import vocabulary as V
from lgw.tuning.options import Number
from lgw.tuning.spec import option
from lgw.tuning.verifying import Claim, Extra, Var, plan, verify_options

TOL = "one RK4 step dt (an event is located on the step grid)"
CLAIMS = {c.name: c for c in (
    Claim("reaching-16", "(16),(18)", "reaching",
          "first time |s1_i| <= eps, started on s2 = 0",
          "T1_exact of lgw.theory.mars.bounds.axis_bounds (<= T1 (18))", "s",
          "|s1_i(0)| <= eps: it starts inside the band it must reach", TOL),
    Claim("T2-26", "(26)", "undisturbed", "first time |s2_i| <= eps",
          "T2_exact of axis_bounds (<= T2 (26))", "s",
          "|s2_i(0)| <= eps: it starts inside the band it must reach", TOL),
    Claim("landing-T2+T1", "T2*+T1*", "undisturbed",
          "the later of the first entry into |r_i| <= eps and the last exit from it, inf if "
          "|r_i| > eps or |v_i| > eps' at the end",
          "landing_time_bound = T2_exact + T1_exact of axis_bounds", "s",
          "|r_i(0)| <= eps and |s2_i(0)| <= eps: it starts landed", TOL),
    Claim("s2-39-40", "(39),(40)", "disturbed",
          "first time |s2_i| is in the (39) band, under |a_p,i| <= a_max (worst and random); "
          "leaving the band afterwards is a violation",
          "T2_practical_exact of axis_bounds", "s",
          "|s2_i(0)| is inside the (39) band: there is no entry to time", TOL),
    Claim("s1-31-45", "(31),(45)", "disturbed",
          "first time |r_i| is in the (31) band from s2's entry into (39) on; leaving it "
          "afterwards is a violation",
          "landing_time_bound_disturbed = T2_practical_exact + T1_practical_exact of "
          "axis_bounds", "s",
          "|r_i| is inside the (31) band when s2 enters (39): there is no entry to time", TOL),
)}
VARIABLES = tuple(Var(n, "m", "position", nonzero=True) for n in ("rx", "ry", "rz")) + tuple(
    Var(n, "m/s", "velocity") for n in ("vx", "vy", "vz"))
EXTRAS = (Extra("disturbance", ("worst", "random"), "the disturbance flown (disturbed claims)"),
          Extra("noise_seed", "int", "seed of the random disturbance"),
          Extra("noise_case", "int", "case index of the random disturbance"))


@dataclass(frozen=True)
class Options(verify_options("lgw.tuning.mars.verify", CLAIMS, VARIABLES,
                             "rx=-500.0,ry=1000.0,rz=1200.0,vx=10.0,vy=-50.0,vz=-40.0",
                             {"ci": 20, "thorough": 150}, EXTRAS, module=__name__)):
    SETTINGS: ClassVar = ("dt", "eps")

    dt: float = V.dt(0.05, 1.0, "RK4 step (the re-check flies at dt/2)")
    eps: float = option("--eps", Number(0, 1e3, lo_open=True, unit="m or m/s"), 0.05,
                        "the bands |s1_i| <= eps (m) and |s2_i| <= eps (m/s) of the time claims",
                        probe=0.1)


__all__ = ["CLAIMS", "EXTRAS", "VARIABLES", "Options", "plan"]
