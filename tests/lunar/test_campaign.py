"""Monte Carlo campaigns of seed 001 (``lgw.sim.lunar.campaign``, ``lgw simulate lunar
--cases``): draws per case, the failure per case in the kernel, streamed JSON."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.sim.lunar import campaign as CP
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.sim.lunar.reference import reference
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.commands import make_command
from lgw.tuning.system import get_system

simulate_cmd = make_command(get_system("lunar"), "simulate")


def test_a_case_draws_the_same_whatever_the_number_of_cases():
    tf = reference().tf
    a = CP.draw(5, 3, tf, RunOptions())
    b = CP.draw(2, 3, tf, RunOptions())
    for x, y in ((a.dh, b.dh), (a.dv, b.dv), (a.Q0, b.Q0), (a.ta, b.ta), (a.t_fail, b.t_fail)):
        np.testing.assert_array_equal(x[..., :2], y)
    env = CP.CAMPAIGN
    assert np.all((a.ta >= env.ta[0]) & (a.ta <= env.ta[1]))
    assert np.all((a.t_fail >= env.t_fail_fraction[0] * tf) & (a.t_fail <= env.t_fail_fraction[1]
                                                               * tf))
    assert np.all(np.abs(a.dv) <= np.asarray(env.dv)[:, None])
    np.testing.assert_allclose(np.linalg.norm(a.Q0, axis=0), 1.0)


def test_states_only_keeps_the_run_s_failure():
    d = CP.draw(4, 0, 200.0, RunOptions(t_fail=50.0, Ta=0.8), dispersion="states")
    assert np.all(d.t_fail == 50.0) and np.all(d.ta == 0.8)


def test_the_failure_of_each_case_is_flown():
    """Two cases with different failure times and levels in one kernel call: the failure the
    kernel measures (the thrust fraction crossing half-way to T_a) is each case's own."""
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.closed_loop import initial_state, make_context

    ref = reference()
    g = paper_gains()
    o = RunOptions(dt=1 / 160, t_end=30.0, thrust_pointing="ideal", failure="step")
    ctx = make_context(ref, [g] * 2, o)
    n = 2
    X0 = initial_state(ref, np.full(n, 10.0), np.zeros((3, n)),
                       np.tile([[1.0], [0], [0], [0]], (1, n)), np.zeros((3, n)), [g] * n)
    c = simulate(ctx, X0, record=False, failures=(np.array([0.6, 0.8]),
                                                  np.array([10.0, 20.0]))).cases
    np.testing.assert_allclose(c["t_failure"], [10.0, 20.0], atol=2 * o.dt)
    assert np.all(np.isfinite(c["time_saturated_orbit_after_failure"]))


def test_cli_campaign_streams_cases_with_statistics(tmp_path):
    r = CliRunner().invoke(simulate_cmd, ["--cases", "3", "--seed", "4", "--t-max", "12",
                                          "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert list(doc)[:3] == ["lgw_version", "command", "gains"]
    assert doc["command"] == "simulate lunar" and doc["cases_n"] == 3
    assert len(doc["cases"]) == 3 and {"t_fail_s", "ta", "outcome"} <= set(doc["cases"][0])
    st = doc["statistics"]["eh_final_m"]
    assert st["n"] + st["excluded"] == 3
    assert doc["convergence"]["refined_cases"] == 3


@pytest.mark.parametrize("args,flag", [(["--ta", "0.8"], "--ta"),
                                       (["--t-fail", "10"], "--t-fail"),
                                       (["--dispersion", "states"], "--dispersion"),
                                       (["--envelope", "certificate"], "--envelope")])
def test_campaign_options_refused_where_they_do_not_apply(args, flag):
    from tests.test_cli_conventions import assert_one_error, run_lgw

    extra = [] if flag in ("--dispersion", "--envelope") else ["--cases", "2"]
    r = run_lgw(["simulate", "lunar", *extra, *args])
    assert_one_error(r)
    assert flag in r.stderr
