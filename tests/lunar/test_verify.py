"""``lgw verify lunar`` (issue 19) for one gain set's orbit loop on Hypothesis-drawn initial
errors: per claim checked and excluded counts, never ``holds`` on fewer than --min-cases
checked cases, exit 1 on a violation (shrunk witness re-checked at half the step, with a
reproduction), exit 4 when inconclusive, strict JSON, --plot written atomically, bad input
exit 2 with nothing written."""

import json
import subprocess

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.cli import cli
from lgw.tuning.lunar import verify as V


def _run(*args):
    res = CliRunner().invoke(cli, ["verify", "lunar", "--t-end", "2", *args, "--json"])
    return res.exit_code, json.loads(res.output) if res.output.startswith("{") else res.output


def test_holds_on_enough_checked_cases_and_plots(tmp_path):
    code, d = _run("--plot", str(tmp_path / "fig"))
    assert code == 0, d
    assert [c["claim"] for c in d["claims"]] == list(V.CLAIMS)
    for c in d["claims"]:
        assert c["verdict"] == "holds"
        assert c["n_checked"] + c["n_excluded"] == c["n_cases"]
        assert c["n_checked"] >= d["min_cases"] and c["worst_margin"] >= 0
        assert 0 < c["fraction_checked"] <= 1
    png = tmp_path / "fig" / "verify_lunar.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert [p.name for p in (tmp_path / "fig").iterdir()] == ["verify_lunar.png"]


def test_too_few_cases_is_inconclusive_exit_4():
    code, d = _run("--examples", "2", "--min-cases", "100000")
    assert code == 4
    for c in d["claims"]:
        assert c["verdict"] == "inconclusive" and "< --min-cases 100000" in c["why"]


def test_shrunk_bound_is_violated_with_a_rechecked_witness_exit_1(tmp_path):
    db = tmp_path / "db"
    code, d = _run("--scale", "(19a)=0.25", "--database", str(db))
    assert code == 1
    # the failure is saved in the example database (replayed first on the next run)
    assert any(p.is_file() for p in (db / "lunar" / "orbit").rglob("*"))
    c = {c["claim"]: c for c in d["claims"]}
    r = c["(19a)"]
    assert r["verdict"] == "violated" and r["bound_scale"] == 0.25
    w = r["witness"]
    assert w["margin"] < 0 and w["rechecked_margin"] < 0 and "dt = 0.01" in w["recheck_method"]
    assert all(c[k]["verdict"] == "holds" for k in c if k != "(19a)")
    # the reproduction, pasted into a shell, shows the same negative margin
    out = subprocess.run(["bash", "-c", r["reproduction"]], capture_output=True, text=True,
                         cwd=tmp_path, check=True).stdout
    assert float(out.split("margin")[-1]) == pytest.approx(w["margin"], rel=1e-6)


def test_excluded_cases_push_a_claim_to_inconclusive(monkeypatch):
    # a claim whose margin is undefined (NaN) on every other case: those are excluded and
    # counted, and the claim is inconclusive once the rest is below --min-cases (never holds)
    real = V.margins

    def margins(t, o, g, case, x1_0, dt, i=0, pairs=None):
        m = real(t, o, g, case, x1_0, dt, i, pairs)
        if i % 2:
            m["(21a)"] = float("nan")
        return m

    monkeypatch.setattr(V, "margins", margins)
    res = {r.claim: r for r in V.run_verify(paper_gains().orbit,
                                           V.VerifyOptions(examples=4, t_end=1.0))}
    r = res["(21a)"]
    assert r.n_excluded > 0 and r.n_checked + r.n_excluded == r.n_cases
    assert r.excluded == {"non-finite run or bound (NaN margin)": r.n_excluded}
    need = r.n_checked + 1
    res = {r.claim: r for r in V.run_verify(paper_gains().orbit, V.VerifyOptions(
        examples=4, t_end=1.0, min_cases=need))}
    assert res["(21a)"].verdict == "inconclusive" and "excluded" in res["(21a)"].why
    assert V.result_exit_code(list(res.values())) == 4


def test_claim_result_never_holds_without_evidence():
    assert V.claim_result(None, 0, 1) == "inconclusive"
    assert V._exclusion("V2_step_outside_band", np.inf).startswith("no step outside")
    assert V._exclusion("(18a)", -np.inf) is not None and V._exclusion("(18a)", 0.1) is None


@pytest.mark.parametrize("args", [["--min-cases", "0"], ["--scale", "nope=2"],
                                  ["--scale", "(19a)=-1"], ["--dt", "0"],
                                  ["--profile", "fast"]])
def test_bad_option_is_one_error_line_exit_2(args, capsys):
    from lgw.tuning.cli import main

    with pytest.raises(SystemExit) as e:
        main(["verify", "lunar", *args])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and err.count("\n") == 1


@pytest.mark.parametrize("sub", ["", "sub"])
def test_bad_plot_path_is_exit_2_before_any_work(tmp_path, capsys, sub, monkeypatch):
    """--plot naming a file, or a folder below a file: one error line, exit 2, nothing
    written (checked before the campaign)."""
    from lgw.tuning.cli import main

    def no_work(*a, **k):
        raise AssertionError("the campaign ran before --plot was checked")

    monkeypatch.setattr(V, "run_verify", no_work)
    f = tmp_path / "a_file"
    f.write_text("x")
    with pytest.raises(SystemExit) as e:
        main(["verify", "lunar", "--plot", str(f / sub if sub else f)])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "--plot" in err and err.count("\n") == 1
    assert [p.name for p in tmp_path.iterdir()] == ["a_file"] and f.read_text() == "x"


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_a_database_makes_the_run_random_so_hypothesis_uses_it(system, tmp_path):
    """Hypothesis ignores the example database in a seeded run (hypothesis.seed sets
    database=None), so --database must drop the seed, or it would silently do nothing."""
    import importlib

    VO = importlib.import_module(f"lgw.tuning.{system}.verify").VerifyOptions
    assert VO(seed=3).seed == 3
    assert VO(seed=3, database=tmp_path).seed is None
