"""The cubic reference (8)-(10): exact coefficients against the printed ones, by two routes."""

from __future__ import annotations

import numpy as np
from lgw.theory.eros import parameters as P
from lgw.theory.eros import reference as REF


def test_exact_coefficients_solve_the_boundary_conditions_in_floats():
    T = P.T_LAND
    A = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [1, T, T**2, T**3], [0, 1, 2 * T, 3 * T**2]])
    for i in range(3):
        c = np.linalg.solve(A, [P.R0[i], P.V0[i], P.RF[i], P.VF[i]])
        assert np.allclose(c, REF.coefficients()[i], rtol=1e-9, atol=1e-12)


def test_printed_are_roundings_and_miss_the_endpoint():
    ex, pr = REF.coefficients(), REF.coefficients(printed=True)
    assert np.allclose(ex[:, :2], pr[:, :2])
    assert np.allclose(ex[:, 2:], pr[:, 2:], rtol=4e-3)  # 3 significant digits
    miss = REF.endpoint_miss()["position_m"]
    # miss = sum (printed - exact) c_j T^j, computed directly
    T = P.T_LAND
    direct = ((pr - ex) * T ** np.arange(4)).sum(axis=1)
    assert np.allclose(miss, direct, atol=1e-6)
    assert abs(miss[0]) > 10.0  # the x endpoint moves by more than 10 m


def test_reference_ends_at_rest_on_target():
    pos, vel, _ = REF.evaluate(REF.coefficients(), P.T_LAND)
    assert np.allclose(pos, P.RF, atol=1e-6) and np.allclose(vel, 0, atol=1e-9)
    roots = REF.velocity_roots()
    assert any(0 < t < P.T_LAND for t in roots[0])  # x_d turns back
    assert not any(0 < t < P.T_LAND - 1e-6 for t in roots[2])  # z_d monotone
