"""Seed 000's client of the generic integrator (``lgw.sim.integrate``): plant, events, metrics.

The hooks below are templates in the sense of ``lgw.sim.integrate``: plain Python copied into
generated modules, where ``law`` is a law's generated code (``lgw.sim.mars.laws.law_source``)
and the integrator's ``kernel`` calls them.  Each law has a kernel module of its own (the law is
inlined into the vector field: passed in as a function, or picked by a switch in one kernel
for every law, it ran 25-60 % slower, docs/sim.md); the hooks run once per case are compiled
once in a shared module (``hooks_module``) that every law's kernel imports.  What they
compute is documented in ``lgw.sim.mars.batch``.

State y = [r (3), v (3), m] (seed 000 (10)-(14)); auxiliary outputs X = [F (3) after the
thrust limit, F (3) before it, s2 (3) of (21), the law's acceleration a (3), stage peaks and the
blown-up flag of the current step attempt (below)]; trackers S, slots below.

Per-case inputs C = (r0, v0, m0, dcoef, domega, dphase); shared Q = (P, SP, grav, area, pkind,
gkind, c, fmax, lim, dkind, damp, eps, tol_r, tol_v, stop_landing, m_dry, blow_acc); results
R = the first ``len(RESULT_FIELDS)`` arrays of ``lgw.sim.mars.batch.ARRAY_FIELDS``.
"""

from __future__ import annotations

import functools
import math

import numba
from lgw.sim.mars.parameters import (
    CD_LANDER,
    H_MARS,
    PRINTED_DRAG_COEF,
    PRINTED_DRAG_DECAY,
    RHO0_MARS,
)

NY = 7  # r, v, m
# F after the limit (0:3), F before (3:6), s2 (6:9), the law's acceleration a (9:12; F before =
# m a); then, over the rhs calls of the current step attempt (reset at its first stage): max
# |F_i| after (12:15) and before (15:18) the limit, and > 0 if any call's command was blown up
# (18: 2.0 if not finite, 1.0 if too large or at a mass <= 0; see sys_rhs)
NX = 19
XPK = 12
XPKU = 15
XBLOWN = 18
# tracker slots in S
TF = 0  # 6: first entry into the band, s1 x/y/z then s2 x/y/z
TX = 6  # 6: last exit
SOLD = 12  # 6: s at the current node
PK = 18  # 3: peak |F| after the limit
PKU = 21  # 3: before
TSAT = 24  # time saturated
ZMIN = 25  # lowest altitude
GROUND = 26  # 1.0 once r_z < 0 before the outcome
LANDED = 27
DRY = 28
TLAND = 29
BLOWN = 30  # > 0 once a step had a blown-up command (2: not finite); the case ended there
PKS = 31  # 3: peak |F| after the limit over every rhs evaluation of the accepted steps
PKUS = 34  # 3: before
PKA = 37  # 3: peak |F_i| after the limit from the first node in axis i's landing band on (NaN
#           until then; the band: |r_i| <= tol_r and |v_i| <= tol_v)
# ground contact (lgw.sim.results: the first crossing of r_z = 0 that goes deeper than the
# contact tolerance tol_r ends the case, dated at the crossing itself)
CONT = 40  # 1.0 once the contact is confirmed (before any other outcome)
OPEN = 41  # 1.0 while r_z < 0 since a crossing not yet deeper than tol_r (a graze, so far)
XT = 42  # the time of that crossing (s)
XR = 43  # 3: r there
XV = 46  # 3: v there
XM = 49  # m there
BELOW = 50  # 1.0 if the initial state is below the ground (r_z(0) < 0) and not landed
NS = 51

RESULT_FIELDS = ("landed", "landing_time", "r_land", "v_land", "fuel", "peak_thrust",
                 "peak_thrust_unsat", "time_saturated", "min_altitude", "ground_contact",
                 "t_s1", "t_s2", "t_s1_last_exit", "t_s2_last_exit", "fuel_exhausted",
                 "blown_up", "peak_thrust_stages", "peak_thrust_unsat_stages",
                 "peak_thrust_after_arrival", "contact", "contact_time", "contact_point",
                 "impact_velocity", "below_surface")


@numba.njit(error_model="numpy", inline="always", cache=True)
def _drag_fac(kind: int, rz: float) -> float:
    """Altitude factor of the drag model (computed once per RHS, shared by the three axes)."""
    if kind == 1:  # physical: rho(rz)/rho0 = e^(-rz/H)
        return math.exp(-rz / H_MARS)
    if kind == 2:  # seed 000 (12) as printed: e^(-0.0009 rz)
        return math.exp(-PRINTED_DRAG_DECAY * rz)
    return 0.0


@numba.njit(error_model="numpy", inline="always", cache=True)
def _drag(kind: int, fac: float, vi: float, area: float, m: float) -> float:
    if kind == 1:  # physical: -(1/2) rho0 e^(-rz/H) C_D A |v| v / m
        return -0.5 * RHO0_MARS * fac * CD_LANDER * area * abs(vi) * vi / m
    if kind == 2:  # seed 000 (12) as printed: -0.699 v^2 e^(-0.0009 rz) / (A m)
        return -PRINTED_DRAG_COEF * vi * vi * fac / (area * m)
    return 0.0


# --- templates ----------------------------------------------------------------------------

def sys_init(i, C, Q, y, S):  # noqa: N803
    r0, v0, m0, dcoef, domega, dphase = C
    for ax in range(3):
        y[ax] = r0[i, ax]
        y[3 + ax] = v0[i, ax]
    y[6] = m0[i]
    for j in range(6):
        S[TF + j] = math.nan
        S[TX + j] = math.nan
    for ax in range(3):
        S[PK + ax] = 0.0
        S[PKU + ax] = 0.0
        S[PKS + ax] = 0.0
        S[PKUS + ax] = 0.0
        S[PKA + ax] = math.nan
    S[TSAT] = 0.0
    S[ZMIN] = y[2]
    S[GROUND] = 1.0 if y[2] < 0.0 else 0.0
    S[LANDED] = 0.0
    S[DRY] = 0.0
    S[TLAND] = math.nan
    S[BLOWN] = 0.0
    S[CONT] = 0.0
    S[OPEN] = 0.0
    S[BELOW] = 0.0
    S[XT] = math.nan
    S[XM] = math.nan
    for ax in range(3):
        S[XR + ax] = math.nan
        S[XV + ax] = math.nan


def sys_rhs(t, Y, yr, K, kr, X, i, C, Q):  # noqa: N803
    """y' at (t, Y[yr]) into K[kr]: seed 000 (10), (11), (13), (14) with the law's command
    saturated by the limit; X = [F after the limit, F before, s2 (21) per axis]."""
    r0, v0, m0, dcoef, domega, dphase = C
    (P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, eps, tol_r, tol_v,
     stop_landing, m_dry, blow_acc) = Q
    m = Y[yr, 6]
    fac_g = _drag_fac(gkind, Y[yr, 2])
    fac_p = fac_g if pkind == gkind else _drag_fac(pkind, Y[yr, 2])
    for ax in range(3):
        am = _drag(gkind, fac_g, Y[yr, 3 + ax], area[ax], m)
        a, X[6 + ax] = law(Y[yr, ax], Y[yr, 3 + ax], grav[ax], am, m, P, SP, ax)  # noqa: F821
        X[3 + ax] = m * a
        X[9 + ax] = a
    if lim == 1:
        for ax in range(3):
            f = X[3 + ax]
            X[ax] = fmax if f > fmax else (-fmax if f < -fmax else f)
    elif lim == 2:
        ninf = 0
        for ax in range(3):
            if math.isinf(X[3 + ax]):
                ninf += 1
        if ninf > 0:  # direction of the infinite components, then scale to the limit
            for ax in range(3):
                fu = X[3 + ax]
                X[ax] = (1.0 if fu > 0 else -1.0) if math.isinf(fu) else 0.0
        else:
            for ax in range(3):
                X[ax] = X[3 + ax]
        n = math.sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2])
        if n > fmax or ninf > 0:
            for ax in range(3):
                X[ax] = X[ax] * (fmax / n)
    else:
        for ax in range(3):
            X[ax] = X[3 + ax]
    fn = math.sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2])
    # a blown-up command: not finite, above blow_acc m0 (BLOWUP_ACCEL, lgw.sim.mars.batch: no
    # thrust), or asked at a non-positive mass (the stage state is not a vehicle).  The step
    # that made it is never accepted (sys_step ends the case at its start), so the stage gets a
    # finite stand-in, no thrust, instead of an inf that would hide it as a non-finite state;
    # dopri5 may instead reject the attempt and retry a smaller step
    # (with blow_acc = inf, the bound checks' unlimited-thrust loop, only a non-finite command
    # counts: there the mass is a bookkeeping state the law divides out, and may run past 0)
    bad_cmd = not (fn <= blow_acc * m0[i]) or (not (m > 0.0) and blow_acc < math.inf)
    if kr <= 1:  # the t = 0 call or the first stage of a step attempt
        for j in range(6):
            X[XPK + j] = 0.0
        X[XBLOWN] = 0.0
    for ax in range(3):
        X[XPK + ax] = max(X[XPK + ax], abs(X[ax]))
        X[XPKU + ax] = max(X[XPKU + ax], abs(X[3 + ax]))
    if bad_cmd:  # 2: the command is not finite (also flagged nonfinite), 1: it is too large
        X[XBLOWN] = max(X[XBLOWN], 1.0 if math.isfinite(fn) else 2.0)
    for ax in range(3):
        # "sin" arrives here as kind 2 with one unit-frequency term (simulate_batch): a
        # separate one-call branch was executed speculatively by LLVM at every RHS
        if dkind == 2:
            ap = 0.0
            for k in range(dcoef.shape[2]):
                ap += dcoef[i, ax, k] * math.sin(domega[i, ax, k] * t + dphase[i, ax, k])
        elif dkind == 3:
            s2 = X[6 + ax]
            ap = -damp[ax] * (1.0 if s2 > 0 else (-1.0 if s2 < 0 else 0.0))
        else:
            ap = 0.0
        K[kr, ax] = Y[yr, 3 + ax]
        if bad_cmd:
            acc = 0.0
        elif Y[yr, ax] == 0.0 and Y[yr, 3 + ax] == 0.0 and X[ax] == X[3 + ax]:
            # an axis exactly at rest on its target with its command unlimited: the law's
            # acceleration a itself, not (m a) / m, which differs from a by an ulp; with a =
            # -g - a_m (the law's limit there, lgw.sim.mars.laws.origin_expr) the sum is
            # exactly 0, so the axis stays at rest instead of drifting into the singular
            # |s1|^(q1-1) v at s1 = 0 (on z, where g != 0)
            acc = X[9 + ax]
        else:
            acc = X[ax] / m
        K[kr, 3 + ax] = (acc + grav[ax]
                         + _drag(pkind, fac_p, Y[yr, 3 + ax], area[ax], m) + ap)
    K[kr, 6] = 0.0 if bad_cmd else -fn / c


def _sat_margin(Xa, fmax, lim):  # noqa: N803
    """How far the command before the limit (Xa[3:6], N) is beyond the thrust limit (> 0:
    saturated): max_i |F_i| - fmax for the per-axis limit, |F| - fmax on the norm, -1 with no
    limit."""
    if lim == 1:
        return max(abs(Xa[3]), abs(Xa[4]), abs(Xa[5])) - fmax
    if lim == 2:
        return math.sqrt(Xa[3] * Xa[3] + Xa[4] * Xa[4] + Xa[5] * Xa[5]) - fmax
    return -1.0


def _arrival(y, X, S, tol_r, tol_v):  # noqa: N803
    """Peak thrust after arrival at an accepted node (state y, rhs outputs X there): per axis,
    max |F_i| (after the limit) from the first node with |r_i| <= tol_r, |v_i| <= tol_v on."""
    for ax in range(3):
        f = abs(X[ax])
        if not math.isnan(S[PKA + ax]):
            S[PKA + ax] = max(S[PKA + ax], f)
        elif abs(y[ax]) <= tol_r and abs(y[3 + ax]) <= tol_v:
            S[PKA + ax] = f


def sys_start(i, y, X, S, C, Q, R):  # noqa: N803
    """Bands entered at t = 0 and landing at t = 0; True if the case ends there."""
    (P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, eps, tol_r, tol_v,
     stop_landing, m_dry, blow_acc) = Q
    (landed, t_land, r_land, v_land, fuel, peak, peak_u, tsat, minalt, ground, ts1, ts2,
     ts1x, ts2x, fexh, blown, peak_s, peak_us, peak_a, cont, t_cont, r_cont, v_cont,
     below) = R
    for ax in range(3):
        S[SOLD + ax] = y[ax]
        S[SOLD + 3 + ax] = X[6 + ax]
    for j in range(6):
        if abs(S[SOLD + j]) <= eps:
            S[TF + j] = 0.0
    if (math.sqrt(y[0] ** 2 + y[1] ** 2 + y[2] ** 2) <= tol_r
            and math.sqrt(y[3] ** 2 + y[4] ** 2 + y[5] ** 2) <= tol_v):
        S[LANDED] = 1.0
        S[TLAND] = 0.0
        for ax in range(3):
            r_land[i, ax] = y[ax]
            v_land[i, ax] = y[3 + ax]
        fuel[i] = 0.0
    if S[LANDED] == 0.0 and y[2] < 0.0:
        S[BELOW] = 1.0  # starts below the ground: named as such, never flown as a mission
    elif S[LANDED] == 0.0 and y[2] == 0.0 and -y[5] > tol_v:
        # on the ground, descending faster than a graze: the contact is at t = 0
        _impact_fn(0.0, y, S, grav, 0.0)  # noqa: F821  (r_z = 0: tau = 0, any a_max)
    stop0 = (S[LANDED] != 0.0 or S[BELOW] != 0.0 or S[CONT] != 0.0) and stop_landing
    if X[XBLOWN] != 0.0 and not stop0:
        # the command at t = 0 is blown up: nothing can be flown; unless no thrust could keep
        # the vehicle off the ground, when that contact is the outcome
        if S[LANDED] != 0.0 or S[BELOW] != 0.0 or not _impact_fn(0.0, y, S, grav,  # noqa: F821
                                                                 blow_acc):
            S[BLOWN] = X[XBLOWN]
        return True
    if X[XBLOWN] == 0.0:  # a blown-up command at t = 0 is never flown (landed there)
        _arrival_fn(y, X, S, tol_r, tol_v)  # noqa: F821
    return stop0


def _impact(t, y, S, grav, a_max):  # noqa: N803
    """At time t and state y: if descending closer to the ground than the stopping distance at
    a_max (m/s^2; r_z >= 0, v_z < 0, r_z < v_z^2 / (2 a_max)), no thrust below a_max can keep
    the vehicle off it: record that contact on the ballistic arc from y (the crossing is
    tau = 2 r_z / (-v_z + sqrt(v_z^2 - 2 g_z r_z)) later; lgw.sim.mars.reference.
    unavoidable_contact) and return True."""
    vz = y[5]
    if not (y[2] >= 0.0 and vz < 0.0 and 2.0 * a_max * y[2] < vz * vz):
        return False
    tau = 2.0 * y[2] / (-vz + math.sqrt(vz * vz - 2.0 * grav[2] * y[2]))
    S[CONT] = 1.0
    S[XT] = t + tau
    for ax in range(3):
        S[XR + ax] = y[ax] + y[3 + ax] * tau + 0.5 * grav[ax] * tau * tau
        S[XV + ax] = y[3 + ax] + grav[ax] * tau
    S[XM] = y[6]
    return True


def _ground(t, h, y, k1, yn, k1n, S, tol_r, tol_v, b):  # noqa: N803
    """Ground contact within [0, b] of the step from (t, y) to (t + h, yn) (b <= 1: the end of
    this step's flight so far, the dry-mass crossing): th where a confirmed contact ends the
    case, or 2.0 (lgw.sim.results).  A crossing of r_z = 0 descending faster than tol_v is a
    contact at once: the case ends at the crossing.  A slower one (within the landing speed
    tolerance) is a graze while r_z stays above -tol_r (the sliding laws chatter about r_z = 0
    by ~1 mm at RK4's default step, where z converges first); deeper, the contact is confirmed
    and dated at that crossing (XT, XR, XV, XM), and the case ends at the crossing if it lies
    in this step, else where the depth passed tol_r.  The crossings are the first points below
    the level on the step's cubic Hermite interpolant of r_z (r_z' = v_z), not only nodes."""
    p0 = y[2]
    d0 = k1[2]
    p1 = yn[2]
    d1 = k1n[2]
    thz = _herm_first_under(p0, d0, p1, d1, h, -tol_r, 0.0, b)  # noqa: F821
    top = b if thz > 1.0 else thz  # the part of the step before a confirmation
    thc = 2.0  # a crossing of r_z = 0 in [0, top] that opens a graze
    if S[OPEN] != 0.0:
        # the open graze closes where r_z comes back above 0 (-r_z below 0); a crossing may
        # follow in the same step
        thu = _herm_first_under(-p0, -d0, -p1, -d1, h, 0.0, 0.0, top)  # noqa: F821
        if thu <= 1.0:
            S[OPEN] = 0.0
            thc = _herm_first_under(p0, d0, p1, d1, h, 0.0, thu, top)  # noqa: F821
    else:
        thc = _herm_first_under(p0, d0, p1, d1, h, 0.0, 0.0, top)  # noqa: F821
    if thc <= 1.0:
        S[OPEN] = 1.0
        S[XT] = t + thc * h
        for ax in range(3):
            S[XR + ax] = _herm(y[ax], k1[ax], yn[ax], k1n[ax], h, thc)  # noqa: F821
            S[XV + ax] = _herm(y[3 + ax], k1[3 + ax], yn[3 + ax], k1n[3 + ax],  # noqa: F821
                               h, thc)
        S[XM] = _herm(y[6], k1[6], yn[6], k1n[6], h, thc)  # noqa: F821
        if -S[XV + 2] > tol_v:  # an impact, not a graze: the contact is this crossing
            S[CONT] = 1.0
            S[OPEN] = 0.0
            return thc
    if thz > 1.0:
        return 2.0
    S[CONT] = 1.0
    S[OPEN] = 0.0
    return thc if thc <= 1.0 else thz


def _blown(t, y, k1, yn, k1n, X, S, grav, blow_acc):  # noqa: N803
    """A blown-up command at a stage of this step (or at its new node): the step is not
    accepted and the case ends at its start (y, finite, every quantity physical), as
    "command_blown_up" (lgw.sim.results); theta = 0 on the interpolant between y and itself
    returns y exactly.  Unless no thrust could keep the vehicle off the ground (the corrected
    law's command diverges as r_z -> 0 with v_z != 0): then that impact is the outcome."""
    for j in range(NY):  # noqa: F821
        yn[j] = y[j]
        k1n[j] = k1[j]
    if (S[LANDED] != 0.0 or S[DRY] != 0.0 or S[CONT] != 0.0 or S[BELOW] != 0.0
            or not _impact_fn(t, y, S, grav, blow_acc)):  # noqa: F821
        S[BLOWN] = X[XBLOWN]


def _norms_at(y, k1, yn, k1n, h, th):
    """(|r|, |v|) at th in [0, 1] of the step, on its cubic Hermite interpolant."""
    rr = 0.0
    vv = 0.0
    for ax in range(3):
        rr += _herm(y[ax], k1[ax], yn[ax], k1n[ax], h, th) ** 2  # noqa: F821
        vv += _herm(y[3 + ax], k1[3 + ax], yn[3 + ax], k1n[3 + ax], h, th) ** 2  # noqa: F821
    return math.sqrt(rr), math.sqrt(vv)


def _landing(i, t, h, thf, y, k1, yn, k1n, S, tol_r, tol_v, r_land, v_land, fuel,  # noqa: N803
             m0):
    """The first th in [0, thf] of the step inside the landing criterion (given that thf is):
    bisection on L(th) = max(|r|/tol_r, |v|/tol_v) - 1, Hermite in th.  If it is <= thf, the
    landing there is recorded (S, r_land, v_land, fuel of case i).  Returns th."""
    a = 0.0
    b = thf
    for _ in range(BISECT_ITERS):  # noqa: F821
        mid = 0.5 * (a + b)
        rr = 0.0
        vv = 0.0
        for ax in range(3):
            rr += _herm(y[ax], k1[ax], yn[ax], k1n[ax], h, mid) ** 2  # noqa: F821
            vv += _herm(y[3 + ax], k1[3 + ax], yn[3 + ax], k1n[3 + ax], h,  # noqa: F821
                        mid) ** 2
        if math.sqrt(rr) <= tol_r and math.sqrt(vv) <= tol_v:
            b = mid
        else:
            a = mid
    if b <= thf:  # landed before (or as) the mass reached m_dry or the ground
        S[LANDED] = 1.0
        S[TLAND] = t + b * h
        for ax in range(3):
            r_land[i, ax] = _herm(y[ax], k1[ax], yn[ax], k1n[ax], h, b)  # noqa: F821
            v_land[i, ax] = _herm(y[3 + ax], k1[3 + ax], yn[3 + ax],  # noqa: F821
                                  k1n[3 + ax], h, b)
        fuel[i] = m0[i] - _herm(y[6], k1[6], yn[6], k1n[6], h, b)  # noqa: F821
    return b


def _touchdown(i, S, tol_r, tol_v, r_land, v_land, fuel, m0):  # noqa: N803
    """A located ground contact (S[XT], S[XR], ...) within the landing tolerance at the
    crossing is a touchdown: recorded as the landing of case i; True if so."""
    rc = math.sqrt(S[XR] ** 2 + S[XR + 1] ** 2 + S[XR + 2] ** 2)
    vc = math.sqrt(S[XV] ** 2 + S[XV + 1] ** 2 + S[XV + 2] ** 2)
    if not (rc <= tol_r and vc <= tol_v):
        return False
    S[LANDED] = 1.0
    S[TLAND] = S[XT]
    for ax in range(3):
        r_land[i, ax] = S[XR + ax]
        v_land[i, ax] = S[XV + ax]
    fuel[i] = m0[i] - S[XM]
    return True


def sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R):  # noqa: N803
    """Dry mass, ground contact, s-bands, landing and the metrics of one accepted step
    (lgw.sim.mars.batch).  The paths taken once per case at most (a blown-up command, the
    landing, a touchdown) are calls of helpers compiled apart (``COMPILED_APART``): inlined,
    they were most of this hook's share of the kernel's build."""
    m0 = C[2]
    (P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, eps, tol_r, tol_v,
     stop_landing, m_dry, blow_acc) = Q
    r_land, v_land, fuel = R[2], R[3], R[4]
    if X[XBLOWN] != 0.0:
        _blown_fn(t, y, k1, yn, k1n, X, S, grav, blow_acc)  # noqa: F821
        return STOP_INSIDE, 0.0  # noqa: F821
    has_landed = S[LANDED] != 0.0
    dry = S[DRY] != 0.0
    # the case's outcome was reached before this step (landing, dry mass, ground contact, or
    # it started below the ground)
    ended = has_landed or dry or S[CONT] != 0.0 or S[BELOW] != 0.0
    # dry mass: first th with m(th) <= m_dry, bisection on the Hermite interpolant
    thd = 1.0
    dry_now = False
    if not dry and yn[6] <= m_dry:
        dry_now = True
        thd = _herm_first_below(y[6], k1[6], yn[6], k1n[6], h, m_dry)  # noqa: F821
    # ground contact before the outcome, up to the dry mass: the case ends at thc if confirmed
    thc = 2.0
    if not ended:
        thc = _ground_fn(t, h, y, k1, yn, k1n, S, tol_r, tol_v, thd)  # noqa: F821
    hit = thc <= 1.0
    if hit:
        dry_now = False  # the contact came first
        thd = 1.0
    thf = thc if hit else thd  # the end of this step's flight (contact or dry mass)
    # with stop="landing" a case that runs dry or meets the ground ends at thf
    bend = thf if stop_landing else 1.0
    # sliding-variable bands, linear between nodes (up to the dry-mass stop)
    for j in range(6):
        s_new = yn[j] if j < 3 else X[3 + j]  # s2 from the rhs call at the new node
        lo, hi = _band(S[SOLD + j], s_new, eps)  # noqa: F821
        if lo <= hi and lo <= bend:
            if math.isnan(S[TF + j]):
                S[TF + j] = t + lo * h
            if hi < bend:
                S[TX + j] = t + hi * h
        S[SOLD + j] = s_new
    if not ended:
        # metrics until the outcome (landing or dry mass): command at the step's left node
        for ax in range(3):
            # node peaks at the left node (states on the trajectory: the tuner's certificate,
            # lgw.tuning.mars.design.limit_measure, is defined on them); stage peaks also
            # over every rhs evaluation of this step (X[XPK], X[XPKU]: its trial states and
            # its new node), where near an s1 = 0 crossing the corrected law's singular term
            # spikes at RK4's trial states
            S[PK + ax] = max(S[PK + ax], abs(XL[ax]))
            S[PKU + ax] = max(S[PKU + ax], abs(XL[3 + ax]))
            S[PKS + ax] = max(S[PKS + ax], abs(XL[ax]), X[XPK + ax])
            S[PKUS + ax] = max(S[PKUS + ax], abs(XL[3 + ax]), X[XPKU + ax])
        # landing: the criterion at the end of this step's flight (the node, or the located
        # contact or dry mass), then its first point by bisection
        if thf >= 1.0:
            rn = math.sqrt(yn[0] ** 2 + yn[1] ** 2 + yn[2] ** 2)
            vn = math.sqrt(yn[3] ** 2 + yn[4] ** 2 + yn[5] ** 2)
        else:
            rn, vn = _norms_at_fn(y, k1, yn, k1n, h, thf)  # noqa: F821
        frac = thf
        if rn <= tol_r and vn <= tol_v:
            b = _landing_fn(i, t, h, thf, y, k1, yn, k1n, S, tol_r, tol_v,  # noqa: F821
                            r_land, v_land, fuel, m0)
            if b <= thf:  # landed before (or as) the mass reached m_dry or the ground
                frac = b
                if hit:  # landed first: the contact after it is not the case's
                    hit = False
                    S[CONT] = 0.0
                has_landed = True
                if stop_landing:
                    dry_now = False  # the case ends at landing, above m_dry
        # a contact within the landing tolerance at the crossing is a touchdown
        if hit and _touchdown_fn(i, S, tol_r, tol_v, r_land, v_land, fuel, m0):  # noqa: F821
            has_landed = True
        if dry_now and not has_landed:  # out of propellant before landing
            # all of it: m = m_dry at the located crossing by definition (the Hermite value
            # there is m_dry to the bisection's 2^-60 of the step, or anything at all if a
            # blown-up stage command made the interpolant wild: fuel above the load)
            fuel[i] = m0[i] - m_dry
        # time saturated: where the limit's margin (|F| before the limit minus the limit),
        # linear between the step's nodes, is > 0, over the part of the step flown (a
        # left-endpoint count would be first order: 0.45 s against 0.475 s at dt/2 on a Table
        # III case)
        gl = _sat_margin_fn(XL, fmax, lim)  # noqa: F821
        gr = _sat_margin_fn(X, fmax, lim)  # noqa: F821
        if gl > 0.0 and gr > 0.0:
            S[TSAT] += frac * h
        elif gl > 0.0 or gr > 0.0:
            ths = gl / (gl - gr)
            if not (0.0 <= ths <= 1.0):  # an infinite margin: the left node decides
                S[TSAT] += frac * h if gl > 0.0 else 0.0
            elif gl > 0.0:
                S[TSAT] += min(ths, frac) * h
            else:
                S[TSAT] += max(0.0, frac - ths) * h
        # lowest point of the step up to its end (landing, dry mass or the node) on the
        # Hermite interpolant: node sampling misses a dip below ground that is shorter than
        # the step (dopri5's steps are ~1 s)
        zn = _herm_min(y[2], k1[2], yn[2], k1n[2], h, frac)  # noqa: F821
        if zn < S[ZMIN]:
            S[ZMIN] = zn
        if zn < 0.0:
            S[GROUND] = 1.0
    if dry_now:
        S[DRY] = 1.0
        if stop_landing:  # out of propellant: the case ends at th = thd
            return STOP_INSIDE, thd  # noqa: F821
    if hit and stop_landing:  # at the ground: the case ends at the contact
        return STOP_INSIDE, thc  # noqa: F821
    if has_landed and stop_landing:
        if (yn[6] < m_dry or thc <= 1.0) and not ended:
            # landed inside the step, and the node beyond is below the dry mass or the
            # ground: end at the landing itself (the end state is the landed vehicle)
            return STOP_INSIDE, frac  # noqa: F821
        _arrival_fn(yn, X, S, tol_r, tol_v)  # noqa: F821  (the node is accepted)
        return STOP_AT_NODE, thd  # noqa: F821
    _arrival_fn(yn, X, S, tol_r, tol_v)  # noqa: F821  (the node is accepted)
    return CONTINUE, thd  # noqa: F821


def sys_finish(i, t, y, S, C, Q, R):  # noqa: N803
    r0, v0, m0, dcoef, domega, dphase = C
    (P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, eps, tol_r, tol_v,
     stop_landing, m_dry, blow_acc) = Q
    (landed, t_land, r_land, v_land, fuel, peak, peak_u, tsat, minalt, ground, ts1, ts2,
     ts1x, ts2x, fexh, blown, peak_s, peak_us, peak_a, cont, t_cont, r_cont, v_cont,
     below) = R
    has_landed = S[LANDED] != 0.0
    dry = S[DRY] != 0.0
    landed[i] = has_landed
    fexh[i] = dry
    blown[i] = S[BLOWN]  # 0, 1 or 2 (lgw.sim.mars.batch turns it into flags)
    if dry and stop_landing and not has_landed:
        y[6] = m_dry  # the case stopped at the crossing: the end state has exactly m_dry
    t_land[i] = S[TLAND]
    below[i] = S[BELOW] != 0.0
    cont[i] = S[CONT] != 0.0
    t_cont[i] = S[XT] if S[CONT] != 0.0 else math.nan
    for ax in range(3):
        r_cont[i, ax] = S[XR + ax] if S[CONT] != 0.0 else math.nan
        v_cont[i, ax] = S[XV + ax] if S[CONT] != 0.0 else math.nan
    if not has_landed:
        if S[CONT] != 0.0:
            fuel[i] = m0[i] - S[XM]  # crashed: what was burnt to the crossing
        elif not dry:
            fuel[i] = m0[i] - y[6]
        for ax in range(3):
            r_land[i, ax] = math.nan
            v_land[i, ax] = math.nan
    for ax in range(3):
        peak[i, ax] = S[PK + ax]
        peak_u[i, ax] = S[PKU + ax]
        peak_s[i, ax] = S[PKS + ax]
        peak_us[i, ax] = S[PKUS + ax]
        peak_a[i, ax] = S[PKA + ax]
        ts1[i, ax] = S[TF + ax]
        ts2[i, ax] = S[TF + 3 + ax]
        ts1x[i, ax] = S[TX + ax]
        ts2x[i, ax] = S[TX + 3 + ax]
    tsat[i] = S[TSAT]
    minalt[i] = S[ZMIN]
    ground[i] = S[GROUND] != 0.0 or S[CONT] != 0.0  # a graze below r_z = 0, or the contact


HOOKS = (sys_init, sys_rhs, _sat_margin, _arrival, _impact, _ground, _blown, _norms_at,
         _landing, _touchdown, sys_start, sys_step, sys_finish)
# helpers, called as "<name>_fn"
COMPILED_APART = (_sat_margin, _arrival, _impact, _ground, _blown, _norms_at, _landing,
                  _touchdown)
# the hooks compiled into each law's kernel module (the vector field calls the law; it and the
# step hook are inlined, lgw.sim.integrate.INLINED_HOOKS); the others, and the helpers, do not
# depend on the law and live in one shared module (``hooks_module``)
KERNEL_HOOKS = (sys_rhs, sys_step)
SLOTS = {"TF": TF, "TX": TX, "SOLD": SOLD, "PK": PK, "PKU": PKU, "TSAT": TSAT, "ZMIN": ZMIN,
         "GROUND": GROUND, "LANDED": LANDED, "DRY": DRY, "TLAND": TLAND, "BLOWN": BLOWN,
         "PKS": PKS, "PKUS": PKUS, "PKA": PKA, "XPK": XPK, "XPKU": XPKU, "XBLOWN": XBLOWN,
         "CONT": CONT, "OPEN": OPEN, "XT": XT, "XR": XR, "XV": XV, "XM": XM, "BELOW": BELOW}


def hooks_source(hooks=HOOKS, cache: bool = False) -> str:
    """``hooks`` as written into a generated module, with the tracker slots they use."""
    from lgw.sim.integrate import hooks_text
    return hooks_text([f for f in hooks if f not in COMPILED_APART],
                      [f for f in hooks if f in COMPILED_APART], consts=SLOTS, cache=cache,
                      imports=("from lgw.sim.integrate import BISECT_ITERS",
                               "from lgw.sim.mars.kernel import _drag, _drag_fac"))


# --- assembly -------------------------------------------------------------------------------

def _deps() -> list[str]:
    """The sources of the modules a generated kernel imports compiled code and constants from
    (numba does not check them), as first read in this process (lgw.sim.kernel_cache)."""
    from lgw.sim import integrate, kernel_cache
    from lgw.sim.mars import kernel, parameters
    return kernel_cache.imported_sources(integrate, kernel, parameters)


def _prefix(kind: str, name: str) -> str:
    slug = "".join(c if c.isalnum() else "_" for c in name)
    return f"mars_{kind}_{slug}"


SIZES = {"NY": NY, "NX": NX, "NS": NS}


def hooks_text() -> str:
    """The full text of the generated module of the hooks that do not call the law."""
    from lgw.sim import integrate
    shared = tuple(f for f in HOOKS if f not in KERNEL_HOOKS)
    return integrate.hooks_module_source(hooks_source(shared, cache=True), SIZES)


@functools.cache
def hooks_module():
    """The generated module of the law-independent hooks (compiled once, numba-cached), which
    every law's kernel module imports."""
    from lgw.sim import kernel_cache
    return kernel_cache.generated_module("mars_hooks", hooks_text, _deps())


def kernel_text(spec) -> str:
    """The full text of the generated kernel module of law ``spec`` (what the cache keys): the
    law's generated code, the shared hooks imported from ``hooks_module``, the inlined hooks
    (``KERNEL_HOOKS``), and the integrator."""
    from lgw.sim import integrate
    from lgw.sim.mars.laws import law_source
    shared = [f.__name__ + ("_fn" if f in COMPILED_APART else "") for f in HOOKS
              if f not in KERNEL_HOOKS]
    imports = f"from {hooks_module().__name__} import {', '.join(shared)}"
    return integrate.kernel_module_source(law_source(spec, True),
                                          imports + "\n" + hooks_source(KERNEL_HOOKS), SIZES)


def law_text(spec) -> str:
    """The full text of the generated module of law ``spec`` alone (no s2)."""
    from lgw.sim.mars.laws import law_source
    return "\n".join(["# generated by lgw.sim.mars.kernel: do not edit (a cache entry)",
                      "import math", "import numba", "", law_source(spec, False)])


@functools.cache
def _kernel_module(spec):
    from lgw.sim import kernel_cache
    from lgw.sim.mars.laws import law_key_parts
    hooks_module()  # imported by the kernel module's text
    return kernel_cache.generated_module(_prefix("kernel", spec.name), lambda: kernel_text(spec),
                                         _deps(), law_key_parts(spec, True))


@functools.cache
def _law_module(spec):
    from lgw.sim import kernel_cache
    from lgw.sim.mars.laws import law_key_parts
    return kernel_cache.generated_module(_prefix("law", spec.name), lambda: law_text(spec),
                                         _deps(), law_key_parts(spec, False))


def kernel_module(name: str):
    """The generated kernel module of law ``name`` (``kernel``, ``law``), from the disk cache
    (written on first use)."""
    from lgw.sim.mars.laws import get_law
    return _kernel_module(get_law(name))


def law_module(name: str):
    """The generated module of law ``name`` alone (``law`` without s2), for tests and tools."""
    from lgw.sim.mars.laws import get_law
    return _law_module(get_law(name))


_deps()  # read the sources the kernels import now, at this module's import (see _deps)
