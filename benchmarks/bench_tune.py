"""Benchmark and report for ``lgw tune mars`` (issue 5).

  python benchmarks/bench_tune.py time        tuner wall time on the default problem
  python benchmarks/bench_tune.py compare     exact vs Polyakov bound: peak thrust and fuel of
                                               the gains tuned on each, same tf and limit
  python benchmarks/bench_tune.py check       tune a few targets (or the nearest feasible tf)
                                               and fly FRESH Table III (50) and Table II (300)
                                               campaigns with another seed than the tuner's
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("time", "compare", "check", "all"))
    ap.add_argument("--envelope", default=None)
    ap.add_argument("--tf", type=float, nargs="*", default=None)
    args = ap.parse_args()
    np.set_printoptions(precision=4)
    if args.what in ("time", "all"):
        bench_time(args.envelope or "table3+table2")
    if args.what in ("compare", "all"):
        bench_compare(tuple(args.tf) if args.tf else (60.0, 120.0, 240.0),
                      envelope=args.envelope or "table3")
    if args.what in ("check", "all"):
        bench_check()


if __name__ == "__main__":
    main()
