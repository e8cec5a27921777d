"""The generic batched integrator (lgw.sim.integrate) with a client that is not seed 000: a
linear field y' = A y of any state size, and an event (the first component falling to a
level) located inside the step.  Checked against closed forms (rotation, oscillator)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from lgw.sim import executors, integrate, kernel_cache
from lgw.sim.options import IntegrationOptions
from lgw.theory.errors import ParameterError

HOOKS = '''
def sys_init(i, C, Q, y, S):
    (y0,) = C
    for j in range(NY):
        y[j] = y0[i, j]
    S[0] = 0.0


def sys_rhs(t, Y, yr, K, kr, X, i, C, Q):
    A, level, stop_at_level = Q
    for j in range(NY):
        acc = 0.0
        for k in range(NY):
            acc += A[j, k] * Y[yr, k]
        K[kr, j] = acc
    X[0] = Y[yr, 0] - level


def sys_start(i, y, X, S, C, Q, R):
    return False


def sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R):
    A, level, stop_at_level = Q
    (t_event,) = R
    if S[0] == 0.0 and y[0] > level and yn[0] <= level:
        th = _herm_first_below(y[0], k1[0], yn[0], k1n[0], h, level)
        t_event[i] = t + th * h
        S[0] = 1.0
        if stop_at_level:
            return STOP_INSIDE, th
    return CONTINUE, 1.0


def sys_finish(i, t, y, S, C, Q, R):
    (t_event,) = R
    if S[0] == 0.0:
        t_event[i] = math.nan


''' + "\n".join(integrate.hook_jit(["sys_init", "sys_rhs", "sys_start", "sys_step",
                                       "sys_finish"]))


@pytest.fixture(scope="module")
def kernels():
    """The kernels for state sizes 2 and 3, generated into the kernel cache (keyed by their
    source, so a second session loads the machine code instead of compiling)."""
    out = {}
    for ny in (2, 3):
        src = integrate.kernel_module_source("", HOOKS, {"NY": ny, "NX": 1, "NS": 1})
        out[ny] = kernel_cache.load_module(f"test_linear_{ny}_{kernel_cache.key([src])}",
                                           lambda src=src: src)
    return out


def _run(mod, y0, A, *, level=0.0, stop=True, t_max=3.0, chunk=1000, parallel=False, **opt):
    n, ny = y0.shape
    io = IntegrationOptions(**{"dt": 0.01, "rtol": 1e-9, "atol": 1e-12, "max_step": 0.5,
                               "max_steps": 100_000, **opt})
    O = integrate.integration_tuple(io, t_max)  # noqa: N806
    t_event = np.empty(n)
    g = integrate.generic_outputs(n, ny)
    G = tuple(g[k] for k in integrate.GENERIC_FIELDS)  # noqa: N806
    shape = (n, O[2] + 1) if io.record else (1, 1)
    rec_y, rec_x = np.full(shape + (ny,), np.nan), np.full(shape + (1,), np.nan)
    executors.run_local(lambda sl: integrate.run_chunk(mod.kernel, sl, (y0,), (A, level, stop),
                                                       (t_event,), O, G, rec_y, rec_x,
                                                       parallel), n, chunk)
    return t_event, g, rec_y


ROT = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])  # y' = e_z x y
OSC = np.array([[0.0, 1.0], [-1.0, 0.0]])  # x'' = -x


@pytest.mark.parametrize("method, tol", [("rk4", 1e-8), ("dopri5", 1e-7)])
def test_event_and_state_against_closed_form(kernels, method, tol):
    rng = np.random.default_rng(1)
    n = 50
    phase = rng.uniform(0.1, 1.4, n)  # x = cos(t + phase) reaches 0 at t = pi/2 - phase
    y3 = np.column_stack([np.cos(phase), np.sin(phase), rng.uniform(-1, 1, n)])
    y2 = np.column_stack([np.cos(phase), -np.sin(phase)])
    for ny, A, y0 in ((3, ROT, y3), (2, OSC, y2)):
        te, g, _ = _run(kernels[ny], y0, A, method=method)
        np.testing.assert_allclose(te, np.pi / 2 - phase, atol=tol)
        np.testing.assert_allclose(g["t_end"], te, atol=0)  # stopped at the event
        np.testing.assert_allclose(g["y_end"][:, 0], 0.0, atol=tol)
        if ny == 3:  # the rotation keeps |y| and y_z
            np.testing.assert_allclose(g["y_end"][:, 2], y0[:, 2], atol=tol)
        assert not g["nonfinite"].any() and not g["step_limit"].any()
        # no stop: integrates to t_max, event still recorded; state = closed form at t_max
        te2, g2, _ = _run(kernels[ny], y0, A, method=method, stop=False)
        np.testing.assert_allclose(te2, te, atol=1e-12)
        np.testing.assert_allclose(g2["t_end"], 3.0, rtol=1e-12)
        np.testing.assert_allclose(g2["y_end"][:, 0], np.cos(3.0 + phase), atol=10 * tol)


def test_chunking_and_threads_do_not_change_results(kernels, monkeypatch):
    rng = np.random.default_rng(2)
    y0 = rng.normal(size=(37, 3))
    base = _run(kernels[3], y0, ROT, method="dopri5")
    monkeypatch.setattr(integrate, "threads", lambda: 3)  # pieces on 3 threads, any machine
    for kw in ({"chunk": 5}, {"chunk": 1}, {"parallel": True, "chunk": 7},
               {"parallel": True, "chunk": 37}):
        other = _run(kernels[3], y0, ROT, method="dopri5", **kw)
        np.testing.assert_array_equal(other[0], base[0])
        for k in integrate.GENERIC_FIELDS:
            np.testing.assert_array_equal(other[1][k], base[1][k])


def test_nonfinite_step_limit_and_record(kernels):
    y0 = np.array([[1.0, 0.0, 0.0], [1e308, 1e308, 0.0]])
    big = ROT * 1e10  # RK4 at h = 0.01 grows |y| ~1e8 per step: both cases overflow
    _, g, _ = _run(kernels[3], y0, big, stop=False)
    assert g["nonfinite"][0] and g["steps"][0] > 0 and not np.isfinite(g["y_end"][0]).all()
    assert np.isfinite(g["t_end"][0]) and g["t_end"][0] < 3.0  # stopped there, flagged
    assert g["nonfinite"][1] and g["t_end"][1] == 0.0 and g["steps"][1] == 0
    _, g, _ = _run(kernels[3], y0[:1], ROT, method="dopri5", max_steps=3, stop=False)
    assert g["step_limit"][0] and g["steps"][0] <= 3
    te, g, rec = _run(kernels[3], y0[:1], ROT, record=True, stop=False, t_max=1.0)
    t = np.arange(rec.shape[1]) * 0.01
    np.testing.assert_allclose(rec[0, :, 0], np.cos(t), atol=1e-9)
    np.testing.assert_allclose(rec[0, :, 1], np.sin(t), atol=1e-9)


def test_options_feed_the_kernel_tuple():
    io = IntegrationOptions(method="dopri5", dt=0.05, rtol=1e-6, atol=1e-7, max_step=1.0,
                            max_steps=10)
    O = integrate.integration_tuple(io, 1.0)  # noqa: N806
    assert O == (1, 0.05, 20, 1e-6, 1e-7, 1.0, 1.0, 10, 0.0, 1, False)  # no sampling
    assert integrate.integration_tuple(io, 0.999)[2] == math.ceil(0.999 / 0.05)
    with pytest.raises(ParameterError, match="record"):
        IntegrationOptions(method="dopri5", dt=0.05, rtol=1e-6, atol=1e-7, max_step=1.0,
                           max_steps=10, record=True)


# --- sampled data with a zero-order hold ------------------------------------------------------

ZOH_HOOKS = '''
def sys_init(i, C, Q, y, S):
    (y0,) = C
    y[0] = y0[i, 0]
    y[1] = y0[i, 1]
    y[2] = 0.0


def sys_rhs(t, Y, yr, K, kr, X, i, C, Q):
    K[kr, 0] = Y[yr, 1]
    K[kr, 1] = Y[yr, 2]  # x'' = u, u held
    K[kr, 2] = 0.0
    X[0] = 0.0


def sys_sample(i, k, t, y, S, C, Q, R):
    kp, kd = Q
    (u_rec, t_rec) = R
    y[2] = -kp * y[0] - kd * y[1]
    u_rec[i, k] = y[2]
    t_rec[i, k] = t
    return False


def sys_start(i, y, X, S, C, Q, R):
    return False


def sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R):
    return CONTINUE, 1.0


def sys_finish(i, t, y, S, C, Q, R):
    pass


''' + "\n".join(integrate.hook_jit(["sys_init", "sys_rhs", "sys_sample", "sys_start",
                                       "sys_step", "sys_finish"]))


@pytest.fixture(scope="module")
def zoh_kernel():
    src = integrate.kernel_module_source("", ZOH_HOOKS, {"NY": 3, "NX": 1, "NS": 1})
    return kernel_cache.load_module(f"test_zoh_{kernel_cache.key([src])}", lambda: src)


@pytest.mark.parametrize("method, nsub", [("rk4", 1), ("rk4", 3), ("dopri5", 1)])
def test_zero_order_hold_against_exact_recurrence(zoh_kernel, method, nsub):
    """x'' = u with u_k = -kp x(t_k) - kd x'(t_k) held on [t_k, t_k+1): the exact sampled
    solution is the recurrence x+ = x + v T + u T^2/2, v+ = v + u T (RK4 and dopri5 are exact
    on a quadratic, so only rounding separates them).  Held value constant, samples at k T."""
    ts, kp, kd, t_max = 0.1, 2.0, 0.7, 3.0
    y0 = np.array([[1.0, 0.0], [-0.3, 2.0]])
    n, kk = len(y0), 30
    io = IntegrationOptions(method=method, dt=0.05, rtol=1e-10, atol=1e-12, max_step=1.0,
                            max_steps=10_000)
    O = integrate.integration_tuple(io, t_max, sample=(ts, nsub))  # noqa: N806
    assert O[-3:-1] == (ts, nsub) and math.isclose(O[6], kk * ts)
    u_rec, t_rec = np.full((n, kk + 1), np.nan), np.full((n, kk + 1), np.nan)
    g = integrate.generic_outputs(n, 3)
    G = tuple(g[k] for k in integrate.GENERIC_FIELDS)  # noqa: N806
    integrate.run_chunk(zoh_kernel.kernel, slice(0, n), (y0,), (kp, kd), (u_rec, t_rec),
                        O, G, np.empty((1, 1, 3)), np.empty((1, 1, 1)), parallel=False)
    x, v = y0[:, 0].copy(), y0[:, 1].copy()
    u_ex = np.empty((n, kk + 1))
    for k in range(kk + 1):
        u_ex[:, k] = -kp * x - kd * v
        if k < kk:  # the last sample, at t_max, is read but not applied
            x, v = x + v * ts + u_ex[:, k] * ts**2 / 2, v + u_ex[:, k] * ts
    np.testing.assert_allclose(t_rec, np.broadcast_to(np.arange(kk + 1) * ts, (n, kk + 1)),
                               rtol=0, atol=1e-15)
    np.testing.assert_allclose(u_rec, u_ex, rtol=0, atol=1e-12)
    np.testing.assert_allclose(g["y_end"][:, 0], x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(g["t_end"], kk * ts, rtol=1e-15)
    if method == "rk4":
        assert (g["steps"] == kk * nsub).all()
    else:  # no step crosses a sample: at least one step per sample
        assert (g["steps"] >= kk).all()
