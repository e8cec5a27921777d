"""A campaign of adversarial seed 001 cases: every case one outcome, nothing impossible.

    python benchmarks/adversarial_lunar.py --cases 20000

Cases (``adversarial_cases``): the height error, the three velocity errors, the four
quaternion components and the three body rates, each independently from one of five families
with random sign: exact zero, tiny 10^U(-300, -3), moderate 10^U(-3, 1), huge 10^U(1, 300), or
a Section 5-like value (``lgw.tuning.lunar.cmd_simulate.random_cases``; rates 0); a quaternion
of four zeros gets q0 = 1 (it has no attitude).  The gains of both loops (K1, F2 diagonal, f3,
q) are the paper's times, per chunk, 1 or 10^U(-12, 12), or, per case and gain, 0 or a random
sign flip with probability 1/8 each (adversarial gains are part of the input).  Each chunk of
``--chunk`` cases shares one set of run options: the failure of (26) ("atan", "step" at a
random time in [0, t_end], or "none") with T_a in U(0, 1), and the saturation reading of (24)
("commanded" or "nominal").  RK4 at the default dt and dopri5 (rtol = atol = 1e-6, at most
``--max-steps`` attempts) fly the same cases to ``--t-end``.

Printed per method: the count per outcome (``lgw.sim.lunar.outcomes``), "unexplained" (a
case whose recorded quantities contradict its outcome: "completed" before t_end, an outcome
time outside [0, t_end], "crashed" with the end radius off R_MOON, "propellant_
exhausted" with the end mass off m_dry, "step_limit" from RK4, ...), "impossible" (end mass
<= 0, below m_dry or above m0; with the "commanded" reading of (24), a delivered thrust above
T_max or above the failure factor times T_max at a saturated node (read "nominal", (24) does not
limit the thrust: no bound to check); a torque above M_max; a stage peak below its node peak; a
negative peak), "nonfinite in output" (a NaN/inf in a quantity that is
a number whatever the outcome, or in the end state unless the outcome is "nonfinite"), and the
RK4/dopri5 agreement on the outcome class (completed / domain exit / numerical, as
tests/lunar/test_outcomes.py) with every disagreement of a named kind or "other":

  step_limit  dopri5 ran out of attempts (chattering at z2 = 0, where (7)'s sign-like term is
              not Lipschitz) before the time of RK4's outcome (RK4 completes, or runs dry
              later, e.g. seed 0 case 923: dry at 1.578 s at dt, 1.569 s at dt/10 and dt/100,
              while dopri5 stalls at 1.098 s);
  refined     RK4 at dt/10 or dt/100 gives dopri5's class (RK4's fixed step was too large:
              e.g. seed 0 case 445, a body rate that drifts ||Q|| past the tolerance at dt and
              dt/10 and completes at dt/100, as dopri5 does).
"""

from __future__ import annotations

import argparse
import json
import time
from collections import Counter
from dataclasses import replace

import numpy as np
from lgw.sim.lunar.batch import simulate
from lgw.sim.lunar.closed_loop import RunOptions, initial_state, make_context
from lgw.sim.lunar.outcomes import DOMAIN_EXITS, OUTCOMES, case_record
from lgw.sim.lunar.reference import reference
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar.cmd_simulate import random_cases

DOPRI = {"rtol": 1e-6, "atol": 1e-6, "max_step": 1.0}
NUMBERS = ("t_outcome", "peak_thrust", "peak_thrust_cmd", "peak_torque",
           "time_saturated_orbit", "time_saturated_torque", "min_height", "peak_thrust_stages",
           "peak_thrust_cmd_stages")


def _family(rng: np.random.Generator, nominal: np.ndarray) -> np.ndarray:
    shape = nominal.shape
    fam = rng.integers(0, 5, shape)
    sign = rng.choice([-1.0, 1.0], shape)
    return np.select([fam == 0, fam == 1, fam == 2, fam == 3],
                     [0.0 * sign, sign * 10.0 ** rng.uniform(-300, -3, shape),
                      sign * 10.0 ** rng.uniform(-3, 1, shape),
                      sign * 10.0 ** rng.uniform(1, 300, shape)], default=nominal)


def adversarial_cases(n: int, seed: int, t_end: float) -> tuple:
    """(ctx, X0 (30, n)) for one chunk: states, gains and run options as the module says."""
    rng = np.random.default_rng(seed)
    dh, dv, Q0 = random_cases(n, seed=seed)
    dh = _family(rng, np.asarray(dh, float))
    dv = _family(rng, np.asarray(dv, float))
    Q0 = _family(rng, np.asarray(Q0, float))
    Q0[0] += np.where(np.all(Q0 == 0, axis=0), 1.0, 0.0)
    w0 = _family(rng, np.zeros((3, n)))
    failure = str(rng.choice(["atan", "step", "none"]))
    opts = RunOptions(t_end=t_end, failure=failure, Ta=float(rng.uniform(0, 1)),
                      t_fail=float(rng.uniform(0, t_end)) if failure == "step" else None,
                      sat_reading=str(rng.choice(["commanded", "nominal"])))
    g = paper_gains()
    ref = reference()
    ctx = make_context(ref, [g] * n, opts)
    scale = 1.0 if rng.random() < 0.5 else 10.0 ** rng.uniform(-12, 12)
    for loop in (ctx.go, ctx.ga):
        for k in ("K1", "F2", "f3", "q"):
            x = np.array(loop[k], float) * scale
            u = rng.random(x.shape)
            x = np.where(u < 0.125, 0.0, np.where(u < 0.25, -x, x))
            if k in ("K1", "F2"):  # diagonal gain matrices stay diagonal
                x = x * np.eye(3)[:, :, None]
            loop[k] = x
    with np.errstate(all="ignore"):
        X0 = initial_state(ref, dh, dv, Q0, w0, [g] * n)
    return ctx, X0


def audit(ctx, X0: np.ndarray, c: dict, method: str) -> dict[str, np.ndarray]:
    """Per case: outcome code and the unexplained / impossible / nonfinite-in-output flags."""
    o = ctx.opts
    t_end = o.t_end
    code = c["outcome"]
    n = len(code)
    name = np.array(OUTCOMES)[code]
    t = c["t_outcome"]
    y = c["y_end"]
    with np.errstate(all="ignore"):  # huge end states: the norms overflow to inf, as meant
        unexplained = ~((code >= 0) & (code < len(OUTCOMES)))
        unexplained |= ~((t >= 0) & (t <= t_end * (1 + 1e-12)))
        unexplained |= (name == "completed") & ~(np.abs(t - t_end) <= 1e-9 * t_end)
        # at the located crossing (bisection to 2^-60 of the step on the interpolant: r is
        # R_MOON to |r'| dt 2^-60 plus rounding; 16x that allowed); below at t = 0 is named so
        tol_r = 1e-6 + 16 * np.abs(y[:, 5]) * o.dt * 2.0 ** -60
        unexplained |= (name == "crashed") & ~(np.abs(y[:, 0] - P.R_MOON) <= tol_r)
        unexplained |= (name == "below_surface") & ~((t == 0) & (y[:, 0] < P.R_MOON))
        unexplained |= (name == "propellant_exhausted") & ~(np.abs(y[:, 6] - o.m_dry)
                                                             <= 1e-9 * o.m_dry)
        unexplained |= (name == "quaternion_drift") & ~(
            np.abs(np.linalg.norm(y[:, 12:16], axis=1) - 1.0) > P.QUAT_NORM_TOL)
        unexplained |= (name == "step_limit") & (method != "dopri5")
        # blown up: the case ends at the start of the step that asked for it (a node)
        unexplained |= (name == "command_blown_up") & ~(t < t_end)
        fin = name != "nonfinite"
        m = y[:, 6]
        tmax = o.thrust_max * (1 + 1e-12)
        impossible = fin & ~((m > 0) & (m >= o.m_dry * (1 - 1e-12)) & (m <= X0[6]))
        for k in ("peak_thrust", "peak_thrust_cmd", "peak_torque", "peak_thrust_stages",
                  "peak_thrust_cmd_stages"):
            impossible |= c[k] < 0
        if o.sat_reading == "commanded":
            # (24) limits the delivered thrust to T_max, and to fac T_max once saturated;
            # read "nominal", (24) does not limit it (lgw.sim.lunar.plant.saturate_thrust)
            impossible |= (c["peak_thrust"] > tmax) | (c["peak_thrust_stages"] > tmax)
            impossible |= c["thrust_excess_saturated"] > 1e-9 * o.thrust_max
        impossible |= c["peak_torque"] > o.torque_max * (1 + 1e-12)
        impossible |= ~(c["peak_thrust_stages"] >= c["peak_thrust"]) & fin
        impossible |= ~(c["peak_thrust_cmd_stages"] >= c["peak_thrust_cmd"]) & fin
    must = np.column_stack([c[k] for k in NUMBERS])
    bad_out = ~np.all(np.isfinite(must), axis=1) & fin
    bad_out |= fin & ~np.all(np.isfinite(y), axis=1)
    for i in range(n):  # the JSON record is strict (NaN -> null) whatever the case
        json.dumps(case_record(c, i), allow_nan=False)
    return {"code": code, "unexplained": unexplained, "impossible": impossible,
            "nonfinite_out": bad_out}


def outcome_class(code: np.ndarray) -> np.ndarray:
    """completed / domain (surface, dry) / numerical, as tests/lunar/test_outcomes.py."""
    names = np.array(OUTCOMES)[code]
    return np.where(names == "completed", "completed",
                    np.where(np.isin(names, DOMAIN_EXITS[:2]), "domain", "numerical"))


def run(n: int, seed: int, chunk: int, t_end: float, max_steps: int) -> dict:
    totals = {m: Counter() for m in ("rk4", "dopri5")}
    kinds: Counter = Counter()
    pairs: Counter = Counter()
    shown: list[str] = []
    secs = Counter()
    ctx, X0 = adversarial_cases(2, seed, t_end)
    for m in ("rk4", "dopri5"):  # compile / load the kernel outside the timers
        simulate(ctx, X0, method=m, record=False, max_steps=max_steps, **DOPRI)
    for start in range(0, n, chunk):
        k = min(chunk, n - start)
        ctx, X0 = adversarial_cases(k, seed + start, t_end)
        cls, codes, times = {}, {}, {}
        for m in ("rk4", "dopri5"):
            t0 = time.perf_counter()
            with np.errstate(all="ignore"):
                res = simulate(ctx, X0, method=m, record=False, max_steps=max_steps, **DOPRI)
            secs[m] += time.perf_counter() - t0
            a = audit(ctx, X0, res.cases, m)
            tot = totals[m]
            tot.update({OUTCOMES[j]: int(np.sum(a["code"] == j)) for j in range(len(OUTCOMES))})
            for key in ("unexplained", "impossible", "nonfinite_out"):
                tot[key] += int(a[key].sum())
            for i in np.flatnonzero(a["unexplained"] | a["impossible"] | a["nonfinite_out"])[:3]:
                shown.append(f"    {m} case {start + i}: {OUTCOMES[a['code'][i]]} "
                             f"{case_record(res.cases, i)}")
            cls[m] = outcome_class(a["code"])
            codes[m] = a["code"]
            times[m] = res.cases["t_outcome"]
        dis = np.flatnonzero(cls["rk4"] != cls["dopri5"])
        if len(dis):
            lim = np.array(OUTCOMES)[codes["dopri5"][dis]] == "step_limit"
            lim &= times["dopri5"][dis] <= times["rk4"][dis]
            sub = _subset(ctx, X0, dis)
            refined = np.zeros(len(dis), bool)
            for div in (10, 100):
                fine_ctx = replace(sub[0], opts=replace(ctx.opts, dt=ctx.opts.dt / div))
                with np.errstate(all="ignore"):
                    fine = simulate(fine_ctx, sub[1], record=False)
                refined |= outcome_class(fine.cases["outcome"]) == cls["dopri5"][dis]
            kind = np.select([lim, refined], ["step_limit", "refined"], default="other")
            kinds.update(kind.tolist())
            pairs.update(zip(cls["rk4"][dis].tolist(), cls["dopri5"][dis].tolist(),
                             kind.tolist(), strict=True))
            for i in dis[kind == "other"][:5]:
                shown.append(f"    other: case {start + i}: rk4 {cls['rk4'][i]}, dopri5 "
                             f"{cls['dopri5'][i]}")
        kinds["agree"] += k - len(dis)
    return {"totals": totals, "kinds": kinds, "pairs": pairs, "shown": shown,
            "seconds": secs}


def _subset(ctx, X0: np.ndarray, idx: np.ndarray) -> tuple:
    """The context and states of cases ``idx`` only (per-case gains sliced)."""
    go = {k: np.asarray(v)[..., idx] for k, v in ctx.go.items()}
    ga = {k: np.asarray(v)[..., idx] for k, v in ctx.ga.items()}
    return replace(ctx, go=go, ga=ga), X0[:, idx]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=20_000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--chunk", type=int, default=1000)
    ap.add_argument("--t-end", type=float, default=5.0)
    ap.add_argument("--max-steps", type=int, default=5000)
    args = ap.parse_args()
    out = run(args.cases, args.seed, args.chunk, args.t_end, args.max_steps)
    for m in ("rk4", "dopri5"):
        c = out["totals"][m]
        s = out["seconds"][m]
        print(f"{m}: {args.cases} cases to t = {args.t_end} s in {s:.1f} s "
              f"({args.cases / s:.0f} cases/s)")
        print("  outcomes: " + ", ".join(f"{k} {c[k]}" for k in OUTCOMES))
        print(f"  unexplained {c['unexplained']}, impossible {c['impossible']}, "
              f"nonfinite in output {c['nonfinite_out']}")
    kinds = out["kinds"]
    print(f"RK4/dopri5 outcome-class agreement: {kinds['agree']} of {args.cases} "
          f"({args.cases - kinds['agree']} disagree)")
    print("  kinds: " + ", ".join(f"{k} {kinds[k]}" for k in ("step_limit", "refined", "other")))
    for (x, y, k), cnt in out["pairs"].most_common():
        print(f"  rk4 {x} / dopri5 {y} ({k}): {cnt}")
    for line in out["shown"][:20]:
        print(line)


if __name__ == "__main__":
    main()
