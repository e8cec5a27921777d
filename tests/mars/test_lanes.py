"""The lane kernel (lgw.sim.mars.lanes) against the scalar kernel (lgw.sim.integrate).

The lane kernel evaluates the same generated law with exp / log from lgw.sim.vmath (within 1
ulp of the C library) and otherwise runs the same hooks, so its campaigns must give the same
outcomes and the same numbers to round-off; the stated tolerance below (1e-9 in landing time
s, fuel kg, landing position m, relative peak thrust) is ~1e4 times what Table II shows
(benchmarks/bench_lanes.py: |dt_land| ~ 1e-13 s) and far below anything physical.
"""

from __future__ import annotations

import numpy as np
import pytest
from lgw.sim import integrate
from lgw.sim.mars import lanes as mars_lanes
from lgw.sim.mars.batch import ARRAY_FIELDS, simulate_batch
from lgw.sim.mars.campaign import table2_states, table3_states
from lgw.sim.mars.laws import get_law, surface_params
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import THRUST_MAX_AXIS

G = default_gains()
TOL = 1e-9


def _lane_buffer(name: str, inputs: np.ndarray):
    """The lane module of law ``name``, its lane buffer holding ``inputs`` (5, 3, NL) = r, v,
    grav, a_m, m per axis and lane, and SP."""
    spec = get_law(name)
    mod = mars_lanes.kernel_module(name)
    nl = mod.NL
    P = np.ascontiguousarray(spec.param_values(G), float)  # noqa: N806
    lay = mars_lanes.lb_layout(P.shape[1], nl)
    LB = np.zeros((3, lay["LB_COLS"]))  # noqa: N806
    LB[:, :P.shape[1]] = P
    for k in range(5):
        LB[:, lay["NPAR"] + k * nl: lay["NPAR"] + (k + 1) * nl] = inputs[k]
    return mod, LB, np.ascontiguousarray(surface_params(G), float), lay


def _inputs(nl: int, rng) -> np.ndarray:
    """Law inputs over several decades, with the entries the scalar law sends to its other
    branches: r = 0 with v != 0 (a genuine inf), r = v = 0 (the origin form), |r| below TINY."""
    x = np.empty((5, 3, nl))
    x[0] = rng.choice([-1, 1], (3, nl)) * 10 ** rng.uniform(-8, 4, (3, nl))
    x[1] = rng.normal(0, 30, (3, nl))
    x[2] = np.array([[0.0], [0.0], [-3.7114]])
    x[3] = rng.normal(0, 0.05, (3, nl))
    x[4] = rng.uniform(1500, 1950, (1, nl))
    x[0, 0, 0] = 0.0  # r = 0, v != 0
    x[0, 1, 1] = x[1, 1, 1] = 0.0  # the origin
    x[0, 2, 2] = 1e-310  # below TINY: the exact form
    x[0, 0, 3] = -0.0
    return x


@pytest.mark.parametrize("name", ["corrected", "super-twisting"])
def test_lane_law_is_the_scalar_law(name: str) -> None:
    """The lane form of the generated law (the share_powers form for the corrected law, the
    exact form for (46), which has none) against the compiled scalar law, entry by entry,
    including the entries it hands to the scalar law's other branches."""
    rng = np.random.default_rng(11)
    nl = mars_lanes.NL
    for _ in range(20):
        x = _inputs(nl, rng)
        mod, LB, SP, lay = _lane_buffer(name, x)  # noqa: N806
        mod.law_lanes(LB, SP, np.ones(nl, bool))
        npar = lay["NPAR"]
        for ax in range(3):
            for ln in range(nl):
                a, s2 = mod.law_scalar(*x[:, ax, ln], LB, SP, ax)
                got = (LB[ax, npar + lay["LB_A"] * nl + ln],
                       LB[ax, npar + lay["LB_S2"] * nl + ln])
                for g, w in zip(got, (a, s2), strict=True):
                    if np.isfinite(w):
                        assert abs(g - w) <= 1e-13 * max(abs(w), 1.0), (name, ax, ln, g, w)
                    else:
                        assert g == w or (np.isnan(g) and np.isnan(w)), (name, ax, ln, g, w)


def test_replay_answers_only_at_the_lane_inputs() -> None:
    """``law`` (what sys_rhs calls in the lane kernel) returns the lane result when asked at
    the inputs the lane pass used (a_m to AM_RTOL) and otherwise the scalar law, counting a
    miss: a change to how sys_rhs calls the law cannot change results."""
    rng = np.random.default_rng(5)
    nl = mars_lanes.NL
    x = _inputs(nl, rng)
    mod, LB, SP, lay = _lane_buffer("corrected", x)  # noqa: N806
    mod.law_lanes(LB, SP, np.ones(nl, bool))
    npar = lay["NPAR"]
    ln, ax = 5, 1
    LB[0, lay["LB_LANE"]] = ln
    r, v, grav, a_m, m = x[:, ax, ln]
    lane = (LB[ax, npar + lay["LB_A"] * nl + ln], LB[ax, npar + lay["LB_S2"] * nl + ln])
    LB[ax, npar + lay["LB_A"] * nl + ln] = 12345.0  # a marker: the lane result is what returns
    assert mod.law(r, v, grav, a_m, m, LB, SP, ax)[0] == 12345.0
    assert mod.law(r, v, grav, a_m * (1 + 1e-15), m, LB, SP, ax)[0] == 12345.0
    assert LB[:, lay["LB_MISS"]].sum() == 0
    for args in ((r * (1 + 1e-15), v, a_m, m), (r, v + 1e-12, a_m, m),
                 (r, v, a_m * (1 + 1e-12), m), (r, v, a_m, m + 1e-9)):
        rr, vv, aa, mm = args
        got = mod.law(rr, vv, grav, aa, mm, LB, SP, ax)
        want = mod.law_scalar(rr, vv, grav, aa, mm, LB, SP, ax)
        assert got == want and got[0] != 12345.0
    assert LB[:, lay["LB_MISS"]].sum() == 4
    assert abs(lane[0] - mod.law_scalar(r, v, grav, a_m, m, LB, SP, ax)[0]) < 1e-9


def _fly(states, kernel: str, misses: list[int] | None = None, **kw):
    r0, v0, m0 = states
    if misses is None:
        return simulate_batch(r0, v0, m0, G, kernel=kernel, **kw)
    run = integrate.run_chunk

    def spy(fn, sl, C, Q, R, O, G_, rec_y, rec_x):  # noqa: N803
        misses.append(int(fn(tuple(a[sl] for a in C), Q, tuple(a[sl] for a in R), O,
                             tuple(a[sl] for a in G_), rec_y, rec_x)))
    integrate.run_chunk = spy
    try:
        return simulate_batch(r0, v0, m0, G, kernel=kernel, **kw)
    finally:
        integrate.run_chunk = run


def _agree(a, b) -> None:
    np.testing.assert_array_equal(a.outcomes()[0], b.outcomes()[0])
    for k in ("landed", "ground_contact", "fuel_exhausted", "nonfinite", "step_limit",
              "blown_up"):
        np.testing.assert_array_equal(getattr(a, k), getattr(b, k), err_msg=k)
    for k in ("landing_time", "fuel", "r_land", "v_land", "t_end", "y_end", "min_altitude",
              "time_saturated"):
        np.testing.assert_allclose(getattr(a, k), getattr(b, k), rtol=0, atol=TOL, err_msg=k)
    for k in ("peak_thrust", "peak_thrust_unsat", "peak_thrust_stages",
              "peak_thrust_unsat_stages", "peak_thrust_after_arrival"):
        np.testing.assert_allclose(getattr(a, k), getattr(b, k), rtol=TOL, atol=TOL,
                                   err_msg=k)


@pytest.mark.slow
@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_lanes_agree_with_scalar_kernel_on_table2(method: str) -> None:
    """Table II, corrected law: the same outcomes, landing times, fuel, landing states and
    peaks as the scalar kernel (TOL), the same step counts, and every law call of the lane
    kernel answered by the lane pass (no miss)."""
    states = table2_states(160, 0)
    kw = {} if method == "rk4" else {"method": "dopri5", "rtol": 1e-5, "atol": 1e-5}
    misses: list[int] = []
    lanes = _fly(states, "lanes", misses, **kw)
    scalar = _fly(states, "scalar", **kw)
    _agree(lanes, scalar)
    np.testing.assert_array_equal(lanes.steps, scalar.steps)
    assert lanes.landed.all() and misses and sum(misses) == 0
    assert lanes.info["kernel"] == "lanes"


@pytest.mark.slow
def test_lanes_agree_on_table3_with_limit_and_disturbance() -> None:
    """Table III with the 50 kN limit and the sine disturbance: saturation, ground contact
    and propellant exhaustion, the paths the Table II cases do not reach."""
    states = table3_states(96, 3)
    kw = {"thrust_limit": THRUST_MAX_AXIS, "disturbance": "sin"}
    lanes = _fly(states, "lanes", **kw)
    scalar = _fly(states, "scalar", **kw)
    _agree(lanes, scalar)
    assert (~lanes.landed).any() and lanes.ground_contact.any() and lanes.fuel_exhausted.any()
    assert (lanes.time_saturated > 0).any()


@pytest.mark.slow
def test_lane_results_do_not_depend_on_blocks_or_threads() -> None:
    """A case's result does not depend on which lane, block, chunk or thread flies it."""
    states = table2_states(70, 2)
    one = _fly(states, "lanes", parallel=False)
    two = _fly(states, "lanes", parallel=True, chunk=24)
    assert all(np.array_equal(getattr(one, k), getattr(two, k), equal_nan=True)
               for k in ARRAY_FIELDS)


def test_lanes_refuse_recording() -> None:
    r0, v0, m0 = table2_states(2, 0)
    with pytest.raises(ParameterError, match="kernel"):
        simulate_batch(r0, v0, m0, G, kernel="lanes", record=True)
    with pytest.raises(ParameterError, match="kernel"):
        simulate_batch(r0, v0, m0, G, kernel="simd")
