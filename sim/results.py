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
  "command_blown_up"       a stage evaluation asked for a command that cannot be a thrust
                           (not finite, or beyond the system's bound, e.g. seed 000's
                           lgw.sim.mars.batch.BLOWUP_ACCEL) before either; the step is not
                           accepted and the case ends at its start; time: that start;
  "nonfinite"              the state became NaN / inf (with a finite command: the plant
                           itself overflowed) before any of these; time: the start of the step
                           that blew up;
  "step_limit"             the adaptive integrator ran out of attempts; time: where it stopped;
  "horizon"                none of these by t_max; time: t_max.

Ground contact is a flag (``ground_contact``, ``min_altitude``), not an outcome: a case may
touch r_z < 0 and still land or not.
"""

from __future__ import annotations

import numpy as np

# indices are stable (new outcomes are appended); precedence is the order of the docstring
OUTCOMES = ("landed", "propellant_exhausted", "nonfinite", "step_limit", "horizon",
            "command_blown_up")
PRECEDENCE = ("landed", "propellant_exhausted", "command_blown_up", "nonfinite", "step_limit")


def classify(*, landed: np.ndarray, fuel_exhausted: np.ndarray, nonfinite: np.ndarray,
             step_limit: np.ndarray, landing_time: np.ndarray, t_end: np.ndarray,
             stop_at_outcome: bool, blown_up: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """(outcome index into OUTCOMES per case, its time in s) from the per-case flags
    (``blown_up`` None: a system without that flag)."""
    landed = np.asarray(landed, bool)
    flags = {"landed": landed, "propellant_exhausted": np.asarray(fuel_exhausted, bool),
             "command_blown_up": (np.zeros(landed.shape, bool) if blown_up is None
                                  else np.asarray(blown_up, bool)),
             "nonfinite": np.asarray(nonfinite, bool),
             "step_limit": np.asarray(step_limit, bool)}
    taken = np.zeros(landed.shape, bool)
    conds = []
    for name in PRECEDENCE:  # the first in precedence wins
        c = flags[name] & ~taken
        taken |= c
        conds.append(c)
    code = np.select(conds, [OUTCOMES.index(k) for k in PRECEDENCE],
                     default=OUTCOMES.index("horizon"))
    dry = conds[1]
    t_end = np.asarray(t_end, float)
    t = np.where(landed, np.asarray(landing_time, float), t_end)
    if not stop_at_outcome:
        t = np.where(dry, np.nan, t)
    return code, t


def counts(code: np.ndarray) -> dict[str, int]:
    """Cases per outcome (every outcome listed, zeros included)."""
    return {name: int(np.sum(np.asarray(code) == k)) for k, name in enumerate(OUTCOMES)}
