"""The mutation harness shared by every system's ``tests/<system>/test_mutations.py``.

A mutation changes one object the verdicts are computed from (a law's expression, a bound
function, a model constant, a gain) for the duration of a ``with`` block.  The harness computes
every claim's verdict before and inside the block and requires that exactly the expected
verdicts flip, to the expected values, and that no other verdict changes.  A mutation that
should flip a verdict and does not, or that changes an unrelated one, fails the test with the
list of differences.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from contextlib import AbstractContextManager, ExitStack, contextmanager
from dataclasses import dataclass
from typing import Any

import pytest


@dataclass(frozen=True)
class Mutation:
    """``patch()`` returns a context manager inside which the mutation is in force;
    ``flips`` maps claim id -> the verdict it must have under the mutation (every other claim
    keeps its verdict)."""

    name: str
    patch: Callable[[], AbstractContextManager[Any]]
    flips: Mapping[str, str]
    why: str = ""


def verdicts(claims: Iterable[Any]) -> dict[str, str]:
    """claim id -> verdict (ids are unique: a duplicate is an error of the claim set)."""
    out: dict[str, str] = {}
    for c in claims:
        if c.id in out:
            raise AssertionError(f"duplicate claim id {c.id}")
        out[c.id] = c.verdict
    return out


def differences(base: Mapping[str, str], mutated: Mapping[str, str],
                flips: Mapping[str, str]) -> list[str]:
    """What the mutation did wrong: an expected flip that did not happen (or went elsewhere),
    a claim that appeared or vanished, and any unrelated verdict that changed."""
    bad: list[str] = []
    for cid, want in flips.items():
        if cid not in base:
            bad.append(f"{cid}: no such claim")
        elif base[cid] == want:
            bad.append(f"{cid}: already {want} before the mutation (not a flip)")
        elif mutated.get(cid) != want:
            bad.append(f"{cid}: expected {base[cid]} -> {want}, got {mutated.get(cid)}")
    for cid in sorted(set(base) | set(mutated)):
        if cid in flips:
            continue
        if base.get(cid) != mutated.get(cid):
            bad.append(f"{cid}: unrelated verdict changed {base.get(cid)} -> {mutated.get(cid)}")
    return bad


def check_mutation(compute: Callable[[], Iterable[Any]], mutation: Mutation,
                   base: Mapping[str, str] | None = None) -> dict[str, str]:
    """Run ``compute`` (every claim of a system) unmutated (unless ``base`` is given) and under
    ``mutation``; raise AssertionError listing every difference.  Returns the mutated
    verdicts."""
    base = dict(verdicts(compute())) if base is None else dict(base)
    with mutation.patch():
        mutated = verdicts(compute())
    bad = differences(base, mutated, mutation.flips)
    if bad:
        raise AssertionError(f"mutation {mutation.name!r}: " + "; ".join(bad))
    return mutated


@contextmanager
def patched(clear: Callable[[], None], *patches: AbstractContextManager[Any]):
    """The mutation ``patches`` (e.g. ``unittest.mock.patch.object``) in force, with the
    system's caches cleared on the way in and out (``clear``: its claims module's
    ``clear_caches``), so that every claim is derived afresh from the mutated objects and the
    unmutated ones afterwards."""
    clear()
    try:
        with ExitStack() as stack:
            for p in patches:
                stack.enter_context(p)
            yield
    finally:
        clear()


def maker(clear: Callable[[], None]) -> Callable[..., Mutation]:
    """``m(name, flips, why, *patches)``: a ``Mutation`` whose ``patches`` are in force with
    the system's caches cleared (``clear``; see ``patched``)."""

    def m(name: str, flips: Mapping[str, str], why: str,
          *patches: AbstractContextManager[Any]) -> Mutation:
        return Mutation(name, lambda: patched(clear, *patches), flips, why)

    return m


class MutationSuite:
    """The tests of a system's mutation table, written once.  A system's test module
    subclasses it (``class TestMutations(MutationSuite)``) and sets ``compute`` (every claim
    of the system, a staticmethod), ``clear`` (its caches), ``mutations`` and ``default``
    (the index of a cheap mutation: the default suite runs it, the slow profile all)."""

    compute: Callable[[], Iterable[Any]]
    clear: Callable[[], None]
    mutations: tuple[Mutation, ...] = ()
    default: int = 0

    def pytest_generate_tests(self, metafunc: pytest.Metafunc) -> None:
        if "mutation" in metafunc.fixturenames:
            metafunc.parametrize("mutation", self.mutations,
                                 ids=[m.name for m in self.mutations])

    @pytest.fixture(scope="class")
    @classmethod
    def base(cls) -> dict[str, str]:
        cls.clear()
        return verdicts(cls.compute())

    @pytest.mark.slow
    def test_mutation_flips_exactly_the_expected_verdicts(self, base, mutation) -> None:
        check_mutation(self.compute, mutation, base)

    def test_one_mutation_in_the_default_suite(self, base) -> None:
        check_mutation(self.compute, self.mutations[self.default], base)

    def test_at_least_six_mutations_across_laws_bounds_and_constants(self, base) -> None:
        kinds = {m.name.split(":")[0] for m in self.mutations}
        assert len(self.mutations) >= 6 and {"law", "bound", "model constant"} <= kinds
        assert all(m.flips and m.why for m in self.mutations)
        assert all(set(m.flips) <= set(base) for m in self.mutations), \
            [sorted(set(m.flips) - set(base)) for m in self.mutations]
