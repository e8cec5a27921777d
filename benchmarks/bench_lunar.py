"""Seed 001: the batched RK4 stand-in (``lgw.sim.lunar.batch.rk4_batch``, all cases in one numpy
array) against a per-case ``solve_ivp`` loop (RK45, rtol 1e-6, atol 1e-8) on the same cases
and horizon, measured in the same run.  Prints the ratio; keep it short (2 s of flight).

    python benchmarks/bench_lunar.py [--cases N] [--t-end S]
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from lgw.sim.lunar.batch import rk4_batch, solve_ivp_case
from lgw.sim.lunar.closed_loop import RunOptions, initial_state, make_context
from lgw.sim.lunar.reference import reference
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar.cmd_simulate import random_cases


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=16)
    ap.add_argument("--t-end", type=float, default=2.0)
    a = ap.parse_args()
    g, ref = paper_gains(), reference()
    opts = RunOptions(t_end=a.t_end)
    dh, dv, Q0 = random_cases(a.cases, seed=0)
    ctx = make_context(ref, [g] * a.cases, opts)
    X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, a.cases)), [g] * a.cases)
    rk4_batch(make_context(ref, [g], RunOptions(t_end=0.1)), X0[:, :1])  # warm-up (lambdify)
    t0 = time.perf_counter()
    res = rk4_batch(ctx, X0, record_every=10)
    t_batch = time.perf_counter() - t0
    ci = make_context(ref, [g], opts)
    t0 = time.perf_counter()
    errs = []
    for i in range(a.cases):
        sol = solve_ivp_case(ci, X0[:, i], res.t, rtol=1e-6, atol=1e-8, method="RK45")
        errs.append(float(np.max(np.abs(sol.y[3:6, -1] - res.X[-1, 3:6, i]))))
    t_loop = time.perf_counter() - t0
    print(f"{a.cases} cases, {a.t_end} s of flight, RK4 dt = {opts.dt} s")
    print(f"batched RK4:          {t_batch:8.3f} s  ({t_batch / a.cases * 1e3:.1f} ms per case)")
    print(f"per-case solve_ivp:   {t_loop:8.3f} s  ({t_loop / a.cases * 1e3:.1f} ms per case)")
    print(f"ratio loop / batched: {t_loop / t_batch:8.2f}")
    print(f"max |V| difference at t_end: {max(errs):.3g} m/s")


if __name__ == "__main__":
    main()
