"""``lgw verify eros`` (issue 19): seed 002's per-axis reaching and reaching + sliding times on
Hypothesis-drawn cases; holds / violated / inconclusive with exit 0 / 1 / 4; a case the batched
RK4 cannot carry goes to the reference route, not to a skip list; only what neither carries is
excluded, counted and shown; --plot is written atomically; bad input exit 2, nothing written."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.theory.eros.gains import default_gains
from lgw.tuning.cli import cli
from lgw.tuning.eros import verify as V


def _run(*args):
    res = CliRunner().invoke(cli, ["verify", "eros", *args, "--json"])
    return res.exit_code, json.loads(res.output) if res.output.startswith("{") else res.output


def test_default_gains_hold_with_counts_and_a_plot(tmp_path):
    code, d = _run("--examples", "3", "--min-cases", "10", "--plot", str(tmp_path / "p"))
    assert code == 0, d
    assert [c["claim"] for c in d["claims"]] == list(V.CLAIMS)
    for c in d["claims"]:
        assert c["verdict"] == "holds", c
        assert c["n_checked"] >= c["min_cases"] == 10
        assert c["n_checked"] + c["n_excluded"] == c["n_cases"]
        assert c["ratio"] <= 1.0 and c["fraction_checked"] == 1.0
    png = tmp_path / "p" / "verify_eros.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert [p.name for p in (tmp_path / "p").iterdir()] == ["verify_eros.png"]


def test_large_min_cases_is_inconclusive_exit_4():
    code, d = _run("--examples", "1", "--min-cases", "100000")
    assert code == 4
    for c in d["claims"]:
        assert c["verdict"] == "inconclusive" and "< --min-cases 100000" in c["why"]


def _nonfinite_first(monkeypatch, reference_too: bool):
    """Make the batched RK4 report case 0 of every batch nonfinite (and the reference route
    too, if asked): the checker must re-fly it, or exclude it and say why."""
    from lgw.sim.eros.batch import OUTCOMES

    real_sim, real_ref = V.simulate, V.reference_solve

    def sim(e0, ed0, g, opts, ph=None):
        res = real_sim(e0, ed0, g, opts, ph)
        res.nonfinite[0] = True
        res.outcome[0] = OUTCOMES.index("nonfinite")
        return res

    def ref(e0, ed0, g, opts, ph=0.0):
        res = real_ref(e0, ed0, g, opts, ph)
        if reference_too:
            res.nonfinite[0] = True
            res.outcome[0] = OUTCOMES.index("nonfinite")
        return res

    monkeypatch.setattr(V, "simulate", sim)
    monkeypatch.setattr(V, "reference_solve", ref)


def test_a_case_rk4_cannot_carry_goes_to_the_reference_route(monkeypatch):
    _nonfinite_first(monkeypatch, reference_too=False)
    res = V.run_verify(default_gains(), V.VerifyOptions(examples=1, min_cases=1))
    for r in res:
        assert r.n_reference == 1 and r.n_excluded == 0  # re-flown, not skipped
        assert r.verdict == "holds"


def test_a_case_no_integrator_carries_is_excluded_and_can_make_it_inconclusive(monkeypatch):
    _nonfinite_first(monkeypatch, reference_too=True)
    res = V.run_verify(default_gains(), V.VerifyOptions(examples=1, min_cases=1))
    for r in res:
        assert r.excluded == {V.NO_INTEGRATOR: 1} and r.n_checked == r.n_cases - 1
    # the same (derandomised) cases with --min-cases = all of them: the exclusion decides
    res = V.run_verify(default_gains(), V.VerifyOptions(examples=1, min_cases=res[0].n_cases))
    assert {r.verdict for r in res} == {"inconclusive"} and V.exit_code(res) == 4
    assert all("1 excluded" in r.why for r in res)


def test_k_not_above_dbar_has_no_bound_inconclusive():
    g = default_gains().replace(k=0.04)  # below DIST_AMP = 0.05: (18) gives no unknown-D bound
    res = {r.claim: r for r in V.run_verify(g, V.VerifyOptions(examples=1, min_cases=1))}
    for c in ("reaching-unknown", "time-unknown"):
        assert res[c].verdict == "inconclusive" and "k = 0.04 <= dbar" in res[c].why


def test_ratio_of_a_zero_bound():
    r = V.ratio(np.array([[-0.01, 0.0, 0.02]]), np.zeros((1, 3)))
    assert r.tolist() == [[0.0, 0.0, np.inf]]


@pytest.mark.slow
def test_shrunk_bound_is_violated_with_a_confirmed_witness_exit_1(tmp_path):
    """reaching-known's bound |s0|/k made 3 % smaller: found, shrunk, confirmed by DOP853, and
    the printed reproduction flies the same reaching time (about 2.5 min on 2 loaded cores)."""
    import subprocess

    p = subprocess.run(["lgw", "verify", "eros", "--scale-bound", "reaching-known=0.97",
                        "--json"], capture_output=True, text=True)
    assert p.returncode == 1, p.stderr
    d = json.loads(p.stdout)
    c = {c["claim"]: c for c in d["claims"]}
    r = c["reaching-known"]
    assert r["verdict"] == "violated" and r["ratio"] > 1
    w = r["witness"]
    assert w["confirmed"] and w["rechecked_observed"] - 0.01 > w["bound"]
    assert all(c[k]["verdict"] == "holds" for k in c if k != "reaching-known")
    out = subprocess.run(["bash", "-c", r["reproduction"]], capture_output=True, text=True,
                         cwd=tmp_path, check=True).stdout
    row = json.loads(out)["rows"][0]
    assert row["t_reach_axes"]["xyz".index(w["axis"])] == pytest.approx(w["observed"])


@pytest.mark.parametrize("args", [["--min-cases", "0"], ["--scale-bound", "nope=2"],
                                  ["--scale-bound", "time-known=-1"],
                                  ["--scale-bound", "time-known=nan"], ["--profile", "fast"]])
def test_bad_option_is_one_error_line_exit_2(args, capsys):
    from lgw.tuning.cli import main

    with pytest.raises(SystemExit) as e:
        main(["verify", "eros", *args])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and err.count("\n") == 1


@pytest.mark.parametrize("sub", ["", "sub"])
def test_bad_plot_path_is_exit_2_before_any_work(tmp_path, capsys, sub, monkeypatch):
    from lgw.tuning.cli import main

    def no_work(*a, **k):
        raise AssertionError("the campaign ran before --plot was checked")

    monkeypatch.setattr(V, "run_verify", no_work)
    f = tmp_path / "a_file"
    f.write_text("x")
    with pytest.raises(SystemExit) as e:
        main(["verify", "eros", "--plot", str(f / sub if sub else f)])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "--plot" in err and err.count("\n") == 1
    assert [p.name for p in tmp_path.iterdir()] == ["a_file"] and f.read_text() == "x"


def test_simulate_initial_states_rejects_bad_csv(tmp_path, capsys):
    from lgw.tuning.cli import main

    p = tmp_path / "s.csv"
    p.write_text("ex,ey,ez,vx,vy\n1,2,3,4,5\n")
    with pytest.raises(SystemExit) as e:
        main(["simulate", "eros", "--initial-states", str(p)])
    assert e.value.code == 2 and "missing vz" in capsys.readouterr().err
    p.write_text("ex,ey,ez,vx,vy,vz\n1,2,x,0,0,0\n")
    with pytest.raises(SystemExit) as e:
        main(["simulate", "eros", "--initial-states", str(p)])
    assert e.value.code == 2 and "row 2 ez" in capsys.readouterr().err
