"""``lgw verify mars`` and its checker (lgw.tuning.mars.verify): the campaign passes on the default
gains,
and a deliberately wrong (too small) bound injected into the same checker is reported."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import default_gains
from lgw.tuning.cli import cli
from lgw.tuning.mars.verify import CLAIMS, exit_code, run_campaign, sample_states


def test_campaign_default_gains_holds():
    res = run_campaign(default_gains(), 8, seed=1)
    assert [r.claim for r in res] == list(CLAIMS)
    assert exit_code(res) == 0
    for r in res:
        assert r.verdict == "holds", r
        assert r.n_nonfinite + r.n_unresolved < r.n_cases  # something was checked
        assert 0.0 <= r.ratio <= 1.0 and r.margin >= 0.0


@pytest.mark.parametrize("claim", ["T2-26", "s2-39-40"])
def test_injected_wrong_bound_is_reported(claim):
    """T2_exact (or T2_practical_exact) scaled by 0.01: the same checker must flag it."""
    res = run_campaign(default_gains(), 8, seed=1, scale={claim: 0.01})
    by = {r.claim: r for r in res}
    assert by[claim].verdict == "VIOLATED"
    assert by[claim].ratio > 1.0 and by[claim].margin < 0.0
    assert exit_code(res) == 1
    # the closest case is reproducible from its seed and index
    c = by[claim].closest
    r0, _, _ = sample_states(8, c["seed"])
    assert np.array_equal(r0[c["case"]], c["r0"])


def test_cli_verify_json_and_exit_codes():
    runner = CliRunner()
    ok = runner.invoke(cli, ["verify", "mars", "--examples", "8", "--seed", "1", "--json"])
    assert ok.exit_code == 0, ok.output
    out = json.loads(ok.output)
    assert out["exit_code"] == 0 and len(out["claims"]) == len(CLAIMS)
    bad = runner.invoke(cli, ["verify", "mars", "--examples", "8", "--seed", "1", "--json",
                              "--scale-bound", "T2-26=0.01"])
    assert bad.exit_code == 1
    assert any(c["verdict"] == "VIOLATED" for c in json.loads(bad.output)["claims"])
    table = runner.invoke(cli, ["verify", "mars", "--examples", "2", "--seed", "1"])
    assert table.exit_code == 0 and "closest case" in table.output


def test_verify_rejects_bad_input():
    with pytest.raises(ParameterError):
        run_campaign(default_gains(), 0, seed=0)
    with pytest.raises(ParameterError):
        run_campaign(default_gains(), 2, seed=0, scale={"nope": 1.0})
    with pytest.raises(ParameterError):
        run_campaign(default_gains().with_disturbance(None), 2, seed=0)
