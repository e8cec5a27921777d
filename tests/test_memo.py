"""The memo of the theory modules: functools.cache's behaviour, plus a store that a mutation
check can keep (derive afresh within, the earlier results back after)."""

from __future__ import annotations

import sys
import types

from lgw.theory.symbolic import clear_module_caches, kept_module_caches, memo


def _module():
    mod = types.ModuleType("lgw_memo_probe")
    calls: list[tuple] = []

    @memo
    def f(x, scale=1):
        calls.append((x, scale))
        return x * scale

    mod.f, mod.calls = f, calls
    sys.modules[mod.__name__] = mod
    return mod


def test_memo_caches_by_arguments_and_clears():
    m = _module()
    try:
        assert m.f(2) == 2 and m.f(2) == 2 and m.f(2, scale=3) == 6 and m.f(2, scale=3) == 6
        assert m.calls == [(2, 1), (2, 3)]
        clear_module_caches((m.__name__,))
        m.f(2)
        assert m.calls[-1] == (2, 1) and len(m.calls) == 3
    finally:
        del sys.modules[m.__name__]


def test_kept_caches_come_back_and_what_was_derived_within_goes():
    m = _module()
    try:
        m.f(1)
        with kept_module_caches((m.__name__,)):
            clear_module_caches((m.__name__,))
            m.f(1)  # derived afresh within
            m.f(5)
            assert len(m.calls) == 3
        n = len(m.calls)
        m.f(1)  # the result from before is back: no call
        assert len(m.calls) == n
        m.f(5)  # derived within: gone
        assert len(m.calls) == n + 1
    finally:
        del sys.modules[m.__name__]


def test_memo_by_key_serves_equal_values_of_unhashable_arguments():
    calls = []

    @memo(key=lambda xs: tuple(xs))
    def total(xs):
        calls.append(list(xs))
        return sum(xs)

    assert total([1, 2]) == 3 and total([1, 2]) == 3 and total([2, 2]) == 4
    assert calls == [[1, 2], [2, 2]]
