"""The paper's 15 s scenario for the six variants and Monte Carlo campaigns over initial offsets.

Scenario: Table 1's start moved by the chosen offset (lgw.theory.eros.parameters.SCENARIO_*;
the paper starts on the reference and prints no offset).  Campaign: offsets uniform in
|e_i(0)| <= MC_POS, |e_i'(0)| <= MC_VEL, disturbance phases uniform per case, seeded.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from lgw.sim.eros import laws as SL
from lgw.sim.eros.batch import SimOptions, metrics, outcome_counts, simulate
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains

SUMMARY_KEYS = ("t_reach_max", "t_track_all", "iae", "iae_int", "u_peak", "effort", "chatter")


def offsets(n: int, seed: int, e_max: float = P.MC_POS,
            v_max: float = P.MC_VEL) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    return (rng.uniform(-e_max, e_max, (n, 3)), rng.uniform(-v_max, v_max, (n, 3)),
            rng.uniform(0, 2 * np.pi, n))


def summarize(m: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Per case scalars: worst axis for times, peaks; sums over axes for effort and chatter;
    the case's outcome (index into lgw.sim.eros.batch.OUTCOMES) and its time."""
    return {"t_reach_max": np.nanmax(np.where(np.isnan(m["t_reach"]), np.inf, m["t_reach"]),
                                     axis=1),
            "t_track_all": m["t_track_all"], "iae": m["iae"], "iae_int": m["iae_int"],
            "u_peak": m["u_peak"].max(axis=1), "effort": m["effort"].sum(axis=1),
            "chatter": m["chatter"].sum(axis=1), "nonfinite": m["nonfinite"],
            "outcome": m["outcome"], "t_outcome": m["t_outcome"]}


def run_variants(e0: np.ndarray, ed0: np.ndarray, g: Gains, base: SimOptions,
                 case_phase: np.ndarray | None = None) -> dict[str, dict[str, np.ndarray]]:
    """Every variant on the same cases: name -> per-case summary (summarize)."""
    out = {}
    for law, sw in SL.VARIANTS:
        res = simulate(e0, ed0, g, replace(base, law=law, switch=sw), case_phase)
        out[SL.variant_name(law, sw)] = summarize(metrics(res))
    return out


def scenario(g: Gains, base: SimOptions | None = None) -> dict[str, dict[str, float]]:
    """The paper's 15 s run (one case per variant)."""
    base = base or SimOptions()
    res = run_variants(P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], g, base)
    return {k: {kk: float(v[0]) for kk, v in d.items()} for k, d in res.items()}


def monte_carlo(g: Gains, n: int, seed: int, base: SimOptions | None = None):
    """Campaign: (offsets, per-variant per-case summaries)."""
    base = base or SimOptions()
    e0, ed0, ph = offsets(n, seed)
    return (e0, ed0, ph), run_variants(e0, ed0, g, base, ph)


def table(res: dict[str, dict[str, np.ndarray]]) -> list[dict[str, float | str]]:
    """Rows of the Table 2 analogue: per variant mean and max of each summary key, over the
    finite values of the cases that tracked or reached the horizon (lgw.sim.stats.finite_stats:
    a crashed or non-finite case is counted in ``outcomes``, never inside a mean or a maximum;
    ``{key}_n`` says how many cases a statistic summarises, None when none)."""
    from lgw.sim.eros.batch import OUTCOMES
    from lgw.sim.stats import finite_stats

    rows = []
    for name, d in res.items():
        row: dict[str, float | str | None] = {"variant": name}
        counted = np.isin(d["outcome"], [OUTCOMES.index("tracked"), OUTCOMES.index("horizon")])
        for k in SUMMARY_KEYS:
            st = finite_stats(d[k], counted)
            row[f"{k}_mean"] = st["mean"]
            row[f"{k}_max"] = st["max"]
            row[f"{k}_n"] = st["n"]
        row["nonfinite"] = int(np.sum(d["nonfinite"]))
        row["outcomes"] = outcome_counts(d["outcome"])
        rows.append(row)
    return rows
