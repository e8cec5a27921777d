"""Dispersions, CSV states, dask executors (identical with 1 and 2 workers), the CLI."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.sim.mars.campaign import (
    TABLE3_R_MAX,
    TABLE3_R_MIN,
    TABLE3_V_MAX,
    TABLE3_V_MIN,
    read_states_csv,
    run_campaign,
    summarize,
    table2_states,
    table3_states,
)
from lgw.theory.errors import ParameterError
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import M0, R0

G = default_gains()


def test_table2_and_table3_states() -> None:
    r0, v0, m0 = table2_states(4000, seed=1)
    np.testing.assert_allclose(r0.mean(axis=0), R0, atol=10)
    np.testing.assert_allclose(r0.std(axis=0), 100, rtol=0.05)
    np.testing.assert_allclose(v0.std(axis=0), 10, rtol=0.05)
    assert abs(m0.mean() - M0) < 2 and abs(m0.std() - 20) < 1.5
    a = table2_states(5, seed=3)
    b = table2_states(5, seed=3)
    assert all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))
    r0, v0, m0 = table3_states(500, seed=2)
    assert np.all((r0 >= TABLE3_R_MIN) & (r0 <= TABLE3_R_MAX))
    assert np.all((v0 >= TABLE3_V_MIN) & (v0 <= TABLE3_V_MAX))
    assert np.all(m0 == M0)
    with pytest.raises(ParameterError, match="cases"):
        table2_states(0)


def test_read_states_csv(tmp_path) -> None:
    p = tmp_path / "s.csv"
    p.write_text("m,rx,ry,rz,vx,vy,vz,note\n1905,-2000,1000,1500,100,-15,-75,a\n"
                 "1800,1,2,3,4,5,6,b\n")
    r0, v0, m0 = read_states_csv(p)
    np.testing.assert_array_equal(r0[0], R0)
    np.testing.assert_array_equal(v0[1], [4, 5, 6])
    np.testing.assert_array_equal(m0, [1905, 1800])
    p.write_text("rx,ry,rz,vx,vy\n1,2,3,4,5\n")
    with pytest.raises(ParameterError, match="missing vz, m"):
        read_states_csv(p)
    p.write_text("rx,ry,rz,vx,vy,vz,m\n1,2,3,4,5,x,7\n")
    with pytest.raises(ParameterError, match="column vz"):
        read_states_csv(p)
    with pytest.raises(ParameterError):
        read_states_csv(tmp_path / "nope.csv")


def test_dask_one_and_two_workers_identical() -> None:
    r0, v0, m0 = table2_states(6, seed=4)
    kw = dict(disturbance="random", dist_amplitude=0.5, seed=7, land_tol=(0.5, 0.5), chunk=2)
    one = run_campaign(r0, v0, m0, G, executor="dask", workers=1, processes=False, **kw)
    two = run_campaign(r0, v0, m0, G, executor="dask", workers=2, processes=False, **kw)
    assert one.equal(two)
    local = run_campaign(r0, v0, m0, G, **kw)
    assert local.equal(one)  # the threaded local kernel gives the same numbers too
    assert one.landed.all()


def _cli(args: list[str]):
    from lgw.tuning.cli import cli

    return CliRunner().invoke(cli, args, standalone_mode=False, catch_exceptions=True)


def test_cli_json_table1() -> None:
    res = _cli(["simulate", "mars", "--json"])
    assert res.exception is None, res.output
    data = json.loads(res.output)
    (case,) = data["cases"]
    assert case["landed"] and case["landing_time"] == pytest.approx(27.39, abs=0.01)
    for key in ("r0", "v0", "m0", "fuel", "peak_thrust", "t_s1", "t_s2", "eps"):
        assert key in case
    assert len(case["peak_thrust"]) == 3 and data["summary"]["eps"] == 0.05
    assert data["summary"]["landing_time_s"]["median"] == case["landing_time"]


def test_cli_csv_states_and_out(tmp_path) -> None:
    p = tmp_path / "s.csv"
    p.write_text("rx,ry,rz,vx,vy,vz,m\n-2000,1000,1500,100,-15,-75,1905\n"
                 "0,1000,1500,10,-15,-75,1905\n")
    out = tmp_path / "out"
    res = _cli(["simulate", "mars", "--initial-states", str(p), "--out", str(out), "--json"])
    assert res.exception is None, res.output
    data = json.loads(res.output)
    assert [c["nonfinite"] for c in data["cases"]] == [False, True]
    assert data["summary"]["nonfinite_cases"][0]["r0"] == [0.0, 1000.0, 1500.0]
    assert (out / "summary.json").exists() and (out / "cases.csv").exists()


def test_cli_m_dry_stops_a_case_out_of_propellant() -> None:
    """Table I needs ~235 kg: with 25 kg of propellant the case runs dry, is not landed, and
    used exactly m0 - m_dry."""
    res = _cli(["simulate", "mars", "--m-dry", str(M0 - 25.0), "--json"])
    assert res.exception is None, res.output
    data = json.loads(res.output)
    (case,) = data["cases"]
    assert case["fuel_exhausted"] and not case["landed"] and case["landing_time"] is None
    assert case["fuel"] == pytest.approx(25.0, abs=1e-9)
    assert data["summary"]["fuel_exhausted"] == 1 and data["summary"]["m_dry"] == M0 - 25.0
    full = json.loads(_cli(["simulate", "mars", "--json"]).output)
    assert full["summary"]["fuel_exhausted"] == 0 and not full["cases"][0]["fuel_exhausted"]


def test_cli_dopri5_agrees_with_rk4() -> None:
    """--method dopri5 flies the same campaign as RK4 (landing times within 0.01 s, the same
    cases landed), says which integrator it used, and takes far fewer steps."""
    args = ["simulate", "mars", "--dispersion", "table2", "--cases", "20", "--json"]
    rk = json.loads(_cli(args).output)
    dp = json.loads(_cli([*args, "--method", "dopri5", "--rtol", "1e-6", "--atol", "1e-6"])
                    .output)
    assert dp["summary"]["settings"]["integrator"].startswith("Dormand-Prince 5(4)")
    assert "rtol=1e-06" in dp["summary"]["settings"]["integrator"]
    assert dp["summary"]["step_limit"] == 0 and dp["summary"]["landed"] == 20
    t_rk = np.array([c["landing_time"] for c in rk["cases"]])
    t_dp = np.array([c["landing_time"] for c in dp["cases"]])
    np.testing.assert_allclose(t_dp, t_rk, atol=0.01)
    assert max(c["steps"] for c in dp["cases"]) < min(c["steps"] for c in rk["cases"]) / 3
    lim = json.loads(_cli(["simulate", "mars", "--json", "--method", "dopri5",
                           "--max-step", "0.01", "--t-max", "30"]).output)
    assert lim["cases"][0]["steps"] >= 2700  # 27 s of flight in steps of at most 0.01 s


@pytest.mark.parametrize("args,name", [
    (["--method", "rk45"], "--method"), (["--method", "dopri5", "--rtol", "0"], "--rtol"),
    (["--method", "dopri5", "--max-step", "-1"], "--max-step"),
    (["--method", "dopri5", "--reference"], "--method"),
    (["--m-dry", str(M0 + 1.0)], "m_dry"), (["--m-dry", "-1"], "--m-dry"),
    (["--law", "pid"], "--law"), (["--dispersion", "table9"], "--dispersion"),
    (["--cases", "5"], "--cases"), (["--dispersion", "table2", "--cases", "0"], "--cases"),
    (["--thrust-max", "-3"], "--thrust-max"), (["--dt", "0"], "--dt"),
    (["--disturbance", "storm"], "--disturbance"), (["--limit", "box"], "--limit"),
])
def test_cli_bad_input_writes_nothing(tmp_path, args, name) -> None:
    out = tmp_path / "out"
    res = _cli(["simulate", "mars", "--out", str(out), *args])
    assert isinstance(res.exception, ParameterError)
    assert res.exception.name == name
    assert not out.exists()


def test_cli_exit_code_2(tmp_path) -> None:
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                           "simulate", "mars", "--law", "nope"], capture_output=True, text=True)
    assert proc.returncode == 2 and "--law" in proc.stderr


def test_summary_flags_nonfinite() -> None:
    from lgw.sim.mars.batch import simulate_batch

    b = simulate_batch(np.array([[0.0, 10.0, 100.0]]), np.array([[1.0, 0.0, 0.0]]), [M0], G)
    s = summarize(b)
    assert s["nonfinite"] == 1 and s["nonfinite_cases"][0]["r0"] == [0.0, 10.0, 100.0]
    assert s["landing_time_s"]["median"] is None


def _same(a, b) -> bool:
    """Equal arrays, NaN equal to NaN."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and bool(np.all(
        (a == b) | (np.isnan(a) & np.isnan(b)) if a.dtype.kind == "f" else a == b))


def test_spilled_campaign_is_the_campaign_in_memory(monkeypatch) -> None:
    """A campaign kept on disk (spill=True) cut into many small spill and record chunks: every
    per-case array, the summary, the records (and their JSON text, byte for byte as the
    one-item-at-a-time writer makes it), ``take`` and ``with_rows`` are those of the same
    campaign held in memory.  Table II and III states with a random disturbance (drawn per
    case number: ``case_offset``), a thrust limit and a dry mass that some cases reach: they
    land or run out of propellant (NaN landing numbers), and saturate."""
    from io import StringIO

    from lgw.sim.mars import campaign as C
    from lgw.sim.mars.batch import ARRAY_FIELDS
    from lgw.tuning.io import Stream, write_json_document

    monkeypatch.setattr(C, "SPILL_CHUNK", 7)
    monkeypatch.setattr(C, "RECORD_CHUNK", 5)
    states = tuple(np.concatenate(x) for x in zip(table2_states(15, seed=4),
                                                    table3_states(15, seed=4), strict=True))
    kw = dict(dt=0.1, disturbance="random", dist_amplitude=1.0, seed=2, thrust_limit=50000.0,
              m_dry=1660.0, parallel=False)
    mem = run_campaign(*states, G, **kw)
    disk = run_campaign(*states, G, spill=True, **kw)
    assert isinstance(disk, C.SpilledResult) and len(disk) == len(mem) == 30
    assert len(set(mem.outcomes()[0].tolist())) > 1  # more than one outcome is exercised
    assert mem.time_saturated.max() > 0
    for k in (*ARRAY_FIELDS, "r0", "v0", "m0"):
        assert _same(getattr(disk, k), getattr(mem, k)), k
    assert json.dumps(C.summarize(disk)) == json.dumps(C.summarize(mem))
    recs = C.case_records(mem)
    assert C.case_records(disk) == recs and [r["case"] for r in recs] == list(range(30))

    def post(rs):  # a per-record addition after the simulator's keys, as the CLI's
        for r in rs:
            r["extra"] = r["case"] % 2 == 0 if r["case"] % 3 else None
            yield r

    def extra(a, b):  # the same addition as a column (CaseJson's form)
        return {"extra": [i % 2 == 0 if i % 3 else None for i in range(a, b)]}

    def doc(stream: Stream) -> str:
        out = StringIO()
        write_json_document({"cases": stream}, out)
        return out.getvalue()

    # the column-wise encoding is the records' JSON: the same keys in the same order and the
    # same values (floats round-trip exactly; NaN is null)
    text = doc(Stream(encoded=C.CaseJson(disk, extra=extra)))
    want = doc(Stream(items=post(C.iter_case_records(mem))))
    assert json.loads(text, object_pairs_hook=list) == json.loads(want, object_pairs_hook=list)
    assert json.loads(doc(Stream(encoded=C.CaseJson(disk, n=3)))) == \
        json.loads(doc(Stream(items=recs[:3])))
    idx = np.array([29, 3, 8])
    assert _same(C.take(disk, "r_land", idx), mem.r_land[idx])
    other = run_campaign(*(x[idx] for x in states), G, **{**kw, "dt": 0.05})
    want = mem.with_rows(idx, other)
    got = disk.with_rows(idx, other)
    assert got is disk and got.info["replaced"] == want.info["replaced"] == [3, 8, 29]
    for k in ARRAY_FIELDS:
        assert _same(getattr(got, k), getattr(want, k)), k
    folder = disk.folder
    disk.close()
    assert not folder.exists()
