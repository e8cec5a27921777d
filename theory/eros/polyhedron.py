"""Constant-density polyhedron gravity, Werner & Scheeres (1997), vectorised numpy.

R. A. Werner, D. J. Scheeres, "Exterior gravitation of a polyhedron derived and compared with
harmonic and mascon gravitation representations of asteroid 4769 Castalia", Celest. Mech. Dyn.
Astr. 65 (1997) 313-344, eqs. (10)-(16):

    U   =  G rho/2 sum_e  r_e . E_e . r_e L_e  -  G rho/2 sum_f  r_f . F_f . r_f w_f
    g   = -G rho   sum_e  E_e . r_e L_e        +  G rho   sum_f  F_f . r_f w_f
    lap = -G rho   sum_f  w_f    (= -4 pi G rho inside, 0 outside)

with r_e, r_f vectors from the field point to any point of the edge / face, F_f = n_f n_f^T,
E_e = n_A n_A,e^T + n_B n_B,e^T over the two faces of edge e, L_e = ln((a+b+l)/(a+b-l)) and
w_f the signed solid angle of face f.  E_e is accumulated per half-edge (face, directed edge):
each half-edge of face f with outward in-plane edge normal n_f,e adds n_f n_f,e^T; both
half-edges of an edge share L_e and any r_e on the edge, so no edge pairing is needed.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from importlib.resources import files

import numpy as np


@dataclass(frozen=True)
class Polyhedron:
    """A closed, outward-oriented triangle mesh (metres) and its precomputed face/edge data."""

    vertices: np.ndarray  # (nv, 3)
    faces: np.ndarray  # (nf, 3) int, counter-clockwise seen from outside
    normals: np.ndarray  # (nf, 3) unit outward face normals
    he_a: np.ndarray  # (nh,) half-edge start vertex
    he_b: np.ndarray  # (nh,) half-edge end vertex
    he_face: np.ndarray  # (nh,) face of the half-edge
    he_dyad_n: np.ndarray  # (nh, 3) n_f of the half-edge's face
    he_dyad_m: np.ndarray  # (nh, 3) outward in-plane edge normal n_f,e

    @property
    def volume(self) -> float:
        v = self.vertices[self.faces]
        return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def make_polyhedron(vertices: np.ndarray, faces: np.ndarray) -> Polyhedron:
    v = np.asarray(vertices, dtype=float)
    fc = np.asarray(faces, dtype=np.int64)
    a, b, c = v[fc[:, 0]], v[fc[:, 1]], v[fc[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    he_a = fc[:, [0, 1, 2]].ravel()
    he_b = fc[:, [1, 2, 0]].ravel()
    he_face = np.repeat(np.arange(len(fc)), 3)
    nn = n[he_face]
    m = np.cross(v[he_b] - v[he_a], nn)
    m /= np.linalg.norm(m, axis=1, keepdims=True)
    return Polyhedron(v, fc, n, he_a, he_b, he_face, nn, m)


@cache
def eros_polyhedron() -> Polyhedron:
    """The Eros mesh (package data) scaled to the measured volume (metres)."""
    from lgw.theory.eros.parameters import MESH_SCALE

    d = files("lgw.theory.eros") / "data"
    verts = np.loadtxt(str(d / "eros_vertices.csv"), delimiter=",", skiprows=1)
    faces = np.loadtxt(str(d / "eros_faces.csv"), delimiter=",", skiprows=1, dtype=np.int64)
    return make_polyhedron(verts * MESH_SCALE, faces)


def _solid_angles(P: Polyhedron, x: np.ndarray) -> np.ndarray:
    """Signed solid angle of every face seen from each field point: (npts, nf)."""
    r = P.vertices[None, :, :] - x[:, None, :]  # (npts, nv, 3)
    r1, r2, r3 = (r[:, P.faces[:, i]] for i in range(3))
    l1, l2, l3 = (np.linalg.norm(ri, axis=-1) for ri in (r1, r2, r3))
    num = np.einsum("pfi,pfi->pf", r1, np.cross(r2, r3))
    den = (l1 * l2 * l3 + l1 * np.einsum("pfi,pfi->pf", r2, r3)
           + l2 * np.einsum("pfi,pfi->pf", r3, r1) + l3 * np.einsum("pfi,pfi->pf", r1, r2))
    return 2.0 * np.arctan2(num, den)


def _eval_chunk(P: Polyhedron, x: np.ndarray, G_rho: float):
    r = P.vertices[None, :, :] - x[:, None, :]
    dist = np.linalg.norm(r, axis=-1)  # (npts, nv)
    w = _solid_angles(P, x)  # (npts, nf)
    rf = r[:, P.faces[:, 0]]  # a point of each face
    nf_r = np.einsum("fi,pfi->pf", P.normals, rf)  # n_f . r_f
    g_face = np.einsum("fi,pf->pi", P.normals, nf_r * w)
    U_face = np.einsum("pf,pf->p", nf_r**2, w)
    ra = r[:, P.he_a]  # (npts, nh, 3) r_e at the edge's start
    la, lb = dist[:, P.he_a], dist[:, P.he_b]
    le = np.linalg.norm(P.vertices[P.he_b] - P.vertices[P.he_a], axis=-1)
    L = np.log((la + lb + le) / (la + lb - le))
    m_r = np.einsum("hi,phi->ph", P.he_dyad_m, ra)
    n_r = np.einsum("hi,phi->ph", P.he_dyad_n, ra)
    g_edge = np.einsum("hi,ph->pi", P.he_dyad_n, m_r * L)
    U_edge = np.einsum("ph,ph->p", n_r * m_r, L)
    g = G_rho * (-g_edge + g_face)
    U = 0.5 * G_rho * (U_edge - U_face)
    lap = -G_rho * w.sum(axis=1)
    return U, g, lap


def polyhedron_gravity(P: Polyhedron, pts: np.ndarray, G_rho: float,
                       chunk: int = 8) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Potential (m^2/s^2), acceleration (m/s^2) and Laplacian (1/s^2) of the uniform polyhedron
    (G rho in 1/s^2) at field points ``pts`` (npts, 3), in chunks of ``chunk`` points."""
    pts = np.atleast_2d(np.asarray(pts, dtype=float))
    U = np.empty(len(pts))
    g = np.empty((len(pts), 3))
    lap = np.empty(len(pts))
    for i in range(0, len(pts), chunk):
        U[i:i + chunk], g[i:i + chunk], lap[i:i + chunk] = _eval_chunk(P, pts[i:i + chunk], G_rho)
    return U, g, lap


def inside(P: Polyhedron, pts: np.ndarray, chunk: int = 8) -> np.ndarray:
    """True where the point is inside the closed mesh (total solid angle 4 pi, not 0)."""
    pts = np.atleast_2d(np.asarray(pts, dtype=float))
    out = np.empty(len(pts), dtype=bool)
    for i in range(0, len(pts), chunk):
        out[i:i + chunk] = _solid_angles(P, pts[i:i + chunk]).sum(axis=1) > 2.0 * np.pi
    return out


def eros_accel(pts: np.ndarray) -> np.ndarray:
    """Polyhedral gravity of Eros (uniform density MASS/VOLUME) at pts (npts, 3), m/s^2."""
    from lgw.theory.eros.parameters import DENSITY, G

    return polyhedron_gravity(eros_polyhedron(), pts, G * DENSITY)[1]
