"""The pytest plugin of lgw.testing for seed 002, as a user would use it: a ten-line test file
and a gains file in a temporary project, run by pytest with the installed plugin (entry point
pytest11).  It passes for the default gains and fails, with a shrunk witness confirmed by the
reference route and an ``lgw simulate eros --initial-states`` reproduction, when the
reaching + sliding bound is deliberately shrunk (the marker's scale option)."""

from __future__ import annotations

import pytest
from lgw.theory.eros.gains import default_gains, gains_to_toml

pytest_plugins = ["pytester"]
# a fresh pytest process per run, each batched simulation about 1.4 s: minutes when loaded
pytestmark = pytest.mark.slow

USER_TEST = """
import pytest


@pytest.mark.lgw_gains("gains.toml", system="eros", examples=3, min_cases=10{extra})
def test_gains_keep_every_proven_bound(lgw_verify):
    lgw_verify.assert_holds()
"""


# made at import: pytester restores sys.modules between tests, so nothing may be imported later
GAINS = gains_to_toml(default_gains())


def _project(pytester, extra: str = ""):
    pytester.makefile(".toml", gains=GAINS)
    pytester.makepyfile(test_user=USER_TEST.format(extra=extra))


def test_plugin_passes_valid_eros_gains(pytester):
    _project(pytester)
    res = pytester.runpytest_subprocess("-q")
    res.assert_outcomes(passed=1)
    assert (pytester.path / ".pytest_cache" / "d" / "lgw-examples").is_dir()


def test_plugin_fails_with_shrunk_witness_for_a_shrunk_eros_bound(pytester):
    _project(pytester, ', scale={"time-known": 0.5}')
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "-q")
    res.assert_outcomes(failed=1)
    out = res.stdout.str()
    assert "time-known" in out and "violated" in out and "reference route" in out
    assert "shrunk witness" in out and "lgw simulate eros --law ftsmc-sign" in out
