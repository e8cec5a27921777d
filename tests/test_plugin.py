"""The pytest plugin of lgw.testing, as a user would use it: a ten-line test file and a gains
file in a temporary project, run by pytest with the installed plugin (entry point pytest11).
It passes for valid gains and fails, with a shrunk witness and a reproduction, for a gains
file whose certificate promises a landing-time bound shorter than a reachable landing."""

from __future__ import annotations

import pytest
from lgw.theory.mars.bounds import landing_time_bound
from lgw.theory.mars.gains import gains_from_dict, gains_to_toml

pytest_plugins = ["pytester"]
# Each run is a fresh pytest process that compiles the simulator's numba kernels (~40 s of the
# ~60 s per test on a shared 2-core machine): long, so behind the slow marker.
pytestmark = pytest.mark.slow

USER_TEST = '''
import pytest


@pytest.mark.lgw_gains("gains.toml", system="mars", examples=4, min_cases=2)
def test_gains_keep_every_proven_bound(lgw_verify):
    lgw_verify.assert_holds()
'''

# A gain set whose worst landing (the search reaches it from |s2(0)| ~ 1e9) is 91.9 s, 0.80 of
# T2* + T1* = 114.7 s.
GAINS = {"gains": {"beta1": 0.2, "beta2": 0.01, "alpha1": 0.5, "alpha2": 0.02, "q1": 0.9,
                   "q2": 1.5, "g1": 0.7, "g2": 1.5},
         "disturbance": {"a_max": 20.0, "theta1": 0.2, "theta2": 0.1}}


def _project(pytester, certificate: str = ""):
    g = gains_from_dict(GAINS)
    pytester.makefile(".toml", gains=gains_to_toml(g) + certificate)
    pytester.makepyfile(test_user=USER_TEST)
    return g


def test_plugin_passes_valid_gains(pytester):
    _project(pytester)
    res = pytester.runpytest_subprocess("-q")
    res.assert_outcomes(passed=1)
    # the example database is kept in the project's pytest cache (cache it between CI runs)
    assert (pytester.path / ".pytest_cache" / "d" / "lgw-examples").is_dir()


def test_plugin_fails_with_shrunk_witness_for_a_shrunk_bound(pytester):
    g = gains_from_dict(GAINS)
    # promise 86 s (0.75 x T2* + T1*), shorter than the 91.9 s landing the search can reach
    promised = 0.75 * landing_time_bound(g)
    _project(pytester, f"\n[certificate]\nlanding_time_bound = {promised!r}\n")
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "-q")
    res.assert_outcomes(failed=1)
    out = res.stdout.str()
    assert "landing-T2+T1" in out and "violated" in out
    assert "shrunk witness" in out and "lgw simulate mars --gains witness_gains.toml" in out
