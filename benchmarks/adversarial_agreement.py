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

Figures (``--out DIR``, default out/agreement/; ``--no-figures`` to skip): one PNG per system,
``agreement_<system>.png``: the outcome classes of RK4 (rows) against dopri5 (columns), counts,
before and after refinement side by side (the diagonal is the agreement the table prints), and
each case's outcome time, RK4 against dopri5 on log scales, the disagreeing cases in red, the
refined ones drawn at their refined time with a line from their default-step time.
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
        code, t = res.outcomes()
        return np.array(OUTCOMES, dtype=object)[code], np.asarray(t, float)

    return fly, DT_DEFAULT, camp.T_MAX


def lunar_flights(n: int, seed: int, chunk: int = 500):
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.outcomes import OUTCOMES

    adv = _bench("adversarial_lunar")
    t_end = 5.0
    chunks = [adv.adversarial_cases(min(chunk, n - s), seed + s, t_end)
              for s in range(0, n, chunk)]
    dt0 = chunks[0][0].opts.dt

    def fly(idx: np.ndarray, h: float | None, method: str = "rk4"):
        out = np.empty(len(idx), dtype=object)
        tout = np.full(len(idx), np.nan)
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
            tout[sel] = res.cases["t_outcome"]
        return out, tout

    return fly, dt0, t_end


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

    def fly(idx: np.ndarray, h: float | None, method: str = "rk4"):
        out = np.empty(len(idx), dtype=object)
        tout = np.full(len(idx), np.nan)
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
            tout[sel] = res.t_outcome
        return out, tout

    return fly, h0, max(b[2].t_final for b in batches)


def agreement(system: str, n: int, seed: int, thrust_max: float | None) -> dict:
    t0 = time.perf_counter()
    if system == "mars":
        fly, h, t_max = mars_flights(n, seed, thrust_max)
    elif system == "lunar":
        fly, h, t_max = lunar_flights(n, seed)
    else:
        fly, h, t_max = eros_flights(n, seed)
    idx = np.arange(n)
    rk, rk_t = fly(idx, None)
    dp, dp_t = fly(idx, None, "dopri5")
    before = classes(rk) == classes(dp)
    half, _ = fly(idx, h / 2)

    def fly_at(cases: np.ndarray, step: float):
        names, t = fly(cases, step)
        return classes(names), t

    # refine on the class (what the agreement is measured on); the outcome names follow
    ref = refine_outcomes(fly_at, classes(rk), classes(half), h)
    final = classes(rk).copy()
    final[ref.cases] = ref.codes
    final_t = rk_t.copy()
    for pos, _, t in ref.results:  # in order of refinement: each case's last flight wins
        final_t[ref.cases[pos]] = t
    after = final == classes(dp)
    pairs = Counter((a, b) for a, b in zip(final[~after], classes(dp)[~after], strict=True))
    return {"system": system, "n": n, "dt": h, "t_max": t_max, "before": int(before.sum()),
            "after": int(after.sum()), "refined": len(ref.cases),
            "settled": int(ref.settled.sum()),
            "steps": Counter(f"{x:g}" for x in ref.dt), "pairs": pairs,
            "rk4": Counter(rk.tolist()), "dopri5": Counter(dp.tolist()),
            "per_case": {"rk4": classes(rk), "dopri5": classes(dp), "refined": final,
                         "t_rk4": rk_t, "t_dopri5": dp_t, "t_refined": final_t,
                         "refined_cases": np.asarray(ref.cases, int)},
            "seconds": time.perf_counter() - t0}


def confusion(rows: np.ndarray, cols: np.ndarray, labels: list[str]) -> np.ndarray:
    """Counts of (row class, column class) pairs: M[i, j] = #{k: rows[k] = labels[i] and
    cols[k] = labels[j]}."""
    pos = {c: i for i, c in enumerate(labels)}
    M = np.zeros((len(labels), len(labels)), int)
    for a, b in zip(rows, cols, strict=True):
        M[pos[a], pos[b]] += 1
    return M


def agreement_figure(r: dict, seed: int, path: Path):
    """One system's agreement figure (module docstring), written to ``path`` (PNG); returns
    the confusion matrices as drawn, read back from the count labels on the figure:
    {"labels": classes, "before": M, "after": M} (rows RK4, columns dopri5)."""
    from lgw.tuning.figures import png_bytes, save_png, styled

    pc = r["per_case"]
    n = r["n"]
    labels = sorted(set(pc["rk4"]) | set(pc["dopri5"]) | set(pc["refined"]))
    mats = {"before": confusion(pc["rk4"], pc["dopri5"], labels),
            "after": confusion(pc["refined"], pc["dopri5"], labels)}
    with styled() as plt:
        fig, axes = plt.subplots(1, 3, figsize=(15.5, 5.6),
                                 gridspec_kw={"width_ratios": [1, 1, 1.25]})
        for ax, (key, M) in zip(axes[:2], mats.items(), strict=True):
            agree = int(np.trace(M))
            ax.imshow(np.log1p(M), cmap="Blues", vmin=0, vmax=np.log1p(max(n, 1)))
            for i in range(len(labels)):
                for j in range(len(labels)):
                    if M[i, j]:
                        ax.text(j, i, str(M[i, j]), ha="center", va="center", gid="count",
                                color="white" if M[i, j] > 0.3 * n else
                                ("black" if i == j else "#b00000"), fontsize=10)
            ax.set_xticks(range(len(labels)), labels, rotation=35, ha="right")
            ax.set_yticks(range(len(labels)), labels)
            ax.set_xlabel("dopri5 outcome")
            ax.set_ylabel("RK4 outcome" + (" (refined)" if key == "after" else ""))
            ax.set_title(f"{key} refinement: {agree}/{n} agree ({100 * agree / n:.2f} %)")
            ax.grid(False)
        ax = axes[2]
        t_rk, t_dp, t_fin = (np.asarray(pc[k], float) for k in ("t_rk4", "t_dopri5",
                                                                   "t_refined"))
        refd = np.zeros(n, bool)
        refd[pc["refined_cases"]] = True
        t_rk_shown = np.where(refd, t_fin, t_rk)  # a refined case at its refined time
        dis = pc["refined"] != pc["dopri5"]
        known = np.isfinite(t_rk_shown) & np.isfinite(t_dp)
        every = np.concatenate([t_rk, t_dp, t_fin])
        pos = every[np.isfinite(every) & (every > 0)]
        # times below a hundredth of the RK4 step (0 included: a state refused at the start,
        # or blown up in its first step) are not resolved by it: drawn at that floor
        floor = r["dt"] / 100
        # and times beyond the horizon (mars adversarial states report up to 1e45 s) at 3x it
        ceil = 3 * r.get("t_max", np.inf)
        hi = min(max(float(np.max(pos)) * 3, 10 * floor), ceil) if pos.size else 10 * floor

        def shown(t):
            return np.clip(t, floor, hi)

        ax.plot([floor, hi], [floor, hi], color="0.6", lw=0.8, zorder=0)
        for k in np.flatnonzero(refd & known):  # default-step time -> refined time
            ax.plot([shown(t_dp[k])] * 2, [shown(t_rk[k]), shown(t_fin[k])], color="k", lw=0.8)

        def cloud(mask, **kw):
            """Coincident cases (same times to 0.01 decades) as one marker, area ~ count."""
            xy = np.column_stack([shown(t_dp[mask]), shown(t_rk_shown[mask])])
            if not len(xy):
                ax.scatter([], [], **kw)
                return
            keys, inv, cnt = np.unique(np.round(np.log10(xy), 2), axis=0,
                                       return_inverse=True, return_counts=True)
            first = np.array([np.flatnonzero(inv.ravel() == q)[0] for q in range(len(keys))])
            ax.scatter(xy[first, 0], xy[first, 1], s=12 + 10 * np.sqrt(cnt), **kw)
            for (x, y), c in zip(xy[first], cnt, strict=True):
                if c > 1:
                    ax.annotate(str(c), (x, y), xytext=(4, 3), textcoords="offset points",
                                fontsize=7, color=kw.get("color", "k"))

        cloud(known & ~dis & ~refd, color="#2166ac", alpha=0.6,
              label=f"same class ({int(np.sum(~dis & ~refd))})")
        cloud(known & refd, facecolors="none", edgecolors="k",
              label=f"refined ({int(refd.sum())}): at the refined time, line from dt's")
        cloud(known & dis, marker="x", color="#b00000",
              label=f"classes differ after refinement ({int(dis.sum())})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(floor / 1.5, hi)
        ax.set_ylim(floor / 1.5, hi)
        ax.set_xlabel("dopri5: time of the outcome (s)")
        ax.set_ylabel("RK4: time of the outcome (s)")
        ax.set_title(f"outcome time per case (clipped to [{floor:.2g}, {hi:.2g}] s)"
                     + (f", {int(np.sum(~known))} without a time" if np.any(~known) else ""))
        ax.legend(loc="upper left", fontsize=8)
        bef, aft = r["before"], r["after"]
        fig.suptitle(f"{r['system']}: RK4 (dt = {r['dt']:g} s) against dopri5 on {n} adversarial "
                     f"cases, seed {seed}: outcome-class agreement {100 * bef / n:.2f} % before, "
                     f"{100 * aft / n:.2f} % after refinement")
        fig.tight_layout()
        drawn = {}
        for ax_, key in zip(axes[:2], mats, strict=True):
            D = np.zeros_like(mats[key])
            for txt in ax_.texts:
                if txt.get_gid() == "count":
                    x, y = txt.get_position()
                    D[int(round(y)), int(round(x))] = int(txt.get_text())
            drawn[key] = D
        save_png(png_bytes(fig), path)
    return {"labels": labels, **drawn}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--systems", default="mars,lunar,eros")
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--thrust-max", type=float, default=None, help="mars only (N per axis)")
    ap.add_argument("--out", type=Path, default=Path("out/agreement"),
                    help="directory of the figures (agreement_<system>.png)")
    ap.add_argument("--no-figures", action="store_true", help="print the tables only")
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
              f"{r['settled']} (at most {REFINE_HALVINGS} halvings"
              + ("; steps " + ", ".join(f"{k} s x{v}" for k, v in sorted(r["steps"].items()))
                 if r["steps"] else "") + ")")
        print(f"  outcome-class agreement after refinement:  {r['after']} of {n} "
              f"({100 * r['after'] / n:.2f} %)")
        for (a, b), c in r["pairs"].most_common():
            print(f"    left: RK4 {a} / dopri5 {b}: {c}")
        if not args.no_figures:
            path = args.out / f"agreement_{system.strip()}.png"
            agreement_figure(r, args.seed, path)
            print(f"  figure: {path}")


if __name__ == "__main__":
    main()
