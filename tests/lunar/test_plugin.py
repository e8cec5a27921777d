"""The pytest plugin of lgw.testing for seed 001, as a user would use it: a ten-line test file
and a gains file in a temporary project, run by pytest with the installed plugin (entry point
pytest11).  It passes for the paper's gains and fails, with a shrunk witness re-checked at dt/2
and a reproduction, when the (19a) bound is deliberately shrunk (the marker's scale option)."""

from __future__ import annotations

import pytest

pytest_plugins = ["pytester"]
# a fresh pytest process per run (imports, Hypothesis): tens of seconds on a loaded machine
pytestmark = pytest.mark.slow

USER_TEST = """
import pytest


@pytest.mark.lgw_gains("gains.toml", system="lunar", examples=8, min_cases=10{extra})
def test_gains_keep_every_proven_bound(lgw_verify):
    lgw_verify.assert_holds()
"""

GAINS = """[orbit]
K1 = [0.1, 0.1, 0.1]
F2 = [1.0, 1.0, 20.0]
f3 = 0.25
d0e0 = 0.0
q = 0.01
"""


def _project(pytester, extra: str = ""):
    pytester.makefile(".toml", gains=GAINS)
    pytester.makepyfile(test_user=USER_TEST.format(extra=extra))


def test_plugin_passes_valid_lunar_gains(pytester):
    _project(pytester)
    res = pytester.runpytest_subprocess("-q")
    res.assert_outcomes(passed=1)
    assert (pytester.path / ".pytest_cache" / "d" / "lgw-examples").is_dir()


def test_plugin_fails_with_shrunk_witness_for_a_shrunk_lunar_bound(pytester):
    _project(pytester, ', scale={"(19a)": 0.25}')
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "-q")
    res.assert_outcomes(failed=1)
    out = res.stdout.str()
    assert "(19a) (19a): violated" in out and "re-checked" in out
    assert "shrunk witness" in out and "from lgw.tuning.lunar.verify import" in out
