"""Seed 002 (probe landing on 433 Eros): every constant, printed or chosen, in one place.

Numbers printed in seed 002 are marked "seed 002, Table 1" (or the equation); measured constants
cite the measurement (via ``../shared/data/eros/README.md``); numbers the workbench chooses are
marked "chosen" with the reason.  Nothing else in ``lgw.*.eros`` hard-codes a constant.
"""

from __future__ import annotations

import math

import numpy as np

# --- Seed 002, Table 1 (as printed) -----------------------------------------------------------
R0 = np.array([3200.0, 1300.0, 9000.0])  # m, initial position, body frame, Table 1
V0 = np.array([-1.2, 0.2, -1.0])  # m/s, initial velocity, Table 1
RF = np.array([2837.0, 928.1, 5708.0])  # m, landing position, Table 1
VF = np.array([0.0, 0.0, 0.0])  # m/s, final velocity, Table 1
T_LAND = 8000.0  # s, final time of the reference (8)-(10), seed 002 text after (9)
PROBE_MASS = 150.0  # kg, Table 1 (unused by the dynamics (1): u is an acceleration)
MASS_PRINTED = 6.69e5  # kg, Table 1 "Average Asteroid Weight": a slip, see MASS
RADIUS_PRINTED = 16000.0  # m, Table 1 "Average Asteroid Radius": the 16 km reference radius
#   of the NEAR spherical-harmonic field (Miller et al. 2002), not a mean radius (see R_MEAN).
G = 6.6743e-11  # m^3 kg^-1 s^-2, Table 1 (units printed wrongly as m^2 kg^-1 / s^-1); CODATA 2018
OMEGA_PRINTED = 3.3118e-4  # rad/s, seed 002 after (1)

# Printed cubic coefficients (9)-(10): [c0, c1, c2, c3] of x_d(t) = c0 + c1 t + c2 t^2 + c3 t^3.
CUBIC_PRINTED = np.array([
    [3200.0, -1.2, 2.83e-4, -1.73e-8],
    [1300.0, 0.2, -6.74e-5, 4.58e-9],
    [9000.0, -1.0, 9.57e-5, -2.76e-9],
])

# Printed simulation settings, seed 002 "MATLAB Simulations"
T_SCENARIO = 15.0  # s, simulation time
DT_SAMPLE = 0.01  # s, sampling time (the controller is sampled-data, zero-order hold)
# Printed results (abstract, Table 2 read with "/" as the decimal separator, conclusions)
TRACK_TIMES_PRINTED = {"pdsmc": 8.0, "ftsmc": 5.0, "fuzzy": 4.0}  # s, "tracked in"
ABS_ERROR_PRINTED = {"fuzzy": 113.4074, "ftsmc": 139.6112, "pdsmc": 244.8155}  # Table 2

# --- Measured constants of 433 Eros (../shared/data/eros/README.md) ---------------------------
MASS = 6.687e15  # kg, Yeomans et al., Science 289 (2000) 2085; Table 1's 6.69e5 kg is 1e10 smaller
GM_NEAR = 4.4628e5  # m^3/s^2, NEAR gravity solution, Miller et al., Icarus 155 (2002)
DENSITY_MEASURED = 2670.0  # kg/m^3, Yeomans et al. 2000 (2.67 +- 0.03 g/cm^3)
VOLUME = 2503e9  # m^3, Yeomans et al. 2000 (2503 +- 25 km^3)
OMEGA = 1639.389232 * math.pi / 180.0 / 86400.0  # rad/s, Miller et al. 2002 (3.31166e-4)
R_MEAN = (3.0 * VOLUME / (4.0 * math.pi)) ** (1.0 / 3.0)  # m, volume-equivalent radius (8.42 km)

# Polyhedral model: the unit mesh (sim/eros/data, volume MESH_VOLUME_UNIT) scaled to VOLUME,
# uniform density MASS / VOLUME (chosen: the measured mass and volume; GM = G MASS differs from
# GM_NEAR by 7e-5 relative, well inside the mass uncertainty).
MESH_VOLUME_UNIT = 0.291331  # unit^3, ../shared/data/eros/README.md
MESH_SCALE = (VOLUME / MESH_VOLUME_UNIT) ** (1.0 / 3.0)  # m per mesh unit
DENSITY = MASS / VOLUME  # kg/m^3 (2671.6, matches DENSITY_MEASURED within its 0.03 g/cm^3)
GM = G * MASS  # m^3/s^2, used by both gravity models

# --- Chosen: what seed 002 does not give --------------------------------------------------------
# Gains.  Seed 002 prints none of alpha, beta, p, q, k, N, M.  Chosen so that the 15 s scenario
# shows the three regimes the paper describes (PD ~ 8 s, FTSMC faster); all are validated by
# lgw.theory.eros.gains and can be replaced by a TOML file.
DEFAULT_GAINS = {
    "alpha": 1.0,  # 1/s, linear gain of (6); also the PD-SMC slope lam (same far-field rate)
    "beta": 1.0,  # m^(1 - p/q)/s, terminal gain of (5)/(6)
    "p": 3,  # odd integers p < q (seed 002 after (5)); 3/5 > 1/2 keeps e'|e|^(p/q-1) bounded
    "q": 5,  #   on the sliding surface (claim singular-term-surface)
    "k": 2.0,  # m/s^2, switching gain of (18)
    "lam": 1.0,  # 1/s, PD-SMC surface s = e' + lam e (the "classic PD sliding mode")
    "N": 5.0,  # s/m, fuzzy a(D) = exp(-N D) of (22); N <= M keeps (1-a)/b <= 1
    "M": 5.0,  # s/m, fuzzy b(D) = 1 - exp(-M D) of (22)
    "phi": 0.05,  # m/s, boundary-layer width of tanh(s/phi) (the "saturation function")
    "e_floor": 1e-4,  # m, |e|^(p/q-1) is evaluated at max(|e|, e_floor) (claim singular-term)
}
# Scenario.  Table 1 starts the probe exactly on the reference (e(0) = 0), so the paper's
# tracking transients need an offset the paper does not print: chosen 5 m per axis, at rest
# relative to the reference.
SCENARIO_OFFSET = np.array([5.0, 5.0, 5.0])  # m, e(0)
SCENARIO_VOFFSET = np.array([0.0, 0.0, 0.0])  # m/s, e'(0)
# Disturbance D of (1) ("modelling uncertainties", unspecified): chosen sinusoid per axis.
DIST_AMP = 0.05  # m/s^2, |D_i| <= DIST_AMP: 2.5 % of k, ten times the gravity (~5e-3 m/s^2)
DIST_FREQ = 0.5  # rad/s
DIST_PHASE = np.array([0.0, 2.0, 4.0])  # rad
# Tracking: "tracked" means |e_i| <= TRACK_TOL for the rest of the run (chosen: 1 cm, the
# order of the chattering band of the sign law at 0.01 s sampling, k dt^2 ~ 2e-4 m, times ~50)
TRACK_TOL = 0.01  # m
# Monte Carlo envelope of initial offsets (chosen): |e_i(0)| <= 10 m, |e_i'(0)| <= 0.5 m/s.
MC_POS = 10.0  # m
MC_VEL = 0.5  # m/s

# --- Two-mass-point gravity (2): fitted (seed 002 gives neither the split nor the positions) ----
# benchmarks/eros_fit_gravity.py: least squares of |g_2pt - g_poly|/|g_poly| over 240 points
# (the exact reference at 120 times, and the same moved by up to 500 m per axis), total mass
# fixed at MASS.  Residual over that region: 1.86 % rms, 5.26 % max (a single point mass at the
# centroid: 125 % rms, 166 % max: Eros's elongation halves the gravity above its waist).
TWO_POINT_MU = 0.24497  # M1 / MASS
TWO_POINT_P1 = np.array([5778.8, -1440.9, 569.8])  # m, body frame
TWO_POINT_P2 = np.array([-2629.7, -1131.8, -3216.3])  # m, body frame
TWO_POINT_GM = (TWO_POINT_MU * GM, (1.0 - TWO_POINT_MU) * GM)  # m^3/s^2
TWO_POINT_FIT_RMS = 0.0186  # relative acceleration residual over the fit region
TWO_POINT_FIT_MAX = 0.0526
# Where the paper's path sits (same script): the landing point RF is outside the shape model,
# 614 m above its surface along the ray from the centroid; the start R0 is 4126 m above it.
LANDING_ALTITUDE = 614.1  # m

# --- The whole descent: from Table 1's start to touchdown on the shape model (chosen) ----------
# lgw.theory.eros.descent builds the profile; lgw.sim.eros.descent flies it.  Seed 002 flies
# 15 s of its 8000 s reference and ends it at Table 1's landing position, which is 513 m from
# the nearest point of the shape model (614 m along the ray from the centroid): a hover.
#
# Touchdown site: the point of the shape model nearest to Table 1's landing position RF
# (computed, lgw.theory.eros.descent.touchdown_site).  The terminal segment flies the straight
# line from RF to it, the shortest way down: that line lies in the surface's normal cone at the
# site, so the touchdown velocity is along the local surface normal (no lateral slip).
# Terminal segment: seed 002's own form, a cubic (8) with boundary conditions of the form (9):
# at rest at RF at T_LAND, at the site at T_LAND + T_TERMINAL with the speed V_TOUCHDOWN along
# the approach line; after that the reference continues down the same line at V_TOUCHDOWN
# (so a probe that is still above the surface keeps descending until it touches).
V_TOUCHDOWN = 0.10  # m/s, reference touchdown speed.  Hayabusa's final vertical descent to
#   Itokawa started at 12 cm/s (JAXA/ISAS, "Hayabusa landed on and took off from Itokawa
#   successfully", 24 Nov 2005): the touch-and-go class of speed.
T_TERMINAL = 2000.0  # s, duration of the terminal segment (chosen: its peak speed 0.36 m/s
#   stays below the 1.57 m/s the paper's own cubic asks for, its acceleration (<= 6.7e-4 m/s^2,
#   ~12 % of the local gravity) is well inside the thrust limit).
T_AFTER = 600.0  # s, horizon after the reference's touchdown time (60 m more descent at 0.1 m/s:
#   a probe that has not touched by then is reported as such, "horizon").
LAND_SPEED_MAX = 0.5  # m/s, landed iff the speed relative to the surface at contact is at most
#   this (chosen: 5x the reference's 0.1 m/s, a third of the 1.5-1.8 m/s at which NEAR
#   Shoemaker, never designed to land, touched down on Eros and survived: NASA release 01-20,
#   14 Feb 2001; Dunham et al., Icarus 159 (2002) 433).  Faster: crashed, with the speed.

# Probe.  Mass: seed 002 Table 1 (150 kg, "probe weight"), taken as the wet mass at the start.
# Thrusters: one 22 N hydrazine thruster per direction and axis, the class of the 22.2 N
# (5 lbf) hydrazine trajectory-correction thrusters of NASA's Genesis probe
# (solarsystem.nasa.gov/genesismission/gm2/spacecraft/propulsion.html); saturated per axis by
# default (a thruster pair per body axis, the probe holding its attitude fixed in the asteroid
# frame), or on the norm (one steerable thruster).
THRUST_MAX = 22.0  # N, per axis (or on the norm); u_max = THRUST_MAX / mass = 0.147 m/s^2
ISP = 225.0  # s, catalytic hydrazine monopropellant, steady state (Sutton & Biblarz, Rocket
#   Propulsion Elements: about 220-235 s for hydrazine thrusters of this class)
G0 = 9.80665  # m/s^2, standard gravity (Isp in s)
PROPELLANT = 15.0  # kg, chosen: Hayabusa's fraction of chemical propellant (50 kg of its 530 kg
#   launch mass, astronautix.com "Hayabusa") on 150 kg; the descent needs a few kg.  The dry
#   mass is PROBE_MASS - PROPELLANT.

# Solar radiation pressure: the unknown disturbance (the controller has no model of it).
# P = 4.56e-6 N/m^2 at 1 AU (1361 W/m^2 / c), at Eros's semi-major axis 1.458 AU; Hayabusa's
# area-to-mass ratio (12 m^2 of solar array on 530 kg, astronautix.com "Hayabusa") and a
# reflectivity coefficient 1.5 (chosen, between absorbing 1 and mirror 2).
SRP_ACCEL = 4.56e-6 / 1.458**2 * 1.5 * 12.0 / 530.0  # m/s^2 (7.3e-8)
SRP_CR_RANGE = (1.0, 2.0)  # reflectivity coefficient range of a campaign (SRP_ACCEL at 1.5)
SUN_DIR0 = np.array([1.0, 0.0, 0.0])  # unit, body frame at t = 0 (chosen: in the equator);
#   fixed in inertial space, so it turns at -OMEGA about z in the body frame

# Navigation error (option; default off): the controller sees r + dr, v + dv, each a first-
# order Gauss-Markov process per axis with standard deviations NAV_SIGMA_R, NAV_SIGMA_V and
# correlation time NAV_TAU (chosen: metre-level position and mm/s-level velocity knowledge, the
# class of landmark-based optical navigation near a small body (seed 002 ref. [16], Li & Cui
# 2008); a filter's error is correlated over its time constant, not white).
NAV_SIGMA_R = 1.0  # m
NAV_SIGMA_V = 0.005  # m/s
NAV_TAU = 100.0  # s

# Guidance for the descent (chosen; seed 002 prints no gains and its defaults (k = 2 m/s^2,
# alpha = 1/s) ask for 14x the thrust of a 22 N thruster and are unstable when sampled at 1 s).
# Sampling: a 1 Hz guidance cycle (the descent's time scales are >= 20 s).  k = 0.01 m/s^2
# dominates the controller's unknowns (the two-point model's error, <= 1.4e-4 m/s^2 on the
# descent, plus SRP) and the drift (5.5e-3 m/s^2 of gravity) as the fuzzy blend's reaching
# condition k >= |F| max(1, N/M) requires; k dt / phi = 0.5 < 2 keeps tanh's boundary layer
# stable under the hold (claim sampled-tanh); alpha = lam = 0.05 /s (a 20 s time constant).
DESCENT_DT = 1.0  # s
DESCENT_GAINS = {"alpha": 0.05, "beta": 0.02, "p": 3, "q": 5, "k": 0.01, "lam": 0.05,
                 "N": 5.0, "M": 5.0, "phi": 0.02, "e_floor": 1e-3}
DESCENT_LAW = ("fuzzy", "tanh")  # seed 002's recommended controller (conclusions)
# Monte Carlo envelope of the descent's start (chosen): navigation-class dispersions about
# Table 1's initial state, |e_i(0)| <= 10 m and |e_i'(0)| <= 1 cm/s.
DESCENT_MC_POS = 10.0  # m
DESCENT_MC_VEL = 0.01  # m/s
# Plant gravity for the descent: the polyhedron, re-evaluated (with its gradient tensor) at a
# sample instant whenever the probe is more than LIN_STEP (near the body: 10 % of its distance
# to the surface) from the last evaluation point, and expanded to first order in between
# (lgw.sim.eros.descent_kernel, gravity code 3).  Chosen by measurement against the polyhedron
# at every evaluation (benchmarks/bench_eros.py --descent; docs/eros.md): on the whole descent
# 10 m moves the touchdown speed by 2e-8 relative, the fuel by 5e-7 relative and the contact
# point by 5e-7 m, at 1/78 of the cost (3 m: 1/31, 30 m: 1/164, the same touchdown).
LIN_STEP = 10.0  # m
