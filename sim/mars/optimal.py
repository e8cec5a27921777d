"""Fuel-optimal powered descent: the open-source stand-in for seed 000's GPOPS baseline.

Seed 000 (Part 1 of section IV) compares its guidance with an "offline fuel optimal guidance"
computed with GPOPS for tf = 30 s (212.9067 kg of fuel).  GPOPS and its settings are not
available, so the workbench solves the same problem as the second-order-cone program of

  [AP07]  B. Acikmese, S. R. Ploen, "Convex programming approach to powered descent guidance
          for Mars landing", JGCD 30(5), 2007;
  [BAS10] L. Blackmore, B. Acikmese, D. P. Scharf, "Minimum-landing-error powered-descent
          guidance for Mars landing using convex optimization", JGCD 33(4), 2010,

with cvxpy and the Clarabel interior-point conic solver.

Change of variables ([AP07], [BAS10]): u = F/m (thrust acceleration), sigma >= ||u||
(slack on its norm), z = ln m.  The rocket equation (13) of seed 000, m' = -||F|| / c with
c = Isp g_e, becomes z' = -alpha sigma, alpha = 1/c, which is linear.  The thrust bounds become

  upper, norm  ||F|| <= rho2 :  sigma <= rho2 e^{-z0} (1 - (z - z0))                  [AP07]
  upper, axis |F_i| <= Fmax :  |u_i| <= Fmax e^{-z0} (1 - (z - z0))          (this module)
  lower        ||F|| >= rho1 :  sigma >= rho1 e^{-z0} (1 - (z - z0) + (z - z0)^2 / 2)  [AP07]

The first-order expansion of the convex e^{-z} is a tangent, i.e. a lower bound, so both upper
bounds are conservative (the true thrust limit holds).  The second-order expansion used for the
lower bound over-estimates e^{-z} for z >= z0, which z >= z0 (enforced) guarantees, so it is
conservative too.  z0(t) = ln(m0 - alpha rho_max t) is the lightest possible mass [AP07]
(rho_max = rho2, or sqrt(3) Fmax for the axis limit), clipped at the dry mass.  Departure: the
upper-bound tangent is then moved to the previous solution's z (``refine`` passes, default
2), which keeps it conservative and removes most of its second-order gap.

Which case applies: with no lower bound (the default, as in seed 000 where no minimum thrust is
stated) the problem above is convex as is and sigma = ||u|| at the optimum simply because sigma is
minimised.  With ``thrust_min`` the bound rho1 <= ||F||, i.e. ||u|| >= rho1 e^{-z}, is a
non-convex annulus; it is made convex by imposing it on sigma (sigma >= rho1 e^{-z}, convex)
and relaxing ||u|| = sigma to ||u|| <= sigma; [AP07]'s lossless
convexification theorem says the relaxation is tight at the optimum (proved for a norm upper
bound; with the per-axis upper bound it is not covered by the theorem).  Either way the
solution is checked a posteriori: ``tightness`` = max_k (sigma_k - ||u_k||) / max_k sigma_k.

Discretisation (departures from [AP07], which uses a first-order-hold basis):
  * u is piecewise constant (zero-order hold) on n steps of dt = tf/n; position and velocity are
    propagated exactly (double integrator with constant gravity), so r, v at the nodes are exact
    for that acceleration profile;
  * on a step sigma is constant, so z_{k+1} = z_k - alpha sigma_k dt is the exact z dynamics;
  * the upper thrust bound is imposed with the step's initial (heaviest) mass z_k and the lower
    bound with its final (lightest) mass z_{k+1}, so the force flown on the step (below)
    satisfies both bounds on the whole step;
  * the force reported per step is the constant F_k = u_k m_k^log, where
    m_k^log = (m_k - m_{k+1}) / ln(m_k / m_{k+1}) is the logarithmic mean mass.  Flying that
    constant force for dt gives exactly the velocity change u_k dt and exactly the mass
    m_{k+1} (when sigma_k = ||u_k||), so an open-loop replay with force held constant per step
    (ZOH force, what a thruster command is) reproduces the nodes up to the O(dt^2) position
    difference between a constant force and a constant acceleration (millimetres).
  * altitude r_z >= 0 is enforced at the nodes (no subsurface flight); no glide-slope cone
    ([BAS10] optional constraint) because seed 000 states none.

Not in the convex model: Martian drag (12) (it is not convex in v) and the disturbance a_p; they
appear only in the open-loop replay (:func:`replay`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from lgw.sim.options import LIMITS
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import (
    G_EARTH,
    G_MARS,
    ISP,
    LAND_POS_TOL,
    LAND_VEL_TOL,
    M_DRY,
    THRUST_MAX_AXIS,
)

DISTURBANCES = ("none", "sin")
N_RANGE = (10, 2000)


@dataclass
class OptimalSolution:
    """A discretised fuel-optimal descent.

    t has n+1 nodes; r, v (n+1, 3) and m (n+1,) are the SOCP's states at the nodes; F (n, 3) is
    the constant force held on each step (see the module docstring for how it is built from u).
    fuel = m0 - m[-1] (kg).  tightness = max(sigma - ||u||) / max(sigma) (0 = the relaxation is
    exact).  status is cvxpy's ("optimal", "optimal_inaccurate", "infeasible", ...); the arrays
    are empty unless a solution exists.
    """

    status: str
    fuel: float
    t: np.ndarray
    r: np.ndarray
    v: np.ndarray
    m: np.ndarray
    F: np.ndarray
    solve_time: float
    tightness: float
    tf: float
    n: int
    u: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    sigma: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tightness_abs: float = math.nan
    settings: dict[str, Any] = field(default_factory=dict)

    @property
    def feasible(self) -> bool:
        return self.status in ("optimal", "optimal_inaccurate")

    @property
    def dt(self) -> float:
        return self.tf / self.n

    @property
    def peak_thrust(self) -> np.ndarray:
        """Largest |F_i| per axis (N), shape (3,)."""
        return np.abs(self.F).max(axis=0) if self.F.size else np.full(3, math.nan)

    @property
    def peak_thrust_norm(self) -> float:
        return float(np.linalg.norm(self.F, axis=1).max()) if self.F.size else math.nan

    def to_dict(self, arrays: bool = True) -> dict[str, Any]:
        out: dict[str, Any] = {
            "status": self.status,
            "tf": self.tf,
            "n": self.n,
            "dt": self.dt,
            "fuel_kg": self.fuel,
            "final_mass_kg": float(self.m[-1]) if self.m.size else math.nan,
            "solve_time_s": self.solve_time,
            "tightness_rel": self.tightness,
            "tightness_abs": self.tightness_abs,
            "peak_thrust_axis_N": [float(x) for x in self.peak_thrust],
            "peak_thrust_norm_N": self.peak_thrust_norm,
            "settings": self.settings,
        }
        if arrays:
            out.update({
                "t": self.t.tolist(), "r": self.r.tolist(), "v": self.v.tolist(),
                "m": self.m.tolist(), "F": self.F.tolist(),
            })
        return out


# --- input checks --------------------------------------------------------------------------


def _vec3(name: str, x: Any) -> np.ndarray:
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, x, "must be three finite numbers (x, y, z)") from None
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise ParameterError(name, x, "must be three finite numbers (x, y, z)")
    return a


def _positive(name: str, x: Any, valid: str) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float | np.floating | np.integer):
        raise ParameterError(name, x, valid)
    xf = float(x)
    if not math.isfinite(xf) or xf <= 0.0:
        raise ParameterError(name, x, valid)
    return xf


def _check(r0, v0, m0, tf, thrust_max, limit, thrust_min, n, isp, m_dry):
    r0 = _vec3("r0", r0)
    v0 = _vec3("v0", v0)
    if r0[2] < 0.0:
        raise ParameterError("r0", r0.tolist(), "altitude r0[2] must be >= 0 m")
    m_dry = _positive("m_dry", m_dry, "must be a finite number > 0 kg")
    m0 = _positive("m0", m0, f"must be a finite number > m_dry = {m_dry:g} kg")
    if m0 <= m_dry:
        raise ParameterError("m0", m0, f"must be a finite number > m_dry = {m_dry:g} kg")
    tf = _positive("tf", tf, "must be a finite number > 0 s")
    thrust_max = _positive("thrust_max", thrust_max, "must be a finite number > 0 N")
    if limit not in LIMITS:
        raise ParameterError("limit", limit,
                             "must be 'axis' (|F_i| <= Fmax) or 'norm' (||F|| <= Fmax)")
    rho_max = thrust_max * (math.sqrt(3.0) if limit == "axis" else 1.0)
    if thrust_min is not None:
        valid = f"must be None or a finite number in [0, {rho_max:g}) N (below the largest ||F||)"
        if isinstance(thrust_min, bool) or not isinstance(thrust_min, int | float | np.floating):
            raise ParameterError("thrust_min", thrust_min, valid)
        thrust_min = float(thrust_min)
        if not math.isfinite(thrust_min) or not 0.0 <= thrust_min < rho_max:
            raise ParameterError("thrust_min", thrust_min, valid)
        if thrust_min == 0.0:
            thrust_min = None
    if (isinstance(n, bool) or not isinstance(n, int | np.integer)
            or not N_RANGE[0] <= n <= N_RANGE[1]):
        raise ParameterError("n", n, f"must be an integer in [{N_RANGE[0]}, {N_RANGE[1]}]")
    isp = _positive("isp", isp, "must be a finite number > 0 s")
    return r0, v0, float(m0), tf, thrust_max, limit, thrust_min, int(n), isp, m_dry, rho_max


# --- the SOCP ------------------------------------------------------------------------------


def _log_mean(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(a - b) / ln(a / b), = a when a == b (the mass that converts u to a constant force)."""
    out = np.array(a, dtype=float)
    d = ~np.isclose(a, b, rtol=1e-13, atol=0.0)
    out[d] = (a[d] - b[d]) / np.log(a[d] / b[d])
    return out


def _zoh_force_correction(u: np.ndarray, m: np.ndarray, dt: float) -> np.ndarray:
    """Position increment of a constant force minus that of a constant acceleration, per step.

    Holding F_k = u_k m_k^log for dt while the mass falls linearly from m_k to m_{k+1} gives the
    velocity change u_k dt exactly but a position change F_k dt^2 phi(x) / m_k with
    x = 1 - m_{k+1}/m_k and phi(x) = (x + (1 - x) ln(1 - x)) / x^2 (= 1/2 + x/6 + ...), instead
    of u_k dt^2 / 2.  The difference is O(dt^3) per step (millimetres), but it is what makes the
    SOCP's nodes match an open-loop flight of its force profile.
    """
    m0, m1 = m[:-1], m[1:]
    x = 1.0 - m1 / m0
    small = x < 1e-4
    xs = np.where(small, 0.5, x)  # placeholder where the series is used
    phi = np.where(small, 0.5 + x / 6.0 + x * x / 12.0,
                   (xs + (1.0 - xs) * np.log1p(-xs)) / (xs * xs))
    factor = _log_mean(m0, m1) / m0 * phi - 0.5
    return u * (dt * dt * factor)[:, None]


def solve_fuel_optimal(
    r0: Any,
    v0: Any,
    m0: float,
    tf: float,
    *,
    thrust_max: float = THRUST_MAX_AXIS,
    limit: str = "axis",
    thrust_min: float | None = None,
    n: int = 80,
    isp: float = ISP,
    m_dry: float = M_DRY,
    g: Any = G_MARS,
    refine: int = 2,
) -> OptimalSolution:
    """Minimum-fuel descent from (r0, v0, m0) to r = v = 0 at exactly tf ([AP07]'s problem).

    thrust_max is per axis (limit="axis", seed 000 Part 3: |F_i| <= 50 kN) or on the norm
    (limit="norm", [AP07]'s rho2); thrust_min is a lower bound on ||F|| ([AP07]'s rho1), None for
    none.  Isp defaults to 225 s ([AP07]; seed 000 does not state it) and m_dry to 1505 kg
    ([AP07]).  g is the constant gravity (seed 000 Table I).  refine: number of extra solves,
    each re-linearising the upper bound about the last z and updating the constant-force
    position correction (module docstring); 2 makes both converge to ~1e-9.  Infeasible flight
    times return status "infeasible" (no exception): that is what :func:`min_time` searches on.
    """
    import cvxpy as cp  # local: importing cvxpy costs ~1 s and most of sim does not need it

    (r0, v0, m0, tf, thrust_max, limit, thrust_min, n, isp, m_dry,
     rho_max) = _check(r0, v0, m0, tf, thrust_max, limit, thrust_min, n, isp, m_dry)
    g = _vec3("g", g)
    if isinstance(refine, bool) or not isinstance(refine, int) or not 0 <= refine <= 5:
        raise ParameterError("refine", refine, "must be an integer in [0, 5]")
    alpha = 1.0 / (isp * G_EARTH)
    dt = tf / n
    t = np.linspace(0.0, tf, n + 1)
    settings = {
        "thrust_max_N": thrust_max, "limit": limit, "thrust_min_N": thrust_min,
        "isp_s": isp, "g_e": G_EARTH, "m_dry_kg": m_dry, "m0_kg": m0,
        "r0": r0.tolist(), "v0": v0.tolist(), "g": g.tolist(), "n": n, "dt": dt,
        "refine": refine,
        "case": ("lossless convexification (lower thrust bound, ||u|| <= sigma relaxed)"
                 if thrust_min else "convex as is (no lower thrust bound)"),
        "solver": "CLARABEL",
    }
    if thrust_min and alpha * thrust_min * tf >= m0 - m_dry:
        # The minimum thrust alone burns the whole propellant before tf: infeasible, and the
        # heaviest-mass profile below would take the log of a mass <= 0 (NaN problem data).
        settings["infeasible_reason"] = (
            f"the minimum thrust {thrust_min:g} N alone burns {alpha * thrust_min * tf:.6g} kg "
            f"in tf = {tf:g} s, more than the {m0 - m_dry:.6g} kg of propellant")
        e2 = np.zeros((0, 3))
        return OptimalSolution("infeasible", math.nan, t, e2, e2, np.zeros(0), e2, 0.0,
                               math.nan, tf, n, settings=settings)
    # Lightest possible mass profile [AP07]: full thrust from t = 0, never below the dry mass.
    z_lo = np.log(np.maximum(m0 - alpha * rho_max * t, m_dry))
    # Heaviest: minimum thrust all along (m0 when there is no lower bound; > m_dry, above).
    z_hi = np.log(m0 - alpha * (thrust_min or 0.0) * t)

    # Scaled unknowns keep the conic solver well conditioned: km for r, 100 m/s for v.
    R, V = 1000.0, 100.0
    rs = cp.Variable((n + 1, 3))
    vs = cp.Variable((n + 1, 3))
    z = cp.Variable(n + 1)
    u = cp.Variable((n, 3))
    sigma = cp.Variable(n)
    # Tangent of Fmax e^{-z} at z_ref: c0 - c1 z with c1 = Fmax e^{-z_ref}, c0 = c1 (1 + z_ref)
    # (two parameters, so the problem is DPP and re-solves skip recompilation).
    c0 = cp.Parameter(n + 1)
    c1 = cp.Parameter(n + 1, nonneg=True)
    r, v = R * rs, V * vs

    cons = [rs[0] == r0 / R, vs[0] == v0 / V, z[0] == math.log(m0),
            rs[n] == 0.0, vs[n] == 0.0]
    acc = u + np.ones((n, 1)) @ g.reshape(1, 3)
    delta = cp.Parameter((n, 3))  # constant-force position correction, from the last pass
    cons += [v[1:] == v[:-1] + dt * acc,
             r[1:] == r[:-1] + dt * v[:-1] + 0.5 * dt * dt * acc + delta,
             z[1:] == z[:-1] - alpha * dt * sigma,
             cp.norm(u, 2, axis=1) <= sigma,
             z >= z_lo, z <= z_hi, z[n] >= math.log(m_dry),
             r[:, 2] >= 0.0]
    lin = c0[:n] - cp.multiply(c1[:n], z[:n])  # step's heaviest mass z_k
    if limit == "axis":
        cons += [cp.abs(u[:, i]) <= lin for i in range(3)]
    else:
        cons += [sigma <= lin]
    if thrust_min:
        dz = z[1:] - z_lo[1:]  # step's lightest mass z_{k+1}; dz >= 0 by z >= z_lo
        mu1 = thrust_min * np.exp(-z_lo[1:])
        cons += [sigma >= cp.multiply(mu1, 1.0 - dz + 0.5 * cp.square(dz))]
    prob = cp.Problem(cp.Maximize(z[n]), cons)

    def _failed(status: str, elapsed: float) -> OptimalSolution:
        e2 = np.zeros((0, 3))
        return OptimalSolution(status, math.nan, t, e2, e2, np.zeros(0), e2, elapsed,
                               math.nan, tf, n, settings=settings)

    def _tangent(zr: np.ndarray) -> None:
        c1.value = thrust_max * np.exp(-zr)
        c0.value = c1.value * (1.0 + zr)

    _tangent(z_lo)
    delta.value = np.zeros((n, 3))
    elapsed = solver_time = 0.0
    for _ in range(refine + 1):
        t0 = time.perf_counter()
        try:
            prob.solve(solver=cp.CLARABEL)
        except cp.error.SolverError:
            return _failed("solver_error", elapsed + time.perf_counter() - t0)
        elapsed += time.perf_counter() - t0
        solver_time += float(prob.solver_stats.solve_time or 0.0)
        if prob.status not in ("optimal", "optimal_inaccurate"):
            return _failed(str(prob.status), elapsed)
        # Re-linearise the upper bound about this solution (still a tangent, still
        # conservative) and update the constant-force position correction.
        _tangent(np.array(z.value))
        delta_used = np.array(delta.value)
        delta.value = _zoh_force_correction(np.array(u.value), np.exp(np.array(z.value)), dt)

    uv = np.array(u.value)
    sv = np.array(sigma.value)
    # The mass follows from the SOCP's own exact dynamics z_{k+1} = z_k - alpha dt sigma_k from
    # m0, not from exp(z) as solved: the solver's residual (~1e-9 in z) would otherwise make the
    # fuel of a nearly free descent (a huge Isp) negative and the final mass exceed m0.  sigma
    # below 0 is solver noise (sigma >= ||u|| >= 0); the dry-mass floor holds z_n >= ln m_dry
    # to the solver's tolerance exactly.
    burn = alpha * dt * np.concatenate([[0.0], np.cumsum(np.maximum(sv, 0.0))])
    m = np.maximum(m0 * np.exp(-burn), m_dry)
    m[0] = m0
    fuel = float(min(-m0 * math.expm1(-burn[-1]), m0 - m_dry))
    unorm = np.linalg.norm(uv, axis=1)
    gap = float(np.max(sv - unorm))
    F = uv * _log_mean(m[:-1], m[1:])[:, None]
    # How far the last solve's correction is from the one its own u and m imply (m): the
    # remaining mismatch between the SOCP's nodes and a constant-force flight.
    settings["zoh_force_residual_m"] = float(np.abs(delta.value - delta_used).max())
    settings["solves"] = refine + 1
    settings["clarabel_time_s"] = solver_time  # the interior-point iterations only
    return OptimalSolution(
        status=str(prob.status), fuel=fuel, t=t,
        r=np.array(r.value), v=np.array(v.value), m=m, F=F, solve_time=elapsed,
        tightness=gap / max(float(sv.max()), 1e-12), tf=tf, n=n, u=uv, sigma=sv,
        tightness_abs=gap, settings=settings,
    )


@dataclass
class MinTimeResult:
    """Shortest feasible tf found by bisection on feasibility, and the solution there."""

    tf_min: float
    bracket: tuple[float, float]
    iterations: int
    solution: OptimalSolution
    history: list[tuple[float, str]]


def min_time(
    r0: Any,
    v0: Any,
    m0: float,
    *,
    thrust_max: float = THRUST_MAX_AXIS,
    limit: str = "axis",
    thrust_min: float | None = None,
    n: int = 80,
    isp: float = ISP,
    m_dry: float = M_DRY,
    tol: float = 0.02,
    tf_hi: float = 30.0,
    tf_max: float = 600.0,
    refine: int = 2,
) -> MinTimeResult:
    """Shortest tf for which :func:`solve_fuel_optimal` is feasible (bisection on feasibility).

    Feasibility in tf is an interval [tf_min, tf_fuel] (too short: the thrust limit cannot stop
    the lander; too long: the fuel runs out).  Find a feasible tf by scanning tf_hi, tf_hi/2,
    2 tf_hi, tf_hi/4, ... up to tf_max, halve it until infeasible (tf -> 0 always is: the lander
    cannot stop in no time), and bisect until the bracket is narrower than tol seconds.  The
    tf_min returned is the feasible end of the bracket (n fixed, so dt changes with tf).
    """
    tol = _positive("tol", tol, "must be a finite number > 0 s")
    tf_hi = _positive("tf_hi", tf_hi, "must be a finite number > 0 s")
    kw = dict(thrust_max=thrust_max, limit=limit, thrust_min=thrust_min, n=n, isp=isp,
              m_dry=m_dry, refine=refine)
    history: list[tuple[float, str]] = []

    def solve(tf: float) -> OptimalSolution:
        s = solve_fuel_optimal(r0, v0, m0, tf, **kw)
        history.append((tf, s.status))
        return s

    # Find a feasible tf: scan tf_hi, tf_hi/2, 2 tf_hi, tf_hi/4, 4 tf_hi, ... (the feasible
    # interval may lie below tf_hi when the fuel runs out, or above it when thrust is short).
    probes = [tf_hi]
    for k in range(1, 12):
        probes += [p for p in (tf_hi / 2**k, tf_hi * 2**k) if tol < p <= tf_max]
    best = None
    for p in probes:
        s = solve(p)
        if s.feasible:
            best, tf_hi = s, p
            break
    if best is None:
        raise ParameterError("r0/v0/m0", [np.asarray(r0, float).tolist(),
                                          np.asarray(v0, float).tolist(), m0],
                             f"no feasible flight time in ({tol:g}, {tf_max:g}] s")
    lo = max((t for t, _ in history if t < tf_hi), default=0.0)
    hi = tf_hi
    # Shrink the lower end fast first: halve until infeasible.
    probe = hi / 2.0
    while probe > max(lo, tol):
        s = solve(probe)
        if s.feasible:
            hi, best = probe, s
            probe /= 2.0
        else:
            lo = probe
            break
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        s = solve(mid)
        if s.feasible:
            hi, best = mid, s
        else:
            lo = mid
    return MinTimeResult(tf_min=hi, bracket=(lo, hi), iterations=len(history), solution=best,
                         history=history)


def max_time(
    r0: Any,
    v0: Any,
    m0: float,
    tf_feasible: float,
    tf_infeasible: float,
    *,
    tol: float = 0.02,
    **kw: Any,
) -> float:
    """Longest feasible tf between a feasible ``tf_feasible`` and an infeasible longer
    ``tf_infeasible`` (bisection on feasibility, to ``tol`` seconds; ``kw``: the keywords of
    :func:`solve_fuel_optimal`).  Past it the propellant runs out: hovering and braking cost
    fuel, and a lower thrust bound burns it whether needed or not.  Returns the feasible end
    of the final bracket."""
    tol = _positive("tol", tol, "must be a finite number > 0 s")
    lo, hi = float(tf_feasible), float(tf_infeasible)
    if not 0.0 < lo < hi:
        raise ParameterError("tf_infeasible", hi, f"must be > tf_feasible = {lo:g} s")
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if solve_fuel_optimal(r0, v0, m0, mid, **kw).feasible:
            lo = mid
        else:
            hi = mid
    return lo


# --- open-loop replay ----------------------------------------------------------------------


def replay(
    solution: OptimalSolution,
    disturbance: str = "none",
    *,
    amplitude: float = 1.0,
    drag: str = "none",
    coast: float = 300.0,
    rtol: float = 1e-10,
    atol: float = 1e-9,
    pos_tol: float = LAND_POS_TOL,
    vel_tol: float = LAND_VEL_TOL,
    ground_tol: float = 1e-3,
) -> dict[str, Any]:
    """Fly the optimal force profile open loop (ZOH: F_k held on [t_k, t_k+1)) in
    lgw.sim.mars.plant.

    disturbance "sin" adds seed 000's (47) a_p,i = amplitude sin t on every axis (amplitude 1 is
    Fig. 3's case, 20 is (47) as printed); drag "none" matches the convex model (the
    cross-check), "physical" / "printed" add (12).  Ground contact is altitude below
    -ground_tol.  Outcomes:

      landed   no ground contact before tf, ||r(tf)|| <= pos_tol and ||v(tf)|| <= vel_tol;
      crashed  ground contact before tf (phase "powered"), or, airborne at tf away from the
               target, ground contact after the profile ends and the engine is off (phase
               "coast", up to ``coast`` seconds after tf: an open-loop profile has nothing to
               fly after tf, which is how seed 000's Fig. 3(c) "collision" comes about);
      missed   still airborne ``coast`` s after tf.

    miss_distance and touchdown_speed are ||r||, ||v|| at touchdown (or at tf when landed);
    the state at tf is reported separately (r_tf, v_tf, miss_tf, speed_tf), and so is the
    lowest altitude while the profile is flown (min_altitude_powered; min_altitude includes the
    coast).  fuel_used is m0 - m(tf) (the coast burns nothing).
    """
    from lgw.sim.mars.plant import plant_rhs
    from scipy.integrate import solve_ivp

    if not isinstance(solution, OptimalSolution) or not solution.feasible:
        raise ParameterError("solution", getattr(solution, "status", solution),
                             "must be a feasible OptimalSolution")
    if disturbance not in DISTURBANCES:
        raise ParameterError("disturbance", disturbance, "must be 'none' or 'sin'")
    amp = float(amplitude)
    if not math.isfinite(amp) or amp < 0.0:
        raise ParameterError("amplitude", amplitude, "must be a finite number >= 0 m/s^2")
    coast = _positive("coast", coast, "must be a finite number > 0 s")
    isp = float(solution.settings["isp_s"])
    use_dist = disturbance == "sin" and amp > 0.0

    def ground(t, y):
        return y[2] + ground_tol
    ground.terminal = True
    ground.direction = -1

    def fly(F: np.ndarray, t0: float, t1: float, y0: np.ndarray):
        def rhs(t, s):
            return plant_rhs(t, s, F, drag=drag, isp=isp,
                             disturbance_accel=np.full(3, amp * math.sin(t)) if use_dist
                             else None)
        return solve_ivp(rhs, (t0, t1), y0, method="DOP853", rtol=rtol, atol=atol,
                         events=ground)

    y = np.concatenate([solution.r[0], solution.v[0], [solution.m[0]]])
    ts, ys, Fs = [np.array([0.0])], [y[:, None]], [solution.F[:1].T]
    contact: float | None = None
    phase = "powered"
    steps = [(solution.F[k], solution.t[k], solution.t[k + 1]) for k in range(solution.n)]
    y_tf: np.ndarray | None = None
    for j, (Fk, t0, t1) in enumerate(steps + [(np.zeros(3), solution.tf, solution.tf + coast)]):
        if j == solution.n:  # the profile is over: at the target, or coast with the engine off
            y_tf = y.copy()
            if (np.linalg.norm(y[:3]) <= pos_tol and np.linalg.norm(y[3:6]) <= vel_tol):
                break
            phase = "coast"
        sol = fly(Fk, t0, t1, y)
        ts.append(sol.t[1:])
        ys.append(sol.y[:, 1:])
        Fs.append(np.repeat(Fk[:, None], sol.t.size - 1, axis=1))
        y = sol.y[:, -1]
        if sol.status == 1:
            contact = float(sol.t_events[0][0])
            break
    t_all = np.concatenate(ts)
    Y = np.concatenate(ys, axis=1)
    r_end, v_end = Y[:3, -1], Y[3:6, -1]
    if contact is not None:
        outcome = "crashed"
    elif phase == "powered":
        outcome = "landed"
    else:
        outcome = "missed"
    out: dict[str, Any] = {
        "disturbance": disturbance, "amplitude": amp if disturbance == "sin" else 0.0,
        "drag": drag, "outcome": outcome, "landed": outcome == "landed",
        "phase": phase if outcome == "crashed" else None,
        "contact_time": contact, "t_end": float(t_all[-1]),
        "r_end": r_end.tolist(), "v_end": v_end.tolist(),
        "miss_distance": float(np.linalg.norm(r_end)),
        "horizontal_miss": float(np.linalg.norm(r_end[:2])),
        "touchdown_speed": float(np.linalg.norm(v_end)),
        "min_altitude": float(Y[2].min()),
        "min_altitude_powered": float(Y[2][t_all <= solution.tf].min()),
        "fuel_predicted": solution.fuel,
    }
    if y_tf is not None:
        out.update({
            "r_tf": y_tf[:3].tolist(), "v_tf": y_tf[3:6].tolist(),
            "miss_tf": float(np.linalg.norm(y_tf[:3])),
            "speed_tf": float(np.linalg.norm(y_tf[3:6])),
            "fuel_used": float(solution.m[0] - y_tf[6]),
            "node_error_r": float(np.linalg.norm(y_tf[:3] - solution.r[-1])),
            "node_error_v": float(np.linalg.norm(y_tf[3:6] - solution.v[-1])),
        })
    else:
        out.update({"r_tf": None, "v_tf": None, "miss_tf": math.nan, "speed_tf": math.nan,
                    "fuel_used": float(solution.m[0] - Y[6, -1]),
                    "node_error_r": math.nan, "node_error_v": math.nan})
    out["trajectory"] = {"t": t_all, "r": Y[:3].T, "v": Y[3:6].T, "m": Y[6],
                         "F": np.concatenate(Fs, axis=1).T}
    return out
