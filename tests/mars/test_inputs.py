"""The input and output reproductions, one test per defect class: each now gives a named
error (one line ``error: ...``, exit 2, nothing written) or a strict, complete output."""

from __future__ import annotations

import copy
import http.server
import json
import math
import socket
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from lgw.sim.mars.campaign import read_states_csv
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.gains import EXP_GAP, EXP_MAX, default_gains, gains_from_dict, load_gains
from lgw.theory.mars.parameters import DEFAULT_GAINS
from lgw.tuning.io import atomic_write_text, atomic_writer, check_out_dir, json_document
from lgw.tuning.options import check_scheduler

from tests.test_cli_conventions import assert_one_error, run_lgw

HEADER = "rx,ry,rz,vx,vy,vz,m\n"
ROW = "-200,1400,1000,-15,-100,-10,1905\n"


def _toml(**changes) -> str:
    d = copy.deepcopy(DEFAULT_GAINS)
    for k, v in changes.items():
        d["disturbance" if k in ("a_max", "theta1", "theta2") else "gains"][k] = v
    lines = []
    for table, vals in d.items():
        lines.append(f"[{table}]")
        lines += [f"{k} = {v!r}" for k, v in vals.items()]
    return "\n".join(lines) + "\n"


def _bounds(tmp_path: Path, content: bytes | str):
    p = tmp_path / "g.toml"
    p.write_bytes(content if isinstance(content, bytes) else content.encode())
    out = tmp_path / "out"
    r = run_lgw(["bounds", "mars", "--gains", str(p), "--json", "--out", str(out)])
    return r, out


# --- gains files ----------------------------------------------------------------------------

@pytest.mark.parametrize("content, words", [
    (b"\x7fELF\x02\x01\x01\x00\x00\x00", "binary"),
    ("[gains]\nbeta1 = 2.8 # caf\xe9\n".encode("latin-1"), "not UTF-8"),
    (b"[gains]\nbeta1 = 1\nbeta1 = 2\n", "not valid TOML"),
    (b"[gains]\nbeta1 = " + b"[" * 5000 + b"]" * 5000 + b"\n", "nested too deeply"),
    (_toml(beta1="fast").encode(), "beta1"),
    (_toml(q2=10**400).encode(), "too large for a double"),
])
def test_malformed_gains_files_are_named_errors(tmp_path, content, words):
    r, out = _bounds(tmp_path, content)
    assert_one_error(r)
    assert "--gains" in r.stderr or "beta1" in r.stderr or "q2" in r.stderr
    assert words in r.stderr
    assert not out.exists()


def test_utf8_bom_gains_file_is_accepted(tmp_path):
    p = tmp_path / "bom.toml"
    p.write_bytes(b"\xef\xbb\xbf" + _toml().encode())
    assert load_gains(p).to_dict() == default_gains().to_dict()


@pytest.mark.parametrize("key, value", [("g2", 1e6), ("q2", 1e300), ("q2", 2047.0),
                                        ("beta1", 1e-308), ("alpha1", 5e-324),
                                        ("q1", math.nextafter(1.0, 0.0)),
                                        ("g1", math.nextafter(1.0, 0.0)),
                                        ("q2", math.nextafter(1.0, 2.0)),
                                        ("g2", math.nextafter(1.0, 2.0)),
                                        ("q1", 1.0 - EXP_GAP / 2)])
def test_values_beyond_the_closed_forms_name_the_users_parameter(tmp_path, key, value):
    """g2 = 1e6 and q2 = 1e300 used to raise OverflowError in _v_route, beta1 = 1e-308 printed
    Infinity, exponents one ulp from 1 named the lemma's internal p, g: now each names the
    gains-file key and its valid range."""
    r, out = _bounds(tmp_path, _toml(**{key: value}))
    assert_one_error(r)
    msg = r.stderr
    assert key in msg.split("is invalid")[0], msg
    assert not any(f" {s} = " in msg or msg.startswith(f"error: {s} ") for s in ("p", "g", "k"))
    assert "must" in msg and not out.exists()


@pytest.mark.parametrize("key, value", [("q1", 1.0 - EXP_GAP), ("q2", 1.0 + EXP_GAP),
                                        ("g2", EXP_MAX), ("q2", EXP_MAX), ("q1", 1e-300),
                                        ("beta2", 1e300), ("theta1", 1e-300)])
def test_the_edges_of_the_evaluable_range_are_accepted_and_finite(tmp_path, key, value):
    r, out = _bounds(tmp_path, _toml(**{key: value}))
    assert r.code == 0, r.stderr
    doc = json.loads(r.stdout, parse_constant=_no_constants)
    assert all(math.isfinite(v) for ax in "xyz" for v in doc[ax].values())
    assert json.loads((out / "bounds.json").read_text(), parse_constant=_no_constants) == doc


def _no_constants(name: str):
    raise AssertionError(f"non-strict JSON token {name}")


gain_value = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                       st.floats(1e-320, 1e-280), st.floats(1e280, 1.7e308))


@given(key=st.sampled_from(["beta1", "beta2", "alpha1", "alpha2", "q1", "q2", "g1", "g2",
                            "a_max", "theta1", "theta2"]), value=gain_value)
def test_any_accepted_gain_set_has_finite_bounds(key, value):
    d = copy.deepcopy(DEFAULT_GAINS)
    d["disturbance" if key in ("a_max", "theta1", "theta2") else "gains"][key] = value
    try:
        g = gains_from_dict(d)
    except ParameterError as e:
        assert key in e.name
        return
    b = axis_bounds(g)
    assert all(math.isfinite(v) and v >= 0 for ax in b.values() for v in ax.values())


# --- states CSV -----------------------------------------------------------------------------

@pytest.mark.parametrize("content, words", [
    (b"\x89PNG\r\n\x1a\n\x00\x00", "binary"),
    ((HEADER + "-200,1400,1000,-15,-100,-10,19\xe905\n").encode("latin-1"), "not UTF-8"),
    ((HEADER.replace("m\n", "m,rx\n") + ROW.replace("\n", ",5\n")).encode(), "duplicated"),
    ((HEADER + ROW.replace("-15", "nan")).encode(), "finite"),
    ((HEADER + ROW.replace("-15", "inf")).encode(), "finite"),
    ((HEADER + ROW.replace("-15", "1e999")).encode(), "finite"),
    ((HEADER + ROW.replace("-15", "fast")).encode(), "number"),
    (HEADER.replace(",m", "").encode() + b"1,2,3,4,5,6\n", "missing m"),
    (b"", "empty"),
    (b"\n\n  \n", "empty"),
    (HEADER.encode(), "no data rows"),
    ((HEADER + "1,2,3\n").encode(), "fields"),
    ((HEADER + ROW.replace("1905", "0")).encode(), r"in \(0, 1e\+09\] kg"),
])
def test_malformed_states_csv_is_a_named_error(tmp_path, content, words):
    p = tmp_path / "s.csv"
    p.write_bytes(content)
    with pytest.raises(ParameterError, match=words) as e:
        read_states_csv(p)
    assert e.value.name.startswith("--initial-states")


def test_states_csv_with_bom_and_crlf_is_read(tmp_path):
    """A spreadsheet's UTF-8 export (BOM, CRLF) used to be rejected as 'missing rx'."""
    p = tmp_path / "s.csv"
    p.write_bytes(b"\xef\xbb\xbf" + (HEADER + ROW).replace("\n", "\r\n").encode())
    r0, v0, m0 = read_states_csv(p)
    np.testing.assert_array_equal(r0, [[-200.0, 1400.0, 1000.0]])
    np.testing.assert_array_equal(v0, [[-15.0, -100.0, -10.0]]) and m0.tolist() == [1905.0]


def test_bad_states_file_through_the_cli_writes_nothing(tmp_path):
    p = tmp_path / "s.csv"
    p.write_bytes(b"\x00\x01\x02")
    out = tmp_path / "out"
    r = run_lgw(["simulate", "mars", "--initial-states", str(p), "--out", str(out)])
    assert_one_error(r)
    assert "--initial-states" in r.stderr and not out.exists()


# --- tuned certificate files ----------------------------------------------------------------

@pytest.mark.parametrize("extra, words", [
    ('[certificate]\n[certificate.request]\ntf = "soon"\n', "certificate.request.tf"),
    ("[certificate]\nrequest = 3\n", "[certificate.request]"),
    ("certificate = 3\n", "[certificate]"),
])
def test_malformed_tuned_file_is_a_named_error(tmp_path, extra, words):
    p = tmp_path / "t.toml"
    text = _toml()
    p.write_text(text.replace("[gains]", extra + "[gains]") if extra.startswith("cert")
                 else text + extra)
    out = tmp_path / "out"
    r = run_lgw(["compare", "mars", "--tuned", str(p), "--out", str(out)])
    assert_one_error(r)
    assert words in r.stderr and not out.exists()


# --- seeds and numeric options --------------------------------------------------------------

@pytest.mark.parametrize("args, name", [
    (["simulate", "mars", "--seed", "-1"], "--seed"),
    (["simulate", "mars", "--seed", str(2**64)], "--seed"),
    (["simulate", "mars", "--seed", "1e3"], "--seed"),
    (["tune", "mars", "--tf", "60", "--thrust-max", "5e4", "--seed", "-5"], "--seed"),
    (["simulate", "mars", "--dt", "nan"], "--dt"),
    (["simulate", "mars", "--t-max", "inf"], "--t-max"),
    (["simulate", "mars", "--dist-amplitude", "-1", "--disturbance", "sin"], "--dist-amplitude"),
    (["simulate", "mars", "--dist-amplitude", "3"], "--dist-amplitude"),
    (["simulate", "mars", "--isp", "0"], "--isp"),
    (["simulate", "mars", "--dt", "1e-7"], "--dt"),
    (["simulate", "mars", "--t-max", "1e7"], "--t-max"),
    (["tune", "mars", "--tf", "1e300", "--thrust-max", "5e4"], "--tf"),
    (["optimal", "mars", "--thrust-max", "1e300"], "--thrust-max"),
    (["simulate", "mars", "--workers", "0"], "--workers"),
    (["simulate", "mars", "--dispersion", "table2", "--cases", "1000000000000"], "--cases"),
    (["tune", "mars", "--tf", "nan", "--thrust-max", "5e4"], "--tf"),
    (["tune", "mars", "--tf", "60", "--thrust-max", "5e4", "--theta1", "1"], "--theta1"),
    (["tune", "mars", "--tf", "60", "--thrust-max", "5e4", "--brake-fraction", "0"],
     "--brake-fraction"),
    (["optimal", "mars", "--n", "3"], "--n"),
    (["optimal", "mars", "--tf", "-inf"], "--tf"),
    (["compare", "mars", "--dist-amplitude", "0"], "--dist-amplitude"),
])
def test_seeds_and_numbers_are_checked_with_their_name(tmp_path, args, name):
    out = tmp_path / ("g.toml" if args[0] == "tune" else "out")
    r = run_lgw([*args, "--out", str(out)])
    assert_one_error(r)
    assert r.stderr.startswith(f"error: {name} ")
    assert not out.exists()


# --- --out checked before any work, written atomically --------------------------------------

def test_unwritable_out_fails_before_any_work(tmp_path, monkeypatch):
    """--out under a file (or anywhere unwritable) used to fail with a traceback after the
    whole campaign, leaving a partial summary.json; now nothing runs."""
    import lgw.sim.mars.campaign as campaign

    def boom(*a, **k):
        raise AssertionError("the campaign ran before --out was checked")

    monkeypatch.setattr(campaign, "run_campaign", boom)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    for out in (blocker, blocker / "sub", Path("/proc/lgw-out")):
        r = run_lgw(["simulate", "mars", "--out", str(out)])
        assert_one_error(r)
        assert "--out" in r.stderr
    assert blocker.read_text() == "x"
    r = run_lgw(["tune", "mars", "--tf", "60", "--thrust-max", "5e4", "--out", str(tmp_path)])
    assert_one_error(r)
    assert "file path" in r.stderr
    r = run_lgw(["tune", "mars", "--tf", "60", "--thrust-max", "5e4",
                 "--out", str(tmp_path / "no" / "g.toml")])
    assert_one_error(r)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]


def test_check_out_dir_creates_nothing(tmp_path):
    assert check_out_dir(tmp_path / "a" / "b") == tmp_path / "a" / "b"
    assert list(tmp_path.iterdir()) == []


def test_atomic_write_leaves_old_file_or_nothing(tmp_path):
    p = tmp_path / "summary.json"
    atomic_write_text(p, "old")
    with pytest.raises(RuntimeError), atomic_writer(p) as f:
        f.write("half a docu")
        raise RuntimeError("disk gone")
    assert p.read_text() == "old" and [x.name for x in tmp_path.iterdir()] == ["summary.json"]
    atomic_write_text(tmp_path / "new.json", "whole")
    assert (tmp_path / "new.json").read_text() == "whole"


def test_strict_json_nonfinite_as_null_with_flag():
    doc = json.loads(json_document({"a": float("nan"), "b": [1.0, float("inf")],
                                    "c": np.float64(-np.inf), "d": np.array([2.0])}),
                     parse_constant=_no_constants)
    assert doc["a"] is None and doc["b"] == [1.0, None] and doc["c"] is None
    assert doc["d"] == [2.0] and doc["nonfinite_replaced"] is True and "lgw_version" in doc
    assert "nonfinite_replaced" not in json.loads(json_document({"a": 1.0}))


# --- --scheduler fails fast -----------------------------------------------------------------

class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *a):
        pass


@pytest.fixture
def http_server():
    srv = http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Quiet)
    th = threading.Thread(target=srv.serve_forever, daemon=True)
    th.start()
    yield f"tcp://127.0.0.1:{srv.server_address[1]}"
    srv.shutdown()
    srv.server_close()


def _closed_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def test_scheduler_that_is_an_http_server_is_one_error_in_bounded_time(http_server):
    t = time.monotonic()
    r = run_lgw(["simulate", "mars", "--scheduler", http_server, "--scheduler-timeout", "1"])
    assert_one_error(r)
    assert "--scheduler" in r.stderr and time.monotonic() - t < 10


# the closed port is found when the test runs: a port in the test's id differs between the
# collections of two pytest-xdist workers, which then refuse to start
@pytest.mark.parametrize("addr", ["closed-port", "http://example.org", "nonsense",
                                  "127.0.0.1:99999"])
def test_scheduler_unreachable_or_malformed_is_one_error(addr):
    if addr == "closed-port":
        addr = f"tcp://127.0.0.1:{_closed_port()}"
    t = time.monotonic()
    r = run_lgw(["simulate", "mars", "--scheduler", addr, "--scheduler-timeout", "1"])
    assert_one_error(r)
    assert "--scheduler" in r.stderr and time.monotonic() - t < 10


def test_scheduler_probe_accepts_a_real_scheduler_and_rejects_a_worker():
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as c:
        assert check_scheduler(c.scheduler_address, 5)["type"] == "Scheduler"
        worker = next(iter(c.workers.values())).address
        with pytest.raises(ParameterError, match="'Worker'"):
            check_scheduler(worker, 5)


def test_scheduler_with_workers_is_an_error():
    r = run_lgw(["simulate", "mars", "--scheduler", "tcp://127.0.0.1:8786", "--workers", "2"])
    assert_one_error(r)
    assert "--workers" in r.stderr and "--scheduler" in r.stderr


# --- impossible values: refused at input, or computed right ----------------------------------

def test_states_file_mass_beyond_float_resolution_is_refused(tmp_path):
    """m0 = 1e30 kg saturated at 50 kN for 120 s reported 0 kg of fuel (the burn is lost in
    the rounding of the mass): m0 is refused above 1e9 kg, with the row and the range."""
    from lgw.sim.mars.campaign import M0_MAX, read_states_csv

    p = tmp_path / "s.csv"
    p.write_text("rx,ry,rz,vx,vy,vz,m\n-2000,1000,1500,100,-15,-75,1905\n"
                 "-2000,1000,1500,100,-15,-75,1e30\n")
    with pytest.raises(ParameterError) as e:
        read_states_csv(p)
    assert e.value.name == "--initial-states row 3 column m" and f"{M0_MAX:g}" in e.value.valid
    p.write_text(f"rx,ry,rz,vx,vy,vz,m\n-2000,1000,1500,100,-15,-75,{M0_MAX!r}\n")
    assert read_states_csv(p)[2][0] == M0_MAX


def test_optimal_fuel_and_mass_are_possible_whatever_the_isp():
    """Isp = 1e300 s gave -4e-12 kg of fuel and a final mass above m0: the mass is integrated
    from the SOCP's own sigma, so fuel in [0, m0 - m_dry] and mass in [m_dry, m0] exactly."""
    from lgw.sim.mars.optimal import solve_fuel_optimal
    from lgw.theory.mars.parameters import M0, M_DRY, R0, V0

    for isp in (1e300, 1e8, 225.0):
        s = solve_fuel_optimal(R0, V0, M0, 30.0, n=20, isp=isp)
        assert s.feasible
        assert 0.0 <= s.fuel <= M0 - M_DRY and s.m[0] == M0
        assert np.all((s.m >= M_DRY) & (s.m <= M0)) and np.all(np.diff(s.m) <= 0)
        assert s.fuel == pytest.approx(M0 - s.m[-1], abs=1e-9)


def test_optimal_minimum_thrust_burning_the_propellant_is_infeasible_not_nan():
    """A lower thrust bound that alone burns more than the propellant before tf made the
    problem data NaN (cvxpy raised); it is an infeasible problem, and the CLI refuses it at
    input with the largest minimum thrust for that tf."""
    from lgw.sim.mars.optimal import max_time, solve_fuel_optimal
    from lgw.theory.mars.parameters import M0, R0, V0

    s = solve_fuel_optimal(R0, V0, M0, 600.0, thrust_min=60_000.0, n=20)
    assert s.status == "infeasible" and "propellant" in s.settings["infeasible_reason"]
    longest = max_time(R0, V0, M0, 30.0, 9999.0, n=20)
    assert solve_fuel_optimal(R0, V0, M0, longest, n=20).feasible
    assert not solve_fuel_optimal(R0, V0, M0, longest + 0.05, n=20).feasible
