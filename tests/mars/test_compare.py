"""Seed 000 Part 1's comparison (issue 6) and the report that includes it.

The rendering tests are structural and fast; one end-to-end run checks the tuned row against
its own certificate by a fresh simulation, and the report's bytes against a second run."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import landing_time_bound
from lgw.theory.mars.gains import default_gains, load_gains
from lgw.theory.mars.report import report_spec
from lgw.theory.report import Section, render_html, render_latex, render_markdown
from lgw.tuning.mars.compare import TUNED_DEFAULT, report_section, run_comparison, tuned_sets

SEC = Section(title="T", paragraphs=("a < b & c",), columns=("method", "|r| m"),
              rows=(("x_1", "1.5"), ("y|z", "-")), image="f.png")


def test_sections_render_in_every_format() -> None:
    g = default_gains()
    md = render_markdown([], report_spec(g, {"x": {}}), [SEC])
    assert "| method | \\|r\\| m |" in md and "| y\\|z | - |" in md and "![T](f.png)" in md
    tex = render_latex([], report_spec(g, {"x": {}}), [SEC])
    assert r"x\_1 & 1.5 \\" in tex and r"a \textless{} b \& c" in tex and "includegraphics" in tex
    html = render_html([], report_spec(g, {"x": {}}), [SEC])
    # the HTML never links a file: without the image bytes it says so, with them it embeds
    assert "<td>y|z</td>" in html and "a &lt; b &amp; c" in html and "src='f.png'" not in html
    assert "not embedded" in html
    spec = report_spec(g, {"x": {}})
    assert render_markdown([], spec) == render_markdown([], spec, ())


def test_shipped_tuned_file_is_certified_and_consistent() -> None:
    """The shipped tuned set: its certificate's bound is recomputed, not trusted."""
    g = load_gains(TUNED_DEFAULT)
    cert = g.extra["certificate"]
    assert cert["feasible"] is True
    tf = cert["request"]["tf"]
    bound = landing_time_bound(g)
    assert bound <= tf * (1 + 1e-9)
    assert math.isclose(bound, cert["landing_time_bound"], rel_tol=1e-9)
    assert cert["worst_case"]["peak_thrust"] <= cert["request"]["thrust_max"]


def test_tuned_sets_rejects_a_bad_file(tmp_path) -> None:
    bad = tmp_path / "g.toml"
    bad.write_text("[gains]\nbeta1 = 1.0\nq1 = 1.2\n")
    with pytest.raises(ParameterError):
        tuned_sets([bad])


def test_comparison_rows_and_tuned_row_checked_by_simulation(tmp_path) -> None:
    tuned = tuned_sets(None)
    rep, trajs = run_comparison(default_gains(), tuned, n=40)
    labels = [r["label"] for r in rep["rows"]]
    assert len(labels) == 2 * (3 + len(tuned)) and len(trajs) == len(labels)
    rows = {(r["label"], r["disturbance"]): r for r in rep["rows"]}
    opt = rows["fuel-optimal (open loop)", "none"]
    # the optimum is a lower bound on fuel for every closed loop that lands (same plant, no drag)
    for r in rep["rows"]:
        if r["landed"] and r["label"] != opt["label"]:
            assert r["fuel"] > opt["fuel"]
    # (46) as printed does not land Table I (the paper says it does): the row ends at touchdown
    st = rows["super-twisting (46)", "none"]
    assert st["outcome"].startswith("crashed at") and st["vel_error"] > 10.0
    assert st["min_altitude"] == 0.0 and st["t_end"] < 120.0
    label, g = tuned[0]
    cert = g.extra["certificate"]
    for dist in ("none", "sin"):
        t = rows[label, dist]
        assert t["landed"], t
        assert t["landing_time"] <= cert["request"]["tf"]
        assert t["min_altitude"] > -0.1
    t = rows[label, "none"]
    assert t["landing_time"] <= landing_time_bound(g)
    assert t["peak_thrust"] <= cert["request"]["thrust_max"]
    # the tuned row is the same law with other gains: a fresh run reproduces its fuel
    from lgw.sim.mars.batch import simulate_batch
    from lgw.theory.mars.parameters import M0, R0, V0

    b = simulate_batch(R0[None], V0[None], np.array([M0]), g, drag="none")
    assert b.fuel[0] == pytest.approx(t["fuel"], rel=1e-12)
    sec = report_section(rep, "compare.png")
    assert len(sec.rows) == len(labels) and all(len(r) == len(sec.columns) for r in sec.rows)


def _lgw(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()", *args],
                          capture_output=True, text=True, timeout=300)


def test_report_without_comparison_is_byte_identical(tmp_path) -> None:
    a, b = tmp_path / "a", tmp_path / "b"
    for d in (a, b):
        p = _lgw("report", "mars", "--no-compare", "--out", str(d))
        assert p.returncode == 0, p.stderr
    for name in ("report.md", "report.tex", "report.html"):
        assert (a / name).read_bytes() == (b / name).read_bytes()
    assert "Part 1 comparison" not in (a / "report.md").read_text()


@pytest.mark.slow
def test_report_with_comparison(tmp_path) -> None:
    p = _lgw("report", "mars", "--out", str(tmp_path))
    assert p.returncode == 0, p.stderr
    md = (tmp_path / "report.md").read_text()
    assert "## Seed 000 Part 1 comparison (simulated)" in md and "tuned tf=" in md
    assert (tmp_path / "compare.png").stat().st_size > 10_000
