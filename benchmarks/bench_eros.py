"""Seed 002: the compiled sampled-data kernel (lgw.sim.eros.batch.simulate, engine "kernel", on
lgw.sim.integrate's zero-order hold) against two baselines measured in the same run:

  1. a per-case solve_ivp loop (reference_solve: DOP853 between samples, the control held),
     on the same cases (``--cases``, ``--t-final``);
  2. the numpy stand-in (simulate_numpy: vectorised RK4 over cases, the same ZOH and substeps)
     on a Monte Carlo campaign (``--mc-cases``, ``--mc-t-final``).

Prints the time ratios and the largest differences.  ``--startup`` also times a fresh process
twice with an empty kernel cache (compile, then load from the cache).

    python benchmarks/bench_eros.py [--cases 20] [--t-final 2] [--mc-cases 500]
                                    [--mc-t-final 15] [--repeat 3] [--startup]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from lgw.sim.eros.batch import SimOptions, reference_solve, simulate, simulate_numpy
from lgw.sim.eros.campaign import offsets
from lgw.theory.eros.gains import default_gains

STARTUP = ("import time; t = time.perf_counter(); import numpy as np; "
           "from lgw.sim.eros.batch import SimOptions, simulate; "
           "from lgw.theory.eros.gains import default_gains; "
           "simulate(np.ones((1, 3)), np.zeros((1, 3)), default_gains(), "
           "SimOptions(t_final=0.05)); print(time.perf_counter() - t)")


def best_of(fn, repeat: int) -> tuple[float, object]:
    """Shortest wall time of ``repeat`` calls (s) and the last result."""
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def startup() -> None:
    with tempfile.TemporaryDirectory(prefix="lgw-bench-eros-") as d:
        env = dict(os.environ, LGW_CACHE_DIR=d)
        times = [float(subprocess.run([sys.executable, "-c", STARTUP], env=env, check=True,
                                      capture_output=True, text=True).stdout.split()[-1])
                 for _ in range(2)]
    print(f"fresh process, empty cache (compile):  {times[0]:.2f} s")
    print(f"fresh process, cached kernel:          {times[1]:.2f} s")
    print(f"ratio compile / cached:                {times[0] / times[1]:.1f}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=20)
    ap.add_argument("--t-final", type=float, default=2.0)
    ap.add_argument("--mc-cases", type=int, default=500)
    ap.add_argument("--mc-t-final", type=float, default=15.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--startup", action="store_true")
    args = ap.parse_args()
    g = default_gains()
    opts = SimOptions(law="ftsmc", switch="tanh", t_final=args.t_final)
    e0, ed0, ph = offsets(args.cases, 3)
    simulate(e0[:1], ed0[:1], g, SimOptions(t_final=0.05))  # kernel load outside the timing
    simulate_numpy(e0[:1], ed0[:1], g, SimOptions(t_final=0.05))  # lambdify caches
    t_kernel, res = best_of(lambda: simulate(e0, ed0, g, opts, ph), args.repeat)
    t_np1, _ = best_of(lambda: simulate_numpy(e0, ed0, g, opts, ph), args.repeat)
    t0 = time.perf_counter()
    refs = [reference_solve(e0[i:i + 1], ed0[i:i + 1], g, opts, float(ph[i]))
            for i in range(args.cases)]
    t_loop = time.perf_counter() - t0
    diff = max(float(np.max(np.abs(res.e[:, i] - refs[i].e[:, 0]))) for i in range(args.cases))
    print(f"1. {args.cases} cases, {args.t_final} s at dt = {opts.dt} s (ftsmc-tanh, known D)")
    print(f"kernel, RK4 n_sub = {opts.n_sub} (best of {args.repeat}): {t_kernel:.4f} s")
    print(f"per-case solve_ivp loop (one run):    {t_loop:.3f} s")
    print(f"ratio loop / kernel:                  {t_loop / t_kernel:.1f}")
    print(f"numpy stand-in (best of {args.repeat}):          {t_np1:.4f} s")
    print(f"ratio stand-in / kernel:              {t_np1 / t_kernel:.1f}")
    print(f"max |e_kernel - e_solve_ivp|:         {diff:.2e} m")

    mo = SimOptions(law="fuzzy", switch="sign", t_final=args.mc_t_final)
    e0, ed0, ph = offsets(args.mc_cases, 4)
    t_k, rk = best_of(lambda: simulate(e0, ed0, g, mo, ph), args.repeat)
    t_n, rn = best_of(lambda: simulate_numpy(e0, ed0, g, mo, ph), args.repeat)
    print(f"2. {args.mc_cases} cases, {args.mc_t_final} s (fuzzy-sign, known D), "
          f"best of {args.repeat}")
    print(f"kernel:                               {t_k:.3f} s")
    print(f"numpy stand-in:                       {t_n:.3f} s")
    print(f"ratio stand-in / kernel:              {t_n / t_k:.1f}")
    print(f"max |e_kernel - e_stand-in|:          {float(np.max(np.abs(rk.e - rn.e))):.2e} m")
    print(f"outcome classes equal:                {bool(np.all(rk.outcome == rn.outcome))}")
    if args.startup:
        startup()


if __name__ == "__main__":
    main()
