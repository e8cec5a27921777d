"""Seed 001: the compiled batched RK4 (``lgw.sim.lunar.batch.simulate`` on ``lgw.sim.integrate``,
no trajectory record) against a per-case ``solve_ivp`` loop (RK45, rtol 1e-6, atol 1e-8) and
against the numpy-vectorised RK4 of the same field (``rk4_numpy``), on the same cases and
horizon, all measured in this run.  Prints the ratios; keep it short.

    python benchmarks/bench_lunar.py [--cases N] [--t-end S] [--loop-cases M]

The solve_ivp loop runs ``--loop-cases`` of the cases (default all) and is scaled to N.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from lgw.sim.lunar.batch import rk4_numpy, simulate, solve_ivp_case
from lgw.sim.lunar.closed_loop import RunOptions, initial_state, make_context
from lgw.sim.lunar.reference import reference
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar.cmd_simulate import random_cases


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=64)
    ap.add_argument("--t-end", type=float, default=2.0)
    ap.add_argument("--loop-cases", type=int, default=None)
    a = ap.parse_args()
    g, ref = paper_gains(), reference()
    opts = RunOptions(t_end=a.t_end)
    dh, dv, Q0 = random_cases(a.cases, seed=0)
    ctx = make_context(ref, [g] * a.cases, opts)
    X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, a.cases)), [g] * a.cases)
    warm = make_context(ref, [g], RunOptions(t_end=0.1))
    simulate(warm, X0[:, :1], record=False)  # compile / load the kernel
    rk4_numpy(warm, X0[:, :1])  # lambdify
    t0 = time.perf_counter()
    res = simulate(ctx, X0, record=False)
    t_nb = time.perf_counter() - t0
    t0 = time.perf_counter()
    res_np = rk4_numpy(ctx, X0, record_every=10)
    t_np = time.perf_counter() - t0
    m = a.cases if a.loop_cases is None else min(a.loop_cases, a.cases)
    ci = make_context(ref, [g], opts)
    errs = []
    t0 = time.perf_counter()
    for i in range(m):
        sol = solve_ivp_case(ci, X0[:, i], np.array([0.0, a.t_end]), rtol=1e-6, atol=1e-8,
                             method="RK45")
        errs.append(float(np.max(np.abs(sol.y[3:6, -1] - res.cases["y_end"][i, 3:6]))))
    t_loop = (time.perf_counter() - t0) * a.cases / m
    d_np = float(np.max(np.abs(res_np.X[-1] - res.cases["y_end"].T)))
    print(f"{a.cases} cases, {a.t_end} s of flight, RK4 dt = {opts.dt} s")
    print(f"compiled RK4 (lgw.sim.integrate): {t_nb:8.3f} s  ({t_nb / a.cases * 1e3:.2f} ms/case)")
    print(f"numpy RK4 (rk4_numpy):            {t_np:8.3f} s  ({t_np / a.cases * 1e3:.2f} ms/case)")
    print(f"per-case solve_ivp (RK45):        {t_loop:8.3f} s  ({t_loop / a.cases * 1e3:.2f} "
          f"ms/case, {m} cases run)")
    print(f"ratio solve_ivp loop / compiled:  {t_loop / t_nb:8.1f}")
    print(f"ratio numpy RK4 / compiled:       {t_np / t_nb:8.1f}")
    print(f"max |state| difference compiled vs numpy at t_end: {d_np:.3g}")
    print(f"max |V| difference compiled vs solve_ivp at t_end: {max(errs):.3g} m/s")


if __name__ == "__main__":
    main()
