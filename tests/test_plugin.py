"""The pytest plugin of lgw.testing, as a user's CI runs it: a temporary project with gains
files and a ten-line test using the ``lgw_claim`` fixture (one test per claim).  A claim that
holds passes, a claim whose inputs the file does not give is a skip with its reason, a violated
bound is one clean failure: observed, bound, state, gains and the reproducing command, with no
traceback and no object repr."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest_plugins = ["pytester"]

TUNED = (Path(__file__).parents[1] / "tuning" / "mars" / "data" /
         "tuned_tf90_50kN.toml").read_text()
LUNAR = """[orbit]
K1 = [0.1, 0.1, 0.1]
F2 = [1.0, 1.0, 20.0]
f3 = 0.25
d0e0 = 0.0
q = 0.01
"""
USER_TEST = '''
import pytest

FAST = dict(t_max=2.0, examples=5, min_cases=3, seed=0)


@pytest.mark.lgw_gains("lunar.toml", system="lunar", **FAST)
def test_lunar_gains(lgw_claim):
    lgw_claim.assert_holds()


@pytest.mark.lgw_gains("tuned.toml", system="mars", claim=("s2-39-40", "s1-31-45"))
def test_tuned_mars_gains(lgw_claim):
    lgw_claim.assert_holds()


@pytest.mark.lgw_gains("lunar.toml", system="lunar", claim="(19a)", scale={"(19a)": 0.25},
                       **FAST)
def test_a_false_promise(lgw_claim):
    lgw_claim.assert_holds()
'''


def test_pass_skip_and_one_clean_failure(pytester):
    pytester.makefile(".toml", lunar=LUNAR, tuned=TUNED)
    pytester.makepyfile(test_user=USER_TEST)
    res = pytester.runpytest_inprocess("-p", "no:cacheprovider", "-rs", "-q")
    # lunar: its 6 campaign claims pass (the paper's (19b) as printed only on --claim), its 8
    # certificate claims skip (a hand-written file promises nothing); mars: 2 skips
    res.assert_outcomes(passed=6, skipped=10, failed=1)
    out = res.stdout.str()
    assert "not applicable, because the gains file has no [disturbance] table" in out
    assert out.count("not applicable, because the gains file has no [certificate] table") == 8
    fail = out[out.index("test_a_false_promise"):]
    for part in ("(19a) (19a): observed", "observed: ||z1||^2", "bound: V2(0)/f1bar",
                 "state: x1 = ", "gains: ", "reproduce: lgw verify lunar --gains "):
        assert part in fail, part
    assert "Traceback" not in out and "ClaimResult(" not in out and "def test_" not in fail


@pytest.mark.slow
def test_whole_file_fixture_in_a_fresh_process_keeps_the_database(pytester):
    """``lgw_verify`` for the whole file in a fresh pytest process (entry point pytest11);
    the example database lands in the project's pytest cache (cache it between CI runs)."""
    pytester.makefile(".toml", lunar=LUNAR)
    pytester.makepyfile(test_user='''
import pytest


@pytest.mark.lgw_gains("lunar.toml", system="lunar", t_max=2.0, examples=6, min_cases=2)
def test_gains(lgw_verify):
    lgw_verify.assert_holds()
''')
    res = pytester.runpytest_subprocess("-q")
    res.assert_outcomes(passed=1)
    assert (pytester.path / ".pytest_cache" / "d" / "lgw-examples").is_dir()
