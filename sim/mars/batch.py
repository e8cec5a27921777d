"""Batched simulation of seed 000's closed loop: N cases advance together.

The plant is seed 000 (10)-(14) (see ``lgw.sim.mars.plant``), the guidance any law of
``lgw.sim.mars.laws``
(compiled from ``theory``'s SymPy expressions), the disturbance one of
``lgw.sim.mars.disturbances``.
Integration is classical RK4 with an explicit step ``dt`` (the default), or, with
method="dopri5", the adaptive Dormand-Prince 5(4) pair with scipy RK45's error control (the
method of the per-case solve_ivp loop a user would write, compiled), compiled with numba and
run in parallel over cases (``numba.prange``); each case stops when it lands (or at t_max), so
cases do not wait for each other and results do not depend on how cases are batched or chunked.

dopri5 is for landing statistics (landed, landing time and state, fuel, min altitude, ground
contact): the closed loop is smooth between the arrivals of s1, s2 at 0, and the error
control takes ~35-70 steps per Table II case where RK4 needs ~550 at dt = 0.05 s; at each
non-smooth arrival it rejects and shrinks the step instead of stepping over it.  Peak thrust,
saturation time and the s-band times are sampled at the accepted nodes, which are up to
``max_step`` apart: use RK4 (whose nodes are dt apart) where those matter, as the tuner does.
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
  peak_thrust / peak_thrust_unsat: max |F_i| at the nodes until landing, after / before the
    thrust limit; time_saturated: node-sampled time (left-endpoint rule) with the command
    limited on some axis, until landing; min_altitude and ground_contact (r_z < 0 before
    landing: the paper's Fig. 8 "collision"), from the minimum of the cubic Hermite interpolant
    of r_z over each step (not only its nodes), up to landing;
  nonfinite: the state became NaN/inf (the corrected law's |s1|^(q1-1) v is +-inf at s1 = 0
    with v != 0; with a thrust limit it saturates, without one the case is flagged and
    stopped, never silently dropped).  ``t_end`` and ``y_end`` give where each case stopped;
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

import math
from dataclasses import dataclass, field, fields
from functools import cache
from typing import Any

import numba
import numpy as np
from lgw.sim.mars.disturbances import KIND_CODE, DisturbanceSpec, make_disturbance
from lgw.sim.mars.laws import get_law, numba_law_s2, surface_params
from lgw.sim.mars.parameters import (
    CD_LANDER,
    DOPRI_ATOL,
    DOPRI_MAX_STEP,
    DOPRI_MAX_STEPS,
    DOPRI_RTOL,
    DT_DEFAULT,
    EPS_DEFAULT,
    H_MARS,
    PRINTED_DRAG_COEF,
    PRINTED_DRAG_DECAY,
    RHO0_MARS,
)
from lgw.sim.mars.plant import check_drag, exhaust_velocity
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import AREA, G_MARS, ISP, M_DRY

DRAG_CODE = {"none": 0, "physical": 1, "printed": 2}
LIMITS = ("axis", "norm")
STOP_MODES = ("landing", "t_max")

# Per-case result arrays; also the order of the kernel's output arguments.
ARRAY_FIELDS = ("landed", "landing_time", "r_land", "v_land", "fuel", "peak_thrust",
                "peak_thrust_unsat", "time_saturated", "min_altitude", "ground_contact", "t_s1",
                "t_s2", "t_s1_last_exit", "t_s2_last_exit", "nonfinite", "fuel_exhausted",
                "t_end", "y_end", "steps", "step_limit")
METHODS = ("rk4", "dopri5")
# dopri5 step control: PI controller with Hairer & Wanner's DOPRI5 beta (Solving ODEs I,
# II.4), growth at most 10x per step (as scipy's RK45) and none right after a rejection.
# Measured on Table II: beta 0, 0.04, 0.08 take 40, 39, 38 attempts per case at rtol 1e-4
# (~13 of them rejected, at the non-smooth arrivals of s1, s2 at 0): the choice barely matters.
PI_BETA = 0.04
PI_MAXFAC = 10.0

# Dormand & Prince (1980) 5(4) tableau, as in scipy's RK45 (Hairer, Norsett & Wanner, Solving
# ODEs I, Table 5.2): stage nodes C, coefficients A, 5th-order weights B (the 7th stage is the
# FSAL derivative at the new node), error weights E = B - B*.
DP_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
DP_A = np.array([
    [0, 0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0]])
DP_B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
DP_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


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
    eps: float
    dt: float
    r0: np.ndarray | None = None
    v0: np.ndarray | None = None
    m0: np.ndarray | None = None
    trajectory: dict[str, np.ndarray] | None = None
    info: dict[str, Any] = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.landed)

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

    def equal(self, other: BatchResult) -> bool:
        """Bitwise equality of every per-case array (NaN == NaN)."""
        return all(np.array_equal(getattr(self, k), getattr(other, k), equal_nan=True)
                   for k in ARRAY_FIELDS) and self.eps == other.eps and self.dt == other.dt


# --- compiled pieces ----------------------------------------------------------------------

@numba.njit(error_model="numpy", inline="always")
def _drag_fac(kind: int, rz: float) -> float:
    """Altitude factor of the drag model (computed once per RHS, shared by the three axes)."""
    if kind == 1:  # physical: rho(rz)/rho0 = e^(-rz/H)
        return math.exp(-rz / H_MARS)
    if kind == 2:  # seed 000 (12) as printed: e^(-0.0009 rz)
        return math.exp(-PRINTED_DRAG_DECAY * rz)
    return 0.0


@numba.njit(error_model="numpy", inline="always")
def _drag(kind: int, fac: float, vi: float, area: float, m: float) -> float:
    if kind == 1:  # physical: -(1/2) rho0 e^(-rz/H) C_D A |v| v / m
        return -0.5 * RHO0_MARS * fac * CD_LANDER * area * abs(vi) * vi / m
    if kind == 2:  # seed 000 (12) as printed: -0.699 v^2 e^(-0.0009 rz) / (A m)
        return -PRINTED_DRAG_COEF * vi * vi * fac / (area * m)
    return 0.0


@numba.njit(error_model="numpy", inline="always")
def _herm(p0: float, d0: float, p1: float, d1: float, h: float, th: float) -> float:
    t2 = th * th
    t3 = t2 * th
    return ((2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + th) * h * d0
            + (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * h * d1)


@numba.njit(error_model="numpy")
def _herm_min(p0: float, d0: float, p1: float, d1: float, h: float, b: float) -> float:
    """Minimum over th in [0, b] of the cubic Hermite interpolant (``_herm``): the end points
    and the roots of its derivative, a quadratic in th."""
    lo = min(p0, _herm(p0, d0, p1, d1, h, b))
    qa = 6.0 * p0 + 3.0 * h * d0 - 6.0 * p1 + 3.0 * h * d1
    qb = -6.0 * p0 - 4.0 * h * d0 + 6.0 * p1 - 2.0 * h * d1
    qc = h * d0
    if qa == 0.0:
        if qb != 0.0:
            th = -qc / qb
            if 0.0 < th < b:
                lo = min(lo, _herm(p0, d0, p1, d1, h, th))
        return lo
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return lo
    sq = math.sqrt(disc)
    for th in ((-qb - sq) / (2.0 * qa), (-qb + sq) / (2.0 * qa)):
        if 0.0 < th < b:
            lo = min(lo, _herm(p0, d0, p1, d1, h, th))
    return lo


@numba.njit(error_model="numpy", inline="always")
def _band(sa: float, sb: float, eps: float) -> tuple[float, float]:
    """[lo, hi] in [0, 1] where the linear interpolant of s has |s| <= eps (lo > hi: empty)."""
    ds = sb - sa
    if ds == 0.0:
        return (0.0, 1.0) if abs(sa) <= eps else (1.0, 0.0)
    a = (-eps - sa) / ds
    b = (eps - sa) / ds
    lo = min(a, b)
    hi = max(a, b)
    return max(lo, 0.0), min(hi, 1.0)


@cache
def _case_fn(law: str):
    """The RK4 integration of one case for one law (shared by the parallel and serial kernels)."""
    law_fn = numba_law_s2(law)

    @numba.njit(error_model="numpy")
    def case(i, r0, v0, m0, P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, dcoef,
             domega, dphase, dt, nsteps, eps, tol_r, tol_v, stop_landing, record, m_dry,
             method, rtol, atol, hmax, t_max, max_steps,
             landed, t_land, r_land, v_land, fuel, peak, peak_u, tsat, minalt, ground,
             ts1, ts2, ts1x, ts2x, nonfinite, fexh, t_end, y_end, nstep_out, steplim,
             rec_y, rec_F):
        """Case i from start to its end.  A serial function called from the kernels' loop:
        with the inlined rhs in the prange body itself the parallel compile took minutes."""
        Y = np.empty((3, 7))  # y, the stage input, the new node
        # RK4: k1..k4 and y' at the new node (row 4); dopri5: k1..k6 and k7 = y' at the new node
        K = np.empty((7, 7))
        nst = 4 if method == 0 else 6  # rhs calls per step; the last one is at the new node
        y = Y[0]
        yt = Y[1]
        yn = Y[2]
        k1 = K[0]
        k2 = K[1]
        k3 = K[2]
        k4 = K[3]
        k1n = K[nst]
        F = np.empty(3)
        Fu = np.empty(3)
        Fn = np.empty(3)
        Fun = np.empty(3)
        s_old = np.empty(6)
        s_new = np.empty(6)
        tf = np.full(6, np.nan)  # first entry, s1 x/y/z then s2 x/y/z
        tx = np.full(6, np.nan)  # last exit
        dc = dcoef[i].copy()
        dw = domega[i].copy()
        dp = dphase[i].copy()
        for ax in range(3):
            y[ax] = r0[i, ax]
            y[3 + ax] = v0[i, ax]
        y[6] = m0[i]
        pk = np.zeros(3)
        pku = np.zeros(3)
        ts = 0.0
        za = y[2]
        gc = y[2] < 0.0
        has_landed = False
        bad = False
        dry = False
        tl = np.nan
        S2 = np.empty(3)

        def rhs(t, yr, kr):
            """y' at (t, Y[yr]) into K[kr], the command after / before the limit into Fn / Fun and
            s2 (21) per axis into S2 (computed with the law).

            A closure over the case's arrays, inlined by numba at its call sites: passing a
            dozen arrays as arguments cost an atomic incref/decref pair each per call (~20 %
            of a step)."""
            m = Y[yr, 6]
            fac_g = _drag_fac(gkind, Y[yr, 2])
            fac_p = fac_g if pkind == gkind else _drag_fac(pkind, Y[yr, 2])
            for ax in range(3):
                am = _drag(gkind, fac_g, Y[yr, 3 + ax], area[ax], m)
                a, S2[ax] = law_fn(Y[yr, ax], Y[yr, 3 + ax], grav[ax], am, m, P, SP, ax)
                Fun[ax] = m * a
            if lim == 1:
                for ax in range(3):
                    f = Fun[ax]
                    Fn[ax] = fmax if f > fmax else (-fmax if f < -fmax else f)
            elif lim == 2:
                ninf = 0
                for ax in range(3):
                    if math.isinf(Fun[ax]):
                        ninf += 1
                if ninf > 0:  # direction of the infinite components, then scale to the limit
                    for ax in range(3):
                        Fn[ax] = (1.0 if Fun[ax] > 0 else -1.0) if math.isinf(Fun[ax]) else 0.0
                else:
                    for ax in range(3):
                        Fn[ax] = Fun[ax]
                n = math.sqrt(Fn[0] * Fn[0] + Fn[1] * Fn[1] + Fn[2] * Fn[2])
                if n > fmax or ninf > 0:
                    for ax in range(3):
                        Fn[ax] = Fn[ax] * (fmax / n)
            else:
                for ax in range(3):
                    Fn[ax] = Fun[ax]
            fn = math.sqrt(Fn[0] * Fn[0] + Fn[1] * Fn[1] + Fn[2] * Fn[2])
            for ax in range(3):
                # "sin" arrives here as kind 2 with one unit-frequency term (simulate_batch): a
                # separate one-call branch was executed speculatively by LLVM at every RHS
                if dkind == 2:
                    ap = 0.0
                    for k in range(dc.shape[1]):
                        ap += dc[ax, k] * math.sin(dw[ax, k] * t + dp[ax, k])
                elif dkind == 3:
                    s2 = S2[ax]
                    ap = -damp[ax] * (1.0 if s2 > 0 else (-1.0 if s2 < 0 else 0.0))
                else:
                    ap = 0.0
                K[kr, ax] = Y[yr, 3 + ax]
                K[kr, 3 + ax] = (Fn[ax] / m + grav[ax]
                                 + _drag(pkind, fac_p, Y[yr, 3 + ax], area[ax], m) + ap)
            K[kr, 6] = -fn / c

        rhs(0.0, 0, 0)  # y' and the command at t = 0
        for ax in range(3):
            F[ax] = Fn[ax]
            Fu[ax] = Fun[ax]
        for ax in range(3):
            s_old[ax] = y[ax]
            s_old[3 + ax] = S2[ax]
        for j in range(6):
            if abs(s_old[j]) <= eps:
                tf[j] = 0.0
        if (math.sqrt(y[0] ** 2 + y[1] ** 2 + y[2] ** 2) <= tol_r
                and math.sqrt(y[3] ** 2 + y[4] ** 2 + y[5] ** 2) <= tol_v):
            has_landed = True
            tl = 0.0
            for ax in range(3):
                r_land[i, ax] = y[ax]
                v_land[i, ax] = y[3 + ax]
            fuel[i] = 0.0
        if record:
            for j in range(7):
                rec_y[i, 0, j] = y[j]
            for ax in range(3):
                rec_F[i, 0, ax] = F[ax]
        t = 0.0
        step = 0  # accepted steps
        attempts = 0  # dopri5: accepted + rejected steps
        stalled = False
        rejected = False
        err_old = 1e-4
        h_try = min(dt, hmax)
        while True:
            if has_landed and stop_landing:
                break
            if method == 0:
                if step >= nsteps:
                    break
                h = dt
                t_new = (step + 1) * dt
            else:
                rem = t_max - t
                if rem <= 1e-12 * t_max:
                    break
                if attempts >= max_steps:
                    stalled = True
                    break
                h = h_try if h_try < rem * (1.0 - 1e-9) else rem
                t_new = t + h if h < rem else t_max
            # RK4 or the Dormand-Prince stages.  The stages and the new node (whose derivative
            # is the next step's k1) share one rhs() call site: rhs is inlined, and four copies
            # of it made the compile several times slower
            finite = True
            for stage in range(nst):
                yr = 1
                tst = t + 0.5 * h
                if stage == nst - 1:
                    # the new node (its derivative is the next step's k1)
                    for j in range(7):
                        if method == 1:
                            acc = 0.0
                            for q in range(6):
                                acc += DP_B[q] * K[q, j]
                            yn[j] = y[j] + h * acc
                        else:
                            yn[j] = y[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
                        if not math.isfinite(yn[j]):
                            finite = False
                    if not finite:
                        break
                    yr = 2
                    tst = t_new
                elif method == 1:
                    st = stage + 1
                    for j in range(7):
                        acc = 0.0
                        for q in range(st):
                            acc += DP_A[st, q] * K[q, j]
                        yt[j] = y[j] + h * acc
                    tst = t + DP_C[st] * h
                elif stage == 0:
                    for j in range(7):
                        yt[j] = y[j] + 0.5 * h * k1[j]
                elif stage == 1:
                    for j in range(7):
                        yt[j] = y[j] + 0.5 * h * k2[j]
                else:
                    for j in range(7):
                        yt[j] = y[j] + h * k3[j]
                    tst = t + h
                rhs(tst, yr, stage + 1)
            if not finite:
                bad = True
                break
            if method == 1:
                # error control as in scipy's RK45 (Hairer, Norsett & Wanner II.4): RMS of
                # h E.K / (atol + rtol max(|y|, |y_new|)); reject above 1, safety 0.9
                attempts += 1
                errn = 0.0
                for j in range(7):
                    acc = 0.0
                    for q in range(7):
                        acc += DP_E[q] * K[q, j]
                    sc = atol + rtol * max(abs(y[j]), abs(yn[j]))
                    errn += (h * acc / sc) ** 2
                errn = math.sqrt(errn / 7.0)
                if not errn <= 1.0:  # NaN rejects too
                    h_try = h * max(0.2, 0.9 * errn ** -0.2) if errn == errn else 0.2 * h
                    rejected = True
                    continue
                # PI control (Hairer & Wanner's DOPRI5: beta = 0.04); no growth right after a
                # rejection (as scipy's RK45)
                fac = 0.9 * max(errn, 1e-10) ** (-0.2 + 0.75 * PI_BETA) * err_old ** PI_BETA
                fac = min(PI_MAXFAC, max(0.2, fac))
                if rejected:
                    fac = min(fac, 1.0)
                rejected = False
                err_old = max(errn, 1e-4)
                h_try = min(h * fac, hmax)
            # dry mass: first th with m(th) <= m_dry, bisection on the Hermite interpolant
            ended = has_landed or dry  # the case's outcome was reached before this step
            thd = 1.0
            dry_now = False
            if not dry and yn[6] <= m_dry:
                dry_now = True
                a = 0.0
                b = 1.0
                for _ in range(60):
                    mid = 0.5 * (a + b)
                    if _herm(y[6], k1[6], yn[6], k1n[6], h, mid) <= m_dry:
                        b = mid
                    else:
                        a = mid
                thd = b
            # with stop="landing" a case that runs dry ends at thd
            bend = thd if stop_landing else 1.0
            # sliding-variable bands, linear between nodes (up to the dry-mass stop)
            for ax in range(3):
                s_new[ax] = yn[ax]
                s_new[3 + ax] = S2[ax]  # from the rhs call at the new node
            for j in range(6):
                lo, hi = _band(s_old[j], s_new[j], eps)
                if lo <= hi and lo <= bend:
                    if math.isnan(tf[j]):
                        tf[j] = t + lo * h
                    if hi < bend:
                        tx[j] = t + hi * h
                s_old[j] = s_new[j]
            if not ended:
                # metrics until the outcome (landing or dry mass): command at the step's
                # left node
                sat = False
                for ax in range(3):
                    pk[ax] = max(pk[ax], abs(F[ax]))
                    pku[ax] = max(pku[ax], abs(Fu[ax]))
                    if F[ax] != Fu[ax]:
                        sat = True
                rn = math.sqrt(yn[0] ** 2 + yn[1] ** 2 + yn[2] ** 2)
                vn = math.sqrt(yn[3] ** 2 + yn[4] ** 2 + yn[5] ** 2)
                frac = thd
                if rn <= tol_r and vn <= tol_v:
                    # bisection on L(th) = max(|r|/tol_r, |v|/tol_v) - 1, Hermite in th
                    a = 0.0
                    b = 1.0
                    for _ in range(60):
                        mid = 0.5 * (a + b)
                        rr = 0.0
                        vv = 0.0
                        for ax in range(3):
                            rr += _herm(y[ax], k1[ax], yn[ax], k1n[ax], h, mid) ** 2
                            vv += _herm(y[3 + ax], k1[3 + ax], yn[3 + ax], k1n[3 + ax], h,
                                        mid) ** 2
                        if math.sqrt(rr) <= tol_r and math.sqrt(vv) <= tol_v:
                            b = mid
                        else:
                            a = mid
                    if b <= thd:  # landed before (or as) the mass reached m_dry
                        frac = b
                        has_landed = True
                        tl = t + b * h
                        for ax in range(3):
                            r_land[i, ax] = _herm(y[ax], k1[ax], yn[ax], k1n[ax], h, b)
                            v_land[i, ax] = _herm(y[3 + ax], k1[3 + ax], yn[3 + ax],
                                                  k1n[3 + ax], h, b)
                        fuel[i] = m0[i] - _herm(y[6], k1[6], yn[6], k1n[6], h, b)
                        if stop_landing:
                            dry_now = False  # the case ends at landing, above m_dry
                if dry_now and not has_landed:  # out of propellant before landing
                    fuel[i] = m0[i] - _herm(y[6], k1[6], yn[6], k1n[6], h, thd)
                if sat:
                    ts += frac * h
                # lowest point of the step up to its end (landing, dry mass or the node) on
                # the Hermite interpolant: node sampling misses a dip below ground that is
                # shorter than the step (dopri5's steps are ~1 s)
                zn = _herm_min(y[2], k1[2], yn[2], k1n[2], h, frac)
                if zn < za:
                    za = zn
                if zn < 0.0:
                    gc = True
                if has_landed:  # the command at the landing node counts too
                    for ax in range(3):
                        pk[ax] = max(pk[ax], abs(Fn[ax]))
                        pku[ax] = max(pku[ax], abs(Fun[ax]))
            if dry_now:
                dry = True
                if stop_landing:  # out of propellant: the case ends at th = thd
                    for j in range(7):
                        y[j] = _herm(y[j], k1[j], yn[j], k1n[j], h, thd)
                    t = t + thd * h
                    break
            for j in range(7):
                y[j] = yn[j]
                k1[j] = k1n[j]
            for ax in range(3):
                F[ax] = Fn[ax]
                Fu[ax] = Fun[ax]
            t = t_new
            step += 1
            if record:
                for j in range(7):
                    rec_y[i, step, j] = y[j]
                for ax in range(3):
                    rec_F[i, step, ax] = F[ax]
        landed[i] = has_landed
        fexh[i] = dry
        nstep_out[i] = step
        steplim[i] = stalled
        t_land[i] = tl
        if not has_landed:
            if not dry:
                fuel[i] = m0[i] - y[6]
            for ax in range(3):
                r_land[i, ax] = np.nan
                v_land[i, ax] = np.nan
        for ax in range(3):
            peak[i, ax] = pk[ax]
            peak_u[i, ax] = pku[ax]
            ts1[i, ax] = tf[ax]
            ts2[i, ax] = tf[3 + ax]
            ts1x[i, ax] = tx[ax]
            ts2x[i, ax] = tx[3 + ax]
        tsat[i] = ts
        minalt[i] = za
        ground[i] = gc
        nonfinite[i] = bad
        t_end[i] = t
        for j in range(7):
            y_end[i, j] = yn[j] if bad else y[j]

    return case


@cache
def _compile(law: str, parallel: bool = True):
    """Build the RK4 kernel for one law (numba compiles it on first call: ~10 s for the case
    function, shared, plus ~10 s for a parallel kernel, ~1 s for a serial one).

    parallel=False gives the same loop without threads, for executors (dask) that parallelise
    over chunks themselves."""
    case = _case_fn(law)

    @numba.njit(error_model="numpy", parallel=parallel)
    def kernel(r0, v0, m0, P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, dcoef,
               domega, dphase, dt, nsteps, eps, tol_r, tol_v, stop_landing, record, m_dry,
               method, rtol, atol, hmax, t_max, max_steps,
               landed, t_land, r_land, v_land, fuel, peak, peak_u, tsat, minalt, ground,
               ts1, ts2, ts1x, ts2x, nonfinite, fexh, t_end, y_end, nstep_out, steplim,
               rec_y, rec_F):
        for i in numba.prange(r0.shape[0]):
            case(i, r0, v0, m0, P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, dcoef,
                 domega, dphase, dt, nsteps, eps, tol_r, tol_v, stop_landing, record, m_dry,
                 method, rtol, atol, hmax, t_max, max_steps,
                 landed, t_land, r_land, v_land, fuel, peak, peak_u, tsat, minalt, ground,
                 ts1, ts2, ts1x, ts2x, nonfinite, fexh, t_end, y_end, nstep_out, steplim,
                 rec_y, rec_F)

    return kernel


# --- Python entry point -------------------------------------------------------------------

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


def _positive(name: str, x: float | None, unit: str, allow_none: bool = False) -> None:
    if x is None and allow_none:
        return
    if x is None or not (np.isfinite(x) and x > 0):
        raise ParameterError(name, x, f"must be a finite number > 0 ({unit})")


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
    _positive("thrust_limit", thrust_limit, "N", allow_none=True)
    if limit not in LIMITS:
        raise ParameterError("limit", limit, f"must be one of {', '.join(LIMITS)}")
    dt = DT_DEFAULT if dt is None else dt
    _positive("dt", dt, "s")
    _positive("t_max", t_max, "s")
    if dt > t_max:
        raise ParameterError("dt", dt, f"must be <= t_max = {t_max} s")
    eps = EPS_DEFAULT if eps is None else eps
    _positive("eps", eps, "m or m/s")
    check_drag(drag)
    if guidance_drag is not None:
        check_drag(guidance_drag, "guidance_drag")
    exhaust_velocity(isp)
    if len(land_tol) != 2:
        raise ParameterError("land_tol", land_tol, "must be (position m, velocity m/s)")
    _positive("land_tol[0]", land_tol[0], "m")
    _positive("land_tol[1]", land_tol[1], "m/s")
    if stop not in STOP_MODES:
        raise ParameterError("stop", stop, f"must be one of {', '.join(STOP_MODES)}")
    return float(dt), float(eps)


def check_method(method: str, *, rtol: float, atol: float, max_step: float,
                 max_steps: int, record: bool) -> int:
    """Validate the integrator choice; return its kernel code (0 rk4, 1 dopri5)."""
    if method not in METHODS:
        raise ParameterError("method", method, f"must be one of {', '.join(METHODS)}")
    if method == "rk4":
        return 0
    _positive("rtol", rtol, "relative tolerance")
    if rtol < 1e-13:
        raise ParameterError("rtol", rtol, "must be >= 1e-13 (double precision)")
    _positive("atol", atol, "absolute tolerance")
    _positive("max_step", max_step, "s")
    if isinstance(max_steps, bool) or not isinstance(max_steps, int | np.integer) \
            or max_steps < 1:
        raise ParameterError("max_steps", max_steps, "must be an integer >= 1")
    if record:
        raise ParameterError("record", record, "needs method='rk4' (the trajectory is "
                             "recorded on the fixed step grid)")
    return 1


def simulate_batch(r0: np.ndarray, v0: np.ndarray, m0: np.ndarray, gains: Gains, *,
                   law: str = "corrected", disturbance: str = "none",
                   dist_amplitude: float | np.ndarray | None = None,
                   thrust_limit: float | None = None, limit: str = "axis",
                   dt: float | None = None, t_max: float = 120.0, eps: float | None = None,
                   seed: int = 0, drag: str = "physical", isp: float = ISP,
                   land_tol: tuple[float, float] = (0.1, 0.1), record: bool = False,
                   progress: bool = False, guidance_drag: str | None = None,
                   stop: str = "landing", case_offset: int = 0,
                   dist_spec: DisturbanceSpec | None = None,
                   chunk: int = 4096, parallel: bool = True,
                   m_dry: float = M_DRY, method: str = "rk4", rtol: float = DOPRI_RTOL,
                   atol: float = DOPRI_ATOL, max_step: float = DOPRI_MAX_STEP,
                   max_steps: int = DOPRI_MAX_STEPS) -> BatchResult:
    """Fly N cases of seed 000's closed loop with RK4 or dopri5 (see the module docstring).

    r0, v0 (N, 3) m and m/s in the landing-site frame, m0 (N,) kg (or one value for all).
    law: a name in ``lgw.sim.mars.laws.LAWS``; gains: the sliding-surface gain set (also defines s2
    for
      diagnostics and the worst-case disturbance; super-twisting ignores it otherwise).
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
    parallel=False runs the cases on one thread (numba prange otherwise).
    m_dry: dry mass (kg, default lgw.theory.mars.parameters.M_DRY = 1505), > 0 and < every m0; a
    case
      whose mass reaches it is ``fuel_exhausted`` (not landed if before landing) and, with
      stop="landing", ends there (see the module docstring for stop="t_max").
    method: "rk4" (fixed step dt, the default) or "dopri5" (adaptive Dormand-Prince 5(4) with
      error control rtol, atol as scipy's RK45; dt is the first step, max_step caps the step;
      a case that needs more than max_steps attempts is flagged ``step_limit`` and stops there).
      ``steps`` holds the accepted steps per case.  record=True needs method="rk4".
    """
    r0, v0, m0 = _check_states(r0, v0, m0)
    m_dry = check_m_dry(m_dry, m0)
    dt, eps = check_options(law=law, disturbance=disturbance, thrust_limit=thrust_limit,
                            limit=limit, dt=dt, t_max=t_max, eps=eps, drag=drag,
                            guidance_drag=guidance_drag, isp=isp, land_tol=land_tol, stop=stop)
    mcode = check_method(method, rtol=rtol, atol=atol, max_step=max_step,
                         max_steps=max_steps, record=record)
    n = r0.shape[0]
    if dist_spec is None:
        dist_spec = make_disturbance(disturbance, n, amplitude=dist_amplitude, seed=seed,
                                     case_offset=case_offset)
    elif dist_spec.coef.shape[0] != n or dist_spec.kind != disturbance:
        raise ParameterError("dist_spec", dist_spec.kind, f"must be a {disturbance!r} spec "
                             f"for {n} cases")
    spec = get_law(law)
    P = np.ascontiguousarray(spec.param_values(gains), float)
    SP = np.ascontiguousarray(surface_params(gains), float)
    kernel = _compile(law, parallel)
    nsteps = int(math.ceil(t_max / dt - 1e-9))
    c = exhaust_velocity(isp)
    fmax = float(thrust_limit) if thrust_limit is not None else np.inf
    lim = 0 if thrust_limit is None else (1 if limit == "axis" else 2)
    pkind = DRAG_CODE[drag]
    gkind = DRAG_CODE[drag if guidance_drag is None else guidance_drag]

    out = {k: np.empty((n, 3)) for k in ("r_land", "v_land", "peak_thrust", "peak_thrust_unsat",
                                         "t_s1", "t_s2", "t_s1_last_exit", "t_s2_last_exit")}
    out.update({k: np.empty(n) for k in ("landing_time", "fuel", "time_saturated",
                                         "min_altitude", "t_end")})
    out.update({k: np.zeros(n, bool) for k in ("landed", "ground_contact", "nonfinite",
                                               "fuel_exhausted", "step_limit")})
    out["steps"] = np.zeros(n, np.int64)
    out["y_end"] = np.empty((n, 7))
    shape_rec = (n, nsteps + 1) if record else (1, 1)
    rec_y = np.full(shape_rec + (7,), np.nan)
    rec_F = np.full(shape_rec + (3,), np.nan)

    dkind = KIND_CODE[disturbance]
    if dkind == KIND_CODE["sin"]:  # A sin(t) = the "random" form with c = A, w = 1, phase 0
        dkind = KIND_CODE["random"]

    def run(sl: slice) -> None:
        ds = dist_spec.take(sl)
        if disturbance == "sin":
            k = sl.stop - sl.start
            ds = DisturbanceSpec("random", ds.amplitude,
                                 np.tile(ds.amplitude[None, :, None], (k, 1, 1)),
                                 np.ones((k, 3, 1)), np.zeros((k, 3, 1)))
        kernel(r0[sl], v0[sl], m0[sl], P, SP, G_MARS.astype(float), AREA.astype(float), pkind,
               gkind, c, fmax, lim, dkind, ds.amplitude,
               np.ascontiguousarray(ds.coef), np.ascontiguousarray(ds.omega),
               np.ascontiguousarray(ds.phase), dt, nsteps, eps, float(land_tol[0]),
               float(land_tol[1]), stop == "landing", record, m_dry,
               mcode, float(rtol), float(atol), float(max_step), float(t_max), int(max_steps),
               *(out[k][sl] for k in ARRAY_FIELDS),
               rec_y[sl] if record else rec_y, rec_F[sl] if record else rec_F)

    chunks = [slice(a, min(a + chunk, n)) for a in range(0, n, chunk)]
    if progress and len(chunks) > 1:
        from rich.console import Console
        from rich.progress import Progress

        with Progress(console=Console(stderr=True), transient=True) as bar:
            task = bar.add_task(f"simulating {n} cases", total=n)
            for sl in chunks:
                run(sl)
                bar.advance(task, sl.stop - sl.start)
    else:
        for sl in chunks:
            run(sl)

    traj = None
    if record:
        traj = {"t": np.arange(nsteps + 1) * dt, "r": rec_y[..., :3], "v": rec_y[..., 3:6],
                "m": rec_y[..., 6], "F": rec_F}
    info = {"law": law, "disturbance": disturbance, "dist_amplitude": dist_spec.amplitude.tolist(),
            "thrust_limit": thrust_limit, "limit": limit if thrust_limit is not None else None,
            "drag": drag, "guidance_drag": guidance_drag or drag, "isp": isp,
            "land_tol": list(land_tol), "t_max": t_max, "seed": seed, "stop": stop,
            "m_dry": m_dry,
            "integrator": (f"RK4 fixed step dt={dt} s (numba)" if mcode == 0 else
                           f"Dormand-Prince 5(4) adaptive rtol={rtol} atol={atol} "
                           f"max_step={max_step} s, first step {dt} s (numba)"),
            "boundary_layer": None}
    return BatchResult(eps=eps, dt=dt, r0=r0, v0=v0, m0=m0, trajectory=traj, info=info, **out)


def result_fields() -> tuple[str, ...]:
    return tuple(f.name for f in fields(BatchResult))
