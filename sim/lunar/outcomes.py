"""Seed 001's per-case outcomes: every case ends in exactly one, with its time.

The kernel (``lgw.sim.lunar.kernel``) stops a case at the first of these and records it; the
names are the shared vocabulary's (``lgw.sim.results``, one meaning each); seed 001 has no
landing criterion (the reference ends at h_f = 100 m above the surface at t_f), so a case that
reaches t_end is "completed", and a contact with the surface is always a crash:

  "completed"              reached t_end inside the model's domain; time: t_end;
  "crashed"                r fell below the lunar radius R_MOON (the first crossing of the
                           surface, lgw.sim.results); time: the crossing, located on the cubic
                           Hermite interpolant of r inside the step, where the case ends (its
                           end state is the contact: ``impact_speed_mps`` = |(u, v, w)|,
                           ``impact_vertical_speed_mps`` = w, downward);
  "below_surface"          r < R_MOON at t = 0: not flown; time 0;
  "propellant_exhausted"   the mass reached the dry mass ``RunOptions.m_dry``; time: the
                           crossing, located likewise;
  "quaternion_drift"       | ||Q|| - 1 | > QUAT_NORM_TOL (the integration does not renormalise
                           Q, so drift means the step is too large); time: the node where
                           detected;
  "nonfinite"              the state became NaN / inf (or was at t = 0); time: the start of the
                           step that blew up;
  "step_limit"             dopri5 ran out of attempts; time: where it stopped;
  "command_blown_up"       a stage evaluation asked for a delivered thrust above
                           ``lgw.sim.lunar.kernel.BLOWUP_ACCEL`` m0 (or for thrust at a mass
                           <= 0): the step is far too large for the dynamics, it is not
                           accepted and the case ends at its start; time: that start (as seed
                           000's outcome of that name, ``lgw.sim.results``).
"""

from __future__ import annotations

import numpy as np
from lgw.sim.results import names as _shared

# s after the failure time from which "after the failure" is measured: the atan of (26) has a
# half-width of 0.5 s (its argument 2t - t_f is in seconds), so at +5 s the thrust fraction is
# within 2 % of (1 - T_a) of T_a (chosen; seed 001 says "after the failure" without a time)
AFTER_FAILURE_S = 5.0

# indexed by the kernel's codes (lgw.sim.lunar.kernel: COMPLETED, SURFACE, DRY, QUAT,
# NONFINITE, STEPLIM, BLOWN, BELOW)
OUTCOMES = _shared("completed", "crashed", "propellant_exhausted", "quaternion_drift",
                   "nonfinite", "step_limit", "command_blown_up", "below_surface")
DOMAIN_EXITS = (*OUTCOMES[1:4], "below_surface")


def counts(code: np.ndarray) -> dict[str, int]:
    """Cases per outcome (every outcome listed, zeros included)."""
    return {name: int(np.sum(np.asarray(code) == k)) for k, name in enumerate(OUTCOMES)}


def names(code: np.ndarray) -> list[str]:
    return [OUTCOMES[int(k)] for k in np.asarray(code)]


def json_safe(x):
    """x with every non-finite float replaced by None (JSON has no NaN / inf), recursively;
    numpy scalars and arrays become Python numbers and lists."""
    if isinstance(x, dict):
        return {str(k): json_safe(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [json_safe(v) for v in x]
    if isinstance(x, np.ndarray):
        return json_safe(x.tolist())
    if isinstance(x, np.bool_ | bool):
        return bool(x)
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, float | np.floating):
        return float(x) if np.isfinite(x) else None
    return x


# kernel results no output prints: the total time the torque is above its limit does not
# converge with the step (the relay of (7) chatters across it, lgw.sim.lunar.parameters, DT);
# the records carry its converged measures (time_saturated_torque_initial, torque_saturation_end)
UNQUOTED = ("time_saturated_torque",)


def case_record(results: dict, i: int) -> dict:
    """Case i of a kernel run's per-case results (``BatchResult.cases``) as a JSON-ready dict:
    its one outcome and time, and the sampled quantities (None where undefined, e.g. no
    saturation entry)."""
    from lgw.sim.lunar.kernel import RESULT_FIELDS

    rec = {"outcome": OUTCOMES[int(results["outcome"][i])],
           "t_outcome_s": float(results["t_outcome"][i])}
    for k in RESULT_FIELDS[2:]:
        if k not in UNQUOTED:
            rec[k] = results[k][i]
    rec["mass_final_kg"] = results["y_end"][i, 6]
    rec["steps"] = results["steps"][i]
    if rec["outcome"] == "crashed":  # the end state is the located contact
        uvw = np.asarray(results["y_end"][i, 3:6], float)
        rec["impact_speed_mps"] = float(np.linalg.norm(uvw))
        rec["impact_vertical_speed_mps"] = float(uvw[2])
    return json_safe(rec)
