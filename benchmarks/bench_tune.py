"""Benchmark and report for ``lgw tune mars``.

  python benchmarks/bench_tune.py time        tuner wall time on the default problem
  python benchmarks/bench_tune.py compare     exact vs Polyakov bound: peak thrust and fuel of
                                               the gains tuned on each, same tf and limit
  python benchmarks/bench_tune.py check       tune a few targets (or the nearest feasible tf)
                                               and fly FRESH Table III (50) and Table II (300)
                                               campaigns with another seed than the tuner's
  python benchmarks/bench_tune.py bounded: end-to-end time of ``lgw tune mars --law
                                               bounded`` against today's corrected-law tuner, same
                                               run (ratio); then fresh Table III (500) and Table
                                               II (1000) campaigns with the tuned bounded gains
  python benchmarks/bench_tune.py bounded-sat the saturated-cancellation law ``--law bounded-sat``:
                                               end-to-end ``tune_bounded`` time against the
                                               corrected-law tuner measured in the same run
                                               (ratio; ``--baseline-from FILE`` reuses a
                                               baseline JSON this mode wrote earlier, said so
                                               in the output), then fresh Table III (500) and
                                               Table II (1000) campaigns of the tuned gains
                                               with the post-arrival peaks from trajectories
  python benchmarks/bench_tune.py gp          the geometric programs of one tuning run's outer
                                               loop: built once as a DPP family and re-solved
                                               (today) against rebuilt per exponent set (the
                                               design.py of --baseline-rev, loaded from git), same
                                               run: seconds, ratio, largest optimum difference
  python benchmarks/bench_tune.py all

Every number printed comes from ``lgw.tuning.mars.design`` and
``lgw.sim.mars.batch.simulate_batch``; nothing is
cached between runs.  The first simulation compiles the numba kernel (~15 s, reported apart).
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import replace

import numpy as np
from lgw.sim.mars.arrival import after_arrival_peaks
from lgw.sim.mars.campaign import table2_states, table3_states
from lgw.theory.mars.bounds import axis_bounds
from lgw.tuning.mars.design import (
    Request,
    check_campaign,
    envelope_from_name,
    evaluate,
    nearest_feasible_tf,
    tune,
)

CHECK_SEED = 20261122  # the tuner uses seeds 0, 1, 7; campaigns use this one
TARGETS = [  # (tf s, thrust N, limit, envelope)
    (60.0, 50_000.0, "axis", "table3+table2"),
    (60.0, 50_000.0, "axis", "table3"),
    (90.0, 50_000.0, "axis", "table3+table2"),
    (120.0, 40_000.0, "axis", "table3"),
]


def _warm() -> float:
    t = time.perf_counter()
    env = envelope_from_name("table3")
    from lgw.theory.mars.gains import default_gains

    evaluate(env.extreme_states(5e4, "axis")[:2], default_gains(), Request(60.0, 5e4))
    return time.perf_counter() - t


def bench_time(envelope: str = "table3+table2", repeat: int = 1) -> dict:
    warm = _warm()
    env = envelope_from_name(envelope)
    times, res = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        res = tune(Request(tf=60.0, thrust_max=50_000.0), env)
        times.append(time.perf_counter() - t)
    out = {"problem": f"tf=60 s, 50 kN/axis, envelope {envelope}", "numba_warmup_s": warm,
           "tune_s": times, "feasible": res.feasible, "reason": res.reason,
           "states_simulated": res.search_counts.get("total"),
           "exponent_sets": len(res.exponent_log)}
    print(json.dumps(out, indent=1))
    return out


def _summary(res, req) -> dict:
    ev = res.evaluation
    if res.gains is None or ev is None:
        return {"feasible": False, "reason": res.reason}
    b = axis_bounds(res.gains)
    return {
        "feasible": res.feasible,
        "exponents": [res.gains.q1, res.gains.q2, res.gains.g1, res.gains.g2],
        "bound_exact_max": max(x["landing_time_bound"] for x in b.values()),
        "bound_polyakov_max": max(x["landing_time_bound_polyakov"] for x in b.values()),
        "peak_thrust_N": ev.worst_value, "peak_axis_N": [round(x) for x in ev.peak_axis],
        "peak_fraction": ev.worst_value / req.thrust_max,
        "fuel_mean_kg": ev.fuel_mean, "fuel_max_kg": ev.fuel_max,
        "max_landing_time_s": ev.max_landing_time,
    }


def bench_compare(tfs=(60.0, 120.0, 240.0), thrust: float = 50_000.0,
                  envelope: str = "table3") -> list[dict]:
    """Gain of the exact bound: same tf, thrust limit and envelope, tuned on each bound."""
    env = envelope_from_name(envelope)
    rows = []
    for tf in tfs:
        row = {"tf": tf, "thrust_max": thrust, "envelope": envelope}
        for bound in ("exact", "polyakov"):
            req = Request(tf=tf, thrust_max=thrust, bound=bound)
            row[bound] = _summary(tune(req, env), req)
        rows.append(row)
        e, p = row["exact"], row["polyakov"]
        if "peak_thrust_N" in e and "peak_thrust_N" in p:
            print(f"tf {tf:6.1f} s: peak exact {e['peak_thrust_N']:9.0f} N  polyakov "
                  f"{p['peak_thrust_N']:9.0f} N  (x{p['peak_thrust_N'] / e['peak_thrust_N']:.2f});"
                  f" fuel mean exact {e['fuel_mean_kg']:.1f} kg polyakov "
                  f"{p['fuel_mean_kg']:.1f} kg; feasible exact {e['feasible']} polyakov "
                  f"{p['feasible']}")
    print(json.dumps(rows, indent=1, default=float))
    return rows


def bench_check(targets=TARGETS, n3: int = 50, n2: int = 300) -> list[dict]:
    """Tune each target (nearest feasible tf if infeasible), then fly fresh campaigns."""
    rows = []
    for tf, thrust, limit, envelope in targets:
        env = envelope_from_name(envelope)
        req = Request(tf=tf, thrust_max=thrust, limit=limit)
        t = time.perf_counter()
        res = tune(req, env)
        row: dict = {"target": [tf, thrust, limit, envelope], "feasible": res.feasible,
                     "reason": res.reason}
        if not res.feasible:
            tf_ok, res_ok = nearest_feasible_tf(replace(req, tf=max(tf, res.tf_min_envelope)),
                                                env)
            row["nearest_feasible_tf"] = tf_ok
            if tf_ok is None:
                rows.append(row)
                continue
            req, res = replace(req, tf=tf_ok), res_ok  # confirmed by the full search
        row["tune_s"] = time.perf_counter() - t
        row["tuned"] = _summary(res, req)
        if res.gains is not None:
            for name, fn, n in (("table3", table3_states, n3), ("table2", table2_states, n2)):
                r0, v0, m0 = fn(n, seed=CHECK_SEED)
                c = check_campaign(res.gains, r0, v0, m0, req, env, seed=CHECK_SEED)
                row[name] = c.__dict__ | {"passed": c.passed}
        rows.append(row)
        print(json.dumps(row, indent=1, default=float))
    return rows


BOUNDED_SEEDS = {"table3": 17_003, "table2": 17_002}  # campaign seeds (tuner: seed 0)


def _tune_bounded_e2e(tf: float, thrust: float, envelope: str) -> tuple[float, object]:
    """What ``lgw tune mars --law bounded`` does, timed: design, then (only if the proven bound
    exceeds tf) the simulation check."""
    from lgw.tuning.mars.design_bounded import BoundedRequest, simulate_check, tune_bounded
    env = envelope_from_name(envelope)
    req = BoundedRequest(tf=tf, thrust_max=thrust)
    t = time.perf_counter()
    res = tune_bounded(req, env.boxes, env.m_max, simulate=lambda bg: simulate_check(
        bg, req, env.boxes, env.m_max, t_max=max(1.5 * tf, tf + 20)))
    return time.perf_counter() - t, res


def bounded_campaign(gains, tf: float, thrust: float, name: str, n: int, seed: int,
                     dt: float = 0.02, chunk: int = 250, law: str = "bounded",
                     extra: dict | None = None, table: str = "bounded") -> dict:
    """A fresh campaign with the bounded law, simulated apart from the tuner (other states and
    seed, RK4 at dt = 0.02 s instead of the tuner's 0.05 s, trajectories recorded)."""
    from dataclasses import replace as _replace

    from lgw.sim.mars.batch import simulate_batch
    from lgw.theory.mars.gains import default_gains
    g = _replace(default_gains(), extra={table: gains.to_dict(), **(extra or {})})
    fn = table3_states if name == "table3" else table2_states
    r0, v0, m0 = fn(n, seed=seed)
    acc: dict[str, list] = {k: [] for k in ("lt", "landed", "peak", "sat", "alt", "after")}
    for a in range(0, n, chunk):
        sl = slice(a, min(a + chunk, n))
        res = simulate_batch(r0[sl], v0[sl], m0[sl], g, law=law, thrust_limit=thrust,
                             t_max=tf + 5.0, dt=dt, record=True, stop="t_max")
        tr = res.trajectory
        _, after = after_arrival_peaks(tr["r"], tr["v"], tr["F"])
        acc["lt"].append(res.landing_time)
        acc["landed"].append(res.landed & (res.landing_time <= tf))
        acc["peak"].append(res.peak_thrust)
        acc["sat"].append(res.time_saturated)
        acc["alt"].append(res.min_altitude)
        acc["after"].append(after)
    lt, landed = np.concatenate(acc["lt"]), np.concatenate(acc["landed"])
    peak, sat = np.concatenate(acc["peak"]), np.concatenate(acc["sat"])
    alt, after = np.concatenate(acc["alt"]), np.concatenate(acc["after"])
    return {"campaign": name, "cases": n, "seed": seed, "dt": dt, "tf": tf,
            "landed_within_tf": int(landed.sum()), "max_landing_time_s": float(np.nanmax(lt)),
            "mean_landing_time_s": float(np.nanmean(lt)),
            "peak_thrust_axis_N": np.max(peak, axis=0).round(0).tolist(),
            "under_limit": bool(np.all(peak <= thrust)), "saturated_cases": int((sat > 0).sum()),
            "min_altitude_m": float(np.min(alt)),
            "below_ground_cases_0.1m": int((alt < -0.1).sum()),
            "below_ground_cases_strict": int((alt < 0).sum()),
            "peak_after_arrival_axis_N": np.nanmax(after, axis=0).round(1).tolist(),
            "passed": bool(landed.all() and np.all(peak <= thrust) and (sat == 0).all()
                           and (alt >= -0.1).all())}


def bench_bounded(tf: float = 60.0, thrust: float = 50_000.0, envelope: str = "table3+table2",
                  baseline: bool = True, n3: int = 500, n2: int = 1000) -> dict:
    from lgw.theory.mars import bounded as B
    from lgw.tuning.mars.design_bounded import simulate_check
    warm = time.perf_counter()
    env = envelope_from_name(envelope)
    from lgw.tuning.mars.design_bounded import BoundedRequest
    simulate_check(B.default_bounded(), BoundedRequest(tf, thrust), env.boxes, env.m_max,
                   t_max=5.0, n_mc=1)  # compile the bounded kernel outside the timing
    warm = time.perf_counter() - warm
    t_new, res = _tune_bounded_e2e(tf, thrust, envelope)
    out: dict = {"problem": f"tf={tf:g} s, {thrust:g} N/axis, envelope {envelope}",
                 "bounded_compile_s": warm, "bounded_e2e_s": t_new,
                 "bounded_feasible": res.feasible, "bounded_reason": res.reason,
                 "bounded_T_proven": res.T_proven, "bounded_F_proven": res.F_proven,
                 "bounded_timings": res.timings}
    print(json.dumps(out, indent=1, default=float), flush=True)
    gains, tf_c = res.gains, tf
    if not res.feasible:
        tf_c = float(np.ceil(res.T_proven * 10) / 10)
        t2, res2 = _tune_bounded_e2e(tf_c, thrust, envelope)
        out.update({"nearest_tf": tf_c, "bounded_e2e_nearest_s": t2,
                    "nearest_feasible": res2.feasible, "nearest_time_proven": res2.time_proven})
        gains = res2.gains
        print(json.dumps({k: out[k] for k in ("nearest_tf", "bounded_e2e_nearest_s")},
                         default=float), flush=True)
    out["gains"] = gains.to_dict()
    for name, n in (("table3", n3), ("table2", n2)):
        out[name] = bounded_campaign(gains, tf_c, thrust, name, n, BOUNDED_SEEDS[name])
        print(json.dumps(out[name], indent=1, default=float), flush=True)
    if baseline:
        _warm()
        t = time.perf_counter()
        base = tune(Request(tf=tf, thrust_max=thrust), env)
        t_old = time.perf_counter() - t
        if not base.feasible:
            t = time.perf_counter()
            nearest_feasible_tf(replace(Request(tf=tf, thrust_max=thrust),
                                        tf=max(tf, base.tf_min_envelope)), env)
            t_old += time.perf_counter() - t
        out.update({"corrected_e2e_s": t_old, "corrected_feasible": base.feasible,
                    "ratio_corrected_over_bounded": t_old / t_new})
        print(json.dumps({k: out[k] for k in ("corrected_e2e_s", "ratio_corrected_over_bounded")},
                         default=float), flush=True)
    return out


SAT_SEEDS = {"table3": 17_031, "table2": 17_032}  # campaign seeds (tuner: seed 0)


def bench_bounded_sat(tf: float = 60.0, thrust: float = 50_000.0,
                      envelope: str = "table3+table2", n3: int = 500, n2: int = 1000,
                      baseline: bool = True, baseline_from: str | None = None,
                      out_file: str | None = None) -> dict:
    """``--law bounded-sat`` end to end (design, plus the simulation check only when the proven
    bound misses tf), the corrected-law tuner (``tune`` + ``nearest_feasible_tf``) on the same
    request and envelope in the same run, and fresh campaigns of the tuned gains (RK4 at
    dt = 0.02 s, trajectories recorded, flown to tf + 5 s; other states and seeds than the
    tuner's).  Every number is measured here."""
    from lgw.theory.mars import bounded_sat as BS
    from lgw.tuning.mars.design_bounded import BoundedRequest, simulate_check, tune_bounded
    env = envelope_from_name(envelope)
    warm = time.perf_counter()
    req = BoundedRequest(tf=tf, thrust_max=thrust)
    simulate_check(BS.default_sat(), req, env.boxes, env.m_max, t_max=5.0, n_mc=1)
    warm = time.perf_counter() - warm
    t = time.perf_counter()
    res = tune_bounded(req, env.boxes, env.m_max, law=BS.NAME, simulate=lambda g: simulate_check(
        g, req, env.boxes, env.m_max, t_max=max(1.5 * tf, tf + 20)))
    t_new = time.perf_counter() - t
    out: dict = {"problem": f"tf={tf:g} s, {thrust:g} N/axis, envelope {envelope}",
                 "law": BS.NAME, "compile_s": warm, "e2e_s": t_new, "feasible": res.feasible,
                 "time_proven": res.time_proven, "T_proven": res.T_proven,
                 "F_proven": res.F_proven, "timings": res.timings}
    print(json.dumps(out, indent=1, default=float), flush=True)
    tf_c = tf if res.feasible else float(np.ceil(res.T_proven * 10) / 10)
    out["gains"] = res.gains.to_dict()
    for name, n in (("table3", n3), ("table2", n2)):
        if n > 0:
            out[name] = bounded_campaign(res.gains, tf_c, thrust, name, n, SAT_SEEDS[name],
                                         law=BS.NAME, table=BS.TABLE)
            print(json.dumps(out[name], indent=1, default=float), flush=True)
    if baseline_from:
        with open(baseline_from) as f:
            base = json.load(f)
        out["corrected_e2e_s"] = base["corrected_e2e_s"]
        out["baseline_source"] = (f"{baseline_from} (measured in an earlier run, not this "
                                  "one)")
    elif baseline:
        _warm()
        t = time.perf_counter()
        b = tune(Request(tf=tf, thrust_max=thrust), env)
        t_old = time.perf_counter() - t
        if not b.feasible:
            t = time.perf_counter()
            nearest_feasible_tf(replace(Request(tf=tf, thrust_max=thrust),
                                        tf=max(tf, b.tf_min_envelope)), env)
            t_old += time.perf_counter() - t
        out.update({"corrected_e2e_s": t_old, "corrected_feasible": b.feasible,
                    "baseline_source": "measured in this run"})
    if "corrected_e2e_s" in out:
        out["ratio_corrected_over_bounded_sat"] = out["corrected_e2e_s"] / t_new
        print(json.dumps({k: out[k] for k in ("corrected_e2e_s", "baseline_source",
                                              "ratio_corrected_over_bounded_sat")},
                         default=float), flush=True)
    if out_file:
        with open(out_file, "w") as f:
            json.dump(out, f, indent=1, default=float)
    return out


def bench_gp(envelope: str, baseline_rev: str, n: int) -> dict:
    """GP solve time of the outer loop's coarse grid, DPP family vs rebuild, one run."""
    import importlib.util
    import itertools
    import subprocess
    import sys

    from lgw.tuning.mars import design as new

    src = subprocess.run(["git", "show", f"{baseline_rev}:tuning/mars/design.py"],
                         capture_output=True, text=True, check=True).stdout
    spec = importlib.util.spec_from_loader("design_baseline", loader=None)
    old = importlib.util.module_from_spec(spec)
    sys.modules["design_baseline"] = old
    exec(compile(src, f"{baseline_rev}:tuning/mars/design.py", "exec"), old.__dict__)
    env = new.envelope_from_name(envelope)
    grid = list(itertools.product(*new.COARSE_GRID.values()))[:n]
    out = {}
    for label, req in (("no disturbance, exact, axis", new.Request(tf=90.0, thrust_max=5e4)),
                       ("a_max 0.5, neighbourhood 20 m (4 branches)",
                        new.Request(tf=200.0, thrust_max=5e4, a_max=0.5, neighborhood=20.0)),
                       ("polyakov, norm", new.Request(tf=90.0, thrust_max=5e4,
                                                      bound="polyakov", limit="norm"))):
        t = time.perf_counter()
        ro = [old.solve_gp(old.Exponents(*e), req, env) for e in grid]
        t_old = time.perf_counter() - t
        t = time.perf_counter()
        rn = [new.solve_gp(new.Exponents(*e), req, env) for e in grid]
        t_new = time.perf_counter() - t
        both = [(a.value, b.value) for a, b in zip(ro, rn, strict=True)
                if np.isfinite(a.value) and np.isfinite(b.value)]
        diff = max((abs(a - b) / abs(a) for a, b in both), default=float("nan"))
        feas = sum((a.gains is None) != (b.gains is None) for a, b in zip(ro, rn, strict=True))
        out[label] = {"gps": len(grid), "rebuild_s": t_old, "family_s": t_new,
                      "ratio": t_old / t_new, "max_rel_optimum_diff": diff,
                      "feasibility_differences": feas}
        print(f"{label}: {len(grid)} GPs, rebuilt {t_old:.2f} s, family {t_new:.2f} s, "
              f"ratio {t_old / t_new:.1f}; largest relative difference of the optimum "
              f"{diff:.1e}; feasibility differences {feas}", flush=True)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("time", "compare", "check", "bounded", "bounded-sat",
                                     "gp", "all"))
    ap.add_argument("--baseline-rev", default="e448ec4",
                    help="gp: the git revision whose design.py rebuilds every GP")
    ap.add_argument("--gps", type=int, default=27, help="gp: exponent sets per request")
    ap.add_argument("--no-baseline", action="store_true", help="bounded: skip the corrected tuner")
    ap.add_argument("--envelope", default=None)
    ap.add_argument("--tf", type=float, nargs="*", default=None)
    ap.add_argument("--baseline-from", default=None,
                    help="bounded-sat: take corrected_e2e_s from a JSON this mode wrote (--save) "
                         "instead of re-measuring it (~20 min); the output says so")
    ap.add_argument("--save", default=None, help="bounded-sat: write the result JSON here")
    ap.add_argument("--cases", type=int, nargs=2, default=(500, 1000),
                    help="bounded-sat: Table III and Table II campaign sizes (0 skips)")
    args = ap.parse_args()
    np.set_printoptions(precision=4)
    if args.what in ("gp", "all"):
        bench_gp(args.envelope or "table3+table2", args.baseline_rev, args.gps)
    if args.what in ("time", "all"):
        bench_time(args.envelope or "table3+table2")
    if args.what in ("compare", "all"):
        bench_compare(tuple(args.tf) if args.tf else (60.0, 120.0, 240.0),
                      envelope=args.envelope or "table3")
    if args.what in ("check", "all"):
        bench_check()
    if args.what in ("bounded", "all"):
        bench_bounded(baseline=not args.no_baseline)
    if args.what in ("bounded-sat", "all"):
        bench_bounded_sat(envelope=args.envelope or "table3+table2", n3=args.cases[0],
                          n2=args.cases[1], baseline=not args.no_baseline,
                          baseline_from=args.baseline_from, out_file=args.save)


if __name__ == "__main__":
    main()
