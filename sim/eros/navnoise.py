"""Reproducible Gaussian numbers for the navigation error, from a counter: the number drawn for
(seed, case, sample k, component j) depends on those four integers only, so a case's errors are
the same whatever the batch, the chunking or the threads (no generator state is shared).

splitmix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014;
the finaliser of Vigna's splitmix64.c) hashes the counter into two 53-bit uniforms, and the
Box-Muller transform makes a standard normal of them.  ``nav_normal`` is the compiled form the
kernel calls; ``nav_normal_py`` the same arithmetic on Python integers (masked to 64 bits), the
independent route the tests compare against.
"""

from __future__ import annotations

import math

import numba
import numpy as np

_GOLDEN = 0x9E3779B97F4A7C15
_M1 = 0xBF58476D1CE4E5B9
_M2 = 0x94D049BB133111EB
_MASK = (1 << 64) - 1
_TWO53 = 2.0 ** -53


@numba.njit(cache=True)
def _mix(x):
    """splitmix64 step on a uint64."""
    z = x + np.uint64(_GOLDEN)
    z = (z ^ (z >> np.uint64(30))) * np.uint64(_M1)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(_M2)
    return z ^ (z >> np.uint64(31))


@numba.njit(cache=True)
def nav_normal(seed: int, case: int, k: int, j: int) -> float:
    """A standard normal number for the counter (seed, case, k, j), all integers >= 0."""
    h = _mix(np.uint64(seed))
    h = _mix(h ^ np.uint64(case))
    h = _mix(h ^ np.uint64(k))
    h1 = _mix(h ^ np.uint64(2 * j))
    h2 = _mix(h ^ np.uint64(2 * j + 1))
    u1 = (float(h1 >> np.uint64(11)) + 1.0) * _TWO53  # (0, 1]
    u2 = float(h2 >> np.uint64(11)) * _TWO53  # [0, 1)
    return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)


def _mix_py(x: int) -> int:
    z = (x + _GOLDEN) & _MASK
    z = ((z ^ (z >> 30)) * _M1) & _MASK
    z = ((z ^ (z >> 27)) * _M2) & _MASK
    return z ^ (z >> 31)


def nav_normal_py(seed: int, case: int, k: int, j: int) -> float:
    """``nav_normal`` in Python integer arithmetic (the reference route)."""
    h = _mix_py(seed & _MASK)
    h = _mix_py(h ^ case)
    h = _mix_py(h ^ k)
    h1 = _mix_py(h ^ (2 * j))
    h2 = _mix_py(h ^ (2 * j + 1))
    u1 = ((h1 >> 11) + 1.0) * _TWO53
    u2 = (h2 >> 11) * _TWO53
    return math.sqrt(-2.0 * math.log(u1)) * math.cos(2.0 * math.pi * u2)
