"""The tight reference: each case integrated by scipy's solve_ivp, for cross-checks.

Independent of ``lgw.sim.mars.batch`` on purpose: the law is ``theory``'s own numpy lambdification
(``lgw.sim.mars.laws.numpy_law``), the plant is ``lgw.sim.mars.plant.plant_rhs`` (numpy), landing
and band
crossings are solve_ivp events located by root finding on the dense output, and the
thrust metrics are sampled on a fine grid of the dense output.  Same options and the same
``BatchResult`` as ``simulate_batch``; slow (seconds per case).
"""

from __future__ import annotations

import numpy as np
from lgw.sim.mars.batch import (
    BLOWUP_ACCEL,
    LAND_TOL,
    BatchResult,
    _check_states,
    check_m_dry,
    check_options,
)
from lgw.sim.mars.disturbances import DisturbanceSpec, make_disturbance
from lgw.sim.mars.laws import get_law, numpy_law
from lgw.sim.mars.parameters import T_MAX_DEFAULT
from lgw.sim.mars.plant import drag_accel, plant_rhs, saturate
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.mss import surfaces_numeric
from lgw.theory.mars.parameters import G_MARS, ISP, M_DRY
from scipy.integrate import solve_ivp

REF_RTOL = 1e-10
REF_ATOL = 1e-10
REF_MAX_STEP = 0.1  # s; bounds the gap in which a band event could be missed
METRIC_GRID = 1e-3  # s, sampling of peak thrust, saturation time and altitude


class ClosedLoopRHS:
    """The closed loop of one case as a numpy function f(t, y) -> y' (also used by interop)."""

    def __init__(self, gains: Gains, *, law: str = "corrected", dist: DisturbanceSpec,
                 case: int = 0, thrust_limit: float | None = None, limit: str = "axis",
                 drag: str = "physical", guidance_drag: str | None = None,
                 isp: float = ISP, m0: float | None = None) -> None:
        self.P = get_law(law).param_values(gains)
        self.law = numpy_law(law)
        self.s2 = surfaces_numeric()[1]
        self.g = gains
        self.dist = dist
        self.case = case
        self.thrust_limit = thrust_limit
        self.limit = limit
        self.drag = drag
        self.gdrag = drag if guidance_drag is None else guidance_drag
        self.isp = isp
        # as lgw.sim.mars.batch: a command above BLOWUP_ACCEL m0 is blown up (None: no check)
        self.blow_force = None if m0 is None else BLOWUP_ACCEL * float(m0)

    def blown(self, y: np.ndarray, f: np.ndarray | None = None) -> bool:
        """The command at y (7,) is blown up: not finite, above BLOWUP_ACCEL m0, or asked at
        a mass <= 0 (lgw.sim.mars.batch.BLOWUP_ACCEL)."""
        if self.blow_force is None:
            return False
        f = self.force(y)[0] if f is None else f
        return not (float(np.linalg.norm(f)) <= self.blow_force and y[6] > 0)

    def s2_of(self, y: np.ndarray) -> np.ndarray:
        g = self.g
        return self.s2(y[:3], y[3:6], g.beta1, g.beta2, g.q1, g.q2)

    def _command(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        y = np.asarray(y, float)
        r, v, m = y[..., :3], y[..., 3:6], y[..., 6]
        with np.errstate(divide="ignore", invalid="ignore"):
            a = np.asarray(self.law(r, v, G_MARS, drag_accel(r, v, m, self.gdrag), m, self.P),
                           float)
        fu = np.asarray(m, float)[..., None] * a
        return saturate(fu, self.thrust_limit, self.limit), fu, a

    def force(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(F after the limit, F before) commanded at state y (7,), or at states y (..., 7)."""
        f, fu, _ = self._command(y)
        return f, fu

    def __call__(self, t: float, y: np.ndarray, ap_extra: np.ndarray | None = None
                 ) -> np.ndarray:
        f, fu, a = self._command(y)
        if self.blown(y, f):
            # a finite stand-in, no thrust (as the batch kernel): the solver either retries a
            # smaller step or meets the "blown" event, which ends the case where the command on
            # the solution reaches the threshold; this value is never part of a result
            f = np.zeros(3)
            fu = np.full(3, np.nan)  # never equal to f: no at-rest shortcut below
        ap = self.dist.accel(t, self.s2_of(y) if self.dist.kind == "worst" else None, self.case)
        if ap_extra is not None:
            ap = ap + ap_extra
        dy = plant_rhs(t, y, f, drag=self.drag, isp=self.isp, disturbance_accel=ap)
        r, v = y[:3], y[3:6]
        rest = (r == 0.0) & (v == 0.0) & (f == fu)
        if np.any(rest):
            # as lgw.sim.mars.kernel: an axis at rest on its target with its command unlimited
            # uses the law's a itself (exactly -g - a_m there), not (m a) / m
            dy[3:6] = np.where(rest, a + G_MARS + drag_accel(r, v, y[6], self.drag) + ap,
                               dy[3:6])
        return dy


class _NonFinite(Exception):  # noqa: N818  (control flow, not an error)
    """The closed-loop derivative is not finite at (t, y): the command is +-inf or NaN."""

    def __init__(self, t: float, y: np.ndarray) -> None:
        super().__init__(t)
        self.t = t
        self.y = y


def after_arrival(r: np.ndarray, v: np.ndarray, f: np.ndarray,
                  tol: tuple[float, float]) -> np.ndarray:
    """Per axis (3,), max |F_i| (N) over the samples from the first one with |r_i| <= tol[0]
    and |v_i| <= tol[1] on; NaN if there is none.  r, v, f: (K, 3) samples in time order."""
    band = (np.abs(r) <= tol[0]) & (np.abs(v) <= tol[1])
    out = np.full(3, np.nan)
    for ax in range(3):
        hit = np.flatnonzero(band[:, ax])
        if hit.size:
            out[ax] = float(np.max(np.abs(f[hit[0]:, ax])))
    return out


def unavoidable_contact(y: np.ndarray, g_z: float, a_max: float) -> float | None:
    """Time (s) to the ground crossing from state y (7,) if no thrust below ``a_max`` (m/s^2)
    can prevent it (descending, r_z >= 0 and r_z < v_z^2 / (2 a_max): the stopping distance at
    a_max exceeds the altitude), on the ballistic arc r_z + v_z tau + g_z tau^2 / 2 = 0; else
    None.  The corrected law's command diverges as r_z -> 0 with v_z != 0, so with unlimited
    thrust it blows up (lgw.sim.mars.batch.BLOWUP_ACCEL) just above the ground, within
    nanoseconds of an impact it can no longer change: that impact is the case's outcome, as
    in lgw.sim.mars.kernel.sys_step."""
    z, vz = float(y[2]), float(y[5])
    if not (z >= 0.0 and vz < 0.0 and 2.0 * a_max * z < vz * vz):
        return None
    return 2.0 * z / (-vz + np.sqrt(vz * vz - 2.0 * g_z * z))


def _start_row(rhs: ClosedLoopRHS, y0: np.ndarray, eps: float, landed0: bool, *,
               t: float = 0.0, y: np.ndarray | None = None, nonfinite: bool = False,
               blown: bool = False, land_tol: tuple[float, float] = LAND_TOL,
               below: bool = False, contact_at: tuple[float, np.ndarray] | None = None
               ) -> dict:
    """A case that ends without a solution: landed, below the ground or blown up at t = 0, or
    a derivative that became non-finite at (t, y) (solve_ivp cannot return a partial solution;
    see ``simulate_reference``): the state there and the t = 0 band entries.  Peaks: the
    as simulate_batch's, 0 (no step was flown); after arrival: the t = 0 command on the axes
    in their band unless it is blown up (as simulate_batch, NaN otherwise)."""
    y = y0 if y is None else y
    contact = contact_at is not None
    t_c, y_c = contact_at if contact else (np.nan, np.full(7, np.nan))
    after = np.full(3, np.nan)
    if not (blown or rhs.blown(y0)):  # as simulate_batch: a blown-up command is never flown
        after = after_arrival(y0[None, :3], y0[None, 3:6], rhs.force(y0[None, :])[0], land_tol)
    s0 = np.concatenate([y0[:3], rhs.s2_of(y0)])
    tf = np.where(np.abs(s0) <= eps, 0.0, np.nan)
    nan3 = np.full(3, np.nan)
    return {"landed": landed0, "landing_time": 0.0 if landed0 else np.nan,
            "r_land": y0[:3] if landed0 else nan3, "v_land": y0[3:6] if landed0 else nan3,
            "fuel": 0.0 if landed0 else y0[6] - y[6], "fuel_exhausted": False,
            "peak_thrust": np.zeros(3), "peak_thrust_unsat": np.zeros(3),
            "time_saturated": 0.0, "min_altitude": float(min(y0[2], y[2])),
            "ground_contact": bool(y0[2] < 0), "t_s1": tf[:3], "t_s2": tf[3:],
            "t_s1_last_exit": nan3, "t_s2_last_exit": nan3, "nonfinite": nonfinite,
            "t_end": float(t), "y_end": y, "steps": 0, "step_limit": False,
            "blown_up": blown, "peak_thrust_stages": np.zeros(3),
            "peak_thrust_unsat_stages": np.zeros(3), "peak_thrust_after_arrival": after,
            "contact": contact, "contact_time": t_c, "contact_point": y_c[:3],
            "impact_velocity": y_c[3:6], "below_surface": below, "sol": None}


def _one(rhs: ClosedLoopRHS, y0: np.ndarray, *, t_max: float, eps: float,
         land_tol: tuple[float, float], stop: str, rtol: float, atol: float, max_step: float,
         method: str, m_dry: float) -> dict:
    tr, tv = land_tol

    def f(t, y):
        dy = rhs(t, y)
        if not np.all(np.isfinite(dy)):
            # LSODA would retry the step forever at a non-finite derivative (measured: millions
            # of evaluations at the same t); the batch flags the case, so does the reference.
            raise _NonFinite(float(t), np.array(y, float))
        return dy

    def landing(t, y):
        return max(np.linalg.norm(y[:3]) / tr, np.linalg.norm(y[3:6]) / tv) - 1.0
    landing.terminal = stop == "landing"
    landing.direction = -1

    def band(j: int, direction: int):
        def e(t, y):
            s = y[j] if j < 3 else rhs.s2_of(y)[j - 3]
            return abs(s) - eps
        e.direction = direction
        return e

    def dry(t, y):
        return y[6] - m_dry
    dry.terminal = stop == "landing"  # as in simulate_batch: "t_max" integrates past it
    dry.direction = -1

    def blown(t, y):  # > 0 while the command is a thrust (lgw.sim.mars.batch.BLOWUP_ACCEL)
        f = rhs.force(y)[0]
        return -1.0 if rhs.blown(y, f) else rhs.blow_force - float(np.linalg.norm(f))
    blown.terminal = True  # the case cannot go on (as in simulate_batch)
    blown.direction = -1

    def ground(t, y):  # crossings of the ground plane r_z = 0 (lgw.sim.results)
        return y[2]
    ground.direction = -1

    def deep(t, y):  # a crossing deeper than the contact tolerance confirms the contact
        return y[2] + tr
    deep.terminal = stop == "landing"
    deep.direction = -1

    events = ([landing] + [band(j, -1) for j in range(6)] + [band(j, 1) for j in range(6)]
              + [dry, blown, ground, deep])
    landed0 = bool(landing(0.0, y0) <= 0)
    below0 = bool(y0[2] < 0) and not landed0
    if landed0 and stop == "landing":  # as simulate_batch: landed at t = 0, nothing to fly
        return _start_row(rhs, y0, eps, True, land_tol=land_tol)
    if below0 and stop == "landing":  # as simulate_batch: below the ground, nothing to fly
        return _start_row(rhs, y0, eps, False, land_tol=land_tol, below=True)
    if y0[2] == 0.0 and -y0[5] > tv and not landed0:
        # on the ground descending faster than a graze: the contact is at t = 0 (solve_ivp
        # reports no event at its first point)
        return _start_row(rhs, y0, eps, False, land_tol=land_tol, contact_at=(0.0, y0))
    if rhs.blown(y0):  # the command at t = 0 cannot be flown (nonfinite too if it is not finite)
        tau = None if landed0 or below0 else unavoidable_contact(y0, float(G_MARS[2]),
                                                                  BLOWUP_ACCEL)
        if tau is not None:  # but no thrust could keep it off the ground: that is the outcome
            y_c = y0.copy()
            y_c[:3] += y0[3:6] * tau + 0.5 * G_MARS * tau * tau
            y_c[3:6] += G_MARS * tau
            return _start_row(rhs, y0, eps, False, land_tol=land_tol, contact_at=(tau, y_c))
        return _start_row(rhs, y0, eps, landed0, blown=True,
                          nonfinite=not np.all(np.isfinite(rhs.force(y0)[0])),
                          land_tol=land_tol)
    try:
        with np.errstate(divide="ignore", invalid="ignore"):
            sol = solve_ivp(f, (0.0, t_max), y0, method=method, rtol=rtol, atol=atol,
                            max_step=max_step, events=events, dense_output=True)
    except _NonFinite as e:
        return _start_row(rhs, y0, eps, landed0, t=e.t, y=e.y, nonfinite=True,
                          land_tol=land_tol)
    s0 = np.concatenate([y0[:3], rhs.s2_of(y0)])
    t_dry = sol.t_events[13][0] if len(sol.t_events[13]) else np.inf
    t_blow = sol.t_events[14][0] if len(sol.t_events[14]) else np.inf
    tl = 0.0 if landed0 else (sol.t_events[0][0] if len(sol.t_events[0]) else np.nan)
    # ground contact (as simulate_batch, lgw.sim.results): the first crossing of r_z = 0
    # descending faster than tol_v, or a slower one followed by r_z below -tol_r (confirmed
    # there, dated at the latest crossing before it, or t = 0 when it starts on the ground);
    # not tracked for a case that starts below it.  t_deep: where it is confirmed
    t_deep = t_cont = np.inf
    if not below0:
        fast = np.flatnonzero(-sol.y_events[15][:, 5] > tv) if len(sol.t_events[15]) else []
        t_fast = sol.t_events[15][fast[0]] if len(fast) else np.inf
        t_slow = sol.t_events[16][0] if len(sol.t_events[16]) else np.inf
        if t_fast <= t_slow:
            t_deep = t_cont = t_fast
        elif np.isfinite(t_slow):
            cross = sol.t_events[15][sol.t_events[15] <= t_slow]
            t_deep, t_cont = t_slow, (float(cross[-1]) if len(cross) else 0.0)
    via_blow = False  # the contact follows a blow-up that could not change it
    if (np.isfinite(t_blow) and not below0 and t_blow < min(t_dry, t_deep)
            and not tl <= t_blow):
        yb = sol.sol(t_blow)
        tau = unavoidable_contact(yb, float(G_MARS[2]), BLOWUP_ACCEL)
        if tau is not None:
            via_blow = True
            t_deep = t_cont = t_blow + tau
            t_blow = np.inf
    if not tl <= min(t_dry, t_blow, t_deep):  # ran dry, blew up or met the ground first
        tl = np.nan
    if not t_deep < min(t_dry, t_blow) or np.isfinite(tl):  # the contact is not the outcome
        t_deep = t_cont = np.inf
    if t_cont < np.inf:  # the contact came first: dry mass or a blow-up after it are moot
        t_dry = t_blow = np.inf
    if t_blow < t_dry and np.isnan(tl):  # as simulate_batch: the dry crossing after it is moot
        t_dry = np.inf
    tf = np.array([0.0 if abs(s0[j]) <= eps else
                   (sol.t_events[1 + j][0] if len(sol.t_events[1 + j]) else np.nan)
                   for j in range(6)])
    tx = np.array([sol.t_events[7 + j][-1] if len(sol.t_events[7 + j]) else np.nan
                   for j in range(6)])
    exhausted = bool(np.isfinite(t_dry))
    blown_up = bool(np.isfinite(t_blow))
    nonfinite = not np.all(np.isfinite(sol.y)) or sol.status == -1
    t_end = float(sol.t[-1])
    contact = bool(np.isfinite(t_cont))
    y_cont = sol.sol(t_cont) if contact and not via_blow else np.full(7, np.nan)
    if via_blow:  # the ballistic arc from the blow-up to the ground (nanoseconds)
        yb = sol.y[:, -1]
        tau = t_cont - t_end
        y_cont = yb.copy()
        y_cont[:3] += yb[3:6] * tau + 0.5 * G_MARS * tau * tau
        y_cont[3:6] += G_MARS * tau
    if contact and stop == "landing":
        t_end = t_cont  # the case ends at the crossing of the ground
    t_metric = min(t_end, t_dry, t_blow, t_cont) if np.isnan(tl) else tl
    if via_blow:
        t_metric = float(sol.t[-1])  # the metrics stop where the command blew up
    # blown up: up to the located crossing, not at it (the root finder may put it an ulp past
    # the threshold, a command that is no thrust)
    nodes = (sol.t[sol.t < t_metric] if (blown_up or via_blow) and np.isnan(tl)
             else sol.t[sol.t <= t_metric])
    grid = np.union1d(np.arange(0.0, t_metric, METRIC_GRID), nodes)
    ys = sol.sol(grid)
    low = float(min(ys[2].min(), y_cont[2])) if contact else float(ys[2].min())
    f_sat, f_uns = rhs.force(ys.T)  # (K, 3) each
    sat = np.any(f_sat != f_uns, axis=1)
    dts = np.diff(np.append(grid, t_metric))
    y_land = sol.sol(tl) if np.isfinite(tl) else np.full(7, np.nan)
    y_end = y_cont.copy() if contact and stop == "landing" else sol.y[:, -1].copy()
    if exhausted and stop == "landing" and np.isnan(tl):
        y_end[6] = m_dry  # the case ended at the located crossing: exactly m_dry (as batch)
    ground = bool(np.any(ys[2] < 0)) or contact
    # after arrival: on the solver's nodes and the metric grid until the case ends (after
    # landing too with stop="t_max"), before a blown-up command
    t_last = min(t_end, t_blow, t_metric if via_blow else np.inf)
    grid_a = np.union1d(np.arange(0.0, t_last, METRIC_GRID),
                        sol.t[sol.t < t_last] if blown_up or via_blow
                        else sol.t[sol.t <= t_last])
    ya = sol.sol(grid_a)
    after = after_arrival(ya[:3].T, ya[3:6].T, rhs.force(ya.T)[0], land_tol)
    return {"landed": bool(np.isfinite(tl)), "landing_time": tl, "r_land": y_land[:3],
            "v_land": y_land[3:6],
            # out of propellant: all of it, m0 - m_dry (the root finder's m there is m_dry
            # to its tolerance, which may put it an ulp beyond the load)
            "fuel": y0[6] - (y_land[6] if np.isfinite(tl) else y_cont[6] if contact else
                             m_dry if exhausted else sol.sol(t_blow)[6] if blown_up
                             else y_end[6]),
            "fuel_exhausted": exhausted,
            "peak_thrust": np.max(np.abs(f_sat), axis=0),
            "peak_thrust_unsat": np.max(np.abs(f_uns), axis=0),
            "time_saturated": float(np.sum(dts[sat])), "min_altitude": low,
            "ground_contact": ground, "t_s1": tf[:3], "t_s2": tf[3:], "t_s1_last_exit": tx[:3],
            "t_s2_last_exit": tx[3:], "nonfinite": bool(nonfinite), "t_end": t_end,
            "y_end": y_end, "steps": len(sol.t) - 1, "step_limit": False,
            "blown_up": blown_up,
            # one kind of peak here: on the dense solution's metric grid (the solver's own
            # evaluations are not states of the solution)
            "peak_thrust_stages": np.max(np.abs(f_sat), axis=0),
            "peak_thrust_unsat_stages": np.max(np.abs(f_uns), axis=0),
            "peak_thrust_after_arrival": after, "contact": contact,
            "contact_time": t_cont if contact else np.nan, "contact_point": y_cont[:3],
            "impact_velocity": y_cont[3:6], "below_surface": below0, "sol": sol}


def simulate_reference(r0: np.ndarray, v0: np.ndarray, m0: np.ndarray, gains: Gains, *,
                       law: str = "corrected", disturbance: str = "none",
                       dist_amplitude: float | np.ndarray | None = None,
                       thrust_limit: float | None = None, limit: str = "axis",
                       dt: float | None = None, t_max: float = T_MAX_DEFAULT,
                       eps: float | None = None, seed: int = 0, drag: str = "physical",
                       isp: float = ISP, land_tol: tuple[float, float] = LAND_TOL,
                       record: bool = False, progress: bool = False,
                       guidance_drag: str | None = None, stop: str = "landing",
                       case_offset: int = 0, dist_spec: DisturbanceSpec | None = None,
                       rtol: float = REF_RTOL, atol: float = REF_ATOL,
                       max_step: float = REF_MAX_STEP, method: str = "LSODA",
                       m_dry: float = M_DRY) -> BatchResult:
    """Per-case solve_ivp (LSODA, rtol = atol = 1e-10, max_step 0.1 s by default) with the
    options of ``lgw.sim.mars.batch.simulate_batch``.  LSODA because the corrected law's damping
    term
    beta1 q1 |s1|^(q1-1) v grows without bound as s1 -> 0: once an axis sits at s1 ~ 0 while
    another is still flying, the problem is stiff and explicit DOP853 crawls (minutes per case);
    LSODA switches to BDF there and agrees with Radau to 1e-8 s in landing time.
    ``dt`` is accepted for signature compatibility and ignored; record=True keeps each case's
    OdeSolution in ``trajectory["sol"]`` (None for a non-finite case).

    Non-finite derivative (the command is +-inf: s1 = 0 exactly with v != 0 and no thrust
    limit): the case stops there, flagged ``nonfinite`` like in ``simulate_batch``, with
    ``t_end``/``y_end`` the point of that evaluation; solve_ivp returns no partial solution, so
    only the t = 0 band entries are kept.  In practice only an initial state reaches it (an
    adaptive step landing on s1 = 0 exactly is a measure-zero event).  An axis exactly at
    r = v = 0 is not singular: ``lgw.sim.mars.laws.numpy_law`` evaluates the limit there.
    Dry mass ``m_dry``: an event, terminal with stop="landing", as in ``simulate_batch``
    (``fuel_exhausted``; a case that runs dry first is not landed)."""
    del dt
    r0, v0, m0 = _check_states(r0, v0, m0)
    m_dry = check_m_dry(m_dry, m0)
    _, eps = check_options(law=law, disturbance=disturbance, thrust_limit=thrust_limit,
                           limit=limit, dt=None, t_max=t_max, eps=eps, drag=drag,
                           guidance_drag=guidance_drag, isp=isp, land_tol=land_tol, stop=stop)
    if disturbance == "worst":
        # -a_max sgn(s2) switches on s2 = 0, where the closed loop slides (a Filippov system);
        # an adaptive solver crawls there with ever smaller steps.  Not a reference.
        raise ParameterError("disturbance", disturbance, "the reference mode supports none, sin "
                             "and random; 'worst' (sign feedback) only in simulate_batch")
    n = r0.shape[0]
    if dist_spec is None:
        dist_spec = make_disturbance(disturbance, n, amplitude=dist_amplitude, seed=seed,
                                     case_offset=case_offset)
    rows = []
    it = range(n)
    if progress and n > 1:
        from rich.console import Console
        from rich.progress import track
        it = track(it, description=f"reference, {n} cases", console=Console(stderr=True),
                   transient=True)
    for i in it:
        rhs = ClosedLoopRHS(gains, law=law, dist=dist_spec, case=i, thrust_limit=thrust_limit,
                            limit=limit, drag=drag, guidance_drag=guidance_drag, isp=isp,
                            m0=m0[i])
        y0 = np.concatenate([r0[i], v0[i], [m0[i]]])
        rows.append(_one(rhs, y0, t_max=t_max, eps=eps, land_tol=land_tol, stop=stop,
                         rtol=rtol, atol=atol, max_step=max_step, method=method,
                         m_dry=m_dry))
    keys = [k for k in rows[0] if k != "sol"]
    out = {k: np.array([row[k] for row in rows]) for k in keys}
    info = {"law": law, "disturbance": disturbance, "thrust_limit": thrust_limit,
            "limit": limit if thrust_limit is not None else None, "drag": drag, "m_dry": m_dry,
            "stop": stop,
            "integrator": f"solve_ivp {method} rtol={rtol} atol={atol} max_step={max_step}",
            "boundary_layer": None}
    traj = {"sol": [row["sol"] for row in rows]} if record else None
    return BatchResult(eps=eps, dt=float("nan"), r0=r0, v0=v0, m0=m0, trajectory=traj,
                       info=info, **out)
