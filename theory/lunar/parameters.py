"""Every constant of seed 001's lunar scenario, and the ones the paper leaves out, in one place.

Numbers printed in seed 001 Section 5 are marked "seed 001 S5"; numbers we chose or took from a
published source are marked "chosen" / "source" with the reason.
"""

from __future__ import annotations

import numpy as np

# --- The Moon and the Earth's standard gravity (not printed in seed 001) --------------------
# GM of the Moon: 4902.800066 km^3/s^2, A. S. Konopliv et al., "The JPL lunar gravity field to
# spherical harmonic degree 660 from the GRAIL Primary Mission", JGR Planets 118 (2013)
# (GL0660B); the same value is used in the JPL DE430 ephemeris (Folkner et al. 2014).
MU_MOON = 4902.800066e9  # m^3/s^2, source: Konopliv et al. 2013 / DE430
# Mean radius of the Moon: 1737.4 km, IAU WGCCRE report, B. A. Archinal et al., Celest. Mech.
# Dyn. Astr. 109 (2011) and 130 (2018).  Heights h = r - R_MOON.
R_MOON = 1737.4e3  # m, source: Archinal et al. (IAU WGCCRE) 2011/2018
# g_E in (1g): the standard acceleration of gravity, 9.80665 m/s^2 exactly (3rd CGPM, 1901;
# ISO 80000-3).  Isp in seconds is impulse per unit weight-on-Earth, so g_E is this constant.
G0 = 9.80665  # m/s^2, source: CGPM 1901 (standard gravity, exact)

# --- Seed 001 Section 5: the descent -------------------------------------------------------
H0 = 15_000.0  # m, nominal initial height, seed 001 S5
V0 = np.array([1609.08, 100.0, 0.0])  # m/s, nominal initial [u, v, w] in F_H, seed 001 S5
HF = 100.0  # m, terminal height of the optimal descent, seed 001 S5
VF = np.array([0.0, 0.0, 0.0])  # m/s, terminal velocity, seed 001 S5
M0 = 5156.0  # kg, initial mass, seed 001 S5
T_NOMINAL = 24_000.0  # N, nominal orbit thrust T_d, seed 001 S5
T_MAX = 34_000.0  # N, orbit-thrust saturation level T_max of (24), seed 001 S5
ISP = 315.0  # s, specific impulse of the orbit thrust, seed 001 S5
DH0 = 100.0  # m, initial height error, seed 001 S5
DV0 = np.array([2.0, 3.0, 5.0])  # m/s, initial velocity error, seed 001 S5
T_A = 0.7  # remaining thrust fraction after the failure, seed 001 (26)
# Initial latitude and longitude: not printed; they enter (1) only through tan(phi) terms.
PHI0 = 0.0  # rad, chosen: start over the equator of F_P (the paper gives no site)
LON0 = 0.0  # rad, chosen

# --- Seed 001 Section 5: the attitude -------------------------------------------------------
J_DIAG = np.array([2.865e3, 1.826e3, 1.826e3])  # kg m^2, J = diag[...], seed 001 S5
Q0 = np.array([np.sqrt(0.8), np.sqrt(0.2), 0.0, 0.0])  # scalar-first, F_H -> F_B, seed 001 S5
OMEGA0 = np.zeros(3)  # rad/s, seed 001 S5
M_MAX = 200.0  # N m, per-axis torque saturation of (28), seed 001 S5
DIST_TORQUE_AMP = 20.0  # N m, d_M = 20 [cos t, sin t, cos 2t], seed 001 S5

# --- Seed 001 Section 5: the gains (orbit, attitude) ------------------------------------------
ORBIT_GAINS = {"K1": [0.1, 0.1, 0.1], "F2": [1.0, 1.0, 20.0], "f3": 0.25, "d0e0": 0.0,
               "q": 0.01}  # seed 001 S5 (diagonal entries)
ATTITUDE_GAINS = {"K1": [1.0, 1.0, 1.0], "F2": [5.0, 5.0, 5.0], "f3": 0.1, "d0e0": 0.0,
                  "q": 0.01}  # seed 001 S5 (diagonal entries)

# --- Simulation choices -------------------------------------------------------------------
# Fixed RK4 step: the fastest linear mode is F2_zz = 20 1/s (time constant 0.05 s); dt = 0.05 s
# puts dt * 20 = 1.0 inside RK4's stability interval (2.78); checked against a tight solve_ivp
# reference in tests/lunar/test_sim_batch.py, and every scenario verdict that fails is re-flown
# at dt/2.
DT = 0.05  # s, chosen
# | |Q| - 1 | above this flags a case as out of the model's domain (RK4 does not preserve the
# norm; a well-resolved run drifts by about 1e-6 over the descent)
QUAT_NORM_TOL = 1e-4
