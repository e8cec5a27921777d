"""Seed 001's claims in report order: Section 3 (general law), Section 4 (instances), and the
Section 5 scenario claims the simulator layer builds (``scenario`` argument: theory never
imports sim)."""

from __future__ import annotations

from collections.abc import Sequence

from lgw.theory.evidence import Claim
from lgw.theory.lunar import derivation as D
from lgw.theory.lunar import instances as I


def theory_claims() -> list[Claim]:
    """Every claim of (5)-(28) that needs no simulation, in report order."""
    return [D.v2dot_claim(), D.rank_claim(), D.smooth_claim(), D.lasalle_claim(),
            D.vlambda_claim(), D.l2_claim(), D.z_l2_claim(), D.transient_claim(),
            I.orbit_claim(), I.saturation_claim(), I.failure_claim(),
            I.attitude_kinematics_claim(), I.attitude_dynamics_claim(), I.attitude_F1_claim()]


def all_claims(scenario: Sequence[Claim] = ()) -> list[Claim]:
    """The theory claims followed by the Section 5 claims (``lgw.sim.lunar.scenario``)."""
    return theory_claims() + list(scenario)
