"""The pytest plugin of lgw.testing for seed 001 in a fresh pytest process (entry point
pytest11), as a user's CI runs it: one test per claim passes for the paper's gains, and a
deliberately shrunk (19a) bound is one clean failure naming observed, bound, state and the
``lgw verify lunar`` command that reproduces it."""

from __future__ import annotations

import pytest

from tests.test_plugin import LUNAR

pytest_plugins = ["pytester"]
# a fresh pytest process per run (imports, Hypothesis): tens of seconds on a loaded machine
pytestmark = pytest.mark.slow

USER_TEST = """
import pytest


@pytest.mark.lgw_gains("gains.toml", system="lunar", examples=8, min_cases=10, t_max=2.0{extra})
def test_gains_keep_every_proven_bound(lgw_claim):
    lgw_claim.assert_holds()
"""

GAINS = LUNAR  # seed 001 Section 5's orbit loop


def _project(pytester, extra: str = ""):
    pytester.makefile(".toml", gains=GAINS)
    pytester.makepyfile(test_user=USER_TEST.format(extra=extra))


def test_plugin_passes_valid_lunar_gains(pytester):
    _project(pytester, ", seed=0")
    res = pytester.runpytest_subprocess("-q")
    res.assert_outcomes(passed=7)


def test_plugin_fails_cleanly_for_a_shrunk_lunar_bound(pytester):
    _project(pytester, ', claim="(19a)", scale={"(19a)": 0.25}')
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "-q")
    res.assert_outcomes(failed=1)
    out = res.stdout.str()
    assert "(19a) (19a): observed" in out and "re-checked" in out and "state: x1 = " in out
    assert "reproduce: lgw verify lunar --gains " in out and "Traceback" not in out
