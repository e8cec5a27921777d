"""Every numbered equation, remark and simulation statement of seed 002, mapped to the claims
that check it or to the reason it cannot be checked."""

from __future__ import annotations

COVERAGE: tuple[tuple[str, str, tuple[str, ...], str], ...] = (
    ("Table 1", "constants", ("table1-constants", "dynamics-1", "cubic-9-10", "landing-point"),
     "the start and end states feed the cubic"),
    ("(1)", "rotating-frame dynamics", ("dynamics-1",), ""),
    ("(2)", "two-mass-point gravity", ("gravity-2",), "the masses and positions are fitted "
     "(benchmarks/eros_fit_gravity.py, parameters.TWO_POINT_*)"),
    ("(3)", "state vector", (), "not checkable, because it is a definition"),
    ("(4)", "state-space form", ("dynamics-1",), ""),
    ("(5)", "terminal surface and its t_s", ("settling-tsm", "settling-ode", "growth-e0"), ""),
    ("(6)", "fast terminal surface; far/near regimes", ("ftsm-faster", "settling-ode"), ""),
    ("(7)", "FTSM settling time", ("settling-ftsm", "settling-ode"), ""),
    ("(8)-(10)", "cubic reference", ("cubic-9-10", "reference-shape"), ""),
    ("(11)", "s1'", ("sdot-11",), ""),
    ("(12)", "s = s' = 0 on the surface", ("ueq-14",),
     "u_eq is the control that keeps s' = 0"),
    ("(13)", "u = u_eq + u_s", ("lyapunov-17",), "the decomposition is a definition"),
    ("(14)", "equivalent control", ("ueq-14",), ""),
    ("(15)-(17)", "Lyapunov argument", ("lyapunov-17", "reaching-sign"), ""),
    ("(18)", "switching law", ("reaching-sign", "reaching-tanh", "sampled-tanh",
                                "sampled-tanh-limit"), ""),
    ("(19)", "the full control", ("lyapunov-17", "printed-exponent-19", "singular-term"), ""),
    ("(20)", "fuzzy blend", ("fuzzy-condition", "fuzzy-reaching", "fuzzy-finite-time"), ""),
    ("(21)", "distance to the surface", ("fuzzy-invariance",), "defined for a linear surface "
     "c^T x; read for the FTSM surface as s_i/sqrt(1+alpha^2) (lgw.theory.eros.laws)"),
    ("(22)a", "D = sqrt(sum D_i^2)", ("fuzzy-invariance",), "the sum over axes couples them"),
    ("(22)b", "a(D), b(D)", ("fuzzy-condition", "fuzzy-finite-time"),
     "the number (22) is used twice"),
    ("(23)", "Fourier derivative", (), "not checkable, because it is a textbook identity with "
     "no statement about this system (nothing is computed for it)"),
    ("Figs. 3-6, 8-11", "tracking, velocity, control, surfaces",
     ("tracked-times", "fastest-sign", "fastest-tanh", "chatter-fuzzy", "chatter-tanh"),
     "scenario claims, judged over a box of gains and a campaign of offsets (the paper "
     "publishes neither its gains nor its offset)"),
    ("Fig. 7", "fuzzy coefficients a, b", ("fuzzy-condition",), "a, b as functions of D"),
    ("Table 2", "absolute error", ("abs-error-sign", "abs-error-tanh"), "metric: sum over the "
     "0.01 s samples and axes of |e_i|; the paper does not define its metric"),
    ("Fig. 12", "8000 s landing", ("reference-shape", "landing-point"),
     "path vs the shape model (the landing "
     "point is 614 m above the surface); the closed-loop 8000 s run is not made by default "
     "(lgw simulate eros --t-final 8000)"),
    ("PD-SMC", "the classic PD sliding mode", ("pd-smc",), ""),
)
