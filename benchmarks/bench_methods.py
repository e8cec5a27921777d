"""RK4 against dopri5 on each system's own scenarios: speed and accuracy, measured in one run
(a script, not a test; it informs the default ``--method``, docs/sim.md).

    python benchmarks/bench_methods.py [--systems mars lunar eros] [--n-speed 1000]
                                       [--n-acc 10] [--repeat 3]

Per system, each method at the system's defaults (mars: dt 0.05 s, rtol = atol = 1e-5; lunar:
dt 0.05 s, rtol = atol = 1e-6; eros: 2 RK4 steps per 0.01 s sample, rtol = atol = 1e-10):

  speed     cases/s on one thread (best of --repeat, after a warm-up call; CPU seconds, so
            other processes on a shared machine matter less), and accepted steps per case;
  accuracy  the largest difference, over --n-acc cases, from the system's tight reference
            (mars: LSODA 1e-10, ``simulate_reference``, landing time and position; lunar:
            DOP853 1e-10, ``solve_ivp_case``, the state at 40 s: position m, velocity m/s;
            eros: DOP853 1e-11 between samples, ``reference_solve``, the tracking error e at
            every sample, m).

mars is measured on Table II (corrected law), Table III with the 50 kN limit and, for speed
only, the bounded law (whose cascade makes dopri5 take tens of thousands of steps per case).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np


def best_cpu(fn, repeat: int) -> tuple[float, object]:
    fn()  # warm-up: compile or load the kernel, first-call costs
    best, out = np.inf, None
    for _ in range(repeat):
        c = time.process_time()
        out = fn()
        best = min(best, time.process_time() - c)
    return best, out


def mars(n_speed: int, n_acc: int, repeat: int) -> None:
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.campaign import table2_states, table3_states
    from lgw.sim.mars.reference import simulate_reference
    from lgw.theory.mars.gains import default_gains

    g = default_gains()
    for label, states, kw in (("Table II", table2_states, {}),
                              ("Table III 50 kN", table3_states, {"thrust_limit": 5e4})):
        r0, v0, m0 = states(max(n_speed, n_acc), seed=0)
        ref = simulate_reference(r0[:n_acc], v0[:n_acc], m0[:n_acc], g, **kw)
        for method in ("rk4", "dopri5"):
            cpu, b = best_cpu(lambda method=method, r0=r0, v0=v0, m0=m0, kw=kw: simulate_batch(
                r0[:n_speed], v0[:n_speed], m0[:n_speed], g, method=method, parallel=False,
                **kw), repeat)
            a = simulate_batch(r0[:n_acc], v0[:n_acc], m0[:n_acc], g, method=method, **kw)
            both = a.landed & ref.landed
            dt_land = np.abs(a.landing_time - ref.landing_time)[both]
            dr_land = np.linalg.norm(a.r_land - ref.r_land, axis=1)[both]
            miss = int(np.sum(a.landed != ref.landed))
            print(f"mars {label:16} {method:7} {n_speed / cpu:9.0f} cases/s "
                  f"{b.steps.mean():8.0f} steps  max dT_land {dt_land.max():.1e} s, "
                  f"max dr_land {dr_land.max():.1e} m, landed {int(b.landed.sum())}/{len(b)}"
                  + (f", {miss} landing outcomes differ" if miss else ""), flush=True)
    r0, v0, m0 = table2_states(20, seed=0)
    for method in ("rk4", "dopri5"):
        cpu, b = best_cpu(lambda method=method: simulate_batch(
            r0, v0, m0, g, law="bounded", method=method, parallel=False), 1)
        print(f"mars {'bounded, Table II':16} {method:7} {20 / cpu:9.1f} cases/s "
              f"{b.steps.mean():8.0f} steps", flush=True)


# lunar accuracy horizon (s): the transients, the saturation and the first part of the descent
# (the 1e-10 DOP853 reference over the whole 276 s takes tens of minutes per case)
T_END_ACC = 40.0


def lunar(n_speed: int, n_acc: int, repeat: int) -> None:
    from lgw.sim.lunar.batch import simulate, solve_ivp_case
    from lgw.sim.lunar.closed_loop import RunOptions, initial_state, make_context
    from lgw.sim.lunar.reference import reference
    from lgw.theory.lunar.gains import paper_gains
    from lgw.tuning.lunar.cmd_simulate import random_cases

    g, ref = paper_gains(), reference()
    n = max(n_speed, n_acc)
    dh, dv, Q0 = random_cases(n, seed=0)
    X0 = initial_state(ref, dh, dv, Q0, np.zeros((3, n)), [g] * n)
    acc_opts = RunOptions(t_end=T_END_ACC)
    exact = []
    for i in range(n_acc):
        sol = solve_ivp_case(make_context(ref, [g], acc_opts), X0[:, i], t_eval=None)
        exact.append(sol.y[:, -1])
    exact = np.array(exact)
    sub = make_context(ref, [g] * n_speed, RunOptions())
    for method in ("rk4", "dopri5"):
        cpu, res = best_cpu(lambda method=method: simulate(sub, X0[:, :n_speed], method=method,
                                                           record=False, parallel=False),
                            repeat)
        acc = simulate(make_context(ref, [g] * n_acc, acc_opts), X0[:, :n_acc],
                       method=method, record=False).cases
        y = acc["y_end"]
        dpos = np.abs(y[:, 0] - exact[:, 0]).max()
        dvel = np.abs(y[:, 3:6] - exact[:, 3:6]).max()
        print(f"lunar {'Section 5 horizon':15} {method:7} {n_speed / cpu:9.1f} cases/s "
              f"{res.cases['steps'].mean():8.0f} steps  max |dr| {dpos:.1e} m, "
              f"max |dv| {dvel:.1e} m/s at {T_END_ACC:g} s (vs DOP853 1e-10)", flush=True)


def eros(n_speed: int, n_acc: int, repeat: int) -> None:
    from dataclasses import replace

    from lgw.sim.eros.batch import SimOptions, reference_solve, simulate_kernel
    from lgw.sim.eros.campaign import offsets
    from lgw.theory.eros.gains import default_gains

    g = default_gains()
    n = max(n_speed, n_acc)
    e0, ed0, ph = offsets(n, seed=1)
    base = SimOptions()
    ref = [reference_solve(e0[i], ed0[i], g, base, ph[i]) for i in range(n_acc)]
    for method in ("rk4", "dopri5"):
        opts = replace(base, method=method)
        cpu, _ = best_cpu(lambda opts=opts: simulate_kernel(
            e0[:n_speed], ed0[:n_speed], g, opts, ph[:n_speed], parallel=False), repeat)
        res = simulate_kernel(e0[:n_acc], ed0[:n_acc], g, opts, ph[:n_acc])
        de = max(np.abs(res.e[:, i] - ref[i].e[:, 0]).max() for i in range(n_acc))
        print(f"eros {'15 s scenario':16} {method:7} {n_speed / cpu:9.1f} cases/s "
              f"{'':14} max |de| {de:.1e} m over the samples (vs DOP853 1e-11)", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--systems", nargs="+", choices=("mars", "lunar", "eros"),
                    default=["mars", "lunar", "eros"])
    ap.add_argument("--n-speed", type=int, default=1000,
                    help="mars cases (lunar / 50, eros / 10)")
    ap.add_argument("--n-acc", type=int, default=10, help="mars cases against the reference "
                    "(lunar / 5, eros / 5)")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    for s in a.systems:
        if s == "mars":
            mars(a.n_speed, a.n_acc, a.repeat)
        elif s == "lunar":
            lunar(max(1, a.n_speed // 50), max(1, a.n_acc // 5), a.repeat)
        else:
            eros(max(1, a.n_speed // 10), max(1, a.n_acc // 5), a.repeat)


if __name__ == "__main__":
    main()
