"""Fuzzing the command line: random bytes, random TOML, random CSV and random option
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
    import lgw.tuning.mars.cmd_simulate as cs
    import lgw.tuning.mars.compare as cc
    import lgw.tuning.mars.design as ct
    import lgw.tuning.mars.design_bounded as cb
    import lgw.tuning.options as topt

    for mod, name in ((scamp, "run_campaign"), (cs, "fig6"), (sr, "simulate_reference"),
                      (ct, "tune"), (cb, "tune_bounded"), (so, "solve_fuel_optimal"),
                      (so, "min_time"), (cc, "run_comparison"), (topt, "check_scheduler")):
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


# --- every system and verb (the registry) ------------------------------------------------------
#
# The fuzz oracle of the issue, for every Verb of every system: exit code in {0, 2, 3, 4, 130};
# on a refusal one error line and nothing written; strict JSON; no impossible quantity (fuel in
# [0, propellant], mass in [dry, m0], every mean within [min, max]).  The short profile (the
# default suite) stops each run once its options are validated, its outputs checked and its
# job planned (``plan_only``: every loader and every check runs, no kernel is compiled); the
# long one (``-m slow``) runs cheap configurations for real.  ``FUZZ_COUNTS`` tallies the
# inputs tried and the exit codes per system (printed at the end with ``-s``).

from collections import Counter, defaultdict  # noqa: E402

from lgw.tuning.spec import option_fields  # noqa: E402
from lgw.tuning.system import NotApplicable, Verb, all_systems  # noqa: E402

ALLOWED_EXIT = {0, 2, 3, 4, 130}
FUZZ_COUNTS: dict[str, Counter] = defaultdict(Counter)


@pytest.fixture(scope="module", autouse=True)
def _print_counts():
    yield
    if FUZZ_COUNTS:
        print("\nfuzz counts per system (inputs tried; exit codes; failures by kind):")
        for system, c in sorted(FUZZ_COUNTS.items()):
            print(f"  {system}: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))


def _tally(system: str, r: Run) -> None:
    c = FUZZ_COUNTS[system]
    c["inputs"] += 1
    c[f"exit {r.code}"] += 1
    if r.exception is not None or r.code == 70:
        c["internal errors"] += 1


def check_any(r: Run, out: Path | None, system: str) -> None:
    """The oracle for every system and verb (see above)."""
    _tally(system, r)
    assert r.exception is None, f"escaped main (a traceback for the user): {r.exception!r}"
    assert r.code in ALLOWED_EXIT, (r.code, r.stdout[-500:], r.stderr[-500:])
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr[-500:]
    if r.code == 2:
        assert_one_error(r)
        if out is not None:
            assert not out.exists(), f"{out} written on a refusal"
    if r.stdout.lstrip().startswith("{"):
        check_quantities(_strict(r.stdout))


def check_quantities(doc) -> None:
    """No impossible quantity anywhere in a document: every {min, mean, max} ordered, fuel in
    [0, propellant], mass in [dry, m0] (mars cases and the optimum)."""
    def walk(x, path=""):
        if isinstance(x, dict):
            lo, mean, hi = x.get("min"), x.get("mean"), x.get("max")
            if all(isinstance(v, int | float) for v in (lo, hi)):
                assert lo <= hi, f"{path}: min {lo} > max {hi}"
                if isinstance(mean, int | float):
                    assert lo <= mean <= hi, f"{path}: mean {mean} outside [{lo}, {hi}]"
            for k, v in x.items():
                walk(v, f"{path}/{k}")
        elif isinstance(x, list):
            for i, v in enumerate(x):
                walk(v, f"{path}[{i}]")

    walk(doc)
    m_dry = (doc.get("summary") or {}).get("m_dry")
    for c in doc.get("cases") or []:
        if isinstance(c, dict) and isinstance(c.get("fuel"), float) and "m0" in c \
                and m_dry is not None:
            assert -1e-9 <= c["fuel"] <= c["m0"] - m_dry + 1e-6 * c["m0"], c
    sol = doc.get("solution")
    if isinstance(sol, dict) and isinstance(sol.get("fuel_kg"), float):
        st = sol["settings"]
        assert 0.0 <= sol["fuel_kg"] <= st["m0_kg"] - st["m_dry_kg"], sol["fuel_kg"]
        assert st["m_dry_kg"] <= sol["final_mass_kg"] <= st["m0_kg"], sol["final_mass_kg"]
    for rep in doc.get("replays") or []:
        if isinstance(rep.get("fuel_used"), float):
            assert rep["fuel_used"] >= -1e-6, rep


class _Planned(SystemExit):
    """Raised by ``plan_only``: the run's inputs are valid and its job is planned."""

    def __init__(self) -> None:
        super().__init__(0)


@pytest.fixture
def plan_only(monkeypatch):
    """Every shared command stops once its options are built, its outputs checked and its job
    planned: the loaders and checks run, the work does not."""
    import lgw.tuning.commands as cmds
    import lgw.tuning.options as topt

    def run(system, verb, mod, opts):
        cmds.check_outputs(opts, mod)
        mod.plan(opts, system)
        raise _Planned()

    monkeypatch.setattr(cmds, "run", run)
    monkeypatch.setattr(topt, "check_scheduler", lambda *a, **k: {"type": "Scheduler"})


def _verb_commands() -> list[tuple[str, str, object]]:
    out = []
    for s in all_systems():
        for verb, v in s.verbs.items():
            if isinstance(v, Verb):
                out.append((verb, s.name, v.load().Options))
    return out


VERB_COMMANDS = _verb_commands()
NOT_APPLICABLE = sorted(f"{verb} {s.name}" for s in all_systems()
                        for verb, v in s.verbs.items() if isinstance(v, NotApplicable))


# gains documents per system, near the valid ones
matrix_cells = st.one_of(scalars, st.sampled_from([1e308, -1e308, 1.7976931348623157e308,
                                                   10**309, 0.5, 1.0]))


@st.composite
def lunar_gains_docs(draw) -> str:
    lines = []
    for loop in ("orbit", "attitude"):
        if draw(st.integers(0, 3)) == 0:
            continue
        lines.append(f"[{loop}]")
        for k in ("K1", "F2", "f3", "d0e0", "q"):
            if draw(st.integers(0, 9)) == 0:
                continue
            if k in ("K1", "F2"):
                shape = draw(st.sampled_from([(3, 3), (3, 3), (3, 3), (2, 3), (3, 2)]))
                v = [[draw(matrix_cells) for _ in range(shape[1])] for _ in range(shape[0])]
                if draw(st.integers(0, 2)) == 0:  # a valid diagonal, scaled
                    a = draw(st.sampled_from([1e-300, 1e-3, 1.0, 20.0, 1e6, 1e300]))
                    v = [[a if i == j else 0.0 for j in range(3)] for i in range(3)]
                val = v
            else:
                val = draw(values)
            lines.append(f"{k} = {_toml_value(val)}")
        if draw(st.integers(0, 7)) == 0:
            lines.append("K3 = 1.0")
    if draw(st.integers(0, 9)) == 0:
        lines.append("[" + ".".join(["deep"] * draw(st.integers(2, 12))) + "]\nx = 1")
    return "\n".join(lines) + "\n"


EROS_KEYS = ("alpha", "beta", "p", "q", "k", "lam", "N", "M", "phi", "e_floor")


@st.composite
def eros_gains_docs(draw) -> str:
    lines = ["[gains]"]
    base = {"alpha": 1.0, "beta": 1.0, "p": 3, "q": 5, "k": 2.0, "lam": 1.0, "N": 5.0,
            "M": 5.0, "phi": 0.05, "e_floor": 1e-4}
    for k in EROS_KEYS:
        r = draw(st.integers(0, 9))
        if r == 0:
            continue
        v = base[k] if r > 5 else draw(st.one_of(values, st.sampled_from(
            [1e300, 1e-300, 2046, 2047, 10**400, 7, 9])))
        lines.append(f"{k} = {_toml_value(v)}")
    if draw(st.integers(0, 7)) == 0:
        lines.append("zeta = 1.0")
    return "\n".join(lines) + "\n"


def _gains_docs(system: str):
    text = {"mars": toml_docs(), "lunar": lunar_gains_docs(), "eros": eros_gains_docs()}[system]
    return st.one_of(
        st.binary(max_size=200),
        text.map(lambda t: t.encode("utf-8", "replace")),
        text.map(lambda t: t.encode("latin-1", "replace")),  # not UTF-8 where it matters
        text.map(lambda t: b"\xef\xbb\xbf" + t.encode("utf-8", "replace")))


EROS_CSV = ("ex", "ey", "ez", "vx", "vy", "vz")


@st.composite
def eros_csv_docs(draw) -> bytes:
    cols = list(draw(st.permutations(EROS_CSV)))
    if draw(st.integers(0, 4)) == 0:
        cols.pop(draw(st.integers(0, len(cols) - 1)))
    if draw(st.integers(0, 3)) == 0:
        cols.append(draw(st.sampled_from(["phase", "phase", "note", "ex"])))
    rows = [",".join(cols)]
    for _ in range(draw(st.integers(0, 3))):
        n = len(cols) + draw(st.sampled_from([0, 0, 0, -1, 1]))
        rows.append(",".join(draw(cells) for _ in range(max(n, 0))))
    return ("\n".join(rows) + "\n").encode("utf-8", "replace")


# upper ends for valid draws that keep a real run short (the option's own range otherwise)
SHORT = {"--t-max": 20.0, "--tf": 120.0, "--ts": 60.0, "--cases": 4, "--n": 40,
         "--t-fail": 20.0, "--fresh-cases": 4, "--workers": 1, "--scheduler-timeout": 5.0}


def _valid_value(o) -> st.SearchStrategy:
    """Values inside the option's declared range (short runs: ``SHORT``), edges included."""
    t = o.type
    lo, hi = getattr(t, "lo", None), getattr(t, "hi", None)
    cap = SHORT.get(o.flag)
    if type(t).__name__ == "Integer":
        lo_i = 0 if lo is None else int(lo)
        hi_i = int(min(hi if hi is not None else lo_i + 100, cap if cap else lo_i + 100))
        return st.integers(lo_i, max(lo_i, hi_i)).map(str)
    if type(t).__name__ == "Number":
        lo_f = 0.0 if lo is None else float(lo)
        hi_f = float(hi) if hi is not None else lo_f + 1e3
        if cap is not None:
            hi_f = min(hi_f, cap)
        edges = [x for x in (lo_f, hi_f) if not (x == lo and t.lo_open)
                 and not (x == hi and t.hi_open)]
        return st.one_of(st.floats(lo_f, hi_f, exclude_min=t.lo_open, exclude_max=t.hi_open,
                                   allow_nan=False).map(repr),
                         st.sampled_from(edges or [(lo_f + hi_f) / 2]).map(repr))
    return option_values


def _option_value(o) -> st.SearchStrategy:
    if getattr(o.type, "choices", None):
        return st.one_of(st.sampled_from(list(o.type.choices)), option_values)
    return st.one_of(_valid_value(o), option_values)


@st.composite
def verb_command_lines(draw, verbs=None):
    """A command line of a Verb: random options of its own with random values."""
    cmds = [c for c in VERB_COMMANDS if verbs is None or c[0] in verbs]
    verb, system, cls = draw(st.sampled_from(cmds))
    opts = [o for _, o in option_fields(cls)
            if o.flag not in ("--out", "--plot", "--database", "--gains", "--initial-states",
                              "--tuned", "--scheduler")]
    chosen = draw(st.lists(st.sampled_from(opts), max_size=4, unique_by=lambda o: o.flag))
    args: list[str] = []
    for o in chosen:
        if o.is_flag:
            args.append(o.flag)
        elif o.secondary is not None:
            args.append(draw(st.sampled_from([o.flag, o.secondary])))
        else:
            args += [o.flag, draw(_option_value(o))]
    if verb == "tune":  # the required options, unless drawn
        req = {"mars": (("--tf", "90"), ("--thrust-max", "50000")),
               "eros": (("--ts", "10"), ("--thrust-max", "30"))}.get(system, ())
        for flag, val in req:
            if flag not in args and draw(st.integers(0, 5)):
                args += [flag, val]
    if verb == "report" and "--json" not in args:
        args.append("--json")
    return verb, system, args


def _out_path(verb: str, d: Path) -> Path:
    return d / ("gains.toml" if verb == "tune" else "out")


@FUNCTION_SCOPED
@given(cmd=verb_command_lines())
def test_fuzz_every_verbs_options(tmp_path_factory, plan_only, cmd):
    """Random option values into every Verb of every system (validated, planned, stopped)."""
    verb, system, args = cmd
    d = tmp_path_factory.mktemp("v")
    out = _out_path(verb, d)
    r = run_lgw([verb, system, *args, "--out", str(out)])
    check_any(r, out, system)
    assert not out.exists()  # stopped before any work


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_fuzz_gains_files_every_verb(system, tmp_path_factory, plan_only):
    """Random gains files (text near the valid ones, binary, latin-1, BOM) into every Verb of
    the system that takes --gains."""
    verbs = [v for v, s, cls in VERB_COMMANDS if s == system
             and any(o.flag == "--gains" for _, o in option_fields(cls))]

    @FUNCTION_SCOPED
    @given(data=_gains_docs(system), verb=st.sampled_from(verbs))
    def run(data, verb):
        d = tmp_path_factory.mktemp("g")
        p = d / "g.toml"
        p.write_bytes(data)
        out = _out_path(verb, d)
        args = [verb, system, "--gains", str(p), "--out", str(out)]
        if verb == "report":
            args.append("--json")
        check_any(run_lgw(args), out, system)

    run()


@pytest.mark.parametrize("system, states", [("mars", csv_docs()), ("eros", eros_csv_docs())])
def test_fuzz_states_files_every_system(system, states, tmp_path_factory, plan_only):
    @FUNCTION_SCOPED
    @given(data=st.one_of(st.binary(max_size=200), states))
    def run(data):
        d = tmp_path_factory.mktemp("s")
        p = d / "s.csv"
        p.write_bytes(data)
        out = d / "out"
        check_any(run_lgw(["simulate", system, "--initial-states", str(p), "--out", str(out)]),
                  out, system)

    run()


@FUNCTION_SCOPED
@given(data=_gains_docs("eros"))
def test_fuzz_bounds_eros_runs_for_real(tmp_path_factory, data):
    """``lgw bounds eros`` (cheap) runs for real on random gains files."""
    d = tmp_path_factory.mktemp("be")
    p = d / "g.toml"
    p.write_bytes(data)
    out = d / "out"
    r = run_lgw(["bounds", "eros", "--gains", str(p), "--json", "--out", str(out)])
    check_any(r, out, "eros")
    if r.code == 0:
        assert _strict((out / "bounds.json").read_text()) == _strict(r.stdout)


def test_every_verb_is_fuzzed():
    """Every Verb is in the fuzz (not-applicable ones only refuse)."""
    assert {(v, s) for v, s, _ in VERB_COMMANDS} == {
        (verb, s.name) for s in all_systems() for verb, v in s.verbs.items()
        if isinstance(v, Verb)}
    print(f"\nfuzzed verbs: {len(VERB_COMMANDS)}; "
          f"not applicable: {len(NOT_APPLICABLE)}")


# --- the long profile: real runs ----------------------------------------------------------------

REAL_ARGS = {
    ("bounds", "mars"): [], ("bounds", "lunar"): [], ("bounds", "eros"): [],
    ("simulate", "mars"): ["--t-max", "30"],
    ("simulate", "lunar"): ["--t-max", "1"],
    ("simulate", "eros"): ["--t-max", "1", "--law", "fuzzy-tanh"],
    ("optimal", "mars"): ["--n", "10", "--no-replay"],
}
LONG = settings(FUNCTION_SCOPED, max_examples=max(60, settings.default.max_examples * 4))


@pytest.mark.slow
@LONG
@given(cmd=verb_command_lines(verbs={"bounds", "simulate", "optimal"}))
def test_fuzz_real_runs_long(tmp_path_factory, cmd):
    """The long profile: random options into cheap configurations, run for real, JSON checked
    for impossible quantities."""
    verb, system, args = cmd
    d = tmp_path_factory.mktemp("r")
    out = _out_path(verb, d)
    base = list(REAL_ARGS.get((verb, system), []))
    for i in range(0, len(base), 2):  # a fuzzed option wins over the cheap default
        if base[i] in args:
            base[i:i + 2] = ["", ""]
    r = run_lgw([verb, system, *[a for a in base if a], *args, "--json", "--out", str(out)])
    check_any(r, out, system)


@pytest.mark.slow
@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_fuzz_gains_files_real_runs_long(system, tmp_path_factory):
    @LONG
    @given(data=_gains_docs(system))
    def run(data):
        d = tmp_path_factory.mktemp("gl")
        p = d / "g.toml"
        p.write_bytes(data)
        out = d / "out"
        check_any(run_lgw(["bounds", system, "--gains", str(p), "--json", "--out", str(out)]),
                  out, system)

    run()


@settings(FUNCTION_SCOPED, max_examples=max(5, settings.default.max_examples // 3))
@given(cmd=verb_command_lines(verbs={"bounds"}))
def test_fuzz_bounds_options_run_for_real(tmp_path_factory, cmd):
    """Random option values into ``lgw bounds SYSTEM`` run for real (cheap for every system):
    values the options accept must be values the bounds can evaluate."""
    verb, system, args = cmd
    d = tmp_path_factory.mktemp("bo")
    out = d / "out"
    check_any(run_lgw([verb, system, *args, "--json", "--out", str(out)]), out, system)


# Inputs that once ended in an internal error, an endless run or an impossible number: each is
# now a named error (exit 2, nothing written) naming the option and its valid range.
NAMED = [
    (["bounds", "lunar", "--eq0-min", "1e-170"], "--eq0-min", "[0.001, 1]"),
    (["simulate", "eros", "--t-max", "0.001", "--dt", "0.01"], "--dt", "<= --t-max"),
    (["simulate", "eros", "--dt", "1e-300"], "--dt", "at most"),
    (["simulate", "lunar", "--dt", "1e-300"], "--dt", "at most"),
    (["optimal", "mars", "--thrust-min", "86000"], "--thrust-min", "must be <"),
    (["optimal", "mars", "--thrust-min", "90000"], "--thrust-min", "must be in [0,"),
    (["optimal", "mars", "--isp", "1e300"], "--isp", "[1, 100000]"),
    (["optimal", "mars", "--tf", "1.0", "--isp", "5e-324"], "--isp", "[1, 100000]"),
    (["optimal", "mars", "--drag", "physical", "--no-replay"], "--drag", "--replay"),
]


@pytest.mark.parametrize("args, name, valid", NAMED, ids=lambda x: str(x)[:40])
def test_former_internal_errors_are_named_errors(args, name, valid, tmp_path):
    out = tmp_path / "out"
    r = run_lgw([*args, "--out", str(out)])
    assert_one_error(r)
    assert name in r.stderr and valid in r.stderr, r.stderr
    assert not out.exists()


@pytest.mark.parametrize("args", [["simulate", "mars", "--dispersion", "table2"],
                                  ["simulate", "lunar"], ["simulate", "eros"],
                                  ["report", "eros", "--json"]])
def test_the_largest_cases_is_estimated_before_allocating(args, tmp_path, monkeypatch):
    """The largest --cases each system allows fails by the memory estimate, with the number
    that fits, never a MemoryError (the available memory is pinned so the test does not depend
    on the machine)."""
    import lgw.tuning.io as tio
    from lgw.tuning.mars import cmd_simulate as ms
    from lgw.tuning.vocabulary import MAX_CASES

    monkeypatch.setattr(tio, "available_memory", lambda: 8 * 2**30)
    monkeypatch.setattr(ms, "available_memory", lambda: 8 * 2**30)
    out = tmp_path / "out"
    r = run_lgw([*args, "--cases", str(MAX_CASES), "--out", str(out)])
    assert_one_error(r)
    assert "--cases" in r.stderr and "GiB" in r.stderr, r.stderr
    assert not out.exists()


def test_optimal_tf_beyond_the_propellant_names_the_feasible_interval():
    """--tf 9999 used to say "must be >= 13.667 s"; it is too long, not too short."""
    r = run_lgw(["optimal", "mars", "--tf", "9999", "--n", "10", "--no-replay"])
    assert_one_error(r)
    assert "--tf" in r.stderr and "must be <=" in r.stderr and "propellant" in r.stderr
