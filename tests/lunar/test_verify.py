"""``lgw verify lunar`` (lgw.tuning.lunar.verify on the shared lgw.tuning.verifying): per claim
informative, excluded and total cases, never ``holds`` on cases that cannot violate a claim, a
provoked violation whose printed reproduction reproduces it (one public ``lgw`` command, no
private function), strict JSON with the shared head, bad input exit 2 with nothing written."""

import json
import shlex

import numpy as np
import pytest
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar import verify as V
from lgw.tuning.verifying import Context

from tests.test_cli_conventions import assert_one_error, run_lgw

FAST = ["--t-max", "2", "--examples", "3", "--min-cases", "5"]


def _json(args):
    r = run_lgw(["verify", "lunar", *args, "--json"])
    assert r.exception is None, r.exception
    return r.code, json.loads(r.stdout)


def test_holds_on_informative_cases_with_the_shared_document():
    code, d = _json(FAST)
    assert code == 0, d
    assert list(d)[:3] == ["lgw_version", "command", "gains"] and d["command"] == "verify lunar"
    assert d["settings"] == {"t_max": 2.0, "dt": 0.02, "thrust_max": 2000.0, "D": 0.5,
                             "cert_cases": 30, "cert_seed": 12345}
    # every claim but the paper's (19b) as printed (false for every gain set: --claim asks)
    assert [c["claim"] for c in d["claims"]] == [c for c in V.CLAIMS if c != V.PRINTED]
    for c in d["claims"]:
        n = c["cases"]
        if c["claim"].startswith("certificate-"):  # the paper's gains promise nothing
            assert c["verdict"] == "not-applicable" and n["total"] == 0, c
            continue
        assert c["verdict"] == "holds" and n["informative"] >= 5, c
        assert n["informative"] + n["excluded"] == n["total"] and c["margin"] >= 0
    assert d["margin"].startswith("(bound - observed) / bound")


def test_saturation_that_never_acts_leaves_18_uninformative():
    """Without saturation (thrust-max 1e9 N) du = 0 and lambda stays 0: (18a)/(18b) would be
    0 <= 0 on every case, so no case counts and the claims are inconclusive, not holds."""
    code, d = _json([*FAST[:2], "--examples", "2", "--min-cases", "1", "--thrust-max", "1e9",
                     "--claim", "(18a)", "--claim", "(19a)"])
    assert code == 4
    c = {c["claim"]: c for c in d["claims"]}
    assert c["(18a)"]["verdict"] == "inconclusive" and c["(18a)"]["cases"]["informative"] == 0
    assert any("saturation never acted" in k for k in c["(18a)"]["cases"]["excluded_reasons"])
    assert c["(19a)"]["verdict"] == "holds"


def test_provoked_violation_prints_a_reproduction_that_reproduces_it():
    r = run_lgw(["verify", "lunar", "--t-max", "1", "--examples", "3", "--claim", "(19a)",
                 "--scale", "(19a)=0.01"])
    assert r.code == 1, r.stdout
    assert "_fly_cases" not in r.stdout and "python" not in r.stdout
    repro = next(ln.split("reproduce: ", 1)[1] for ln in r.stdout.splitlines()
                 if "reproduce: " in ln)
    args = shlex.split(repro)
    assert args[:3] == ["lgw", "verify", "lunar"] and "--t-max" in args
    observed = next(ln for ln in r.stdout.splitlines() if ln.strip().startswith("observed:"))
    again = run_lgw(args[1:])
    assert again.code == 1 and observed in again.stdout, again.stdout


def test_judge_counts_a_nan_as_excluded_never_as_a_check(monkeypatch):
    real = V.observations

    def nan21(t, o, g, case, x1_0, dt, i=0):
        out = real(t, o, g, case, x1_0, dt, i)
        if i % 2:
            out["(21a)"] = (out["(21a)"][0], float("nan"), True)
        return out

    monkeypatch.setattr(V, "observations", nan21)
    from lgw.tuning.verifying import Tally

    ctx = Context(paper_gains(), {"t_max": 1.0, "dt": 0.02, "thrust_max": 2000.0, "D": 0.5},
                  {}, 0)
    X = np.array([[10.0, 1.0, 0.0, 0.0], [20.0, 0.0, 1.0, 0.0], [5.0, 0, 0, 1.0]])
    j = V.judge(ctx, "orbit", X)["(21a)"]
    t = Tally(V.CLAIMS["(21a)"], V.AXES)
    t.add(j, 1.0)
    assert (t.total, t.informative) == (3, 2) and len(t.excluded) == 1


@pytest.mark.parametrize("args", [["--min-cases", "0"], ["--scale", "nope=2"],
                                  ["--scale", "(19a)=-1"], ["--dt", "0"],
                                  ["--profile", "fast"], ["--t-max", "0"]])
def test_bad_option_is_one_error_line_exit_2(args):
    assert_one_error(run_lgw(["verify", "lunar", *args]))


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_a_database_makes_the_run_random_so_hypothesis_uses_it(system, tmp_path):
    """Hypothesis ignores the example database in a seeded run (hypothesis.seed sets
    database=None), so --database gives a random run: the document says seed null."""
    from lgw.tuning.system import get_system

    mod = get_system(system).verb("verify").load()
    assert mod.Options(seed=3).run_seed == 3
    assert mod.Options(database=tmp_path).run_seed is None


SHIPPED = "tuning/lunar/data/tuned_section5.toml"
PROVEN = ["--claim", "certificate-redundancy", "--claim", "certificate-hypotheses",
          "--claim", "certificate-l2-lambda1", "--claim", "certificate-l2-lambda2"]


def test_tuned_file_certificate_is_rederived_and_an_edited_promise_fails_by_name(
        tmp_path, monkeypatch):
    """``lgw verify lunar --gains FILE`` re-derives the proven promises of a tuned file's
    [certificate] (no campaign flown for them); the same file with lambda1_gain_18a edited
    below the linfnorm of the loop is violated, with the promise's name and observed value."""
    from pathlib import Path

    from lgw.tuning.lunar import design

    def no_flight(*a, **k):
        raise AssertionError("a campaign was flown for proven promises only")

    monkeypatch.setattr(design, "acceptance", no_flight)
    code, d = _json(["--gains", SHIPPED, *FAST, *PROVEN])
    assert code == 0, d
    c = {c["claim"]: c for c in d["claims"]}
    assert set(c) == {p for p in PROVEN if p != "--claim"}
    assert all(x["verdict"] == "holds" and x["evidence"] == "proven" for x in c.values()), c
    assert "--cert-cases" not in json.dumps(d)  # nothing was flown for a proof
    bad = tmp_path / "broken.toml"
    bad.write_text(Path(SHIPPED).read_text().replace("lambda1_gain_18a = 2.23606797749979",
                                                     "lambda1_gain_18a = 0.5"))
    r = run_lgw(["verify", "lunar", "--gains", str(bad), *FAST, *PROVEN])
    assert r.code == 1, r.stdout
    line = next(ln for ln in r.stdout.splitlines() if ln.startswith("certificate-l2-lambda1"))
    assert "observed 0.745418 > bound 0.5" in line, line


def test_printed_19b_row_uses_the_printed_constant():
    """The row "(19b) printed" is the paper's statement as printed (z_l2_bounds_printed:
    V2(0) = |z1(0)|^2/2 + |z2(0)|^2/2 over f2bar), beside the derived (19b); from a zero
    initial error the printed bound is 0 while ||z2|| is not, and the derived one holds."""
    from lgw.sim.lunar.closed_loop import gain_arrays
    from lgw.sim.lunar.general import GeneralCase, fly
    from lgw.theory.lunar.bounds import z_l2_bounds_printed

    g = paper_gains().orbit
    case = GeneralCase(D=0.5, u_max=2000.0)
    X0 = np.zeros((9, 2))
    X0[0, 1], X0[1:4, 1] = 30.0, [1.0, -2.0, 0.5]
    t, o = fly(X0, gain_arrays([g] * 2), case, 2.0, 0.02)
    for i, x1 in enumerate((0.0, 30.0)):
        ob = V.observations(t, o, g, case, x1, 0.02, i)
        want = z_l2_bounds_printed(np.array([x1]), o["z2"][0, :, i], float(g.K1[2, 2]),
                                   g.f2bar)[1]
        assert ob["(19b) printed"][0] == pytest.approx(float(want), rel=1e-12)
        assert ob["(19b) printed"][1] == ob["(19b) derived"][1]  # the same ||z2||^2
        assert ob["(19b) derived"][0] > ob["(19b) printed"][0]
    zero = V.observations(t, o, g, case, 0.0, 0.02, 0)
    assert zero["(19b) printed"][0] == 0 < zero["(19b) printed"][1] <= zero["(19b) derived"][0]
