"""SymPy -> numba code generation for vector / matrix laws (lgw.sim.codegen) agrees with the
SymPy expression at random points (exact arithmetic on the SymPy side), and its modules are
cached on disk by numba (lgw.sim.kernel_cache)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from lgw.sim import codegen, kernel_cache
from lgw.theory.symbolic import sig

q = sp.Matrix(sp.symbols("q0:4", real=True))
w = sp.Matrix(sp.symbols("w0:3", real=True))
r = sp.Matrix(sp.symbols("r0:3", real=True))
v = sp.Matrix(sp.symbols("v0:3", real=True))


def quat_mul(a: sp.Matrix, b: sp.Matrix) -> sp.Matrix:
    """Hamilton product a (x) b, scalar first."""
    a0, av = a[0], sp.Matrix(a[1:])
    b0, bv = b[0], sp.Matrix(b[1:])
    return sp.Matrix([a0 * b0 - av.dot(bv), *(a0 * bv + b0 * av + av.cross(bv))])


# q' = 1/2 q (x) [0, w] (body rates w); the rotating-frame acceleration -2 w x v - w x (w x r)
QDOT = quat_mul(q, sp.Matrix([0, *w])) / 2
CORIOLIS = -2 * w.cross(v) - w.cross(w.cross(r))
# a matrix output: the rotation matrix of a unit quaternion (body -> inertial)
_a, _b, _c, _d = q
ROT = sp.Matrix([
    [1 - 2 * (_c**2 + _d**2), 2 * (_b * _c - _a * _d), 2 * (_b * _d + _a * _c)],
    [2 * (_b * _c + _a * _d), 1 - 2 * (_b**2 + _d**2), 2 * (_c * _d - _a * _b)],
    [2 * (_b * _d - _a * _c), 2 * (_c * _d + _a * _b), 1 - 2 * (_b**2 + _c**2)]])
# a coupled non-smooth law: a terminal-sliding-like term on each axis of s = v + c r
c = sp.Symbol("c", positive=True)
SLIDE = sp.Matrix([-sig(v[k] + c * r[k], sp.Rational(1, 2)) - sp.sign(r[k]) * w.norm()
                   for k in range(3)])


@pytest.fixture(scope="module")
def fns():
    return {
        "qdot": codegen.compile_source(codegen.vector_source("qdot", [("q", q), ("w", w)],
                                                             QDOT), "qdot"),
        "cor": codegen.compile_source(codegen.vector_source(
            "cor", [("w", w), ("r", r), ("v", v)], CORIOLIS), "cor"),
        "rot": codegen.compile_source(codegen.vector_source("rot", [("q", q)], ROT), "rot"),
        "slide": codegen.compile_source(codegen.vector_source(
            "slide", [("r", r), ("v", v), ("w", w), ("c", c)], SLIDE), "slide"),
    }


def _exact(expr: sp.Matrix, subs: dict) -> np.ndarray:
    vals = {k: sp.Float(repr(float(x)), 40) for k, x in subs.items()}
    return np.array(sp.N(expr.xreplace(vals), 30).tolist(), dtype=float).reshape(expr.shape)


finite = st.floats(-50, 50, allow_nan=False, allow_infinity=False)


@settings(max_examples=40, deadline=None)
@given(st.lists(finite, min_size=4, max_size=4), st.lists(finite, min_size=3, max_size=3))
def test_quaternion_kinematics(fns, qv, wv):
    qa, wa = np.array(qv), np.array(wv)
    got = fns["qdot"](qa, wa, np.empty(4))
    want = _exact(QDOT, {**dict(zip(q, qa, strict=True)), **dict(zip(w, wa, strict=True))})
    np.testing.assert_allclose(got, want.ravel(), rtol=1e-12, atol=1e-12 * (1 + abs(want).max()))


@settings(max_examples=40, deadline=None)
@given(st.lists(finite, min_size=9, max_size=9))
def test_rotating_frame_acceleration(fns, x):
    wa, ra, va = np.array(x[:3]), np.array(x[3:6]), np.array(x[6:])
    got = fns["cor"](wa, ra, va, np.empty(3))
    # independent route: numpy cross products
    ind = -2 * np.cross(wa, va) - np.cross(wa, np.cross(wa, ra))
    want = _exact(CORIOLIS, {**dict(zip(w, wa, strict=True)), **dict(zip(r, ra, strict=True)),
                             **dict(zip(v, va, strict=True))}).ravel()
    scale = 1e-12 * (1 + abs(want).max())
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=scale)
    np.testing.assert_allclose(ind, want, rtol=1e-10, atol=1e3 * scale)


def test_matrix_output_and_nonsmooth(fns):
    rng = np.random.default_rng(5)
    for _ in range(30):
        qa = rng.normal(size=4)
        qa /= np.linalg.norm(qa)
        got = fns["rot"](qa, np.empty((3, 3)))
        np.testing.assert_allclose(got, _exact(ROT, dict(zip(q, qa, strict=True))),
                                   rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(got @ got.T, np.eye(3), atol=1e-12)  # a rotation
        ra, va, wa = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
        ca = float(rng.uniform(0.1, 2))
        got = fns["slide"](ra, va, wa, ca, np.empty(3))
        want = _exact(SLIDE, {**dict(zip(r, ra, strict=True)), **dict(zip(v, va, strict=True)),
                              **dict(zip(w, wa, strict=True)), c: ca}).ravel()
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-14)
    # sign and sig at 0 follow SymPy (0), not 0 * inf or a smoothed value
    z = np.zeros(3)
    assert np.all(fns["slide"](z, z, z, 1.0, np.empty(3)) == 0.0)


def test_shared_subexpressions_and_errors():
    src = codegen.vector_source("cor", [("w", w), ("r", r), ("v", v)], CORIOLIS)
    assert "_x0 = " in src  # w x r is shared by the three components
    with pytest.raises(ValueError, match="not arguments"):
        codegen.vector_source("bad", [("q", q)], QDOT)  # w is not an argument


def test_module_is_cached_on_disk(tmp_path, monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path))
    src = codegen.module_source([("qdot", codegen.vector_source("qdot", [("q", q), ("w", w)],
                                                                 QDOT))])
    stem = "test_qdot_" + kernel_cache.key([src])
    mod = kernel_cache.load_module(stem, lambda: src)
    assert not kernel_cache.is_cached(mod.qdot)
    out = mod.qdot(np.array([1.0, 0, 0, 0]), np.array([0.0, 0, 2.0]), np.empty(4))
    np.testing.assert_allclose(out, [0, 0, 0, 1.0])
    assert kernel_cache.is_cached(mod.qdot)  # numba wrote its index next to the module
    assert (tmp_path / "kernels" / f"{stem}.py").read_text() == src


def test_unwritable_cache_falls_back(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("")
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(blocker / "sub"))  # a file as a parent
    monkeypatch.setattr(kernel_cache, "_FALLBACK", None)
    with pytest.warns(RuntimeWarning, match="not writable"):
        d = kernel_cache.cache_dir()
    assert d.is_dir() and str(blocker) not in str(d)
