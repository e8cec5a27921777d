"""Seed 000's figures: Monte Carlo overlays and landing dispersions (the paper's Figs. 7-8),
settling time against the initial state beside the bounds (Fig. 6), thrust against time with
the limit, and s1-s2 phase portraits.

Each ``*_figure`` function takes data (a ``BatchResult`` with trajectories, or a sweep dict)
and returns PNG bytes (``lgw.tuning.figures``: Agg, one style, deterministic).  The data
functions fly the simulator (``lgw.sim.mars.batch.simulate_batch``, RK4 at its default step)
and the bounds come from ``lgw.theory.mars.bounds.axis_bounds`` (the same functions the CLI,
the report and the tests call).  ``report_figures`` makes the set that ``lgw report mars``
embeds; ``lgw simulate mars --plot DIR`` writes the ones that fit its run.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim.mars.batch import ARRAY_FIELDS as _ARRAY_FIELDS
from lgw.sim.mars.batch import BatchResult, simulate_batch
from lgw.sim.mars.campaign import table1_state, table2_states
from lgw.sim.mars.parameters import T_MAX_DEFAULT
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.mss import surfaces_numeric
from lgw.theory.mars.parameters import LAND_POS_TOL, M0, R0, THRUST_MAX_AXIS, V0
from lgw.theory.report import Figure
from lgw.tuning.figures import BOUND_STYLES, limit_line, png_bytes, save_png, shared_legend, styled

AXES = "xyz"
FIG6_SWEEP = tuple(float(x) for x in np.linspace(-8000.0, -1000.0, 15))  # m, s1x(0), Fig. 6
MC_DISTURBANCE_AMPLITUDE = 20.0  # m/s^2, seed 000 (47): a_p,i = 20 sin t (Part 2, Figs. 7-8)


@dataclass(frozen=True)
class FigureOptions:
    """What the report's figures fly: the Table II campaign of Figs. 7-8 (``cases`` cases
    from ``seed``, a_p,i = 20 sin t), the Fig. 6 sweep of s1x(0), and the law."""

    cases: int = 300
    seed: int = 0
    law: str = "corrected"
    drag: str = "physical"
    sweep: tuple[float, ...] = FIG6_SWEEP
    overlay: int = 300  # trajectories drawn in the overlays (all cases' end points are drawn)


# --- data -----------------------------------------------------------------------------------

def campaign(gains: Gains, opts: FigureOptions) -> BatchResult:
    """Seed 000 Part 2 (Figs. 7-8): Table II states, a_p,i = 20 sin t, trajectories kept."""
    r0, v0, m0 = table2_states(opts.cases, opts.seed)
    return simulate_batch(r0, v0, m0, gains, law=opts.law, disturbance="sin",
                          dist_amplitude=MC_DISTURBANCE_AMPLITUDE, drag=opts.drag, record=True)


def single_case(gains: Gains, law: str = "corrected", drag: str = "physical",
                thrust_limit: float | None = None) -> BatchResult:
    """The Table I case, trajectory kept (no disturbance)."""
    r0, v0, m0 = table1_state()
    return simulate_batch(r0, v0, m0, gains, law=law, drag=drag, thrust_limit=thrust_limit,
                          record=True)


def settling_sweep(gains: Gains, opts: FigureOptions) -> dict[str, Any]:
    """Fig. 6: from s1x(0) in ``opts.sweep`` (other states Table I), the first times |s2x|,
    |s1x| enter the eps band, beside the x-axis bounds (exact and Polyakov).  The horizon
    covers the exact landing bound T2* + T1*: a case that has not settled by then is a
    violation, and shows as a missing point."""
    b = axis_bounds(gains)["x"]
    n = len(opts.sweep)
    r0 = np.tile(R0, (n, 1))
    r0[:, 0] = opts.sweep
    t_max = max(T_MAX_DEFAULT, 1.2 * b["landing_time_bound"])
    res = simulate_batch(r0, np.tile(V0, (n, 1)), np.full(n, M0), gains, law=opts.law,
                         drag=opts.drag, t_max=t_max, stop="t_max")
    rows = [{"s1x0": float(s), "t_s2x": float(res.t_s2[i, 0]), "t_s1x": float(res.t_s1[i, 0])}
            for i, s in enumerate(opts.sweep)]
    return {"law": opts.law, "eps": res.eps, "dt": res.dt, "t_max": t_max, "rows": rows,
            "bounds_x": {k: b[k] for k in ("T2_exact", "T1_exact", "landing_time_bound",
                                           "T2_polyakov", "T1_polyakov",
                                           "landing_time_bound_polyakov")}}


def _valid(tr: dict[str, np.ndarray], i: int) -> np.ndarray:
    return np.isfinite(tr["r"][i, :, 0])


def final_states(res: BatchResult) -> tuple[np.ndarray, np.ndarray]:
    """(r, v) where each case stopped: at landing, else the last integrated state."""
    r_end = np.where(res.landed[:, None], res.r_land, res.y_end[:, :3])
    v_end = np.where(res.landed[:, None], res.v_land, res.y_end[:, 3:6])
    return r_end, v_end


# --- figures --------------------------------------------------------------------------------

def trajectories_figure(res: BatchResult, title: str, n_draw: int = 300) -> bytes:
    """Fig. 7: 3-D trajectories and the velocity components against time, every case."""
    tr = res.trajectory
    if tr is None:
        raise ValueError("trajectories_figure needs a BatchResult flown with record=True")
    n = min(len(res), n_draw)
    with styled() as plt:
        fig = plt.figure(figsize=(11.5, 8.2))
        ax3 = fig.add_subplot(2, 2, 1, projection="3d")
        axv = [fig.add_subplot(2, 2, k) for k in (2, 3, 4)]
        t = tr["t"]
        for i in range(n):
            ok = _valid(tr, i)
            r, v = tr["r"][i][ok], tr["v"][i][ok]
            ax3.plot(r[:, 0], r[:, 1], r[:, 2], color="C0", lw=0.5, alpha=0.35)
            for k, ax in enumerate(axv):
                ax.plot(t[ok], v[:, k], color="C0", lw=0.5, alpha=0.35)
        r_end, _ = final_states(res)
        ax3.scatter(r_end[:n, 0], r_end[:n, 1], r_end[:n, 2], color="C3", s=4,
                    label="end of each run")
        ax3.scatter([0], [0], [0], color="k", marker="x", s=40, label="landing site")
        ax3.set_xlabel("r_x [m]")
        ax3.set_ylabel("r_y [m]")
        ax3.set_zlabel("r_z (altitude) [m]")
        ax3.set_title("(a) trajectories")
        ax3.legend(loc="upper left", fontsize=8)
        for k, ax in enumerate(axv):
            ax.axhline(0.0, color="k", lw=0.6)
            ax.set_xlabel("t [s]")
            ax.set_ylabel(f"v_{AXES[k]} [m/s]")
            ax.set_title(f"({'bcd'[k]}) {AXES[k]}-axis velocity")
        fig.suptitle(title)
        fig.tight_layout()
        return png_bytes(fig)


def dispersion_figure(res: BatchResult, title: str, s1_bound: float | None = None) -> bytes:
    """Fig. 8: where each case stopped (XOY, XOZ) and its final velocity (XOZ, XOY)."""
    r_end, v_end = final_states(res)
    landed = res.landed
    with styled() as plt:
        fig, ax = plt.subplots(2, 2, figsize=(10.5, 8.2))
        panels = ((ax[0, 0], r_end, (0, 1), "(a) final position, XOY plane", "m"),
                  (ax[0, 1], r_end, (0, 2), "(b) final position, XOZ plane", "m"),
                  (ax[1, 0], v_end, (0, 2), "(c) final velocity, XOZ plane", "m/s"),
                  (ax[1, 1], v_end, (0, 1), "(d) final velocity, XOY plane", "m/s"))
        for a, data, (i, j), name, unit in panels:
            sym = "r" if unit == "m" else "v"
            if (~landed).any():
                a.scatter(data[~landed, i], data[~landed, j], s=9, color="C3", alpha=0.7,
                          label=f"not landed ({int((~landed).sum())})")
            if landed.any():
                a.scatter(data[landed, i], data[landed, j], s=9, color="C2", alpha=0.7,
                          label=f"landed ({int(landed.sum())})")
            a.axhline(0.0, color="k", lw=0.6)
            a.axvline(0.0, color="k", lw=0.6)
            a.set_xlabel(f"{sym}_{AXES[i]} [{unit}]")
            a.set_ylabel(f"{sym}_{AXES[j]} [{unit}]")
            a.set_title(name)
            if unit == "m" and s1_bound is not None and s1_bound <= 5 * np.abs(data).max():
                a.add_patch(plt.Rectangle((-s1_bound, -s1_bound), 2 * s1_bound, 2 * s1_bound,
                                          fill=False, **BOUND_STYLES[0],
                                          label="(31) neighbourhood"))
        shared_legend(fig, ax.ravel(), ncol=3)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.04, 1, 1))
        return png_bytes(fig)


def settling_figure(sweep: dict[str, Any], title: str) -> bytes:
    """Fig. 6: t_s2x and t_s1x against s1x(0), with the exact and the Polyakov bounds."""
    rows, b = sweep["rows"], sweep["bounds_x"]
    s = np.array([r["s1x0"] for r in rows])
    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(11.5, 4.6), sharey=True)
        for a, key, name, lines in (
                (ax[0], "t_s2x", "(a) second surface: first |s2x| <= eps",
                 (("T2_exact", "T2* (exact least upper bound)"),
                  ("T2_polyakov", "(26) T2, Polyakov"))),
                (ax[1], "t_s1x", "(b) first surface: first |s1x| <= eps (from t = 0)",
                 (("landing_time_bound", "T2* + T1* (sound landing bound)"),
                  ("landing_time_bound_polyakov", "(26) + (18), Polyakov")))):
            y = np.array([np.nan if r[key] is None else r[key] for r in rows], dtype=float)
            a.plot(s, y, "o-", color="C0", label=f"simulated ({sweep['law']} law)")
            for (k, lab), style in zip(lines, BOUND_STYLES[::2], strict=True):
                if k in b:
                    a.axhline(b[k], label=f"{lab} = {b[k]:.4g} s", **style)
            a.set_yscale("log")
            a.set_xlabel("s1x(0) = r_x(0) [m]")
            a.set_title(name)
            a.legend(loc="center right", fontsize=8)
        ax[0].set_ylabel("time [s] (log scale)")
        fig.suptitle(title + f" (eps = {sweep['eps']:g}, dt = {sweep['dt']:g} s)")
        fig.tight_layout()
        return png_bytes(fig)


def thrust_figure(runs: list[tuple[str, BatchResult]], title: str,
                  limit: float = THRUST_MAX_AXIS) -> bytes:
    """|F_i| against time per axis for each run, the per-axis limit drawn."""
    with styled() as plt:
        fig, ax = plt.subplots(1, 3, figsize=(12.5, 4.4), sharey=True)
        for k, a in enumerate(ax):
            for j, (label, res) in enumerate(runs):
                tr = res.trajectory
                ok = _valid(tr, 0)
                a.plot(tr["t"][ok], np.abs(tr["F"][0][ok, k]) / 1e3, color=f"C{j}",
                       ls="-" if j == 0 else "--", label=label)
            limit_line(a, limit / 1e3, f"per-axis limit {limit / 1e3:g} kN (Part 3)")
            a.set_xlabel("t [s]")
            a.set_title(f"{AXES[k]} axis")
        ax[0].set_ylabel("|F_i| [kN]")
        shared_legend(fig, ax, ncol=3)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


def surfaces(gains: Gains, res: BatchResult, i: int) -> tuple[np.ndarray, np.ndarray]:
    """(s1, s2) (15), (21) along case ``i`` of a recorded run, per axis: (S, 3) each."""
    tr = res.trajectory
    ok = _valid(tr, i)
    r, v = tr["r"][i][ok], tr["v"][i][ok]
    s2f = surfaces_numeric()[1]
    s1 = r.copy()
    s2 = np.empty_like(r)
    for k in range(3):
        ax = gains.axis(k)
        s2[:, k] = s2f(r[:, k], v[:, k], ax["beta1"], ax["beta2"], ax["q1"], ax["q2"])
    return s1, s2


def phase_figure(gains: Gains, res: BatchResult, title: str, n_draw: int = 30) -> bytes:
    """s1-s2 phase portraits per axis (symmetric-log axes: s1 spans km, s2 tens of m/s)."""
    n = min(len(res), n_draw)
    with styled() as plt:
        fig, ax = plt.subplots(1, 3, figsize=(12.5, 4.6))
        for i in range(n):
            s1, s2 = surfaces(gains, res, i)
            for k, a in enumerate(ax):
                a.plot(s1[:, k], s2[:, k], color="C0", lw=0.7 if n > 1 else 1.4, alpha=0.6,
                       label="trajectory" if i == 0 else "_")
                a.plot(s1[0, k], s2[0, k], "o", color="C1", ms=3,
                       label="start" if i == 0 else "_")
                a.plot(s1[-1, k], s2[-1, k], "s", color="C3", ms=3,
                       label="end (landing or t_max)" if i == 0 else "_")
        for k, a in enumerate(ax):
            a.axhline(0.0, color="C2", lw=1.2, label="s2 = 0: the reaching law (16)")
            a.plot([0], [0], "kx", ms=8, label="target s1 = s2 = 0")
            a.set_xscale("symlog", linthresh=1.0)
            a.set_yscale("symlog", linthresh=0.1)
            a.set_xlabel(f"s1{AXES[k]} = r_{AXES[k]} [m] (symlog)")
            a.set_ylabel(f"s2{AXES[k]} [m/s] (symlog)")
            a.set_title(f"{AXES[k]} axis")
        shared_legend(fig, ax, ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


# --- the report's set and the command's --plot ----------------------------------------------

def report_figures(gains: Gains, opts: FigureOptions = FigureOptions()) -> list[Figure]:
    """The figures ``lgw report mars`` embeds, with captions that state what was flown."""
    b = axis_bounds(gains)
    mc = campaign(gains, opts)
    r_end, v_end = final_states(mc)
    mc_note = (f"{len(mc)} Table II cases (seed {opts.seed}), a_p,i = "
               f"{MC_DISTURBANCE_AMPLITUDE:g} sin t (47), {opts.law} law, drag {opts.drag!r}, "
               f"RK4 dt = {mc.dt:g} s")
    sweep = settling_sweep(gains, opts)
    free = single_case(gains, opts.law, opts.drag)
    limited = single_case(gains, opts.law, opts.drag, thrust_limit=THRUST_MAX_AXIS)
    r2, v2, m2 = table2_states(29, opts.seed)
    calm = simulate_batch(r2, v2, m2, gains, law=opts.law, drag=opts.drag, record=True)
    phase_runs = _concat_cases([free, calm], 30)
    figs = [
        Figure("mc_trajectories.png",
               f"Monte Carlo trajectories and velocities (seed 000 Fig. 7): {mc_note}.  "
               f"{int(mc.landed.sum())} landed (|r| <= {LAND_POS_TOL:g} m); "
               f"{int(mc.ground_contact.sum())} went below r_z = 0 first; "
               f"{int(mc.fuel_exhausted.sum())} ran out of propellant (m_dry), where their "
               "runs stop.",
               trajectories_figure(mc, "Seed 000 Fig. 7: 300-case Monte Carlo, "
                                   "trajectories and velocities", opts.overlay)),
        Figure("mc_dispersion.png",
               f"Where each run stopped and its velocity there (seed 000 Fig. 8): {mc_note}.  "
               f"max_i |r_i| = {np.abs(r_end).max():.3g} m, max |v| = "
               f"{np.linalg.norm(v_end, axis=1).max():.3g} m/s; the workbench's (31) "
               f"neighbourhood for this gain set is {b['x']['s1_bound']:.4g} m per axis.",
               dispersion_figure(mc, "Seed 000 Fig. 8: final positions and velocities",
                                 b["x"]["s1_bound"])),
        Figure("settling_fig6.png",
               "Settling time against the initial state (seed 000 Fig. 6): from s1x(0) in "
               f"[{min(opts.sweep):g}, {max(opts.sweep):g}] m (other states Table I), the "
               "first entry of |s2x| and |s1x| into the eps band, beside the exact bounds "
               "and Polyakov's (3)-form bounds (18), (26) (log scale).",
               settling_figure(sweep, "Seed 000 Fig. 6: settling against s1x(0)")),
        Figure("thrust.png",
               f"Commanded thrust per axis on the Table I case ({opts.law} law, no "
               f"disturbance), unlimited and with the 50 kN per-axis limit of Part 3 "
               f"(peak {np.max(free.peak_thrust[0]) / 1e3:.3g} kN per axis unlimited).",
               thrust_figure([("unlimited", free), ("limited to 50 kN per axis", limited)],
                             "Thrust against time, Table I case")),
        Figure("phase_s1_s2.png",
               "s1-s2 phase portraits per axis: the Table I case and 29 Table II states "
               f"(seed {opts.seed}), no disturbance, {opts.law} law.  The line s2 = 0 is "
               "the reaching law (16); each run stops at landing, which with these gains can "
               "come before s2 has reached 0 (the end points off the line).",
               phase_figure(gains, phase_runs, "Phase portraits s1-s2", 30)),
    ]
    return figs


def _concat_cases(runs: list[BatchResult], n: int) -> BatchResult:
    """A recorded BatchResult holding the first cases of ``runs`` in order (``n`` in all), on
    the shortest common time grid (for the phase portraits)."""
    S = min(r.trajectory["t"].shape[0] for r in runs)
    tr = {"t": runs[0].trajectory["t"][:S]}
    for k in ("r", "v", "m", "F"):
        tr[k] = np.concatenate([r.trajectory[k][:, :S] for r in runs])[:n]
    base = runs[0]
    return BatchResult(**{f: np.concatenate([getattr(r, f) for r in runs])[:n]
                          for f in _ARRAY_FIELDS}, eps=base.eps, dt=base.dt, trajectory=tr)


def write(figs: list[Figure], out_dir: Path) -> list[Path]:
    """Write each figure's PNG into ``out_dir``; the paths written."""
    return [save_png(f.png, out_dir / f.file) for f in figs]


def simulation_figures(gains: Gains, res: BatchResult, opts: dict[str, Any],
                       states: tuple[np.ndarray, np.ndarray, np.ndarray],
                       n_overlay: int = 300) -> list[Figure]:
    """The figures for an ``lgw simulate mars`` run: a campaign gets the overlays (its first
    ``n_overlay`` cases re-flown with trajectories, the same options), the dispersion of every
    case and the phase portraits; a single case gets thrust against time and its phase
    portrait.  ``opts`` are the simulate_batch keywords the run used (RK4 only)."""
    r0, v0, m0 = states
    n = min(len(res), n_overlay)
    kw = {k: v for k, v in opts.items() if k not in ("method", "rtol", "atol", "max_step")}
    rec = simulate_batch(r0[:n], v0[:n], m0[:n], gains, record=True, **kw)
    what = (f"{opts.get('law', 'corrected')} law, disturbance {opts.get('disturbance')!r}, "
            f"drag {opts.get('drag')!r}, RK4 dt = {rec.dt:g} s")
    limit = opts.get("thrust_limit") or THRUST_MAX_AXIS
    figs = [Figure("thrust.png" if len(res) == 1 else "thrust_case0.png",
                   f"|F_i| against time, case 0 ({what}); the line is the "
                   f"{limit / 1e3:g} kN per-axis limit.",
                   thrust_figure([("case 0", rec)], "Thrust against time", limit)),
            Figure("phase_s1_s2.png", f"s1-s2 phase portraits ({min(n, 30)} cases; {what}).",
                   phase_figure(gains, rec, "Phase portraits s1-s2", 30))]
    if len(res) > 1:
        figs += [Figure("mc_trajectories.png", f"Trajectories and velocities of the first {n} "
                        f"of {len(res)} cases ({what}).",
                        trajectories_figure(rec, f"{len(res)} cases: trajectories and "
                                            "velocities", n)),
                 Figure("mc_dispersion.png", f"Final positions and velocities of all "
                        f"{len(res)} cases ({what}).",
                        dispersion_figure(res, f"{len(res)} cases: final positions and "
                                          "velocities", axis_bounds(gains)["x"]["s1_bound"]))]
    return figs
