"""Fit seed 002's two-mass-point gravity (2) to the polyhedral gravity of the Eros shape model
over the region the probe flies through, and say where the paper's path sits.

    python benchmarks/eros_fit_gravity.py            (about a minute on one core)

Region: the exact cubic reference (8)-(10) at 120 times on [0, 8000] s, each point also moved
by a random offset of up to 500 m per axis (the probe is never far from its reference; 500 m
is 50 times the Monte Carlo envelope), points inside the body dropped.  Unknowns: the mass
fraction mu of M1 (M1 + M2 = MASS fixed, so the far field is exact) and the two positions.
Objective: the relative acceleration error |g_2pt - g_poly| / |g_poly| in least squares.
The chosen values are written into lgw.theory.eros.parameters by hand (TWO_POINT_*), with the
residuals this prints.
"""

from __future__ import annotations

import json

import numpy as np
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gravity import two_point_accel
from lgw.theory.eros.polyhedron import eros_accel, eros_polyhedron, inside
from lgw.theory.eros.reference import coefficients, evaluate
from scipy.optimize import least_squares


def region(n_t: int = 120, jitter: float = 500.0, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    tt = np.linspace(0.0, P.T_LAND, n_t)
    pos = evaluate(coefficients(), tt)[0].T
    pts = np.vstack([pos, pos + rng.uniform(-jitter, jitter, pos.shape)])
    return pts[~inside(eros_polyhedron(), pts)]


def residuals(theta: np.ndarray, pts: np.ndarray, g_ref: np.ndarray) -> np.ndarray:
    mu, p1, p2 = theta[0], theta[1:4], theta[4:7]
    g2 = two_point_accel(pts, p1, p2, mu * P.GM, (1.0 - mu) * P.GM)
    return ((g2 - g_ref) / np.linalg.norm(g_ref, axis=1, keepdims=True)).ravel()


def altitude(pt: np.ndarray, tol: float = 1.0) -> float:
    """Height of pt above the surface along the ray from the centroid (bisection, m)."""
    P_ = eros_polyhedron()
    lo, hi = 0.0, 1.0  # fraction of pt: lo inside, hi outside (checked by the caller)
    while (hi - lo) * np.linalg.norm(pt) > tol:
        mid = 0.5 * (lo + hi)
        if inside(P_, mid * pt[None])[0]:
            lo = mid
        else:
            hi = mid
    return float((1.0 - hi) * np.linalg.norm(pt))


def main() -> None:
    pts = region()
    g_ref = eros_accel(pts)
    best = None
    for x0 in ([0.5, 6e3, 0, 0, -6e3, 0, 0], [0.5, 8e3, 1e3, 0, -4e3, -1e3, 0],
               [0.3, 10e3, 0, 0, -3e3, 0, 0]):
        sol = least_squares(residuals, np.array(x0, float), args=(pts, g_ref),
                            bounds=([0.01] + [-2e4] * 6, [0.99] + [2e4] * 6),
                            x_scale=[0.1] + [1e3] * 6)
        if best is None or sol.cost < best.cost:
            best = sol
    rel = np.linalg.norm(residuals(best.x, pts, g_ref).reshape(-1, 3), axis=1)
    # the point-mass model for comparison
    pm = two_point_accel(pts, [0, 0, 0], [0, 0, 0], P.GM, 0.0)
    rel_pm = np.linalg.norm(pm - g_ref, axis=1) / np.linalg.norm(g_ref, axis=1)
    path = evaluate(coefficients(), np.linspace(0, P.T_LAND, 81))[0].T
    out = {
        "n_points": len(pts), "mu": best.x[0], "p1_m": best.x[1:4].tolist(),
        "p2_m": best.x[4:7].tolist(),
        "rel_residual_rms": float(np.sqrt(np.mean(rel**2))), "rel_residual_max": float(rel.max()),
        "point_mass_rel_rms": float(np.sqrt(np.mean(rel_pm**2))),
        "point_mass_rel_max": float(rel_pm.max()),
        "landing_point_inside": bool(inside(eros_polyhedron(), P.RF[None])[0]),
        "landing_point_altitude_m": altitude(P.RF),
        "start_altitude_m": altitude(P.R0),
        "path_min_altitude_m": min(altitude(p) for p in path[::8]),
    }
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
