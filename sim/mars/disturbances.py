"""The lumped disturbance a_p of seed 000 (30): the four models the simulator offers.

  "none"    a_p = 0;
  "sin"     a_p,i = A sin(t) on every axis, seed 000 eq. (47) (A = 20 m/s^2 in the paper,
            ``lgw.theory.mars.parameters.A_MAX_PAPER``; configurable);
  "random"  bounded band-limited noise: per case and axis a sum of K random-phase sinusoids
            a_p,i(t) = sum_k c_k sin(w_k t + phi_k), c_k >= 0, sum_k c_k = a_max, so
            |a_p,i| <= a_max holds by construction (the per-axis bound of Hypothesis 1 as
            ``lgw.theory.mars.gains.Disturbance`` reads it).  w_k ~ U(RANDOM_OMEGA_BAND), phi_k ~
            U(0, 2 pi),
            (c_k / a_max) ~ Dirichlet(1, ..., 1).  Seeded per case: case j of a campaign with
            seed S draws from SeedSequence(S).spawn(...)[j], so its disturbance does not depend
            on how the campaign is chunked or how many workers run it;
  "worst"   a_p,i = -a_max sgn(s2_i), the feedback disturbance that opposes the s2 reaching law
            of (25) hardest under |a_p,i| <= a_max (s2 of (21) with the gain set's beta, q).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from lgw.sim.mars.parameters import RANDOM_N_SINES, RANDOM_OMEGA_BAND
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import A_MAX_PAPER

DISTURBANCES = ("none", "sin", "random", "worst")
KIND_CODE = {name: k for k, name in enumerate(DISTURBANCES)}


@dataclass(frozen=True)
class DisturbanceSpec:
    """A disturbance for N cases: amplitude per axis and, for "random", per-case sinusoids."""

    kind: str
    amplitude: np.ndarray  # (3,) m/s^2
    coef: np.ndarray  # (N, 3, K) m/s^2 (K = 0 unless random)
    omega: np.ndarray  # (N, 3, K) rad/s
    phase: np.ndarray  # (N, 3, K) rad

    def take(self, sl: slice) -> DisturbanceSpec:
        return DisturbanceSpec(self.kind, self.amplitude, self.coef[sl], self.omega[sl],
                               self.phase[sl])

    def accel(self, t: float, s2: np.ndarray, case: int) -> np.ndarray:
        """a_p (3,) at time t for case ``case`` (numpy; the batch kernel compiles the same)."""
        if self.kind == "none":
            return np.zeros(3)
        if self.kind == "sin":
            return self.amplitude * np.sin(t)
        if self.kind == "random":
            return np.sum(self.coef[case] * np.sin(self.omega[case] * t + self.phase[case]), axis=1)
        return -self.amplitude * np.sign(s2)


def amplitude_array(amplitude: float | np.ndarray | None) -> np.ndarray:
    a = np.broadcast_to(np.asarray(A_MAX_PAPER if amplitude is None else amplitude, float),
                        (3,)).copy()
    if not (np.all(np.isfinite(a)) and np.all(a >= 0)):
        raise ParameterError("dist_amplitude", amplitude, "must be finite and >= 0 (m/s^2)")
    return a


def make_disturbance(kind: str, n: int, *, amplitude: float | np.ndarray | None = None,
                     seed: int = 0, case_offset: int = 0) -> DisturbanceSpec:
    """Build the disturbance of cases case_offset .. case_offset + n - 1 of a campaign."""
    if kind not in DISTURBANCES:
        raise ParameterError("disturbance", kind, f"must be one of {', '.join(DISTURBANCES)}")
    amp = amplitude_array(amplitude)
    k = RANDOM_N_SINES if kind == "random" else 0
    coef = np.zeros((n, 3, k))
    omega = np.zeros((n, 3, k))
    phase = np.zeros((n, 3, k))
    if kind == "random":
        for j in range(n):
            # SeedSequence(seed, spawn_key=(i,)) is SeedSequence(seed).spawn(i + 1)[i].
            ss = np.random.SeedSequence(seed, spawn_key=(case_offset + j,))
            rng = np.random.default_rng(ss)
            coef[j] = rng.dirichlet(np.ones(k), size=3) * amp[:, None]
            omega[j] = rng.uniform(*RANDOM_OMEGA_BAND, size=(3, k))
            phase[j] = rng.uniform(0.0, 2 * np.pi, size=(3, k))
    return DisturbanceSpec(kind, amp, coef, omega, phase)
