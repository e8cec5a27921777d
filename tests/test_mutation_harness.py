"""The shared mutation harness itself: it catches a flip that does not happen, a flip to the
wrong verdict and an unrelated change."""

from __future__ import annotations

import contextlib

import pytest

from tests.mutation import Mutation, check_mutation, differences


class _C:
    def __init__(self, id_: str, verdict: str) -> None:
        self.id, self.verdict = id_, verdict


STATE = {"a": "proved", "b": "refuted", "c": "checked"}


def _compute():
    return [_C(k, v) for k, v in STATE.items()]


@contextlib.contextmanager
def _set(**kw):
    old = dict(STATE)
    STATE.update(kw)
    try:
        yield
    finally:
        STATE.clear()
        STATE.update(old)


def test_expected_flip_passes():
    check_mutation(_compute, Mutation("fix b", lambda: _set(b="proved"), {"b": "proved"}))


def test_missing_flip_wrong_flip_and_unrelated_change_are_caught():
    with pytest.raises(AssertionError, match="expected refuted -> proved, got refuted"):
        check_mutation(_compute, Mutation("no-op", contextlib.nullcontext, {"b": "proved"}))
    with pytest.raises(AssertionError, match="got unproven"):
        check_mutation(_compute, Mutation("wrong", lambda: _set(b="unproven"), {"b": "proved"}))
    with pytest.raises(AssertionError, match="unrelated verdict changed"):
        check_mutation(_compute, Mutation("spill", lambda: _set(b="proved", c="refuted"),
                                          {"b": "proved"}))
    assert differences({"a": "proved"}, {"a": "proved"}, {"a": "proved"}) == [
        "a: already proved before the mutation (not a flip)"]
