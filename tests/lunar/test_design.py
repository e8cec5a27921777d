"""``lgw tune lunar``'s design (``lgw.tuning.lunar.design``): the exact redundancy, the closed
form of the failure offset against the simulation, the bandwidth rule, the certificate's
validation and checks, and the shipped tuned file against a fresh campaign.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from lgw.sim.lunar import parameters as SP
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.theory.errors import ParameterError
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import from_dict, load, paper_gains
from lgw.tuning.lunar import design as D

SHIPPED = Path(D.__file__).parent / "data" / "tuned_section5.toml"


def test_redundancy_is_exact_and_the_paper_is_short():
    r = D.redundancy(P.T_A, P.T_MAX)
    assert not r["holds"] and r["margin_N"] == pytest.approx(-200.0, abs=1e-9)
    s = D.redundancy(P.T_A)
    assert s["sized"] and s["holds"] and s["thrust_max_N"] == 36000.0  # 24000/0.7 x 1.05
    assert s["required_N"] == pytest.approx(24000 / 0.7)


def test_failure_offset_matches_the_simulated_final_error():
    """The closed form of step 2 against the ideal-pointing Section 5 run with enough thrust
    (no saturation after the failure): the final velocity error is the filter's offset."""
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.scenario import case_numbers, section5_case

    g = paper_gains()
    ctx, X0 = section5_case(g, RunOptions(dt=SP.DT_CAMPAIGN, thrust_pointing="ideal",
                                          thrust_max=36000.0))
    n = case_numbers(simulate(ctx, X0, record=False).cases, ctx)
    est = D.failure_offset(np.diag(g.orbit.F2), float(g.orbit.K1[2, 2]), P.T_A)
    assert n["orbit_saturated_after_failure_s"] == 0.0
    assert n["ev_final_norm_m_s"] == pytest.approx(est["ev_m_s"], rel=0.05)


def _pt(wn, score, score_fine=None, outcome="completed", sat_after=0.0):
    return D.SweepPoint(wn, 0, 0, 0, 0, outcome, outcome, 0, sat_after, score,
                        score if score_fine is None else score_fine, True)


def test_bandwidth_rule_picks_the_centre_of_the_widest_robust_band():
    pts = (_pt(1, math.inf, outcome="crashed"), _pt(2, 0.5), _pt(4, 3.0),
           _pt(8, 0.4), _pt(16, 0.6), _pt(32, 0.9), _pt(64, 0.5, 1.5))
    bw = D.choose_bandwidth(pts)
    assert bw.band == (8, 32) and bw.wn == 16  # 64 fails at dt/2, 4 misses the target
    # no point meets the target: the band is where the score is within 2x the best
    pts = (_pt(1, 5.0), _pt(2, 1.4), _pt(4, 1.5), _pt(8, 9.0), _pt(16, 1.3))
    bw = D.choose_bandwidth(pts)
    assert bw.band == (2, 4) and bw.best_score == 1.3


def test_bandwidth_rule_refuses_a_point_saturated_after_the_failure():
    """Small final errors do not make a point robust when the orbit thrust rides its limit
    after the failure (the premise of seed 001's Section 5)."""
    pts = (_pt(8, 0.3, sat_after=84.0), _pt(12, 0.3, sat_after=2.0), _pt(16, 0.3, sat_after=0.5),
           _pt(25, 0.6, sat_after=56.0), _pt(30, 0.6), _pt(35, 0.6))
    bw = D.choose_bandwidth(pts)
    assert bw.band == (30, 35) and bw.wn == 30 and bw.robust == (30, 35)
    # the table a reader sees says why: the saturation after the failure, and the verdict
    rows = bw.rows(str)
    assert [r[bw.COLUMNS.index("sat after failure s")] for r in rows] == \
        ["84.0", "2.0", "0.5", "56.0", "0.0", "0.0"]
    assert [r[bw.COLUMNS.index("robust")] for r in rows] == ["no"] * 4 + ["yes"] * 2


@pytest.mark.slow
def test_the_default_command_filter_is_the_rule_s_choice_for_the_paper():
    bw = D.select_bandwidth(paper_gains(), RunOptions(dt=SP.DT_CAMPAIGN))
    assert bw.wn == SP.CMD_WN, bw.to_dict()


def _cert_gains(**changes):
    g = load(SHIPPED)
    cert = {**g.extra["certificate"], **changes}
    d = g.to_dict()
    d["certificate"] = cert
    return from_dict(d)


@pytest.mark.parametrize("key,value", [("eh_max_m", "10"), ("ev_max_m_s", [2.0]),
                                       ("thrust_max_N", float("nan")), ("cmd_wn_rad_s", -1.0),
                                       ("envelope_ta", ["a"]), ("envelope_dv_half_width_m_s",
                                                                [1.0, 2.0])])
def test_certificate_values_are_validated_by_name(key, value):
    with pytest.raises(ParameterError) as e:
        D.certificate_request(_cert_gains(**{key: value}))
    assert key in str(e.value)


def test_shipped_design_is_a_tuned_file_every_loader_reads():
    g = load(SHIPPED)
    assert {"command_filter", "vehicle", "certificate"} <= set(g.extra)
    cert = g.extra["certificate"]
    assert cert["thrust_max_N"] == g.extra["vehicle"]["thrust_max"]
    assert cert["cmd_wn_rad_s"] == g.extra["command_filter"]["wn"]
    # "proven" only where the evidence is a proof; the simulated promises say sampled
    for k, v in cert.items():
        if k.endswith("_evidence") and k.startswith(("tracking", "no_saturation", "cmd_wn")):
            assert v.startswith("sampled") and "proven" not in v


def test_shipped_design_against_a_fresh_campaign():
    """The tuned set cross-checked by a fresh campaign (a seed the tuner never used): every
    promise of its certificate holds, the proven ones recomputed."""
    checks = D.check_certificate(load(SHIPPED), cases=4, seed=98765)
    bad = [c.to_dict() for c in checks if not c.holds]
    assert not bad, bad
    assert {c.evidence for c in checks} == {"proven", "sampled"}


def test_a_false_promise_is_caught_with_its_observed_value():
    g = _cert_gains(ev_max_m_s=0.01)  # promise far below what the design achieves
    checks = D.check_certificate(g, cases=2, seed=5)
    c = next(x for x in checks if x.promise.startswith("|e_v"))
    assert not c.holds and c.observed > c.bound == 0.01 and c.margin < 0
    g = _cert_gains(thrust_max_N=30000.0)  # below T_d / T_a: the proven check fails exactly
    c = D.check_certificate(g, cases=1, seed=5)[0]
    assert not c.holds and c.evidence == "proven" and c.margin < 0


def test_tune_below_the_redundancy_is_infeasible_and_writes_nothing(tmp_path):
    from tests.test_cli_conventions import run_lgw

    out = tmp_path / "g.toml"
    r = run_lgw(["tune", "lunar", "--thrust-max", "34000", "--out", str(out)])
    assert r.code == 3 and not out.exists()
    assert "34285.7" in r.stderr and "nothing written" in r.stderr


def test_tune_text_names_a_missing_band():
    """The tuner's text output with no robust band on the sweep (the certificate then carries
    an empty band and says which wn it flew): the band's line says so instead of failing."""
    from lgw.tuning.lunar.cmd_tune import _band
    from lgw.tuning.tables import fmt

    cert = {"cmd_band_rad_s": [], "cmd_wn_evidence": "sampled: 3 bandwidths, none robust"}
    assert _band(cert, fmt) == "no robust band: sampled: 3 bandwidths, none robust"
    assert _band({**cert, "cmd_band_rad_s": [25.0, 35.0]}, fmt) == "robust band 25-35"
