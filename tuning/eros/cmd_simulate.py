"""``lgw simulate eros``: the six controllers on the paper's 15 s scenario, or a campaign."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.tuning.eros.options import resolve_gains
from lgw.tuning.io import json_document
from lgw.tuning.options import SEED, Integer, Number, choice, gains_option
from rich.console import Console
from rich.table import Table

OUTCOME_NOTE = ("one per case, the first that happened: surface_contact (a sample inside the "
                "shape model), nonfinite (control or state NaN/inf), tracked (|e_i| <= 1 cm on "
                "every axis to t_final), horizon (none of these by t_final); t_outcome in s")
COLUMNS = (("t_reach_max", "reach s"), ("t_track_all", "tracked s"), ("iae", "IAE m"),
           ("u_peak", "peak m/s^2"), ("effort", "effort m/s"), ("chatter", "TV(u) m/s^2"))


@click.command("eros")
@gains_option
@click.option("--law", type=choice(("pdsmc-sign", "pdsmc-tanh", "ftsmc-sign", "ftsmc-tanh",
                                    "fuzzy-sign", "fuzzy-tanh", "all")),
              default="all", show_default=True,
              help="pdsmc-sign, pdsmc-tanh, ftsmc-sign, ftsmc-tanh, fuzzy-sign, fuzzy-tanh or all")
@click.option("--cases", type=Integer(0, 10**6, "cases"), default=0, show_default=True,
              help="Monte Carlo cases over the initial-offset envelope (0: the paper's scenario)")
@click.option("--initial-states", "initial_states", default=None,
              type=click.Path(dir_okay=False, path_type=Path),
              help="CSV of initial errors, header ex, ey, ez, vx, vy, vz [, phase] (m, m/s, "
                   "rad; UTF-8), e.g. a witness of lgw verify eros [default: none]")
@click.option("--seed", type=SEED, default=1, show_default=True,
              help="random seed (numpy SeedSequence); integer in [0, 2^64 - 1]")
@click.option("--t-final", type=Number(0, 1e5, lo_open=True, unit="s"), default=15.0,
              show_default=True, help="simulated time (s)")
@click.option("--dt", type=Number(0, 10, lo_open=True, unit="s"), default=0.01,
              show_default=True, help="sampling time of the controller (s)")
@click.option("--gravity", type=choice(("two-point", "polyhedron", "none")),
              default="two-point", show_default=True,
              help="plant gravity: two-point, polyhedron (slow: single cases) or none")
@click.option("--disturbance", type=choice(("known", "unknown", "none")), default="known",
              show_default=True,
              help="known (D in u_eq, (14)), unknown (bounded, not in u_eq) or none")
@click.option("--reference", type=choice(("exact", "printed")), default="exact",
              show_default=True,
              help="cubic coefficients: exact or printed")
@click.option("--json", "as_json", is_flag=True, help="print the rows as JSON")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              default=None, help="write figures (PNG) to DIR: the variants' tracking errors "
                                 "per axis, control and chattering (case 0); a campaign: also "
                                 "the reaching and tracked times of every case")
def command(gains_path: Path | None, law: str, cases: int, initial_states: Path | None,
            seed: int, t_final: float, dt: float,
            gravity: str, disturbance: str, reference: str, as_json: bool,
            plot_dir: Path | None) -> None:
    """Fly seed 002's closed loop (sampled-data, zero-order hold) and print the Table 2 analogue:
    per variant the reaching and tracking times, IAE (sum over the samples and axes of |e_i|),
    control peak, effort and chattering (total variation of u); campaign rows give mean / max."""
    from dataclasses import replace

    import numpy as np
    from lgw.sim.eros import laws as SL
    from lgw.sim.eros.batch import OUTCOMES, SimOptions, metrics, outcome_counts, simulate
    from lgw.sim.eros.campaign import offsets, summarize
    from lgw.theory.eros import parameters as P
    from lgw.theory.errors import ParameterError
    from lgw.tuning.io import check_out_dir

    check_out_dir(plot_dir, "--plot")  # before any work
    g = resolve_gains(gains_path)
    variants = SL.VARIANTS if law == "all" else (SL.parse_variant(law),)
    if cases < 0:
        raise ParameterError("--cases", cases, "must be >= 0")
    base = SimOptions(t_final=t_final, dt=dt, gravity=gravity, disturbance=disturbance,
                      reference=reference)
    if initial_states is not None:
        if cases:
            raise ParameterError("--cases", cases, "does not apply with --initial-states")
        from lgw.tuning.eros.options import read_offsets_csv

        e0, ed0, ph = read_offsets_csv(initial_states)
    elif cases == 0:
        e0, ed0, ph = P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], np.zeros(1)
    else:
        e0, ed0, ph = offsets(cases, seed)
    rows = []
    for lw, sw in variants:
        res = simulate(e0, ed0, g, replace(base, law=lw, switch=sw), ph)
        m = metrics(res)
        s = summarize(m)
        row = {"variant": SL.variant_name(lw, sw), "cases": len(e0),
               "nonfinite": int(s["nonfinite"].sum()), "outcomes": outcome_counts(s["outcome"])}
        for k, _ in COLUMNS:
            row[k] = float(np.mean(s[k]))
            row[k + "_max"] = float(np.max(s[k]))
        if len(e0) == 1:
            row["outcome"] = OUTCOMES[int(s["outcome"][0])]
            row["t_outcome"] = float(s["t_outcome"][0])
            row["t_reach_axes"] = m["t_reach"][0].tolist()
            row["t_track_axes"] = m["t_track"][0].tolist()
            row["e_final"] = m["e_final"][0].tolist()
            row["ed_final"] = m["ed_final"][0].tolist()
        rows.append(row)
    if plot_dir is not None:
        from lgw.tuning.eros.figures import plot_run

        plot_run(g, base, tuple(SL.variant_name(*v) for v in variants), e0, ed0, ph, plot_dir,
                 seed, quiet=as_json)
    if as_json:
        # strict JSON (json_document): a time that never happened (inf / NaN, e.g. never
        # tracked) or an overflowed measure is null, with "nonfinite_replaced": true
        click.echo(json_document({"options": {"t_final": t_final, "dt": dt, "gravity": gravity,
                                              "disturbance": disturbance,
                                              "reference": reference, "cases": cases,
                                              "seed": seed},
                                  "rows": rows,
                                  "notes": {"null": "never happened within t_final (e.g. never "
                                                    "tracked)",
                                            "outcomes": OUTCOME_NOTE}}, indent=2))
        return
    title = ("seed 002 scenario" if cases == 0 and initial_states is None else
             f"seed 002, {len(e0)} cases (mean/max)")
    t = Table(title=title)
    t.add_column("variant", no_wrap=True)
    for _, label in COLUMNS:
        t.add_column(label, justify="right")
    for r in rows:
        cells = [f"{r[k]:.4g}" if len(e0) == 1 else f"{r[k]:.4g}/{r[k + '_max']:.4g}"
                 for k, _ in COLUMNS]
        t.add_row(r["variant"], *cells)
    Console().print(t)
    for r in rows:
        click.echo(f"{r['variant']} outcomes: " + ", ".join(f"{k} {v}" for k, v in
                                                            r["outcomes"].items()))
    if any(r["nonfinite"] for r in rows):
        click.echo("warning: some cases became non-finite (flagged and frozen)")
