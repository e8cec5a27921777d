"""Speed and accuracy of the simulators (a script, not a timed test).

    /work/venv/bin/python benchmarks/bench_sim.py                 # (a), (b), (c), numpy batch
    /work/venv/bin/python benchmarks/bench_sim.py --million       # + 1,000,000 Table II landings
    /work/venv/bin/python benchmarks/bench_sim.py --floor         # chattering floor vs dt
    /work/venv/bin/python benchmarks/bench_sim.py --dt-sweep      # accuracy, landing, speed vs dt
    /work/venv/bin/python benchmarks/bench_sim.py --tol-sweep     # the same for dopri5 vs rtol
    /work/venv/bin/python benchmarks/bench_sim.py --before e448ec4   # every system now vs a commit
    python benchmarks/bench_sim.py --before e4c8ca7 --cache-before ~/.cache/lgw-before

Measures, on Table II cases (seed 000, corrected law, default gains, physical drag):
  (a) a per-case scipy solve_ivp loop (RK45, rtol = atol = 1e-8, landing event) written as a
      user would: numpy RHS calling lgw.theory.mars.mss.law_numeric;
  (b) python-control: input_output_response of lgw.sim.mars.interop.closed_loop_nlsys per case
      (RK45, rtol = atol = 1e-8, output grid every 0.01 s to 30 s);
  (c) lgw.sim.mars.batch.simulate_batch (numba RK4, fixed dt), after a warm-up call (compile time is
      printed separately);
  (c5) the same simulator with method="dopri5": adaptive Dormand-Prince 5(4), the method of
      (a), with error control at rtol = atol = --tol (default lgw.sim.mars.parameters.DOPRI_RTOL);
  (d) the same batched RK4 in plain numpy arrays (no numba, no events): what batching alone
      buys, to show whether numba pays;
and prints cases/second, the ratios (c)/(a), (c5)/(a), (c)/(b), (c5)/(b), (c)/(d), and the
accuracy of (c) and (c5) against (a): landing time and landing position.  Each route is
warmed up on one case first (lambdify / compile / first-call costs are not part of the per-case
rate).

--tol-sweep: for each tolerance, (c5)'s accuracy against (a) and against the tight LSODA
reference (Table II, and Table III with the 50 kN limit), landed fraction, steps, cases/s.

--before COMMIT: the simulators of that commit (its theory/, sim/ and tuning/ from git, run in a
worker process of their own with their own kernel cache) against this checkout's, on the same
cases, one thread each, RK4 and dopri5, for each workload (--systems): mars Table II
(--n-before cases), lunar Section 5 (/ 50), a lunar Monte Carlo campaign (lunar-campaign, / 50;
RK4 at the converged step, and at 4x it in the dopri5 row: the campaign flies RK4 only), eros
Monte Carlo offsets (/ 10) and the whole eros descent's last 20 s on the shape model
(eros-descent, / 200, Monte Carlo dispersions); best CPU time of --repeat interleaved runs:
cases/s of both, the ratio now/before, and whether the per-case results are bitwise equal.
--now COMMIT takes "now" from a commit too (a run that stays valid while the checkout is
edited).

--dt-sweep: for each dt, (c)'s accuracy against (a) and against the tight LSODA reference
(Table II, and Table III with the 50 kN limit), the fraction of Table II cases that meet the
landing criterion (|r| <= 0.1 m, |v| <= 0.1 m/s) by t_max, and cases/s: at which dt the
fixed step stops meeting the targets, and what (c)/(a) = 1000 would require.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import os
import time
from pathlib import Path

import numpy as np
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.campaign import table2_states
from lgw.sim.mars.parameters import DOPRI_RTOL
from lgw.sim.mars.plant import drag_accel, exhaust_velocity
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.mss import law_numeric
from lgw.theory.mars.parameters import G_MARS, M0, R0, V0
from scipy.integrate import solve_ivp


def user_solve_ivp(r0, v0, m0, g, t_max=60.0):
    """(a): the loop a user would write."""
    law = law_numeric("corrected")
    c = exhaust_velocity()
    out = []
    for i in range(len(r0)):
        def rhs(t, y):
            r, v, m = y[:3], y[3:6], y[6]
            am = drag_accel(r, v, m, "physical")
            a = law(r, v, G_MARS, am, g.beta1, g.beta2, g.alpha1, g.alpha2, g.q1, g.q2,
                    g.g1, g.g2)
            return np.concatenate([v, a + G_MARS + am, [-m * np.linalg.norm(a) / c]])

        def land(t, y):
            return max(np.linalg.norm(y[:3]) / 0.1, np.linalg.norm(y[3:6]) / 0.1) - 1.0
        land.terminal = True
        land.direction = -1
        y0 = np.concatenate([r0[i], v0[i], [m0[i]]])
        sol = solve_ivp(rhs, (0, t_max), y0, method="RK45", rtol=1e-8, atol=1e-8,
                        events=land, dense_output=True)
        tl = sol.t_events[0][0] if len(sol.t_events[0]) else np.nan
        out.append((tl, sol.sol(tl)[:3] if np.isfinite(tl) else np.full(3, np.nan)))
    return np.array([o[0] for o in out]), np.array([o[1] for o in out])


def python_control(r0, v0, m0, g):
    """(b): python-control per case."""
    import control
    from lgw.sim.mars.interop import closed_loop_nlsys

    sys = closed_loop_nlsys(g)
    T = np.arange(0.0, 30.0 + 1e-9, 0.01)
    for i in range(len(r0)):
        x0 = np.concatenate([r0[i], v0[i], [m0[i]]])
        control.input_output_response(sys, T, U=0, X0=x0, solve_ivp_method="RK45",
                                      solve_ivp_kwargs={"rtol": 1e-8, "atol": 1e-8})


def numpy_batch(r0, v0, m0, g, dt=0.05, t_end=28.0):
    """(d): RK4 on (N, 3) numpy arrays, fixed horizon, no events."""
    law = law_numeric("corrected")
    c = exhaust_velocity()

    def f(r, v, m):
        am = drag_accel(r, v, m, "physical")
        a = law(r, v, G_MARS, am, g.beta1, g.beta2, g.alpha1, g.alpha2, g.q1, g.q2, g.g1, g.g2)
        return v, a + G_MARS + am, -m * np.linalg.norm(a, axis=1) / c

    r, v, m = r0.copy(), v0.copy(), m0.copy()
    with np.errstate(all="ignore"):
        for _ in range(int(t_end / dt)):
            k1 = f(r, v, m)
            k2 = f(r + dt / 2 * k1[0], v + dt / 2 * k1[1], m + dt / 2 * k1[2])
            k3 = f(r + dt / 2 * k2[0], v + dt / 2 * k2[1], m + dt / 2 * k2[2])
            k4 = f(r + dt * k3[0], v + dt * k3[1], m + dt * k3[2])
            r = r + dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v = v + dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            m = m + dt / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])
    return r


def chatter_floor(g, dts=(0.01, 0.02, 0.05, 0.1, 0.2)) -> None:
    """Max |s1|, |s2| over t in [90, 120] s on Table I with stop="t_max" (the RK4 floor)."""
    from lgw.theory.mars.mss import surfaces_numeric

    s2f = surfaces_numeric()[1]
    print("chattering floor (Table I, corrected law, max over t in [90, 120] s):")
    print(f"{'dt s':>8} {'|s1| m':>10} {'|s2| m/s':>10} {'0.85 dt^1.5':>12}")
    for dt in dts:
        b = simulate_batch(R0[None], V0[None], [M0], g, dt=dt, t_max=120.0, stop="t_max",
                           record=True)
        tr = b.trajectory
        w = tr["t"] >= 90.0
        s2 = s2f(tr["r"][0], tr["v"][0], g.beta1, g.beta2, g.q1, g.q2)
        print(f"{dt:8.3f} {np.abs(tr['r'][0][w]).max():10.2e} {np.abs(s2[w]).max():10.2e} "
              f"{0.85 * dt**1.5:12.2e}")


def _timed(g, r0, v0, m0, **kw):
    """simulate_batch on the given cases after a 2-case warm-up (compile, first call): the
    result and its rate in cases/s."""
    simulate_batch(r0[:2], v0[:2], m0[:2], g, **kw)
    t = time.perf_counter()
    res = simulate_batch(r0, v0, m0, g, **kw)
    return res, len(r0) / (time.perf_counter() - t)


def _err(b, tl, rl) -> str:
    """Max landing-time / landing-position difference of b against (tl, rl), and misses."""
    both = b.landed & np.isfinite(tl)
    dT = np.abs(b.landing_time - tl)[both]
    dR = np.linalg.norm(b.r_land - rl, axis=1)[both]
    miss = int(np.sum(b.landed != np.isfinite(tl)))
    tag = f" ({miss} miss)" if miss else ""
    return (f"{dT.max() if dT.size else np.nan:>9.1e}{tag:>12} "
            f"{dR.max() if dR.size else np.nan:>8.1e}")


def sweep(g, settings: list[tuple[str, dict]], n_acc: int = 20, n_land: int = 4000) -> None:
    """Accuracy, landing criterion and speed for each (label, simulate_batch options)."""
    from lgw.sim.mars.campaign import table3_states
    from lgw.sim.mars.reference import simulate_reference

    r0, v0, m0 = table2_states(max(n_acc, n_land), seed=0)
    user_solve_ivp(r0[:1], v0[:1], m0[:1], g)  # warm-up
    t = time.perf_counter()
    tl_a, rl_a = user_solve_ivp(r0[:n_acc], v0[:n_acc], m0[:n_acc], g)
    rate_a = n_acc / (time.perf_counter() - t)
    ref2 = simulate_reference(r0[:n_acc], v0[:n_acc], m0[:n_acc], g)
    s3 = table3_states(6, seed=0)
    ref3 = simulate_reference(*s3, g, thrust_limit=50e3)
    print(f"(a) {rate_a:.1f} cases/s ({n_acc} Table II cases): (c)/(a) = 1000 needs "
          f"{1000 * rate_a:.0f} cases/s")
    print(f"{'setting':>12} | {'Table II vs (a): dT s':>21} {'dr m':>8} | {'vs LSODA: dT s':>14} "
          f"{'dr m':>8} | {'Table III 50 kN: dT s':>21} {'dr m':>8} | {'landed':>13} | "
          f"{'steps':>5} {'cases/s':>8} {'x (a)':>6}")
    for label, kw in settings:
        b, rate = _timed(g, r0[:n_land], v0[:n_land], m0[:n_land], **kw)
        b3 = simulate_batch(*s3, g, thrust_limit=50e3, **kw)
        print(f"{label:>12} | {_err(_head(b, n_acc), tl_a, rl_a):>30} | "
              f"{_err(_head(b, n_acc), ref2.landing_time, ref2.r_land):>23} | "
              f"{_err(b3, ref3.landing_time, ref3.r_land):>30} | "
              f"{b.landed.sum():>6}/{n_land:<6} | {b.steps.mean():5.0f} {rate:8.0f} "
              f"{rate / rate_a:6.0f}")


def dt_sweep(g, dts=(0.05, 0.06, 0.07, 0.08, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5)) -> None:
    """RK4: accuracy and landing criterion against dt (see the module docstring)."""
    sweep(g, [(f"rk4 dt {dt:g}", {"dt": dt}) for dt in dts])


def tol_sweep(g, tols=(1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)) -> None:
    """dopri5: accuracy and landing criterion against rtol = atol."""
    sweep(g, [(f"dopri5 {tol:g}", {"method": "dopri5", "rtol": tol, "atol": tol})
              for tol in tols])


def _head(b, n: int):
    """The first n cases of a BatchResult (landing fields only)."""
    from types import SimpleNamespace
    return SimpleNamespace(landed=b.landed[:n], landing_time=b.landing_time[:n],
                           r_land=b.r_land[:n])


def million(g, kw: dict, label: str, n: int = 1_000_000, chunk: int = 100_000) -> None:
    """Fly n Table II cases in chunks (seeded per chunk), keeping only the statistics."""
    from rich.progress import Progress

    landed = 0
    worst_err = 0.0
    times = []
    t0 = time.perf_counter()
    with Progress() as bar:
        task = bar.add_task(f"{n} Table II landings", total=n)
        for k in range(0, n, chunk):
            m = min(chunk, n - k)
            r0, v0, m0 = table2_states(m, seed=1000 + k)
            b = simulate_batch(r0, v0, m0, g, chunk=m, **kw)
            landed += int(b.landed.sum())
            worst_err = max(worst_err, float(np.nanmax(np.linalg.norm(b.r_land, axis=1))))
            times.append(b.landing_time)
            bar.advance(task, m)
    el = time.perf_counter() - t0
    lt = np.concatenate(times)
    print(f"{label}: {n} Table II cases: {el:.1f} s wall = {n / el:.0f} cases/s; "
          f"landed {landed}/{n}; landing time min/median/max {np.nanmin(lt):.2f}/"
          f"{np.nanmedian(lt):.2f}/{np.nanmax(lt):.2f} s; max landing error {worst_err:.3f} m")
    full = el * 1_000_000 / n
    tag = "measured" if n == 1_000_000 else f"EXTRAPOLATED linearly from {n} cases"
    print(f"   1,000,000 landings: {full / 60:.1f} min ({tag}) -> "
          f"{'under' if full < 600 else 'OVER'} the 10-minute target")


# --- the kernels now against the kernels at a commit, in one run -----------------------------

def before_tree(commit: str) -> Path:
    """The package ``lgw`` as it was at ``commit`` (``git archive`` of theory/, sim/, tuning/
    laid out as pyproject.toml maps them), in a temporary folder to put on PYTHONPATH."""
    import subprocess
    import tarfile
    import tempfile

    repo = Path(__file__).resolve().parents[1]
    tmp = Path(tempfile.mkdtemp(prefix=f"lgw-before-{commit[:10]}-"))
    tar = subprocess.run(["git", "archive", commit, "theory", "sim", "tuning"], cwd=repo,
                         capture_output=True, check=True).stdout
    src = tmp / "src"
    src.mkdir()
    with tarfile.open(fileobj=io.BytesIO(tar)) as tf:
        tf.extractall(src, filter="data")
    pkg = tmp / "pkg" / "lgw"
    pkg.mkdir(parents=True)
    for f in (src / "tuning" / "_root").iterdir():
        (pkg / f.name).symlink_to(f)
    for name, target in (("theory", "theory"), ("sim", "sim"), ("tuning", "tuning"),
                         ("testing", "tuning/testing")):
        (pkg / name).symlink_to(src / target)
    return tmp


def _digest(obj) -> str:
    """sha256 of every numpy array of a result (attributes, or a dict's values), by name."""
    h = hashlib.sha256()
    d = obj if isinstance(obj, dict) else vars(obj)
    for k in sorted(d):
        v = d[k]
        if isinstance(v, dict):
            h.update(_digest(v).encode())
        elif isinstance(v, np.ndarray):
            h.update(k.encode())
            h.update(np.ascontiguousarray(v).tobytes())
    return h.hexdigest()[:16]


SYSTEMS = ("mars", "lunar", "lunar-campaign", "eros", "eros-descent")


def workload(system: str, method: str, n: int):
    """A function running ``n`` cases of ``system`` with ``method`` on one thread, through
    the public batch entry points every version of the simulators has."""
    if system == "mars":
        g = default_gains()
        r0, v0, m0 = table2_states(n, seed=0)
        return lambda: simulate_batch(r0, v0, m0, g, method=method, parallel=False)
    if system == "lunar":
        from lgw.sim.lunar.batch import simulate
        from lgw.sim.lunar.scenario import section5_case

        ctx, X0 = section5_case(n=n)
        return lambda: simulate(ctx, X0, method=method, record=False, parallel=False).cases
    if system == "lunar-campaign":
        # a Monte Carlo campaign (failure time and level, initial state drawn), RK4 at the
        # run options' converged step; dopri5 through the same kernel as "lunar" above
        from dataclasses import replace

        from lgw.sim.lunar import campaign as LC
        from lgw.sim.lunar.closed_loop import RunOptions
        from lgw.theory.lunar.gains import paper_gains

        opts = RunOptions()
        if method != "rk4":  # the campaign flies RK4 only: a coarser step as a second load
            opts = replace(opts, dt=4 * opts.dt)
        return lambda: LC.run(paper_gains(), opts, n, seed=0, check_cases=0)
    if system == "eros-descent":
        # the whole descent (shape model's gravity, probe, navigation error) from the
        # profile's last 20 s, Monte Carlo dispersions
        from dataclasses import replace

        from lgw.sim.eros.descent import (
            DescentOptions,
            descent_gains,
            dispersions,
            simulate_descent,
        )

        d = dispersions(n, seed=0, pos=1.0, vel=0.01)
        base = DescentOptions(method=method, stride=5)
        opts = replace(base, t0=float(base.profile().t_touchdown - 20.0))
        return lambda: simulate_descent(d["e0"], d["ed0"], descent_gains(), opts,
                                        srp=d["srp"], case_phase=d["case_phase"],
                                        nav_ids=d["nav_ids"], parallel=False)
    from lgw.sim.eros.batch import SimOptions, simulate_kernel
    from lgw.sim.eros.campaign import offsets
    from lgw.theory.eros.gains import default_gains as eros_gains

    e0, ed0, ph = offsets(n, seed=1)
    opts = SimOptions(method=method)
    return lambda: simulate_kernel(e0, ed0, eros_gains(), opts, ph, parallel=False)


def worker() -> None:
    """Serve timing requests on stdin (one JSON line each: system, method, n); answer on
    stdout with the CPU and wall seconds of the run and a digest of its results."""
    import json
    import sys

    import lgw
    print(json.dumps({"lgw": lgw.__file__}), flush=True)
    runs = {}
    for line in sys.stdin:
        req = json.loads(line)
        key = (req["system"], req["method"], req["n"])
        if key not in runs:
            workload(req["system"], req["method"], 2)()  # compile or load from the cache
            runs[key] = workload(*key)
        c, t = time.process_time(), time.perf_counter()
        res = runs[key]()
        print(json.dumps({"cpu": time.process_time() - c, "wall": time.perf_counter() - t,
                          "digest": _digest(res)}), flush=True)


def before_after(commit: str, systems: list[str], n: int, repeat: int,
                 now: str | None = None, cache_before: str | None = None) -> None:
    """The simulators now against ``commit``: two worker processes (this checkout, or the
    tree of commit ``now``, and the tree of ``commit``), the same cases on one thread each,
    runs interleaved, best CPU time of ``repeat``; the ratio now/before of the rates and
    whether the results are bitwise equal.  A commit's kernels are compiled in a cache of
    their own (cold: minutes), under ``cache_before`` (kept: a second run loads them) if given,
    else in the commit's temporary tree."""
    import json
    import subprocess
    import sys
    import tempfile

    trees = {"before": before_tree(commit)}
    if now is not None:
        trees["now"] = before_tree(now)
    procs = {}
    for label in ("before", "now"):
        # one thread everywhere (the campaigns run their chunks in the kernels' threads)
        env = dict(os.environ, NUMBA_NUM_THREADS="1")
        if label in trees:
            cache = trees[label] / "cache"
            if cache_before is not None and label == "before":
                cache = Path(cache_before).expanduser() / commit
            env.update(PYTHONPATH=str(trees[label] / "pkg"), LGW_CACHE_DIR=str(cache))
        elif "LGW_CACHE_DIR" not in os.environ:
            env["LGW_CACHE_DIR"] = tempfile.mkdtemp(prefix="lgw-now-")
        procs[label] = subprocess.Popen([sys.executable, __file__, "--worker"], env=env,
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                        text=True)
        print(f"{label}: lgw from {json.loads(procs[label].stdout.readline())['lgw']}")
    sizes = {"mars": n, "lunar": max(1, n // 50), "lunar-campaign": max(1, n // 50),
             "eros": max(1, n // 10), "eros-descent": max(1, n // 200)}
    print(f"{'system':6} {'method':7} {'cases':>6} {'before /s':>10} {'now /s':>10} "
          f"{'now/before':>10}  bitwise equal")
    try:
        for system in systems:
            for method in ("rk4", "dopri5"):
                req = json.dumps({"system": system, "method": method, "n": sizes[system]})
                best = {"before": np.inf, "now": np.inf}
                dig = {}
                for _ in range(repeat):
                    for label, p in procs.items():
                        p.stdin.write(req + "\n")
                        p.stdin.flush()
                        ans = json.loads(p.stdout.readline())
                        best[label] = min(best[label], ans["cpu"])
                        dig[label] = ans["digest"]
                m = sizes[system]
                print(f"{system:6} {method:7} {m:6d} {m / best['before']:10.1f} "
                      f"{m / best['now']:10.1f} {best['before'] / best['now']:10.3f}  "
                      f"{dig['before'] == dig['now']}", flush=True)
    finally:
        import shutil
        for p in procs.values():
            p.stdin.close()
            p.wait()
        for tree in trees.values():
            shutil.rmtree(tree, ignore_errors=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n-batch", type=int, default=20_000)
    ap.add_argument("--before", metavar="COMMIT",
                    help="compare the simulators with those at COMMIT (rates and bitwise "
                    "equality, in one run)")
    ap.add_argument("--now", metavar="COMMIT", default=None,
                    help="with --before: the simulators at COMMIT instead of this checkout")
    ap.add_argument("--cache-before", metavar="DIR", default=None,
                    help="with --before: keep the commit's compiled kernels in DIR/COMMIT "
                    "(a second run loads them instead of compiling) [default: a temporary one]")
    ap.add_argument("--systems", nargs="+", choices=SYSTEMS, default=list(SYSTEMS),
                    help="workloads for --before")
    ap.add_argument("--n-before", type=int, default=2000,
                    help="mars cases for --before (lunar and lunar-campaign / 50, eros / 10, "
                         "eros-descent / 200)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--n-ivp", type=int, default=8)
    ap.add_argument("--n-control", type=int, default=3)
    ap.add_argument("--n-numpy", type=int, default=2_000)
    ap.add_argument("--dt", type=float, default=0.05)
    ap.add_argument("--million", action="store_true", help="also fly 1,000,000 Table II cases")
    ap.add_argument("--million-n", type=int, default=1_000_000,
                    help="cases for --million (fewer: the 1e6 time is extrapolated, and said so)")
    ap.add_argument("--million-method", choices=("rk4", "dopri5", "both"), default="both")
    ap.add_argument("--floor", action="store_true", help="only the chattering-floor table")
    ap.add_argument("--dt-sweep", action="store_true",
                    help="only the accuracy / landing / speed table against dt")
    ap.add_argument("--tol", type=float, default=DOPRI_RTOL, help="rtol = atol of (c5)")
    ap.add_argument("--tol-sweep", action="store_true",
                    help="only the accuracy / landing / speed table of dopri5 against rtol")
    args = ap.parse_args()
    if args.worker:
        worker()
        return
    g = default_gains()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} "
          "(other processes share the cores: numbers are lower bounds)")
    if args.before:
        before_after(args.before, args.systems, args.n_before, args.repeat, args.now,
                     args.cache_before)
        return
    if args.floor:
        chatter_floor(g)
        return
    if args.dt_sweep:
        dt_sweep(g)
        return
    if args.tol_sweep:
        tol_sweep(g)
        return
    r0, v0, m0 = table2_states(max(args.n_batch, args.n_ivp), seed=0)

    t = time.perf_counter()
    simulate_batch(r0[:2], v0[:2], m0[:2], g, dt=args.dt)
    print(f"numba compile + first call: {time.perf_counter() - t:.1f} s")
    t = time.perf_counter()
    b = simulate_batch(r0[:args.n_batch], v0[:args.n_batch], m0[:args.n_batch], g, dt=args.dt)
    rate_c = args.n_batch / (time.perf_counter() - t)
    print(f"(c) batched numba RK4 dt={args.dt}: {args.n_batch} cases, {rate_c:.0f} cases/s "
          f"({b.landed.sum()} landed)")
    kw5 = {"method": "dopri5", "rtol": args.tol, "atol": args.tol}
    b5, rate_5 = _timed(g, r0[:args.n_batch], v0[:args.n_batch], m0[:args.n_batch], **kw5)
    print(f"(c5) batched numba dopri5 rtol=atol={args.tol:g}: {args.n_batch} cases, "
          f"{rate_5:.0f} cases/s ({b5.landed.sum()} landed, {b5.steps.mean():.0f} steps/case)")

    n = args.n_ivp
    user_solve_ivp(r0[:1], v0[:1], m0[:1], g)  # warm-up: lambdify, first calls
    t = time.perf_counter()
    tl_a, rl_a = user_solve_ivp(r0[:n], v0[:n], m0[:n], g)
    rate_a = n / (time.perf_counter() - t)
    print(f"(a) solve_ivp RK45 1e-8 loop: {n} cases, {rate_a:.2f} cases/s")

    python_control(r0[:1], v0[:1], m0[:1], g)  # warm-up
    t = time.perf_counter()
    python_control(r0[:args.n_control], v0[:args.n_control], m0[:args.n_control], g)
    rate_b = args.n_control / (time.perf_counter() - t)
    print(f"(b) python-control input_output_response: {args.n_control} cases, "
          f"{rate_b:.2f} cases/s")

    numpy_batch(r0[:2], v0[:2], m0[:2], g, dt=args.dt)  # warm-up
    t = time.perf_counter()
    numpy_batch(r0[:args.n_numpy], v0[:args.n_numpy], m0[:args.n_numpy], g, dt=args.dt)
    rate_d = args.n_numpy / (time.perf_counter() - t)
    print(f"(d) batched numpy RK4 (no numba, no events) dt={args.dt}: {args.n_numpy} cases, "
          f"{rate_d:.0f} cases/s")

    print(f"ratios: (c)/(a) = {rate_c / rate_a:.0f}x, (c5)/(a) = {rate_5 / rate_a:.0f}x, "
          f"(c)/(b) = {rate_c / rate_b:.0f}x, (c5)/(b) = {rate_5 / rate_b:.0f}x, "
          f"(c)/(d) numba vs numpy = {rate_c / rate_d:.1f}x")
    for name, res, rate in (("(c)", b, rate_c), ("(c5)", b5, rate_5)):
        dT = np.abs(res.landing_time[:n] - tl_a)
        dR = np.linalg.norm(res.r_land[:n] - rl_a, axis=1)
        acc_ok = dT.max() < 0.01 and dR.max() < 0.01
        print(f"{name}: accuracy vs (a) on {n} cases: max |dT_land| = {dT.max():.2e} s, "
              f"max |dr_land| = {dR.max():.2e} m (targets 0.01 s, 0.01 m): "
              f"{'OK' if acc_ok else 'FAIL'}; >= 1000 x (a): "
              f"{'OK' if rate >= 1000 * rate_a else 'FAIL'} ({rate / rate_a:.0f}x); "
              f"1e6 Table II landings extrapolated {1e6 / rate / 60:.1f} min")
    if args.million:
        for meth in (("rk4", "dopri5") if args.million_method == "both"
                     else (args.million_method,)):
            kw = {"dt": args.dt} if meth == "rk4" else kw5
            million(g, kw, f"(c) RK4 dt = {args.dt} s" if meth == "rk4" else
                    f"(c5) dopri5 rtol = atol = {args.tol:g}", n=args.million_n)



if __name__ == "__main__":
    main()
