"""The pytest plugin of lgw.testing for seed 002 in a fresh pytest process (entry point
pytest11), as a user's CI runs it: the default gains pass, the certificate claims of a file
without [certificate] are skips with their reason, and a tuned file whose certificate promises
a tracking time it does not meet is one clean failure with its reproduction."""

from __future__ import annotations

import pytest
from lgw.theory.eros.gains import default_gains, gains_to_toml

pytest_plugins = ["pytester"]
# a fresh pytest process per run, each batched simulation about 1.4 s: minutes when loaded
pytestmark = pytest.mark.slow

USER_TEST = """
import pytest


@pytest.mark.lgw_gains("gains.toml", system="eros", examples=3, min_cases=5, seed=0)
def test_gains_keep_every_proven_bound(lgw_claim):
    lgw_claim.assert_holds()
"""


# made at import: pytester restores sys.modules between tests, so nothing may be imported later
GAINS = gains_to_toml(default_gains())
FALSE_PROMISE = ('\n[certificate]\nlaw = "ftsmc-sign"\ne_max = 2.0\nv_max = 0.1\ndbar = 0.0\n'
                 'bound_t_total = 1.0\nu_max = 100.0\n')


def test_plugin_passes_and_skips_what_does_not_apply(pytester):
    pytester.makefile(".toml", gains=GAINS)
    pytester.makepyfile(test_user=USER_TEST)
    res = pytester.runpytest_subprocess("-q", "-rs")
    res.assert_outcomes(passed=4, skipped=2)
    assert "no [certificate] table" in res.stdout.str()


def test_plugin_fails_cleanly_for_a_false_certificate(pytester):
    pytester.makefile(".toml", gains=GAINS + FALSE_PROMISE)
    pytester.makepyfile(test_user=USER_TEST)
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "-q")
    res.assert_outcomes(passed=5, failed=1)
    out = res.stdout.str()
    assert "certificate-time certificate: observed" in out and "bound_t_total" in out
    assert "reproduce: lgw verify eros --gains " in out and "Traceback" not in out
