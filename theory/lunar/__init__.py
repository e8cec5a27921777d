"""lgw.theory.lunar: seed 001 (adaptive backstepping lunar descent with input saturation and
failure): parameters, gains, the law as SymPy expressions, bounds, claims and coverage."""
