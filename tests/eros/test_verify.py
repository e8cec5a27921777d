"""``lgw verify eros`` (lgw.tuning.eros.verify on the shared lgw.tuning.verifying): seed 002's
per-axis reaching and reaching + sliding times on Hypothesis-drawn cases of the envelope, a
tuned file's certificate promises checked over its own envelope, a provoked violation whose
printed reproduction reproduces it with a readable witness (no denormals), a case the batched
RK4 cannot carry re-flown by the reference route (only what neither carries is excluded),
gains files without e_floor accepted (its documented default)."""

from __future__ import annotations

import json
import shlex

import numpy as np
import pytest
from lgw.theory.eros.gains import default_gains, gains_to_toml, load_gains
from lgw.tuning.eros import verify as V
from lgw.tuning.verifying import Context, run_checks

from tests.test_cli_conventions import assert_one_error, run_lgw


def _json(args):
    r = run_lgw(["verify", "eros", *args, "--json"])
    assert r.exception is None, r.exception
    return r.code, json.loads(r.stdout)


def _cert(**kw):
    c = {"law": "ftsmc-sign", "e_max": 2.0, "v_max": 0.1, "dbar": 0.0, "bound_t_total": 30.0,
         "u_max": 100.0, **kw}
    return "\n[certificate]\n" + "\n".join(f"{k} = {json.dumps(v)}" for k, v in c.items())


def test_default_gains_hold_and_certificate_claims_do_not_apply():
    code, d = _json(["--examples", "2", "--min-cases", "5"])
    assert code == 0, d
    by = {c["claim"]: c for c in d["claims"]}
    for name in ("reaching-known", "time-known", "reaching-unknown", "time-unknown"):
        n = by[name]["cases"]
        assert by[name]["verdict"] == "holds" and n["informative"] >= 5
        assert n["informative"] + n["excluded"] == n["total"] and by[name]["margin"] >= 0
    for name in ("certificate-time", "certificate-u"):
        assert by[name]["verdict"] == "not-applicable"
        assert "no [certificate]" in by[name]["why"]


def test_provoked_violation_prints_a_reproduction_that_reproduces_it():
    r = run_lgw(["verify", "eros", "--claim", "time-known", "--scale", "time-known=0.5",
                 "--examples", "2"])
    assert r.code == 1, r.stdout
    repro = next(ln.split("reproduce: ", 1)[1] for ln in r.stdout.splitlines()
                 if "reproduce: " in ln)
    args = shlex.split(repro)
    assert args[:3] == ["lgw", "verify", "eros"] and "simulate" not in args
    w = dict(kv.split("=") for kv in args[args.index("--witness") + 1].split(","))
    x = np.array([float(v) for v in w.values()])
    assert not np.any((x != 0) & (np.abs(x) < 1e-6)), w  # no denormals, no crumbs
    observed = next(ln for ln in r.stdout.splitlines() if ln.strip().startswith("observed:"))
    again = run_lgw(args[1:])
    assert again.code == 1 and observed in again.stdout, again.stdout


def test_false_certificate_promises_are_violated_over_its_envelope(tmp_path):
    """A tuned file promising tracking in 1 s and |u_i| <= 0.5 m/s^2: both violated, from
    states of the certificate's own envelope (|e_i(0)| <= 2 m, |e_i'(0)| <= 0.1 m/s)."""
    p = tmp_path / "g.toml"
    p.write_text(gains_to_toml(default_gains()) + _cert(bound_t_total=1.0, u_max=0.5))
    code, d = _json(["--gains", str(p), "--claim", "certificate-time", "--claim",
                     "certificate-u", "--examples", "2"])
    assert code == 1
    assert d["envelope"]["boxes"][0]["hi"][:6] == [2.0, 2.0, 2.0, 0.1, 0.1, 0.1]
    for c in d["claims"]:
        assert c["verdict"] == "violated", c
        row = c["witness"]["row"]
        assert all(abs(v) <= 2.0 for v in row[:3]) and all(abs(v) <= 0.1 for v in row[3:6])
    u = next(c for c in d["claims"] if c["claim"] == "certificate-u")
    assert u["witness"]["bound"] == 0.5 and u["witness"]["observed"] > 0.5


def test_e_floor_is_optional_and_certificate_values_are_checked_by_name(tmp_path):
    g = default_gains()
    text = "\n".join(ln for ln in gains_to_toml(g).splitlines() if "e_floor" not in ln)
    p = tmp_path / "g.toml"
    p.write_text(text + "\n")
    assert load_gains(p).e_floor == g.e_floor  # docs/eros.md: default 1e-4 m
    for bad in ('"1.0"', "[1.0]", "-2.0"):
        p.write_text(text + f"\n[certificate]\nbound_t_total = {bad}\n")
        r = run_lgw(["verify", "eros", "--gains", str(p), "--claim", "time-known"])
        assert_one_error(r)
        assert "certificate.bound_t_total" in r.stderr


def test_k_not_above_dbar_is_not_applicable():
    g = default_gains().replace(k=0.04)  # below DIST_AMP = 0.05: (18) gives no unknown-D bound
    res = {r.claim: r for r in run_checks("eros", g, claim=("reaching-unknown",),
                                          examples=1)}
    r = res["reaching-unknown"]
    assert r.verdict == "not-applicable" and "k = 0.04 <= dbar" in r.why


def _nonfinite_first(monkeypatch, reference_too: bool):
    """Make the batched RK4 report case 0 of every batch nonfinite (and the reference route
    too, if asked): the judge must re-fly it, or exclude it and say why."""
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


X = np.array([[5.0, -3.0, 1.0, 0.1, 0.0, -0.2, 1.0], [2.0, 2.0, 2.0, 0.0, 0.0, 0.0, 0.0]])


@pytest.mark.parametrize("reference_too", [False, True])
def test_a_case_rk4_cannot_carry_goes_to_the_reference_route(monkeypatch, reference_too):
    _nonfinite_first(monkeypatch, reference_too)
    ctx = Context(default_gains(), {}, {}, 0)
    j = V.judge(ctx, "known", X)["time-known"]
    if reference_too:
        assert j.excluded == [V.NO_INTEGRATOR, None]
    else:
        assert j.excluded == [None, None] and j.fallback.tolist() == [True, False]
        assert np.isfinite(j.observed[0]).all()


@pytest.mark.parametrize("args", [["--min-cases", "0"], ["--scale", "nope=2"],
                                  ["--scale", "time-known=-1"], ["--scale", "time-known=nan"],
                                  ["--profile", "fast"]])
def test_bad_option_is_one_error_line_exit_2(args):
    assert_one_error(run_lgw(["verify", "eros", *args]))


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
    err = capsys.readouterr().err
    assert e.value.code == 2 and "row 2" in err and "ez" in err
