"""lgw.sim.vmath: exp and log to 1 ulp of numpy's over the whole double range, numpy's values
at the special points, and a loop over them that LLVM turns into vector code."""

from __future__ import annotations

import re

import numba
import numpy as np
import pytest
from lgw.sim.vmath import EXP_HI, EXP_LO, vexp, vlog

# the law's own flags: the vectorisable functions must keep their accuracy inside such a loop
LAW_FASTMATH = {"contract", "reassoc", "arcp", "nsz", "afn"}


@numba.njit(error_model="numpy", fastmath=LAW_FASTMATH)
def _exp_loop(x, out):
    for j in range(x.shape[0]):
        out[j] = vexp(x[j])


@numba.njit(error_model="numpy", fastmath=LAW_FASTMATH)
def _log_loop(x, out):
    for j in range(x.shape[0]):
        out[j] = vlog(x[j])


def _run(fn, x):
    out = np.empty_like(x)
    fn(x, out)
    return out


def _ulps(a: np.ndarray, b: np.ndarray) -> float:
    ok = np.isfinite(b) & (b != 0)
    return float(np.max(np.abs(a[ok] - b[ok]) / np.spacing(np.abs(b[ok]))))


def test_exp_within_one_ulp_and_special_values() -> None:
    rng = np.random.default_rng(3)
    x = np.concatenate([rng.uniform(EXP_LO, EXP_HI, 400_000), rng.uniform(-3, 3, 200_000),
                        np.linspace(-1e-300, 1e-300, 101)])
    with np.errstate(all="ignore"):
        assert _ulps(_run(_exp_loop, x), np.exp(x)) <= 1.0
    special = np.array([0.0, -0.0, np.inf, -np.inf, np.nan, EXP_HI, np.nextafter(EXP_HI, 1e3),
                        EXP_LO, np.nextafter(EXP_LO, -1e3), -1e4, 1e4, -744.5, -740.0])
    with np.errstate(all="ignore"):
        ref = np.exp(special)
    got = _run(_exp_loop, special)
    # subnormal results: within one unit of the smallest subnormal
    np.testing.assert_allclose(got, ref, rtol=1e-15, atol=5e-324)
    assert np.array_equal(np.isnan(got), np.isnan(ref))
    assert np.array_equal(np.isinf(got), np.isinf(ref))


def test_log_within_one_ulp_and_special_values() -> None:
    rng = np.random.default_rng(4)
    y = np.concatenate([10 ** rng.uniform(-323, 308, 400_000), rng.uniform(0.5, 2.0, 200_000),
                        np.array([5e-324, 1e-310, 2.2250738585072014e-308, 1.0,
                                  np.finfo(float).max])])
    assert _ulps(_run(_log_loop, y), np.log(y)) <= 1.0
    special = np.array([0.0, -0.0, np.inf, np.nan, -1.0, -np.inf, 1.0])
    with np.errstate(all="ignore"):
        ref = np.log(special)
    got = _run(_log_loop, special)
    np.testing.assert_array_equal(got, ref)  # -inf, -inf, inf, nan, nan, nan, 0


@pytest.mark.parametrize("fn", [_exp_loop, _log_loop])
def test_loops_are_vector_code_without_calls(fn) -> None:
    """The point of the module: no call to the C library in the loop, and vector registers
    wider than one double (xmm is scalar SSE, ymm AVX, zmm AVX-512)."""
    asm = fn.inspect_asm(fn.signatures[0])
    body = asm[asm.index(".cfi_startproc"):]
    assert not re.search(r"call\w*\s+\*?\S*(exp|log)", body)
    assert re.search(r"\b(v\w+pd)\s.*%[yz]mm", body), "the loop was not vectorised"
