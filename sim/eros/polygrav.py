"""The polyhedral gravity of Eros compiled for the kernels: Werner & Scheeres (1997) with the
per-edge and per-face data precomputed, evaluated by numba in one pass over the mesh.

The same closed form as ``lgw.theory.eros.polyhedron`` (numpy, the direct route the tests
compare against), restated per unique edge instead of per half-edge:

    g   = -G rho sum_e E_e r_e L_e  +  G rho sum_f F_f r_f w_f
    U   =  G rho/2 sum_e r_e.E_e.r_e L_e  -  G rho/2 sum_f r_f.F_f.r_f w_f
    Gam =  G rho sum_e E_e L_e  -  G rho sum_f F_f w_f           (= grad g, symmetric)
    sum_f w_f = 4 pi inside, 0 outside (2 pi on a face)

with E_e = n_A m_A^T + n_B m_B^T the sum over the edge's two half-edges of (face normal) x
(outward in-plane edge normal), F_f = n_f n_f^T, r_e the vector from the field point to the
edge's first vertex, L_e = ln((a + b + l)/(a + b - l)) and w_f the signed solid angle of face f
(van Oosterom & Strackee).  Werner & Scheeres (1997) eqs. (10)-(16); the gradient tensor is
their eq. (17) (the derivatives of L_e and w_f cancel in the sums).  The per-vertex vectors and
distances are computed once per evaluation (each vertex serves ~6 faces and ~6 edges).

Cost: one evaluation visits 7374 vertices, 22116 edges (one log) and 14744 faces (one atan2);
benchmarks/bench_eros.py prints the time per evaluation.
"""

from __future__ import annotations

import functools
import math

import numba
import numpy as np

# layout of the output vector of ``poly_field``
GX, GY, GZ, POT, OMEGA_SUM, GXX, GXY, GXZ, GYY, GYZ, GZZ = range(11)
NOUT = 11


def edge_data(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, ...]:
    """(EA, EB, EE, EL) per unique edge of a closed, outward-oriented triangle mesh: the two
    vertex indices, the 3 x 3 dyad E_e flattened row-major (9,) and the length (m).

    Every half-edge (face f, directed edge a -> b) adds n_f m_fe^T with m_fe = (b - a) x n_f /
    |b - a| the outward edge normal in the face's plane; an edge of a closed mesh has exactly
    two half-edges (checked)."""
    v = np.asarray(vertices, float)
    fc = np.asarray(faces, np.int64)
    a_, b_, c_ = v[fc[:, 0]], v[fc[:, 1]], v[fc[:, 2]]
    n = np.cross(b_ - a_, c_ - a_)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    ha = fc[:, [0, 1, 2]].ravel()
    hb = fc[:, [1, 2, 0]].ravel()
    hf = np.repeat(np.arange(len(fc)), 3)
    m = np.cross(v[hb] - v[ha], n[hf])
    m /= np.linalg.norm(m, axis=1, keepdims=True)
    dyad = np.einsum("hi,hj->hij", n[hf], m).reshape(-1, 9)
    lo, hi = np.minimum(ha, hb), np.maximum(ha, hb)
    key = lo * len(v) + hi
    uniq, inv, counts = np.unique(key, return_inverse=True, return_counts=True)
    if not np.all(counts == 2):
        raise ValueError("the mesh is not closed: an edge has other than two faces")
    EE = np.zeros((len(uniq), 9))
    np.add.at(EE, inv, dyad)
    EA, EB = uniq // len(v), uniq % len(v)
    EL = np.linalg.norm(v[EB] - v[EA], axis=1)
    return EA.astype(np.int64), EB.astype(np.int64), EE, EL


def face_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    v = np.asarray(vertices, float)
    fc = np.asarray(faces, np.int64)
    n = np.cross(v[fc[:, 1]] - v[fc[:, 0]], v[fc[:, 2]] - v[fc[:, 0]])
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def mesh_arrays(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, ...]:
    """(V, F, FN, EA, EB, EE, EL): contiguous arrays for ``poly_field`` / ``solid_angle_sum``."""
    EA, EB, EE, EL = edge_data(vertices, faces)
    return tuple(np.ascontiguousarray(x) for x in (
        np.asarray(vertices, float), np.asarray(faces, np.int64),
        face_normals(vertices, faces), EA, EB, EE, EL))


@functools.cache
def eros_arrays() -> tuple[np.ndarray, ...]:
    """``mesh_arrays`` of the Eros shape model (metres, ``lgw.theory.eros.polyhedron``)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron

    P = eros_polyhedron()
    return mesh_arrays(P.vertices, P.faces)


@numba.njit(cache=True, error_model="numpy")
def poly_field(x0: float, x1: float, x2: float, V, F, FN, EA, EB, EE, EL, grho: float,
               out) -> None:
    """Acceleration (m/s^2), potential (m^2/s^2), the sum of the faces' solid angles and the
    gravity-gradient tensor (1/s^2) of the uniform polyhedron at (x0, x1, x2) (m), G rho in
    1/s^2, into ``out`` (NOUT,) in the order GX, GY, GZ, POT, OMEGA_SUM, GXX, GXY, GXZ, GYY,
    GYZ, GZZ (module docstring)."""
    nv = V.shape[0]
    R = np.empty((nv, 4))  # vertex - x and its norm
    for i in range(nv):
        a = V[i, 0] - x0
        b = V[i, 1] - x1
        c = V[i, 2] - x2
        R[i, 0] = a
        R[i, 1] = b
        R[i, 2] = c
        R[i, 3] = math.sqrt(a * a + b * b + c * c)
    g0 = g1 = g2 = 0.0
    u = 0.0
    t00 = t01 = t02 = t11 = t12 = t22 = 0.0
    for e in range(EA.shape[0]):
        ia = EA[e]
        ib = EB[e]
        s = R[ia, 3] + R[ib, 3]
        le = EL[e]
        L = math.log((s + le) / (s - le))
        r0 = R[ia, 0]
        r1 = R[ia, 1]
        r2 = R[ia, 2]
        E = EE[e]
        q0 = E[0] * r0 + E[1] * r1 + E[2] * r2
        q1 = E[3] * r0 + E[4] * r1 + E[5] * r2
        q2 = E[6] * r0 + E[7] * r1 + E[8] * r2
        g0 -= q0 * L
        g1 -= q1 * L
        g2 -= q2 * L
        u += (r0 * q0 + r1 * q1 + r2 * q2) * L
        t00 += E[0] * L
        t01 += 0.5 * (E[1] + E[3]) * L
        t02 += 0.5 * (E[2] + E[6]) * L
        t11 += E[4] * L
        t12 += 0.5 * (E[5] + E[7]) * L
        t22 += E[8] * L
    wsum = 0.0
    for f in range(F.shape[0]):
        ia = F[f, 0]
        ib = F[f, 1]
        ic = F[f, 2]
        a0 = R[ia, 0]
        a1 = R[ia, 1]
        a2 = R[ia, 2]
        b0 = R[ib, 0]
        b1 = R[ib, 1]
        b2 = R[ib, 2]
        c0 = R[ic, 0]
        c1 = R[ic, 1]
        c2 = R[ic, 2]
        la = R[ia, 3]
        lb = R[ib, 3]
        lc = R[ic, 3]
        num = a0 * (b1 * c2 - b2 * c1) + a1 * (b2 * c0 - b0 * c2) + a2 * (b0 * c1 - b1 * c0)
        den = (la * lb * lc + la * (b0 * c0 + b1 * c1 + b2 * c2)
               + lb * (c0 * a0 + c1 * a1 + c2 * a2) + lc * (a0 * b0 + a1 * b1 + a2 * b2))
        w = 2.0 * math.atan2(num, den)
        wsum += w
        n0 = FN[f, 0]
        n1 = FN[f, 1]
        n2 = FN[f, 2]
        nr = n0 * a0 + n1 * a1 + n2 * a2
        g0 += n0 * nr * w
        g1 += n1 * nr * w
        g2 += n2 * nr * w
        u -= nr * nr * w
        t00 -= n0 * n0 * w
        t01 -= n0 * n1 * w
        t02 -= n0 * n2 * w
        t11 -= n1 * n1 * w
        t12 -= n1 * n2 * w
        t22 -= n2 * n2 * w
    out[GX] = grho * g0
    out[GY] = grho * g1
    out[GZ] = grho * g2
    out[POT] = 0.5 * grho * u
    out[OMEGA_SUM] = wsum
    out[GXX] = grho * t00
    out[GXY] = grho * t01
    out[GXZ] = grho * t02
    out[GYY] = grho * t11
    out[GYZ] = grho * t12
    out[GZZ] = grho * t22


@numba.njit(cache=True, error_model="numpy")
def solid_angle_sum(x0: float, x1: float, x2: float, V, F) -> float:
    """Sum of the signed solid angles of the faces seen from x: 4 pi inside, 0 outside
    (``lgw.theory.eros.polyhedron.inside``: inside iff > 2 pi)."""
    tot = 0.0
    for f in range(F.shape[0]):
        ia = F[f, 0]
        ib = F[f, 1]
        ic = F[f, 2]
        a0 = V[ia, 0] - x0
        a1 = V[ia, 1] - x1
        a2 = V[ia, 2] - x2
        b0 = V[ib, 0] - x0
        b1 = V[ib, 1] - x1
        b2 = V[ib, 2] - x2
        c0 = V[ic, 0] - x0
        c1 = V[ic, 1] - x1
        c2 = V[ic, 2] - x2
        la = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        lb = math.sqrt(b0 * b0 + b1 * b1 + b2 * b2)
        lc = math.sqrt(c0 * c0 + c1 * c1 + c2 * c2)
        num = a0 * (b1 * c2 - b2 * c1) + a1 * (b2 * c0 - b0 * c2) + a2 * (b0 * c1 - b1 * c0)
        den = (la * lb * lc + la * (b0 * c0 + b1 * c1 + b2 * c2)
               + lb * (c0 * a0 + c1 * a1 + c2 * a2) + lc * (a0 * b0 + a1 * b1 + a2 * b2))
        tot += 2.0 * math.atan2(num, den)
    return tot


def field(pts: np.ndarray, arrays: tuple[np.ndarray, ...] | None = None,
          grho: float | None = None) -> np.ndarray:
    """``poly_field`` at points (n, 3): (n, NOUT) (defaults: the Eros mesh, G rho of
    lgw.theory.eros.parameters)."""
    if arrays is None:
        arrays = eros_arrays()
    if grho is None:
        from lgw.theory.eros.parameters import DENSITY, G
        grho = G * DENSITY
    pts = np.atleast_2d(np.asarray(pts, float))
    out = np.empty((len(pts), NOUT))
    for i, p in enumerate(pts):
        poly_field(p[0], p[1], p[2], *arrays, float(grho), out[i])
    return out
