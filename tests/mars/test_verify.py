"""``lgw verify mars`` (lgw.tuning.mars.verify on the shared lgw.tuning.verifying): evidence that
informs (cases that start inside a band do not count), computed verdicts with exit 0 / 1 / 4,
a provoked violation whose printed reproduction reproduces it, files lgw writes accepted
(claims without their inputs are not applicable), certificate values checked by name, the
search over the envelope (not the whole domain) by default."""

from __future__ import annotations

import json
import shlex
from pathlib import Path

import numpy as np
import pytest
from lgw.theory.mars.gains import default_gains, gains_from_dict, gains_to_toml
from lgw.tuning.mars import verify as MV
from lgw.tuning.verifying import Context, run_checks

from tests.test_cli_conventions import assert_one_error, run_lgw

TUNED = Path(__file__).parents[2] / "tuning" / "mars" / "data" / "tuned_tf90_50kN.toml"
FAST = ["--examples", "3", "--min-cases", "2"]
# A gain set for which the paper's max{T1*, T2*} is not a landing-time bound (the engine's
# worst point of tests/mars/test_properties.py::HARD_LANDING): T1* = 86.3 s, T2* = 28.4 s,
# and a landing from s2(0) = 1e9 m/s takes 91.9 s.
BALANCED = {"gains": {"beta1": 0.2, "beta2": 0.01, "alpha1": 0.5, "alpha2": 0.02, "q1": 0.9,
                      "q2": 1.5, "g1": 0.7, "g2": 1.5},
            "disturbance": {"a_max": 20.0, "theta1": 0.2, "theta2": 0.1}}


def _json(args):
    r = run_lgw(["verify", "mars", *args, "--json"])
    assert r.exception is None, r.exception
    return r.code, json.loads(r.stdout)


def test_undisturbed_claims_hold_on_informative_cases_of_the_envelope(tmp_path):
    code, d = _json(["--claim", "T2-26", "--claim", "reaching-16", *FAST, "--plot",
                     str(tmp_path / "p")])
    assert code == 0, d
    png = tmp_path / "p" / "verify_mars.png"  # observed against bound, written with the run
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert d["command"] == "verify mars" and "gains" in d and d["lgw_version"]
    assert list(d)[:3] == ["lgw_version", "command", "gains"]
    assert d["domain"] == "envelope" and d["envelope"]["name"] == "table3+table2"
    for c in d["claims"]:
        n = c["cases"]
        assert c["verdict"] == "holds" and n["informative"] >= 2
        assert n["informative"] + n["excluded"] == n["total"]
        assert c["margin"] >= 0 and c["worst"]["row"] is not None
        # the search ran over the envelope's boxes, not the whole domain
        assert {s["domain_name"] for s in c["search"]} == {"box 1", "box 2"}


def test_cases_inside_the_band_do_not_count():
    """Seed 000's (31) band for the default gains is 2378 m wide: a state of the envelope that
    starts inside it (and any whose s2 starts inside (39)) cannot violate the entry time, so it
    is excluded with that reason; with too few informative cases the claim is inconclusive,
    never holds (exit 4)."""
    g = default_gains()
    ctx = Context(g, {"dt": 0.05, "eps": 0.05}, {}, 0)
    X = np.array([[-500.0, 1000.0, 1200.0, 10.0, -50.0, -40.0]])
    j = MV.judge(ctx, "disturbed", X)
    assert not j["s1-31-45"].informative.any()  # |r_i| < 2378 m on every axis
    code, d = _json(["--claim", "s1-31-45", "--examples", "2", "--min-cases", "1"])
    c = d["claims"][0]
    assert code == 4 and c["verdict"] == "inconclusive"
    assert c["cases"]["informative"] == 0 < c["cases"]["total"]
    assert any(k.startswith("cannot violate: |r_i| is inside the (31) band")
               for k in c["cases"]["excluded_reasons"])


def test_provoked_violation_prints_a_reproduction_that_reproduces_it():
    """T2_exact x 0.3: a simulated case over its bound, confirmed at dt/2; the printed
    ``lgw verify`` command flies that state alone and exits 1 with the same observed time."""
    r = run_lgw(["verify", "mars", "--claim", "T2-26", "--scale", "T2-26=0.3",
                 "--examples", "3"])
    assert r.code == 1, r.stdout
    assert "observed:" in r.stdout and "bound:" in r.stdout and "state: rx = " in r.stdout
    assert "gains: the built-in gain set" in r.stdout
    repro = next(ln.split("reproduce: ", 1)[1] for ln in r.stdout.splitlines()
                 if "reproduce: " in ln)
    args = shlex.split(repro)
    assert args[:3] == ["lgw", "verify", "mars"] and "--witness" in args
    observed = next(ln for ln in r.stdout.splitlines() if ln.strip().startswith("observed:"))
    again = run_lgw([*args[1:]])
    assert again.code == 1, again.stdout
    assert observed in again.stdout  # the same observed time on the same axis
    # no crumbs in the witness: every coordinate as Hypothesis and the rounding left it
    w = args[args.index("--witness") + 1]
    assert "e-" not in w


def test_tuned_file_without_disturbance_names_the_claims_that_do_not_apply():
    r = run_lgw(["verify", "mars", "--gains", str(TUNED), "--claim", "s2-39-40",
                 "--claim", "s1-31-45"])
    assert r.code == 0, r.stderr
    assert r.stdout.count("not applicable, because the gains file has no [disturbance]") == 2


def test_bounded_law_file_is_not_applicable(tmp_path):
    p = tmp_path / "b.toml"
    p.write_text(gains_to_toml(default_gains()) + "\n[bounded]\nc1 = 1.0\n")
    res = run_checks("mars", p)
    assert {r.verdict for r in res} == {"not-applicable"}
    assert "[bounded] law" in res[0].why


@pytest.mark.parametrize("value", ['"90"', "[90.0]", "nan", "-3.0", "true"])
def test_certificate_values_are_checked_by_name_exit_2(tmp_path, value):
    p = tmp_path / "g.toml"
    p.write_text(gains_to_toml(default_gains()) + f"\n[certificate]\nlanding_time_bound = "
                 f"{value}\n")
    r = run_lgw(["verify", "mars", "--gains", str(p), "--claim", "s2-39-40"])
    assert_one_error(r)
    assert "landing_time_bound" in r.stderr


def test_certificate_promise_caps_the_bound_and_its_envelope_is_searched(tmp_path):
    """A promise shorter than a reachable landing is what is checked, over the certificate's
    own envelope (one small box here)."""
    g = gains_from_dict(BALANCED)
    p = tmp_path / "g.toml"
    p.write_text(gains_to_toml(g) + "\n[certificate]\nlanding_time_bound = 20.0\n"
                 "[certificate.envelope]\nname = \"small\"\n"
                 "boxes_lo = [[100.0, 100.0, 100.0, -1.0, -1.0, -1.0, 1905.0]]\n"
                 "boxes_hi = [[200.0, 200.0, 200.0, 1.0, 1.0, 1.0, 1905.0]]\n")
    code, d = _json(["--gains", str(p), "--claim", "landing-T2+T1", "--examples", "2"])
    c = d["claims"][0]
    assert code == 1 and c["verdict"] == "violated"
    assert c["promise"]["value"] == 20.0 and c["worst"]["bound"] <= 20.0
    assert d["envelope"]["boxes"] == [{"lo": [100.0, 100.0, 100.0, -1.0, -1.0, -1.0],
                                       "hi": [200.0, 200.0, 200.0, 1.0, 1.0, 1.0]}]
    row = c["witness"]["row"]
    assert all(100.0 <= x <= 200.0 for x in row[:3]) and all(abs(v) <= 1 for v in row[3:])


def test_search_on_the_envelope_stays_inside_it():
    g = gains_from_dict(BALANCED)
    env = MV.default_envelope(g, None)
    ctx = Context(g, {"dt": 0.05, "eps": 0.05}, {"T2-26": 0.5}, 0)
    found = MV.search(ctx, "T2-26", env, "ci")
    refuted = [s for s in found if s["status"] == "refuted"]
    assert refuted, [s["best_margin"] for s in found]
    for s in refuted:
        assert env.contains(s["witness"]["row"]), s["witness"]["row"]
        assert s["witness"]["rechecked_margin"] < 0


def test_whole_domain_is_a_named_level():
    code, d = _json(["--claim", "reaching-16", "--domain", "whole", *FAST])
    assert d["domain"] == "whole" and d["envelope"]["name"] == "whole domain"
    assert {s["domain_name"] for s in d["claims"][0]["search"]} == {"whole domain"}


def test_landing_max_in_place_of_the_sum_is_violated_on_the_whole_domain(monkeypatch):
    """The paper's max{T1*, T2*} as the landing bound: found by the whole-domain search,
    shrunk, re-checked by LSODA (bounds patched for this test only)."""
    import lgw.theory.mars.bounds as B

    orig = B.axis_bounds

    def paper_max(g):
        out = orig(g)
        for ax in out.values():
            ax["landing_time_bound"] = max(ax["T1_exact"], ax["T2_exact"])
        return out

    monkeypatch.setattr(B, "axis_bounds", paper_max)
    g = gains_from_dict(BALANCED)
    ctx = Context(g, {"dt": 0.05, "eps": 0.05}, {}, 0)
    found = MV.search(ctx, "landing-T2+T1", None, "ci")
    s = next(s for s in found if s["status"] == "refuted")
    assert s["witness"]["confirmed"] and s["witness"]["rechecked_margin"] < 0
