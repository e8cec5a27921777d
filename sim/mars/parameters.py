"""Constants only the simulator needs, each with its source or the reasoning behind it.

Seed 000's constants (Table I, Isp, thrust limit, landing tolerances) live in
``lgw.theory.mars.parameters``; this file holds what the physical drag model and the integrator add.
"""

from __future__ import annotations

# --- Martian atmosphere for the physical drag model (departure from seed 000, eq. (12)) ----
# Printed (12): a_m,i = -0.699 v_i^2 exp(-0.0009 r_z) / (A_i m).  Three defects: v_i^2 does not
# change sign with v_i (the "drag" pushes along -axis even when the lander moves that way), it
# divides by the area where drag grows with it, and 0.0009 /m is a 1.1 km scale height where
# Mars' is about 11 km.  The physical model used by default is
#   a_m,i = -(1/2) rho0 exp(-r_z / H) C_D A_i |v_i| v_i / m.
RHO0_MARS = 0.020  # kg/m^3, surface density; NASA Mars Fact Sheet ("~0.020 kg/m^3")
H_MARS = 11_100.0  # m, atmospheric scale height; NASA Mars Fact Sheet ("11.1 km")
# C_D: chosen.  A lander in powered descent (aeroshell jettisoned) is a bluff body; a flat plate
# normal to subsonic flow has C_D ~ 1.2 (Hoerner, Fluid-Dynamic Drag, ch. 3), which we take per
# axis with the Table I areas.  Drag is small here (~0.03 m/s^2 at 100 m/s, 1.5 km), so the
# landing results are insensitive to this choice; it only has to oppose motion and scale with A.
CD_LANDER = 1.2
# Printed (12) coefficients, kept selectable as drag="printed".
PRINTED_DRAG_COEF = 0.699  # seed 000, eq. (12)
PRINTED_DRAG_DECAY = 0.0009  # 1/m, seed 000, eq. (12)
DRAG_MODELS = ("physical", "printed", "none")
# The registered laws (lgw.sim.mars.laws.LAWS, which loads SymPy) by name, for option choices
# that must answer before SymPy loads; tests/mars/test_sim_laws.py checks the two agree.
LAW_NAMES = ("corrected", "printed", "super-twisting", "bounded", "bounded-sat")

# --- Integrator defaults (fixed-step RK4 in lgw.sim.mars.batch)
# --------------------------------------
# DT_DEFAULT: chosen by accuracy (docs/sim.md).  Against the tight solve_ivp reference (LSODA,
# rtol = atol = 1e-10), default gains, RK4 at dt = 0.05 s: Table II cases 3.6e-6 s / 1.6e-7 m
# in landing time / position; Table III cases with the 50 kN limit 8.6e-4 s / 1.4e-4 m (an axis
# reaching s1 ~ 0 early makes those stiff).  dt = 0.1 s gives 1.9e-2 s on Table III, outside
# the 0.01 s / 1 cm the workbench asks for.
DT_DEFAULT = 0.05  # s
# EPS_DEFAULT: the band |s_i| <= eps in which a sliding variable counts as "reached".
# The explicit step chatters around s = 0 (the laws are not Lipschitz there: |s|^q, q < 1, and
# the corrected law's |s1|^(q1-1) gain grows without bound as s1 -> 0).  Measured floor
# (default gains, Table I, max over t in [90, 120] s with stop="t_max"; docs/sim.md):
#     dt (s)      0.01     0.02     0.05     0.1      0.2
#     |s1| (m)    2.6e-6   1.4e-5   1.4e-4   7.5e-4   4.1e-3
#     |s2| (m/s)  8.4e-4   2.3e-3   9.0e-3   2.5e-2   6.7e-2     (~0.85 dt^1.5)
# eps = 0.05 is 5.5x the s2 floor at the default dt (2x at dt = 0.1) and half the landing
# tolerance; use a smaller eps only with a smaller dt (the floor scales like dt^1.5).
EPS_DEFAULT = 0.05  # m for s1, m/s for s2
# Adaptive Dormand-Prince 5(4) (lgw.sim.mars.batch, method="dopri5"): an option for long landing
# campaigns, where the closed loop is smooth until landing and the error control takes far
# fewer steps than the fixed RK4 step needs.  Tolerance chosen by measurement
# (benchmarks/bench_sim.py --tol-sweep, docs/sim.md): against the per-case RK45 1e-8 loop and
# the LSODA reference, rtol = atol = 1e-4 / 1e-5 / 1e-6 give landing times within
# 1.1e-3 / 1.3e-4 / 2.0e-5 s on Table II (20 cases) and 2.8e-4 / 1.5e-5 / 1.4e-5 s on
# Table III at 50 kN; 1e-5 keeps a ~75x margin under the 0.01 s target on gains and states we
# have not seen, at ~15 % more steps than 1e-4 (46 against 39 per Table II case).
DOPRI_RTOL = 1e-5
DOPRI_ATOL = 1e-5
# max step: peak thrust, saturation time and the s-band times are sampled at the accepted
# nodes (landing, dry mass and min altitude use the Hermite interpolants), so the step is
# capped to keep those samples meaningful.
DOPRI_MAX_STEP = 1.0  # s
# attempted steps per case before the case is flagged ``step_limit`` (e.g. an axis chattering
# at s = 0 with stop="t_max", where the error control shrinks the step without end)
DOPRI_MAX_STEPS = 200_000
T_MAX_DEFAULT = 120.0  # s

# --- Random disturbance (lgw.sim.mars.disturbances): band-limited, bounded
# ---------------------------
RANDOM_N_SINES = 4  # sinusoids per axis
RANDOM_OMEGA_BAND = (0.1, 2.0)  # rad/s; brackets (47)'s 1 rad/s; slow enough to be "lumped"
