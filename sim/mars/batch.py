"""Batched simulation of seed 000's closed loop: N cases advance together.

The plant is seed 000 (10)-(14) (see ``lgw.sim.mars.plant``), the guidance any law of
``lgw.sim.mars.laws``
(compiled from ``theory``'s SymPy expressions), the disturbance one of
``lgw.sim.mars.disturbances``.
Integration is classical RK4 with an explicit step ``dt`` (the default), or, with
method="dopri5", the adaptive Dormand-Prince 5(4) pair with scipy RK45's error control (the
method of the per-case solve_ivp loop a user would write, compiled), compiled with numba and
run in parallel over cases (threads, ``lgw.sim.integrate.run_chunk``); each case stops when it
lands (or at t_max), so cases do not wait for each other and results do not depend on how cases
are batched or chunked.

dopri5 is for landing statistics (landed, landing time and state, fuel, min altitude, ground
contact): the closed loop is smooth between the arrivals of s1, s2 at 0, and the error
control takes ~35-70 steps per Table II case where RK4 needs ~550 at dt = 0.05 s; at each
non-smooth arrival it rejects and shrinks the step instead of stepping over it.  Peak thrust,
saturation time and the s-band times are sampled at the accepted steps (peaks at their
stages too), which are up to ``max_step`` apart: use RK4 (whose nodes are dt apart) where those
matter, as the tuner does.
A case that needs more than ``max_steps`` attempts (e.g. chattering at s = 0 with
stop="t_max") stops there, flagged ``step_limit``, not landed.

What is recorded per case (``BatchResult``):
  landing: the first time |r| <= tol_r and |v| <= tol_v.  It is detected at the step nodes and
    located inside the step by bisection on cubic Hermite interpolants of r (with r' = v) and
    v (with v' from the RHS at both nodes), which are O(dt^4) accurate like RK4 itself;
    r_land, v_land, fuel (m0 - m at landing) are evaluated there;
  t_s1, t_s2: per axis, the first time |s| <= eps (s1 = r, (15); s2 of (21) with the gain
    set's beta, q), from the signed linear interpolant of s between nodes (so a zero crossing
    inside a step counts); t_s1_last_exit, t_s2_last_exit: the last time s left that band
    (NaN if it never left after entering).  These are tracked until t_max when stop="t_max";
  peak_thrust / peak_thrust_unsat: max |F_i| (N per axis) over the nodes (t = 0 and each
    accepted step's left node) until the outcome, after / before the thrust limit: the
    commands of states on the trajectory (the tuner's certificate,
    lgw.tuning.mars.design.limit_measure, is defined on them);
  peak_thrust_stages / peak_thrust_unsat_stages: the same maxima over every right-hand-side
    evaluation of those steps too (RK4's three trial states and the new node; dopri5's five
    and the new node; rejected dopri5 attempts excluded), so >= the node peaks: what the
    integrator asked of the engine.  They differ where the command is not smooth between
    nodes: near an s1 = 0 crossing the corrected law's |s1|^(q1-1) v spikes at a trial state
    (up to 85 kN at RK4 trial states for a gain set whose node peaks stay under 50 kN);
  peak_thrust_after_arrival: per axis, max |F_i| after the limit (N) over the accepted nodes
    from the first one where the axis is in its landing band (|r_i| <= tol_r and
    |v_i| <= tol_v, the land_tol of the landing criterion) on, until the case ends (with
    stop="t_max" also after landing); NaN if the axis never enters its band at a node.  A
    node whose command is blown up is not counted (the case ends there: at t = 0 a case
    that has landed there with such a command).  The spikes after arrival;
    time_saturated: time with the command limited (on some axis, or on the norm), until the
    outcome: where the limit's margin (|F| before the limit minus the limit), linear between
    the nodes, is > 0 (second order in the step; a left-endpoint count of the nodes was first
    order); min_altitude and ground_contact (r_z < 0 before
    the outcome, a graze included), from the minimum of the cubic Hermite interpolant
    of r_z over each step (not only its nodes), up to the outcome;
  contact, contact_time, contact_point, impact_velocity (and the properties impact_speed,
    crashed): the first crossing of the ground plane r_z = 0 (lgw.sim.results), located on
    the Hermite interpolant of r_z inside the step: one descending faster than the landing
    speed tolerance is a contact at once, a slower one (a graze: the laws chatter ~1 mm about
    r_z = 0 at RK4's default step where z converges first) is one once r_z passes -tol_r,
    dated at its crossing.  With stop="landing" the case ends there (at the crossing when it
    lies in the step that confirms it: always for an impact), "landed" if the crossing state is
    within the landing tolerance, else "crashed" with the fuel burnt to the crossing.  A command
    that blows up while the vehicle descends closer to the ground than its stopping distance
    at BLOWUP_ACCEL is not that outcome: no thrust could change the impact, which is recorded
    on the ballistic arc (nanoseconds; the corrected law's command diverges as r_z -> 0 with
    v_z != 0, so with no thrust limit every impact is preceded by such a blow-up);
  below_surface: r_z(0) < 0 and not landed at t = 0: the case is not flown (stop="landing"),
    outcome "below_surface";
  blown_up: a stage asked for a command that cannot be flown (BLOWUP_ACCEL below: not
    finite, above BLOWUP_ACCEL m0, or at a mass <= 0; e.g. the corrected law's |s1|^(q1-1) v
    at s1 ~ 0 with v != 0 and no thrust limit): the step is not accepted, the case ends at
    its start (outcome "command_blown_up");
  nonfinite: a NaN/inf appeared: the state (the plant overflowed) or a blown-up command
    that was not finite (then blown_up too), never silently dropped.  ``t_end`` and ``y_end``
    give where each case stopped;
  fuel_exhausted: the mass reached the dry mass ``m_dry`` (default
  lgw.theory.mars.parameters.M_DRY),
    located inside the step by bisection on the cubic Hermite interpolant of m, like the
    landing.  A case that runs dry before landing is not landed, and its fuel, peaks,
    saturation time, min altitude and ground contact are taken up to that point.  With
    stop="landing" (the mission) the case ends there (t_end, y_end at the crossing).  With
    stop="t_max" (observing the closed loop to t_max, as the bound checks of lgw.tuning.mars.verify
    do,
    where the law divides the mass out) the integration goes on past m_dry as it goes on past
    landing; the flags still say which came first, and a landed case that later runs dry
    (hovering) is both landed and fuel_exhausted.

Chattering: the laws are not Lipschitz at s = 0 (|s|^q with q < 1), so an explicit step
leaves a residual oscillation of s whose size depends on dt.  ``eps`` must sit above it; the
default (``lgw.sim.mars.parameters.EPS_DEFAULT``) does by a wide margin at the default dt, see
benchmarks/bench_sim.py --floor and docs/sim.md.  sign() is never smoothed: no boundary layer.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
from lgw.sim import executors, integrate
from lgw.sim.integrate import (  # noqa: F401  (re-exported: the integrator's tableau, helpers)
    DP_A,
    DP_B,
    DP_C,
    DP_E,
    PI_BETA,
    PI_MAXFAC,
    _band,
    _herm,
    _herm_min,
)
from lgw.sim.kernel_cache import CompileNotice
from lgw.sim.mars import kernel as mars_kernel
from lgw.sim.mars.disturbances import KIND_CODE, DisturbanceSpec, make_disturbance
from lgw.sim.mars.laws import get_law, surface_params
from lgw.sim.mars.parameters import (
    DOPRI_ATOL,
    DOPRI_MAX_STEP,
    DOPRI_MAX_STEPS,
    DOPRI_RTOL,
    DT_DEFAULT,
    EPS_DEFAULT,
    T_MAX_DEFAULT,
)
from lgw.sim.mars.plant import check_drag, exhaust_velocity
from lgw.sim.options import (  # noqa: F401  (re-exported)
    LIMITS,
    METHODS,
    STOP_MODES,
    IntegrationOptions,
    LimitOptions,
    StoppingOptions,
    positive,
)
from lgw.sim.results import classify, names
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import AREA, G_MARS, ISP, LAND_POS_TOL, LAND_VEL_TOL, M_DRY

DRAG_CODE = {"none": 0, "physical": 1, "printed": 2}

# Per-case result arrays: the Mars hooks' results (lgw.sim.mars.kernel.RESULT_FIELDS), then the
# integrator's (lgw.sim.integrate.GENERIC_FIELDS), in this order.
ARRAY_FIELDS = ("landed", "landing_time", "r_land", "v_land", "fuel", "peak_thrust",
                "peak_thrust_unsat", "time_saturated", "min_altitude", "ground_contact", "t_s1",
                "t_s2", "t_s1_last_exit", "t_s2_last_exit", "nonfinite", "fuel_exhausted",
                "t_end", "y_end", "steps", "step_limit", "blown_up", "peak_thrust_stages",
                "peak_thrust_unsat_stages", "peak_thrust_after_arrival", "contact",
                "contact_time", "contact_point", "impact_velocity", "below_surface")
# the per-axis (N, 3) arrays among them
VECTOR_FIELDS = ("r_land", "v_land", "peak_thrust", "peak_thrust_unsat", "t_s1", "t_s2",
                 "t_s1_last_exit", "t_s2_last_exit", "peak_thrust_stages",
                 "peak_thrust_unsat_stages", "peak_thrust_after_arrival", "contact_point",
                 "impact_velocity")
# the seed 000 outcomes of the shared vocabulary (lgw.sim.results), in report order
OUTCOMES_USED = names("landed", "crashed", "below_surface", "propellant_exhausted",
                      "command_blown_up", "nonfinite", "step_limit", "horizon")
assert set(ARRAY_FIELDS) == set(mars_kernel.RESULT_FIELDS) | set(integrate.GENERIC_FIELDS)

# Seed 000's integration defaults (values and their reasons in lgw.sim.mars.parameters).
INTEGRATION = IntegrationOptions(dt=DT_DEFAULT, rtol=DOPRI_RTOL, atol=DOPRI_ATOL,
                                 max_step=DOPRI_MAX_STEP, max_steps=DOPRI_MAX_STEPS)
LAND_TOL = (LAND_POS_TOL, LAND_VEL_TOL)
DEFAULT_CHUNK = 4096
# A commanded force above BLOWUP_ACCEL * m0 (N; m0 the case's initial mass) cannot be a thrust:
# 1e5 m/s^2 is ~10^4 g, ~4000 times seed 000's 50 kN per axis on 1905 kg (26 m/s^2).  Such a
# command (or one that is not finite, or one asked at a stage mass <= 0) is "blown up": the
# law's |s1|^(q1-1) v at s1 ~ 0 with v != 0, or a step far too large for the dynamics.  The
# step that evaluated it is not accepted; the case ends at that step's start, outcome
# "command_blown_up" (lgw.sim.results), with every reported quantity from the accepted
# steps.  Applied command: with a thrust limit it never exceeds the limit, so only a command
# that is NaN or asked at a non-positive mass is blown up there.  The reference mode uses the
# same threshold.
BLOWUP_ACCEL = 1e5


def stopping_defaults(**changes: Any) -> StoppingOptions:
    """Seed 000's stopping options: stop at landing, t_max = T_MAX_DEFAULT, the landing
    tolerances and dry mass of lgw.theory.mars.parameters; ``changes`` override them."""
    kw: dict[str, Any] = {"t_max": T_MAX_DEFAULT, "land_tol": LAND_TOL, "m_dry": M_DRY}
    kw.update(changes)
    return StoppingOptions(**kw)


@dataclass
class BatchResult:
    """Per-case outcomes of a batch (arrays of length N) and the integration settings."""

    landed: np.ndarray
    landing_time: np.ndarray
    r_land: np.ndarray
    v_land: np.ndarray
    fuel: np.ndarray
    peak_thrust: np.ndarray
    peak_thrust_unsat: np.ndarray
    time_saturated: np.ndarray
    min_altitude: np.ndarray
    ground_contact: np.ndarray
    t_s1: np.ndarray
    t_s2: np.ndarray
    t_s1_last_exit: np.ndarray
    t_s2_last_exit: np.ndarray
    nonfinite: np.ndarray
    fuel_exhausted: np.ndarray
    t_end: np.ndarray
    y_end: np.ndarray
    steps: np.ndarray
    step_limit: np.ndarray
    blown_up: np.ndarray
    peak_thrust_stages: np.ndarray
    peak_thrust_unsat_stages: np.ndarray
    peak_thrust_after_arrival: np.ndarray
    contact: np.ndarray
    contact_time: np.ndarray
    contact_point: np.ndarray
    impact_velocity: np.ndarray
    below_surface: np.ndarray
    eps: float
    dt: float
    r0: np.ndarray | None = None
    v0: np.ndarray | None = None
    m0: np.ndarray | None = None
    trajectory: dict[str, np.ndarray] | None = None
    info: dict[str, Any] = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.landed)

    @property
    def crashed(self) -> np.ndarray:
        """Ground contact outside the landing tolerance (the outcome "crashed")."""
        return self.contact & ~self.landed

    @property
    def impact_speed(self) -> np.ndarray:
        """|v| at the located ground contact (m/s; NaN without a contact)."""
        return np.linalg.norm(self.impact_velocity, axis=1)

    @staticmethod
    def concat(parts: list[BatchResult]) -> BatchResult:
        """Join chunk results in order (trajectories are not joined)."""
        first = parts[0]
        kw: dict[str, Any] = {k: np.concatenate([getattr(p, k) for p in parts])
                              for k in ARRAY_FIELDS}
        for k in ("r0", "v0", "m0"):
            kw[k] = np.concatenate([getattr(p, k) for p in parts])
        return BatchResult(eps=first.eps, dt=first.dt, info=dict(first.info), **kw)

    def with_rows(self, idx: np.ndarray, other: BatchResult) -> BatchResult:
        """A copy with cases ``idx`` replaced by the cases of ``other`` (in order), e.g. the
        same initial states re-flown at a smaller dt; ``info["replaced"]`` lists them."""
        idx = np.asarray(idx, dtype=np.int64)
        if len(idx) != len(other):
            raise ValueError(f"with_rows: {len(idx)} indices for {len(other)} cases")
        kw: dict[str, Any] = {}
        for k in ARRAY_FIELDS:
            a = getattr(self, k).copy()
            a[idx] = getattr(other, k)
            kw[k] = a
        info = dict(self.info)
        info["replaced"] = sorted({*info.get("replaced", []), *idx.tolist()})
        return BatchResult(eps=self.eps, dt=self.dt, r0=self.r0, v0=self.v0, m0=self.m0,
                           info=info, **kw)

    def outcomes(self) -> tuple[np.ndarray, np.ndarray]:
        """(outcome per case as an index into ``lgw.sim.results.OUTCOMES``, its time in s):
        exactly one per case, the first that happened (see lgw.sim.results)."""
        return classify(landed=self.landed, fuel_exhausted=self.fuel_exhausted,
                        nonfinite=self.nonfinite, step_limit=self.step_limit,
                        blown_up=self.blown_up, contact=self.contact,
                        contact_time=self.contact_time, below_surface=self.below_surface,
                        landing_time=self.landing_time, t_end=self.t_end,
                        stop_at_outcome=self.info.get("stop", "landing") == "landing")

    def equal(self, other: BatchResult) -> bool:
        """Bitwise equality of every per-case array (NaN == NaN)."""
        return all(np.array_equal(getattr(self, k), getattr(other, k), equal_nan=True)
                   for k in ARRAY_FIELDS) and self.eps == other.eps and self.dt == other.dt


# --- Python entry points ------------------------------------------------------------------

def _check_states(r0, v0, m0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r0 = np.atleast_2d(np.asarray(r0, float))
    v0 = np.atleast_2d(np.asarray(v0, float))
    m0 = np.atleast_1d(np.asarray(m0, float))
    n = r0.shape[0]
    if r0.shape != (n, 3):
        raise ParameterError("r0", r0.shape, "must have shape (N, 3)")
    if v0.shape != (n, 3):
        raise ParameterError("v0", v0.shape, f"must have shape ({n}, 3) like r0")
    if m0.shape == (1,) and n > 1:
        m0 = np.full(n, m0[0])
    if m0.shape != (n,):
        raise ParameterError("m0", m0.shape, f"must have shape ({n},) like r0")
    for name, a in (("r0", r0), ("v0", v0), ("m0", m0)):
        if not np.all(np.isfinite(a)):
            raise ParameterError(name, "non-finite values", "initial states must be finite")
    if np.any(m0 <= 0):
        raise ParameterError("m0", float(m0.min()), "masses must be > 0 (kg)")
    return r0, v0, m0


def check_m_dry(m_dry: float, m0: np.ndarray) -> float:
    """Validate the dry mass against the initial masses: finite, > 0 and < every m0."""
    try:
        m_dry = float(m_dry)
    except (TypeError, ValueError):
        raise ParameterError("m_dry", m_dry, "must be a number (kg)") from None
    if not (np.isfinite(m_dry) and m_dry > 0):
        raise ParameterError("m_dry", m_dry, "must be a finite number > 0 (kg)")
    if np.any(m0 <= m_dry):
        raise ParameterError("m_dry", m_dry, "must be < every initial mass m0 (smallest m0 = "
                             f"{float(np.min(m0)):g} kg)")
    return m_dry


def check_options(*, law: str, disturbance: str, thrust_limit: float | None, limit: str,
                  dt: float | None, t_max: float, eps: float | None, drag: str,
                  guidance_drag: str | None, isp: float, land_tol: tuple[float, float],
                  stop: str) -> tuple[float, float]:
    """Validate the options shared by the batch and reference simulators; return (dt, eps)."""
    get_law(law)
    if disturbance not in KIND_CODE:
        raise ParameterError("disturbance", disturbance,
                             f"must be one of {', '.join(KIND_CODE)}")
    LimitOptions(thrust_limit=thrust_limit, kind=limit)
    dt = DT_DEFAULT if dt is None else dt
    positive("dt", dt, "s")
    positive("t_max", t_max, "s")
    if dt > t_max:
        raise ParameterError("dt", dt, f"must be <= t_max = {t_max} s")
    eps = EPS_DEFAULT if eps is None else eps
    positive("eps", eps, "m or m/s")
    check_drag(drag)
    if guidance_drag is not None:
        check_drag(guidance_drag, "guidance_drag")
    exhaust_velocity(isp)
    StoppingOptions(stop=stop, t_max=t_max, land_tol=tuple(land_tol), m_dry=M_DRY)
    return float(dt), float(eps)


def simulate_batch(r0: np.ndarray, v0: np.ndarray, m0: np.ndarray, gains: Gains, *,
                   law: str = "corrected", disturbance: str = "none",
                   dist_amplitude: float | np.ndarray | None = None,
                   thrust_limit: float | None = None, limit: str = "axis",
                   dt: float | None = None, t_max: float = T_MAX_DEFAULT,
                   eps: float | None = None, seed: int = 0, drag: str = "physical",
                   isp: float = ISP, land_tol: tuple[float, float] = LAND_TOL,
                   record: bool = False, progress: bool = False,
                   guidance_drag: str | None = None, stop: str = "landing",
                   case_offset: int = 0, dist_spec: DisturbanceSpec | None = None,
                   chunk: int = DEFAULT_CHUNK, parallel: bool = True,
                   m_dry: float = M_DRY, method: str = "rk4", rtol: float = DOPRI_RTOL,
                   atol: float = DOPRI_ATOL, max_step: float = DOPRI_MAX_STEP,
                   max_steps: int = DOPRI_MAX_STEPS,
                   blowup_accel: float | None = None) -> BatchResult:
    """Fly N cases of seed 000's closed loop with RK4 or dopri5 (see the module docstring).

    The keyword front of ``simulate`` (which takes option objects): it validates the keywords,
    builds ``IntegrationOptions``, ``StoppingOptions``, ``LimitOptions`` and the disturbance,
    and calls it.

    r0, v0 (N, 3) m and m/s in the landing-site frame, m0 (N,) kg (or one value for all).
    law: a name in ``lgw.sim.mars.laws.LAWS``; gains: the sliding-surface gain set (also
      defines s2 for diagnostics and the worst-case disturbance; super-twisting ignores it
      otherwise).
    disturbance: "none" | "sin" | "random" | "worst" with amplitude ``dist_amplitude`` (m/s^2,
      scalar or per axis; default 20 = seed 000 (47)); ``seed`` and ``case_offset`` place the
      cases in a campaign so that random disturbances do not depend on chunking.
    thrust_limit (N) with limit "axis" (each |F_i|) or "norm" (|F|); None: unlimited.
    drag: plant drag model ("physical", "printed", "none"); guidance_drag: the a_m the law
      cancels (default: the same model as the plant).
    dt: RK4 step (default ``lgw.sim.mars.parameters.DT_DEFAULT``); eps: sliding band (default
      ``EPS_DEFAULT``); t_max: horizon; land_tol: (|r| m, |v| m/s); stop: "landing" ends each
      case at landing, "t_max" keeps integrating (to observe chattering / s1, s2 after landing).
    record=True adds ``trajectory`` = {t (S,), r (N,S,3), v (N,S,3), m (N,S), F (N,S,3)}, NaN
    after a case stopped.  progress=True shows a rich progress bar over chunks of ``chunk``.
    parallel=False runs the cases on one thread (threads over pieces of a chunk otherwise).
    m_dry: dry mass (kg, default lgw.theory.mars.parameters.M_DRY = 1505), > 0 and < every m0;
      a case whose mass reaches it is ``fuel_exhausted`` (not landed if before landing) and,
      with stop="landing", ends there (see the module docstring for stop="t_max").
    method: "rk4" (fixed step dt, the default) or "dopri5" (adaptive Dormand-Prince 5(4) with
      error control rtol, atol as scipy's RK45; dt is the first step, max_step caps the step;
      a case that needs more than max_steps attempts is flagged ``step_limit`` and stops there).
      ``steps`` holds the accepted steps per case.  record=True needs method="rk4".
    blowup_accel: a commanded acceleration above it (m/s^2) ends the case as
      ``command_blown_up`` (default ``BLOWUP_ACCEL``; inf: only a non-finite command does, as
      the bound checks with unlimited thrust need).
    """
    r0, v0, m0 = _check_states(r0, v0, m0)
    m_dry = check_m_dry(m_dry, m0)
    dt, eps = check_options(law=law, disturbance=disturbance, thrust_limit=thrust_limit,
                            limit=limit, dt=dt, t_max=t_max, eps=eps, drag=drag,
                            guidance_drag=guidance_drag, isp=isp, land_tol=land_tol, stop=stop)
    integration = IntegrationOptions(method=method, dt=dt, rtol=rtol, atol=atol,
                                     max_step=max_step, max_steps=max_steps, record=record)
    stopping = StoppingOptions(stop=stop, t_max=float(t_max), land_tol=tuple(land_tol),
                               m_dry=m_dry, blowup_accel=blowup_accel)
    limits = LimitOptions(thrust_limit=thrust_limit, kind=limit)
    n = r0.shape[0]
    if dist_spec is None:
        dist_spec = make_disturbance(disturbance, n, amplitude=dist_amplitude, seed=seed,
                                     case_offset=case_offset)
    elif dist_spec.coef.shape[0] != n or dist_spec.kind != disturbance:
        raise ParameterError("dist_spec", dist_spec.kind, f"must be a {disturbance!r} spec "
                             f"for {n} cases")
    res = simulate(r0, v0, m0, gains, integration=integration, stopping=stopping,
                   limits=limits, law=law, dist=dist_spec, drag=drag,
                   guidance_drag=guidance_drag, isp=isp, eps=eps, chunk=chunk,
                   parallel=parallel, progress=progress)
    res.info["seed"] = seed
    return res


def simulate(r0: np.ndarray, v0: np.ndarray, m0: np.ndarray, gains: Gains, *,
             integration: IntegrationOptions = INTEGRATION,
             stopping: StoppingOptions | None = None,
             limits: LimitOptions = LimitOptions(), law: str = "corrected",  # noqa: B008
             dist: DisturbanceSpec | None = None, drag: str = "physical",
             guidance_drag: str | None = None, isp: float = ISP, eps: float = EPS_DEFAULT,
             chunk: int = DEFAULT_CHUNK, parallel: bool = True,
             progress: bool = False) -> BatchResult:
    """Fly N cases of seed 000's closed loop with option objects (``lgw.sim.options``):
    ``stopping`` defaults to ``stopping_defaults()``, ``dist`` to no disturbance.  The
    integrator is ``lgw.sim.integrate`` with the hooks of ``lgw.sim.mars.kernel``."""
    r0, v0, m0 = _check_states(r0, v0, m0)
    stopping = stopping_defaults() if stopping is None else stopping
    stopping.check_masses(m0)
    check_drag(drag)
    if guidance_drag is not None:
        check_drag(guidance_drag, "guidance_drag")
    positive("eps", eps, "m or m/s")
    if integration.dt > stopping.t_max:
        raise ParameterError("dt", integration.dt, f"must be <= t_max = {stopping.t_max} s")
    n = r0.shape[0]
    dist = make_disturbance("none", n) if dist is None else dist
    spec = get_law(law)
    t_max = stopping.t_max
    O = integrate.integration_tuple(integration, t_max)  # noqa: N806
    kind = dist.kind
    dkind = KIND_CODE[kind]
    if dkind == KIND_CODE["sin"]:  # A sin(t) = the "random" form with c = A, w = 1, phase 0
        dkind = KIND_CODE["random"]
        dist = DisturbanceSpec("random", dist.amplitude,
                               np.tile(dist.amplitude[None, :, None], (n, 1, 1)),
                               np.ones((n, 3, 1)), np.zeros((n, 3, 1)))
    C = (r0, v0, m0, np.ascontiguousarray(dist.coef, float),  # noqa: N806
         np.ascontiguousarray(dist.omega, float), np.ascontiguousarray(dist.phase, float))
    gkind = DRAG_CODE[drag if guidance_drag is None else guidance_drag]
    Q = (np.ascontiguousarray(spec.param_values(gains), float),  # noqa: N806
         np.ascontiguousarray(surface_params(gains), float), G_MARS.astype(float),
         AREA.astype(float), DRAG_CODE[drag], gkind, exhaust_velocity(isp), limits.fmax,
         limits.code, dkind, np.asarray(dist.amplitude, float), float(eps),
         stopping.land_tol[0], stopping.land_tol[1], stopping.stop == "landing",
         float(stopping.m_dry),
         BLOWUP_ACCEL if stopping.blowup_accel is None else float(stopping.blowup_accel))

    C, Q = integrate.kernel_args(C), integrate.kernel_args(Q)  # noqa: N806
    out = {k: np.empty((n, 3)) for k in VECTOR_FIELDS}
    out.update({k: np.empty(n) for k in ("landing_time", "fuel", "time_saturated",
                                         "min_altitude", "contact_time")})
    out.update({k: np.zeros(n, bool) for k in ("landed", "ground_contact", "fuel_exhausted",
                                               "contact", "below_surface")})
    out["blown_up"] = np.zeros(n)  # the kernel's code: 0, 1 too large, 2 not finite
    out.update(integrate.generic_outputs(n, mars_kernel.NY))
    R = tuple(out[k] for k in mars_kernel.RESULT_FIELDS)  # noqa: N806
    G = tuple(out[k] for k in integrate.GENERIC_FIELDS)  # noqa: N806
    record = integration.record
    shape_rec = (n, O[2] + 1) if record else (1, 1)
    rec_y = np.full(shape_rec + (mars_kernel.NY,), np.nan)
    rec_x = np.full(shape_rec + (mars_kernel.NX,), np.nan)

    kernel = mars_kernel.kernel_module(law).kernel
    notice = CompileNotice(kernel, f"the mars/{law} kernel", expected="~10-20 s")

    def run(sl: slice) -> None:
        integrate.run_chunk(kernel, sl, C, Q, R, O, G, rec_y, rec_x, parallel)

    with notice:
        executors.run_local(run, n, chunk, progress=progress)

    # a command that was not finite is also a non-finite value (the state stays finite: the
    # step that made it was not accepted); one outcome per case all the same (outcomes())
    code = out["blown_up"]
    out["nonfinite"] |= code == 2.0
    out["blown_up"] = code > 0.0
    traj = None
    if record:
        dt = integration.dt
        traj = {"t": np.arange(O[2] + 1) * dt, "r": rec_y[..., :3], "v": rec_y[..., 3:6],
                "m": rec_y[..., 6], "F": rec_x[..., :3]}
    lim = limits.thrust_limit
    rtol, atol = integration.rtol, integration.atol
    info = {"law": law, "disturbance": kind,
            "dist_amplitude": np.asarray(dist.amplitude).tolist(),
            "thrust_limit": lim, "limit": limits.kind if lim is not None else None,
            "drag": drag, "guidance_drag": guidance_drag or drag, "isp": isp,
            "land_tol": list(stopping.land_tol), "t_max": t_max, "seed": None,
            # ground contact (lgw.sim.results): r_z below -contact_tol after a crossing of
            # r_z = 0; the landing position tolerance
            "contact_tol": stopping.land_tol[0],
            "stop": stopping.stop, "m_dry": stopping.m_dry,
            "integrator": (f"RK4 fixed step dt={integration.dt} s (numba)"
                           if integration.method == "rk4" else
                           f"Dormand-Prince 5(4) adaptive rtol={rtol} atol={atol} "
                           f"max_step={integration.max_step} s, first step {integration.dt} s "
                           "(numba)"),
            "boundary_layer": None}
    return BatchResult(eps=float(eps), dt=float(integration.dt), r0=r0, v0=v0, m0=m0,
                       trajectory=traj, info=info, **out)


def result_fields() -> tuple[str, ...]:
    return tuple(f.name for f in fields(BatchResult))


def warmup_kernels() -> list[tuple[str, Any]]:
    """The compiled kernels of seed 000, as (name, build): one per registered law (the
    integrator with the law inlined, ``lgw.sim.mars.kernel``), each built by flying one
    Table I case for 0.1 s through ``simulate_batch`` (the argument types of every run)."""
    from lgw.sim.mars.laws import LAWS
    from lgw.theory.mars.gains import default_gains
    from lgw.theory.mars.parameters import M0, R0, V0

    def build(law: str) -> None:
        simulate_batch(R0[None], V0[None], [M0], default_gains(), law=law, t_max=0.1,
                       dt=0.05, parallel=False)

    return [(f"mars/{law}", lambda law=law: build(law)) for law in LAWS]
