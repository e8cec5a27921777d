"""The pytest plugin of ``lgw.testing`` (entry point ``pytest11``: ``lgw``).

A user's test marks a test with the gains file to verify and asks for the ``lgw_verify``
fixture, which runs ``lgw verify``'s checks (the same records, the same verdicts) and returns
a report::

    @pytest.mark.lgw_gains("gains.toml", system="mars", profile="ci")
    def test_gains(lgw_verify):
        lgw_verify.assert_holds()

The path is relative to the test file.  Options of the marker: system ("mars", "lunar" or
"eros": lgw.testing.SYSTEMS), profile ("ci" | "thorough"), seed (default: see below; None for
random), min_cases, examples, scale (a dict claim -> factor on its bound: a self-test) and
database (a
folder for Hypothesis' example database; default the pytest cache folder
``.pytest_cache/lgw-examples``, kept between CI runs by caching that folder).  A database makes
the run random (Hypothesis uses none in a seeded run): without ``seed=`` the marker runs random
examples with the cached database; with ``seed=S`` (and no ``database=``) a derandomised run
without one.  The command-line
option ``--lgw-profile`` overrides the marker's profile.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("lgw", "lgw gain-set verification")
    group.addoption("--lgw-profile", default=None, choices=("ci", "thorough"),
                    help="verification profile for tests marked lgw_gains")


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "lgw_gains(path, system='mars', **options): verify a gains file with "
                   "the lgw_verify fixture")


@dataclass
class VerifyReport:
    """The records of one verification and how to read them."""

    path: Path
    system: str
    results: list

    @property
    def ok(self) -> bool:
        return all(r.verdict == "holds" for r in self.results)

    def by_claim(self) -> dict[str, Any]:
        return {r.claim: r for r in self.results}

    def explain(self) -> str:
        lines = [f"lgw verify {self.system} {self.path}:"]
        for r in self.results:
            lines.append(f"  {r.claim} {r.equation}: {r.verdict} ({r.n_checked} checked, "
                         f"{r.n_adaptive} by the fallback integrator, {r.n_excluded} "
                         "excluded)"
                         + (f" - {r.why}" if r.why else ""))
            if r.witness:
                lines.append(f"    shrunk witness: {r.witness}")
            if r.reproduction:
                lines.append("    reproduce:\n      " + r.reproduction.replace("\n", "\n      "))
        return "\n".join(lines)

    def assert_holds(self) -> None:
        if not self.ok:
            raise AssertionError(self.explain())


@pytest.fixture
def lgw_verify(request: pytest.FixtureRequest) -> VerifyReport:
    """Verify the gains file of the test's ``lgw_gains`` marker; returns a VerifyReport."""
    mark = request.node.get_closest_marker("lgw_gains")
    if mark is None or not mark.args:
        raise pytest.UsageError("lgw_verify needs @pytest.mark.lgw_gains(path, ...)")
    opts = dict(mark.kwargs)
    system = opts.pop("system", "mars")
    from lgw.testing import SYSTEMS

    if system not in SYSTEMS:
        raise pytest.UsageError(f"lgw_gains: system {system!r} is not available "
                                f"({', '.join(SYSTEMS)})")
    path = Path(mark.args[0])
    if not path.is_absolute():
        path = Path(request.node.fspath).parent / path
    cli_profile = request.config.getoption("--lgw-profile")
    if cli_profile:
        opts["profile"] = cli_profile
    cache = getattr(request.config, "cache", None)  # None under -p no:cacheprovider
    if "database" not in opts and "seed" not in opts and cache is not None:
        opts["database"] = Path(cache.mkdir("lgw-examples"))
    import importlib

    check_bounds = importlib.import_module(f"lgw.testing.{system}").check_bounds
    return VerifyReport(path, system, check_bounds(path, **opts))
