"""``lgw tune mars --law bounded``: proven certificates, infeasibility, the file."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from lgw.theory.mars import bounded as B
from lgw.theory.mars.gains import load_gains
from lgw.tuning.mars.design import envelope_from_name
from lgw.tuning.mars.design_bounded import (
    BoundedRequest,
    axis_certificate,
    packed_states,
    tune_bounded,
)


@pytest.fixture(scope="module")
def table3_result():
    env = envelope_from_name("table3")
    return env, tune_bounded(BoundedRequest(tf=150.0, thrust_max=50_000.0), env.boxes,
                             env.m_max, e1_grid=(0.2,))


def test_proven_certificate_covers_the_box(table3_result):
    env, res = table3_result
    assert res.feasible and res.time_proven
    assert res.F_proven <= 50_000.0 and res.T_proven <= 150.0
    # the certificate is for the gains returned (rounded), recomputed independently here
    for i, ax in enumerate("xyz"):
        again = axis_certificate(res.gains, i, env.boxes, env.m_max)
        assert again["F_b"] == pytest.approx(res.axes[ax]["F_b"])
        assert again["T_land"] == pytest.approx(res.axes[ax]["T_land"])


def test_tighter_tf_is_not_proven(table3_result):
    env, res = table3_result
    r2 = tune_bounded(BoundedRequest(tf=res.T_proven / 2, thrust_max=50_000.0), env.boxes,
                      env.m_max, e1_grid=(0.2,))
    assert not r2.feasible and not r2.time_proven  # no simulate function: nothing checked


def test_lower_thrust_gives_slower_bound(table3_result):
    env, res = table3_result
    r2 = tune_bounded(BoundedRequest(tf=1e4, thrust_max=30_000.0), env.boxes, env.m_max,
                      e1_grid=(0.2,))
    assert r2.feasible and r2.F_proven <= 30_000.0 and r2.T_proven > res.T_proven


def test_packed_states_cover_every_axis_corner():
    env = envelope_from_name("table3")
    r0, v0, _ = packed_states(env.boxes, env.m_max, n_mc=0)
    lo, hi = env.boxes[0][0], env.boxes[0][1]
    for i in range(3):
        pairs = {(a, b) for a, b in zip(r0[:, i], v0[:, i], strict=True)}
        for rr in (lo[i], hi[i]):
            for vv in (lo[3 + i], hi[3 + i]):
                assert (rr, vv) in pairs


LGW = [sys.executable, "-c", "from lgw.tuning.cli import main; main()"]


def _run(args: list[str]) -> subprocess.CompletedProcess:
    return subprocess.run(LGW + args, capture_output=True, text=True, timeout=300)


def test_cli_writes_a_loadable_file(tmp_path):
    out = tmp_path / "g.toml"
    run = _run(["tune", "mars", "--law", "bounded", "--tf", "200", "--thrust-max", "50000",
                "--envelope", "table3", "--out", str(out)])
    assert run.returncode == 0, run.stderr
    g = load_gains(out)
    bg = B.bounded_from_extra(g.extra)
    cert = g.extra["certificate"]
    assert cert["law"] == "bounded" and cert["time_proven"]
    assert cert["thrust_bound_proven"] <= 50_000.0
    assert np.all(bg.c1 > 0) and 0 < bg.e1 < 1


def test_cli_bad_law_is_exit_2(tmp_path):
    run = _run(["tune", "mars", "--law", "nope", "--tf", "60", "--thrust-max", "50000",
                "--out", str(tmp_path / "g.toml")])
    assert run.returncode == 2 and "error:" in run.stderr
    assert not (tmp_path / "g.toml").exists()
