"""Seed 000 Part 1's comparison and the report that includes it.

The rendering tests are structural and fast; one end-to-end run checks the tuned row against
its own certificate by a fresh simulation, and the report's bytes against a second run."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from lgw.sim.mars.arrival import after_arrival_peaks
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import landing_time_bound
from lgw.theory.mars.gains import default_gains, load_gains
from lgw.theory.mars.report import report_spec
from lgw.theory.report import Section, render_html, render_latex, render_markdown
from lgw.tuning.mars.compare import (
    TUNED_DEFAULT,
    law_gain_sets,
    report_section,
    run_comparison,
    tuned_sets,
)

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


@pytest.fixture(scope="module")
def comparison() -> tuple[dict, list[dict], list[tuple[str, object]]]:
    """The comparison as ``lgw compare mars`` runs it by default (also docs/optimal.md's)."""
    tuned = tuned_sets(None)
    rep, trajs = run_comparison(default_gains(), tuned)
    return rep, trajs, tuned


def _gain_sets(rep: dict, tuned: list) -> dict[str, tuple[str, object]]:
    """label -> (law, gains) of every closed-loop row, from the per-law gain sets."""
    out = {}
    for law in rep["laws"]:
        for label, g in law_gain_sets(law, default_gains(), tuned, "default gains"):
            out[label] = (law, g)
    return out


def _kw(rep: dict, row: dict) -> dict:
    return {"law": row["method"], "disturbance": row["disturbance"],
            "dist_amplitude": row["dist_amplitude"] if row["disturbance"] == "sin" else None,
            "drag": rep["drag"], "thrust_limit": rep["thrust_max_axis"]}


@pytest.mark.slow  # the full comparison: every law by RK4 and dopri5, ~4 min cold in CI
def test_every_registered_law_has_rows_with_an_outcome(comparison) -> None:
    from lgw.sim.mars.laws import LAWS

    rep, trajs, tuned = comparison
    assert rep["laws"] == list(LAWS)  # nothing dropped, any law registered later included
    sets = _gain_sets(rep, tuned)
    n_dist = 1 + len(rep["amplitudes"])
    assert rep["amplitudes"] == [1.0, 20.0]
    labels = [r["label"] for r in rep["rows"]]
    assert len(labels) == n_dist * (1 + len(sets)) and len(trajs) == len(labels)
    for law in LAWS:
        assert any(r["method"] == law for r in rep["rows"]), law
    for r in rep["rows"]:
        assert r["outcome"]  # a run that crashed or blew up has its outcome, not a blank row
        assert len(r["peak_thrust_axis"]) == 3 and len(r["peak_after_arrival_axis"]) == 3
        assert max(r["peak_thrust_axis"]) <= rep["thrust_max_axis"] * (1 + 1e-12)
    rows = {(r["label"], r["dist_amplitude"]): r for r in rep["rows"]}
    opt = rows["fuel-optimal (open loop)", 0.0]
    # the optimum (same plant, no drag, same per-axis limit) is a lower bound on every landing
    for r in rep["rows"]:
        if r["landed"] and r["label"] != opt["label"]:
            assert r["fuel"] > opt["fuel"]
    # (46) as printed does not land Table I (the paper says it does): the row ends at touchdown
    st = rows["super-twisting (46), paper's B1, B2", 0.0]
    assert st["outcome"].startswith("crashed at") and st["vel_error"] > 10.0
    # ended at the located contact (lgw.sim.results): on the ground plane, never below it
    assert abs(st["min_altitude"]) < 1e-6 and st["t_end"] < 120.0 and st["converged"] in (
        True, False)
    label, g = tuned[0]
    cert = g.extra["certificate"]
    for amp in (0.0, 1.0):
        t = rows[label, amp]
        assert t["landed"], t
        assert t["landing_time"] <= cert["request"]["tf"]
        assert t["min_altitude"] > -0.1
    t = rows[label, 0.0]
    assert t["landing_time"] <= landing_time_bound(g)
    assert max(t["peak_thrust_axis"]) <= cert["request"]["thrust_max"]
    sec = report_section(rep, "compare.png")
    assert len(sec.rows) == len(labels) and all(len(r) == len(sec.columns) for r in sec.rows)


@pytest.mark.slow  # the full comparison: every law by RK4 and dopri5, ~4 min cold in CI
def test_each_row_against_independent_runs(comparison) -> None:
    """Every closed-loop row against (a) a fresh RK4 simulate_batch of the same law, gains,
    state, disturbance and limit, without recording (the row's plumbing: equal to 1e-12), and
    (b) the adaptive dopri5 of the same closed loop (another integrator): same outcome, landing
    time within 0.3 s, crash time bracketed to 0.1 s, dry-mass time within 0.1 s, fuel within
    the RK4 chattering's share (5 %)."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.theory.mars.parameters import M0, R0, V0

    rep, trajs, tuned = comparison
    sets = _gain_sets(rep, tuned)
    one = (R0[None], V0[None], np.array([M0]))
    for row in rep["rows"]:
        if row["method"] == "optimal":
            continue
        law, g = sets[row["label"]]
        assert law == row["method"]
        kw = _kw(rep, row)
        # a row whose RK4 outcome changed with the step was refined (its step in refined_dt)
        b = simulate_batch(*one, g, dt=row.get("refined_dt") or 0.05, **kw)
        d5 = simulate_batch(*one, g, method="dopri5", **kw)
        what = (row["label"], row["dist_amplitude"])
        assert bool(b.landed[0]) == row["landed"] == bool(d5.landed[0]), what
        if row["landed"]:
            assert b.landing_time[0] == pytest.approx(row["landing_time"], abs=1e-12), what
            assert b.fuel[0] == pytest.approx(row["fuel"], rel=1e-12), what
            assert np.allclose(b.peak_thrust[0], row["peak_thrust_axis"], rtol=1e-12), what
            assert b.time_saturated[0] == pytest.approx(row["time_saturated"], abs=1e-12)
            assert abs(d5.landing_time[0] - row["landing_time"]) <= 0.3, what
            assert abs(d5.fuel[0] - row["fuel"]) <= 0.05 * row["fuel"], what
            assert row["dopri5"]["fuel"] == pytest.approx(d5.fuel[0], rel=1e-12), what
        elif row["outcome"].startswith("crashed at"):
            # the row's contact is RK4's located crossing; dopri5's is within 0.1 s
            tc = row["t_end"]
            assert b.contact_time[0] == pytest.approx(tc, abs=1e-12), what
            assert d5.contact[0] and abs(d5.contact_time[0] - tc) <= 0.1, what
        else:
            assert row["outcome"].startswith("propellant exhausted at"), what
            assert b.fuel_exhausted[0] and d5.fuel_exhausted[0], what
            assert abs(d5.t_end[0] - row["t_end"]) <= 0.1, what


@pytest.mark.slow  # the full comparison: every law by RK4 and dopri5, ~4 min cold in CI
def test_after_arrival_column_from_the_recorded_flight(comparison) -> None:
    """The after-arrival peaks are the trajectory function applied to the plotted flight, and
    they are no larger than the whole-flight peaks; '-' (NaN) exactly where no axis band is
    entered in the record."""
    rep, trajs, _ = comparison
    for row, tr in zip(rep["rows"], trajs, strict=True):
        assert (row["label"], row["disturbance"]) == (tr["label"], tr["disturbance"])
        _, after = after_arrival_peaks(tr["r"], tr["v"], tr["F"])
        assert np.array_equal(np.isnan(after), np.isnan(row["peak_after_arrival_axis"]))
        ok = ~np.isnan(after)
        assert np.allclose(after[ok], np.asarray(row["peak_after_arrival_axis"])[ok])
        if row["method"] != "optimal":
            assert np.all(after[ok] <= np.asarray(row["peak_thrust_axis"])[ok] * (1 + 1e-12))


@pytest.mark.slow
def test_rows_against_the_reference_mode(comparison) -> None:
    """The rows of the laws whose LSODA reference is quick (corrected with its own gains,
    printed, super-twisting) against ``simulate_reference`` (numpy law from theory's SymPy,
    solve_ivp): outcome, landing time within 0.05 s, fuel within 0.1 kg, crash time within
    0.1 s (from the dense output), dry-mass time within 0.1 s."""
    from lgw.sim.mars.reference import simulate_reference
    from lgw.theory.mars.parameters import M0, R0, V0

    rep, _, tuned = comparison
    sets = _gain_sets(rep, tuned)
    for row in rep["rows"]:
        if row["method"] not in ("corrected", "printed", "super-twisting") or "tuned" in \
                row["label"]:
            continue
        law, g = sets[row["label"]]
        ref = simulate_reference(R0[None], V0[None], np.array([M0]), g, record=True,
                                 **_kw(rep, row))
        what = (row["label"], row["dist_amplitude"])
        assert bool(ref.landed[0]) == row["landed"], what
        if row["landed"]:
            assert abs(ref.landing_time[0] - row["landing_time"]) <= 0.05, what
            assert abs(ref.fuel[0] - row["fuel"]) <= 0.1, what
        elif row["outcome"].startswith("crashed at"):
            # the reference's contact: a solve_ivp event on r_z = 0
            tc = float(ref.contact_time[0])
            assert abs(tc - row["t_end"]) <= 0.1, what
            assert abs(ref.fuel[0] - row["fuel"]) <= 0.5, what
        else:
            assert ref.fuel_exhausted[0] and abs(ref.t_end[0] - row["t_end"]) <= 0.1, what


def _lgw(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()", *args],
                          capture_output=True, text=True, timeout=300)


@pytest.mark.slow  # the full comparison: every law by RK4 and dopri5, ~4 min cold in CI
def test_report_without_comparison_is_byte_identical(tmp_path) -> None:
    a, b = tmp_path / "a", tmp_path / "b"
    for d in (a, b):
        p = _lgw("report", "mars", "--no-sim", "--out", str(d))
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


DOC = Path(__file__).resolve().parents[2] / "docs" / "optimal.md"
NUM = re.compile(r"-?\d+(?:\.\d+)?(?:e[+-]\d+)?")


def _doc_table() -> list[str]:
    text = DOC.read_text()
    a = text.index("<!-- lgw compare mars: begin -->")
    b = text.index("<!-- lgw compare mars: end -->")
    return [line.strip() for line in text[a:b].splitlines()[1:] if line.strip()]


def _unit(tok: str) -> float | None:
    """One unit of the last printed digit of a number token; None for an integer (exact)."""
    mant, _, exp = tok.partition("e")
    if "." not in mant and not exp:
        return None
    dec = len(mant.partition(".")[2])
    return 10.0 ** (-dec) * 10.0 ** (int(exp) if exp else 0)


def _same_within_rounding(doc: str, fresh: str) -> str | None:
    """None if the two table lines agree: the same words, integers equal, every decimal
    number within one unit of its last printed digit (a rounding flip); else the reason."""
    d_words, f_words = NUM.split(doc), NUM.split(fresh)
    if [" ".join(w.split()) for w in d_words] != [" ".join(w.split()) for w in f_words]:
        return f"text differs: {doc!r} vs {fresh!r}"
    for a, b in zip(NUM.findall(doc), NUM.findall(fresh), strict=True):
        u = _unit(a)
        if (u is None and a != b) or (u is not None and abs(float(a) - float(b)) > u * 1.000001):
            return f"{a} (doc) vs {b} (fresh) in {doc!r}"
    return None


def test_doc_table_comparison_catches_a_change() -> None:
    row = "tuned tf=90 s   0 landed  40.90  222.29  8.7/10.4/27.8  4.39e-07"
    assert _same_within_rounding(row, row) is None
    assert _same_within_rounding(row, row.replace("222.29", "222.30")) is None  # rounding
    assert _same_within_rounding(row, row.replace("222.29", "221.53")) is not None  # stale
    assert _same_within_rounding(row, row.replace("27.8", "16.7")) is not None
    assert _same_within_rounding(row, row.replace("4.39e-07", "4.39e-06")) is not None
    assert _same_within_rounding(row, row.replace("tf=90", "tf=91")) is not None
    assert _same_within_rounding(row, row.replace("landed", "crashed")) is not None


@pytest.mark.slow  # the full comparison: every law by RK4 and dopri5, ~4 min cold in CI
def test_optimal_doc_matches_a_fresh_comparison(comparison) -> None:
    """docs/optimal.md's comparison table and the statements it makes about it, against a
    fresh ``run_comparison`` with the command's defaults (they had gone stale once)."""
    from lgw.tuning.mars.compare import format_table

    rep, _, tuned = comparison
    fresh = format_table(rep).splitlines()  # the header too
    doc = _doc_table()
    assert len(doc) == len(fresh), "docs/optimal.md: rows added or removed; paste the table anew"
    bad = [why for d, f in zip(doc, fresh, strict=True)
           if (why := _same_within_rounding(d, f)) is not None]
    assert not bad, "docs/optimal.md is stale (re-run lgw compare mars):\n" + "\n".join(bad)
    # the prose's numbers and claims
    rows = {(r["label"], r["dist_amplitude"]): r for r in rep["rows"]}
    text = " ".join(DOC.read_text().split())
    opt, cor = rows["fuel-optimal (open loop)", 0.0], rows[
        "fixed-time (25) corrected, default gains", 0.0]
    assert (f"the corrected law uses {cor['fuel']:.1f} kg" in text
            and f"against {opt['fuel']:.1f} kg, a ratio of {cor['fuel'] / opt['fuel']:.2f}"
            in text)
    closed = [r for r in rep["rows"] if r["method"] != "optimal"]
    assert not any(r["landed"] for r in closed if r["dist_amplitude"] == 20.0)
    assert all(r["outcome"].startswith("propellant exhausted") for r in closed
               if r["method"] == "printed")
    label = tuned[0][0]
    t = rows[label, 0.0]
    assert t["peak_after_arrival_axis"][2] == t["peak_thrust_axis"][2]
    for r in closed:
        if r["method"] == "bounded" and r["landed"]:
            assert max(r["peak_after_arrival_axis"]) < 10e3  # near the hover thrust
        if "tuned" in r["label"] or r["method"] == "bounded":
            if r["landed"]:
                assert r["fuel"] - r["dopri5"]["fuel"] > 1.0  # the chattering's share


def test_cli_choices_and_bad_input_write_nothing(tmp_path) -> None:
    """--law takes the registered laws only; bad numbers and a bad [bounded] table of --gains
    are lgw errors (exit 2, one line) and nothing is written."""
    from tests.test_cli_conventions import assert_one_error, run_lgw

    out = tmp_path / "out"
    bad = tmp_path / "bad.toml"
    bad.write_text((TUNED_DEFAULT.read_text().split("[certificate]")[0])
                   + "\n[bounded]\nc1 = -1.0\n")
    for args, word in ((["--law", "no-such-law"], "--law"),
                       (["--law", "bounded", "--law", "nope"], "--law"),
                       (["--dist-amplitude", "-1"], "--dist-amplitude"),
                       (["--dist-amplitude", "inf"], "--dist-amplitude"),
                       (["--thrust-max", "0"], "--thrust-max"),
                       (["--thrust-max", "nan"], "--thrust-max"),
                       (["--gains", str(bad), "--law", "bounded"], "bounded.c1")):
        r = run_lgw(["compare", "mars", *args, "--out", str(out)])
        assert_one_error(r)
        assert word in r.stderr, (args, r.stderr)
        assert not out.exists(), args


def test_cli_one_law_writes_json_and_figure(tmp_path) -> None:
    """`lgw compare mars --law bounded --dist-amplitude 1 --out DIR --json`: only the asked law
    beside the optimum, one disturbed run, and both files (the figure used to crash --out)."""
    import json

    from tests.test_cli_conventions import run_lgw

    out = tmp_path / "out"
    r = run_lgw(["compare", "mars", "--law", "bounded", "--dist-amplitude", "1", "--json",
                 "--out", str(out)])
    assert r.code == 0 and r.exception is None, r.stderr
    doc = json.loads(r.stdout)
    assert doc["laws"] == ["bounded"] and doc["settings"]["tuned"] == []
    assert {(x["method"], x["dist_amplitude"]) for x in doc["rows"]} == {
        ("optimal", 0.0), ("optimal", 1.0), ("bounded", 0.0), ("bounded", 1.0)}
    assert json.loads((out / "compare.json").read_text())["rows"] == doc["rows"]
    png = (out / "compare.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000


def test_a_tuned_file_is_flown_with_the_law_its_certificate_names(tmp_path) -> None:
    """A bounded-law tuned file gets a bounded row (not a corrected one); a file naming an
    unregistered law is refused, not silently left out."""
    from lgw.theory.mars.bounded import default_bounded
    from lgw.tuning.mars.design_bounded import write_bounded_gains

    from tests.test_cli_conventions import assert_one_error, run_lgw

    f = tmp_path / "b.toml"
    bg = default_bounded()
    write_bounded_gains(f, bg, {"law": "bounded", "request": {"tf": 101.6}}, "# test")
    tuned = tuned_sets([f])
    assert tuned[0][0] == "bounded cascade, tuned tf=101.6 s"
    sets = law_gain_sets("bounded", default_gains(), tuned, "default gains")
    assert [lab for lab, _ in sets] == ["bounded cascade, [bounded] default", tuned[0][0]]
    assert law_gain_sets("corrected", default_gains(), tuned, "default gains")[1:] == []
    from lgw.sim.mars.laws import get_law

    assert np.array_equal(get_law("bounded").param_values(sets[1][1]), bg.params())
    bad = tmp_path / "x.toml"
    bad.write_text(f.read_text().replace('law = "bounded"', 'law = "no-such-law"'))
    r = run_lgw(["compare", "mars", "--tuned", str(bad), "--out", str(tmp_path / "o")])
    assert_one_error(r)
    assert "no-such-law" in r.stderr and not (tmp_path / "o").exists()


def test_a_law_registered_later_is_a_row_even_when_it_cannot_fly() -> None:
    """A law registered after the comparison was written gets rows; if its parameters cannot
    be had from the gain set (here: a gain with no default), the rows say so; the figure still
    draws.  (Registered for this test only.)"""
    from lgw.sim.mars.laws import LAWS, LawSpec, register_law
    from lgw.theory.mars import bounded as B
    from lgw.tuning.mars.compare import figure_png

    def params(g):
        return np.column_stack([B.bounded_from_extra(g.extra).params(),
                                np.full(3, float(g.extra["w0"]))])
    register_law(LawSpec("later-law", B.law_bounded_sat, B.PARAMS_SAT, params, "test only"))
    try:
        rep, trajs = run_comparison(default_gains(), [], amplitudes=[1.0], n=40)
        assert rep["laws"][-1] == "later-law"
        later = [r for r in rep["rows"] if r["method"] == "later-law"]
        assert len(later) == 2 and all(r["outcome"].startswith("not flown: its gains (KeyError")
                                       for r in later)
        assert len(trajs) == len(rep["rows"])
        assert figure_png(trajs)[:4] == b"\x89PNG"
    finally:
        LAWS.pop("later-law")
