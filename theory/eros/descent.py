"""The whole descent of seed 002's probe: from Table 1's start to touchdown on the shape model.

Seed 002's reference (8)-(10) brings the probe from R0 (t = 0) to Table 1's landing position RF
at rest at t = 8000 s; RF is above the surface of Eros (claim landing-point).  The descent
profile continues it to the ground (choices and sources in lgw.theory.eros.parameters):

  segment 0, [0, T_LAND]:        the paper's cubic (8)-(10) (exact coefficients, (9));
  segment 1, [T_LAND, T_TD]:     a cubic of the same form (8) along the straight line from RF to
                                 the touchdown site, with (9)-type boundary conditions: at rest
                                 at RF, at the site at T_TD = T_LAND + T_TERMINAL with the speed
                                 V_TOUCHDOWN towards the surface;
  segment 2, [T_TD, inf):        straight on down that line at V_TOUCHDOWN.

The touchdown site is the point of the shape model nearest to RF.  Each segment is a cubic per
axis in the time since its start, so the sampled controller evaluates one representation
(``Profile``: break times and (segments, 3, 4) coefficients).

Also here: where a point is on the body (latitude, longitude, nearest face, altitude), and the
error of the fitted two-point gravity (2) against the polyhedron along a descent and in the far
field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np
from lgw.theory.eros import parameters as P
from lgw.theory.eros import reference as REF

# --- the shape model: nearest points -----------------------------------------------------------

def _closest_on_segments(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.einsum("fi,fi->f", p - a, ab) / np.einsum("fi,fi->f", ab, ab)
    return a + np.clip(t, 0.0, 1.0)[:, None] * ab


def closest_points(p: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """The point of each triangle (f, 3, 3) nearest to p (3,): the projection onto the plane
    if it falls inside the triangle, else the nearest point of its three edges."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    q = p - np.einsum("fi,fi->f", p - a, n)[:, None] * n
    inside = np.ones(len(tri), bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("fi,fi->f", np.cross(v - u, q - u), n) >= 0.0
    best = q.copy()
    dbest = np.where(inside, np.linalg.norm(q - p, axis=1), np.inf)
    for u, v in ((a, b), (b, c), (c, a)):
        e = _closest_on_segments(p, u, v)
        d = np.linalg.norm(e - p, axis=1)
        take = ~inside & (d < dbest)
        best[take], dbest[take] = e[take], d[take]
    return best


@cache
def _faces() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The shape model's triangles (f, 3, 3), their centroids and the radius about each
    centroid that holds the triangle (m)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron

    E = eros_polyhedron()
    tri = E.vertices[E.faces]
    cen = tri.mean(axis=1)
    return tri, cen, np.linalg.norm(tri - cen[:, None], axis=2).max(axis=1)


def nearest_surface_point(p: np.ndarray) -> tuple[np.ndarray, int, float]:
    """(point of the shape model nearest to p, its face index, distance in m).  Only the
    faces that can hold it are examined: a face is at least |p - c| - rho from p (c its
    centroid, rho its radius) and the nearest is at most min |p - c| away (exact pruning)."""
    tri, cen, rad = _faces()
    p = np.asarray(p, float)
    dc = np.linalg.norm(cen - p, axis=1)
    cand = np.flatnonzero(dc - rad <= dc.min())
    q = closest_points(p, tri[cand])
    d = np.linalg.norm(q - p, axis=1)
    j = int(np.argmin(d))
    return q[j], int(cand[j]), float(d[j])


def lat_lon(p: np.ndarray) -> tuple[float, float]:
    """Body-fixed planetocentric latitude and east longitude (deg) of p (centroid frame, z the
    spin axis, x the long axis)."""
    p = np.asarray(p, float)
    return (math.degrees(math.asin(p[2] / np.linalg.norm(p))),
            math.degrees(math.atan2(p[1], p[0])))


@dataclass(frozen=True)
class Site:
    """A touchdown site on the shape model: the point (m, body frame), the face it lies on and
    its outward normal, the approach line's unit direction (from the site upwards), and the
    height H of the terminal segment's start above it along that line (m)."""

    point: np.ndarray
    face: int
    normal: np.ndarray
    approach: np.ndarray
    height: float

    @property
    def lat_lon(self) -> tuple[float, float]:
        return lat_lon(self.point)

    @property
    def approach_to_normal_deg(self) -> float:
        """Angle between the approach line and the normal of the face holding the site (a site
        on an edge or a vertex of the mesh has more than one face: this one's)."""
        c = float(np.clip(self.approach @ self.normal, -1.0, 1.0))
        return math.degrees(math.acos(c))


@cache
def touchdown_site() -> Site:
    """The point of the shape model nearest to Table 1's landing position RF."""
    from lgw.theory.eros.polyhedron import eros_polyhedron

    q, f, d = nearest_surface_point(P.RF)
    return Site(q, f, eros_polyhedron().normals[f].copy(), (P.RF - q) / d, d)


# --- the profile ------------------------------------------------------------------------------

@dataclass(frozen=True)
class Profile:
    """A piecewise-cubic reference: on [breaks[j], breaks[j+1]) (the last segment open-ended)
    x_d(t) = sum_i coef[j, :, i] tau^i with tau = t - breaks[j]."""

    breaks: np.ndarray  # (S,) s
    coef: np.ndarray  # (S, 3, 4)
    t_touchdown: float  # s, the time the reference reaches the surface
    site: Site

    def segment(self, t: np.ndarray) -> np.ndarray:
        return np.clip(np.searchsorted(self.breaks, t, side="right") - 1, 0,
                       len(self.breaks) - 1)

    def evaluate(self, tt) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity, acceleration at times tt: (3, len(tt)) (or (3,) for a scalar)."""
        tt = np.asarray(tt, float)
        flat = np.atleast_1d(tt)
        j = self.segment(flat)
        tau = flat - self.breaks[j]
        c = self.coef[j]  # (n, 3, 4)
        ta = tau[:, None]
        pos = c[..., 0] + ta * (c[..., 1] + ta * (c[..., 2] + ta * c[..., 3]))
        vel = c[..., 1] + ta * (2 * c[..., 2] + 3 * ta * c[..., 3])
        acc = 2 * c[..., 2] + 6 * ta * c[..., 3]
        out = tuple(x.T for x in (pos, vel, acc))
        return tuple(x[:, 0] for x in out) if tt.ndim == 0 else out


def terminal_cubic(height: float, duration: float, v_end: float) -> np.ndarray:
    """Coefficients (h0..h3) of the height h(tau) along the approach line: the form (8) with
    (9)-type conditions h(0) = height, h'(0) = 0, h(T) = 0, h'(T) = -v_end (T = duration):
    h2 = (v_end T - 3 H)/T^2, h3 = (2 H - v_end T)/T^3.  Monotone descending on [0, T] iff
    0 < v_end T < 2 H (then h' < 0 on (0, T])."""
    H, T, v = float(height), float(duration), float(v_end)
    return np.array([H, 0.0, (v * T - 3 * H) / T**2, (2 * H - v * T) / T**3])


def descent_profile(t_terminal: float = P.T_TERMINAL, v_touchdown: float = P.V_TOUCHDOWN,
                    cubic: str = "exact", site: Site | None = None) -> Profile:
    """The descent reference (module docstring): the paper's cubic (``cubic``: "exact" or
    "printed" coefficients), the terminal cubic to ``site`` (default: touchdown_site()) and the
    straight continuation at v_touchdown."""
    from lgw.theory.errors import ParameterError

    site = site or touchdown_site()
    for name, v in (("t_terminal", t_terminal), ("v_touchdown", v_touchdown)):
        if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
            raise ParameterError(name, v, "must be a finite number > 0")
    if not v_touchdown * t_terminal < 2.0 * site.height:
        raise ParameterError("v_touchdown", v_touchdown, f"must be < 2 H / T = "
                             f"{2 * site.height / t_terminal:.4g} m/s with T = t_terminal "
                             "(else the terminal cubic climbs before it descends)")
    c0 = REF.coefficients(printed=cubic == "printed")
    start = REF.evaluate(c0, P.T_LAND)[0]  # RF for the exact cubic (the printed one misses it)
    line = start - site.point
    height = float(np.linalg.norm(line))
    h = terminal_cubic(height, t_terminal, v_touchdown)
    up = line / height  # site.approach for the exact cubic
    c1 = np.zeros((3, 4))
    c1[:, 0] = start
    c1[:, 1:] = up[:, None] * h[None, 1:]
    c2 = np.zeros((3, 4))
    c2[:, 0] = site.point
    c2[:, 1] = -v_touchdown * up
    t_td = P.T_LAND + t_terminal
    return Profile(np.array([0.0, P.T_LAND, t_td]), np.stack([c0, c1, c2]), t_td, site)


# --- the two-point fit against the polyhedron ------------------------------------------------

def fit_error(pts: np.ndarray) -> dict[str, np.ndarray]:
    """|g_2pt - g_poly| / |g_poly|, the angle between them (deg) and |g_poly| (m/s^2) at points
    (n, 3): the fitted two-point model (2) (parameters TWO_POINT_*) against the polyhedron."""
    from lgw.theory.eros.gravity import two_point_accel
    from lgw.theory.eros.polyhedron import eros_accel

    pts = np.atleast_2d(np.asarray(pts, float))
    gp = eros_accel(pts)
    g2 = two_point_accel(pts, P.TWO_POINT_P1, P.TWO_POINT_P2, *P.TWO_POINT_GM)
    n = np.linalg.norm(gp, axis=1)
    cos = np.einsum("pi,pi->p", gp, g2) / (n * np.linalg.norm(g2, axis=1))
    return {"rel": np.linalg.norm(g2 - gp, axis=1) / n, "abs": np.linalg.norm(g2 - gp, axis=1),
            "angle_deg": np.degrees(np.arccos(np.clip(cos, -1, 1))), "g_poly": n}


def height_above(p: np.ndarray) -> float:
    """Distance (m) from p to the nearest point of the shape model (p outside)."""
    return nearest_surface_point(p)[2]


def fit_error_along(profile: Profile, times: np.ndarray) -> list[dict[str, float]]:
    """The two-point fit's error at the reference positions at ``times`` (s): one row per time
    with t, the height above the surface (m), |g_poly|, the relative and absolute errors and
    the angle."""
    pos = profile.evaluate(np.asarray(times, float))[0].T
    err = fit_error(pos)
    return [{"t": float(t), "height_m": height_above(p), "g_poly": float(err["g_poly"][i]),
             "rel": float(err["rel"][i]), "abs": float(err["abs"][i]),
             "angle_deg": float(err["angle_deg"][i])} for i, (t, p) in
            enumerate(zip(times, pos, strict=True))]


def two_point_centre() -> np.ndarray:
    """Centre of mass of the fitted two-point model (m, body frame): mu p1 + (1 - mu) p2.  The
    polyhedron's is the origin (the mesh is centred at its centroid)."""
    return P.TWO_POINT_MU * P.TWO_POINT_P1 + (1.0 - P.TWO_POINT_MU) * P.TWO_POINT_P2


FAR_RADII = (20e3, 50e3, 100e3, 1000e3)  # m


def far_field_error(radii=FAR_RADII, n_dir: int = 26) -> list[dict[str, float]]:
    """Largest relative error of the two-point model, and of a point mass at the centroid, over
    n_dir directions (the 26 of a cube's faces, edges and corners) at each radius (m)."""
    from lgw.theory.eros.gravity import two_point_accel

    d = np.array([(i, j, k) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1)
                  if (i, j, k) != (0, 0, 0)], float)[:n_dir]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    rows = []
    for r in radii:
        pts = r * d
        e2 = fit_error(pts)
        pm = two_point_accel(pts, np.zeros(3), np.zeros(3), P.GM, 0.0)
        from lgw.theory.eros.polyhedron import eros_accel
        gp = eros_accel(pts)
        epm = np.linalg.norm(pm - gp, axis=1) / np.linalg.norm(gp, axis=1)
        rows.append({"radius_m": float(r), "two_point_max": float(e2["rel"].max()),
                     "point_mass_max": float(epm.max())})
    return rows


def quadrature_accel(pt: np.ndarray, n: int = 3) -> np.ndarray:
    """The shape model's gravity at pt (m/s^2) by Gauss-Legendre quadrature over the
    tetrahedra (centroid, face), each mapped from the unit cube by the Duffy transform: a route
    independent of Werner & Scheeres (accurate far from the body, where the integrand is
    smooth; n nodes per direction)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron

    E = eros_polyhedron()
    tri = E.vertices[E.faces]
    c = E.vertices.mean(axis=0) * 0.0  # any interior point: the centroid frame's origin
    gl, wl = np.polynomial.legendre.leggauss(n)
    gl, wl = 0.5 * (gl + 1), 0.5 * wl
    A, B, W = (x.ravel() for x in np.meshgrid(gl, gl, gl, indexing="ij"))
    wt = (wl[:, None, None] * wl[None, :, None] * wl[None, None, :]).ravel()
    d1, d2, d3 = tri[:, 0] - c, tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 1]
    det = np.einsum("fi,fi->f", d1, np.cross(d2, d3))
    g = np.zeros(3)
    for j in range(len(A)):
        q = c + A[j] * (d1 + B[j] * (d2 + W[j] * d3))
        r = q - np.asarray(pt, float)
        jac = A[j] ** 2 * B[j] * det * wt[j]
        g += (jac[:, None] * r / np.linalg.norm(r, axis=1)[:, None] ** 3).sum(axis=0)
    return P.G * P.DENSITY * g
