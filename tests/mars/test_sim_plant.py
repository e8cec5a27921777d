"""The plant of seed 000 (10)-(14) and the drag models (12)."""

from __future__ import annotations

import numpy as np
import pytest
from lgw.sim.mars.parameters import CD_LANDER, H_MARS, RHO0_MARS
from lgw.sim.mars.plant import drag_accel, exhaust_velocity, plant_rhs, saturate
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import AREA, G_EARTH, G_MARS


def test_physical_drag_opposes_motion_and_scales_with_area() -> None:
    r = np.array([0.0, 0.0, 1500.0])
    for v in (np.array([100.0, -15.0, -75.0]), np.array([-100.0, 15.0, 75.0])):
        a = drag_accel(r, v, 1905.0, "physical")
        assert np.all(a * v < 0)
        expect = -0.5 * RHO0_MARS * np.exp(-1500 / H_MARS) * CD_LANDER * AREA * np.abs(v) * v / 1905
        np.testing.assert_allclose(a, expect, rtol=1e-14)
    v = np.array([10.0, 10.0, 10.0])
    a = drag_accel(r, v, 1000.0, "physical")
    np.testing.assert_allclose(a / a[0], AREA / AREA[0])


def test_printed_drag_is_literal_eq_12() -> None:
    r = np.array([1.0, 2.0, 1000.0])
    v = np.array([-10.0, 20.0, -30.0])
    a = drag_accel(r, v, 1500.0, "printed")
    np.testing.assert_allclose(a, -0.699 * v**2 * np.exp(-0.0009 * 1000) / (AREA * 1500))
    assert np.all(a < 0)  # printed (12) never changes sign with v: the defect documented
    assert np.all(drag_accel(r, v, 1500.0, "none") == 0)
    with pytest.raises(ParameterError):
        drag_accel(r, v, 1500.0, "stokes")


def test_plant_rhs() -> None:
    y = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 1800.0])
    f = np.array([3000.0, -4000.0, 12000.0])
    ap = np.array([0.1, 0.2, 0.3])
    dy = plant_rhs(0.0, y, f, drag="none", isp=225.0, disturbance_accel=ap)
    np.testing.assert_allclose(dy[:3], y[3:6])
    np.testing.assert_allclose(dy[3:6], f / 1800.0 + G_MARS + ap)
    assert dy[6] == pytest.approx(-13000.0 / (225.0 * G_EARTH))
    with pytest.raises(ParameterError, match="isp"):
        exhaust_velocity(-1.0)


def test_saturation() -> None:
    f = np.array([60e3, -70e3, 10e3])
    np.testing.assert_allclose(saturate(f, 50e3, "axis"), [50e3, -50e3, 10e3])
    fn = saturate(f, 50e3, "norm")
    assert np.linalg.norm(fn) == pytest.approx(50e3)
    np.testing.assert_allclose(fn / np.linalg.norm(fn), f / np.linalg.norm(f))
    np.testing.assert_allclose(saturate(np.array([-np.inf, 1.0, 2.0]), 5.0, "axis"),
                               [-5.0, 1.0, 2.0])
    np.testing.assert_allclose(saturate(np.array([-np.inf, 1.0, 2.0]), 5.0, "norm"),
                               [-5.0, 0.0, 0.0])
    assert np.isnan(saturate(np.array([np.nan, 1.0, 2.0]), 5.0, "axis")[0])
    np.testing.assert_array_equal(saturate(f, None), f)
