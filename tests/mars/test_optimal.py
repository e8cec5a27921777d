"""Fuel-optimal SOCP (lgw.sim.mars.optimal): cross-checked by independent routes, not by its own
output.

* the SOCP's final state against an open-loop replay of its force profile in lgw.sim.mars.plant;
* the SOCP's fuel against the mass lost in the replay and against the rocket equation summed
  over the force profile;
* the relaxation ||u|| <= sigma is tight (lossless convexification, checked a posteriori);
* the thrust bounds hold on the force actually flown;
* tf below the shortest feasible time is refused (infeasible), tf at it is not.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from lgw.sim.mars.optimal import OptimalSolution, min_time, replay, solve_fuel_optimal
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import G_EARTH, ISP, M0, M_DRY, R0, THRUST_MAX_AXIS, V0


@pytest.fixture(scope="module")
def sol() -> OptimalSolution:
    return solve_fuel_optimal(R0, V0, M0, 30.0)


@pytest.fixture(scope="module")
def rep_none(sol: OptimalSolution) -> dict:
    return replay(sol)


def test_default_solution_is_optimal_and_tight(sol: OptimalSolution) -> None:
    assert sol.status == "optimal"
    assert sol.n == 80 and sol.t.shape == (81,) and sol.F.shape == (80, 3)
    assert sol.tightness < 1e-6
    assert M_DRY < sol.m[-1] < M0
    assert 100.0 < sol.fuel < 300.0
    np.testing.assert_allclose(sol.r[-1], 0.0, atol=1e-6)
    np.testing.assert_allclose(sol.v[-1], 0.0, atol=1e-6)
    assert sol.r[:, 2].min() >= -1e-6


def test_axis_limit_holds_on_the_flown_force(sol: OptimalSolution) -> None:
    assert sol.peak_thrust.max() <= THRUST_MAX_AXIS * (1 + 1e-6)
    # and the limit is active somewhere (bang-bang structure of a fuel-optimal descent)
    assert sol.peak_thrust.max() > 0.99 * THRUST_MAX_AXIS


def test_fuel_matches_rocket_equation_over_the_force_profile(sol: OptimalSolution) -> None:
    # m' = -||F|| / (Isp g_e), with ||F|| constant on each step: an independent sum.
    burnt = np.linalg.norm(sol.F, axis=1).sum() * sol.dt / (ISP * G_EARTH)
    assert burnt == pytest.approx(sol.fuel, rel=1e-6)


def test_replay_reaches_target_and_burns_the_predicted_fuel(rep_none: dict,
                                                            sol: OptimalSolution) -> None:
    assert rep_none["outcome"] == "landed"
    assert rep_none["node_error_r"] < 1e-3  # m
    assert rep_none["node_error_v"] < 1e-3  # m/s
    assert rep_none["fuel_used"] == pytest.approx(sol.fuel, abs=1e-3)
    assert rep_none["min_altitude_powered"] > -1e-3


def test_replay_intermediate_nodes_match(rep_none: dict, sol: OptimalSolution) -> None:
    traj = rep_none["trajectory"]
    idx = np.searchsorted(traj["t"], sol.t[40])
    assert traj["t"][idx] == pytest.approx(sol.t[40])
    np.testing.assert_allclose(traj["r"][idx], sol.r[40], atol=1e-3)
    np.testing.assert_allclose(traj["m"][idx], sol.m[40], atol=1e-4)


def test_replay_with_sin_disturbance_does_not_land(sol: OptimalSolution) -> None:
    rep = replay(sol, "sin", amplitude=1.0)
    # a_p,i = sin t integrates to a drift t - sin t >= 0 upward: ~31 m high at tf, then the
    # engine is off and the lander falls (seed 000 Fig. 3(c): "the collision occurs").
    assert rep["outcome"] == "crashed" and rep["phase"] == "coast"
    assert rep["r_tf"][2] == pytest.approx(30.0 - np.sin(30.0), rel=0.02)
    assert rep["touchdown_speed"] > 5.0


def test_min_time_brackets_feasibility() -> None:
    res = min_time(R0, V0, M0, n=40, tol=0.05)
    lo, hi = res.bracket
    assert hi - lo <= 0.05 and res.tf_min == hi
    assert res.solution.feasible
    assert solve_fuel_optimal(R0, V0, M0, lo, n=40).status == "infeasible"
    assert solve_fuel_optimal(R0, V0, M0, res.tf_min - 0.5, n=40).status == "infeasible"
    # at minimum time the limit is saturated (to within the log-mean/initial mass ratio of a
    # step, the limit being imposed at the step's heaviest mass) and more fuel is burnt
    assert res.solution.peak_thrust.max() > 0.99 * THRUST_MAX_AXIS
    assert res.solution.fuel > solve_fuel_optimal(R0, V0, M0, 30.0, n=40).fuel


def test_min_time_from_a_too_long_start() -> None:
    # tf = 200 s is infeasible the other way (the fuel runs out hovering); the scan must find
    # the feasible interval below it and land on the same tf_min
    res = min_time(R0, V0, M0, n=30, tol=0.05, tf_hi=200.0)
    assert res.history[0] == (200.0, "infeasible")
    ref = min_time(R0, V0, M0, n=30, tol=0.05)
    assert abs(res.tf_min - ref.tf_min) <= 0.05


def test_norm_limit_and_lossless_lower_bound() -> None:
    s = solve_fuel_optimal(R0, V0, M0, 30.0, limit="norm", thrust_max=60_000.0,
                           thrust_min=15_000.0, n=40)
    assert s.status == "optimal"
    assert s.tightness < 1e-6  # lossless: ||u|| = sigma along the solution
    norms = np.linalg.norm(s.F, axis=1)
    assert norms.max() <= 60_000.0 * (1 + 1e-6)
    assert norms.min() >= 15_000.0 * (1 - 1e-6)
    free = solve_fuel_optimal(R0, V0, M0, 30.0, limit="norm", thrust_max=60_000.0, n=40)
    assert s.fuel >= free.fuel - 1e-6  # a lower bound can only cost fuel


def test_discretisation_converges() -> None:
    f40 = solve_fuel_optimal(R0, V0, M0, 30.0, n=40).fuel
    f160 = solve_fuel_optimal(R0, V0, M0, 30.0, n=160).fuel
    assert f40 >= f160 - 1e-6 and f40 - f160 < 0.1


@pytest.mark.parametrize("kw", [
    {"tf": -1.0}, {"tf": float("nan")}, {"n": 5}, {"n": 80.5}, {"limit": "box"},
    {"thrust_max": 0.0}, {"thrust_min": 90_000.0}, {"thrust_min": -1.0}, {"isp": 0.0},
    {"m0": 1000.0}, {"r0": [1.0, 2.0]}, {"r0": [0.0, 0.0, -5.0]},
])
def test_bad_input_raises_parameter_error(kw: dict) -> None:
    args = {"r0": R0, "v0": V0, "m0": M0, "tf": 30.0} | kw
    name = next(iter(kw))
    with pytest.raises(ParameterError) as ei:
        solve_fuel_optimal(args.pop("r0"), args.pop("v0"), args.pop("m0"), args.pop("tf"),
                           **args)
    assert ei.value.name == name


def test_replay_bad_disturbance(sol: OptimalSolution) -> None:
    with pytest.raises(ParameterError):
        replay(sol, "gust")


def _lgw(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()", *args],
                          capture_output=True, text=True, timeout=120)


def test_cli_infeasible_tf_exits_2_and_names_tf() -> None:
    p = _lgw("optimal", "mars", "--tf", "10", "--n", "30", "--no-replay")
    assert p.returncode == 2
    assert "--tf" in p.stderr and "must be >=" in p.stderr


def test_cli_json(tmp_path) -> None:
    import json

    p = _lgw("optimal", "mars", "--n", "30", "--json", "--out", str(tmp_path))
    assert p.returncode == 0, p.stderr
    rep = json.loads(p.stdout)
    assert rep["solution"]["status"] == "optimal"
    assert rep["replays"][0]["outcome"] == "landed"
    assert (tmp_path / "thrust.csv").read_text().count("\n") == 31


def test_compare_optimal_rows_and_figure(tmp_path) -> None:
    from lgw.tuning.mars.compare import _fmt, _optimal_rows
    from lgw.tuning.mars.compare import figure as _figure

    rows, trajs = _optimal_rows([("none", 0.0), ("sin", 1.0)], "none", 30, THRUST_MAX_AXIS)
    assert [r["disturbance"] for r in rows] == ["none", "sin"]
    assert rows[0]["landed"] and rows[0]["pos_error"] < 1e-3
    assert not rows[1]["landed"] and rows[1]["outcome"].startswith("crashed")
    assert rows[0]["fuel"] < rows[0]["paper_fuel"]  # the optimum is below the paper's GPOPS
    _figure(trajs, THRUST_MAX_AXIS, tmp_path / "c.png")
    assert (tmp_path / "c.png").stat().st_size > 10_000
    assert _fmt(float("nan"), "9.2f") == " " * 8 + "-"
