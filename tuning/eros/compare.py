"""Seed 002's own comparison: its six controllers (PD-SMC, FTSMC and the fuzzy FTSMC, each with
the sign and the tanh switching) on the paper's 15 s tracking scenario, measured on Table 2's
metric and on the times and control the paper's figures discuss, against the printed numbers,
with the paper's ranking judged per switching function.

Metrics per variant (``lgw.sim.eros.batch.metrics``): tracked time (|e_i| <= 1 cm for the
rest of the run on every axis; the paper: PD-SMC 8 s, FTSMC 5 s, fuzzy < 4 s), reaching time
(worst axis), Table 2's "absolute error" (the paper prints 244.8155, 139.6112, 113.4074 for
PD-SMC, FTSMC, fuzzy without a definition or a unit; the workbench gives the sum over the
0.01 s samples and the axes of |e_i| (m), MATLAB's sum(abs(e)), and its integral (m s)),
control peak, effort, chattering (total variation of u).

Convergence: every variant is flown twice, RK4 with ``n_sub`` substeps per sample (the
default) and the kernel's dopri5 at rtol = atol = 1e-10 between the same samples (the
sampled-data controller is the same; only the plant's integration differs); each metric is
converged when the two agree to 1 % (or to the metric's absolute floor).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from lgw.sim.eros import laws as SL
from lgw.sim.eros.batch import OUTCOMES, Result, SimOptions, metrics, simulate
from lgw.sim.eros.campaign import summarize
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains

LAWS = ("pdsmc", "ftsmc", "fuzzy")  # the paper's order, worst first
LAW_NAMES = {"pdsmc": "PD-SMC", "ftsmc": "FTSMC", "fuzzy": "fuzzy FTSMC"}
RTOL = 0.01
# metric -> (label, unit, absolute floor of the convergence check)
METRICS = {"t_track_all": ("tracked", "s", 2 * P.DT_SAMPLE),
           "t_reach_max": ("reached", "s", 2 * P.DT_SAMPLE),
           "iae": ("abs. error sum", "m", 1e-3), "iae_int": ("abs. error int.", "m s", 1e-5),
           "u_peak": ("peak |u|", "m/s^2", 1e-6), "effort": ("effort", "m/s", 1e-6),
           "chatter": ("TV(u)", "m/s^2", 1e-3)}
REFERENCE = {"method": "dopri5", "rtol": 1e-10, "atol": 1e-10}


@dataclass
class VariantResult:
    name: str
    law: str
    switch: str
    numbers: dict
    reference: dict
    res: Result  # RK4 run with histories (for the figures)

    def converged(self, key: str) -> bool:
        a, b = self.numbers[key], self.reference[key]
        if not (math.isfinite(a) and math.isfinite(b)):
            return (math.isnan(a) and math.isnan(b)) or a == b
        return abs(a - b) <= RTOL * max(abs(b), METRICS[key][2])

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"variant": self.name, "law": self.law, "switch": self.switch,
                               "outcome": OUTCOMES[int(self.numbers["outcome"])],
                               "paper_tracked_s": P.TRACK_TIMES_PRINTED[self.law],
                               "paper_abs_error": P.ABS_ERROR_PRINTED[self.law]}
        for k in METRICS:
            out[k] = _num(self.numbers[k])
            out[f"{k}_reference"] = _num(self.reference[k])
            out[f"{k}_converged"] = self.converged(k)
        return out


def _num(x: float) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def run_variants(g: Gains, base: SimOptions, progress: Any = None) -> list[VariantResult]:
    """The six variants on the scenario, RK4 and the dopri5 reference."""
    e0, ed0 = P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None]
    out = []
    for law, sw in SL.VARIANTS:
        name = SL.variant_name(law, sw)
        if progress is not None:
            progress.stage(f"{name}: RK4 and the dopri5 reference")
        o = replace(base, law=law, switch=sw)
        r = simulate(e0, ed0, g, o)
        ref = simulate(e0, ed0, g, replace(o, **REFERENCE))
        a = {k: float(v[0]) for k, v in summarize(metrics(r)).items()}
        b = {k: float(v[0]) for k, v in summarize(metrics(ref)).items()}
        out.append(VariantResult(name, law, sw, a, b, r))
    return out


def rankings(rows: list[VariantResult]) -> list[dict[str, Any]]:
    """The paper's ranking (fuzzy < FTSMC < PD-SMC) per switching function, for the tracked
    time and Table 2's absolute error: the margin min(FTSMC - fuzzy, PD - FTSMC) (> 0: the
    ranking holds) and the order found."""
    by = {(r.law, r.switch): r for r in rows}
    out = []
    for key, what in (("t_track_all", "tracked time"), ("iae", "absolute error (Table 2)")):
        for sw in ("sign", "tanh"):
            v = {law: by[(law, sw)].numbers[key] for law in LAWS}
            margin = min(v["ftsmc"] - v["fuzzy"], v["pdsmc"] - v["ftsmc"])
            order = sorted(LAWS, key=lambda law: v[law])
            out.append({"metric": key, "what": what, "switch": sw,
                        "paper": "fuzzy FTSMC < FTSMC < PD-SMC",
                        "found": " < ".join(LAW_NAMES[law] for law in order),
                        "values": {LAW_NAMES[law]: _num(v[law]) for law in LAWS},
                        "margin": _num(margin), "holds": bool(margin > 0)})
    return out


def table2_figure(rows: list[VariantResult], title: str) -> bytes:
    """Table 2 and the tracked times, simulated (bars, sign and tanh side by side) against the
    printed values (black markers): (a) absolute error, (b) tracked time, (c) chattering."""
    from lgw.tuning.figures import png_bytes, shared_legend, styled

    by = {(r.law, r.switch): r for r in rows}
    x = np.arange(len(LAWS))
    with styled() as plt:
        fig, ax = plt.subplots(1, 3, figsize=(13.5, 4.4))
        for j, sw in enumerate(("sign", "tanh")):
            for a, key in ((ax[0], "iae"), (ax[1], "t_track_all"), (ax[2], "chatter")):
                vals = [by[(law, sw)].numbers[key] for law in LAWS]
                a.bar(x + (j - 0.5) * 0.36, vals, 0.36, color=f"C{j}",
                      label=f"simulated, {sw}")
        ax[0].plot(x, [P.ABS_ERROR_PRINTED[law] for law in LAWS], "k_", ms=22, mew=2.5,
                   label="printed (Table 2; its unit is not given)")
        ax[1].plot(x, [P.TRACK_TIMES_PRINTED[law] for law in LAWS], "k_", ms=22, mew=2.5,
                   label="printed (\"tracked in\")")
        ax[0].set_ylabel("absolute error: sum over samples and axes of |e_i| [m]")
        ax[1].set_ylabel("tracked (|e_i| <= 1 cm from then on) [s]")
        ax[2].set_ylabel("total variation of u [m/s^2] (log)")
        ax[2].set_yscale("log")
        for a, t in zip(ax, ("(a) Table 2: absolute error", "(b) tracking time",
                             "(c) chattering"), strict=True):
            a.set_xticks(x, [LAW_NAMES[law] for law in LAWS])
            a.set_title(t)
        shared_legend(fig, ax, ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.08, 1, 1))
        return png_bytes(fig)
