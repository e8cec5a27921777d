"""``lgw verify mars`` and its checker (lgw.tuning.mars.verify): verdicts need evidence (holds /
violated / inconclusive, exit 0 / 1 / 4), a violation comes with a shrunk witness and a
reproduction, and a deliberately wrong bound is reported."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.theory.errors import ParameterError
from lgw.theory.falsify import Budget
from lgw.theory.mars.gains import default_gains, gains_from_dict
from lgw.tuning.cli import cli
from lgw.tuning.mars.verify import (
    CLAIMS,
    VerifyOptions,
    claim_problems,
    exit_code,
    run_verify,
    search_claim,
)

FAST = dict(examples=6, min_cases=2)
SMALL = Budget(popsize=6, maxiter=6, local_evals=20, seed=0)
# A gain set for which the paper's max{T1*, T2*} is not a landing-time bound (the engine's
# worst point of tests/mars/test_properties.py::HARD_LANDING): T1* = 86.3 s, T2* = 28.4 s,
# and a landing from s2(0) = 1e9 m/s takes 91.9 s.
BALANCED = {"gains": {"beta1": 0.2, "beta2": 0.01, "alpha1": 0.5, "alpha2": 0.02, "q1": 0.9,
                      "q2": 1.5, "g1": 0.7, "g2": 1.5},
            "disturbance": {"a_max": 20.0, "theta1": 0.2, "theta2": 0.1}}


@pytest.fixture(scope="module")
def default_run():
    return run_verify(default_gains(), VerifyOptions(**FAST))


def test_default_gains_hold_with_evidence(default_run):
    res = default_run
    assert [r.claim for r in res] == list(CLAIMS)
    assert exit_code(res) == 0
    for r in res:
        assert r.verdict == "holds", r
        assert r.n_checked >= r.min_cases  # no holds without checked cases
        assert r.n_checked + r.n_excluded == r.n_cases  # every case accounted for
        assert r.search and all(s["status"] == "checked" for s in r.search)
        assert r.ratio <= 1.0


def test_cases_rk4_cannot_carry_go_to_dopri5(default_run):
    """The undisturbed claims re-fly RK4's failures on the adaptive path instead of
    skipping them (their states: tiny |r| with large |v|)."""
    by = {r.claim: r for r in default_run}
    assert sum(by[c].n_adaptive for c in ("reaching-16", "T2-26", "landing-T2+T1")) > 0


def test_exclusions_make_a_claim_inconclusive_exit_4():
    """--min-cases above what the run can check: inconclusive, exit 4, and why."""
    res = run_verify(default_gains(), VerifyOptions(examples=2, min_cases=1000))
    assert exit_code(res) == 4
    for r in res:
        assert r.verdict == "inconclusive" and "min-cases" in r.why


def test_landing_max_in_place_of_the_sum_is_violated(monkeypatch):
    """The paper's max{T1*, T2*} as the landing bound: found by the search, shrunk, re-checked
    by LSODA, exit 1 with a reproduction (bounds patched for this test only)."""
    import lgw.theory.mars.bounds as B
    orig = B.axis_bounds

    def paper_max(g):
        out = orig(g)
        for ax in out.values():
            ax["landing_time_bound"] = max(ax["T1_exact"], ax["T2_exact"])
        return out
    monkeypatch.setattr(B, "axis_bounds", paper_max)
    g = gains_from_dict(BALANCED)
    res = run_verify(g, VerifyOptions(simulate=False, min_cases=1))
    by = {r.claim: r for r in res}
    r = by["landing-T2+T1"]
    assert r.verdict == "violated" and exit_code(res) == 1
    assert r.witness["confirmed"] and r.witness["rechecked_margin"] < 0
    assert "lgw simulate mars --gains witness_gains.toml --initial-states" in r.reproduction


@pytest.mark.parametrize("claim", ["reaching-16", "T2-26"])
def test_bound_three_percent_too_small_is_found_by_search(claim):
    """The bounds that are suprema at every gain set (T1*, T2*, approached as s0 -> inf):
    3 % less is violated.  (T2* + T1* is the supremum over all gains, not at every gain set:
    for BALANCED the worst landing is 0.83 of it, so 3 % less is still a true bound there;
    tests/mars/test_properties.py checks it over the full box.)"""
    g = gains_from_dict(BALANCED)
    found = search_claim(claim, g, SMALL, scale=0.97)
    assert any(s.status == "refuted" for _, s in found), [s.best_margin for _, s in found]
    for _, s in found:
        if s.status == "refuted":
            assert s.witness.margin < 0 and s.witness.rechecked_margin < 0


def test_injected_wrong_bound_is_reported_by_simulation():
    """T2_exact scaled by 0.01: the simulated cases flag it (Hypothesis shrinks the case)."""
    res = run_verify(default_gains(), VerifyOptions(examples=4, min_cases=1, search=False,
                                                    scale={"T2-26": 0.01}))
    r = {x.claim: x for x in res}["T2-26"]
    assert r.verdict == "violated" and r.witness["ratio"] > 1.0
    assert "--initial-states witness_states.csv" in r.reproduction
    assert exit_code(res) == 1


def test_problems_fix_the_gains():
    g = default_gains()
    for c in CLAIMS:
        for pr in claim_problems(c, g, 0):
            assert not {d.name for d in pr.dims} & {"beta1", "alpha1", "q1", "a_max"}
            assert pr.fixed["beta1"] == pytest.approx(float(np.asarray(g.beta1)[0]))


def test_cli_verify_json_exit_codes_and_reproduction():
    runner = CliRunner()
    ok = runner.invoke(cli, ["verify", "mars", "--examples", "6", "--min-cases", "2",
                             "--json"])
    assert ok.exit_code == 0, ok.output
    out = json.loads(ok.output)
    assert out["exit_code"] == 0 and len(out["claims"]) == len(CLAIMS)
    assert all(c["n_checked"] >= 2 and c["verdict"] == "holds" for c in out["claims"])
    bad = runner.invoke(cli, ["verify", "mars", "--examples", "4", "--min-cases", "1",
                              "--scale-bound", "reaching-16=0.9"])
    assert bad.exit_code == 1, bad.output
    assert "violated" in bad.output and "lgw simulate mars --gains" in bad.output
    few = runner.invoke(cli, ["verify", "mars", "--examples", "2", "--min-cases", "500"])
    assert few.exit_code == 4 and "inconclusive" in few.output


def test_verify_rejects_bad_input():
    with pytest.raises(ParameterError):
        VerifyOptions(profile="nope")
    with pytest.raises(ParameterError):
        VerifyOptions(min_cases=0)
    with pytest.raises(ParameterError):
        VerifyOptions(scale={"nope": 1.0})
    with pytest.raises(ParameterError):
        run_verify(default_gains().with_disturbance(None), VerifyOptions(**FAST))


def test_plot_observed_against_bound_is_written(default_run, tmp_path):
    """--plot's figure from the same records: one point per checked (case, axis), written
    atomically (only the PNG lands in the folder)."""
    from lgw.tuning.figures import write_verify_plot
    from lgw.tuning.mars.verify import plot_panels

    panels = plot_panels(default_run)
    for r, p in zip(default_run, panels, strict=True):
        assert len(p["bound"]) == len(p["observed"]) == 3 * r.n_checked
        assert not p["violated"].any()
    path = write_verify_plot(tmp_path / "fig", "mars", panels, "test")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 20_000
    assert [p.name for p in (tmp_path / "fig").iterdir()] == ["verify_mars.png"]


@pytest.mark.parametrize("sub", ["", "sub"])
def test_bad_plot_path_is_exit_2_before_any_work(tmp_path, sub):
    from lgw.tuning.cli import main

    f = tmp_path / "a_file"
    f.write_text("x")
    with pytest.raises(SystemExit) as e:
        main(["verify", "mars", "--plot", str(f / sub if sub else f)])
    assert e.value.code == 2
    assert [p.name for p in tmp_path.iterdir()] == ["a_file"] and f.read_text() == "x"
