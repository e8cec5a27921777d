"""Claims judged for a gain set: gain-dependent verdicts follow the gains, the report separates
them from the general claims, and ``lgw report mars --gains FILE --json`` prints them."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from lgw.theory.mars.bounds import t1_polyakov, t2_polyakov
from lgw.theory.mars.claims import all_claims, gain_set_claims, general_claims
from lgw.theory.mars.gains import default_gains, gains_from_toml_text
from lgw.tuning.cli import cli

# with pytest-xdist (--dist loadgroup), on the worker that derives seed 000's claims once
pytestmark = pytest.mark.xdist_group("mars-claims")


def part1_gains_toml(a_max: float = 35.0) -> str:
    """Gains solved so that (18) = 74.5780 s and (26) = 30.8217 s (seed 000 Part 1), with
    beta2 = alpha2 = 0.05 and the default exponents: an independent route (closed-form solve
    of the printed formulas) to a gain set that must reproduce the printed numbers."""
    q1, q2, g1, g2, b2, a2 = 0.6, 1.5, 0.7, 1.9, 0.05, 0.05

    def c(e):
        return (1 - e) * 2 ** ((e - 1) / 2)

    def d(e):
        return (e - 1) * 2 ** ((e - 1) / 2)

    b1 = 1 / (c(q1) * (74.5780 - 1 / (b2 * d(q2))))
    a1 = 1 / (c(g1) * (30.8217 - 1 / (a2 * d(g2))))
    return (f"[gains]\nbeta1 = {b1!r}\nbeta2 = {b2!r}\nalpha1 = {a1!r}\nalpha2 = {a2!r}\n"
            f"q1 = {q1}\nq2 = {q2}\ng1 = {g1}\ng2 = {g2}\n\n[disturbance]\na_max = {a_max}\n"
            "theta1 = 0.2\ntheta2 = 0.1\n")


def _verdicts(claims):
    return {c.id: c.verdict for c in claims}


def test_gain_dependent_verdicts_differ_between_two_gain_sets():
    g_a = default_gains()
    g_b = gains_from_toml_text(part1_gains_toml())
    assert float(t1_polyakov(g_b)[0]) == pytest.approx(74.5780, abs=1e-9)
    assert float(t2_polyakov(g_b)[0]) == pytest.approx(30.8217, abs=1e-9)
    va, vb = _verdicts(gain_set_claims(g_a)), _verdicts(gain_set_claims(g_b))
    assert va["paper-numbers-part1@gains"] == "refuted"
    assert vb["paper-numbers-part1@gains"] == "proved"
    # Hypothesis 1 in norm needs a_max >= 20 sqrt(3) = 34.64 for (47)
    assert va["practical-hypotheses@gains"] == "refuted"
    assert vb["practical-hypotheses@gains"] == "proved"
    # nudge a_max just below 20 sqrt 3: the verdict follows
    from lgw.theory.mars.claims import hypotheses_gain_claim

    g_c = gains_from_toml_text(part1_gains_toml(a_max=34.6))
    assert hypotheses_gain_claim(g_c).verdict == "refuted"
    # the claim names the gains that would reproduce the printed numbers: for g_b, its own
    from lgw.theory.mars.claims import reproducing_gains
    rep = reproducing_gains(g_b)
    assert rep["beta1_x"] == pytest.approx(g_b.beta1[0], rel=1e-12)
    assert rep["alpha1_x"] == pytest.approx(g_b.alpha1[0], rel=1e-12)
    assert reproducing_gains(g_a)["beta1_x"] is None  # beta2 = 4e-4 alone exceeds 74.578 s
    # the general claims do not depend on the gains
    assert _verdicts(all_claims(g_a))["T1"] == _verdicts(all_claims(g_b))["T1"]


def test_thrust_claim_witness_is_rechecked():
    """The Part-1 gains ask for far more than 50 kN at t = 0 on Table I: the witness's margin
    and its independent re-check (dry mass, SymPy law) are both negative."""
    g_b = gains_from_toml_text(part1_gains_toml())
    c = {c.id: c for c in gain_set_claims(g_b)}["thrust-table1-corrected@gains"]
    assert c.verdict == "refuted"
    w = c.counterexample
    assert w.margin < 0 and w.rechecked_margin < 0 and w["t"] == 0.0
    # default gains: no violation on the grid, and the best margin is stated
    c0 = {c.id: c for c in gain_set_claims(default_gains())}["thrust-table1-corrected@gains"]
    assert c0.verdict == "checked" and 0 < c0.steps[0].evidence.best_margin < 50_000


def test_scopes_are_separated():
    assert all(c.scope != "gain-set" for c in general_claims())
    assert all(c.scope == "gain-set" for c in gain_set_claims(default_gains()))


def test_report_json_and_claims_json(tmp_path):
    gfile = tmp_path / "part1.toml"
    gfile.write_text(part1_gains_toml())
    runner = CliRunner()
    # one run writes both: the --json document to stdout and the report into --out
    res = runner.invoke(cli, ["report", "mars", "--gains", str(gfile), "--no-sim", "--json",
                              "--out", str(tmp_path / "out")], catch_exceptions=False)
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    by = {c["id"]: c for c in out["claims"]}
    c = by["paper-numbers-part1@gains"]
    assert c["verdict"] == "proved" and c["scope"] == "gain-set"
    for key in ("id", "equations", "paper", "derived", "verdict", "steps", "witness"):
        assert key in c
    assert c["steps"][0]["evidence"]["kind"] == "inequality"
    assert c["steps"][0]["evidence"]["box"]
    assert by["theorem1"]["witness"]["point"]["x(0) = x*"] == pytest.approx(0.5248885986564)
    # claims.json is the --json document without the provenance head (lgw_version, command,
    # gains, disturbance) every --json document starts with
    file_doc = json.loads((tmp_path / "out" / "claims.json").read_text())
    assert {k: out[k] for k in file_doc} == file_doc
    assert set(out) - set(file_doc) <= {"lgw_version", "command", "gains", "disturbance",
                                        "library_warnings"}
    # the findings give the command that reproduces one claim: --claim reports it alone
    cmd = {f["id"]: f["command"] for f in out["findings"]}["paper-numbers-part1@gains"] \
        if any(f["id"] == "paper-numbers-part1@gains" for f in out["findings"]) else None
    assert cmd is None  # these gains reproduce Part 1: not a finding
    one = runner.invoke(cli, ["report", "mars", "--gains", str(gfile), "--no-sim", "--claim",
                              "T2-printed", "--json"], catch_exceptions=False)
    doc = json.loads(one.output)
    assert [c["id"] for c in doc["claims"]] == ["T2-printed"]
    assert doc["findings"][0]["command"] == (f"lgw report mars --gains {gfile} --no-sim "
                                             "--claim T2-printed --json")
    assert doc["findings"][0]["witness"] and doc["claims"][0]["witness"]["rechecked_margin"] < 0
    bad = runner.invoke(cli, ["report", "mars", "--no-sim", "--claim", "no-such", "--json"])
    from lgw.theory.errors import ParameterError
    assert isinstance(bad.exception, ParameterError) and "--claim" in str(bad.exception)
    assert "T2-printed" in str(bad.exception)  # the valid ids are named


def test_report_needs_out_or_json():
    """Neither --out nor --json: a ParameterError (which ``lgw`` prints as one line
    ``error: ...`` with exit code 2), before anything is computed."""
    from lgw.theory.errors import ParameterError

    res = CliRunner().invoke(cli, ["report", "mars"])
    assert isinstance(res.exception, ParameterError) and "--out" in str(res.exception)


def other_gains_toml() -> str:
    """A second gain set unlike the defaults in every table a gain-set claim reads: [gains]
    (gains and exponents), [disturbance], [bounded] and [bounded-sat]."""
    from lgw.theory.mars.bounded import DEFAULT_BOUNDED
    from lgw.theory.mars.bounded_sat import DEFAULT_SAT

    def table(name, d, scale):
        lines = [f"[{name}]"]
        for k, val in d.items():
            if isinstance(val, list):
                lines.append(f"{k} = [{', '.join(repr(scale * x) for x in val)}]")
            else:
                lines.append(f"{k} = {val!r}")
        return "\n".join(lines) + "\n"
    bounded = {**DEFAULT_BOUNDED, "e1": 0.5}
    sat = {**DEFAULT_SAT, "e1": 0.5}
    return ("[gains]\nbeta1 = 0.3\nbeta2 = 0.002\nalpha1 = 0.9\nalpha2 = 0.001\nq1 = 0.7\n"
            "q2 = 1.3\ng1 = 0.8\ng2 = 1.2\n\n[disturbance]\na_max = 40.0\ntheta1 = 0.3\n"
            "theta2 = 0.2\n\n" + table("bounded", bounded, 1.1) + "\n"
            + table("bounded-sat", sat, 1.05))


def test_every_gain_set_claim_follows_the_gain_file(tmp_path):
    """Two gain sets through ``lgw report mars --json``: every claim in the gain-set scope
    reports different numbers for them (each reads the file's tables, the bounded laws' too),
    and names the table it judged."""
    from lgw.theory.mars.gains import gains_from_toml_text

    text = other_gains_toml()
    gains_from_toml_text(text)  # valid
    gfile = tmp_path / "other.toml"
    gfile.write_text(text)
    runner = CliRunner()
    docs = []
    for extra in ([], ["--gains", str(gfile)]):
        res = runner.invoke(cli, ["report", "mars", "--no-sim", "--json", *extra],
                            catch_exceptions=False)
        assert res.exit_code == 0, res.output
        docs.append({c["id"]: c for c in json.loads(res.output)["claims"]})
    a, b = docs
    scoped = sorted(cid for cid, c in a.items() if c["scope"] == "gain-set")
    assert scoped == sorted(cid for cid, c in b.items() if c["scope"] == "gain-set")
    assert {"bounded-invariants", "bounded-sat-bounds", "thrust-table1-printed@gains",
            "bounded-command-printed@gains", "tuning-rule@gains"} <= set(scoped)
    same = [cid for cid in scoped if a[cid]["numbers"] == b[cid]["numbers"]
            or not b[cid]["numbers"]]
    assert not same, f"gain-set claims whose numbers do not follow the gains: {same}"
    assert "the gain file's [bounded] table" in b["bounded-invariants"]["numbers"]["gains"]
    assert "DEFAULT_BOUNDED" in a["bounded-invariants"]["numbers"]["gains"]
    assert "[bounded-sat] table" in b["bounded-sat-bounds"]["numbers"]["gains"]
    # the general claims do not depend on the gain file
    gen = [cid for cid, c in a.items() if c["scope"] == "all-gains"]
    assert all(a[cid]["verdict"] == b[cid]["verdict"] for cid in gen)


def test_every_witness_lies_inside_the_hypotheses():
    """Every witness of every claim (steps, searches, remarks, cited hypotheses) that names an
    exponent of (16), (25) has it in the range the statement claims: 0 < q1, g1 < 1 < q2, g2
    (a witness outside the hypotheses refutes nothing)."""
    from fractions import Fraction

    from lgw.theory.evidence import Cited

    def walk(steps):
        for s in steps:
            yield s
            if isinstance(s.evidence, Cited):
                yield from walk(s.evidence.hypotheses)

    ranges = {"q1": (0, 1), "g1": (0, 1), "q2": (1, 1e9), "g2": (1, 1e9)}
    seen = 0
    for c in all_claims(default_gains()):
        for s in walk(c.steps + c.searches + c.remarks):
            w = s.evidence.witness
            if w is None:
                continue
            for name, (lo, hi) in ranges.items():
                if name in w.point:
                    seen += 1
                    assert lo < Fraction(str(w.point[name])) < hi, (c.id, name, w.point)
    assert seen >= 5
