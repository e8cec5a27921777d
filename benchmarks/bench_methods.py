"""RK4 against dopri5 on each system's own scenarios: speed and accuracy, measured in one run
(a script, not a test; it informs the default ``--method``, docs/sim.md).

    python benchmarks/bench_methods.py [--systems mars lunar eros] [--n-speed 1000]
                                       [--n-acc 10] [--repeat 3]
    python benchmarks/bench_methods.py --printed [--n-speed 2000] [--n-acc 30]

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


# what ``lgw simulate mars --dispersion table2`` prints per case and in its summary, as
# (label, function of a BatchResult -> per-case values, (n,) or (n, 3))
PRINTED = (
    ("landing time s", lambda b: b.landing_time),
    ("fuel kg", lambda b: b.fuel),
    ("landing error |r| m", lambda b: np.linalg.norm(b.r_land, axis=1)),
    ("landing speed |v| m/s", lambda b: np.linalg.norm(b.v_land, axis=1)),
    ("peak thrust N", lambda b: b.peak_thrust),
    ("time saturated s", lambda b: b.time_saturated),
    ("t_s1 s", lambda b: b.t_s1),
    ("t_s2 s", lambda b: b.t_s2),
    ("min altitude m", lambda b: b.min_altitude),
)
SCENARIOS = (("Table II", "table2", {}),
             ("Table III 50 kN", "table3", {"thrust_limit": 5e4}),
             ("Table II sin 50 kN", "table2", {"thrust_limit": 5e4, "disturbance": "sin"}))


def _diff(a: np.ndarray, r: np.ndarray) -> tuple[float, int]:
    """(max |a - r| where both are finite, cases where exactly one is NaN: an event one
    found and the other did not)."""
    a, r = np.asarray(a, float), np.asarray(r, float)
    one = np.isnan(a) != np.isnan(r)
    d = np.abs(a - r)[np.isfinite(a) & np.isfinite(r)]
    return (float(d.max()) if d.size else 0.0), int(one.reshape(len(a), -1).any(axis=1).sum())


def mars_printed(n_speed: int, n_acc: int, repeat: int) -> None:
    """Every number ``simulate mars`` prints, RK4 (dt 0.05 s) and dopri5 (rtol = atol = 1e-5,
    and 1e-7) against the LSODA 1e-10 reference on the same cases; with each method's rate."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.campaign import table2_states, table3_states
    from lgw.sim.mars.reference import simulate_reference
    from lgw.theory.mars.gains import default_gains

    g = default_gains()
    methods = (("RK4 dt 0.05", {"method": "rk4"}), ("dopri5 1e-5", {"method": "dopri5"}),
               ("dopri5 1e-7", {"method": "dopri5", "rtol": 1e-7, "atol": 1e-7}))
    for label, disp, kw in SCENARIOS:
        draw = table2_states if disp == "table2" else table3_states
        r0, v0, m0 = draw(max(n_speed, n_acc), seed=0)
        ref = simulate_reference(r0[:n_acc], v0[:n_acc], m0[:n_acc], g, **kw)
        code_ref = ref.outcomes()[0]
        rows = {}
        for name, mk in methods:
            cpu, b = best_cpu(lambda mk=mk, r0=r0, v0=v0, m0=m0, kw=kw: simulate_batch(
                r0[:n_speed], v0[:n_speed], m0[:n_speed], g, parallel=False, **mk, **kw),
                repeat)
            a = simulate_batch(r0[:n_acc], v0[:n_acc], m0[:n_acc], g, **mk, **kw)
            rows[name] = ([_diff(f(a), f(ref)) for _, f in PRINTED],
                          int(np.sum(a.outcomes()[0] != code_ref)), n_speed / cpu,
                          float(b.steps.mean()))
        print(f"\nmars {label}: max |method - reference| over {n_acc} cases (LSODA 1e-10; "
              "[k]: cases where only one of the two has the event)", flush=True)
        print(f"{'quantity':24}" + "".join(f"{n:>22}" for n, _ in methods))
        for q, (qname, _) in enumerate(PRINTED):
            cells = []
            for n, _ in methods:
                d, k = rows[n][0][q]
                cells.append(f"{d:.1e}" + (f" [{k}]" if k else ""))
            print(f"{qname:24}" + "".join(f"{c:>22}" for c in cells))
        print(f"{'outcomes differ':24}" + "".join(f"{rows[n][1]:>22}" for n, _ in methods))
        print(f"{'cases/s, one thread':24}" + "".join(f"{rows[n][2]:>22.0f}"
                                                     for n, _ in methods))
        print(f"{'accepted steps per case':24}" + "".join(f"{rows[n][3]:>22.0f}"
                                                         for n, _ in methods), flush=True)


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
    ap.add_argument("--printed", action="store_true", help="mars only: every number "
                    "'simulate mars' prints, each method against the reference, on Table II, "
                    "Table III at 50 kN and Table II with the sin disturbance at 50 kN")
    a = ap.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    if a.printed:
        mars_printed(a.n_speed, a.n_acc, a.repeat)
        print(f"load average at the end {os.getloadavg()[0]:.2f}")
        return
    for s in a.systems:
        if s == "mars":
            mars(a.n_speed, a.n_acc, a.repeat)
        elif s == "lunar":
            lunar(max(1, a.n_speed // 50), max(1, a.n_acc // 5), a.repeat)
        else:
            eros(max(1, a.n_speed // 10), max(1, a.n_acc // 5), a.repeat)


if __name__ == "__main__":
    main()
