"""Polyhedral gravity (Werner & Scheeres) against independent routes, and the two-point model."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from lgw.theory.eros import gravity as GR
from lgw.theory.eros import parameters as P
from lgw.theory.eros.polyhedron import (
    eros_polyhedron,
    inside,
    make_polyhedron,
    polyhedron_gravity,
)
from scipy.spatial import ConvexHull


def _hull_mesh(seed: int = 0, n: int = 12):
    """A coarse random convex polyhedron with outward counter-clockwise faces."""
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(n, 3)) * np.array([2.0, 1.0, 0.7])
    hull = ConvexHull(pts)
    faces = hull.simplices.copy()
    c = pts.mean(axis=0)
    for i, f in enumerate(faces):
        a, b, d = pts[f]
        if np.dot(np.cross(b - a, d - a), a - c) < 0:
            faces[i] = f[[0, 2, 1]]
    return pts, faces


def _brute_force(verts, faces, x, G_rho, n=10):
    """Acceleration by Gauss-Legendre quadrature over the tetrahedra (centroid, face), each
    mapped from the unit cube by the Duffy transform (independent of Werner-Scheeres)."""
    c = verts.mean(axis=0)
    gl, wl = np.polynomial.legendre.leggauss(n)
    gl, wl = 0.5 * (gl + 1), 0.5 * wl
    A, Bq, W = np.meshgrid(gl, gl, gl, indexing="ij")
    wt = (wl[:, None, None] * wl[None, :, None] * wl[None, None, :]).ravel()
    a, b, w = A.ravel(), Bq.ravel(), W.ravel()
    g = np.zeros(3)
    for f in faces:
        v1, v2, v3 = verts[f]
        d1, d2, d3 = v1 - c, v2 - v1, v3 - v2
        det = np.dot(d1, np.cross(d2, d3))
        pts = c + a[:, None] * (d1 + b[:, None] * (d2 + w[:, None] * d3))
        jac = a**2 * b * det
        r = pts - x
        g += (G_rho * (wt * jac)[:, None] * r / np.linalg.norm(r, axis=1)[:, None] ** 3).sum(0)
    return g


def test_against_brute_force_quadrature():
    verts, faces = _hull_mesh()
    P_ = make_polyhedron(verts, faces)
    assert P_.volume > 0
    for x in (np.array([5.0, 1.0, 0.5]), np.array([-1.0, 3.0, -2.0])):
        g_ws = polyhedron_gravity(P_, x[None], 1.0)[1][0]
        g_bf = _brute_force(verts, faces, x, 1.0)
        assert np.allclose(g_ws, g_bf, rtol=1e-6, atol=1e-10), (g_ws, g_bf)


def test_far_field_is_point_mass():
    E = eros_polyhedron()
    d = np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 0.6, 0.8]]) * 5e6
    g = polyhedron_gravity(E, d, P.G * P.DENSITY)[1]
    gm = P.G * P.DENSITY * E.volume
    expect = -gm * d / np.linalg.norm(d, axis=1, keepdims=True) ** 3
    assert np.allclose(g, expect, rtol=1e-4)


def test_laplacian_inside_and_outside():
    verts, faces = _hull_mesh(1)
    P_ = make_polyhedron(verts, faces)
    pts = np.array([verts.mean(axis=0), [10.0, 0, 0], [0, 0, 8.0]])
    _, _, lap = polyhedron_gravity(P_, pts, 1.0)
    assert lap[0] == pytest.approx(-4 * np.pi, rel=1e-12)
    assert abs(lap[1]) < 1e-12 and abs(lap[2]) < 1e-12
    # and the divergence of g by central differences (independent of the solid-angle sum)
    h = 1e-4
    for x, want in ((pts[0], -4 * np.pi), (pts[1], 0.0)):
        div = 0.0
        for i in range(3):
            dx = np.zeros(3)
            dx[i] = h
            gp = polyhedron_gravity(P_, (x + dx)[None], 1.0)[1][0, i]
            gm = polyhedron_gravity(P_, (x - dx)[None], 1.0)[1][0, i]
            div += (gp - gm) / (2 * h)
        assert div == pytest.approx(want, abs=1e-5)


def test_gradient_of_potential():
    verts, faces = _hull_mesh(2)
    P_ = make_polyhedron(verts, faces)
    x = np.array([4.0, -1.0, 1.0])
    h = 1e-5
    U = lambda y: polyhedron_gravity(P_, y[None], 1.0)[0][0]  # noqa: E731
    num = np.array([(U(x + h * np.eye(3)[i]) - U(x - h * np.eye(3)[i])) / (2 * h)
                    for i in range(3)])
    assert np.allclose(polyhedron_gravity(P_, x[None], 1.0)[1][0], num, rtol=1e-6)


def test_eros_scaling_and_landing_point():
    E = eros_polyhedron()
    assert E.volume == pytest.approx(P.VOLUME, rel=1e-5)
    ext = E.vertices.max(axis=0) - E.vertices.min(axis=0)
    assert 30e3 < ext[0] < 36e3 and 10e3 < ext[1] < 16e3  # "about 34 x 11 x 11 km"
    assert not inside(E, P.RF[None])[0]
    assert inside(E, (0.9 * P.RF)[None])[0] or inside(E, (0.85 * P.RF)[None])[0]


def test_two_point_generated_is_attracting_gradient():
    p1, p2 = np.array([5e3, 0, 0]), np.array([-3e3, 1e3, 0])
    x = np.array([[3000.0, 1000.0, 6000.0]])
    g = GR.two_point_accel(x, p1, p2, 2e5, 3e5)[0]
    want = sum(-gm * (x[0] - p) / np.linalg.norm(x[0] - p) ** 3
               for gm, p in ((2e5, p1), (3e5, p2)))
    assert np.allclose(g, want, rtol=1e-12)
    # and against the SymPy gradient at an exact point
    subs = {GR.x: 3000, GR.y: 1000, GR.z: 6000, GR.x1: 5000, GR.y1: 0, GR.z1: 0,
            GR.x2: -3000, GR.y2: 1000, GR.z2: 0, GR.Gs: 1, GR.M1: 200000, GR.M2: 300000}
    exact = [float(sp.N(c.subs(subs), 20)) for c in GR.gradient()]
    assert np.allclose(g, exact, rtol=1e-12)


def test_two_point_fit_residual_as_documented():
    """The fitted two-point model (parameters.TWO_POINT_*) against the polyhedron on the
    reference path: within the documented maximum residual."""
    from lgw.theory.eros.polyhedron import eros_accel
    from lgw.theory.eros.reference import coefficients, evaluate

    pts = evaluate(coefficients(), np.linspace(0, P.T_LAND, 25))[0].T
    g2 = GR.two_point_accel(pts, P.TWO_POINT_P1, P.TWO_POINT_P2, *P.TWO_POINT_GM)
    gp = eros_accel(pts)
    rel = np.linalg.norm(g2 - gp, axis=1) / np.linalg.norm(gp, axis=1)
    assert rel.max() <= P.TWO_POINT_FIT_MAX * 1.01
    assert np.sqrt(np.mean(rel**2)) <= 2 * P.TWO_POINT_FIT_RMS
