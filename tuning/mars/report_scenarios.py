"""The record behind seed 000's simulation claims (``lgw.theory.mars.scenario_claims``): the
Part 1 comparison (``lgw.tuning.mars.compare.run_comparison``) and a search over the gains of
(25) the paper does not state, each trial flown on the paper's own scenarios.

Trials: the report's gain set, every tuned file of the comparison, then ``RANDOM_TRIALS`` gain
sets drawn (seeded) from ``BOX``.  Each flies the printed law (25), the paper's own, with the
comparison's per-axis thrust limit and drag model:
  part1      the Table I case, no disturbance (landed, fuel, landing time);
  part1_sin  the Table I case under a_p,i = sin t (landed, lowest altitude);
  part2      ``PART2_CASES`` Table II states under a_p,i = 20 sin t (47), touchdown speeds
             (landed: |v| at landing; ground contact first: |v| where r_z crosses 0);
  part3      ``PART3_CASES`` Table III states with the 50 kN per-axis limit (landed, latest
             landing time).
The claims compute their margins from these numbers (theory may not import the simulator).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from lgw.theory.mars.gains import Gains, gains_from_dict

# The box of the gains of (25) the paper does not state: gains log-uniform, exponents where
# the printed command stays bounded (q1 >= 1/2, claim bounded-command-printed) and within the
# hypotheses of (16), (25).
BOX: dict[str, tuple[float, float, str]] = {
    "beta1": (1e-2, 1e1, "log"), "beta2": (1e-5, 1e-1, "log"),
    "alpha1": (1e-2, 1e1, "log"), "alpha2": (1e-5, 1e-1, "log"),
    "q1": (0.5, 0.95, "linear"), "q2": (1.05, 2.0, "linear"),
    "g1": (0.5, 0.95, "linear"), "g2": (1.05, 2.0, "linear")}
RANDOM_TRIALS = 16
PART2_CASES = 100
PART3_CASES = 50
SEED = 0
T_MAX = 120.0  # s: every Part's horizon
T_S1_BAND, T_S2_BAND = 9.76, 7.89  # s: seed 000 Figs. 10 and 9


def _draw(rng: np.random.Generator) -> dict[str, float]:
    out = {}
    for k, (lo, hi, scale) in BOX.items():
        u = rng.uniform()
        x = 10 ** (math.log10(lo) + u * (math.log10(hi) - math.log10(lo))) if scale == "log" \
            else lo + u * (hi - lo)
        out[k] = float(f"{x:.4g}")
    return out


def _plain(g: Gains) -> dict[str, Any]:
    d = g.to_dict()["gains"]
    return {k: (list(v) if isinstance(v, list) else v) for k, v in d.items()}


def _touchdown_speeds(b: Any) -> np.ndarray:
    """Per case: |v| at landing, or where r_z first crosses 0 before landing (linear between
    the recorded nodes), or inf if neither happened by the horizon."""
    tr = b.trajectory
    out = np.full(len(b.landed), np.inf)
    for i in range(len(b.landed)):
        if b.landed[i]:
            out[i] = float(np.linalg.norm(b.v_land[i]))
            continue
        rz = tr["r"][i, :, 2]
        k = np.flatnonzero(np.isfinite(rz) & (rz < 0.0))
        if k.size and k[0] > 0:
            j = int(k[0])
            th = rz[j - 1] / (rz[j - 1] - rz[j])
            v = tr["v"][i, j - 1] + th * (tr["v"][i, j] - tr["v"][i, j - 1])
            out[i] = float(np.linalg.norm(v))
    return out


def _bands(b: Any, g: Gains) -> dict[str, float]:
    """Largest |s1,i| = |r_i| after 9.76 s and |s2,i| after 7.89 s over the recorded nodes of
    every case and axis until it stopped (seed 000 Figs. 9-10), and the largest time the
    cases were flown (a case that stopped earlier contributes its nodes up to then)."""
    from lgw.theory.mars.mss import surfaces_numeric

    tr = b.trajectory
    t = tr["t"]
    r, v = tr["r"], tr["v"]
    s2 = surfaces_numeric()[1](r, v, g.beta1, g.beta2, g.q1, g.q2)
    with np.errstate(invalid="ignore"):
        late1 = np.where((t >= T_S1_BAND)[None, :, None], np.abs(r), np.nan)
        late2 = np.where((t >= T_S2_BAND)[None, :, None], np.abs(s2), np.nan)
    m1, m2 = np.nanmax(late1, initial=0.0), np.nanmax(late2, initial=0.0)
    return {"max_s1_after": float(m1), "max_s2_after": float(m2)}


def fly_trial(g: Gains, thrust_max: float, drag: str) -> dict[str, Any]:
    """One gain set of (25) (printed) on the paper's scenarios (see the module docstring)."""
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.campaign import table1_state, table2_states, table3_states

    law = "printed"
    one = table1_state()
    b = simulate_batch(*one, g, law=law, thrust_limit=thrust_max, drag=drag, t_max=T_MAX)
    part1 = {"landed": bool(b.landed[0]), "fuel": float(b.fuel[0]),
             "landing_time": float(b.landing_time[0]) if b.landed[0] else math.nan}
    bs = simulate_batch(*one, g, law=law, thrust_limit=thrust_max, drag=drag, t_max=T_MAX,
                        disturbance="sin", dist_amplitude=1.0)
    part1_sin = {"landed": bool(bs.landed[0]), "min_altitude": float(bs.min_altitude[0])}
    b2 = simulate_batch(*table2_states(PART2_CASES, SEED), g, law=law, drag=drag, t_max=T_MAX,
                        disturbance="sin", dist_amplitude=20.0, thrust_limit=thrust_max,
                        record=True)
    td = _touchdown_speeds(b2)
    part2 = {"cases": PART2_CASES, "landed": int(b2.landed.sum()),
             "ground_contact": int(b2.ground_contact.sum()),
             "max_touchdown_speed": float(np.max(td)), **_bands(b2, g)}
    b3 = simulate_batch(*table3_states(PART3_CASES, SEED), g, law=law, drag=drag,
                        t_max=T_MAX, thrust_limit=thrust_max)
    part3 = {"cases": PART3_CASES, "landed": int(b3.landed.sum()),
             "max_landing_time": float(np.max(b3.landing_time)) if b3.landed.all()
             else math.inf}
    return {"part1": part1, "part1_sin": part1_sin, "part2": part2, "part3": part3}


def scenario_record(g: Gains, comparison: dict[str, Any],
                    tuned: list[tuple[str, Gains]]) -> dict[str, Any]:
    """The record ``lgw.theory.mars.scenario_claims.comparison_claims`` judges."""
    thrust_max = float(comparison["thrust_max_axis"])
    drag = str(comparison["drag"])
    sets: list[tuple[str, Gains]] = [("the report's gain set", g), *tuned]
    rng = np.random.default_rng(SEED)
    for j in range(RANDOM_TRIALS):
        sets.append((f"random {j + 1}", gains_from_dict({"gains": _draw(rng)})))
    trials = [{"label": label, "gains": _plain(gs), **fly_trial(gs, thrust_max, drag)}
              for label, gs in sets]
    return {"comparison": comparison,
            "search": {"law": "printed (25), the paper's own",
                       "box": {k: [lo, hi, sc] for k, (lo, hi, sc) in BOX.items()},
                       "budget": f"{len(trials)} gain sets (the report's, {len(tuned)} tuned, "
                                 f"{RANDOM_TRIALS} random, seed {SEED}); per set 1 + 1 Table I "
                                 f"flights, {PART2_CASES} Table II and {PART3_CASES} Table III "
                                 "states",
                       "seed": SEED,
                       "method": "random search over the box (the report's and the tuned gain "
                                 "sets first), each set flown by the RK4 simulator "
                                 f"(lgw.sim.mars.batch), thrust limit {thrust_max:g} N per "
                                 f"axis, drag {drag!r}",
                       "trials": trials}}
