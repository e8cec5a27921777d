"""Convergence measured, never assumed (lgw.sim.convergence): the comparison rule, the record and
its flags, the refinement of fixed-step outcomes, and every system's ``simulate`` carrying the
check (an unconverged number flagged in the output and in the JSON)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from lgw.sim.convergence import (
    ConvergenceRecord,
    Tol,
    check_indices,
    compare_cases,
    refine_outcomes,
    refinement,
)

from tests.test_cli_conventions import run_lgw


def test_tolerance_rule() -> None:
    t = Tol(rtol=0.01, atol=1e-3)
    assert t.ok(100.0, 100.9) and not t.ok(100.0, 101.2)
    assert t.ok(0.0, 9e-4) and not t.ok(0.0, 2e-3)
    assert t.ok(math.nan, math.nan)  # undefined in both runs: agree
    assert not t.ok(1.0, math.nan) and not t.ok(math.inf, 1e308)


def test_record_counts_outcome_changes_apart_and_names_the_worst_case() -> None:
    base = [{"outcome": "landed", "fuel": 200.0, "peak": [1.0, 2.0, 3.0]},
            {"outcome": "landed", "fuel": 210.0, "peak": [1.0, 2.0, 3.0]},
            {"outcome": "landed", "fuel": 220.0, "peak": [1.0, 2.0, None]},
            {"outcome": "crashed", "fuel": 50.0, "peak": [1.0, 2.0, 3.0]}]
    check = [{"outcome": "landed", "fuel": 200.5, "peak": [1.0, 2.0, 3.0]},
             {"outcome": "landed", "fuel": 230.0, "peak": [1.0, 2.0, 3.0]},
             {"outcome": "landed", "fuel": 220.0, "peak": [1.0, 2.0, 3.0]},
             {"outcome": "landed", "fuel": 50.0, "peak": [1.0, 2.0, 3.0]}]
    rec = compare_cases(base, check, {"fuel": Tol(), "peak": Tol()}, how="step halving",
                        base_label="RK4 dt = 0.05 s", check_label="RK4 dt = 0.025 s",
                        cases=[10, 20, 30, 40], total=100)
    assert not rec.converged
    assert rec.outcome_changed == [40] and rec.metrics["fuel"].checked == 3
    assert rec.metrics["fuel"].unconverged == [20] and rec.metrics["peak"].unconverged == [30]
    assert rec.metrics["fuel"].worst["case"] == 20
    assert rec.case_ok == {10: True, 20: False, 30: False, 40: False}
    flags = rec.flags("simulate x")
    assert len(flags) == 3 and all("UNCONVERGED" in f for f in flags)
    assert "fuel in 1 of 3 checked cases" in flags[1] and "worst case 20" in flags[1]
    d = rec.to_dict()
    json.dumps(d, allow_nan=False)
    assert d["converged"] is False and d["cases"] == 100 and d["cases_checked"] == 4
    good = compare_cases(base[:1], check[:1], {"fuel": Tol()}, how="h", base_label="a",
                         check_label="b")
    assert good.converged and good.flags() == [] and "converged" in good.notes()[0]


def test_refinement_settles_where_two_successive_steps_agree() -> None:
    """Case 0's outcome depends on the step until h <= 0.015 (as a step too large for the
    dynamics); case 1 flips at every step (never settles: kept at the finest step, flagged);
    case 2 does not change."""
    def outcome(case: int, h: float) -> str:
        if case == 0:
            return "landed" if h <= 0.015 else ("numerical" if h > 0.03 else "crashed")
        if case == 1:
            return "landed" if round(math.log2(0.05 / h)) % 2 else "crashed"
        return "landed"

    flown = []

    def fly(idx, h):
        flown.append((idx.tolist(), h))
        return np.array([outcome(int(i), h) for i in idx], dtype=object), None

    dt = 0.05
    codes = np.array([outcome(i, dt) for i in range(3)], dtype=object)
    half = np.array([outcome(i, dt / 2) for i in range(3)], dtype=object)
    ref = refine_outcomes(fly, codes, half, dt, halvings=5)
    assert ref.cases.tolist() == [0, 1]
    assert ref.codes.tolist() == ["landed", "landed"]
    assert ref.settled.tolist() == [True, False]
    assert ref.dt[0] == pytest.approx(dt / 8)  # crashed at dt/2, landed at dt/4 and dt/8
    assert ref.dt[1] == pytest.approx(dt / 32)  # the finest step
    assert all(2 not in idx for idx, _ in flown)  # an unchanged case is never re-flown
    rec = ConvergenceRecord("step halving", "a", "b", 3, 3, [0, 1], {}, {0: False, 1: False})
    rec.with_refinement({0: float(ref.dt[0]), 1: None}, None)
    assert rec.unresolved == [1] and not rec.converged
    assert "refined down to the finest step" in rec.flags()[0]


def test_refinement_and_indices_helpers() -> None:
    assert refinement("rk4", dt=0.05) == ("step halving", {"dt": 0.025})
    how, ch = refinement("dopri5", rtol=1e-5, atol=1e-6)
    assert how == "tolerance tightened" and ch == pytest.approx({"rtol": 1e-6, "atol": 1e-7})
    with pytest.raises(ValueError):
        refinement("rk4")
    assert check_indices(5, 10).tolist() == [0, 1, 2, 3, 4]
    idx = check_indices(10_000, 100)
    assert len(idx) == 100 and idx[0] == 0 and idx[-1] == 9999


def _doc(args: list[str]) -> dict:
    r = run_lgw(args + ["--json"])
    assert r.code == 0, r.stderr
    return json.loads(r.stdout)


def test_simulate_mars_flags_an_unconverged_run_and_not_a_converged_one() -> None:
    """Table I at the default step: every number converged.  Five Table III cases at a coarse
    dt = 0.2 s: the landing error (among others) moves by more than 1 % when dt is halved:
    flagged in the JSON record, per case, and as warnings on the terminal."""
    ok = _doc(["simulate", "mars"])
    conv = ok["summary"]["convergence"]
    assert conv["converged"] and conv["how"] == "step halving" and conv["cases_checked"] == 1
    assert ok["cases"][0]["converged"] is True
    args = ["simulate", "mars", "--dispersion", "table3", "--cases", "5", "--dt", "0.2"]
    bad = _doc(args)
    conv = bad["summary"]["convergence"]
    assert not conv["converged"] and conv["base"] == "RK4 dt = 0.2 s"
    assert conv["metrics"]["landing_error"]["unconverged"] > 0
    assert any(c["converged"] is False for c in bad["cases"])
    text = run_lgw(args)
    assert text.code == 0 and "warning: simulate mars: UNCONVERGED landing_error" in text.stdout


def test_simulate_mars_refines_a_step_dependent_outcome() -> None:
    """Table I at dt = 0.5 s: the outcome at 0.5 s differs from the one at 0.25 s; the case is
    re-flown until two successive steps agree (0.25 and 0.125 s), marked refined, and lands."""
    d = _doc(["simulate", "mars", "--dt", "0.5"])
    conv = d["summary"]["convergence"]
    assert conv["outcome_changed"] == 1 and conv["refined"]["settled"] == 1
    assert d["cases"][0]["refined_dt"] == 0.125 and d["cases"][0]["outcome"] == "landed"
    assert conv["refined"]["check"]["cases_checked"] == 1


@pytest.mark.parametrize("system", ["lunar", "eros"])
def test_simulate_carries_the_check_for_every_system(system: str) -> None:
    args = ["simulate", system, "--t-max", "5"]
    d = _doc(args)
    recs = [d["convergence"]] if system == "lunar" else [r["convergence"] for r in d["rows"]]
    for rec in recs:
        assert rec["how"] == "step halving" and rec["cases_checked"] == 1
    text = run_lgw(args)
    warned = "UNCONVERGED" in text.stdout
    assert warned == (not all(rec["converged"] for rec in recs))
    assert "convergence: 1 of 1 cases checked" in text.stdout


def test_simulate_mars_statistics_leave_out_what_cannot_be_summarised() -> None:
    """A campaign's statistics never include a non-finite or blown-up case: counted apart."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.campaign import summarize
    from lgw.theory.mars.gains import default_gains
    from lgw.theory.mars.parameters import M0, R0, V0

    r0 = np.array([R0, [1e-100, R0[1], R0[2]], [0.0, 0.0, 300.0]])
    v0 = np.array([V0, [0.0, V0[1], V0[2]], [0.0, 0.0, -200.0]])
    res = simulate_batch(r0, v0, [M0] * 3, default_gains())
    s = summarize(res)
    assert s["outcomes"]["landed"] == 1 and s["outcomes"]["command_blown_up"] == 1
    assert s["outcomes"]["crashed"] == 1
    assert s["fuel_kg"]["n"] == 1 and s["fuel_kg"]["excluded"] == 2
    assert s["impact_speed_mps"]["n"] == 1 and s["impact_speed_mps"]["min"] > 80
    for st in (s["fuel_kg"], s["landing_time_s"], s["impact_speed_mps"]):
        assert st["min"] <= st["mean"] <= st["max"]


@pytest.mark.parametrize("system", [
    "mars", pytest.param("lunar", marks=pytest.mark.slow),
    pytest.param("eros", marks=pytest.mark.slow)])
def test_rk4_and_dopri5_agree_on_adversarial_states(system: str) -> None:
    """benchmarks/adversarial_agreement.py on 2000 adversarial states (seed 0): after the RK4
    outcomes are refined, RK4 and dopri5 agree on the outcome class of at least 99 % of the
    cases; refinement never makes it worse."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "benchmarks" / "adversarial_agreement.py"
    spec = importlib.util.spec_from_file_location("adversarial_agreement", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    r = mod.agreement(system, 2000, 0, None)
    assert r["after"] >= 0.99 * r["n"], r
    assert r["after"] >= r["before"] - r["refined"], r
