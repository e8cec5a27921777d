"""Per-case outcomes, for every system: each case ends in exactly one, with its time.

One vocabulary (``OUTCOMES``, each name with one meaning, ``MEANINGS``) for the three systems:
a system uses the subset that applies to it (``lgw.sim.mars.batch``, ``lgw.sim.lunar.outcomes``,
``lgw.sim.eros.batch`` name theirs from this set, and a test holds them to it).

Contact with the surface is one notion for every system (``contact_outcome``, ``CONTACT``):
the first crossing of the surface (seed 000: the ground plane r_z = 0 of the landing-site
frame; seed 001: the sphere r = R_MOON; seed 002: the shape model) ends the case at the
crossing, located inside the step on the integrator's cubic Hermite interpolant (never at the
node after it).  Within the landing tolerance the contact is a touchdown and the case is
"landed"; otherwise it is "crashed", with the impact time, point, velocity and speed recorded.
A penetration shallower than the system's contact tolerance (seed 000: the landing position
tolerance; the sliding-mode laws chatter about r_z = 0 by ~1 mm at RK4's default step where the
z axis converges first, a numerical graze, not a contact) is not a contact; a deeper one is,
dated at the crossing of the surface itself that it followed.  A state that starts below the
surface is "below_surface" at t = 0 (the command line refuses it as input).

The integrator and a system's hooks record flags (``lgw.sim.integrate``: ``nonfinite``,
``step_limit``; a landing system: ``landed``, ``contact``, ``fuel_exhausted``, ...);
``classify`` turns them into one outcome per case, the first thing that happened, in this order
of precedence (a later flag can only be set after an earlier outcome when the case keeps
integrating, stop="t_max"; the hooks record at most one of landed / contact / dry mass):

  "below_surface"          the initial state is below the surface (and not landed); time 0;
  "landed"                 the landing criterion was met (before the mass reached dry mass and
                           before any contact), or a contact within the landing tolerance;
                           time: the located landing (or contact) time;
  "crashed"                contact with the surface outside the landing tolerance; time: the
                           located crossing of the surface;
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

Outcomes of systems whose scenario does not end at touchdown (seed 001, seed 002's tracking
scenario): "completed" (the scenario's planned end time reached inside the model's domain),
"tracked" (the tracking criterion held to the end), "quaternion_drift" (the attitude
quaternion's norm left 1 by more than the tolerance: the step is too large).

``ground_contact`` / ``min_altitude`` (seed 000) stay flags: any dip below the surface (a graze
included) before the outcome, and the lowest altitude flown.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# indices are stable (new outcomes are appended); precedence is PRECEDENCE
OUTCOMES = ("landed", "propellant_exhausted", "nonfinite", "step_limit", "horizon",
            "command_blown_up", "crashed", "below_surface", "completed", "tracked",
            "quaternion_drift")
MEANINGS = {
    "landed": "the landing criterion was met, or the surface was reached within the landing "
              "tolerance",
    "crashed": "the surface was reached outside the landing tolerance (impact speed and time "
               "recorded at the located crossing)",
    "below_surface": "the initial state is below the surface",
    "propellant_exhausted": "the mass reached the dry mass first",
    "command_blown_up": "a stage asked for a command that cannot be a thrust; the case ends at "
                        "the start of that step",
    "nonfinite": "the state became NaN or inf",
    "step_limit": "the adaptive integrator ran out of attempts",
    "horizon": "none of the scenario's terminal events by t_max",
    "completed": "the scenario's planned end time was reached inside the model's domain",
    "tracked": "the tracking criterion held from some time to the end of the run",
    "quaternion_drift": "the attitude quaternion's norm left 1 by more than the tolerance",
}
assert set(MEANINGS) == set(OUTCOMES)
PRECEDENCE = ("below_surface", "landed", "crashed", "propellant_exhausted", "command_blown_up",
              "nonfinite", "step_limit")
# outcomes that end a case at the surface (the contact record is defined for them)
CONTACT = ("landed", "crashed")
# The outcome class two integrators of the same case must agree on: each physical outcome is
# its own class; the ones that say the run could not be carried on (the command or the state
# broke down, the adaptive integrator gave up, the step drifted the quaternion) are one class,
# "numerical", since which of them comes first is a property of the integrator, not the loop.
NUMERICAL = ("command_blown_up", "nonfinite", "step_limit", "quaternion_drift")


def outcome_class(name: str) -> str:
    """The outcome's class for integrator agreement (``NUMERICAL`` or the outcome itself)."""
    if name not in OUTCOMES:
        raise ValueError(f"outcome {name!r} is not in the shared vocabulary lgw.sim.results")
    return "numerical" if name in NUMERICAL else name


def names(*wanted: str) -> tuple[str, ...]:
    """A system's outcome names, each checked against the shared vocabulary (in the order the
    system's own codes index them)."""
    for w in wanted:
        if w not in OUTCOMES:
            raise ValueError(f"outcome {w!r} is not in the shared vocabulary lgw.sim.results")
    return tuple(wanted)


def classify(*, landed: np.ndarray, fuel_exhausted: np.ndarray, nonfinite: np.ndarray,
             step_limit: np.ndarray, landing_time: np.ndarray, t_end: np.ndarray,
             stop_at_outcome: bool, blown_up: np.ndarray | None = None,
             contact: np.ndarray | None = None, contact_time: np.ndarray | None = None,
             below_surface: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(outcome index into OUTCOMES per case, its time in s) from the per-case flags
    (``blown_up``, ``contact``, ``below_surface`` None: a system without that flag).  A case
    with ``contact`` that is not ``landed`` crashed at ``contact_time``."""
    landed = np.asarray(landed, bool)

    def flag(x):
        return np.zeros(landed.shape, bool) if x is None else np.asarray(x, bool)

    crashed = flag(contact) & ~landed
    below = flag(below_surface)
    flags = {"below_surface": below, "landed": landed, "crashed": crashed,
             "propellant_exhausted": np.asarray(fuel_exhausted, bool),
             "command_blown_up": flag(blown_up), "nonfinite": np.asarray(nonfinite, bool),
             "step_limit": np.asarray(step_limit, bool)}
    taken = np.zeros(landed.shape, bool)
    conds = []
    for name in PRECEDENCE:  # the first in precedence wins
        c = flags[name] & ~taken
        taken |= c
        conds.append(c)
    code = np.select(conds, [OUTCOMES.index(k) for k in PRECEDENCE],
                     default=OUTCOMES.index("horizon"))
    dry = conds[PRECEDENCE.index("propellant_exhausted")]
    t_end = np.asarray(t_end, float)
    t = np.where(landed, np.asarray(landing_time, float), t_end)
    if contact_time is not None:
        t = np.where(conds[PRECEDENCE.index("crashed")], np.asarray(contact_time, float), t)
    t = np.where(conds[0], 0.0, t)
    if not stop_at_outcome:
        t = np.where(dry, np.nan, t)
    return code, t


def counts(code: np.ndarray, listed: tuple[str, ...] | None = None) -> dict[str, int]:
    """Cases per outcome (``code`` indexes OUTCOMES): every outcome of ``listed`` (default:
    all of OUTCOMES) listed, zeros included."""
    code = np.asarray(code)
    return {name: int(np.sum(code == OUTCOMES.index(name))) for name in (listed or OUTCOMES)}


# --- contact --------------------------------------------------------------------------------

@dataclass(frozen=True)
class Contact:
    """The record of one case's first contact with the surface (SI units, the system's frame).

    time: s, the located crossing of the surface; point: (3,) m, where; velocity: (3,) m/s, the
    velocity there; speed: m/s, its norm (the impact speed); normal_speed: m/s, the speed
    into the surface (>= 0 for a descent); outcome: "landed" (within the landing tolerance) or
    "crashed"."""

    time: float
    point: tuple[float, float, float]
    velocity: tuple[float, float, float]
    speed: float
    normal_speed: float
    outcome: str

    def to_dict(self) -> dict:
        return {"time_s": self.time, "point_m": list(self.point),
                "velocity_mps": list(self.velocity), "impact_speed_mps": self.speed,
                "normal_speed_mps": self.normal_speed, "outcome": self.outcome}


def contact_outcome(offset: float, speed: float,
                    land_tol: tuple[float, float] | None) -> str:
    """"landed" if the contact is within the landing tolerance (|position - target| <= tol[0]
    m and speed <= tol[1] m/s), else "crashed"; ``land_tol`` None (a scenario with no landing
    criterion: seed 001 ends 100 m above the surface) makes every contact a crash."""
    if land_tol is None:
        return "crashed"
    ok = offset <= land_tol[0] and speed <= land_tol[1]
    return "landed" if ok else "crashed"


def contact_record(time: float, point, velocity, normal, land_tol, target=None) -> Contact:
    """A ``Contact`` from the located crossing: ``normal`` the surface's outward unit normal
    there, ``target`` the landing target (default: the origin of the frame)."""
    p = np.asarray(point, float)
    v = np.asarray(velocity, float)
    tgt = np.zeros(3) if target is None else np.asarray(target, float)
    speed = float(np.linalg.norm(v))
    return Contact(float(time), tuple(map(float, p)), tuple(map(float, v)), speed,
                   float(-np.dot(v, np.asarray(normal, float))),
                   contact_outcome(float(np.linalg.norm(p - tgt)), speed, land_tol))


def num(x) -> float | None:
    """A JSON number: None for NaN / inf."""
    x = float(x)
    return x if math.isfinite(x) else None
