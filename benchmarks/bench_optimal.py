"""Solve time of the fuel-optimal SOCP (lgw.sim.mars.optimal), Table I case, per-axis 50 kN limit.

    /work/venv/bin/python benchmarks/bench_optimal.py [--repeats 5]

Prints, per number of steps N: the fuel; the solve time (``OptimalSolution.solve_time``: the
1 + refine ``Problem.solve`` calls, cvxpy canonicalisation included), median and min; Clarabel's
own time (median); the wall time of the whole call (problem construction included).  Then the
wall time of the minimum-time bisection at N = 80.  Not a timed test: numbers depend on the
machine (and on its load).
"""

from __future__ import annotations

import argparse
import statistics
import time

from lgw.sim.mars.optimal import min_time, solve_fuel_optimal
from lgw.theory.mars.parameters import M0, R0, V0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    solve_fuel_optimal(R0, V0, M0, 30.0, n=20)  # warm-up: imports, cvxpy/Clarabel first use
    print(f"{'N':>5} {'dt [s]':>8} {'fuel [kg]':>11} {'solve med [ms]':>15} "
          f"{'solve min [ms]':>15} {'clarabel [ms]':>14} {'wall med [ms]':>14}")
    for n in (40, 80, 160, 320):
        solves, walls, clar = [], [], []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            s = solve_fuel_optimal(R0, V0, M0, 30.0, n=n)
            walls.append(time.perf_counter() - t0)
            solves.append(s.solve_time)
            clar.append(s.settings["clarabel_time_s"])
        print(f"{n:5d} {30.0 / n:8.4f} {s.fuel:11.4f} {1e3 * statistics.median(solves):15.1f} "
              f"{1e3 * min(solves):15.1f} {1e3 * statistics.median(clar):14.1f} "
              f"{1e3 * statistics.median(walls):14.1f}")
    t0 = time.perf_counter()
    res = min_time(R0, V0, M0, n=80)
    print(f"min-time bisection (N = 80): tf_min = {res.tf_min:.3f} s in {res.iterations} solves, "
          f"{time.perf_counter() - t0:.2f} s wall")


if __name__ == "__main__":
    main()
