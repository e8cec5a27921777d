"""The lane kernel against the scalar kernel on seed 000 Table II (a script, not a timed test).

    python benchmarks/bench_lanes.py                  # rk4 and dopri5, 2000 cases, all threads
    python benchmarks/bench_lanes.py --serial         # one thread (steadier on a loaded machine)
    python benchmarks/bench_lanes.py --lanes 8 16 32  # lanes per block (one kernel each)
    python benchmarks/bench_lanes.py --law            # + the law alone, ns per axis evaluation

Both kernels fly the same Table II cases (seed 000, corrected law, default gains, physical
drag, no limit) with the same options, in the same process, interleaved --repeat times after
a warm-up (compile time is printed apart).  Per method it prints cases/s of each (CPU time of
the process, all threads, and wall time), the ratio lanes/scalar of CPU time (best and
median over the repeats; CPU time because the machine may be shared: wall time then measures
the other processes), and how far the results of the two kernels are apart: outcomes, landing
time, fuel, landing position, peak thrust, steps, and the law calls that missed their lane
result (0 expected).  It also says whether numba has a vector math library (SVML): the lane
kernel does not need one (``lgw.sim.vmath``).

The scalar kernel is ``lgw.sim.integrate`` (one case at a time, the law's exp / log from the
C library); the lane kernel is ``lgw.sim.mars.lanes`` (``lgw.sim.lanes``: NL cases stepped
together, the law in SIMD across them).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from contextlib import contextmanager
from unittest import mock

import numpy as np
from lgw.sim import integrate
from lgw.sim.mars import lanes as mars_lanes
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.campaign import table2_states
from lgw.sim.results import OUTCOMES
from lgw.theory.mars.gains import default_gains


@contextmanager
def captured_misses():
    """The lane kernels' return values (law calls that missed their lane result), per chunk."""
    seen: list[int] = []

    def spy(kernel_fn, sl, C, Q, R, O, G, rec_y, rec_x):  # noqa: N803
        out = kernel_fn(tuple(a[sl] for a in C), Q, tuple(a[sl] for a in R), O,
                        tuple(a[sl] for a in G), rec_y, rec_x)
        if out is not None:
            seen.append(int(out))
    with mock.patch.object(integrate, "run_chunk", spy):
        yield seen


def fly(states, kernel: str, nl: int, parallel: bool, kw: dict):
    r0, v0, m0 = states
    with mock.patch.object(mars_lanes, "NL", nl):
        return simulate_batch(r0, v0, m0, default_gains(), kernel=kernel, parallel=parallel,
                              **kw)


def timed(states, kernel, nl, parallel, kw):
    c0, w0 = time.process_time(), time.perf_counter()
    res = fly(states, kernel, nl, parallel, kw)
    return res, time.process_time() - c0, time.perf_counter() - w0


def apart(a, b) -> dict[str, float]:
    """How far two results are apart, over the cases both landed."""
    ca, cb = a.outcomes()[0], b.outcomes()[0]
    both = a.landed & b.landed

    def dmax(x, y):
        d = np.abs(np.asarray(x, float) - np.asarray(y, float))
        d = d[np.isfinite(d)]
        return float(d.max()) if d.size else 0.0
    rel_peak = np.abs(a.peak_thrust[both] - b.peak_thrust[both]) / np.maximum(
        np.abs(b.peak_thrust[both]), 1.0)
    return {"outcome_diffs": int(np.sum(ca != cb)),
            "landing_time_s": dmax(a.landing_time[both], b.landing_time[both]),
            "fuel_kg": dmax(a.fuel[both], b.fuel[both]),
            "r_land_m": dmax(a.r_land[both], b.r_land[both]),
            "peak_thrust_rel": float(rel_peak.max()) if rel_peak.size else 0.0,
            "steps_diffs": int(np.sum(a.steps != b.steps))}


def bench_method(states, method: str, kw: dict, nl: int, parallel: bool, repeat: int) -> None:
    n = len(states[0])
    t0 = time.perf_counter()
    fly(tuple(x[:2 * nl] for x in states), "scalar", nl, parallel, kw)
    t_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    with captured_misses() as misses:
        fly(tuple(x[:2 * nl] for x in states), "lanes", nl, parallel, kw)
    t_l = time.perf_counter() - t0
    print(f"  warm-up (compile or cache load): scalar {t_s:.1f} s, lanes {t_l:.1f} s")
    cpu = {"scalar": [], "lanes": []}
    wall = {"scalar": [], "lanes": []}
    ratios = []
    res = {}
    for _ in range(repeat):
        for kernel in ("scalar", "lanes"):
            with captured_misses() as m:
                res[kernel], c, w = timed(states, kernel, nl, parallel, kw)
            if kernel == "lanes":
                misses += m
            cpu[kernel].append(c)
            wall[kernel].append(w)
        ratios.append(cpu["scalar"][-1] / cpu["lanes"][-1])
    for kernel in ("scalar", "lanes"):
        print(f"  {kernel:6s}: {n / min(cpu[kernel]):8.0f} cases/s per CPU second (best), "
              f"{n / statistics.median(wall[kernel]):8.0f} cases/s wall (median)")
    print(f"  ratio lanes/scalar (CPU time): best {max(ratios):.2f}x, median "
          f"{statistics.median(ratios):.2f}x over {repeat} interleaved runs "
          f"({', '.join(f'{r:.2f}' for r in ratios)})")
    d = apart(res["lanes"], res["scalar"])
    a, b = res["lanes"], res["scalar"]
    counts = {OUTCOMES[k]: int(v) for k, v in zip(*np.unique(b.outcomes()[0],
                                                            return_counts=True), strict=True)}
    print(f"  agreement: {d['outcome_diffs']} of {n} outcomes differ (scalar: {counts}); "
          f"landed cases: |dt_land| <= {d['landing_time_s']:.1e} s, |dfuel| <= "
          f"{d['fuel_kg']:.1e} kg, |dr_land| <= {d['r_land_m']:.1e} m, peak thrust "
          f"<= {d['peak_thrust_rel']:.1e} relative; steps differ in {d['steps_diffs']} cases; "
          f"mean steps {a.steps.mean():.1f}; law calls that missed their lane result: "
          f"{sum(misses)}")


def bench_law(nl: int, repeat: int) -> None:
    """ns per axis evaluation of the corrected law (with s2): the scalar kernel's compiled law
    (C-library exp / log) in a loop, against the lane law over NL lanes and three axes."""
    import numba
    from lgw.sim.mars import kernel as mars_kernel
    from lgw.sim.mars.laws import get_law, surface_params

    g = default_gains()
    spec = get_law("corrected")
    P = np.ascontiguousarray(spec.param_values(g), float)  # noqa: N806
    SP = np.ascontiguousarray(surface_params(g), float)  # noqa: N806
    smod = mars_kernel.kernel_module("corrected")
    lmod = mars_lanes.kernel_module("corrected", nl)
    lay = mars_lanes.lb_layout(P.shape[1], nl)
    npar = lay["NPAR"]
    rng = np.random.default_rng(0)
    LB = np.zeros((3, lay["LB_COLS"]))  # noqa: N806
    LB[:, :npar] = P
    blocks = [rng.normal(0, 300, (3, nl)), rng.normal(0, 20, (3, nl)),
              np.tile([[0.0], [0.0], [-3.7114]], (1, nl)), rng.normal(0, 0.05, (3, nl)),
              rng.uniform(1500, 1900, (3, nl))]
    for k, blk in enumerate(blocks):
        LB[:, npar + k * nl: npar + (k + 1) * nl] = blk
    run = np.ones(nl, bool)
    slaw = smod.law
    llaw = lmod.law_lanes

    @numba.njit(error_model="numpy")
    def scalar(reps, LB, P, SP, out):  # noqa: N803
        for _ in range(reps):
            for ax in range(3):
                for ln in range(nl):
                    out[ax, ln], _s2 = slaw(LB[ax, npar + ln], LB[ax, npar + nl + ln],
                                           LB[ax, npar + 2 * nl + ln],
                                           LB[ax, npar + 3 * nl + ln],
                                           LB[ax, npar + 4 * nl + ln], P, SP, ax)

    @numba.njit(error_model="numpy")
    def lanes(reps, LB, SP, run):  # noqa: N803
        for _ in range(reps):
            llaw(LB, SP, run)

    out = np.empty((3, nl))
    scalar(1, LB, P, SP, out)
    lanes(1, LB, SP, run)
    reps = 200_000 // nl
    best = {"scalar": 1e9, "lanes": 1e9}
    for _ in range(repeat):
        t0 = time.process_time()
        scalar(reps, LB, P, SP, out)
        best["scalar"] = min(best["scalar"], time.process_time() - t0)
        t0 = time.process_time()
        lanes(reps, LB, SP, run)
        best["lanes"] = min(best["lanes"], time.process_time() - t0)
    a_l = LB[:, npar + mars_lanes.LB_A * nl: npar + (mars_lanes.LB_A + 1) * nl]
    rel = np.max(np.abs(a_l - out) / np.abs(out))
    per = {k: v / (reps * 3 * nl) * 1e9 for k, v in best.items()}
    print(f"law alone (corrected, with s2; {nl} lanes): scalar {per['scalar']:.1f} ns, lanes "
          f"{per['lanes']:.1f} ns per axis evaluation: {per['scalar'] / per['lanes']:.2f}x; "
          f"largest relative difference of a: {rel:.1e}")


def svml_state() -> str:
    try:
        from numba.misc.numba_sysinfo import get_sysinfo
        info = get_sysinfo()
        return (f"SVML library loaded: {info.get('SVML Lib Loaded')}, LLVM patched for SVML: "
                f"{info.get('LLVM SVML Patched')}, SVML operational: "
                f"{info.get('SVML Operational')}")
    except Exception as e:  # noqa: BLE001  (informative only)
        return f"SVML state unknown ({e})"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--methods", nargs="+", default=["rk4", "dopri5"],
                    choices=["rk4", "dopri5"])
    ap.add_argument("--rtol", type=float, default=1e-5, help="dopri5 rtol = atol")
    ap.add_argument("--lanes", type=int, nargs="+", default=[mars_lanes.NL])
    ap.add_argument("--serial", action="store_true", help="one thread (parallel=False)")
    ap.add_argument("--law", action="store_true", help="also time the law alone")
    args = ap.parse_args()
    import numba

    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; numba "
          f"{numba.__version__}, {numba.get_num_threads() if not args.serial else 1} "
          f"thread(s); {svml_state()}")
    states = table2_states(args.cases, 0)
    for nl in args.lanes:
        if args.law:
            bench_law(nl, args.repeat)
        for method in args.methods:
            kw = {} if method == "rk4" else {"method": "dopri5", "rtol": args.rtol,
                                              "atol": args.rtol}
            desc = "dt 0.05 s" if method == "rk4" else f"rtol = atol = {args.rtol:g}"
            print(f"{method} ({desc}), {args.cases} Table II cases, {nl} lanes:")
            bench_method(states, method, kw, nl, not args.serial, args.repeat)
    print(f"load average at the end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
