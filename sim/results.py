"""Per-case outcomes, for every system: each case ends in exactly one, with its time.

The integrator and a system's hooks record flags (``lgw.sim.integrate``: ``nonfinite``,
``step_limit``; a landing system: ``landed``, ``fuel_exhausted``); ``classify`` turns them into
one outcome per case, the first thing that happened, in this order of precedence (a later
flag can only be set after an earlier outcome when the case keeps integrating, stop="t_max"):

  "landed"                 the landing criterion was met (before the mass reached dry mass);
                           time: the located landing time;
  "propellant_exhausted"   the mass reached the dry mass before landing; time: where the case
                           stopped (the located crossing with stop="landing"; NaN with
                           stop="t_max", where the crossing time is not kept);
  "nonfinite"              the state or command became NaN / inf before either; time: the
                           start of the step that blew up;
  "step_limit"             the adaptive integrator ran out of attempts; time: where it stopped;
  "horizon"                none of these by t_max; time: t_max.

Ground contact is a flag (``ground_contact``, ``min_altitude``), not an outcome: a case may
touch r_z < 0 and still land or not.
"""

from __future__ import annotations

import numpy as np

OUTCOMES = ("landed", "propellant_exhausted", "nonfinite", "step_limit", "horizon")


def classify(*, landed: np.ndarray, fuel_exhausted: np.ndarray, nonfinite: np.ndarray,
             step_limit: np.ndarray, landing_time: np.ndarray, t_end: np.ndarray,
             stop_at_outcome: bool) -> tuple[np.ndarray, np.ndarray]:
    """(outcome index into OUTCOMES per case, its time in s) from the per-case flags."""
    landed = np.asarray(landed, bool)
    dry = np.asarray(fuel_exhausted, bool) & ~landed
    bad = np.asarray(nonfinite, bool) & ~landed & ~dry
    lim = np.asarray(step_limit, bool) & ~landed & ~dry & ~bad
    code = np.select([landed, dry, bad, lim], [0, 1, 2, 3], default=4)
    t_end = np.asarray(t_end, float)
    t = np.where(landed, np.asarray(landing_time, float), t_end)
    if not stop_at_outcome:
        t = np.where(dry, np.nan, t)
    return code, t


def counts(code: np.ndarray) -> dict[str, int]:
    """Cases per outcome (every outcome listed, zeros included)."""
    return {name: int(np.sum(np.asarray(code) == k)) for k, name in enumerate(OUTCOMES)}
