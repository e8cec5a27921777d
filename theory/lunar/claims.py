"""Seed 001's claims in report order: Section 3 (general law), Section 4 (instances), and the
Section 5 scenario claims the simulator layer builds (``scenario`` argument: theory never
imports sim).

``theory_claims(gains)`` judges every gain-dependent claim (scope "gain-set") for ``gains``
(default: seed 001 Section 5's); the others hold or fail whatever the valid gains.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from lgw.theory.evidence import Claim
from lgw.theory.lunar import derivation as D
from lgw.theory.lunar import instances as I
from lgw.theory.lunar import l2 as L2
from lgw.theory.lunar.gains import Gains, paper_gains


def theory_claims(gains: Gains | None = None) -> list[Claim]:
    """Every claim of (5)-(28) that needs no simulation, in report order; each paper claim
    that the workbench corrects is followed by the correction."""
    g = gains or paper_gains()
    return [D.v2dot_claim(), D.v2dot_bound_claim(), D.rank_claim(), D.smooth_claim(),
            D.lasalle_claim(g), D.vlambda_claim(), L2.l2_claim(g), L2.l2_hinf_claim(g),
            L2.z_l2_claim(g), L2.z_l2_derived_claim(g), L2.transient_claim(g),
            L2.transient_derived_claim(g), I.orbit_claim(), I.saturation_claim(),
            I.saturation_commanded_claim(), I.failure_claim(), I.failure_model_claim(),
            I.attitude_kinematics_claim(), I.attitude_dynamics_claim(), I.attitude_F1_claim(),
            I.attitude_F1_bound_claim()]


def all_claims(gains: Gains | None = None, scenario: Sequence[Claim] = ()) -> list[Claim]:
    """The theory claims for ``gains`` followed by the Section 5 claims
    (``lgw.sim.lunar.scenario``)."""
    return theory_claims(gains) + list(scenario)


MODULES = ("lgw.theory.lunar.law", "lgw.theory.lunar.derivation", "lgw.theory.lunar.l2",
           "lgw.theory.lunar.instances", "lgw.theory.lunar.scalar_run",
           "lgw.theory.lunar.comparison")


def clear_caches() -> None:
    """Forget every cached claim and intermediate result (a changed law, bound or constant is
    then derived afresh: the mutation tests use it)."""
    for name in MODULES:
        mod = sys.modules.get(name)
        for obj in vars(mod).values() if mod else ():
            if callable(getattr(obj, "cache_clear", None)):
                obj.cache_clear()
