"""RK4 against dopri5 on adversarial states, for every system: outcome-class agreement before and
after the fixed-step result is refined.

    python benchmarks/adversarial_agreement.py --cases 2000
    python benchmarks/adversarial_agreement.py --systems mars --cases 2000 --thrust-max 50000

The states are each system's adversarial campaign's (benchmarks/adversarial_campaign.py for
mars: exact zeros, tiny, moderate, huge and Table III-box components with random signs;
adversarial_lunar.py: initial errors and gains of those families, random failure and (24)
reading; adversarial_eros.py: offsets of those families, a random law variant, gain scaling
and disturbance mode per batch).  Each case is flown by RK4 at the system's default step and by
dopri5; their outcomes (``lgw.sim.results``) are compared by class (``outcome_class``: every
physical outcome its own class, the numerical break-downs one class).

Refinement (``lgw.sim.convergence.refine_outcomes``, what ``lgw simulate`` does
automatically): every case is flown again by RK4 at half the step; a case whose outcome changes
is flown at a quarter, an eighth, ... until two successive steps agree (at most
REFINE_HALVINGS halvings), and its RK4 outcome is the settled one.  Printed per system: the
agreement before and after, the cases refined and settled, and the disagreeing pairs left.
Seeded; the output is the same on every run.
"""

from __future__ import annotations

import argparse
import importlib.util
import time
from collections import Counter
from dataclasses import replace
from pathlib import Path

import numpy as np
from lgw.sim.convergence import REFINE_HALVINGS, refine_outcomes
from lgw.sim.results import outcome_class

HERE = Path(__file__).parent


def _bench(name: str):
    spec = importlib.util.spec_from_file_location(name, HERE / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def classes(names) -> np.ndarray:
    return np.array([outcome_class(n) for n in names], dtype=object)


# --- per system: fly(idx, level) -> outcome names; level 0 = the default step ----------------

def mars_flights(n: int, seed: int, thrust_max: float | None):
    from lgw.sim.mars.batch import DT_DEFAULT, simulate_batch
    from lgw.sim.results import OUTCOMES
    from lgw.theory.mars.gains import default_gains

    camp = _bench("adversarial_campaign")
    r0, v0, m0 = camp.adversarial_states(n, seed)
    g = default_gains()
    kw = dict(t_max=camp.T_MAX, thrust_limit=thrust_max)

    def fly(idx: np.ndarray, h: float | None, method: str = "rk4") -> np.ndarray:
        res = simulate_batch(r0[idx], v0[idx], m0[idx], g, method=method,
                             dt=DT_DEFAULT if h is None else h, **kw)
        return np.array(OUTCOMES, dtype=object)[res.outcomes()[0]]

    return fly, DT_DEFAULT


def lunar_flights(n: int, seed: int, chunk: int = 500):
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.outcomes import OUTCOMES

    adv = _bench("adversarial_lunar")
    t_end = 5.0
    chunks = [adv.adversarial_cases(min(chunk, n - s), seed + s, t_end)
              for s in range(0, n, chunk)]
    dt0 = chunks[0][0].opts.dt

    def fly(idx: np.ndarray, h: float | None, method: str = "rk4") -> np.ndarray:
        out = np.empty(len(idx), dtype=object)
        for c, (ctx, X0) in enumerate(chunks):
            lo = c * chunk
            sel = np.flatnonzero((idx >= lo) & (idx < lo + X0.shape[1]))
            if not len(sel):
                continue
            sub_ctx, sub_X0 = adv._subset(ctx, X0, idx[sel] - lo)
            if h is not None:
                sub_ctx = replace(sub_ctx, opts=replace(ctx.opts, dt=h))
            with np.errstate(all="ignore"):
                res = simulate(sub_ctx, sub_X0, method=method, record=False,
                               max_steps=5000, **adv.DOPRI)
            out[sel] = np.array(OUTCOMES, dtype=object)[res.cases["outcome"]]
        return out

    return fly, dt0


def eros_flights(n: int, seed: int, batch: int = 50):
    from lgw.sim.eros import laws as SL
    from lgw.sim.eros.batch import OUTCOMES, SimOptions, simulate

    adv = _bench("adversarial_eros")
    rng = np.random.default_rng(seed)
    batches = []
    for s in range(0, n, batch):
        k = min(batch, n - s)
        law, sw = SL.VARIANTS[rng.integers(len(SL.VARIANTS))]
        g = adv.gain_set(rng)
        dist = ("known", "unknown", "none")[rng.integers(3)]
        opts = SimOptions(law=law, switch=sw, t_final=0.5, disturbance=dist)
        e0, ed0 = adv.components(rng, (k, 3), 1e12), adv.components(rng, (k, 3), 1e8)
        batches.append((s, g, opts, e0, ed0, rng.uniform(0, 2 * np.pi, k)))
    h0 = batches[0][2].dt / batches[0][2].n_sub  # the RK4 step: n_sub per sample

    def fly(idx: np.ndarray, h: float | None, method: str = "rk4") -> np.ndarray:
        out = np.empty(len(idx), dtype=object)
        for s, g, opts, e0, ed0, ph in batches:
            sel = np.flatnonzero((idx >= s) & (idx < s + len(e0)))
            if not len(sel):
                continue
            j = idx[sel] - s
            o = replace(opts, method=method)
            if h is not None:  # the sample time is the controller's: more RK4 steps per sample
                o = replace(o, n_sub=int(round(opts.dt / h)))
            with np.errstate(all="ignore"):
                res = simulate(e0[j], ed0[j], g, o, ph[j])
            out[sel] = np.array(OUTCOMES, dtype=object)[res.outcome]
        return out

    return fly, h0


def agreement(system: str, n: int, seed: int, thrust_max: float | None) -> dict:
    t0 = time.perf_counter()
    if system == "mars":
        fly, h = mars_flights(n, seed, thrust_max)
    elif system == "lunar":
        fly, h = lunar_flights(n, seed)
    else:
        fly, h = eros_flights(n, seed)
    idx = np.arange(n)
    rk = fly(idx, None)
    dp = fly(idx, None, "dopri5")
    before = classes(rk) == classes(dp)
    half = fly(idx, h / 2)

    def fly_at(cases: np.ndarray, step: float):
        names = fly(cases, step)
        return classes(names), names

    # refine on the class (what the agreement is measured on); the outcome names follow
    ref = refine_outcomes(fly_at, classes(rk), classes(half), h)
    final = classes(rk).copy()
    final[ref.cases] = ref.codes
    after = final == classes(dp)
    pairs = Counter((a, b) for a, b in zip(final[~after], classes(dp)[~after], strict=True))
    return {"system": system, "n": n, "dt": h, "before": int(before.sum()),
            "after": int(after.sum()), "refined": len(ref.cases),
            "settled": int(ref.settled.sum()),
            "steps": Counter(f"{x:g}" for x in ref.dt), "pairs": pairs,
            "rk4": Counter(rk.tolist()), "dopri5": Counter(dp.tolist()),
            "seconds": time.perf_counter() - t0}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--systems", default="mars,lunar,eros")
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--thrust-max", type=float, default=None, help="mars only (N per axis)")
    args = ap.parse_args()
    for system in args.systems.split(","):
        r = agreement(system.strip(), args.cases, args.seed, args.thrust_max)
        n = r["n"]
        print(f"{system}: {n} adversarial cases, RK4 dt = {r['dt']:g} s against dopri5 "
              f"({r['seconds']:.0f} s)")
        print("  RK4 outcomes:    " + ", ".join(f"{k} {v}" for k, v in sorted(r["rk4"].items())))
        print("  dopri5 outcomes: " + ", ".join(f"{k} {v}"
                                                for k, v in sorted(r["dopri5"].items())))
        print(f"  outcome-class agreement before refinement: {r['before']} of {n} "
              f"({100 * r['before'] / n:.2f} %)")
        print(f"  refined (outcome changed at dt/2): {r['refined']}, settled "
              f"{r['settled']} (at most {REFINE_HALVINGS} halvings; steps "
              + ", ".join(f"{k} s x{v}" for k, v in sorted(r["steps"].items())) + ")")
        print(f"  outcome-class agreement after refinement:  {r['after']} of {n} "
              f"({100 * r['after'] / n:.2f} %)")
        for (a, b), c in r["pairs"].most_common():
            print(f"    left: RK4 {a} / dopri5 {b}: {c}")


if __name__ == "__main__":
    main()
