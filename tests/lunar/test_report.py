"""``lgw report lunar --no-sim`` writes the three formats with every theory claim's verdict
and the coverage table."""

import pytest
from click.testing import CliRunner
from lgw.theory.lunar.claims import theory_claims
from lgw.theory.lunar.coverage import COVERAGE
from lgw.tuning.commands import make_command
from lgw.tuning.system import get_system

command = make_command(get_system("lunar"), "report")


def test_report_without_scenario(tmp_path):
    r = CliRunner().invoke(command, ["--out", str(tmp_path), "--no-sim"])
    assert r.exit_code == 0, r.output
    md = (tmp_path / "report.md").read_text()
    for c in theory_claims():
        assert f"[{c.id}](#claim-{c.id}) |" in md and f"**{c.verdict}**" in md
    assert "## Coverage of the paper" in md
    assert md.count("\n| ") >= len(COVERAGE)
    assert (tmp_path / "report.tex").read_text().startswith("\\documentclass")
    assert "<html" in (tmp_path / "report.html").read_text()
    assert (tmp_path / "claims.json").exists()


def test_coverage_names_only_existing_claims():
    ids = {c.id for c in theory_claims()} | {"s5-no-saturation", "s5-d0e", "s5-tracking",
                                             "reference-3-4"}
    for item, claims, note in COVERAGE:
        assert set(claims) <= ids, item
        assert claims or note, item  # "not checkable" items say why


class _Quiet:
    def stage(self, *_a, **_k) -> None:
        pass


def _report_claims(gains):
    from lgw.tuning.lunar.cmd_report import Inputs, parts

    return {c.id: c for c in parts(Inputs(gains, False), _Quiet()).claims}


def test_two_gain_sets_change_every_gain_set_claim():
    """The report's claims are judged for the gains passed: two gain sets (the paper's and
    other orbit and attitude gains) change the numbers of every claim in the gain-set scope,
    and the L2-18 claims show the gain set's own true L2 gain and printed bound."""
    from lgw.theory.lunar.gains import from_dict, paper_gains

    g2 = from_dict({"orbit": {"K1": [0.2, 0.2, 0.4], "F2": [2.0, 2.0, 8.0], "f3": 0.5,
                              "d0e0": 0.0, "q": 0.05},
                    "attitude": {"K1": [2.0, 2.0, 2.0], "F2": [3.0, 3.0, 3.0], "f3": 0.2,
                                 "d0e0": 0.0, "q": 0.02}})
    a, b = _report_claims(paper_gains()), _report_claims(g2)
    scoped = [cid for cid, c in a.items() if c.scope == "gain-set"]
    assert len(scoped) >= 6
    for cid in scoped:
        assert b[cid].scope == "gain-set"
        assert a[cid].numbers != b[cid].numbers, cid
    n = b["L2-18-hinf"].numbers["orbit"]
    assert n["lambda1_gain_18a"] == pytest.approx(1 / (2 * 0.4) ** 0.5)
    assert n["lambda1_hinf"] == pytest.approx(1 / 4.2, rel=1e-6)  # K1_zz F2_zz / (.. + 1)
    assert b["L2-18"].numbers["orbit"] == n
