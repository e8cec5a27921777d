"""The whole Eros descent as hooks of the shared integrator (``lgw.sim.integrate``, its zero-order
hold): the plant with the shape model's gravity, a thrust-limited probe that burns propellant,
an unknown disturbance, a navigation error, and touchdown located inside the step.

Plant (seed 002 (1)/(4) in the rotating body frame), state y (NY = 22):

    r' = v
    v' = -2 W x v - W x (W x r) + g(r) + F / m + D(t),      W = (0, 0, OMEGA)
    m' = -|F| / (Isp g0)          (|F| = |F_x| + |F_y| + |F_z| per-axis thrusters, or the norm)
    F' = 0, and the held gravity model (g_k, Gamma_k, r_k)' = 0     (zero-order holds)

y = (r (3), v (3), F (3, N, held), m, g_k (3), Gamma_k (6), r_k (3)).  Gravity g(r) (code in
Q): 0 the two-point model (2) (generated from lgw.theory.eros.gravity), 1 the polyhedron at
every evaluation (``lgw.sim.eros.polygrav.poly_field``, Werner & Scheeres), 2 none, 3 the
polyhedron re-evaluated at a sample instant whenever the probe is more than ``lin_step`` (or,
near the body, LIN_FRAC times its distance to the surface) from the point of the last
evaluation, and between evaluations its first-order expansion
g_k + Gamma_k (r - r_k) with the exact gradient tensor Gamma_k (error <= 1/2 max|grad Gamma|
|r - r_k|^2; measured by tests/eros/test_descent.py against code 1).  D(t): solar radiation
pressure a_srp s(t) (s the Sun's direction, fixed in inertial space, so turning at -OMEGA about
z in the body frame; a_srp per case) plus the paper's sinusoid amp sin(freq t + phase_i +
case_phase) (both unknown to the controller).

Controller (``sys_sample``, at t_k = t0 + k dt): the navigation estimate r + dr, v + dv (dr, dv
first-order Gauss-Markov per axis, ``lgw.sim.eros.navnoise``: the same numbers for a case
whatever the batch), the piecewise-cubic reference (``lgw.theory.eros.descent.Profile``), the
drift f = rotating terms + the controller's gravity model (two-point, polyhedron or none) at the
estimate, D_k = 0 (the disturbance is unknown), the generated law (lgw.theory.eros.laws via
``lgw.sim.eros.kernel``'s header and its ``_u_axis``, ``_s_axis``), then the thrust limit:
F = m u saturated per axis (|F_i| <= F_max) or on the norm (direction kept).  The mass is the
controller's own bookkeeping (known).

Events (``sys_step``, every accepted step): contact with the shape model (the lazy exact
inside test of lgw.sim.eros.kernel: a bounding box, then the solid-angle sum, re-done only when
the path since the last test reaches that point's clearance bound), located inside the step by
bisection on the step's cubic Hermite interpolant to BISECT_TOL m; the dry mass, located by
bisection on m's interpolant; the earlier ends the case there (STOP_INSIDE), with the state at
that point.  A crossing in and out again within one step (the path moves <= |v| h, ~1 m) is not
seen.

Per-case inputs C = (pos0 (N, 3), vel0 (N, 3), m0 (N,), case_phase (N,), nav_id (N,) int,
srp (N,) m/s^2).  Shared Q: see ``shared``.  Results R = (code (N,) int, t_event (N,), yend
(N, 7) = r, v, m at the end, summary (N, NSUM), klast (N,) int, histories every ``stride``
samples: pos, e, ed, u (applied acceleration F/m), u_cmd (before the limit), s, dr (N, KR, 3)
and m (N, KR)); histories after the end are NaN.
"""

from __future__ import annotations

import functools
import math

NY = 22
NX = 17  # rotating terms (0:3), gravity (3:6), poly_field's output (6:17) of the latest call
# tracker slots
(ST, CLR, PATH, HASLAST, LX, LY, LZ, OUT, TEV, KCUR) = range(10)
NAV0 = 10  # dr (3), dv (3)
F0, G0, SV0, U0, UC0, DSC, UP0, EH0, EDH0 = 16, 19, 22, 25, 28, 31, 32, 35, 38
PF0 = 41  # poly_field output (11)
NS = 52
# the shared values Q, in order (``shared`` builds the tuple; the hooks index it by these)
Q_NAMES = ("law", "switch", "gains", "breaks", "coef", "t0", "dt", "omega", "gravity",
           "ctrl_gravity", "p1", "p2", "gm", "grho", "lin_step", "limit", "fmax", "ve",
           "m_dry", "sun0", "amp", "freq", "phase", "nav_on", "sig_r", "sig_v", "phi_nav",
           "seed", "stride", "lo", "hi", "V", "F", "FN", "EA", "EB", "EE", "EL", "A", "NRM",
           "CEN", "RAD")
(Q_LAW, Q_SW, Q_GAINS, Q_BREAKS, Q_COEF, Q_T0, Q_DT, Q_OMEGA, Q_GRAV, Q_CGRAV, Q_P1, Q_P2,
 Q_GM, Q_GRHO, Q_LIN, Q_LIMIT, Q_FMAX, Q_VE, Q_MDRY, Q_SUN, Q_AMP, Q_FREQ, Q_PHASE, Q_NAV,
 Q_SIGR, Q_SIGV, Q_PHIN, Q_SEED, Q_STRIDE, Q_LO, Q_HI, Q_V, Q_F, Q_FN, Q_EA, Q_EB, Q_EE, Q_EL,
 Q_A, Q_NRM, Q_CEN, Q_RAD) = range(len(Q_NAMES))
# the results R, in order
R_NAMES = ("code", "t_event", "yend", "summary", "klast", "pos", "e", "ed", "u", "u_cmd", "s",
           "dr", "m")
(R_CODE, R_TEV, R_YEND, R_SUM, R_KLAST, R_POS, R_E, R_ED, R_U, R_UC, R_S, R_DR,
 R_M) = range(len(R_NAMES))
# outcome codes (``lgw.sim.eros.descent`` names them)
RUNNING, CONTACT, DRY, NONFINITE = 0, 1, 2, 3
GRAVITY_CODE = {"two-point": 0, "polyhedron-exact": 1, "none": 2, "polyhedron": 3}
CTRL_GRAVITY_CODE = {"two-point": 0, "polyhedron": 1, "none": 2}
LIMIT_CODE = {"axis": 1, "norm": 2}
# summary columns
SUMMARY = ("e_max", "ed_max", "iae", "saturated", "samples", "u_peak", "u_cmd_peak", "chatter",
           "delta_v", "nav_r_max")
NSUM = len(SUMMARY)
BISECT_TOL = 1e-6  # m: the contact point is located to this along the path
LIN_FRAC = 0.1  # gravity code 3: re-evaluate within 10 % of the distance to the surface
BISECT_MAX = 80


# --- hooks (templates: names resolve in the generated module) --------------------------------

def _touching(x0, x1, x2, S, Q):  # noqa: N803
    """The lazy exact inside test at a step node (lgw.sim.eros.kernel._contact's rule)."""
    lo = Q[Q_LO]
    hi = Q[Q_HI]
    if S[HASLAST] != 0.0:
        d0 = x0 - S[LX]
        d1 = x1 - S[LY]
        d2 = x2 - S[LZ]
        S[PATH] += math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    S[HASLAST] = 1.0
    S[LX] = x0
    S[LY] = x1
    S[LZ] = x2
    if not (lo[0] <= x0 <= hi[0] and lo[1] <= x1 <= hi[1] and lo[2] <= x2 <= hi[2]):
        S[ST] = 0.0
        S[CLR] = -1.0
        return False
    if not (S[PATH] < S[CLR]):
        S[ST] = 1.0 if _inside_fn(x0, x1, x2, Q[Q_V], Q[Q_F]) else 0.0  # noqa: F821
        S[CLR] = _clearance_fn(x0, x1, x2, Q[Q_A], Q[Q_NRM], Q[Q_CEN], Q[Q_RAD])  # noqa: F821
        S[PATH] = 0.0
    return S[ST] != 0.0


def _gravity(x0, x1, x2, code, Q, out, pf):  # noqa: N803
    """The gravity model ``code`` (two-point 0, polyhedron 1, none 2) at x into out (3,); pf:
    scratch for poly_field (11,)."""
    if code == 0:
        p1 = Q[Q_P1]
        p2 = Q[Q_P2]
        gm = Q[Q_GM]
        two_point(x0, x1, x2, p1[0], p1[1], p1[2], p2[0], p2[1], p2[2], 1.0,  # noqa: F821
                  gm[0], gm[1], out)
    elif code == 1:
        poly_field(x0, x1, x2, Q[Q_V], Q[Q_F], Q[Q_FN], Q[Q_EA], Q[Q_EB], Q[Q_EE],  # noqa: F821
                   Q[Q_EL], Q[Q_GRHO], pf)
        out[0] = pf[0]
        out[1] = pf[1]
        out[2] = pf[2]
    else:
        out[0] = 0.0
        out[1] = 0.0
        out[2] = 0.0


def _refresh_gravity(y, S, Q):  # noqa: N803
    """Gravity code 3: the polyhedron and its gradient tensor at r, held in y[10:22]."""
    pf = S[PF0:PF0 + 11]
    poly_field(y[0], y[1], y[2], Q[Q_V], Q[Q_F], Q[Q_FN], Q[Q_EA], Q[Q_EB], Q[Q_EE],  # noqa
               Q[Q_EL], Q[Q_GRHO], pf)
    for a in range(3):
        y[10 + a] = pf[a]
        y[19 + a] = y[a]
    for j in range(6):
        y[13 + j] = pf[5 + j]


def sys_init(i, C, Q, y, S):  # noqa: N803
    pos0 = C[0]
    vel0 = C[1]
    m0 = C[2]
    for a in range(3):
        y[a] = pos0[i, a]
        y[3 + a] = vel0[i, a]
    for j in range(6, NY):
        y[j] = 0.0
    y[9] = m0[i]
    for j in range(NS):
        S[j] = 0.0
    S[CLR] = -1.0
    S[TEV] = math.nan


def sys_rhs(t, Y, yr, K, kr, X, i, C, Q):  # noqa: N803
    """r' = v, v' = rotating terms + g + F/m + D(t0 + t), m' = -|F| / v_e, holds' = 0."""
    cph = C[3]
    srp = C[5]
    omega = Q[Q_OMEGA]
    gravc = Q[Q_GRAV]
    sun = Q[Q_SUN]
    amp = Q[Q_AMP]
    phase = Q[Q_PHASE]
    y = Y[yr]
    rot_terms(y[0], y[3], y[1], y[4], y[2], y[5], omega, X[0:3])  # noqa: F821
    if gravc == 3:
        d0 = y[0] - y[19]
        d1 = y[1] - y[20]
        d2 = y[2] - y[21]
        X[3] = y[10] + y[13] * d0 + y[14] * d1 + y[15] * d2
        X[4] = y[11] + y[14] * d0 + y[16] * d1 + y[17] * d2
        X[5] = y[12] + y[15] * d0 + y[17] * d1 + y[18] * d2
    else:
        _gravity_fn(y[0], y[1], y[2], gravc, Q, X[3:6], X[6:17])  # noqa: F821
    tt = Q[Q_T0] + t
    c = math.cos(omega * tt)
    s = math.sin(omega * tt)
    sb0 = c * sun[0] + s * sun[1]
    sb1 = -s * sun[0] + c * sun[1]
    m = y[9]
    for a in range(3):
        acc = X[a] + X[3 + a] + y[6 + a] / m
        acc += srp[i] * (sb0 if a == 0 else (sb1 if a == 1 else sun[2]))
        if amp != 0.0:
            acc += amp * math.sin(Q[Q_FREQ] * tt + (phase[a] + cph[i]))
        K[kr, a] = y[3 + a]
        K[kr, 3 + a] = acc
    for j in range(6, NY):
        K[kr, j] = 0.0
    if Q[Q_LIMIT] == 2:
        fn = math.sqrt(y[6] * y[6] + y[7] * y[7] + y[8] * y[8])
    else:
        fn = abs(y[6]) + abs(y[7]) + abs(y[8])
    K[kr, 9] = -fn / Q[Q_VE]


def sys_sample(i, k, t, y, S, C, Q, R):  # noqa: N803
    """The navigation estimate, the controller and the thrust limit at sample k; the held F
    into y[6:9] (and gravity code 3's refreshed model into y[10:22]).  True: stop."""
    nav_id = C[4]
    lawc = Q[Q_LAW]
    gv = Q[Q_GAINS]
    breaks = Q[Q_BREAKS]
    coef = Q[Q_COEF]
    ts = Q[Q_DT]
    stride = Q[Q_STRIDE]
    summ = R[R_SUM]
    HP = R[R_POS]
    S[KCUR] = k
    if Q[Q_GRAV] == 3:
        # re-evaluate beyond lin_step, or beyond LIN_FRAC of the distance to the surface
        # (its lower bound from the contact monitor) near the body
        lim = Q[Q_LIN]
        if S[CLR] >= 0.0:
            lim = min(lim, LIN_FRAC * max(S[CLR] - S[PATH], 0.0))
        d0 = y[0] - y[19]
        d1 = y[1] - y[20]
        d2 = y[2] - y[21]
        if k == 0 or d0 * d0 + d1 * d1 + d2 * d2 >= lim * lim:
            _refresh_gravity_fn(y, S, Q)  # noqa: F821
    tk = Q[Q_T0] + k * ts
    # navigation error: first-order Gauss-Markov per component, stationary from k = 0
    if Q[Q_NAV]:
        phi_n = Q[Q_PHIN]
        q = math.sqrt(1.0 - phi_n * phi_n)
        for j in range(6):
            w = nav_normal(Q[Q_SEED], nav_id[i], k, j)  # noqa: F821
            sig = Q[Q_SIGR] if j < 3 else Q[Q_SIGV]
            if k == 0:
                S[NAV0 + j] = sig * w
            else:
                S[NAV0 + j] = phi_n * S[NAV0 + j] + sig * q * w
    # the reference's segment and the errors (true and as the controller sees them)
    seg = 0
    for j in range(breaks.shape[0]):
        if tk >= breaks[j]:
            seg = j
    tau = tk - breaks[seg]
    xh0 = y[0] + S[NAV0]
    xh1 = y[1] + S[NAV0 + 1]
    xh2 = y[2] + S[NAV0 + 2]
    vh0 = y[3] + S[NAV0 + 3]
    vh1 = y[4] + S[NAV0 + 4]
    vh2 = y[5] + S[NAV0 + 5]
    rot_terms(xh0, vh0, xh1, vh1, xh2, vh2, Q[Q_OMEGA], S[F0:F0 + 3])  # noqa: F821
    _gravity_fn(xh0, xh1, xh2, Q[Q_CGRAV], Q, S[G0:G0 + 3], S[PF0:PF0 + 11])  # noqa: F821
    rec = stride > 0 and k % stride == 0 and k // stride < HP.shape[1]
    kr = k // stride if stride > 0 else 0
    e_sq = 0.0
    ed_sq = 0.0
    for a in range(3):
        c1 = coef[seg, a, 1]
        c2 = coef[seg, a, 2]
        c3 = coef[seg, a, 3]
        et = y[a] - (coef[seg, a, 0] + tau * (c1 + tau * (c2 + tau * c3)))
        edt = y[3 + a] - (c1 + tau * (2.0 * c2 + 3.0 * tau * c3))
        e_sq += et * et
        ed_sq += edt * edt
        S[EH0 + a] = et + S[NAV0 + a]
        S[EDH0 + a] = edt + S[NAV0 + 3 + a]
        _s_axis_fn(lawc, S[EH0 + a], S[EDH0 + a], gv, S[SV0 + a:SV0 + a + 1])  # noqa: F821
        if rec:
            HP[i, kr, a] = y[a]
            R[R_E][i, kr, a] = et
            R[R_ED][i, kr, a] = edt
            R[R_S][i, kr, a] = S[SV0 + a]
            R[R_DR][i, kr, a] = S[NAV0 + a]
    d = 0.0
    if lawc == 2:
        fuzzy_d(S[SV0], S[SV0 + 1], S[SV0 + 2], gv[0], S[DSC:DSC + 1])  # noqa: F821
        d = S[DSC]
    ok = True
    un = 0.0
    for a in range(3):
        xdd = 2.0 * coef[seg, a, 2] + 6.0 * tau * coef[seg, a, 3]
        _u_axis_fn(lawc, Q[Q_SW], S[EH0 + a], S[EDH0 + a], S[F0 + a] + S[G0 + a], 0.0,  # noqa
                   xdd, d, gv, S[UC0 + a:UC0 + a + 1])
        un += S[UC0 + a] * S[UC0 + a]
        if not (math.isfinite(S[UC0 + a]) and math.isfinite(S[SV0 + a])):
            ok = False
    un = math.sqrt(un)
    if not ok:
        S[OUT] = NONFINITE
        S[TEV] = tk
        for a in range(3):
            y[6 + a] = 0.0
        return True
    # the thrust limit, on the acceleration F / m (m: the controller's own bookkeeping)
    m = y[9]
    umax = Q[Q_FMAX] / m
    sat = False
    for a in range(3):
        S[U0 + a] = S[UC0 + a]
    if Q[Q_LIMIT] == 2:
        if un > umax:
            sat = True
            for a in range(3):
                S[U0 + a] *= umax / un
    else:
        for a in range(3):
            if S[U0 + a] > umax:
                S[U0 + a] = umax
                sat = True
            elif S[U0 + a] < -umax:
                S[U0 + a] = -umax
                sat = True
    ua = 0.0
    tv = 0.0
    dr = 0.0
    for a in range(3):
        y[6 + a] = m * S[U0 + a]
        ua += S[U0 + a] * S[U0 + a]
        if k > 0:
            tv += abs(S[U0 + a] - S[UP0 + a])
        S[UP0 + a] = S[U0 + a]
        dr += S[NAV0 + a] * S[NAV0 + a]
        if rec:
            R[R_U][i, kr, a] = S[U0 + a]
            R[R_UC][i, kr, a] = S[UC0 + a]
    if rec:
        R[R_M][i, kr] = m
    ua = math.sqrt(ua)
    en = math.sqrt(e_sq)
    summ[i, 0] = max(summ[i, 0], en)
    summ[i, 1] = max(summ[i, 1], math.sqrt(ed_sq))
    summ[i, 2] += en * ts
    if sat:
        summ[i, 3] += 1.0
    summ[i, 4] += 1.0
    summ[i, 5] = max(summ[i, 5], ua)
    summ[i, 6] = max(summ[i, 6], un)
    summ[i, 7] += tv
    summ[i, 8] += ua * ts
    summ[i, 9] = max(summ[i, 9], math.sqrt(dr))
    return False


def sys_start(i, y, X, S, C, Q, R):  # noqa: N803
    """A start inside the shape model is refused by the caller (lgw.sim.eros.descent)."""
    return False


def sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R):  # noqa: N803
    """Contact with the shape model and the dry mass, each located inside the step."""
    theta = 2.0
    what = RUNNING
    if _touching_fn(yn[0], yn[1], yn[2], S, Q):  # noqa: F821
        # bisection on the step's cubic Hermite interpolant: lo outside, hi inside
        lo = 0.0
        hi = 1.0
        dx = yn[0] - y[0]
        dy = yn[1] - y[1]
        dz = yn[2] - y[2]
        span = math.sqrt(dx * dx + dy * dy + dz * dz)
        for _ in range(BISECT_MAX):
            if (hi - lo) * span <= BISECT_TOL:
                break
            mid = 0.5 * (lo + hi)
            p0 = _herm(y[0], k1[0], yn[0], k1n[0], h, mid)  # noqa: F821
            p1 = _herm(y[1], k1[1], yn[1], k1n[1], h, mid)  # noqa: F821
            p2 = _herm(y[2], k1[2], yn[2], k1n[2], h, mid)  # noqa: F821
            if _inside_fn(p0, p1, p2, Q[Q_V], Q[Q_F]):  # noqa: F821
                hi = mid
            else:
                lo = mid
        theta = hi
        what = CONTACT
    if yn[9] <= Q[Q_MDRY]:
        th = _herm_first_below(y[9], k1[9], yn[9], k1n[9], h, Q[Q_MDRY])  # noqa: F821
        if th < theta:
            theta = th
            what = DRY
    if what == RUNNING:
        return CONTINUE, 1.0  # noqa: F821
    S[OUT] = what
    S[TEV] = Q[Q_T0] + t + theta * h
    return STOP_INSIDE, theta  # noqa: F821


def sys_finish(i, t, y, S, C, Q, R):  # noqa: N803
    """Outcome, event time, the end state; histories after the end are NaN."""
    stride = Q[Q_STRIDE]
    kc = int(S[KCUR])
    R[R_CODE][i] = int(S[OUT])
    R[R_TEV][i] = S[TEV]
    R[R_KLAST][i] = kc
    yend = R[R_YEND]
    for a in range(6):
        yend[i, a] = y[a]
    yend[i, 6] = y[9]
    if stride > 0:
        first = kc // stride + 1
        for hh in (R[R_POS], R[R_E], R[R_ED], R[R_U], R[R_UC], R[R_S], R[R_DR]):
            for kk in range(first, hh.shape[1]):
                for a in range(3):
                    hh[i, kk, a] = math.nan
        hm = R[R_M]
        for kk in range(first, hm.shape[1]):
            hm[i, kk] = math.nan


HELPERS = (_touching, _gravity, _refresh_gravity)
HOOKS = (sys_init, sys_rhs, sys_sample, sys_start, sys_step, sys_finish)
SLOTS = {"ST": ST, "CLR": CLR, "PATH": PATH, "HASLAST": HASLAST, "LX": LX, "LY": LY, "LZ": LZ,
         "OUT": OUT, "TEV": TEV, "KCUR": KCUR, "NAV0": NAV0, "F0": F0, "G0": G0, "SV0": SV0,
         "U0": U0, "UC0": UC0, "DSC": DSC, "UP0": UP0, "EH0": EH0, "EDH0": EDH0, "PF0": PF0,
         "RUNNING": RUNNING, "CONTACT": CONTACT, "DRY": DRY, "NONFINITE": NONFINITE,
         "BISECT_TOL": BISECT_TOL, "LIN_FRAC": LIN_FRAC, "BISECT_MAX": BISECT_MAX,
         **{f"Q_{n}": v for n, v in zip(("LAW", "SW", "GAINS", "BREAKS", "COEF", "T0", "DT",
                                          "OMEGA", "GRAV", "CGRAV", "P1", "P2", "GM", "GRHO",
                                          "LIN", "LIMIT", "FMAX", "VE", "MDRY", "SUN", "AMP",
                                          "FREQ", "PHASE", "NAV", "SIGR", "SIGV", "PHIN",
                                          "SEED", "STRIDE", "LO", "HI", "V", "F", "FN", "EA",
                                          "EB", "EE", "EL", "A", "NRM", "CEN", "RAD"),
                                         range(len(Q_NAMES)), strict=True)},
         **{f"R_{n}": v for n, v in zip(("CODE", "TEV", "YEND", "SUM", "KLAST", "POS", "E",
                                          "ED", "U", "UC", "S", "DR", "M"),
                                         range(len(R_NAMES)), strict=True)}}


def hooks_source() -> str:
    """The hooks as written into the kernel module: the tracking kernel's shared helpers
    (clearance bound, one axis's control and surface), this module's helpers and hooks."""
    from lgw.sim.eros import kernel as KN
    from lgw.sim.integrate import hooks_text

    shared = (KN._inside, KN._clearance, KN._u_axis, KN._s_axis)
    return hooks_text(HOOKS, shared + HELPERS, consts=SLOTS, inline=(KN._u_axis, KN._s_axis))


HEADER_IMPORTS = ("from lgw.sim.eros.polygrav import poly_field",
                  "from lgw.sim.eros.navnoise import nav_normal")


def _deps() -> list[str]:
    """The sources of the modules the generated kernel imports compiled code from (numba does
    not check them), as first read in this process (lgw.sim.kernel_cache)."""
    from lgw.sim import codegen, integrate, kernel_cache
    from lgw.sim.eros import descent_kernel, kernel, navnoise, polygrav
    return kernel_cache.imported_sources(codegen, integrate, kernel, descent_kernel, polygrav,
                                         navnoise)


def kernel_text() -> str:
    """The full text of the generated kernel module (what the cache keys)."""
    from lgw.sim import integrate
    from lgw.sim.eros import kernel as KN
    return integrate.kernel_module_source(KN.law_header() + "\n" + "\n".join(HEADER_IMPORTS),
                                          hooks_source(), {"NY": NY, "NX": NX, "NS": NS})


@functools.cache
def kernel_module():
    """The generated kernel module of the descent (``kernel`` and the generated laws), from
    the disk cache, keyed by its text and found by its inputs
    (``lgw.sim.kernel_cache.generated_module``)."""
    from lgw.sim import kernel_cache
    return kernel_cache.generated_module("eros_descent", kernel_text, _deps())


def shared(values: dict) -> tuple:
    """The Q tuple from a dict keyed by ``Q_NAMES`` without the mesh entries (those are added
    here: lgw.sim.eros.kernel.body_arrays and lgw.sim.eros.polygrav.eros_arrays); flat,
    numba's parallel wrapper takes no nested tuples."""
    from lgw.sim.eros.kernel import body_arrays
    from lgw.sim.eros.polygrav import eros_arrays

    lo, hi, _, _, A, NRM, CEN, RAD = body_arrays()
    V, F, FN, EA, EB, EE, EL = eros_arrays()
    mesh = {"lo": lo, "hi": hi, "V": V, "F": F, "FN": FN, "EA": EA, "EB": EB, "EE": EE,
            "EL": EL, "A": A, "NRM": NRM, "CEN": CEN, "RAD": RAD}
    v = dict(values, **mesh)
    missing = set(Q_NAMES) - set(v)
    extra = set(v) - set(Q_NAMES)
    if missing or extra:
        raise ValueError(f"Q: missing {sorted(missing)}, unknown {sorted(extra)}")
    return tuple(v[n] for n in Q_NAMES)


_deps()  # read the sources the kernel imports now, at this module's import (see _deps)
