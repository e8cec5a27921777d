"""Gains validation: every range names its parameter; the CLI answers exit 2, writes nothing."""

import subprocess
import sys

import pytest
from lgw.theory.errors import ParameterError
from lgw.theory.lunar.gains import from_dict, load, paper_gains
from lgw.theory.lunar.parameters import ATTITUDE_GAINS, ORBIT_GAINS


def _with(loop, **kw):
    base = {"orbit": dict(ORBIT_GAINS), "attitude": dict(ATTITUDE_GAINS)}
    base[loop].update(kw)
    return base


@pytest.mark.parametrize("loop,kw,name", [
    ("orbit", {"F2": [0.4, 1, 1]}, "orbit.F2"),  # min eigenvalue <= 1/2
    ("orbit", {"F2": [[1, 2, 0], [0, 1, 0], [0, 0, 1]]}, "orbit.F2"),  # not symmetric
    ("attitude", {"F2": [[1, 2, 0], [2, 1, 0], [0, 0, 1]]}, "attitude.F2"),  # indefinite
    ("orbit", {"f3": 1.0}, "orbit.f3"),  # f3 = f2bar
    ("attitude", {"f3": 0.0}, "attitude.f3"),
    ("orbit", {"q": 0.0}, "orbit.q"),
    ("orbit", {"d0e0": -1.0}, "orbit.d0e0"),
    ("orbit", {"K1": [1, 1, 0]}, "orbit.K1"),  # F1 = K1_zz = 0
    ("attitude", {"K1": [1, -1, 1]}, "attitude.K1"),  # F1 singular / indefinite
    ("orbit", {"K1": [1, 1]}, "orbit.K1"),
    ("orbit", {"f3": "0.1"}, "orbit.f3"),
    ("orbit", {"bogus": 1}, "orbit.bogus"),
])
def test_bad_gains_name_the_parameter(loop, kw, name):
    with pytest.raises(ParameterError) as e:
        from_dict(_with(loop, **kw))
    assert e.value.name == name


def test_paper_gains_valid():
    g = paper_gains()
    assert g.orbit.f2bar == 1.0 and g.attitude.f2bar == 5.0


def test_malformed_toml(tmp_path):
    p = tmp_path / "g.toml"
    p.write_text("[orbit\nK1 = ")
    with pytest.raises(ParameterError) as e:
        load(p)
    assert e.value.name == "--gains"


def test_cli_bad_gains_exit_2_nothing_written(tmp_path):
    p = tmp_path / "g.toml"
    p.write_text('[orbit]\nK1 = [0.1, 0.1, 0.1]\nF2 = [1, 1, 20]\nf3 = 2.0\nd0e0 = 0\nq = 0.01\n')
    out = tmp_path / "rep"
    r = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                        "report", "lunar", "--gains", str(p), "--out", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert r.stderr.startswith("error: orbit.f3")
    assert not out.exists()


def test_cli_bad_option_exit_2():
    r = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                        "simulate", "lunar", "--dt", "1.0"], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 2 and "error: --dt" in r.stderr
