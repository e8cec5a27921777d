"""The shared verify machinery (lgw.tuning.verifying), without flying anything: one margin
convention, evidence that informs (only cases that can violate a claim count), computed
verdicts, witnesses parsed without eval and printed exactly, envelopes and certificate values
checked by name, and options refused where they do not apply (exit 2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from lgw.theory.errors import ParameterError
from lgw.tuning import verifying as VF

from tests.test_cli_conventions import assert_one_error, run_lgw

CLAIM = VF.Claim("c", "(1)", "g", "time to the band", "T", "s", "starts inside the band",
                 "one step")
VARS = (VF.Var("a", "m", nonzero=True), VF.Var("b", "m/s"))


def test_margin_is_bound_minus_observed_over_bound():
    m = VF.margins(np.array([1.0, 3.0, np.inf, np.nan, 0.5, 0.2]),
                   np.array([2.0, 2.0, 2.0, 2.0, 0.0, 0.0]))
    assert m[0] == pytest.approx(0.5) and m[1] == pytest.approx(-0.5)
    assert m[2] == -np.inf and np.isnan(m[3])
    assert m[4] == -np.inf  # bound 0, observed above it: a violation without a scale
    # a bound of 0 with its own reference (lunar's V2 step over V2(0))
    assert VF.margins(np.array([0.2]), np.array([0.0]), np.array([1.0]))[0] == pytest.approx(-0.2)
    assert VF.margins(np.array([-1.0]), np.array([0.0]))[0] == np.inf


def _judged(obs, bnd, inf, excl=None):
    n = len(obs)
    return VF.Judged(np.arange(2 * n, dtype=float).reshape(n, 2) + 1, np.array(obs, float),
                     np.array(bnd, float), np.array(inf, bool), excl or [None] * n, 0.05)


def test_only_cases_that_can_violate_count():
    t = VF.Tally(CLAIM, ("x", "y"))
    least, bad = t.add(_judged([[1, 1], [0, 0], [1, 9]], [[2, 2], [2, 2], [2, 2]],
                               [[True, False], [False, False], [False, False]],
                               [None, None, "no integrator"]), 1.0)
    assert (t.total, t.informative) == (3, 1)
    assert t.excluded == {"cannot violate: starts inside the band": 1, "no integrator": 1}
    assert least == pytest.approx(0.5) and bad is None  # the excluded case's 9 s is not judged
    # an uninformative value that violates all the same is a violation, and informative
    least, bad = t.add(_judged([[0, 5]], [[2, 2]], [[False, False]]), 1.0)
    assert t.informative == 2 and bad["axis"] == "y" and bad["margin"] == pytest.approx(-1.5)
    assert bad["observed"] == 5 and bad["measured"] == pytest.approx(5.05)
    # --scale shrinks the bound; a certificate's promise caps it
    t2 = VF.Tally(CLAIM, ("x",))
    _, bad = t2.add(_judged([[1.5]], [[2.0]], [[True]]), 0.5)
    assert bad["bound"] == 1.0
    _, bad = t2.add(_judged([[1.5]], [[2.0]], [[True]]), 1.0, cap=1.2)
    assert bad["bound"] == 1.2


def _result(**kw):
    base = dict(total=40, informative=35, excluded={"x": 5}, min_cases=30, max_excluded=0.5)
    base.update(kw)
    return VF.ClaimResult("c", "(1)", "o", "b", "s", "?", **base)


@pytest.mark.parametrize("kw, na, found, search, verdict, why", [
    ({}, None, None, False, "holds", ""),
    ({"informative": 29}, None, None, False, "inconclusive", "29 informative cases < --min"),
    ({"informative": 10, "excluded": {"x": 30}}, None, None, False, "inconclusive",
     "informative"),
    ({"informative": 31, "excluded": {"x": 60}, "total": 91}, None, None, False,
     "inconclusive", "60 of 91 cases excluded"),
    ({}, "no [disturbance]", None, False, "not-applicable", "not applicable, because no"),
    ({}, None, {"margin": -0.1, "confirmed": True}, False, "violated", ""),
    ({}, None, {"margin": -0.1, "confirmed": False, "rechecked_margin": 0.01}, False,
     "inconclusive", "does not confirm"),
    ({}, None, None, True, "violated", ""),
])
def test_verdicts_are_computed_never_holds_on_missing_evidence(kw, na, found, search, verdict,
                                                                why):
    r = _result(**kw)
    VF.decide(r, na, found, search)
    assert r.verdict == verdict and why in r.why


def test_exit_codes():
    def rs(*v):
        return [VF.ClaimResult("c", "", "", "", "", x) for x in v]
    assert VF.exit_code(rs("holds", "not-applicable")) == 0
    assert VF.exit_code(rs("holds", "inconclusive")) == 4
    assert VF.exit_code(rs("inconclusive", "violated")) == 1


def test_witness_round_trip_exact_and_named_errors():
    extras = (VF.Extra("kind", ("worst", "random")), VF.Extra("case", "int"))
    w = VF.parse_witness("a=-0.1,b=3.0000000000000004,kind=random,case=2", VARS, extras)
    assert w.row == (-0.1, 3.0000000000000004) and w.extra == {"kind": "random", "case": 2}
    text = VF.format_witness(w.row, w.extra, VARS)
    assert VF.parse_witness(text, VARS, extras) == w
    for bad, name in (("a=1", "--witness"), ("a=1,b=x", "--witness b"),
                      ("a=1,b=nan", "--witness b"), ("a=1,b=2,c=3", "--witness"),
                      ("a=1,b=2,kind=best", "--witness kind"), ("a=1,a=2,b=1", "--witness"),
                      ("a=__import__('os'),b=1", "--witness a")):
        with pytest.raises(ParameterError) as e:
            VF.parse_witness(bad, VARS, extras)
        assert e.value.name == name


ENV = VF.Envelope("box", ("a", "b"), (((-2.0, -1.0), (3.0, 1.0)),))


@settings(max_examples=60, database=None, deadline=None)
@given(X=VF.state_batches(ENV, VARS, 1, 4))
def test_states_lie_in_the_envelope_without_subnormals_or_forbidden_zeros(X):
    assert X.shape[1] == 2 and 1 <= len(X) <= 4
    assert all(ENV.contains(row) for row in X)
    assert np.all(X[:, 0] != 0.0)  # a is nonzero
    tiny = (X != 0) & (np.abs(X) < np.finfo(float).tiny)
    assert not tiny.any()


def test_envelope_file_is_checked_by_name(tmp_path):
    p = tmp_path / "env.toml"
    p.write_text('[envelope]\nname = "mine"\na = [-1.0, 0.5]\n')
    env = VF.read_envelope(p, VARS, ENV)
    assert env.boxes == (((-1.0, -1.0), (0.5, 1.0)),) and env.name == "mine"
    p.write_text('[[envelope.box]]\na = [0.5, 1.0]\n[[envelope.box]]\nb = [0.0, 0.5]\n')
    assert len(VF.read_envelope(p, VARS, ENV).boxes) == 2
    for text, name in (('[envelope]\na = "wide"\n', "envelope.a"),
                       ("[envelope]\na = [1.0]\n", "envelope.a"),
                       ("[envelope]\na = [2.0, 1.0]\n", "envelope.a"),
                       ("[envelope]\nc = [0.0, 1.0]\n", "envelope.c"),
                       ("[envelope]\na = [0.0, inf]\n", "envelope.a[1]"),
                       ("[other]\na = 1\n", "--envelope")):
        p.write_text(text)
        with pytest.raises(ParameterError) as e:
            VF.read_envelope(p, VARS, ENV)
        assert e.value.name.startswith(name), (text, e.value.name)


@pytest.mark.parametrize("value", ["90", [90.0], math.nan, -1.0, True])
def test_certificate_values_are_checked_by_name(value):
    with pytest.raises(ParameterError) as e:
        VF.cert_number({"landing_time_bound": value}, "landing_time_bound", "g.toml")
    assert e.value.name == "--gains g.toml certificate.landing_time_bound"
    assert VF.cert_number({}, "landing_time_bound", "g.toml") is None
    with pytest.raises(ParameterError):
        VF.certificate({"certificate": "yes"}, "g.toml")


@pytest.mark.parametrize("system, args", [
    ("mars", ["--witness", "rx=1,ry=1,rz=1,vx=0,vy=0,vz=0", "--examples", "3"]),
    ("mars", ["--witness", "rx=1,ry=1,rz=1,vx=0,vy=0,vz=0", "--seed", "3"]),
    ("lunar", ["--witness", "x1=1,x2x=0,x2y=0,x2z=0", "--domain", "whole"]),
    ("eros", ["--witness", "ex=1,ey=0,ez=0,vx=0,vy=0,vz=0,phase=0", "--profile",
              "thorough"]),
    ("eros", ["--witness", "ex=1,ey=0,ez=0,vx=0,vy=0"]),
    ("mars", ["--domain", "whole", "--envelope", "tests/mars/golden/none.toml"]),
    ("lunar", ["--scale", "nope=0.5"]),
    ("lunar", ["--scale", "(19a)=0.5", "--scale", "(19a)=0.4"]),
    ("eros", ["--max-excluded", "1.5"]),
    ("eros", ["--claim", "nope"]),
    ("mars", ["--random", "--seed", "2"]),
])
def test_options_that_do_not_apply_are_refused_exit_2(system, args):
    r = run_lgw(["verify", system, *args])
    assert_one_error(r)


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
@pytest.mark.parametrize("sub", ["", "sub"])
def test_bad_plot_path_is_exit_2_before_any_work(tmp_path, sub, system, monkeypatch):
    """--plot naming a file, or a folder below a file: one error line, exit 2, nothing written
    and nothing flown (checked by the shared command before the work)."""
    import importlib

    def no_work(*a, **k):
        raise AssertionError("flew before --plot was checked")

    monkeypatch.setattr(importlib.import_module(f"lgw.tuning.{system}.verify"), "judge",
                        no_work)
    f = tmp_path / "a_file"
    f.write_text("x")
    r = run_lgw(["verify", system, "--plot", str(f / sub if sub else f)])
    assert_one_error(r)
    assert [p.name for p in tmp_path.iterdir()] == ["a_file"] and f.read_text() == "x"


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_every_verify_option_changes_what_is_computed_or_is_refused(system, tmp_path):
    """In the spirit of python-control's kwargs_test.py: each option of ``lgw verify SYSTEM``
    set alone to a valid non-default value either changes the planned job (its fingerprint)
    or is refused with a named error; an accepted and ignored option is a defect."""
    from lgw.tuning.spec import NO_PROBE, fingerprint, option_fields, probe_value
    from lgw.tuning.system import get_system
    from lgw.tuning.vocabulary import PROBE_GAINS

    sysobj = get_system(system)
    mod = sysobj.verb("verify").load()
    base = fingerprint(mod.plan(mod.Options(), sysobj))
    env = tmp_path / "env.toml"
    first = mod.Options.VARIABLES[0].name
    env.write_text(f"[envelope]\n{first} = [0.5, 1.0]\n")
    gains = tmp_path / "g.toml"
    gains.write_text(sysobj.gains_module().example())
    special = {"envelope": env, "database": tmp_path / "db"}
    seen = []
    for f, o in option_fields(mod.Options):
        if o.execution:
            continue
        v = special.get(f.name, o.probe)
        v = gains if v == PROBE_GAINS else v
        if v is NO_PROBE or v is None:
            v = probe_value(f, o)
        try:
            opts = mod.Options(**{f.name: v})
        except ParameterError:
            seen.append((f.name, "refused"))
            continue
        assert fingerprint(mod.plan(opts, sysobj)) != base, f"{o.flag} = {v!r} is ignored"
        seen.append((f.name, "changes"))
    names = {n for n, _ in seen}
    assert {"gains", "domain", "envelope", "witness", "claim", "scale", "max_excluded",
            "min_cases", "examples", "profile", "seed", "random", "database"} <= names
