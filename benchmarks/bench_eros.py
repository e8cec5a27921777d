"""Seed 002: the batched sampled-data RK4 (lgw.sim.eros.batch.simulate, the numpy stand-in)
against a per-case solve_ivp loop (reference_solve: DOP853 between samples), same cases, same
run.  Prints the time ratio and the largest state difference.

    python benchmarks/bench_eros.py [--cases 20] [--t-final 2]
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from lgw.sim.eros.batch import SimOptions, reference_solve, simulate
from lgw.sim.eros.campaign import offsets
from lgw.theory.eros.gains import default_gains


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=20)
    ap.add_argument("--t-final", type=float, default=2.0)
    args = ap.parse_args()
    g = default_gains()
    opts = SimOptions(law="ftsmc", switch="tanh", t_final=args.t_final)
    e0, ed0, ph = offsets(args.cases, 3)
    simulate(e0[:1], ed0[:1], g, SimOptions(t_final=0.05))  # lambdify / caches outside timing
    t0 = time.perf_counter()
    res = simulate(e0, ed0, g, opts, ph)
    t_batch = time.perf_counter() - t0
    t0 = time.perf_counter()
    refs = [reference_solve(e0[i:i + 1], ed0[i:i + 1], g, opts, float(ph[i]))
            for i in range(args.cases)]
    t_loop = time.perf_counter() - t0
    diff = max(float(np.max(np.abs(res.e[:, i] - refs[i].e[:, 0]))) for i in range(args.cases))
    print(f"cases {args.cases}, {args.t_final} s at dt = {opts.dt} s (ftsmc-tanh)")
    print(f"batched RK4 (n_sub = {opts.n_sub}): {t_batch:.3f} s")
    print(f"per-case solve_ivp loop:         {t_loop:.3f} s")
    print(f"ratio loop / batched:            {t_loop / t_batch:.1f}")
    print(f"max |e_batch - e_ref|:           {diff:.2e} m")


if __name__ == "__main__":
    main()
