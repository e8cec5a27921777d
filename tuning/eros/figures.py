"""Seed 002's figures: the six controller variants side by side on the paper's 15 s scenario
(tracking errors per axis, control against time, the chattering measure), and the Monte Carlo
reaching and tracking times.

The scenario is re-flown here with trajectories (``lgw.sim.eros.batch.simulate``, the same
sampled-data loop and options as ``lgw.sim.eros.campaign.scenario``, whose summaries keep no
histories); the chattering bars are ``lgw.sim.eros.batch.metrics``' total variation of u, the
number the report's tables and the chattering claims use.  Each ``*_figure`` returns PNG bytes
in the shared style (``lgw.tuning.figures``: Agg, deterministic).  ``report_figures`` is the set
``lgw report eros`` embeds; ``lgw simulate eros --plot DIR`` writes the same kinds for its run.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
from lgw.sim.eros import laws as SL
from lgw.sim.eros.batch import Result, SimOptions, metrics, simulate
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains
from lgw.theory.report import Figure
from lgw.tuning.figures import limit_line, png_bytes, save_png, shared_legend, styled

AXES = "xyz"
NAMES = tuple(SL.variant_name(*v) for v in SL.VARIANTS)
# one colour per law, solid for sgn and dashed for tanh: the pairs read side by side
COLOURS = {"pdsmc": "C0", "ftsmc": "C1", "fuzzy": "C2"}
LINES = {"sign": "-", "tanh": "--"}
LABELS = {"pdsmc": "PD-SMC", "ftsmc": "FTSMC", "fuzzy": "fuzzy FTSMC"}
FLOOR = 1e-6  # m, bottom of the log error axes (sampled errors below it are drawn there)


def label(name: str) -> str:
    law, sw = SL.parse_variant(name)
    return f"{LABELS[law]}, {'sgn' if sw == 'sign' else 'tanh'}"


def style(name: str) -> dict[str, str]:
    law, sw = SL.parse_variant(name)
    return {"color": COLOURS[law], "ls": LINES[sw]}


def fly(g: Gains, base: SimOptions, e0: np.ndarray, ed0: np.ndarray,
        phase: np.ndarray | None = None, names: tuple[str, ...] = NAMES) -> dict[str, Result]:
    """Every variant in ``names`` on the same cases, histories kept."""
    return {n: simulate(e0, ed0, g, replace(base, law=SL.parse_variant(n)[0],
                                            switch=SL.parse_variant(n)[1]), phase)
            for n in names}


def scenario_runs(g: Gains, base: SimOptions | None = None) -> dict[str, Result]:
    """The paper's scenario (offset SCENARIO_OFFSET, e0' = SCENARIO_VOFFSET), six variants."""
    return fly(g, base or SimOptions(), P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None])


def tracking_figure(runs: dict[str, Result], title: str, i: int = 0) -> bytes:
    """|e_i| against time per axis, every variant, with the 'tracked' band TRACK_TOL."""
    with styled() as plt:
        fig, ax = plt.subplots(1, 3, figsize=(12.5, 4.4), sharey=True)
        for k, a in enumerate(ax):
            for name, r in runs.items():
                a.plot(r.t, np.maximum(np.abs(r.e[:, i, k]), FLOOR), label=label(name),
                       **style(name))
            limit_line(a, P.TRACK_TOL, f"'tracked' band |e_i| = {P.TRACK_TOL:g} m (chosen)")
            a.set_yscale("log")
            a.set_xlabel("t [s]")
            a.set_title(f"{AXES[k]} axis")
        ax[0].set_ylabel(f"|e_i| [m] (log scale, floor {FLOOR:g} m)")
        shared_legend(fig, ax, ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.1, 1, 1))
        return png_bytes(fig)


def control_figure(runs: dict[str, Result], title: str, i: int = 0,
                   limit: float | None = None) -> bytes:
    """The held control u_i (m/s^2) against time, one panel per variant (rows: sgn, tanh;
    columns: the laws), the three axes in each; ``limit`` drawn if one applies."""
    names = list(runs)
    laws = [law for law in SL.L.LAWS if any(SL.parse_variant(n)[0] == law for n in names)]
    sws = [sw for sw in SL.L.SWITCHES if any(SL.parse_variant(n)[1] == sw for n in names)]
    with styled() as plt:
        fig, ax = plt.subplots(len(sws), len(laws), figsize=(4.2 * len(laws) + 0.5,
                                                            3.3 * len(sws) + 0.6),
                               sharex=True, sharey=True, squeeze=False)
        for name, r in runs.items():
            law, sw = SL.parse_variant(name)
            a = ax[sws.index(sw), laws.index(law)]
            tu = r.t[:-1]
            for k in range(3):
                a.step(tu, r.u[:, i, k], where="post", color=f"C{k + 3}", lw=0.9,
                       label=f"u_{AXES[k]}")
            if limit is not None:
                limit_line(a, limit, f"limit {limit:g} m/s^2", both_signs=True)
            a.set_title(label(name))
        for a in ax[-1]:
            a.set_xlabel("t [s]")
        for a in ax[:, 0]:
            a.set_ylabel("u_i [m/s^2]")
        shared_legend(fig, ax.ravel(), ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.05, 1, 1))
        return png_bytes(fig)


def chatter_figure(chatter: dict[str, float], title: str, note: str = "") -> bytes:
    """The chattering measure, total variation of u summed over the axes, per variant (log)."""
    names = list(chatter)
    vals = np.array([chatter[n] for n in names])
    with styled() as plt:
        fig, ax = plt.subplots(figsize=(8.5, 4.4))
        bars = ax.bar(range(len(names)), vals, color=[style(n)["color"] for n in names],
                      hatch=None)
        for b, n in zip(bars, names, strict=True):
            if SL.parse_variant(n)[1] == "tanh":
                b.set_hatch("//")
                b.set_edgecolor("white")
        for x, v in enumerate(vals):
            ax.annotate(f"{v:.3g}", (x, v), ha="center", va="bottom", fontsize=8.5,
                        xytext=(0, 2), textcoords="offset points")
        ax.set_xticks(range(len(names)), [label(n).replace(", ", "\n") for n in names])
        ax.set_yscale("log")
        ax.set_ylabel("TV(u) = sum_k,i |u_i(k+1) - u_i(k)| [m/s^2] (log)")
        ax.set_title(note)
        fig.suptitle(title)
        fig.tight_layout()
        return png_bytes(fig)


def times_figure(per_case: dict[str, dict[str, np.ndarray]], title: str) -> bytes:
    """Monte Carlo reaching time (worst axis) and tracked time per variant: one point per case
    (jittered), the median marked; cases never tracked within the run are counted, not drawn."""
    names = list(per_case)
    rng = np.random.default_rng(0)  # fixed jitter: the same bytes every time
    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(12.5, 4.6), sharey=False)
        for a, key, name in ((ax[0], "t_reach_max", "(a) reaching time, worst axis"),
                             (ax[1], "t_track_all", "(b) tracked time, all axes "
                                                    f"(|e_i| <= {P.TRACK_TOL:g} m after)")):
            ticks = []
            for x, n in enumerate(names):
                v = np.asarray(per_case[n][key], float)
                ok = np.isfinite(v)
                jit = rng.uniform(-0.18, 0.18, ok.sum())
                a.scatter(x + jit, v[ok], s=7, alpha=0.55, color=style(n)["color"])
                if ok.any():
                    a.plot([x - 0.3, x + 0.3], [np.median(v[ok])] * 2, color="k", lw=1.6,
                           label="median" if x == 0 else "_")
                miss = int((~ok).sum())
                ticks.append(label(n).replace(", ", "\n") + (f"\n({miss} never)" if miss
                                                              else ""))
            a.set_xticks(range(len(names)), ticks, fontsize=8)
            a.set_ylabel("t [s]")
            a.set_title(name)
        shared_legend(fig, ax, ncol=1)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.06, 1, 1))
        return png_bytes(fig)


def _chatter(runs: dict[str, Result]) -> dict[str, float]:
    return {n: float(metrics(r)["chatter"][0].sum()) for n, r in runs.items()}


def run_figures(runs: dict[str, Result], what: str) -> list[Figure]:
    """Tracking, control and chattering figures of recorded runs (case 0 of each)."""
    ch = _chatter(runs)
    first = next(iter(runs.values())).options
    note = (f"{what}; dt = {first.dt:g} s sampling (zero-order hold), gravity "
            f"{first.gravity!r}, disturbance {first.disturbance!r}")
    return [
        Figure("eros_tracking.png",
               f"Tracking errors |e_i| per axis, the variants side by side ({note}); the line "
               f"is the 'tracked' band {P.TRACK_TOL:g} m (chosen, lgw.theory.eros.parameters)."
               , tracking_figure(runs, "Seed 002: tracking errors per axis")),
        Figure("eros_control.png",
               f"Held control u_i against time per variant ({note}); seed 002 states no "
               "control limit, so none is drawn.",
               control_figure(runs, "Seed 002: control against time")),
        Figure("eros_chatter.png",
               f"Chattering measure: total variation of the held u, summed over the axes "
               f"({note}); hatched bars: tanh switching.  "
               + "; ".join(f"{label(n)}: {v:.4g}" for n, v in ch.items()) + " m/s^2.",
               chatter_figure(ch, "Seed 002: chattering, total variation of u",
                              "the paper's scenario")),
    ]


def campaign_figure(per_case: dict[str, dict[str, np.ndarray]], n: int, seed: int) -> Figure:
    """The Monte Carlo times (per-case summaries of lgw.sim.eros.campaign.monte_carlo)."""
    return Figure("eros_mc_times.png",
                  f"Monte Carlo reaching and tracked times per variant: {n} cases (seed {seed}), "
                  f"|e_i(0)| <= {P.MC_POS:g} m, |e_i'(0)| <= {P.MC_VEL:g} m/s, disturbance "
                  "phases uniform; one point per case, the bar is the median; a case never "
                  "tracked within the run is counted under its variant.",
                  times_figure(per_case, f"Seed 002: Monte Carlo times, {n} cases"))


def report_figures(g: Gains, base: SimOptions, mc=None, n: int = 0, seed: int = 0
                   ) -> list[Figure]:
    """The figures ``lgw report eros`` embeds: the scenario re-flown with histories, and the
    campaign's times if ``mc`` (lgw.sim.eros.campaign.monte_carlo output) is given."""
    figs = run_figures(scenario_runs(g, base),
                       f"the paper's scenario: offset {P.SCENARIO_OFFSET.tolist()} m, "
                       f"{base.t_final:g} s")
    if mc is not None:
        figs.append(campaign_figure(mc[1], n, seed))
    return figs


def write(figs: list[Figure], out_dir: Path) -> list[Path]:
    """Write each figure's PNG into ``out_dir``; the paths written."""
    return [save_png(f.png, out_dir / f.file) for f in figs]


def run_figures_for(g: Gains, base: SimOptions, names: tuple[str, ...], e0: np.ndarray,
                    ed0: np.ndarray, phase: np.ndarray, seed: int = 0) -> list[Figure]:
    """``lgw simulate eros --plot DIR``: the variants flown by the command, re-flown with
    histories on the same cases and options; tracking, control and chattering of case 0, and
    for a campaign the per-case times."""
    from lgw.sim.eros.campaign import summarize

    runs = fly(g, base, e0, ed0, phase, names)
    n = len(np.atleast_2d(e0))
    what = (f"case 0 of {n}" if n > 1 else "one case") + (
        f": e(0) = {np.round(np.atleast_2d(e0)[0], 4).tolist()} m, "
        f"e'(0) = {np.round(np.atleast_2d(ed0)[0], 4).tolist()} m/s, {base.t_final:g} s")
    figs = run_figures({k: _case0(r) for k, r in runs.items()}, what)
    if n > 1:
        figs.append(campaign_figure({k: summarize(metrics(r)) for k, r in runs.items()}, n,
                                    seed))
    return figs


def _case0(r: Result) -> Result:
    """Case 0 of a run (the figures draw case 0; metrics of it alone for the bars)."""
    return replace(r, e=r.e[:, :1], ed=r.ed[:, :1], s=r.s[:, :1], u=r.u[:, :1], pos=r.pos[:1],
                   vel=r.vel[:1], nonfinite=r.nonfinite[:1])
