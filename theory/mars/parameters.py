"""Every number the seed papers leave out, or that the workbench chooses, in one place.

Each constant says where it comes from.  Numbers printed in seed 000 are marked "seed 000";
numbers we chose are marked "chosen" with the reason.
"""

from __future__ import annotations

import numpy as np

# --- Seed 000, Table I (the lander of Acikmese & Ploen 2007) --------------------------------
M0 = 1905.0  # kg, initial (wet) mass, seed 000 Table I
AREA = np.array([6.0, 7.5, 8.7])  # m^2, effective cross-sectional areas A_x, A_y, A_z, Table I
R0 = np.array([-2000.0, 1000.0, 1500.0])  # m, initial position, Table I
V0 = np.array([100.0, -15.0, -75.0])  # m/s, initial velocity, Table I
G_MARS = np.array([0.0, 0.0, -3.7114])  # m/s^2, Table I
G_EARTH = 9.807  # m/s^2, Table I (g_e in c = Isp g_e, eq. (13))

# --- Not in seed 000 -----------------------------------------------------------------------
# Isp: Table I's lander is Acikmese & Ploen (2007), which uses Isp = 225 s.
ISP = 225.0  # s, chosen (source: Acikmese & Ploen 2007)
# Dry mass: Acikmese & Ploen (2007) / Blackmore et al. (2010) use m_dry = 1505 kg for this
# lander. Used only where a sound bound needs the lightest possible mass (Remark 1's tf minimum).
M_DRY = 1505.0  # kg, chosen (source: Acikmese & Ploen 2007)

# --- Seed 000, Part 3 and Part 2 ------------------------------------------------------------
THRUST_MAX_AXIS = 50_000.0  # N per axis, seed 000 Part 3
A_MAX_PAPER = 20.0  # m/s^2, amplitude of (47), seed 000 Part 2
THETA1_PAPER = 0.2  # seed 000 Part 2
THETA2_PAPER = 0.1  # seed 000 Part 2

# --- Landing criterion (default) ----------------------------------------------------
LAND_POS_TOL = 0.1  # m, |r| <= this counts as landed
LAND_VEL_TOL = 0.1  # m/s, |v| <= this counts as landed

AXES = ("x", "y", "z")

# --- Default gain set for seed 000 (the paper does not print its gains) ---------------------
# Chosen by a random search over 16,000 gain sets (log-uniform gains, uniform exponents) flying
# the Table I case with the corrected law and no disturbance, keeping those that land
# (|r| <= 0.1 m, |v| <= 0.1 m/s) within 30 s, peak thrust under 45 kN per axis and never below
# ground, then taking the one with the smallest sound landing-time bound and rounding it.
# Verified with a tight solve_ivp (rtol = atol = 1e-8): lands in 27.4 s, peak 32.4 kN (y axis),
# 235 kg of fuel; sound landing-time bound (T1* + T2*) 157.9 s.  q1 = 0.6 > 1/2 keeps the printed
# law's |s1|^(2 q1 - 1) term bounded.  Reproduce: python benchmarks/default_gains_search.py.
DEFAULT_GAINS = {
    "gains": {
        "beta1": 2.8, "beta2": 4.0e-4, "alpha1": 0.5, "alpha2": 2.0e-5,
        "q1": 0.6, "q2": 1.5, "g1": 0.7, "g2": 1.9,
    },
    "disturbance": {"a_max": A_MAX_PAPER, "theta1": THETA1_PAPER, "theta2": THETA2_PAPER},
}
