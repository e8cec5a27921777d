"""Seed 001's figures from a Section 5 run: tracking errors with the failure time marked, thrust
around the failure with the 34 kN saturation level, the adaptive estimates d0e against the
measured disturbance norms, and V2 (12) and Vlambda (16) against time.

Each ``*_figure`` function takes recorded runs (``lgw.sim.lunar.batch.BatchResult`` with its
``Context``) and returns PNG bytes in the shared style (``lgw.tuning.figures``: Agg,
deterministic).  ``report_figures`` makes the set that ``lgw report lunar`` embeds from the
runs the report already flies; ``lgw simulate lunar --plot DIR`` writes the same set for its
run.  ``section5_figure`` is the older one-file overview (``lgw simulate lunar --out``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from lgw.sim.lunar.batch import BatchResult
from lgw.sim.lunar.closed_loop import Context
from lgw.theory.lunar import parameters as P
from lgw.theory.report import Figure
from lgw.tuning.figures import limit_line, png_bytes, save_png, shared_legend, styled

Run = tuple[str, BatchResult, Context]  # (label, result, context)
FAIL_STYLE = {"color": "#444444", "ls": ":", "lw": 1.2}
YMAX_FRACTION = 1.6  # thrust axis top / T_max: the saturated command can be 100x T_max
WINDOW_BEFORE, WINDOW_AFTER = 20.0, 60.0  # s, the thrust panel's zoom around the failure


def failure_time(ctx: Context) -> float:
    """The failure time of (26): ``t_fail`` or, by default, t_f / 2 (seed 001 Section 5)."""
    return ctx.tf / 2 if ctx.opts.t_fail is None else float(ctx.opts.t_fail)


def _mark_failure(ax, t_fail: float, label: bool = True) -> None:
    ax.axvline(t_fail, label=f"failure (26), t = {t_fail:.4g} s" if label else "_",
               **FAIL_STYLE)


def attitude_error_deg(res: BatchResult, i: int = 0) -> np.ndarray:
    """Rotation angle of the error quaternion, 2 acos|e_Q0| (deg)."""
    return np.degrees(2 * np.arccos(np.clip(np.abs(res.out["eq"][:, 0, i]), 0.0, 1.0)))


def attitude_disturbance_norm(t: np.ndarray, amp: float = P.DIST_TORQUE_AMP) -> np.ndarray:
    """||d(t)|| = ||J^-1 d_M(t)|| (rad/s^2), d_M = amp [cos t, sin t, cos 2t] (seed 001 S5)."""
    dM = amp * np.stack([np.cos(t), np.sin(t), np.cos(2 * t)])
    return np.linalg.norm(dM / P.J_DIAG[:, None], axis=0)


def lyapunov_v2(res: BatchResult, ctx: Context, i: int = 0) -> dict[str, np.ndarray]:
    """V2 (12) per loop along case i: (|z1|^2 + |z2|^2)/2 + (d0e - D)^2 / (2 q), with D the
    disturbance norm measured at each record time (orbit: ||d_o(t)|| of (22b), attitude:
    ||J^-1 d_M(t)||).  Departure: (12) takes D constant; with a time-varying ||d|| this is
    the pointwise value, not a function whose derivative (13) bounds."""
    o, t = res.out, res.t
    d_o = np.linalg.norm(o["d_orbit"][:, :, i], axis=1)
    d_a = attitude_disturbance_norm(t, ctx.opts.dist_amp)
    return {"orbit": o["V2o_part"][:, i] + (o["d0e_orbit"][:, i] - d_o) ** 2
            / (2 * ctx.go["q"][i]),
            "attitude": o["V2a_part"][:, i] + (o["d0e_attitude"][:, i] - d_a) ** 2
            / (2 * ctx.ga["q"][i])}


def tracking_figure(runs: list[Run], title: str, i: int = 0) -> bytes:
    """e_h, |e_v| and the attitude error angle against time, the failure time marked."""
    with styled() as plt:
        fig, ax = plt.subplots(1, 3, figsize=(12.5, 4.3))
        for j, (label, res, _) in enumerate(runs):
            ls = "-" if j == 0 else "--"
            ax[0].plot(res.t, res.out["eh"][:, i], ls, color=f"C{j}", label=label)
            ax[1].plot(res.t, np.linalg.norm(res.out["ev"][:, :, i], axis=1), ls,
                       color=f"C{j}", label=label)
            ax[2].plot(res.t, attitude_error_deg(res, i), ls, color=f"C{j}", label=label)
        for a in ax:
            _mark_failure(a, failure_time(runs[0][2]))
            a.set_xlabel("t [s]")
        ax[0].set_ylabel("height error e_h [m]")
        ax[0].set_title("(a) height")
        ax[1].set_ylabel("|e_v| [m/s] (log scale)")
        ax[1].set_yscale("log")
        ax[1].set_title("(b) velocity")
        ax[2].set_ylabel("attitude error 2 acos|e_Q0| [deg] (log scale)")
        ax[2].set_yscale("log")
        ax[2].set_title("(c) attitude")
        shared_legend(fig, ax, ncol=3)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


def thrust_figure(runs: list[Run], title: str, i: int = 0) -> bytes:
    """Commanded and delivered orbit thrust, whole run and around the failure, with T_max of
    (24) and the nominal T_d."""
    ctx = runs[0][2]
    tfail = failure_time(ctx)
    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(12.5, 4.4))
        for a, zoom in ((ax[0], False), (ax[1], True)):
            for j, (label, res, _) in enumerate(runs):
                t = res.t
                w = ((t >= tfail - WINDOW_BEFORE) & (t <= tfail + WINDOW_AFTER) if zoom
                     else np.ones_like(t, dtype=bool))
                a.plot(t[w], res.out["thrust_cmd"][w, i] / 1e3, color=("C0", "C2")[j],
                       ls="-" if j == 0 else "--", label=f"commanded |u_o| m, {label}")
                a.plot(t[w], res.out["thrust"][w, i] / 1e3, color=("C1", "C4")[j],
                       ls="-" if j == 0 else "--", label=f"delivered T, {label}")
            limit_line(a, ctx.opts.thrust_max / 1e3,
                       f"saturation T_max = {ctx.opts.thrust_max / 1e3:g} kN (24)")
            a.axhline(P.T_NOMINAL / 1e3, color="#555555", lw=0.8,
                      label=f"nominal T_d = {P.T_NOMINAL / 1e3:g} kN")
            _mark_failure(a, tfail)
            a.set_xlabel("t [s]")
            a.set_ylim(0.0, YMAX_FRACTION * ctx.opts.thrust_max / 1e3)
            a.set_ylabel(f"thrust [kN] (axis cut at {YMAX_FRACTION:g} T_max)")
        ax[0].set_title("(a) whole run")
        ax[1].set_title(f"(b) around the failure ({WINDOW_BEFORE:g} s before to "
                        f"{WINDOW_AFTER:g} s after)")
        shared_legend(fig, ax, ncol=3)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.12, 1, 1))
        return png_bytes(fig)


def d0e_figure(res: BatchResult, ctx: Context, title: str, i: int = 0) -> bytes:
    """The adaptive estimates d0e (8) against the disturbance norms measured along the run."""
    t, o = res.t, res.out
    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(12.5, 4.4))
        ax[0].plot(t, o["d0e_attitude"][:, i], color="C0", label="estimate d0e (8)")
        ax[0].plot(t, attitude_disturbance_norm(t, ctx.opts.dist_amp), color="C1", lw=0.8,
                   label="measured ||d(t)||")
        ax[0].set_ylabel("attitude: ||J^-1 d_M|| [rad/s^2]")
        ax[0].set_title("(a) attitude loop")
        ax[1].plot(t, o["d0e_orbit"][:, i], color="C0", label="estimate d0e (8)")
        ax[1].plot(t, np.linalg.norm(o["d_orbit"][:, :, i], axis=1), color="C1", lw=0.8,
                   label="measured ||d(t)||")
        ax[1].set_ylabel("orbit: ||d_o|| of (22b) [m/s^2] (log scale)")
        ax[1].set_yscale("log")
        ax[1].set_title("(b) orbit loop")
        for a in ax:
            _mark_failure(a, failure_time(ctx))
            a.set_xlabel("t [s]")
        shared_legend(fig, ax, ncol=3)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


def lyapunov_figure(res: BatchResult, ctx: Context, title: str, i: int = 0) -> bytes:
    """V2 (12) and Vlambda (16) of both loops against time (log scale; each loop in its own
    units: orbit m^2 and m^2/s^2 terms, attitude dimensionless and rad^2/s^2)."""
    t, o = res.t, res.out
    v2 = lyapunov_v2(res, ctx, i)

    def pos(x):  # log axes: exact zeros (lambda(0) = 0) are left out, not drawn at a floor
        return np.where(x > 0, x, np.nan)

    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(12.5, 4.4))
        for loop, c in (("orbit", "C0"), ("attitude", "C2")):
            ax[0].plot(t, pos(v2[loop]), color=c, label=f"{loop} loop")
            key = "Vlam_o" if loop == "orbit" else "Vlam_a"
            ax[1].plot(t, pos(o[key][:, i]), color=c, label=f"{loop} loop")
        ax[0].set_ylabel("V2 (12), log")
        ax[0].set_title("(a) V2 = |z1|^2/2 + |z2|^2/2 + (d0e - ||d||)^2/(2q)")
        ax[1].set_ylabel("Vlambda (16), log (zeros not drawn)")
        ax[1].set_title("(b) Vlambda = (|lambda1|^2 + |lambda2|^2)/2 (saturation filter)")
        for a in ax:
            a.set_yscale("log")
            _mark_failure(a, failure_time(ctx))
            a.set_xlabel("t [s]")
        shared_legend(fig, ax, ncol=3)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


def report_figures(res: BatchResult, ctx: Context, ideal: tuple[BatchResult, Context] | None
                   = None, what: str = "Section 5 case, paper gains") -> list[Figure]:
    """The figures of a recorded run (case 0), with captions stating what was flown; the
    ideal-pointing run, if given, is drawn dashed beside the coupled one."""
    o = ctx.opts
    runs: list[Run] = [("coupled", res, ctx)]
    if ideal is not None:
        runs.append(("ideal pointing", *ideal))
    tfail = failure_time(ctx)
    note = (f"{what}, RK4 dt = {res.dt:g} s, failure {o.failure!r} "
            f"to T_a = {o.Ta:g} at t = {tfail:.4g} s, saturation reading {o.sat_reading!r}")
    after = res.out["thrust_cmd"][res.t > tfail + 5.0, 0]
    peak = float(np.max(after)) if after.size else float("nan")  # NaN: run ends before
    v2 = lyapunov_v2(res, ctx)
    return [
        Figure("lunar_tracking.png",
               f"Tracking errors against time: height, velocity and attitude ({note}).  "
               f"e_h(t_end) = {res.out['eh'][-1, 0]:.4g} m.",
               tracking_figure(runs, "Seed 001: tracking errors")),
        Figure("lunar_thrust.png",
               f"Orbit thrust commanded and delivered, whole run and around the failure, with "
               f"the saturation level of (24) ({note}).  Commanded peak after t_fail + 5 s: "
               f"{peak / 1e3:.4g} kN; whole run {np.max(res.out['thrust_cmd'][:, 0]) / 1e3:.4g} "
               f"kN (the axis is cut at {YMAX_FRACTION:g} T_max: a command above the cut "
               "runs off the top).",
               thrust_figure(runs, "Seed 001: thrust around the failure")),
        Figure("lunar_d0e.png",
               f"Adaptive estimates d0e (8) against the disturbance norms measured along the "
               f"coupled run ({note}); d0e' = q||z2|| >= 0, so d0e never decreases.  "
               f"d0e(t_end): attitude {res.out['d0e_attitude'][-1, 0]:.4g} rad/s^2, orbit "
               f"{res.out['d0e_orbit'][-1, 0]:.4g} m/s^2.",
               d0e_figure(res, ctx, "Seed 001: adaptive estimate d0e and ||d||")),
        Figure("lunar_lyapunov.png",
               f"V2 (12) with D the measured ||d(t)||, and Vlambda (16), coupled run ({note}).  "
               f"V2 orbit from {v2['orbit'][0]:.4g} to {v2['orbit'][-1]:.4g}, attitude from "
               f"{v2['attitude'][0]:.4g} to {v2['attitude'][-1]:.4g}.",
               lyapunov_figure(res, ctx, "Seed 001: V2 and Vlambda")),
    ]


def write(figs: list[Figure], out_dir: Path) -> list[Path]:
    """Write each figure's PNG into ``out_dir``; the paths written."""
    return [save_png(f.png, out_dir / f.file) for f in figs]


def plot_run(res: BatchResult, ctx: Context, plot_dir: Path, quiet: bool = False) -> list[Path]:
    """``lgw simulate lunar --plot DIR``: the report's figures of case 0 of the run flown."""
    what = ("Section 5 case" if res.n_cases == 1 else
            f"case 0 of {res.n_cases} random cases")
    paths = write(report_figures(res, ctx, what=f"{what}, {ctx.opts.thrust_pointing} pointing, "
                                 "the command's gains"), plot_dir)
    if not quiet:
        import click

        click.echo("wrote " + ", ".join(str(p) for p in paths))
    return paths


def section5_figure(res, path: Path, i: int = 0, ideal=None) -> None:
    """Height error, velocity error, error quaternion, thrust, torque and d0e of case i (and
    optionally the ideal-pointing run, dashed), written to ``path``."""
    save_png(section5_png(res, i, ideal), path)


def section5_png(res, i: int = 0, ideal=None) -> bytes:
    """The overview figure of ``section5_figure`` as PNG bytes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(3, 2, figsize=(11, 9))
    t, o = res.t, res.out
    runs = [(res, "-", "coupled")] + ([(ideal, "--", "ideal pointing")] if ideal else [])
    for r, ls, lab in runs:
        ax[0, 0].plot(r.t, r.out["eh"][:, i], ls, label=lab)
        ax[0, 1].plot(r.t, np.linalg.norm(r.out["ev"][:, :, i], axis=1), ls, label=lab)
        ax[1, 1].plot(r.t, r.out["thrust"][:, i] / 1e3, ls, label=lab)
    ax[0, 0].set_ylabel("e_h [m]")
    ax[0, 1].set_ylabel("|e_v| [m/s]")
    ax[0, 1].set_yscale("log")
    for k in range(4):
        ax[1, 0].plot(t, o["eq"][:, k, i], label=f"e_Q{k}")
    ax[1, 0].set_ylabel("error quaternion")
    ax[1, 1].axhline(34.0, color="k", lw=0.5)
    ax[1, 1].set_ylabel("thrust [kN]")
    for k, n in enumerate("xyz"):
        ax[2, 0].plot(t, o["torque"][:, k, i], label=f"M_{n}")
    ax[2, 0].set_ylabel("torque [N m]")
    ax[2, 1].plot(t, o["d0e_attitude"][:, i], label="d0e attitude [rad/s^2]")
    ax[2, 1].plot(t, o["d0e_orbit"][:, i] / 100, label="d0e orbit / 100 [m/s^2]")
    ax[2, 1].set_ylabel("d0e")
    for a in ax.ravel():
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
        a.set_xlabel("t [s]")
    fig.suptitle("seed 001 Section 5 case (lgw)")
    fig.tight_layout()
    return png_bytes(fig, dpi=90)


def bandwidth_figure(bw, ideal: dict | None, title: str, targets: tuple[float, float]
                     | None = None, chosen: float | None = None) -> bytes:
    """The command filter's effect (``lgw.tuning.lunar.design.Bandwidth``): final height and
    velocity errors and the time the torque saturation ends against wn (log axis), the run at dt
    (filled) and at dt/2 (open) for every wn, surface contact and other stops marked at the
    top, the robust band shaded, the chosen wn marked, and the ideal-pointing run (``ideal``:
    its numbers) as a horizontal line."""
    pts = bw.points
    wn = np.array([p.wn for p in pts])
    done = np.array([p.outcome == "completed" for p in pts])
    with styled() as plt:
        fig, ax = plt.subplots(1, 3, figsize=(13.5, 4.4))
        for a, key, fine, label, ideal_key, tgt in (
                (ax[0], "eh", "eh_fine", "|e_h(t_f)| [m] (log)", "eh_final_m",
                 targets[0] if targets else None),
                (ax[1], "ev", "ev_fine", "|e_v(t_f)| [m/s] (log)", "ev_final_norm_m_s",
                 targets[1] if targets else None)):
            y = np.abs([getattr(p, key) for p in pts])
            yf = np.abs([getattr(p, fine) for p in pts])
            a.plot(wn[done], y[done], "o-", color="C0", label="coupled, dt")
            a.plot(wn, yf, "s", mfc="none", color="C1", label="coupled, dt/2")
            top = max(float(np.nanmax(np.where(np.isfinite(y), y, np.nan))), 1.0) * 3
            for p in pts:
                if p.outcome != "completed":
                    a.plot([p.wn], [top], "x", color="#b00000", ms=8,
                           label=f"stopped: {p.outcome}")
            if ideal is not None:
                a.axhline(abs(ideal[ideal_key]), color="C2", ls="--",
                          label="ideal pointing (no filter in the loop)")
            if tgt is not None:
                limit_line(a, tgt, "target")
            a.set_yscale("log")
            a.set_ylabel(label)
        ax[2].plot(wn, [p.torque_saturation_end_s for p in pts], "o-", color="C3",
                   label="coupled, dt")
        for p in pts:  # a stopped run's saturation ends at its contact at the latest: marked
            if p.outcome != "completed":
                ax[2].plot([p.wn], [p.torque_saturation_end_s], "x", color="#b00000", ms=9,
                           label=f"stopped: {p.outcome}")
        ax[2].set_ylabel("torque (28) saturated until [s]")
        for a in ax:
            a.set_xscale("log")
            a.set_xlabel("command filter natural frequency wn [rad/s] (log)")
            if bw.band is not None:
                a.axvspan(bw.band[0], bw.band[1], color="#1b7837", alpha=0.12,
                          label="robust band")
            if chosen is not None:
                a.axvline(chosen, color="#1b7837", lw=1.4, label=f"wn = {chosen:g} rad/s")
        ax[0].set_title("(a) height error at t_f")
        ax[1].set_title("(b) velocity error at t_f")
        ax[2].set_title("(c) when the torque saturation ends")
        shared_legend(fig, ax, ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.1, 1, 1))
        return png_bytes(fig)


def compare_figure(runs: list[tuple[str, str, BatchResult]], title: str) -> bytes:
    """``lgw compare lunar``: e_h and |e_v| against time for each condition (colour) and
    pointing (solid coupled, dashed ideal); ``runs``: (condition, pointing, recorded run)."""
    conds = list(dict.fromkeys(c for c, _, _ in runs))
    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(12.5, 4.6))
        for cond, pointing, res in runs:
            j = conds.index(cond)
            ls = "-" if pointing == "coupled" else "--"
            lab = f"{cond}, {pointing}"
            ax[0].plot(res.t, res.out["eh"][:, 0], ls, color=f"C{j}", label=lab)
            ax[1].plot(res.t, np.linalg.norm(res.out["ev"][:, :, 0], axis=1), ls,
                       color=f"C{j}", label=lab)
        ax[0].set_ylabel("height error e_h [m] (symlog)")
        ax[0].set_yscale("symlog", linthresh=1.0)
        ax[1].set_ylabel("|e_v| [m/s] (log)")
        ax[1].set_yscale("log")
        for a in ax:
            a.set_xlabel("t [s]")
        ax[0].set_title("(a) height")
        ax[1].set_title("(b) velocity")
        shared_legend(fig, ax, ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.14, 1, 1))
        return png_bytes(fig)
