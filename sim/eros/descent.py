"""The whole Eros descent, batched: from seed 002's initial state to touchdown on the shape model.

``simulate_descent`` flies cases of the descent profile (lgw.theory.eros.descent: the paper's
cubic (8)-(10), then a terminal cubic to the touchdown site nearest Table 1's landing position,
then straight down at the touchdown speed) with the compiled kernel of
``lgw.sim.eros.descent_kernel``: the shape model's gravity in the plant, the fitted two-point
model (2) in the controller, a thrust-limited probe burning propellant, solar radiation
pressure as an unknown disturbance, optional navigation errors, and contact with the shape
model located inside the step.  ``reference_solve_descent`` is the independent route for one
case: the same sampled controller written with numpy (the generated numpy law of
lgw.sim.eros.laws), solve_ivp (DOP853) between samples with the exact polyhedron at every
evaluation, and the contact found by solve_ivp's event location on the solid-angle sum.

Outcomes (``OUTCOMES``; the names follow the workbench's shared vocabulary): every case ends in
exactly one, the first that happened, with its time:

  "landed"                contact with the shape model at a speed relative to the surface of
                          at most ``land_speed`` (m/s); time: the located contact;
  "crashed"               contact faster than that; time: the located contact (the impact
                          speed is reported);
  "propellant_exhausted"  the mass reached the dry mass before any contact; time: located;
  "nonfinite"             the command or the state became NaN / inf; time: the sample (command)
                          or the start of the sample interval (state);
  "step_limit"            dopri5 ran out of attempts;
  "horizon"               none of these by the reference's touchdown time + t_after.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from lgw.sim.eros import descent_kernel as DK
from lgw.sim.eros import laws as SL
from lgw.theory.eros import descent as TD
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains, gains_from_dict
from lgw.theory.errors import ParameterError

OUTCOMES = ("landed", "crashed", "propellant_exhausted", "nonfinite", "step_limit", "horizon")
PLANT_GRAVITY = tuple(DK.GRAVITY_CODE)  # "two-point", "polyhedron-exact", "none", "polyhedron"
CONTROLLER_GRAVITY = tuple(DK.CTRL_GRAVITY_CODE)


def _positive(name: str, v: Any, unit: str, allow_inf: bool = False, allow_zero: bool = False
              ) -> None:
    ok = isinstance(v, int | float | np.integer | np.floating) and not isinstance(v, bool)
    if ok:
        ok = (v >= 0 if allow_zero else v > 0) and (math.isfinite(v) or (allow_inf and v > 0))
    if not ok:
        raise ParameterError(name, v, f"must be a {'' if allow_inf else 'finite '}number "
                             f"{'>= 0' if allow_zero else '> 0'} ({unit})")


@dataclass(frozen=True, kw_only=True)
class Probe:
    """The probe: wet mass at the start (kg), propellant (kg; dry mass = mass - propellant),
    thrust limit (N; inf: none) per axis ("axis") or on the norm ("norm"), Isp (s; inf: no
    propellant is used).  Defaults: lgw.theory.eros.parameters (sources there)."""

    mass: float = P.PROBE_MASS
    propellant: float = P.PROPELLANT
    thrust_max: float = P.THRUST_MAX
    limit: str = "axis"
    isp: float = P.ISP

    def __post_init__(self) -> None:
        _positive("mass", self.mass, "kg")
        _positive("propellant", self.propellant, "kg")
        if not self.propellant < self.mass:
            raise ParameterError("propellant", self.propellant, f"must be < mass = {self.mass} kg")
        _positive("thrust_max", self.thrust_max, "N", allow_inf=True)
        _positive("isp", self.isp, "s", allow_inf=True)
        if self.limit not in DK.LIMIT_CODE:
            raise ParameterError("limit", self.limit, "one of " + ", ".join(DK.LIMIT_CODE))

    @property
    def m_dry(self) -> float:
        return self.mass - self.propellant

    @property
    def u_max(self) -> float:
        """The acceleration limit at the start (m/s^2)."""
        return self.thrust_max / self.mass


@dataclass(frozen=True, kw_only=True)
class Navigation:
    """Navigation error: each component of r and v is seen with a first-order Gauss-Markov
    error of standard deviation sigma_r (m) / sigma_v (m/s) and correlation time tau (s; the
    sampled process has phi = exp(-dt / tau)); seed picks the numbers (per case with the
    case's nav id).  sigma_r = sigma_v = 0: perfect navigation (the default)."""

    sigma_r: float = 0.0
    sigma_v: float = 0.0
    tau: float = P.NAV_TAU
    seed: int = 0

    def __post_init__(self) -> None:
        _positive("nav sigma_r", self.sigma_r, "m", allow_zero=True)
        _positive("nav sigma_v", self.sigma_v, "m/s", allow_zero=True)
        _positive("nav tau", self.tau, "s", allow_inf=True)
        if isinstance(self.seed, bool) or not isinstance(self.seed, int | np.integer) or \
                not 0 <= self.seed < 2**63:
            raise ParameterError("nav seed", self.seed, "must be an integer in [0, 2^63)")

    @property
    def on(self) -> bool:
        return self.sigma_r > 0 or self.sigma_v > 0

    @classmethod
    def typical(cls, seed: int = 0) -> Navigation:
        """The chosen error levels of lgw.theory.eros.parameters (NAV_*)."""
        return cls(sigma_r=P.NAV_SIGMA_R, sigma_v=P.NAV_SIGMA_V, tau=P.NAV_TAU, seed=seed)


@dataclass(frozen=True, kw_only=True)
class Environment:
    """Disturbances the controller does not know: solar radiation pressure srp (m/s^2) along
    the Sun's direction (sun0 at t = 0 in the body frame, fixed in inertial space), and the
    paper's sinusoid D_i = amp sin(freq t + phase_i + case phase) (amp = 0: off)."""

    srp: float = P.SRP_ACCEL
    sun0: tuple[float, float, float] = tuple(P.SUN_DIR0)
    amp: float = 0.0
    freq: float = P.DIST_FREQ
    phase: tuple[float, float, float] = tuple(P.DIST_PHASE)

    def __post_init__(self) -> None:
        _positive("srp", self.srp, "m/s^2", allow_zero=True)
        _positive("amp", self.amp, "m/s^2", allow_zero=True)
        s = np.asarray(self.sun0, float)
        if s.shape != (3,) or not np.all(np.isfinite(s)) or abs(np.linalg.norm(s) - 1) > 1e-9:
            raise ParameterError("sun0", self.sun0, "must be a unit 3-vector")


@dataclass(frozen=True, kw_only=True)
class DescentOptions:
    """What to fly and how.  law/switch: one of the six variants; dt: sampling (s); n_sub: RK4
    steps per sample (method "rk4") or dopri5 with rtol/atol; gravity: the plant's
    (PLANT_GRAVITY; "polyhedron" re-evaluated every lin_step m, "polyhedron-exact" at every
    evaluation); controller_gravity: the controller's model (CONTROLLER_GRAVITY); the probe,
    the navigation error and the environment; the profile (t_terminal s, v_touchdown m/s,
    cubic "exact" | "printed"); t0: start time on the profile (s); t_after: horizon after
    the reference's touchdown time (s); t_max: an earlier end of the horizon (absolute, s;
    None: none); land_speed: the landed / crashed threshold (m/s); stride: histories every
    stride samples (0: none)."""

    law: str = P.DESCENT_LAW[0]
    switch: str = P.DESCENT_LAW[1]
    dt: float = P.DESCENT_DT
    n_sub: int = 1
    method: str = "rk4"
    rtol: float = 1e-9
    atol: float = 1e-9
    gravity: str = "polyhedron"
    lin_step: float = P.LIN_STEP
    controller_gravity: str = "two-point"
    probe: Probe = field(default_factory=Probe)
    nav: Navigation = field(default_factory=Navigation)
    env: Environment = field(default_factory=Environment)
    t_terminal: float = P.T_TERMINAL
    v_touchdown: float = P.V_TOUCHDOWN
    cubic: str = "exact"
    t0: float = 0.0
    t_after: float = P.T_AFTER
    t_max: float | None = None
    land_speed: float = P.LAND_SPEED_MAX
    stride: int = 1

    def __post_init__(self) -> None:
        if (self.law, self.switch) not in SL.VARIANTS:
            raise ParameterError("law", f"{self.law}-{self.switch}", "one of " + ", ".join(
                SL.variant_name(*v) for v in SL.VARIANTS))
        for name, unit in (("dt", "s"), ("lin_step", "m"), ("t_terminal", "s"),
                           ("v_touchdown", "m/s"), ("t_after", "s"), ("land_speed", "m/s")):
            _positive(name, getattr(self, name), unit)
        _positive("t0", self.t0, "s", allow_zero=True)
        if self.t_max is not None:
            _positive("t_max", self.t_max, "s")
        for name, least in (("n_sub", 1), ("stride", 0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < least:
                raise ParameterError(name, v, f"must be an integer >= {least}")
        if self.method not in ("rk4", "dopri5"):
            raise ParameterError("method", self.method, "rk4 or dopri5")
        for name in ("rtol", "atol"):
            _positive(name, getattr(self, name), "tolerance")
        if self.rtol < 1e-13:
            raise ParameterError("rtol", self.rtol, "must be >= 1e-13 (double precision)")
        if self.gravity not in PLANT_GRAVITY:
            raise ParameterError("gravity", self.gravity, "one of " + ", ".join(PLANT_GRAVITY))
        if self.controller_gravity not in CONTROLLER_GRAVITY:
            raise ParameterError("controller_gravity", self.controller_gravity,
                                 "one of " + ", ".join(CONTROLLER_GRAVITY))
        if self.cubic not in ("exact", "printed"):
            raise ParameterError("cubic", self.cubic, "exact or printed")

    def profile(self) -> TD.Profile:
        return TD.descent_profile(self.t_terminal, self.v_touchdown, self.cubic)

    @property
    def t_end(self) -> float:
        """Absolute end of the horizon (s)."""
        end = self.profile().t_touchdown + self.t_after
        return end if self.t_max is None else min(end, self.t_max)


def descent_gains() -> Gains:
    """The chosen gains of the descent (lgw.theory.eros.parameters.DESCENT_GAINS)."""
    return gains_from_dict({"gains": dict(P.DESCENT_GAINS)})


@dataclass
class DescentResult:
    """Cases of a descent.  Histories (KR, cases, 3) at the sample times ``t`` (every
    ``stride`` samples; NaN after a case ended); per case: outcome (index into OUTCOMES), its
    time, the end state and the touchdown measures (NaN where there was no contact)."""

    t: np.ndarray
    pos: np.ndarray
    e: np.ndarray
    ed: np.ndarray
    u: np.ndarray
    u_cmd: np.ndarray
    s: np.ndarray
    dr: np.ndarray
    m: np.ndarray
    outcome: np.ndarray
    t_outcome: np.ndarray
    pos_end: np.ndarray
    vel_end: np.ndarray
    m_end: np.ndarray
    summary: dict[str, np.ndarray]
    touchdown: dict[str, np.ndarray]
    options: DescentOptions
    gains: Gains
    steps: np.ndarray

    @property
    def fuel(self) -> np.ndarray:
        """Propellant used (kg)."""
        return self.options.probe.mass - self.m_end

    def outcome_names(self) -> list[str]:
        return [OUTCOMES[int(c)] for c in self.outcome]

    def case(self, i: int) -> dict[str, Any]:
        """One case's numbers as plain Python values (the CLI's and the report's record)."""
        td = {k: (v[i].tolist() if np.ndim(v[i]) else float(v[i])) for k, v in
              self.touchdown.items()}
        return {"outcome": OUTCOMES[int(self.outcome[i])], "t_outcome": float(self.t_outcome[i]),
                "fuel_kg": float(self.fuel[i]), "m_end_kg": float(self.m_end[i]),
                "pos_end_m": self.pos_end[i].tolist(), "vel_end_m_s": self.vel_end[i].tolist(),
                "touchdown": td,
                "summary": {k: float(v[i]) for k, v in self.summary.items()}}


def initial_states(e0: np.ndarray, ed0: np.ndarray, opts: DescentOptions
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Positions and velocities: the profile at t0 plus the offsets (cases, 3)."""
    p, v, _ = opts.profile().evaluate(opts.t0)
    return p[None, :] + e0, v[None, :] + ed0


def _checked(e0, ed0) -> tuple[np.ndarray, np.ndarray]:
    e0 = np.atleast_2d(np.asarray(e0, float))
    ed0 = np.atleast_2d(np.asarray(ed0, float))
    if e0.ndim != 2 or e0.shape != ed0.shape or e0.shape[1] != 3:
        raise ParameterError("e0", e0.shape, "e0 and ed0 must both be (cases, 3)")
    if not (np.all(np.isfinite(e0)) and np.all(np.isfinite(ed0))):
        raise ParameterError("e0", "non-finite", "initial offsets must be finite")
    return e0, ed0


def _per_case(name: str, v, n: int, default: float, unit: str) -> np.ndarray:
    if v is None:
        v = default
    out = np.asarray(v, float).reshape(-1)
    if out.shape == (1,):  # one value for every case
        out = np.full(n, out[0])
    if out.shape != (n,) or not np.all(np.isfinite(out)):
        raise ParameterError(name, out.shape, f"must be {n} finite numbers ({unit})")
    return out


def _refuse_inside(pos: np.ndarray) -> None:
    from lgw.sim.eros.batch import in_body

    bad = np.flatnonzero(in_body(pos))
    if len(bad):
        raise ParameterError("e0", pos[bad[0]].tolist(), f"case {int(bad[0])} starts inside the "
                             "shape model of Eros (a start must be outside the surface)")


def simulate_descent(e0, ed0, g: Gains, opts: DescentOptions, *, case_phase=None, srp=None,
                     nav_ids=None, chunk: int = 64, parallel: bool = True) -> DescentResult:
    """Fly the descent for each case: initial offsets e0, ed0 (cases, 3) from the profile at
    opts.t0; case_phase (rad) of the sinusoid, srp (m/s^2, default opts.env.srp) and the nav
    ids (the navigation numbers' case counter, default 0..n-1) per case."""
    from lgw.sim import executors, integrate
    from lgw.sim.kernel_cache import CompileNotice
    from lgw.sim.options import IntegrationOptions

    e0, ed0 = _checked(e0, ed0)
    n = len(e0)
    cph = _per_case("case_phase", case_phase, n, 0.0, "rad")
    srp_c = _per_case("srp", srp, n, opts.env.srp, "m/s^2")
    if np.any(srp_c < 0):
        raise ParameterError("srp", float(srp_c.min()), "must be >= 0 (m/s^2)")
    ids = np.arange(n, dtype=np.int64) if nav_ids is None else np.asarray(nav_ids, np.int64)
    if ids.shape != (n,) or np.any(ids < 0):
        raise ParameterError("nav_ids", ids.shape, f"must be {n} integers >= 0")
    prof = opts.profile()
    pos0, vel0 = initial_states(e0, ed0, opts)
    _refuse_inside(pos0)
    t_span = opts.t_end - opts.t0
    if not t_span > 0:
        raise ParameterError("t0", opts.t0, f"must be < the horizon's end {opts.t_end:g} s")
    K = int(math.ceil(t_span / opts.dt - 1e-9))
    KR = K // opts.stride + 1 if opts.stride > 0 else 0
    pr, nv = opts.probe, opts.nav
    Q = DK.shared({
        "law": DK_LAW[opts.law], "switch": DK_SWITCH[opts.switch],
        "gains": np.array(SL.gain_values(g), float), "breaks": prof.breaks, "coef": prof.coef,
        "t0": float(opts.t0), "dt": float(opts.dt), "omega": float(P.OMEGA),
        "gravity": DK.GRAVITY_CODE[opts.gravity],
        "ctrl_gravity": DK.CTRL_GRAVITY_CODE[opts.controller_gravity],
        "p1": np.asarray(P.TWO_POINT_P1, float), "p2": np.asarray(P.TWO_POINT_P2, float),
        "gm": np.array(P.TWO_POINT_GM, float), "grho": float(P.G * P.DENSITY),
        "lin_step": float(opts.lin_step), "limit": DK.LIMIT_CODE[pr.limit],
        "fmax": float(pr.thrust_max), "ve": float(pr.isp * P.G0), "m_dry": float(pr.m_dry),
        "sun0": np.asarray(opts.env.sun0, float), "amp": float(opts.env.amp),
        "freq": float(opts.env.freq), "phase": np.asarray(opts.env.phase, float),
        "nav_on": nv.on, "sig_r": float(nv.sigma_r), "sig_v": float(nv.sigma_v),
        "phi_nav": float(math.exp(-opts.dt / nv.tau)), "seed": int(nv.seed),
        "stride": int(opts.stride)})
    R = (np.zeros(n, np.int64), np.full(n, np.nan), np.empty((n, 7)),
         np.zeros((n, DK.NSUM)), np.zeros(n, np.int64),
         *(np.full((n, KR, 3), np.nan) for _ in range(7)), np.full((n, KR), np.nan))
    io = IntegrationOptions(method=opts.method, dt=opts.dt, rtol=opts.rtol, atol=opts.atol,
                            max_step=opts.dt, max_steps=50 * K + 1000)
    O = integrate.integration_tuple(io, K * opts.dt, sample=(opts.dt, opts.n_sub))  # noqa: N806
    gout = integrate.generic_outputs(n, DK.NY)
    G = tuple(gout[k] for k in integrate.GENERIC_FIELDS)  # noqa: N806
    C = (pos0, vel0, np.full(n, float(pr.mass)), cph, ids, srp_c)
    C, Q = integrate.kernel_args(C), integrate.kernel_args(Q)  # noqa: N806
    kernel = DK.kernel_module().kernel
    empty = np.empty((1, 1, 1))
    with CompileNotice(kernel, "the eros descent kernel", "~20-40 s"):
        executors.run_local(lambda sl: integrate.run_chunk(kernel, sl, C, Q, R, O, G, empty,
                                                           empty, parallel), n, chunk)
    return _result(R, gout, opts, g, K, KR)


DK_LAW = {"pdsmc": 0, "ftsmc": 1, "fuzzy": 2}
DK_SWITCH = {"sign": 0, "tanh": 1}


def _result(R: tuple, gout: dict, opts: DescentOptions, g: Gains, K: int, KR: int
            ) -> DescentResult:
    code, tev, yend, summ, klast = R[:5]
    blew = gout["nonfinite"] & (code == DK.RUNNING)
    tev = tev.copy()
    tev[blew] = opts.t0 + klast[blew] * opts.dt
    pos_end, vel_end, m_end = yend[:, :3].copy(), yend[:, 3:6].copy(), yend[:, 6].copy()
    contact = code == DK.CONTACT
    td = touchdown_measures(pos_end, vel_end, contact)
    landed = contact & (td["speed"] <= opts.land_speed)
    out = np.select([landed, contact, code == DK.DRY, (code == DK.NONFINITE) | blew,
                     gout["step_limit"]], [0, 1, 2, 3, 4], default=5)
    t_out = np.where(out == 5, opts.t_end, tev)
    t_out = np.where(out == 4, opts.t0 + gout["t_end"], t_out)
    ts = opts.t0 + opts.dt * opts.stride * np.arange(KR) if KR else np.empty(0)

    def tr(a: np.ndarray) -> np.ndarray:  # (cases, KR, ...) -> (KR, cases, ...)
        return np.ascontiguousarray(np.moveaxis(a, 0, 1))

    return DescentResult(ts, *(tr(a) for a in R[5:13]), out, t_out, pos_end, vel_end, m_end,
                         {k: summ[:, j].copy() for j, k in enumerate(DK.SUMMARY)}, td, opts, g,
                         gout["steps"].copy())


def touchdown_measures(pos: np.ndarray, vel: np.ndarray, contact: np.ndarray
                       ) -> dict[str, np.ndarray]:
    """At each contact point (NaN elsewhere): the speed relative to the surface |v| (the frame
    rotates with the body), its components into the surface along the normal of the face hit
    and along the surface, the body-fixed latitude and longitude (deg), the face index, the
    contact point's distance to the mesh (m, a check of the location) and its distance to the
    profile's touchdown site (m)."""
    n = len(pos)
    out = {k: np.full(n, np.nan) for k in ("speed", "v_normal", "v_tangential", "lat_deg",
                                            "lon_deg", "face", "mesh_distance_m",
                                            "site_distance_m")}
    out["point_m"] = np.full((n, 3), np.nan)
    from lgw.theory.eros.polyhedron import eros_polyhedron

    normals = eros_polyhedron().normals
    site = TD.touchdown_site().point
    for i in np.flatnonzero(contact):
        q, f, d = TD.nearest_surface_point(pos[i])
        nrm = normals[f]
        v = vel[i]
        vn = float(-v @ nrm)
        out["speed"][i] = float(np.linalg.norm(v))
        out["v_normal"][i] = vn
        out["v_tangential"][i] = float(np.linalg.norm(v + vn * nrm))
        out["lat_deg"][i], out["lon_deg"][i] = TD.lat_lon(pos[i])
        out["face"][i] = f
        out["mesh_distance_m"][i] = d
        out["site_distance_m"][i] = float(np.linalg.norm(pos[i] - site))
        out["point_m"][i] = pos[i]
    return out


def landing_margin(res: DescentResult) -> np.ndarray:
    """Per case: land_speed - touchdown speed (m/s) for a case that touched the surface (>= 0:
    landed, < 0: crashed by that much), -inf for a case that never touched it (propellant
    exhausted, non-finite, step limit, horizon).  The property a verifier checks over the
    descent's envelope (``dispersions``): every case lands (margin >= 0); a violation is
    re-flown by ``reference_solve_descent``."""
    m = res.options.land_speed - res.touchdown["speed"]
    return np.where(np.isfinite(m), m, -np.inf)


def counts(outcome: np.ndarray) -> dict[str, int]:
    return {name: int(np.sum(np.asarray(outcome) == k)) for k, name in enumerate(OUTCOMES)}


# --- campaigns --------------------------------------------------------------------------------

def dispersions(n: int, seed: int, pos: float = P.DESCENT_MC_POS, vel: float = P.DESCENT_MC_VEL
                ) -> dict[str, np.ndarray]:
    """A Monte Carlo campaign's per-case inputs (seeded): offsets uniform in |e_i(0)| <= pos
    (m) and |e_i'(0)| <= vel (m/s) from the profile's start, the SRP acceleration for a
    reflectivity uniform in SRP_CR_RANGE (the nominal SRP_ACCEL is at 1.5), the sinusoid's phase
    and the navigation numbers' case ids 0..n-1."""
    rng = np.random.default_rng(seed)
    cr = rng.uniform(*P.SRP_CR_RANGE, n)
    return {"e0": rng.uniform(-pos, pos, (n, 3)), "ed0": rng.uniform(-vel, vel, (n, 3)),
            "srp": P.SRP_ACCEL * cr / 1.5, "case_phase": rng.uniform(0, 2 * np.pi, n),
            "nav_ids": np.arange(n, dtype=np.int64)}


# --- convergence -------------------------------------------------------------------------------

CONVERGENCE_KEYS = ("t_outcome", "speed", "fuel")
CONVERGENCE_TOL = 0.01  # relative (the 1 % on the numbers a report quotes)


def convergence(res: DescentResult, e0, ed0, **kw) -> dict[str, Any]:
    """The same cases re-flown with the step halved (RK4: 2 n_sub; dopri5: rtol and atol / 10):
    per case the relative change of the outcome time, touchdown speed and fuel, the outcome
    agreement, and ``converged`` (every change <= CONVERGENCE_TOL and the same outcome)."""
    o = res.options
    fine = (replace(o, n_sub=2 * o.n_sub, stride=0) if o.method == "rk4"
            else replace(o, rtol=o.rtol / 10, atol=o.atol / 10, stride=0))
    r2 = simulate_descent(e0, ed0, res.gains, fine, **kw)
    a = {"t_outcome": res.t_outcome, "speed": res.touchdown["speed"], "fuel": res.fuel}
    b = {"t_outcome": r2.t_outcome, "speed": r2.touchdown["speed"], "fuel": r2.fuel}
    rel = {}
    for k in CONVERGENCE_KEYS:
        with np.errstate(invalid="ignore", divide="ignore"):
            d = np.abs(a[k] - b[k]) / np.maximum(np.abs(b[k]), 1e-12)
        rel[k] = np.where(np.isnan(a[k]) & np.isnan(b[k]), 0.0, d)
    same = res.outcome == r2.outcome
    conv = same & np.all([np.nan_to_num(rel[k], nan=np.inf) <= CONVERGENCE_TOL
                          for k in CONVERGENCE_KEYS], axis=0)
    return {"check": "RK4 step halved" if o.method == "rk4" else "dopri5 tolerances / 10",
            "relative_change": rel, "same_outcome": same, "converged": conv,
            "tolerance": CONVERGENCE_TOL}


# --- the independent route -------------------------------------------------------------------

def reference_solve_descent(e0, ed0, g: Gains, opts: DescentOptions, *, case_phase: float = 0.0,
                            srp: float | None = None, nav_id: int = 0, rtol: float = 1e-10,
                            atol: float = 1e-9) -> dict[str, Any]:
    """One case by solve_ivp (DOP853) between the samples, the control held, the plant's
    gravity at every evaluation (the exact polyhedron for both "polyhedron" modes), the contact
    and the dry mass located by solve_ivp's events; the controller in numpy (generated numpy
    law, nav numbers from ``nav_normal_py``).  Returns the outcome name and time, the end
    state, fuel and the touchdown measures."""
    from lgw.sim.eros import plant as PL
    from lgw.sim.eros import polygrav as PG
    from lgw.sim.eros.navnoise import nav_normal_py
    from scipy.integrate import solve_ivp

    e0, ed0 = _checked(e0, ed0)
    prof = opts.profile()
    pos0, vel0 = initial_states(e0[:1], ed0[:1], opts)
    _refuse_inside(pos0)
    pr, nv, env = opts.probe, opts.nav, opts.env
    a_srp = env.srp if srp is None else float(srp)
    arrays = PG.eros_arrays()
    grho = P.G * P.DENSITY
    V, F = arrays[0], arrays[1]
    sun0 = np.asarray(env.sun0, float)
    ve = pr.isp * P.G0
    K = int(math.ceil((opts.t_end - opts.t0) / opts.dt - 1e-9))

    def plant_g(x: np.ndarray) -> np.ndarray:
        if opts.gravity in ("polyhedron", "polyhedron-exact"):
            return PG.field(x[None], arrays, grho)[0, :3]
        return PL.gravity(x[None], opts.gravity)[0]

    def ctrl_g(x: np.ndarray) -> np.ndarray:
        if opts.controller_gravity == "polyhedron":
            return PG.field(x[None], arrays, grho)[0, :3]
        return PL.gravity(x[None], opts.controller_gravity)[0]

    def disturbance(t: float) -> np.ndarray:
        c, s = math.cos(P.OMEGA * t), math.sin(P.OMEGA * t)
        sb = np.array([c * sun0[0] + s * sun0[1], -s * sun0[0] + c * sun0[1], sun0[2]])
        d = a_srp * sb
        if env.amp != 0.0:
            d = d + env.amp * np.sin(env.freq * t + np.asarray(env.phase) + case_phase)
        return d

    y = np.concatenate([pos0[0], vel0[0], [pr.mass]])
    nav = np.zeros(6)
    phi = math.exp(-opts.dt / nv.tau)
    gv = SL.gain_values(g)
    outcome, t_out = "horizon", opts.t_end
    for k in range(K + 1):
        tk = opts.t0 + k * opts.dt
        if nv.on:
            w = np.array([nav_normal_py(nv.seed, nav_id, k, j) for j in range(6)])
            sig = np.array([nv.sigma_r] * 3 + [nv.sigma_v] * 3)
            nav = sig * w if k == 0 else phi * nav + sig * math.sqrt(1 - phi * phi) * w
        rp, rv, ra = prof.evaluate(tk)
        xh, vh = y[:3] + nav[:3], y[3:6] + nav[3:]
        f = PL.rotating_terms(xh[None], vh[None])[0] + ctrl_g(xh)
        e, ed = xh - rp, vh - rv
        s = np.asarray(SL.surface_fn(opts.law)(e, ed, *gv), float) * np.ones(3)
        d = (SL.distance_fn()(s[0], s[1], s[2], g.alpha) if opts.law == "fuzzy" else 0.0)
        u = np.asarray(SL.control_fn(opts.law, opts.switch)(e, ed, f, 0.0, ra, d, *gv), float)
        u = u * np.ones(3)
        if not (np.all(np.isfinite(u)) and np.all(np.isfinite(s))):
            outcome, t_out = "nonfinite", tk
            break
        m = y[6]
        umax = pr.thrust_max / m
        if pr.limit == "norm":
            un = float(np.linalg.norm(u))
            if un > umax:
                u = u * (umax / un)
        else:
            u = np.clip(u, -umax, umax)
        Fh = m * u
        fn = float(np.linalg.norm(Fh)) if pr.limit == "norm" else float(np.abs(Fh).sum())
        if k == K:
            break

        def rhs(t, yy, Fh=Fh, fn=fn):
            acc = (PL.rotating_terms(yy[None, :3], yy[None, 3:6])[0] + plant_g(yy[:3])
                   + Fh / yy[6] + disturbance(t))
            return np.concatenate([yy[3:6], acc, [-fn / ve]])

        def contact(t, yy):
            return 2.0 * math.pi - PG.solid_angle_sum(yy[0], yy[1], yy[2], V, F)
        contact.terminal, contact.direction = True, -1

        def dry(t, yy):
            return yy[6] - pr.m_dry
        dry.terminal, dry.direction = True, -1
        sol = solve_ivp(rhs, (tk, tk + opts.dt), y, method="DOP853", rtol=rtol, atol=atol,
                        events=(contact, dry))
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            outcome, t_out = "nonfinite", tk
            break
        if sol.status == 1:
            if len(sol.t_events[0]):
                te, ye = sol.t_events[0][0], sol.y_events[0][0]
                outcome = "contact"
            else:
                te, ye = sol.t_events[1][0], sol.y_events[1][0]
                outcome = "propellant_exhausted"
            y, t_out = ye, float(te)
            break
        y = sol.y[:, -1]
    contact_ = outcome == "contact"
    td = touchdown_measures(y[None, :3], y[None, 3:6], np.array([contact_]))
    if contact_:
        outcome = "landed" if td["speed"][0] <= opts.land_speed else "crashed"
    return {"outcome": outcome, "t_outcome": t_out, "pos_end": y[:3], "vel_end": y[3:6],
            "m_end": float(y[6]), "fuel": float(pr.mass - y[6]),
            "touchdown": {k: v[0] for k, v in td.items()}}
