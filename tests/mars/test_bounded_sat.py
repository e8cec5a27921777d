"""The saturated-cancellation law ``bounded-sat``: generated code = SymPy, bad gains,
claims' verdicts, and the box bounds of ``axis_box_bounds_sat`` against two independent flights
(solve_ivp on the SymPy law, and the batch simulator), plus its tuner and fresh campaigns."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.laws import LEAD_ARGS, numba_law, numpy_law
from lgw.theory.errors import ParameterError
from lgw.theory.mars import bounded as B
from lgw.theory.mars import bounded_sat as BS
from lgw.theory.mars.bounded_claims import TABLE3_AXES, all_claims, fly_axis
from lgw.theory.mars.gains import default_gains, load_gains
from lgw.theory.mars.parameters import G_MARS, M0
from lgw.tuning.mars.design import envelope_from_name
from lgw.tuning.mars.design_bounded import (
    BoundedRequest,
    axis_certificate,
    packed_states,
    tune_bounded,
)

RNG = np.random.default_rng(1717)
NAME = BS.NAME
ROOT = Path(__file__).resolve().parents[2]


def _gains(sg: BS.SatGains):
    return replace(default_gains(), extra={BS.TABLE: sg.to_dict()})


def _random_sg() -> BS.SatGains:
    return BS.sat_gains_from_dict({
        "c1": float(10 ** RNG.uniform(-0.5, 1)), "delta": float(10 ** RNG.uniform(0, 3)),
        "c2": float(10 ** RNG.uniform(-9, -3)), "k1": float(10 ** RNG.uniform(-1, 1)),
        "k2": float(10 ** RNG.uniform(-5, -1)), "w0": float(10 ** RNG.uniform(-1, 1.3)),
        "p2": float(RNG.uniform(1.05, 3)), "e1": float(RNG.uniform(0.05, 0.95)),
        "e2": float(RNG.uniform(1.05, 3))})


@pytest.mark.parametrize("sg", [BS.default_sat(), _random_sg(), _random_sg()])
def test_generated_equals_symbolic(sg):
    """numba and numpy code vs the SymPy expression (Max/Min of the saturation included) at
    exact points inside Omega, outside it on both sides, and at r = 0."""
    expr = B.law_bounded_sat()
    args = LEAD_ARGS + B.PARAMS_SAT
    f_nb, f_np = numba_law(NAME), numpy_law(NAME)
    P = sg.params()
    outside = 0
    for k in range(18):
        i = k % 3
        r = 0.0 if k < 3 else float(RNG.choice([-1, 1]) * 10 ** RNG.uniform(-3, 3.5))
        W = float(B.psi_np(abs(r), sg, i)) + sg.w0[i]
        v = float(RNG.choice([-1, 1]) * W * RNG.uniform(0.0, 2.0))
        outside += abs(v) > W
        grav, am = float(G_MARS[i]), float(RNG.uniform(-0.5, 0.5))
        m = float(RNG.uniform(1500, 2000))
        subs = dict(zip(args, [sp.Float(x, 30) for x in (r, v, grav, am, m, *P[i])], strict=True))
        want = float(sp.N(expr.subs(subs), 30))
        assert f_nb(r, v, grav, am, m, P, i) == pytest.approx(want, rel=1e-10, abs=1e-10)
        rr = np.zeros((1, 3)); vv = np.zeros((1, 3))  # noqa: E702
        rr[0, i], vv[0, i] = r, v
        a = f_np(rr, vv, G_MARS, np.full((1, 3), am), np.array([m]), P)
        assert a[0, i] == pytest.approx(want, rel=1e-10, abs=1e-10)
    assert outside >= 3  # the saturated branch was exercised


def test_bad_gains_are_named_parameter_errors():
    d = dict(BS.DEFAULT_SAT)
    for key, bad in (("w0", 0.0), ("w0", -1.0), ("w0", [1, 2]), ("w0", "5"), ("w0", True),
                     ("e1", 1.2), ("c1", -1.0), ("delta", [1, 2])):
        with pytest.raises(ParameterError) as e:
            BS.sat_gains_from_dict({**d, key: bad})
        assert e.value.name == f"bounded-sat.{key}"
    with pytest.raises(ParameterError) as e:
        BS.sat_gains_from_dict({k: x for k, x in d.items() if k != "w0"})
    assert e.value.name == "bounded-sat.w0"
    with pytest.raises(ParameterError) as e:
        BS.sat_gains_from_dict({**d, "zeta": 1.0})
    assert e.value.name == "bounded-sat.zeta"
    with pytest.raises(ParameterError):  # Omega not invariant: k(w0) <= a_max
        BS.axis_box_bounds_sat(BS.default_sat(), 0, TABLE3_AXES[0], a_max=1e3)


def test_cli_bad_sat_gains_exit_2(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[gains]\nbeta1 = 2.8\nbeta2 = 4e-4\nalpha1 = 0.5\nalpha2 = 2e-5\nq1 = 0.6\n"
                   "q2 = 1.5\ng1 = 0.7\ng2 = 1.9\n\n[bounded-sat]\nc1 = 3.0\ndelta = 10.0\n"
                   "c2 = 1e-9\nk1 = 2.0\nk2 = 1e-5\nw0 = -1.0\np2 = 1.5\ne1 = 0.4\ne2 = 1.5\n")
    out = tmp_path / "o"
    run = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                          "simulate", "mars", "--law", NAME, "--gains", str(bad), "--out",
                          str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 2 and "bounded-sat.w0" in run.stderr, run.stderr
    assert not out.exists() or not any(out.iterdir())


def test_claims_have_verdicts():
    from lgw.theory.mars.bounded_claims import gain_set_claims
    got = {c.id: c for c in [*all_claims(), *gain_set_claims()]}
    assert got["bounded-sat-invariance"].verdict == "proved"
    assert got["bounded-sat-outside"].verdict == "proved"
    assert got["bounded-sat-growth"].verdict == "proved-given"
    assert got["bounded-sat-bounds"].verdict == "proved-given"  # flights are its searches
    for s in got["bounded-sat-bounds"].searches:
        if s.evidence.kind == "search":
            assert s.evidence.best_margin >= 0


def test_growth_bound_matches_quadrature():
    """growth_bound's closed form vs adaptive quadrature of (sigma - p)/(k1 sigma^e1)."""
    from scipy.integrate import quad
    for p, S, k1, e1 in ((0.0, 5.0, 2.0, 0.4), (30.0, 120.0, 1.5, 0.2), (10.0, 11.0, 3.0, 0.7)):
        q, _ = quad(lambda x, p=p, k1=k1, e1=e1: (x - p) / (k1 * x**e1), p, S)
        assert float(BS.growth_bound(p, S, k1, e1)) == pytest.approx(q, rel=1e-9)
    assert float(BS.growth_bound(5.0, 3.0, 1.0, 0.5)) == 0.0


def test_default_gains_certify_the_envelope():
    """DEFAULT_SAT (the tf 60 s design) re-certified from the bound function: proven landing
    <= 60 s and |F_i| <= 50 kN on the whole Table III + Table II envelope; the altitude
    provably never crosses 0 on the Table III box (the y axis's overshooting states can)."""
    env = envelope_from_name("table3+table2")
    sg = BS.default_sat()
    certs = [axis_certificate(sg, i, env.boxes, env.m_max) for i in range(3)]
    assert max(c["T_land"] for c in certs) <= 60.0
    assert max(c["F_b"] for c in certs) <= 50_000.0
    assert BS.axis_box_bounds_sat(sg, 2, TABLE3_AXES[2])["crosses_zero"] == 0.0
    assert BS.axis_box_bounds_sat(sg, 1, TABLE3_AXES[1])["crosses_zero"] == 1.0


AXIS_STATE = st.tuples(st.integers(0, 2), st.floats(0.0, 1.0), st.floats(0.0, 1.0))


@settings(max_examples=12, deadline=None)
@given(AXIS_STATE)
def test_bounds_hold_on_solve_ivp(x):
    """One axis from a random Table III state (corners hit by the 0/1 ends), flown by solve_ivp
    on the SymPy law: |r|, |v|, |u| and the landing time within the proven bounds."""
    i, a, b = x
    box = TABLE3_AXES[i]
    sg = BS.default_sat()
    d = BS.axis_box_bounds_sat(sg, i, box)
    r0, v0 = box.r_lo + a * (box.r_hi - box.r_lo), box.v_lo + b * (box.v_hi - box.v_lo)
    o = fly_axis(sg, i, r0, v0, t_max=d["T_land"] + 5)
    assert o["t_land"] <= d["T_land"] and o["u"] <= d["u_b"]
    assert o["r"] <= d["R_b"] * (1 + 1e-9) and o["v"] <= d["V_b"] * (1 + 1e-9)


GAINS = st.fixed_dictionaries({
    "c1": st.floats(1.0, 5.0), "delta": st.floats(5.0, 100.0), "k1": st.floats(0.5, 5.0),
    "k2": st.floats(1e-6, 1e-3), "w0": st.floats(1.0, 10.0), "e1": st.floats(0.2, 0.6)})
BOX = st.tuples(st.floats(-2000, 2000), st.floats(0, 1500), st.floats(-100, 60),
                st.floats(0, 80))


@pytest.mark.slow  # solve_ivp at 1e-10 through non-Lipschitz reaching: minutes on some draws
@settings(max_examples=5, deadline=None)
@given(GAINS, BOX, st.integers(0, 2))
def test_bounds_hold_for_random_gains_and_boxes(gd, bx, i):
    """The bounds are for any valid gains and box, not only the tuned ones: random gains, a
    random box, its corners and r0 = 0 flown by solve_ivp on the SymPy law."""
    sg = BS.sat_gains_from_dict({**BS.DEFAULT_SAT, **gd, "c2": 1e-9, "p2": 1.5, "e2": 1.5})
    box = B.AxisBox(bx[0], bx[0] + bx[1], bx[2], bx[2] + bx[3])
    d = BS.axis_box_bounds_sat(sg, i, box)
    pts = [(a, b) for a in (box.r_lo, box.r_hi) for b in (box.v_lo, box.v_hi)]
    if box.r_lo < 0 < box.r_hi:
        pts += [(0.0, box.v_lo), (0.0, box.v_hi)]
    for r0, v0 in pts:
        o = fly_axis(sg, i, r0, v0, t_max=d["T_land"] + 5)
        assert o["t_land"] <= d["T_land"] and o["u"] <= d["u_b"]
        assert o["r"] <= d["R_b"] * (1 + 1e-9) and o["v"] <= d["V_b"] * (1 + 1e-9)


STATE = st.tuples(*(st.floats(0.0, 1.0) for _ in range(6)))


@pytest.mark.slow  # compiles and flies the bounded-sat kernel, ~2 min cold in CI
@settings(max_examples=6, deadline=None)
@given(st.lists(STATE, min_size=8, max_size=8))
def test_simulated_landing_within_proven_bound(us):
    """The batch simulator (RK4, 50 kN per axis) from Table III states (random, plus every
    per-axis corner and r0 = 0, where the peaks are): no saturation, lands,
    landing time <= the proven bound, per-axis peak thrust <= the proven thrust bound."""
    sg = BS.default_sat()
    u = np.array(us)
    lo = np.array([[b.r_lo for b in TABLE3_AXES], [b.v_lo for b in TABLE3_AXES]])
    hi = np.array([[b.r_hi for b in TABLE3_AXES], [b.v_hi for b in TABLE3_AXES]])
    boxes = [(np.r_[lo[0], lo[1], M0], np.r_[hi[0], hi[1], M0])]
    rc, vc, _ = packed_states(boxes, M0, n_grid=2, n_mc=0)  # every per-axis corner, r0 = 0
    r0 = np.vstack([lo[0] + u[:, :3] * (hi[0] - lo[0]), rc])
    v0 = np.vstack([lo[1] + u[:, 3:] * (hi[1] - lo[1]), vc])
    cert = [axis_certificate(sg, i, boxes, M0) for i in range(3)]
    T = max(c["T_land"] for c in cert)
    res = simulate_batch(r0, v0, np.full(len(r0), M0), _gains(sg), law=NAME,
                         thrust_limit=50_000.0, t_max=T + 5)
    assert res.landed.all() and not res.nonfinite.any()
    assert np.all(res.time_saturated == 0)
    assert np.all(res.landing_time <= T)
    for i in range(3):
        assert np.all(res.peak_thrust[:, i] <= cert[i]["F_b"])


@pytest.mark.slow
def test_cli_tunes_tf60_proven(tmp_path):
    """``lgw tune mars --law bounded-sat --tf 60 --thrust-max 50000`` writes a proven
    certificate whose numbers the bound function reproduces from the file."""
    out = tmp_path / "g.toml"
    run = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                          "tune", "mars", "--law", NAME, "--tf", "60", "--thrust-max", "50000",
                          "--out", str(out)], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    g = load_gains(out)
    cert = g.extra["certificate"]
    assert cert["law"] == NAME and cert["time_proven"] and cert["feasible"]
    assert cert["landing_time_bound_proven"] <= 60 and cert["thrust_bound_proven"] <= 50_000
    sg = BS.sat_from_extra(g.extra)
    env = envelope_from_name("table3+table2")
    T = max(axis_certificate(sg, i, env.boxes, env.m_max)["T_land"] for i in range(3))
    assert T == pytest.approx(cert["landing_time_bound_proven"])


@pytest.mark.slow
def test_tighter_tf_is_not_proven_and_nearest_is_reported():
    env = envelope_from_name("table3")
    res = tune_bounded(BoundedRequest(tf=20.0, thrust_max=50_000.0), env.boxes, env.m_max,
                       law=NAME)
    assert not res.feasible and not res.time_proven and res.T_proven > 20.0


def _bench():
    spec = importlib.util.spec_from_file_location("bench_tune",
                                                  ROOT / "benchmarks" / "bench_tune.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.slow
@pytest.mark.parametrize("name,n,seed", [("table3", 500, 17_031), ("table2", 1000, 17_032)])
def test_fresh_campaigns(name, n, seed):
    """Fresh campaigns with DEFAULT_SAT (the tf 60 s design), apart from the tuner: RK4 at
    dt = 0.02 s, trajectories recorded to tf + 5 s; all land within 60 s, under 50 kN per
    axis, never saturated, never below ground by 0.1 m, and the peak thrust after each axis
    enters its landing band (from the trajectories, ``after_arrival_peaks``) below 15 kN."""
    c = _bench().bounded_campaign(BS.default_sat(), 60.0, 50_000.0, name, n, seed, law=NAME,
                                  table=BS.TABLE)
    assert c["landed_within_tf"] == n and c["under_limit"] and c["saturated_cases"] == 0
    assert c["below_ground_cases_0.1m"] == 0
    assert max(c["peak_after_arrival_axis_N"]) < 15_000.0
