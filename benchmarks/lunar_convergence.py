"""Seed 001 Section 5: every number ``lgw simulate lunar`` and ``lgw report lunar`` quote, at the
default RK4 step, at dt/4, and from a tight ``solve_ivp`` of the same compiled vector field.

    python benchmarks/lunar_convergence.py                    # the three columns (~10 min)
    python benchmarks/lunar_convergence.py --no-reference     # dt and dt/4 only (seconds)
    python benchmarks/lunar_convergence.py --halvings 4 --no-reference   # dt ... dt/16

Columns: the value at dt (``lgw.sim.lunar.parameters.DT``), at dt/4, the reference
(``lgw.sim.lunar.batch.solve_ivp_numbers``: DOP853 at rtol = atol = --tol, the L2 integrals and
saturated times carried as extra states of the ODE), and the differences of dt/4 and of the
reference from the default run with the shared tolerance (``lgw.sim.lunar.convergence``: 1 % of
the refined value, or of the quantity's floor near zero).  ``--halvings N`` adds the run at
dt/2, ..., dt/2^N (the convergence sequence).  The last line counts the numbers within 1 % of
both; the script exits 1 when one is not.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import replace

from lgw.sim.lunar import convergence as CV
from lgw.sim.lunar import parameters as SP
from lgw.sim.lunar.batch import simulate, solve_ivp_numbers
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.sim.lunar.scenario import case_numbers, section5_case


def fly(opts: RunOptions) -> tuple[dict, float]:
    """The quoted numbers of the Section 5 case at ``opts.dt`` (kernel RK4) and the seconds."""
    t0 = time.perf_counter()
    ctx, X0 = section5_case(opts=opts)
    n = case_numbers(simulate(ctx, X0, record=False).cases, ctx)
    return n, time.perf_counter() - t0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pointing", choices=("coupled", "ideal"), default="coupled")
    ap.add_argument("--tol", type=float, default=1e-6, help="solve_ivp rtol = atol")
    ap.add_argument("--halvings", type=int, default=2, help="runs at dt/2 ... dt/2^N (>= 2)")
    ap.add_argument("--no-reference", action="store_true", help="skip the solve_ivp run")
    args = ap.parse_args()
    o = RunOptions(thrust_pointing=args.pointing)
    steps = [2 ** k for k in range(max(2, args.halvings) + 1)]
    runs = {}
    for k in steps:
        runs[k], sec = fly(replace(o, dt=SP.DT / k))
        print(f"RK4 dt/{k} = {SP.DT / k:.6g} s: {sec:.1f} s, outcome {runs[k]['outcome']}")
    ref = None
    if not args.no_reference:
        t0 = time.perf_counter()
        ctx, X0 = section5_case(opts=o)
        ref, sol = solve_ivp_numbers(ctx, X0[:, 0], rtol=args.tol, atol=args.tol)
        print(f"solve_ivp DOP853 rtol = atol = {args.tol:g}: {time.perf_counter() - t0:.0f} s, "
              f"{ref['evaluations']} evaluations, {ref['steps']} steps, status {sol.status}")
    a, b = runs[1], runs[4]
    head = f"{'number':34s} {'dt':>12s} {'dt/4':>12s}"
    head += "" if ref is None else f" {'solve_ivp':>12s}"
    head += f" {'dt/4 diff':>10s}" + ("" if ref is None else f" {'ref diff':>10s}")
    print(f"\nSection 5 ({args.pointing} pointing), dt = {SP.DT:g} s; diff = |x(dt) - y| / "
          f"max(|y|, floor), tolerance {100 * CV.RTOL:g} %")
    print(head)
    good = 0
    for name, (_, floor) in CV.QUOTED.items():
        tol = CV.tolerance(floor)
        x, y = float(a[name]), float(b[name])
        row = f"{name:34s} {x:12.6g} {y:12.6g}"
        ok = tol.ok(x, y)
        d4 = f"{100 * tol.difference(x, y):9.3g}%" + (" " if tol.ok(x, y) else "*")
        dr = ""
        if ref is not None:
            r = float(ref[name])
            row += f" {r:12.6g}"
            ok = ok and tol.ok(x, r)
            dr = f" {100 * tol.difference(x, r):9.3g}%" + (" " if tol.ok(x, r) else "*")
        print(row + f" {d4}" + dr)
        good += ok
    if len(steps) > 3:
        print("\nsequence dt/1 ... dt/" + str(steps[-1]) + ":")
        for name in CV.QUOTED:
            print(f"{name:34s} " + " ".join(f"{float(runs[k][name]):11.6g}" for k in steps))
    n = len(CV.QUOTED)
    what = "dt/4" + ("" if ref is None else " and solve_ivp")
    print(f"\n{good} of {n} quoted numbers within tolerance of {what} (* = outside)")
    return 0 if good == n and all(math.isfinite(float(a[k])) for k in CV.QUOTED) else 1


if __name__ == "__main__":
    sys.exit(main())
