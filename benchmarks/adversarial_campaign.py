"""A campaign of adversarial seed 000 states: every case one outcome, nothing impossible.

    python benchmarks/adversarial_campaign.py --cases 1000000 --method dopri5
    python benchmarks/adversarial_campaign.py --cases 100000 --method both

States (``adversarial_states``): each of the six components of r, v independently from one of
five families with random sign, exact zero, tiny 10^U(-300, -3), moderate 10^U(-3, 4), huge
10^U(4, 300), or the Table III box value of that component (so that a good share of cases
flies); mass m_dry + 10^U(-6, 4) kg.  Corrected law, default gains, no thrust limit (where
commands blow up) unless ``--thrust-max``, stop at landing, t_max 120 s.

Printed per method: the count per outcome (lgw.sim.results), "unexplained" (a case whose
recorded quantities contradict its outcome: landed outside the tolerances, propellant
exhausted without exactly m_dry / m0 - m_dry, horizon before t_max, ...), "impossible" (fuel
outside [0, m0 - m_dry], end mass below m_dry, a peak (node, stage or after arrival) above
BLOWUP_ACCEL m0 or negative, a stage peak below the node peak),
"nonfinite in output" (a NaN/inf in a quantity the case's outcome says is a number), and with
``--method both`` the RK4/dopri5 outcome agreement with the disagreeing pairs.  Chunks of
``--chunk`` cases keep the memory flat; the seed makes every run reproducible.
"""

from __future__ import annotations

import argparse
import time
from collections import Counter

import numpy as np
from lgw.sim.mars.batch import BLOWUP_ACCEL, DT_DEFAULT, simulate_batch
from lgw.sim.mars.campaign import TABLE3_R_MAX, TABLE3_R_MIN, TABLE3_V_MAX, TABLE3_V_MIN
from lgw.sim.results import OUTCOMES
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import LAND_POS_TOL, LAND_VEL_TOL, M_DRY

T_MAX = 120.0
NEAR_TARGET = 1e-6  # m, as tests/mars/test_adversarial.py
FUEL_EDGE = 0.01  # of the load, as tests/mars/test_adversarial.py


def adversarial_states(n: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(r0 (n, 3), v0 (n, 3), m0 (n,)): the families of the module docstring."""
    rng = np.random.default_rng(seed)
    fam = rng.integers(0, 5, (n, 6))
    sign = rng.choice([-1.0, 1.0], (n, 6))
    box = rng.uniform(np.r_[TABLE3_R_MIN, TABLE3_V_MIN], np.r_[TABLE3_R_MAX, TABLE3_V_MAX],
                      (n, 6))
    x = np.select([fam == 0, fam == 1, fam == 2, fam == 3],
                  [0.0, sign * 10.0 ** rng.uniform(-300, -3, (n, 6)),
                   sign * 10.0 ** rng.uniform(-3, 4, (n, 6)),
                   sign * 10.0 ** rng.uniform(4, 300, (n, 6))], default=box)
    m0 = M_DRY + 10.0 ** rng.uniform(-6, 4, n)
    return x[:, :3].copy(), x[:, 3:].copy(), m0


def audit(res, m_dry: float = M_DRY, t_max: float = T_MAX) -> dict[str, np.ndarray]:
    """Per case: outcome code, and the unexplained / impossible / nonfinite-in-output flags."""
    code, t = res.outcomes()
    name = np.array(OUTCOMES)[code]
    load = res.m0 - m_dry
    landed = name == "landed"
    dry = name == "propellant_exhausted"
    with np.errstate(invalid="ignore"):
        unexplained = np.zeros(len(res), bool)
        unexplained |= landed & ~((np.linalg.norm(res.r_land, axis=1) <= LAND_POS_TOL * (1 + 1e-9))
                                  & (np.linalg.norm(res.v_land, axis=1)
                                     <= LAND_VEL_TOL * (1 + 1e-9))
                                  & (res.landing_time <= t_max))
        unexplained |= dry & ~((res.y_end[:, 6] == m_dry) & (res.fuel == load))
        unexplained |= (name == "horizon") & (res.t_end != t_max)
        unexplained |= (name == "command_blown_up") & ~(res.t_end < t_max)
        unexplained |= (name == "step_limit") & ~res.step_limit
        blow = BLOWUP_ACCEL * res.m0[:, None]
        # the end state of a "nonfinite" case is the failed step's (flagged, not a result)
        impossible = ~((res.fuel >= -1e-9 * res.m0) & (res.fuel <= load)
                       & ((res.y_end[:, 6] >= m_dry) | (name == "nonfinite"))
                       & np.all((res.peak_thrust >= 0) & (res.peak_thrust <= blow), axis=1)
                       & np.all((res.peak_thrust_unsat >= 0) & (res.peak_thrust_unsat <= blow),
                                axis=1)
                       # stage peaks: a thrust, and at least the node peaks they include
                       & np.all((res.peak_thrust_stages >= res.peak_thrust)
                                & (res.peak_thrust_stages <= blow), axis=1)
                       & np.all((res.peak_thrust_unsat_stages >= res.peak_thrust_unsat)
                                & (res.peak_thrust_unsat_stages <= blow), axis=1)
                       # after arrival: a thrust, or NaN (null) if the axis never arrived
                       & np.all(np.isnan(res.peak_thrust_after_arrival)
                                | ((res.peak_thrust_after_arrival >= 0)
                                   & (res.peak_thrust_after_arrival <= blow)), axis=1))
    must = np.column_stack([res.fuel, res.time_saturated, res.min_altitude, res.t_end, t,
                            res.peak_thrust, res.peak_thrust_unsat, res.peak_thrust_stages,
                            res.peak_thrust_unsat_stages])
    bad_out = ~np.all(np.isfinite(must), axis=1)
    bad_out |= landed & ~np.all(np.isfinite(np.column_stack([res.r_land, res.v_land])), axis=1)
    # a case whose outcome is "nonfinite" carries a non-finite end state by definition: it is
    # counted as its outcome; any other NaN/inf is counted here
    bad_out |= (name != "nonfinite") & ~np.all(np.isfinite(res.y_end), axis=1)
    return {"code": code, "unexplained": unexplained, "impossible": impossible,
            "nonfinite_out": bad_out}


def run(n: int, seed: int, method: str, chunk: int, thrust_max: float | None) -> dict:
    gains = default_gains()
    totals: Counter = Counter()
    codes, times, shown, fuels = [], [], [], []
    near = []
    t0 = time.perf_counter()
    for start in range(0, n, chunk):
        k = min(chunk, n - start)
        r0, v0, m0 = adversarial_states(k, seed + start)
        res = simulate_batch(r0, v0, m0, gains, method=method, t_max=T_MAX,
                             thrust_limit=thrust_max)
        a = audit(res)
        totals.update({OUTCOMES[c]: int(np.sum(a["code"] == c)) for c in range(len(OUTCOMES))})
        for key in ("unexplained", "impossible", "nonfinite_out"):
            totals[key] += int(a[key].sum())
        codes.append(a["code"])
        times.append(res.outcomes()[1])
        fuels.append(res.fuel)
        near.append(np.min(np.abs(r0), axis=1) < NEAR_TARGET)
        for i in np.flatnonzero(a["unexplained"] | a["impossible"] | a["nonfinite_out"])[:3]:
            shown.append(f"    case {start + i}: {OUTCOMES[a['code'][i]]} r0 {r0[i].tolist()} "
                         f"v0 {v0[i].tolist()} m0 {m0[i]!r}: fuel {res.fuel[i]!r}, y_end "
                         f"{res.y_end[i].tolist()}, peaks {res.peak_thrust_unsat[i].tolist()}")
    seconds = time.perf_counter() - t0
    return {"counts": totals, "codes": np.concatenate(codes), "times": np.concatenate(times),
            "fuel": np.concatenate(fuels),
            "near": np.concatenate(near), "shown": shown, "seconds": seconds}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=100_000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--method", choices=["rk4", "dopri5", "both"], default="both")
    ap.add_argument("--chunk", type=int, default=100_000)
    ap.add_argument("--thrust-max", type=float, default=None)
    args = ap.parse_args()
    methods = ["rk4", "dopri5"] if args.method == "both" else [args.method]
    out = {}
    for m in methods:
        out[m] = run(args.cases, args.seed, m, args.chunk, args.thrust_max)
        c = out[m]["counts"]
        print(f"{m}: {args.cases} cases in {out[m]['seconds']:.1f} s "
              f"({args.cases / out[m]['seconds']:.0f} cases/s)")
        print("  outcomes: " + ", ".join(f"{k} {c[k]}" for k in OUTCOMES))
        print(f"  unexplained {c['unexplained']}, impossible {c['impossible']}, "
              f"nonfinite in output {c['nonfinite_out']}")
        for line in out[m]["shown"][:10]:
            print(line)
    if len(methods) == 2:
        a, b = out["rk4"]["codes"], out["dopri5"]["codes"]
        dis = a != b
        print(f"RK4/dopri5 outcome agreement: {int((~dis).sum())} of {len(a)} "
              f"({int(dis.sum())} disagree)")
        kind = disagreement_kinds(np.flatnonzero(dis), out, args)
        print("  kinds: " + ", ".join(f"{k} {int(np.sum(kind == k))}"
                                      for k in ("refined", "near", "step", "fuel", "other")))
        pairs = Counter((OUTCOMES[x], OUTCOMES[y], k)
                        for x, y, k in zip(a[dis], b[dis], kind, strict=True))
        for (x, y, k), cnt in pairs.most_common():
            print(f"  rk4 {x} / dopri5 {y} ({k}): {cnt}")
        for i in np.flatnonzero(dis)[kind == "other"][:20]:
            print(f"    other: case {i}: rk4 {OUTCOMES[a[i]]} at {out['rk4']['times'][i]:.6g} s,"
                  f" dopri5 {OUTCOMES[b[i]]} at {out['dopri5']['times'][i]:.6g} s")


def disagreement_kinds(idx: np.ndarray, out: dict, args) -> np.ndarray:
    """The kinds of tests/mars/test_adversarial.py for the disagreeing cases idx: "refined"
    (RK4 at dt/10 gives dopri5's outcome), "near" (an axis within 1e-6 m of its target),
    "step" (both outcomes within one RK4 step), "fuel" (landed vs dry with the larger fuel
    within 1 % of the load), else "other"."""
    rows = []
    for start in range(0, args.cases, args.chunk):
        sel = idx[(idx >= start) & (idx < start + args.chunk)] - start
        if len(sel):
            r0, v0, m0 = adversarial_states(min(args.chunk, args.cases - start), args.seed + start)
            rows.append(np.column_stack([r0[sel], v0[sel], m0[sel]]))
    x = np.concatenate(rows) if rows else np.empty((0, 7))
    ca, cb = out["rk4"]["codes"][idx], out["dopri5"]["codes"][idx]
    ta, tb = out["rk4"]["times"][idx], out["dopri5"]["times"][idx]
    fine = simulate_batch(x[:, :3], x[:, 3:6], x[:, 6], default_gains(), t_max=T_MAX,
                          dt=DT_DEFAULT / 10, thrust_limit=args.thrust_max)
    refined = fine.outcomes()[0] == cb
    near = np.min(np.abs(x[:, :3]), axis=1) < NEAR_TARGET
    step = np.abs(ta - tb) < DT_DEFAULT
    pair = np.array([{OUTCOMES[p], OUTCOMES[q]} == {"landed", "propellant_exhausted"}
                     for p, q in zip(ca, cb, strict=True)], bool)
    fuel = pair & (np.maximum(out["rk4"]["fuel"][idx], out["dopri5"]["fuel"][idx])
                   >= (1 - FUEL_EDGE) * (x[:, 6] - M_DRY))
    return np.select([refined, near, step, fuel], ["refined", "near", "step", "fuel"],
                     default="other")


if __name__ == "__main__":
    main()
