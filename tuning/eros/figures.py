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


# --- the whole descent ------------------------------------------------------------------------

FIG_POINTS = 400  # history points per curve in the descent figures (the histories decimated)


def _decimate(n: int, k: int = FIG_POINTS) -> np.ndarray:
    return np.unique(np.linspace(0, n - 1, min(n, k)).round().astype(int))


def _valid(r, i: int = 0) -> np.ndarray:
    """Sample indices where case i still flew (histories are NaN after the end)."""
    return np.flatnonzero(np.isfinite(r.pos[:, i, 0]))


def _velocity(r, i: int = 0) -> np.ndarray:
    """True velocity history (KR, 3): e' + the profile's velocity."""
    return r.ed[:, i] + r.options.profile().evaluate(r.t)[1].T


def heights(pts: np.ndarray) -> np.ndarray:
    """Distance (m) of each point to the shape model (the nearest point of any face)."""
    from lgw.theory.eros.descent import height_above

    return np.array([height_above(p) for p in pts])


def trajectory_figure(runs: dict, title: str) -> bytes:
    """The trajectory over the shape model: (a) the whole body and the path from Table 1's start,
    (b) the last kilometre around the touchdown site (faces within 0.8 km drawn)."""
    from lgw.theory.eros.polyhedron import eros_polyhedron
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    E = eros_polyhedron()
    tri = E.vertices[E.faces] / 1e3
    first = next(iter(runs.values()))
    site = first.options.profile().site.point / 1e3
    with styled() as plt:
        fig = plt.figure(figsize=(12.5, 5.6))
        for j, (zoom, sub) in enumerate(((False, "(a) the whole descent"),
                                         (True, "(b) the terminal segment"))):
            ax = fig.add_subplot(1, 2, j + 1, projection="3d")
            if zoom:
                near = np.all(np.abs(tri - site).max(axis=2) < 0.8, axis=1)
                faces = tri[near]
            else:
                faces = tri[::3]
            col = Poly3DCollection(faces, facecolor="0.75", edgecolor="0.55", lw=0.15,
                                   alpha=0.35 if not zoom else 0.55)
            ax.add_collection3d(col)
            for name, r in runs.items():
                idx = _valid(r)
                p = r.pos[idx, 0] / 1e3
                if zoom:
                    p = p[np.linalg.norm(p - site, axis=1) < 1.0]
                law, sw = SL.parse_variant(name)
                ax.plot(*p.T, color=COLOURS[law], ls=LINES[sw], lw=1.3, label=label(name))
                end = r.pos_end[0] / 1e3
                ax.scatter(*end, color=COLOURS[law], s=14)
            ax.scatter(*site, marker="x", color="k", s=40, label="touchdown site")
            if zoom:
                lo, hi = site - 0.8, site + 0.8
            else:
                pts = np.vstack([tri.reshape(-1, 3), first.pos[_valid(first), 0] / 1e3])
                lo, hi = pts.min(axis=0), pts.max(axis=0)
            c, half = (lo + hi) / 2, (hi - lo).max() / 2
            ax.set_xlim(c[0] - half, c[0] + half)
            ax.set_ylim(c[1] - half, c[1] + half)
            ax.set_zlim(c[2] - half, c[2] + half)
            ax.set_xlabel("x [km]")
            ax.set_ylabel("y [km]")
            ax.set_zlabel("z [km]")
            ax.set_title(sub)
            ax.view_init(elev=20, azim=-60 if not zoom else -30)
        handles, labels = fig.axes[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=4, frameon=False)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


def altitude_speed_figure(runs: dict, title: str) -> bytes:
    """Height above the shape model and speed relative to the surface against time, case 0 of
    each variant, with the reference's; the last 2000 s in the right panels."""
    first = next(iter(runs.values()))
    prof = first.options.profile()
    with styled() as plt:
        fig, ax = plt.subplots(2, 2, figsize=(12.5, 7.2))
        idx = _decimate(len(first.t))
        tref = first.t[idx]
        pref, vref, _ = prof.evaluate(tref)
        href = heights(pref.T)
        for col, t_lo in ((0, -np.inf), (1, prof.t_touchdown - 2000.0)):
            m = tref >= t_lo
            ax[0, col].plot(tref[m], href[m], color="k", lw=1.0, ls=":", label="reference")
            ax[1, col].plot(tref[m], np.linalg.norm(vref, axis=0)[m], color="k", lw=1.0,
                            ls=":", label="reference")
        for name, r in runs.items():
            ok = _valid(r)
            ii = ok[_decimate(len(ok))]
            t = np.append(r.t[ii], r.t_outcome[0])
            h = np.append(heights(r.pos[ii, 0]), 0.0 if r.outcome[0] <= 1 else np.nan)
            v = np.append(np.linalg.norm(_velocity(r)[ii], axis=1),
                          np.linalg.norm(r.vel_end[0]))
            for col, t_lo in ((0, -np.inf), (1, prof.t_touchdown - 2000.0)):
                m = t >= t_lo
                ax[0, col].plot(t[m], h[m], label=label(name), **style(name))
                ax[1, col].plot(t[m], v[m], label=label(name), **style(name))
        for col in (0, 1):
            ax[0, col].set_ylabel("height above the shape model [m]")
            ax[1, col].set_ylabel("speed relative to the surface [m/s]")
            ax[1, col].set_xlabel("t [s]")
        limit_line(ax[1, 1], first.options.land_speed,
                   f"landed / crashed threshold {first.options.land_speed:g} m/s (chosen)")
        ax[0, 0].set_title("(a) the whole descent")
        ax[0, 1].set_title("(b) the last 2000 s")
        shared_legend(fig, ax.ravel(), ncol=4)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.08, 1, 1))
        return png_bytes(fig)


def thrust_figure(runs: dict, title: str) -> bytes:
    """Thrust per axis m u_i (N) against time and the limit, per variant; the command before
    the limit dotted where it differs."""
    names = list(runs)
    ncol = min(3, len(names))
    nrow = int(np.ceil(len(names) / ncol))
    with styled() as plt:
        fig, ax = plt.subplots(nrow, ncol, figsize=(4.3 * ncol + 0.5, 3.3 * nrow + 0.7),
                               sharex=True, squeeze=False)
        for a, name in zip(ax.ravel(), names, strict=False):
            r = runs[name]
            ok = _valid(r)
            pr = r.options.probe
            m = r.m[ok, 0]
            for k in range(3):
                a.step(r.t[ok], m * r.u[ok, 0, k], where="post", color=f"C{k + 3}", lw=0.8,
                       label=f"F_{AXES[k]}")
                clipped = np.abs(r.u_cmd[ok, 0, k] - r.u[ok, 0, k]) > 0
                if clipped.any():
                    a.plot(r.t[ok][clipped], (m * r.u_cmd[ok, 0, k])[clipped], ".",
                           color=f"C{k + 3}", ms=2, label="command before the limit")
            if np.isfinite(pr.thrust_max):
                limit_line(a, pr.thrust_max, f"limit {pr.thrust_max:g} N ({pr.limit})",
                           both_signs=True)
            a.set_title(label(name))
            a.set_yscale("symlog", linthresh=0.1)
        for a in ax[-1]:
            a.set_xlabel("t [s]")
        for a in ax[:, 0]:
            a.set_ylabel("thrust [N] (symlog)")
        for a in ax.ravel()[len(names):]:
            a.set_visible(False)
        shared_legend(fig, ax.ravel()[:len(names)], ncol=5)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        return png_bytes(fig)


def fit_error_figure(rows: list[dict], path_rows: list[dict] | None, title: str) -> bytes:
    """The two-point model's relative error against the polyhedron along the descent (the
    reference), and along a flown trajectory if given; against time and against height."""
    with styled() as plt:
        fig, ax = plt.subplots(1, 2, figsize=(12.5, 4.4))
        for rr, lab, st in ((rows, "along the reference", {"color": "k"}),
                            (path_rows, "along the flown trajectory",
                             {"color": "C2", "ls": "--"})):
            if not rr:
                continue
            t = np.array([r["t"] for r in rr])
            h = np.array([r["height_m"] for r in rr])
            e = 100 * np.array([r["rel"] for r in rr])
            ax[0].plot(t, e, label=lab, **st)
            ax[1].plot(np.maximum(h, 1e-2), e, label=lab, **st)
        ax[0].set_xlabel("t [s]")
        ax[1].set_xlabel("height above the shape model [m] (log)")
        ax[1].set_xscale("log")
        for a in ax:
            a.set_ylabel("|g_2pt - g_poly| / |g_poly| [%]")
        shared_legend(fig, ax, ncol=2)
        fig.suptitle(title)
        fig.tight_layout(rect=(0, 0.08, 1, 1))
        return png_bytes(fig)


def descent_figures(runs: dict, fit_rows: list[dict] | None = None) -> list[Figure]:
    """The descent's figures for ``lgw simulate eros --scenario descent --plot`` and the report:
    runs = variant name -> DescentResult (case 0 drawn; histories needed, stride >= 1)."""
    from lgw.theory.eros.descent import fit_error_along

    first = next(iter(runs.values()))
    o = first.options
    prof = o.profile()
    what = (f"plant gravity {o.gravity!r}, controller {o.controller_gravity!r}; probe "
            f"{o.probe.mass:g} kg, {o.probe.thrust_max:g} N ({o.probe.limit}), Isp "
            f"{o.probe.isp:g} s; sampling {o.dt:g} s; navigation "
            f"{'errors on' if o.nav.on else 'perfect'}; SRP {o.env.srp:.2g} m/s^2 (unknown)")
    outcomes = "; ".join(
        f"{label(n)}: {r.outcome_names()[0]} at {r.t_outcome[0]:.1f} s"
        + (f", {r.touchdown['speed'][0]:.3f} m/s, fuel {r.fuel[0]:.2f} kg"
           if np.isfinite(r.touchdown["speed"][0]) else "") for n, r in runs.items())
    if fit_rows is None:
        fit_rows = fit_error_along(prof, np.linspace(0.0, prof.t_touchdown, 81))
    ok = _valid(first)
    ii = ok[_decimate(len(ok), 60)]
    path_rows = _fit_rows_at(first.t[ii], first.pos[ii, 0])
    return [
        Figure("eros_descent_trajectory.png",
               f"The whole descent over the shape model of Eros (body frame, km): Table 1's "
               f"start to touchdown at the site nearest Table 1's landing position ({what}). "
               f"{outcomes}.",
               trajectory_figure(runs, "Seed 002: the descent to the surface of Eros")),
        Figure("eros_descent_altitude_speed.png",
               "Height above the shape model (distance to the nearest face) and speed relative "
               "to the surface against time, flown and reference; the dashed line is the "
               f"landed / crashed threshold ({what}).",
               altitude_speed_figure(runs, "Seed 002 descent: height and speed")),
        Figure("eros_descent_thrust.png",
               f"Thrust per axis (N, symmetric log scale) against its limit; dots: the "
               f"command before the limit where the limit cut it ({what}).",
               thrust_figure(runs, "Seed 002 descent: thrust against the limit")),
        Figure("eros_descent_fit_error.png",
               "The fitted two-point model (2) against the polyhedron along the descent: "
               "relative acceleration error against time and against the height above the "
               "surface (it is the controller's model; the plant flies the polyhedron).",
               fit_error_figure(fit_rows, path_rows,
                                "Seed 002 descent: two-point gravity error")),
    ]


def _fit_rows_at(t: np.ndarray, pts: np.ndarray) -> list[dict]:
    from lgw.theory.eros.descent import fit_error, height_above

    err = fit_error(pts)
    return [{"t": float(tt), "height_m": height_above(p), "rel": float(err["rel"][i])}
            for i, (tt, p) in enumerate(zip(t, pts, strict=True))]
