"""Plant and actuator checks: quaternions against scipy's Rotation, (2), (24), (26), (28)."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from lgw.sim.lunar import plant as PL
from lgw.theory.lunar import parameters as P
from scipy.spatial.transform import Rotation

unit = st.lists(st.floats(-1, 1), min_size=4, max_size=4).filter(
    lambda v: np.linalg.norm(v) > 0.1)


@given(unit, unit)
def test_quaternions_against_scipy(a, b):
    a = np.array(a) / np.linalg.norm(a)
    b = np.array(b) / np.linalg.norm(b)
    ra = Rotation.from_quat([*a[1:], a[0]])  # scipy is scalar-last
    rb = Rotation.from_quat([*b[1:], b[0]])
    # dcm is the passive matrix: the transpose of the active rotation matrix
    np.testing.assert_allclose(PL.dcm(a[:, None])[:, :, 0], ra.as_matrix().T, atol=1e-12)
    ab = PL.qmul(a[:, None], b[:, None])[:, 0]
    rab = (ra * rb).as_quat()
    np.testing.assert_allclose(np.abs(np.dot(ab, [rab[3], *rab[:3]])), 1.0, atol=1e-12)


@given(st.floats(-1.5, 1.5), st.floats(-1.4, 1.4))
def test_thrust_axis_from_yaw_pitch_is_2(psi, alpha):
    Q = PL.quat_from_yaw_pitch(np.array([psi]), np.array([-alpha]))
    n = PL.thrust_axis(Q)[:, 0]
    np.testing.assert_allclose(n, [np.cos(alpha) * np.cos(psi), np.cos(alpha) * np.sin(psi),
                                   np.sin(alpha)], atol=1e-12)
    r = Rotation.from_euler("ZYX", [psi, -alpha, 0.0])
    np.testing.assert_allclose(PL.dcm(Q)[:, :, 0], r.as_matrix().T, atol=1e-12)


def test_quaternion_kinematics_against_scipy_integration():
    w = np.array([[0.02], [-0.05], [0.03]])
    Q = np.array([[1.0], [0.0], [0.0], [0.0]])
    dt, n = 0.01, 500
    for _ in range(n):  # constant body rate: RK4 of Q' = Q x [0, w] / 2
        f = lambda q: 0.5 * PL.qmul(q, np.vstack([[0.0], w]))  # noqa: E731
        k1 = f(Q)
        k2 = f(Q + dt / 2 * k1)
        k3 = f(Q + dt / 2 * k2)
        k4 = f(Q + dt * k3)
        Q = Q + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    r = Rotation.from_rotvec(w[:, 0] * dt * n)
    np.testing.assert_allclose(PL.dcm(Q)[:, :, 0], r.as_matrix().T, atol=1e-9)


def test_thrust_saturation_readings():
    un = np.array([[24000.0], [0.0], [0.0]])
    uc = np.array([[16000.0], [3000.0], [-2000.0]])
    s = PL.saturate_thrust(uc, un, P.T_MAX, "commanded")
    assert abs(np.linalg.norm(s + un) - P.T_MAX) < 1e-6
    s2 = PL.saturate_thrust(uc, un, P.T_MAX, "nominal")
    assert np.linalg.norm(s2 + un) > P.T_MAX  # the nominal reading does not limit
    small = np.array([[100.0], [0.0], [0.0]])
    assert np.all(PL.saturate_thrust(small, un, P.T_MAX) == small)


def test_failure_and_torque_saturation():
    tf = 276.0
    assert abs(PL.failure_factor(tf / 2, tf) - (1 + P.T_A) / 2) < 1e-12
    assert abs(PL.failure_factor(tf, tf) - P.T_A) < 0.01
    assert abs(PL.failure_factor(0.0, tf) - 1) < 0.01
    assert PL.failure_factor(tf / 2 + 0.01, tf, "step") == P.T_A
    M = PL.saturate_torque(np.array([[300.0], [-250.0], [10.0]]))
    assert M[:, 0].tolist() == [200.0, -200.0, 10.0]
