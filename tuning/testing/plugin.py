"""The pytest plugin of ``lgw.testing`` (entry point ``pytest11``: ``lgw``).

Mark a test with the gains file to verify and ask for ``lgw_claim``: the test runs once per
claim of the system, each a pass, a skip (the claim does not apply to the file, with the
reason) or one clean failure (what was observed against which bound, at which state and gains,
and the ``lgw verify`` command that reproduces it; no traceback)::

    @pytest.mark.lgw_gains("gains.toml", system="mars")
    def test_gains(lgw_claim):
        lgw_claim.assert_holds()

or ask for ``lgw_verify`` for the whole file in one test (``.results``, ``.ok``,
``.explain()``, ``.assert_holds()``: fails on a violated or inconclusive claim, skips when no
claim applies).  The checks run once per file and options, whatever the number of tests.

The path is relative to the test file.  Marker options: ``system`` ("mars", "lunar" or
"eros"), and any option of ``lgw verify SYSTEM`` by its Python name (``profile``, ``seed``,
``examples``, ``min_cases``, ``max_excluded``, ``domain``, ``envelope``, ``claim``, ``scale``
as a dict claim -> factor, ``database``, the system's own settings).  ``--lgw-profile``
overrides the marker's profile.  Hypothesis' example database defaults to the pytest cache
(``.pytest_cache/d/lgw-examples``, kept between CI runs by caching that folder): a database
makes the run random (Hypothesis uses none in a seeded run), so give ``seed=S`` (and no
``database=``) for a derandomised run without one.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

_CACHE = pytest.StashKey[dict]()


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("lgw", "lgw gain-set verification")
    group.addoption("--lgw-profile", default=None, choices=("ci", "thorough"),
                    help="verification profile for tests marked lgw_gains")


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "lgw_gains(path, system='mars', **options): verify a gains file with "
                   "the lgw_claim (one test per claim) or lgw_verify fixture")
    config.stash[_CACHE] = {}


def _claims(system: str, options: dict[str, Any]) -> list[str]:
    """The claims a run with the marker's options checks (its ``claim``, else the system's
    default selection), one test each."""
    from lgw.theory.errors import ParameterError
    from lgw.tuning.verifying import offered_claims

    opts = {k: v for k, v in options.items() if k != "system"}
    try:
        return offered_claims(system, **opts)
    except ParameterError:  # reported by the fixture, as one clean failure per test
        from lgw.tuning.system import get_system

        return list(get_system(system).verb("verify").load().CLAIMS)


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    if "lgw_claim" not in metafunc.fixturenames:
        return
    mark = metafunc.definition.get_closest_marker("lgw_gains")
    if mark is None:
        return
    system = mark.kwargs.get("system", "mars")
    names = _claims(system, dict(mark.kwargs))
    metafunc.parametrize("lgw_claim", names, indirect=True, ids=names)


@dataclass
class ClaimCheck:
    """One claim's result for the marked gains file."""

    path: Path
    system: str
    result: Any  # lgw.tuning.verifying.ClaimResult

    def assert_holds(self) -> None:
        r = self.result
        if r.verdict == "not-applicable":
            pytest.skip(f"lgw verify {self.system} {r.claim}: {r.why}")
        if r.verdict != "holds":
            pytest.fail(f"lgw verify {self.system} {self.path}:\n{r.explain()}", pytrace=False)


@dataclass
class VerifyReport:
    """The records of one verification of a gains file and how to read them."""

    path: Path
    system: str
    results: list

    @property
    def ok(self) -> bool:
        return all(r.verdict in ("holds", "not-applicable") for r in self.results)

    def by_claim(self) -> dict[str, Any]:
        return {r.claim: r for r in self.results}

    def explain(self) -> str:
        lines = [f"lgw verify {self.system} {self.path}:"]
        for r in self.results:
            if r.verdict == "holds":
                lines.append(f"  {r.claim} {r.equation}: holds ({r.informative} informative "
                             f"of {r.total} cases, worst margin {r.margin:.4g})")
            elif r.verdict == "not-applicable":
                lines.append(f"  {r.claim} {r.equation}: {r.why}")
            else:
                lines.append("  " + r.explain().replace("\n", "\n  "))
        return "\n".join(lines)

    def assert_holds(self) -> None:
        """Fail (one clean message) on a violated or inconclusive claim; skip when no claim
        applies to the file."""
        if not self.ok:
            pytest.fail(self.explain(), pytrace=False)
        if all(r.verdict == "not-applicable" for r in self.results):
            pytest.skip(self.explain())


def _run(request: pytest.FixtureRequest) -> tuple[Path, str, list]:
    node = getattr(request, "node", None)
    mark = node.get_closest_marker("lgw_gains") if node is not None else None
    if mark is None or not mark.args:
        raise pytest.UsageError("lgw_verify / lgw_claim need @pytest.mark.lgw_gains(path, ...)")
    opts = dict(mark.kwargs)
    system = opts.pop("system", "mars")
    from lgw import SYSTEMS

    if system not in SYSTEMS:
        raise pytest.UsageError(f"lgw_gains: system {system!r} is not one of "
                                f"{', '.join(SYSTEMS)}")
    path = Path(mark.args[0])
    if not path.is_absolute():
        path = Path(node.path).parent / path
    cli_profile = request.config.getoption("--lgw-profile")
    if cli_profile:
        opts["profile"] = cli_profile
    cache = getattr(request.config, "cache", None)  # None under -p no:cacheprovider
    if "database" not in opts and "seed" not in opts and cache is not None:
        opts["database"] = Path(cache.mkdir("lgw-examples"))
    key = (str(path), system, repr(sorted(opts.items(), key=lambda kv: kv[0])))
    store = request.config.stash[_CACHE]
    if key not in store:
        from lgw.theory.errors import ParameterError
        from lgw.tuning.verifying import run_checks

        try:
            store[key] = run_checks(system, path, **opts)
        except ParameterError as e:  # a bad gains file or option: one line, no traceback
            store[key] = e
    res = store[key]
    if isinstance(res, Exception):
        pytest.fail(f"lgw verify {system} {path}: error: {res}", pytrace=False)
    return path, system, res


@pytest.fixture
def lgw_verify(request: pytest.FixtureRequest) -> VerifyReport:
    """Verify the gains file of the test's ``lgw_gains`` marker; returns a VerifyReport."""
    return VerifyReport(*_run(request))


@pytest.fixture
def lgw_claim(request: pytest.FixtureRequest) -> ClaimCheck:
    """One claim (the test is parametrized over the system's claims) of the marked file."""
    path, system, results = _run(request)
    name = getattr(request, "param", None)
    by = {r.claim: r for r in results}
    if name not in by:
        raise pytest.UsageError(f"lgw_claim: claim {name!r} was not checked")
    return ClaimCheck(path, system, by[name])
