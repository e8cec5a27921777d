"""Seed 002: the compiled sampled-data kernel (lgw.sim.eros.batch.simulate, engine "kernel", on
lgw.sim.integrate's zero-order hold) against two baselines measured in the same run:

  1. a per-case solve_ivp loop (reference_solve: DOP853 between samples, the control held),
     on the same cases (``--cases``, ``--t-final``);
  2. the numpy stand-in (simulate_numpy: vectorised RK4 over cases, the same ZOH and substeps)
     on a Monte Carlo campaign (``--mc-cases``, ``--mc-t-final``).

Prints the time ratios and the largest differences.  ``--startup`` also times a fresh process
twice with an empty kernel cache (compile, then load from the cache).

``--descent`` times the whole descent instead (lgw.sim.eros.descent, one case from Table 1's
start to touchdown), against baselines measured in the same run:

  3. one evaluation of the polyhedral gravity: the compiled one (lgw.sim.eros.polygrav, the
     kernels') against the direct numpy one (lgw.theory.eros.polyhedron);
  4. the whole descent with the plant's polyhedron re-evaluated every LIN_STEP m (the default)
     against the same kernel with the polyhedron at every evaluation, and coarser / finer
     re-evaluation steps: time and the change of the touchdown numbers;
  5. the last ``--segment`` s of the descent: the kernel against the per-sample solve_ivp loop
     (reference_solve_descent: DOP853, rtol 1e-10, the polyhedron at every evaluation, the
     contact by event location): time ratio and differences.

    python benchmarks/bench_eros.py [--cases 20] [--t-final 2] [--mc-cases 500]
                                    [--mc-t-final 15] [--repeat 3] [--startup]
    python benchmarks/bench_eros.py --descent [--segment 1000] [--repeat 3]
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


def descent(args) -> None:
    from dataclasses import replace

    from lgw.sim.eros import polygrav as PG
    from lgw.sim.eros.descent import (
        DescentOptions,
        descent_gains,
        reference_solve_descent,
        simulate_descent,
    )
    from lgw.theory.eros import parameters as P
    from lgw.theory.eros.polyhedron import eros_accel

    pts = np.array([P.R0, P.RF, [2888.6, 688.0, 5300.0]])
    PG.field(pts[:1])  # compile / load outside the timing
    eros_accel(pts[:1])
    t_c, _ = best_of(lambda: PG.field(np.repeat(pts, 20, axis=0)), args.repeat)
    t_n, _ = best_of(lambda: eros_accel(np.repeat(pts, 2, axis=0)), args.repeat)
    per_c, per_n = t_c / 60, t_n / 6
    print("3. one polyhedron evaluation (14744 faces, 22116 edges)")
    print(f"compiled (polygrav, with the gradient tensor): {1e3 * per_c:.3f} ms")
    print(f"direct numpy (theory.eros.polyhedron):         {1e3 * per_n:.3f} ms")
    print(f"ratio numpy / compiled:                        {per_n / per_c:.1f}")

    g = descent_gains()
    z = np.zeros((1, 3))
    base = DescentOptions(stride=0)
    simulate_descent(z, z, g, replace(base, t0=base.profile().t_touchdown - 5.0))  # load

    def touch(r):
        return (float(r.t_outcome[0]), float(r.touchdown["speed"][0]), float(r.fuel[0]),
                r.pos_end[0].copy())
    t_ex, r_ex = best_of(lambda: simulate_descent(z, z, g, replace(
        base, gravity="polyhedron-exact")), 1)
    ex = touch(r_ex)
    print(f"4. the whole descent from Table 1's start ({r_ex.outcome_names()[0]} at "
          f"{ex[0]:.3f} s, {ex[1]:.5f} m/s, fuel {ex[2]:.4f} kg), fuzzy-tanh")
    print(f"polyhedron at every evaluation (one run):      {t_ex:.2f} s")
    for step in (3.0, P.LIN_STEP, 30.0):
        t_l, r_l = best_of(lambda step=step: simulate_descent(z, z, g, replace(
            base, lin_step=step)), args.repeat)
        li = touch(r_l)
        print(f"re-evaluated every {step:4g} m (best of {args.repeat}):    {t_l:.3f} s, "
              f"ratio {t_ex / t_l:.1f}; touchdown time {li[0] - ex[0]:+.2e} s, speed "
              f"{(li[1] - ex[1]) / ex[1]:+.1e} rel., fuel {(li[2] - ex[2]) / ex[2]:+.1e} rel.,"
              f" point {np.linalg.norm(li[3] - ex[3]):.1e} m")

    seg = replace(base, t0=float(base.profile().t_touchdown - args.segment))
    e0, ed0 = np.array([[0.5, -0.3, 0.4]]), np.array([[0.002, 0.001, -0.003]])
    t_k, r_k = best_of(lambda: simulate_descent(e0, ed0, g, seg), args.repeat)
    t0 = time.perf_counter()
    ref = reference_solve_descent(e0, ed0, g, seg)
    t_r = time.perf_counter() - t0
    k = touch(r_k)
    print(f"5. the last {args.segment:g} s to touchdown, offset {e0[0].tolist()} m, "
          f"{ed0[0].tolist()} m/s")
    print(f"kernel (best of {args.repeat}):                        {t_k:.3f} s")
    print(f"per-sample solve_ivp loop (one run):           {t_r:.2f} s")
    print(f"ratio loop / kernel:                           {t_r / t_k:.0f}")
    print(f"outcome kernel / solve_ivp:                    {r_k.outcome_names()[0]} / "
          f"{ref['outcome']}")
    print(f"touchdown time difference:                     {k[0] - ref['t_outcome']:+.2e} s")
    print(f"touchdown speed difference:                    "
          f"{k[1] - ref['touchdown']['speed']:+.2e} m/s")
    print(f"fuel difference:                               {k[2] - ref['fuel']:+.2e} kg")
    print(f"contact point distance:                        "
          f"{np.linalg.norm(k[3] - ref['pos_end']):.2e} m")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=20)
    ap.add_argument("--t-final", type=float, default=2.0)
    ap.add_argument("--mc-cases", type=int, default=500)
    ap.add_argument("--mc-t-final", type=float, default=15.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--startup", action="store_true")
    ap.add_argument("--descent", action="store_true")
    ap.add_argument("--segment", type=float, default=1000.0)
    args = ap.parse_args()
    if args.descent:
        descent(args)
        return
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
