"""``lgw report lunar --no-sim`` writes the three formats with every theory claim's verdict
and the coverage table."""

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
    ids = {c.id for c in theory_claims()} | {"s5-no-saturation", "s5-d0e", "s5-tracking"}
    for item, claims, note in COVERAGE:
        assert set(claims) <= ids, item
        assert claims or note, item  # "not checkable" items say why
