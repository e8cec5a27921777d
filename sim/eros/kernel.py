"""Seed 002's client of the generic integrator (``lgw.sim.integrate``): the sampled-data closed
loop of ``lgw.sim.eros.batch`` as hooks of a compiled kernel, on the integrator's zero-order
hold (``integration_tuple(..., sample=(dt, n_sub))``).

Plant (seed 002, eqs. (1)/(4)), state y = (r (3), r' (3), u_held (3)), m and m/s:

    r'' = -2 W x r' - W x (W x r) + g(r) + u_k + D(t),   W = (0, 0, OMEGA),   u_held' = 0

with the rotating-frame terms generated from ``lgw.theory.eros.laws.rotating_frame_accel``
(derived form), the two-mass-point gravity (2) generated from the derived gradient
``lgw.theory.eros.gravity.gradient`` with the fitted masses and positions (or no gravity), and
D_i(t) = amp sin(freq t + phase_i + case_phase) (``lgw.sim.eros.plant.Disturbance``) at the
integrator's stage times.  The polyhedral gravity is not in the kernel (its Werner-Scheeres sum
over 14744 faces and 22116 edges per right-hand side would dominate): it stays on the numpy path.

Controller (``sys_sample``, at t_k = t0 + k dt): the reference (8)-(10), the errors, the drift
f = rotating terms + two-point gravity (the controller's model always), D_k = D(t_k) in the
known-D case (else 0), the surface (6) or the PD surface, the fuzzy distance (21)-(22) and the
control (13)/(19)/(20): all six variants generated from ``lgw.theory.eros.laws.control`` (with
the |e| floor) by ``lgw.sim.codegen.vector_source``; the law in use is picked by a code in Q.
The per-sample histories (e, e', s, u held) are written into R, so the metrics of
``lgw.sim.eros.batch.metrics`` apply unchanged.

Outcomes as in ``lgw.sim.eros.batch`` (the numpy stand-in, the independent route): at each
sample the shape-model contact test (the stand-in's lazy exact test: a bounding-box screen,
then the solid-angle sum over the faces, re-done only when the path since the last exact test
reaches that point's clearance bound), then the control; a contact or a non-finite u or s stops
the case at t_k (its held control recorded as 0); a non-finite state inside a sample interval is
the integrator's ``nonfinite`` (time: that interval's t_k).  ``sys_finish`` fills the samples
after a stop from the frozen state, as the stand-in does.

Per-case inputs C = (pos0 (N, 3), vel0 (N, 3), case_phase (N,)); shared Q = (law code, switch
code, gains (9,) in the order of lgw.sim.eros.laws.GAIN_ARGS, reference coefficients (3, 4),
t0, dt, D amplitude, frequency, phases (3), D mode code, gravity code, OMEGA, the two points
(3), (3), their G M (2), contact test on, and the shape model: box lo, hi, vertices, faces, a
vertex per face, normals, centroids, radii) (flat: numba's parallel wrapper takes no nested
tuples);
results R = (E, ED, SV (N, K+1, 3), U (N, K, 3), code (N,) int, t_event (N,), k_last (N,) int,
pos (N, 3), vel (N, 3)).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp

NY = 9
NX = 6  # scratch: rotating terms (0:3) and gravity (3:6) of the latest rhs call
# tracker slots: contact monitor (status, clearance, path, last position), outcome, scratch
ST, CLR, PATH, HASLAST, LX, LY, LZ, OUT, TEV, KCUR, F0, G0, SV0, U0, DSC = (
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 13, 16, 19, 22)
NS = 23
# outcome codes of R's ``code`` (RUNNING: nothing happened)
RUNNING, CONTACT, NONFINITE = 0, 1, 2
LAW_CODE = {"pdsmc": 0, "ftsmc": 1, "fuzzy": 2}
SWITCH_CODE = {"sign": 0, "tanh": 1}
DIST_CODE = {"known": 0, "unknown": 1, "none": 2}
GRAVITY_CODE = {"two-point": 0, "none": 2}


# --- generated law and plant terms ---------------------------------------------------------

@functools.cache
def law_functions() -> list[tuple[str, str]]:
    """(name, source) of the generated functions: u_<law>_<switch>, the two surfaces, the fuzzy
    distance, the rotating-frame terms and the two-point gravity (all from SymPy)."""
    from lgw.sim.codegen import vector_source
    from lgw.theory.eros import gravity as GR
    from lgw.theory.eros import laws as L
    state = [("e", L.e), ("ed", L.ed), ("f", L.f), ("Dk", L.Dk), ("xdd", L.xdd), ("d", L.dist)]
    gains = [("alpha", L.alpha), ("beta", L.beta), ("r", L.r), ("k", L.k), ("lam", L.lam),
             ("N", L.N), ("M", L.M), ("phi", L.phi), ("ef", L.eps)]
    out = []
    for law in L.LAWS:
        for sw in L.SWITCHES:
            name = f"u_{law}_{sw}"
            out.append((name, vector_source(name, state + gains,
                                            L.control(law, sw, floor=True))))
    out.append(("s_pd", vector_source("s_pd", state[:2] + gains, L.surface("pdsmc"))))
    out.append(("s_ftsm", vector_source("s_ftsm", state[:2] + gains, L.surface("ftsmc"))))
    s1, s2, s3 = sp.symbols("s1:4", real=True)
    out.append(("fuzzy_d", vector_source("fuzzy_d", [("s1", s1), ("s2", s2), ("s3", s3),
                                                     ("alpha", L.alpha)],
                                         L.fuzzy_distance((s1, s2, s3)))))
    _, derived = L.rotating_frame_accel()
    w = sp.Symbol("omega", positive=True)
    xs = sp.symbols("x1:7", real=True)
    # arguments x1..x6 = (x, x', y, y', z, z'), the paper's state order in (4)
    out.append(("rot_terms", vector_source("rot_terms", [(str(x), x) for x in xs]
                                           + [("omega", w)], list(derived))))
    gsyms = (GR.x, GR.y, GR.z, GR.x1, GR.y1, GR.z1, GR.x2, GR.y2, GR.z2, GR.Gs, GR.M1, GR.M2)
    names = ("x", "y", "z", "xa", "ya", "za", "xb", "yb", "zb", "G", "M1", "M2")
    out.append(("two_point", vector_source("two_point", list(zip(names, gsyms, strict=True)),
                                           list(GR.gradient()))))
    return out


def law_header() -> str:
    """The generated laws and plant terms, and the compiled solid-angle sum of the mesh."""
    from lgw.sim.codegen import VECTOR_IMPORTS
    from lgw.sim.integrate import callee_source
    return "\n".join([*VECTOR_IMPORTS[1:], "from lgw.sim.eros.polygrav import solid_angle_sum",
                      "", *callee_source(law_functions())])


# --- templates (hooks; names resolve in the generated module) --------------------------------

def _inside(x0, x1, x2, V, F):
    """True if x is inside the mesh: the solid-angle sum of its faces > 2 pi
    (lgw.sim.eros.polygrav.solid_angle_sum; lgw.theory.eros.polyhedron.inside)."""
    return solid_angle_sum(x0, x1, x2, V, F) > 2.0 * math.pi  # noqa: F821


def _clearance(x0, x1, x2, A, NRM, CEN, RAD):
    """Lower bound (m) on the distance from x to the mesh surface (lgw.sim.eros.batch.clearance):
    min over faces of max(distance to the face's plane, to the ball about its centroid)."""
    best = math.inf
    for f in range(A.shape[0]):
        pl = abs((x0 - A[f, 0]) * NRM[f, 0] + (x1 - A[f, 1]) * NRM[f, 1]
                 + (x2 - A[f, 2]) * NRM[f, 2])
        d0 = x0 - CEN[f, 0]
        d1 = x1 - CEN[f, 1]
        d2 = x2 - CEN[f, 2]
        ball = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2) - RAD[f]
        v = pl if pl > ball else ball
        if v < best:
            best = v
    return best


def _contact(y, S, Q):  # noqa: N803
    """The stand-in's ContactMonitor for one case at one sample (lgw.sim.eros.batch)."""
    (lawc, swc, gv, coef, t0, ts, amp, freq, phase, distc, gravc, omega, p1, p2, gm,
     contact_on, lo, hi, V, F, A, NRM, CEN, RAD) = Q
    if S[HASLAST] != 0.0:  # noqa: F821
        d0 = y[0] - S[LX]  # noqa: F821
        d1 = y[1] - S[LY]  # noqa: F821
        d2 = y[2] - S[LZ]  # noqa: F821
        S[PATH] += math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)  # noqa: F821
    S[HASLAST] = 1.0  # noqa: F821
    S[LX] = y[0]  # noqa: F821
    S[LY] = y[1]  # noqa: F821
    S[LZ] = y[2]  # noqa: F821
    box = True
    for a in range(3):
        if not (y[a] >= lo[a] and y[a] <= hi[a]):  # NaN: outside
            box = False
    if not box:
        S[ST] = 0.0  # noqa: F821
        S[CLR] = -1.0  # noqa: F821
        return False
    if not (S[PATH] < S[CLR]):  # noqa: F821
        S[ST] = 1.0 if _inside_fn(y[0], y[1], y[2], V, F) else 0.0  # noqa: F821
        S[CLR] = _clearance_fn(y[0], y[1], y[2], A, NRM, CEN, RAD)  # noqa: F821
        S[PATH] = 0.0  # noqa: F821
    return S[ST] != 0.0  # noqa: F821


def _u_axis(lawc, swc, e, ed, f, dk, xdd, d, gv, out):
    """One axis of the generated control (lgw.theory.eros.laws.control): the variant picked
    by the law and switch codes, gains gv in the order of lgw.sim.eros.laws.GAIN_ARGS."""
    alpha, beta, r, kk, lam, N, M, phi, ef = (gv[0], gv[1], gv[2], gv[3], gv[4], gv[5],  # noqa: N806
                                              gv[6], gv[7], gv[8])
    if lawc == 0:
        if swc == 0:
            u_pdsmc_sign(e, ed, f, dk, xdd, d, alpha, beta, r, kk, lam, N, M, phi, ef,  # noqa
                         out)
        else:
            u_pdsmc_tanh(e, ed, f, dk, xdd, d, alpha, beta, r, kk, lam, N, M, phi, ef,  # noqa
                         out)
    elif lawc == 1:
        if swc == 0:
            u_ftsmc_sign(e, ed, f, dk, xdd, d, alpha, beta, r, kk, lam, N, M, phi, ef,  # noqa
                         out)
        else:
            u_ftsmc_tanh(e, ed, f, dk, xdd, d, alpha, beta, r, kk, lam, N, M, phi, ef,  # noqa
                         out)
    else:
        if swc == 0:
            u_fuzzy_sign(e, ed, f, dk, xdd, d, alpha, beta, r, kk, lam, N, M, phi, ef,  # noqa
                         out)
        else:
            u_fuzzy_tanh(e, ed, f, dk, xdd, d, alpha, beta, r, kk, lam, N, M, phi, ef,  # noqa
                         out)


def _s_axis(lawc, e, ed, gv, out):
    """One axis's surface value: the PD surface (law code 0) or the FTSM surface (6)."""
    if lawc == 0:
        s_pd(e, ed, gv[0], gv[1], gv[2], gv[3], gv[4], gv[5], gv[6], gv[7], gv[8],  # noqa
             out)
    else:
        s_ftsm(e, ed, gv[0], gv[1], gv[2], gv[3], gv[4], gv[5], gv[6], gv[7], gv[8],  # noqa
               out)


def _controller(i, k, y, S, C, Q, R):  # noqa: N803
    """Sample k (time t0 + k dt): reference, errors, drift, surface and the generated control;
    writes e, e', s into R's histories and u into S[U0:U0+3]; returns True if u and s are
    finite."""
    pos0, vel0, cph = C
    (lawc, swc, gv, coef, t0, ts, amp, freq, phase, distc, gravc, omega, p1, p2, gm,
     contact_on, lo, hi, V, F, A, NRM, CEN, RAD) = Q
    E, ED, SVH = R[0], R[1], R[2]
    alpha = gv[0]
    t = t0 + k * ts
    rot_terms(y[0], y[3], y[1], y[4], y[2], y[5], omega, S[F0:F0 + 3])  # noqa: F821
    two_point(y[0], y[1], y[2], p1[0], p1[1], p1[2], p2[0], p2[1], p2[2], 1.0,  # noqa: F821
              gm[0], gm[1], S[G0:G0 + 3])  # noqa: F821
    for a in range(3):
        c0 = coef[a, 0]
        c1 = coef[a, 1]
        c2 = coef[a, 2]
        c3 = coef[a, 3]
        e = y[a] - (c0 + c1 * t + c2 * t ** 2 + c3 * t ** 3)
        ed = y[3 + a] - (c1 + 2 * c2 * t + 3 * c3 * t ** 2)
        E[i, k, a] = e
        ED[i, k, a] = ed
        _s_axis_fn(lawc, e, ed, gv, S[SV0 + a:SV0 + a + 1])  # noqa: F821
        SVH[i, k, a] = S[SV0 + a]  # noqa: F821
    d = 0.0
    if lawc == 2:
        fuzzy_d(S[SV0], S[SV0 + 1], S[SV0 + 2], alpha, S[DSC:DSC + 1])  # noqa: F821
        d = S[DSC]  # noqa: F821
    ok = True
    for a in range(3):
        e = E[i, k, a]
        ed = ED[i, k, a]
        f = S[F0 + a] + S[G0 + a]  # noqa: F821
        dk = amp * math.sin(freq * t + (phase[a] + cph[i])) if distc == 0 else 0.0
        xdd = 2 * coef[a, 2] + 6 * coef[a, 3] * t
        _u_axis_fn(lawc, swc, e, ed, f, dk, xdd, d, gv, S[U0 + a:U0 + a + 1])  # noqa: F821
        if not (math.isfinite(S[U0 + a]) and math.isfinite(S[SV0 + a])):  # noqa: F821
            ok = False
    return ok


def sys_init(i, C, Q, y, S):  # noqa: N803
    pos0, vel0, cph = C
    for a in range(3):
        y[a] = pos0[i, a]
        y[3 + a] = vel0[i, a]
        y[6 + a] = 0.0
    for j in range(NS):  # noqa: F821
        S[j] = 0.0
    S[CLR] = -1.0  # noqa: F821
    S[TEV] = math.nan  # noqa: F821


def sys_rhs(t, Y, yr, K, kr, X, i, C, Q):  # noqa: N803
    """(4) with the held control: r' = v, v' = rotating terms + g + u_held + D(t0 + t)."""
    pos0, vel0, cph = C
    (lawc, swc, gv, coef, t0, ts, amp, freq, phase, distc, gravc, omega, p1, p2, gm,
     contact_on, lo, hi, V, F, A, NRM, CEN, RAD) = Q
    y = Y[yr]
    rot_terms(y[0], y[3], y[1], y[4], y[2], y[5], omega, X[0:3])  # noqa: F821
    if gravc == 0:
        two_point(y[0], y[1], y[2], p1[0], p1[1], p1[2], p2[0], p2[1], p2[2], 1.0,  # noqa: F821
                  gm[0], gm[1], X[3:6])
    else:
        X[3] = 0.0
        X[4] = 0.0
        X[5] = 0.0
    tt = t0 + t
    for a in range(3):
        acc = X[a] + X[3 + a] + y[6 + a]
        if distc != 2:
            acc = acc + amp * math.sin(freq * tt + (phase[a] + cph[i]))
        K[kr, a] = y[3 + a]
        K[kr, 3 + a] = acc
        K[kr, 6 + a] = 0.0


def sys_sample(i, k, t, y, S, C, Q, R):  # noqa: N803
    """Contact test, then the controller at sample k; the held u into y[6:9].  True: stop."""
    contact_on = Q[15]
    U = R[3]
    nk = U.shape[1]
    S[KCUR] = k  # noqa: F821
    hit = False
    if contact_on:
        hit = _contact_fn(y, S, Q)  # noqa: F821
    ok = _controller_fn(i, k, y, S, C, Q, R)  # noqa: F821
    if hit:
        S[OUT] = CONTACT  # noqa: F821
    elif not ok:
        S[OUT] = NONFINITE  # noqa: F821
    if S[OUT] != RUNNING:  # noqa: F821
        S[TEV] = Q[4] + k * Q[5]  # noqa: F821
        for a in range(3):
            y[6 + a] = 0.0
            if k < nk:
                U[i, k, a] = 0.0
        return True
    for a in range(3):
        y[6 + a] = S[U0 + a]  # noqa: F821
        if k < nk:
            U[i, k, a] = S[U0 + a]  # noqa: F821
    return False


def sys_start(i, y, X, S, C, Q, R):  # noqa: N803
    return False


def sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R):  # noqa: N803
    return CONTINUE, 1.0  # noqa: F821


def sys_finish(i, t, y, S, C, Q, R):  # noqa: N803
    """Outcome, event time and the final (frozen) state; the samples after a stop (or after a
    non-finite step, which the integrator ends the case on) from the frozen state, u = 0."""
    U, code, tev, klast, pos, vel = R[3], R[4], R[5], R[6], R[7], R[8]
    nk = U.shape[1]
    kc = int(S[KCUR])  # noqa: F821
    code[i] = int(S[OUT])  # noqa: F821
    tev[i] = S[TEV]  # noqa: F821
    klast[i] = kc
    for a in range(3):
        pos[i, a] = y[a]
        vel[i, a] = y[3 + a]
    for k in range(kc + 1, nk + 1):
        _controller_fn(i, k, y, S, C, Q, R)  # noqa: F821
        if k < nk:
            for a in range(3):
                U[i, k, a] = 0.0


HELPERS = (_inside, _clearance, _contact, _u_axis, _s_axis, _controller)
# inlined into sys_sample (measured: see benchmarks/bench_eros.py)
INLINE = (_u_axis, _s_axis, _controller)
HOOKS = (sys_init, sys_rhs, sys_sample, sys_start, sys_step, sys_finish)
SLOTS = {"ST": ST, "CLR": CLR, "PATH": PATH, "HASLAST": HASLAST, "LX": LX, "LY": LY, "LZ": LZ,
         "OUT": OUT, "TEV": TEV, "KCUR": KCUR, "F0": F0, "G0": G0, "SV0": SV0, "U0": U0,
         "DSC": DSC, "RUNNING": RUNNING, "CONTACT": CONTACT, "NONFINITE": NONFINITE}


def hooks_source() -> str:
    """The hooks as written into a kernel module, with their slots."""
    from lgw.sim.integrate import hooks_text
    return hooks_text(HOOKS, HELPERS, consts=SLOTS, inline=INLINE)


def _deps() -> list[str]:
    """The sources of the modules the generated kernel imports compiled code from (numba does
    not check them), as first read in this process (lgw.sim.kernel_cache)."""
    from lgw.sim import codegen, integrate, kernel_cache
    from lgw.sim.eros import kernel, polygrav
    return kernel_cache.imported_sources(codegen, integrate, kernel, polygrav)


def kernel_text() -> str:
    """The full text of the generated kernel module (what the cache keys)."""
    from lgw.sim import integrate
    return integrate.kernel_module_source(law_header(), hooks_source(),
                                          {"NY": NY, "NX": NX, "NS": NS})


@functools.cache
def kernel_module():
    """The generated kernel module of seed 002's sampled-data loop (all six variants), from
    the disk cache, keyed by its text and found by its inputs
    (``lgw.sim.kernel_cache.generated_module``)."""
    from lgw.sim import kernel_cache
    return kernel_cache.generated_module("eros_kernel", kernel_text, _deps())


@functools.cache
def body_arrays() -> tuple[np.ndarray, ...]:
    """(box lo, box hi, vertices, faces, a vertex per face, normals, centroids, radii) of the
    shape model (m), as lgw.sim.eros.batch._body."""
    from lgw.sim.eros.batch import _body
    from lgw.theory.eros.polyhedron import eros_polyhedron
    P = eros_polyhedron()
    lo, hi, a, n, cen, rad = _body()
    return tuple(np.ascontiguousarray(x) for x in (lo, hi, P.vertices, P.faces.astype(np.int64),
                                                   a, n, cen, rad))


_deps()  # read the sources the kernel imports now, at this module's import (see _deps)
