"""``lgw verify lunar`` (issue 19): per claim checked and excluded counts, never ``holds`` on
fewer than --min-cases checked cases, exit 1 on a violation (with a witness re-checked at half
the step), exit 4 when inconclusive, strict JSON."""

import json

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.tuning.cli import cli
from lgw.tuning.lunar import verify as V


def _run(*args):
    res = CliRunner().invoke(cli, ["verify", "lunar", "--t-end", "2", *args, "--json"])
    return res.exit_code, json.loads(res.output) if res.output.startswith("{") else res.output


def test_holds_on_enough_checked_cases():
    code, d = _run("--cases", "32")
    assert code == 0, d
    assert [c["claim"] for c in d["claims"]] == list(V.CLAIMS)
    for c in d["claims"]:
        assert c["result"] == "holds"
        assert c["checked"] + c["excluded"] == 32 and c["checked"] >= d["min_cases"]
        assert c["worst_margin"] >= 0 and c["violations"] == 0


def test_too_few_cases_is_inconclusive_exit_4():
    code, d = _run("--cases", "8")
    assert code == 4
    assert {c["result"] for c in d["claims"]} == {"inconclusive"}


def test_shrunk_bound_is_violated_with_a_rechecked_witness_exit_1():
    code, d = _run("--cases", "32", "--scale", "(19a)=0.5")
    assert code == 1
    c = {c["claim"]: c for c in d["claims"]}
    assert c["(19a)"]["result"] == "violated" and c["(19a)"]["violations"] > 0
    w = c["(19a)"]["witness"]
    assert w["margin"] < 0 and w["rechecked_margin"] < 0 and "dt = 0.01" in w["recheck_method"]
    assert c["(19a)"]["worst_margin"] == pytest.approx(w["margin"])
    assert all(c[k]["result"] == "holds" for k in c if k != "(19a)")


def test_excluded_cases_push_a_claim_to_inconclusive(monkeypatch):
    # a claim whose margin is undefined (NaN) on half the cases: those are excluded and
    # counted, and 16 checked < 30 makes the claim inconclusive (never holds)
    real = V.margins

    def margins(t, o, g, case, x1_0, dt, i=0):
        m = real(t, o, g, case, x1_0, dt, i)
        if i % 2:
            m["(21a)"] = float("nan")
        return m

    monkeypatch.setattr(V, "margins", margins)
    rows = V.verify(32, 0, 2.0)
    r = {x["claim"]: x for x in rows}["(21a)"]
    assert (r["checked"], r["excluded"]) == (16, 16)
    assert r["excluded_reasons"] == {"non-finite run or bound (NaN margin)": 16}
    assert r["result"] == "inconclusive" and V.exit_code(rows) == 4
    # with --min-cases 16 the same evidence suffices
    assert {x["claim"]: x for x in V.verify(32, 0, 2.0, min_cases=16)}["(21a)"]["result"] \
        == "holds"


def test_claim_result_never_holds_without_evidence():
    assert V.claim_result(None, 0, 1) == "inconclusive"
    assert V._exclusion("V2_step_outside_band", np.inf).startswith("no step outside")
    assert V._exclusion("(18a)", -np.inf) is not None and V._exclusion("(18a)", 0.1) is None


@pytest.mark.parametrize("args", [["--min-cases", "0"], ["--scale", "nope=2"],
                                  ["--scale", "(19a)=-1"], ["--dt", "0"]])
def test_bad_option_is_one_error_line_exit_2(args, capsys):
    from lgw.tuning.cli import main

    with pytest.raises(SystemExit) as e:
        main(["verify", "lunar", *args])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and err.count("\n") == 1
