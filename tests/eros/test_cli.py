"""``lgw bounds/simulate/tune/report eros`` through the real command line."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest


def lgw(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                           *args], capture_output=True, text=True, timeout=600)


def test_bounds_json_matches_library():
    from lgw.theory.eros.gains import default_gains
    from lgw.theory.eros.report import axis_bounds

    r = lgw("bounds", "eros", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    lib = axis_bounds(default_gains())
    assert out["x"]["t_total"] == pytest.approx(lib["x"]["t_total"])
    assert out["x"]["ts_tsm_printed"] < 0


def test_simulate_one_variant_json():
    r = lgw("simulate", "eros", "--law", "ftsmc-tanh", "--t-max", "1", "--json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    rows = doc["rows"]
    assert rows[0]["variant"] == "ftsmc-tanh" and rows[0]["nonfinite"] == 0
    assert doc["lgw_version"] and doc["command"] == "simulate eros" and doc["gains"]["k"] > 0


def test_variant_names_for_the_command_line_are_the_registered_variants():
    from lgw.sim.eros.laws import VARIANTS, variant_name
    from lgw.tuning.eros.cmd_simulate import VARIANT_NAMES

    assert tuple(variant_name(*v) for v in VARIANTS) == VARIANT_NAMES


def test_simulate_the_whole_descent_json():
    """Table 1's start to touchdown on the shape model through the command line: landed near
    the reference's 0.1 m/s, the contact point and fuel reported, converged."""
    r = lgw("simulate", "eros", "--scenario", "descent", "--law", "fuzzy-tanh", "--json")
    assert r.returncode == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["settings"]["scenario"] == "descent" and doc["gains"]["k"] == 0.01
    row = doc["rows"][0]
    assert row["outcomes"]["landed"] == 1 and row["converged"] == 1
    case = row["case_records"][0]
    assert case["outcome"] == "landed" and abs(case["touchdown"]["speed"] - 0.1) < 0.01
    assert 2.0 < case["fuel_kg"] < 6.0 and case["touchdown"]["mesh_distance_m"] < 1e-5
    assert -90 <= case["touchdown"]["lat_deg"] <= 90


@pytest.mark.parametrize("args,name", [
    (("simulate", "eros", "--thrust-max", "10"), "--thrust-max"),
    (("simulate", "eros", "--nav"), "--nav"),
    (("simulate", "eros", "--gravity", "polyhedron-exact"), "--gravity"),
    (("simulate", "eros", "--scenario", "descent", "--disturbance", "known"), "--disturbance"),
    (("simulate", "eros", "--scenario", "descent", "--srp", "-1"), "--srp"),
    (("simulate", "eros", "--law", "bogus"), "--law"),
    (("simulate", "eros", "--dt", "-1"), "dt"),
    (("bounds", "eros", "--dbar", "5"), "--dbar"),
    (("tune", "eros", "--ts", "-3", "--thrust-max", "600"), "--ts"),
])
def test_bad_input_is_one_line_exit_2(args, name, tmp_path):
    r = lgw(*args)
    assert r.returncode == 2
    assert r.stderr.startswith("error: ") and name in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_bad_gains_file_writes_nothing(tmp_path):
    bad = tmp_path / "g.toml"
    bad.write_text("[gains]\nalpha = 1\n")
    out = tmp_path / "rep"
    r = lgw("report", "eros", "--gains", str(bad), "--out", str(out), "--no-sim")
    assert r.returncode == 2 and "gains.beta" in r.stderr
    assert not out.exists()


@pytest.mark.slow
def test_tune_meets_target_on_a_fresh_campaign(tmp_path):
    out = tmp_path / "tuned.toml"
    r = lgw("tune", "eros", "--ts", "10", "--thrust-max", "600", "--out", str(out), "--json")
    assert r.returncode == 0, r.stderr
    cert = json.loads(r.stdout)["certificate"]
    assert cert["bound_t_total"] <= 10 and cert["acceptance_peak"] <= 4
    from lgw.theory.eros.gains import load_gains

    load_gains(out)  # the written file round-trips through the validator


def test_verify_no_violation_small_campaign():
    r = lgw("verify", "eros", "--examples", "2", "--min-cases", "2", "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    for c in out["claims"]:  # (the full checks: tests/eros/test_verify.py)
        assert c["verdict"] in ("holds", "not-applicable") and (c["margin"] or 0) >= 0


@pytest.mark.slow
def test_report_no_sim_writes_every_format(tmp_path):
    out = tmp_path / "rep"
    r = lgw("report", "eros", "--out", str(out), "--no-sim")
    assert r.returncode == 0, r.stderr
    for name in ("report.md", "report.tex", "report.html", "claims.json"):
        assert (out / name).stat().st_size > 1000
    claims = json.loads((out / "claims.json").read_text())["claims"]
    md = (out / "report.md").read_text()
    for c in claims:  # every claim in the verdict table with its computed verdict
        assert f"[{c['id']}](#claim-{c['id']})" in md
        assert c["verdict"] in ("proved", "proved-given", "checked", "unproven", "refuted")
    assert "## Coverage of the paper" in md


def test_tune_infeasible_exit_3_writes_nothing(tmp_path):
    out = tmp_path / "t.toml"
    r = lgw("tune", "eros", "--ts", "0.5", "--thrust-max", "150", "--out", str(out))
    assert r.returncode == 3 and "infeasible" in r.stderr and not out.exists()
