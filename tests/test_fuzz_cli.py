"""Fuzzing the command line (issue 14): random bytes, random TOML, random CSV and random option
values into every command, in-process through ``lgw.tuning.cli.main``.

Each run must exit 0 or 2; on 2 exactly one line ``error: ...`` on stderr, no traceback, and
nothing written under ``--out``; on 0 any JSON printed is strict.  The number of examples comes
from the Hypothesis profile (tests/conftest.py: ``dev``/``ci`` 30 per test, a few seconds;
``--hypothesis-profile=thorough`` 1000).  The heavy work behind a command (the campaign, the
tuner, the SOCP, the comparison) is replaced by a stub that ends the run with exit 0: the fuzz
loop exercises every loader and every check in front of it without compiling numba; the
loaders are also fuzzed directly, and ``bounds`` (cheap) runs for real.
"""

from __future__ import annotations

import json
import math
import string
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lgw.sim.mars.campaign import CSV_COLUMNS, read_states_csv
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import AXIS_GAINS, DISTURBANCE_KEYS, EXPONENTS, load_gains

from tests.test_cli_conventions import Run, assert_one_error, run_lgw

FUNCTION_SCOPED = settings(suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                  HealthCheck.too_slow])


def _strict(text: str):
    def no(name: str):
        raise AssertionError(f"non-strict JSON token {name}")
    return json.loads(text, parse_constant=no)


def check_run(r: Run, out: Path | None) -> None:
    """The fuzz oracle: exit 0 or 2; on 2 one error line and nothing written; never a
    traceback; printed JSON is strict."""
    assert r.exception is None, f"escaped main (a traceback for the user): {r.exception!r}"
    assert r.code in (0, 2), (r.code, r.stdout[-500:], r.stderr[-500:])
    assert "Traceback" not in r.stderr
    if r.code == 2:
        assert_one_error(r)
        if out is not None:
            assert not out.exists(), f"{out} written on failure"
    elif r.stdout.lstrip().startswith("{"):
        _strict(r.stdout)


class _Stop(SystemExit):
    """Raised by the stubs: validation passed and the heavy work would start (exit 0)."""

    def __init__(self) -> None:
        super().__init__(0)


def _stub(*a, **k):
    raise _Stop()


@pytest.fixture
def no_heavy_work(monkeypatch):
    import lgw.sim.mars.campaign as scamp
    import lgw.sim.mars.optimal as so
    import lgw.sim.mars.reference as sr
    import lgw.tuning.mars.cmd_compare as cc
    import lgw.tuning.mars.cmd_simulate as cs
    import lgw.tuning.mars.cmd_tune as ct
    import lgw.tuning.options as topt

    for mod, name in ((scamp, "run_campaign"), (cs, "fig6"), (sr, "simulate_reference"),
                      (ct, "tune"), (so, "solve_fuel_optimal"), (so, "min_time"),
                      (cc, "run_comparison"), (topt, "check_scheduler")):
        monkeypatch.setattr(mod, name, _stub)


# --- strategies -------------------------------------------------------------------------------

scalars = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True), st.floats(0.0, 3.0),
    st.integers(-(10**400), 10**400), st.integers(-5, 5), st.booleans(),
    st.text(max_size=8), st.sampled_from([1e-308, 5e-324, 1e300, 1e6, 2046.0, 2047.0,
                                          0.999999999, 1.000000001, 0.0, -0.0]))
values = st.one_of(scalars, st.lists(scalars, max_size=4),
                   st.lists(st.lists(scalars, max_size=2), max_size=2))


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) \
            else repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    return "[" + ", ".join(_toml_value(x) for x in v) + "]"


@st.composite
def toml_docs(draw) -> str:
    """Gains documents near the valid ones: the right keys mostly, random values, sometimes a
    missing, unknown or duplicated key, a stray table, a certificate, broken syntax."""
    lines = []
    for table, keys in (("gains", AXIS_GAINS + EXPONENTS), ("disturbance", DISTURBANCE_KEYS)):
        if table == "disturbance" and draw(st.booleans()):
            continue
        lines.append(f"[{table}]")
        for k in keys:
            if draw(st.integers(0, 9)) == 0:
                continue  # missing key
            lines.append(f"{k} = {_toml_value(draw(values))}")
        if draw(st.integers(0, 7)) == 0:
            lines.append(f"{draw(st.sampled_from(keys + ('zeta', 'Beta1')))} = 1.0")
    if draw(st.integers(0, 3)) == 0:
        lines += ["[certificate]", f"feasible = {_toml_value(draw(values))}",
                  "[certificate.request]", f"tf = {_toml_value(draw(values))}"]
    if draw(st.integers(0, 7)) == 0:
        lines.insert(draw(st.integers(0, len(lines))), draw(st.text(max_size=12)))
    text = "\n".join(lines) + "\n"
    return ("\ufeff" if draw(st.integers(0, 5)) == 0 else "") + text


cells = st.one_of(st.floats(allow_nan=True, allow_infinity=True).map(repr),
                  st.integers(-10**6, 10**6).map(str),
                  st.sampled_from(["", " ", "nan", "inf", "-inf", "1e999", "0", "-0", "1_0",
                                   "1905", "x", '"3"', "1,5"]),
                  st.text(alphabet=string.printable, max_size=6))


@st.composite
def csv_docs(draw) -> bytes:
    cols = list(draw(st.permutations(CSV_COLUMNS)))
    if draw(st.integers(0, 4)) == 0:
        cols.pop(draw(st.integers(0, len(cols) - 1)))
    if draw(st.integers(0, 4)) == 0:
        cols.append(draw(st.sampled_from(list(CSV_COLUMNS) + ["note", " rx "])))
    rows = [",".join(cols)]
    for _ in range(draw(st.integers(0, 3))):
        n = len(cols) + draw(st.sampled_from([0, 0, 0, -1, 1]))
        rows.append(",".join(draw(cells) for _ in range(max(n, 0))))
    text = draw(st.sampled_from(["\n", "\r\n"])).join(rows) + "\n"
    raw = text.encode("utf-8", "surrogatepass") if draw(st.booleans()) else text.encode(
        "utf-8", "replace")
    prefix = draw(st.sampled_from([b"", b"", b"\xef\xbb\xbf", b"\xff\xfe", b"\x00"]))
    return prefix + raw


# --- loaders, directly ------------------------------------------------------------------------

@FUNCTION_SCOPED
@given(data=st.one_of(st.binary(max_size=300), toml_docs().map(lambda t: t.encode("utf-8",
                                                                                    "replace"))))
def test_fuzz_gains_loader(tmp_path, data):
    p = tmp_path / "g.toml"
    p.write_bytes(data)
    try:
        g = load_gains(p)
    except ParameterError as e:
        assert "\n" not in str(e)
        return
    for k in AXIS_GAINS:
        assert np.all(np.isfinite(getattr(g, k))) and np.all(getattr(g, k) > 0)


@FUNCTION_SCOPED
@given(data=st.one_of(st.binary(max_size=200), csv_docs()))
def test_fuzz_states_loader(tmp_path, data):
    p = tmp_path / "s.csv"
    p.write_bytes(data)
    try:
        r0, v0, m0 = read_states_csv(p)
    except ParameterError as e:
        assert e.name.startswith("--initial-states") and "\n" not in str(e)
        return
    n = len(m0)
    assert n >= 1 and r0.shape == (n, 3) and v0.shape == (n, 3)
    assert np.all(np.isfinite(r0)) and np.all(np.isfinite(v0)) and np.all(m0 > 0)


# --- commands ---------------------------------------------------------------------------------

@FUNCTION_SCOPED
@given(data=st.one_of(st.binary(max_size=300), toml_docs().map(lambda t: t.encode("utf-8",
                                                                                    "replace"))))
def test_fuzz_bounds_with_random_gains_files(tmp_path_factory, data):
    """``lgw bounds mars`` runs for real (it is cheap): any accepted file gives strict JSON and
    the same document in --out/bounds.json."""
    d = tmp_path_factory.mktemp("b")
    p = d / "g.toml"
    p.write_bytes(data)
    out = d / "out"
    r = run_lgw(["bounds", "mars", "--gains", str(p), "--json", "--out", str(out)])
    check_run(r, out)
    if r.code == 0:
        doc = _strict(r.stdout)
        assert all(isinstance(v, float) and math.isfinite(v)
                   for ax in "xyz" for v in doc[ax].values())
        assert _strict((out / "bounds.json").read_text()) == doc


@FUNCTION_SCOPED
@given(data=csv_docs())
def test_fuzz_simulate_with_random_states_files(tmp_path_factory, no_heavy_work, data):
    d = tmp_path_factory.mktemp("s")
    p = d / "s.csv"
    p.write_bytes(data)
    out = d / "out"
    check_run(run_lgw(["simulate", "mars", "--initial-states", str(p), "--out", str(out)]),
              out)


option_values = st.one_of(
    st.sampled_from(["nan", "inf", "-inf", "1e309", "-1", "0", "-0", "1", "0.5", "2", "1e-300",
                     "1e300", "50000", "60", "0x10", "1_000", "", " ", "--", "true",
                     str(2**64), str(-(2**63)), "corrected", "table2", "axis", "none"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-(10**30), 10**30).map(str),
    st.text(max_size=10))

# the options fuzzed per command (the others keep their defaults)
FUZZ_OPTIONS = {
    ("simulate", "mars"): ["--law", "--dispersion", "--cases", "--seed", "--disturbance",
                           "--dist-amplitude", "--thrust-max", "--limit", "--drag",
                           "--guidance-drag", "--isp", "--m-dry", "--dt", "--method", "--rtol",
                           "--atol", "--max-step", "--eps", "--t-max", "--land-r", "--land-v",
                           "--workers", "--scheduler", "--scheduler-timeout"],
    ("tune", "mars"): ["--tf", "--thrust-max", "--limit", "--envelope", "--a-max",
                       "--neighborhood", "--theta1", "--theta2", "--bound", "--objective",
                       "--keep-out", "--brake-fraction", "--seed"],
    ("optimal", "mars"): ["--tf", "--thrust-max", "--limit", "--thrust-min", "--n", "--isp",
                          "--drag"],
    ("compare", "mars"): ["--dist-amplitude", "--amplitude", "--drag", "--n"],
}
FLAGS = {("simulate", "mars"): ["--reference", "--fig6", "--json"],
         ("tune", "mars"): ["--fast", "--no-suggest", "--json"],
         ("optimal", "mars"): ["--min-tf", "--no-replay", "--json"],
         ("compare", "mars"): ["--json"]}


@st.composite
def command_lines(draw) -> tuple[str, str, list[str]]:
    verb, system = draw(st.sampled_from(sorted(FUZZ_OPTIONS)))
    opts = draw(st.lists(st.sampled_from(FUZZ_OPTIONS[(verb, system)]), max_size=4,
                         unique=True))
    args = []
    for o in opts:
        args += [o, draw(option_values)]
    args += draw(st.lists(st.sampled_from(FLAGS[(verb, system)]), max_size=2, unique=True))
    if verb == "tune":
        for req, val in (("--tf", "60"), ("--thrust-max", "50000")):
            if req not in opts:
                args += [req, val]
    return verb, system, args


@FUNCTION_SCOPED
@given(cmd=command_lines())
def test_fuzz_option_values(tmp_path_factory, no_heavy_work, cmd):
    verb, system, args = cmd
    d = tmp_path_factory.mktemp("o")
    out = d / ("g.toml" if verb == "tune" else "out")
    check_run(run_lgw([verb, system, *args, "--out", str(out)]), out)
    if verb != "tune":
        assert not out.exists()  # the stub stops every run before anything is written


def test_strict_json_for_a_case_that_blows_up(tmp_path):
    """Real flight of two states (r_x = 0 with v_x != 0 is non-finite at t = 0): exit 0, the
    JSON is strict with null for the non-finite values, and --out holds the same cases."""
    p = tmp_path / "s.csv"
    p.write_text("rx,ry,rz,vx,vy,vz,m\n0,1000,1500,10,-15,-75,1905\n"
                 "-2000,1000,1500,100,-15,-75,1905\n")
    out = tmp_path / "out"
    r = run_lgw(["simulate", "mars", "--initial-states", str(p), "--json", "--out", str(out)])
    assert r.code == 0 and r.exception is None, r.stderr
    doc = _strict(r.stdout)
    assert doc["lgw_version"] and doc["gains"]["q1"] > 0 and doc["command"] == "simulate mars"
    assert [c["nonfinite"] for c in doc["cases"]] == [True, False]
    assert doc["summary"]["settings"]["dist_amplitude"] is None  # --disturbance none
    assert _strict((out / "cases.json").read_text())["cases"] == doc["cases"]
    _strict((out / "summary.json").read_text())
    assert sorted(x.name for x in out.iterdir() if x.name != ".lgw-output.json") == [
        "cases.csv", "cases.json", "summary.json"]


adversarial = st.one_of(st.sampled_from([0.0, -0.0, 1e-100, -1e-100, 1e-9, 1e6, -1e6, 1e12,
                                         -1e12]),
                        st.floats(-3000.0, 3000.0))
state_rows = st.lists(st.tuples(*[adversarial] * 6, st.sampled_from([1905.0, 1600.0, 1e6,
                                                                     1505.0 + 1e-9])),
                      min_size=1, max_size=3)


@settings(FUNCTION_SCOPED, max_examples=max(4, settings.default.max_examples // 6))
@given(rows=state_rows, extra=st.lists(st.sampled_from(
    ["--method dopri5", "--thrust-max 50000", "--disturbance sin", "--limit norm",
     "--t-max 40", "--drag none"]), max_size=2, unique=True))
def test_fuzz_simulate_real_flights_few_cases(tmp_path_factory, rows, extra):
    """Real flights of 1-3 adversarial states (exact zeros, tiny, huge, sign mixtures): exit
    0 with strict JSON holding one record per state and the same files under --out, or one
    error line and nothing written."""
    d = tmp_path_factory.mktemp("f")
    p = d / "s.csv"
    p.write_text("rx,ry,rz,vx,vy,vz,m\n" + "".join(",".join(repr(x) for x in r) + "\n"
                                                 for r in rows))
    out = d / "out"
    args = ["simulate", "mars", "--initial-states", str(p), "--json", "--out", str(out)]
    for e in extra:
        args += e.split()
    r = run_lgw(args)
    check_run(r, out)
    if r.code == 0:
        doc = _strict(r.stdout)
        assert len(doc["cases"]) == len(rows) == doc["summary"]["cases"]
        assert _strict((out / "cases.json").read_text())["cases"] == doc["cases"]
