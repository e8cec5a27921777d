"""Fly seed 002's closed loop (sampled-data, zero-order hold): the six controllers on the
paper's 15 s scenario, a Monte Carlo campaign over the initial-offset envelope, or the states
of a CSV file; print the Table 2 analogue per variant: reaching and tracking times, IAE (sum
over the samples and axes of |e_i|), control peak, effort and chattering (total variation of
u).  Campaign rows give mean / max over the cases that flew to the horizon or tracked; cases
that touched the body or became non-finite are counted apart, never in a statistic.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import choice
from lgw.tuning.spec import Options, option
from lgw.tuning.system import Job, Outcome

VARIANT_NAMES = ("pdsmc-sign", "pdsmc-tanh", "ftsmc-sign", "ftsmc-tanh", "fuzzy-sign",
                 "fuzzy-tanh")  # lgw.sim.eros.laws.VARIANTS by name (tests check they agree)
OUTCOME_NOTE = ("one per case, the first that happened: crashed (a sample inside the "
                "shape model), nonfinite (control or state NaN/inf), tracked (|e_i| <= 1 cm on "
                "every axis to the horizon), horizon (none of these by the horizon); "
                "t_outcome in s")
COLUMNS = (("t_reach_max", "reach s"), ("t_track_all", "tracked s"), ("iae", "IAE m"),
           ("u_peak", "peak m/s^2"), ("effort", "effort m/s"), ("chatter", "TV(u) m/s^2"))
COUNTED = ("tracked", "horizon")  # outcomes whose cases enter the statistics


@dataclass(frozen=True)
class Options(Options):
    gains: Path | None = V.gains()
    law: str = option("--law", choice((*VARIANT_NAMES, "all")), "all",
                      "controller variant, or all six")
    cases: int | None = V.cases(None, "Monte Carlo cases over the initial-offset envelope "
                                "[default: the paper's scenario]")
    initial_states: Path | None = V.initial_states("ex, ey, ez, vx, vy, vz [, phase] (m, m/s, "
                                                   "rad), e.g. a witness of lgw verify eros")
    seed: int = V.seed(1, "seed of the Monte Carlo offsets and disturbance phases")
    t_max: float = V.t_max(15.0, "simulated time", hi=1e5)
    dt: float = V.dt(0.01, 10.0, "sampling time of the controller (zero-order hold)")
    gravity: str = option("--gravity", choice(("two-point", "polyhedron", "none")),
                          "two-point", "plant gravity: two-point, polyhedron (slow: single "
                          "cases) or none")
    disturbance: str = option("--disturbance", choice(("known", "unknown", "none")), "known",
                              "known (D in u_eq, (14)), unknown (bounded, not in u_eq) or none")
    cubic: str = option("--cubic", choice(("exact", "printed")), "exact",
                        "reference cubic (8)-(10): the exact coefficients or the printed ones")
    json: bool = V.json_flag()
    out: Path | None = V.out_dir("simulate.json (the --json document)")
    plot: Path | None = V.plot_dir("the variants' tracking errors per axis, control and "
                                   "chattering (case 0); a campaign: also the reaching and "
                                   "tracked times of every case")

    def check(self) -> None:
        super().check()
        self.refuse_unless(self.initial_states is None, "cases",
                           "does not apply with --initial-states (the file gives the cases)")
        self.refuse_unless(self.cases is not None, "seed", "only applies with --cases (the "
                           "scenario and a states file draw nothing)")
        if self.dt > self.t_max:
            from lgw.theory.errors import ParameterError

            raise ParameterError("--dt", self.dt, f"must be <= --t-max = {self.t_max} s (at "
                                 "least one sample)")


def inputs(opts: Options) -> list[Path]:
    return [p for p in (opts.initial_states,) if p is not None]


@dataclass(frozen=True)
class SimulateJob(Job):
    gains: Any
    variants: tuple[tuple[str, str], ...]
    states: tuple[np.ndarray, np.ndarray, np.ndarray]
    base: Any  # lgw.sim.eros.batch.SimOptions
    settings: dict[str, Any]
    figures_seed: int | None  # None: no figures

    def run(self, progress: Any) -> Outcome:
        from dataclasses import replace

        from lgw.sim.eros import laws as SL
        from lgw.sim.eros.batch import OUTCOMES, metrics, simulate
        from lgw.sim.eros.campaign import summarize
        from lgw.tuning.stats import finite_stats, outcome_counts

        e0, ed0, ph = self.states
        rows = []
        convs: list[tuple[str, Any]] = []
        for lw, sw in self.variants:
            name = SL.variant_name(lw, sw)
            progress.stage(f"{name}: {len(e0)} case{'s' if len(e0) > 1 else ''}")
            res = simulate(e0, ed0, self.gains, replace(self.base, law=lw, switch=sw), ph)
            m = metrics(res)
            s = summarize(m)
            counts = outcome_counts(s["outcome"], OUTCOMES)
            counted = np.isin(s["outcome"], [OUTCOMES.index(o) for o in COUNTED])
            row: dict[str, Any] = {"variant": name, "cases": len(e0), "outcomes": counts,
                                   "nonfinite": counts["nonfinite"]}
            for k, _ in COLUMNS:
                row[k] = finite_stats(s[k], counted)
            conv = convergence(e0, ed0, ph, self.gains, replace(self.base, law=lw, switch=sw),
                               s)
            row["convergence"] = conv.to_dict()
            convs.append((name, conv))
            if len(e0) == 1:
                row.update(outcome=OUTCOMES[int(s["outcome"][0])],
                           t_outcome=float(s["t_outcome"][0]),
                           t_reach_axes=m["t_reach"][0].tolist(),
                           t_track_axes=m["t_track"][0].tolist(),
                           e_final=m["e_final"][0].tolist(), ed_final=m["ed_final"][0].tolist())
            rows.append(row)
        figures = []
        if self.figures_seed is not None:
            progress.stage("figures")
            from lgw.tuning.eros.figures import run_figures_for

            figures = run_figures_for(self.gains, self.base,
                                      tuple(SL.variant_name(*v) for v in self.variants),
                                      e0, ed0, ph, self.figures_seed)
        doc = {"settings": self.settings, "rows": rows,
               "notes": {"statistics": "over the cases whose outcome is tracked or horizon; "
                         "the others are counted in outcomes", "null": "never happened "
                         "within the horizon (e.g. never tracked)", "outcomes": OUTCOME_NOTE}}
        def render(con: Any) -> None:
            _render(con, rows, self.settings)
            for name, conv in convs:
                for line in conv.notes():
                    con.print(f"{name}: {line}", markup=False)

        return Outcome(doc, render=render, files={"simulate.json": DOCUMENT}, figures=figures,
                       flags=[f"{r['variant']}: {r['nonfinite']} case(s) became non-finite "
                              "(counted apart)" for r in rows if r["nonfinite"]]
                       + [f for name, conv in convs for f in conv.flags(f"simulate eros {name}")])


# per-case tolerances of the table's numbers (lgw.sim.convergence: 1 % or the resolution)
ATOL = {"t_reach_max": 1e-3, "t_track_all": 1e-3, "iae": 1e-6, "u_peak": 1e-6, "effort": 1e-6,
        "chatter": 1e-6}


def convergence(e0: np.ndarray, ed0: np.ndarray, ph: np.ndarray, gains: Any, opts: Any,
                summary: dict[str, np.ndarray]) -> Any:
    """The convergence record of one variant's run (lgw.sim.convergence): its cases (all, or
    an even spread of a campaign) flown again with the RK4 step halved (twice the steps per
    controller sample: the sample time is the controller's, not the integrator's), every
    number of the table compared per case."""
    from dataclasses import replace

    from lgw.sim.convergence import Tol, check_indices, compare_cases
    from lgw.sim.eros.batch import OUTCOMES, metrics, simulate
    from lgw.sim.eros.campaign import summarize

    idx = check_indices(len(e0))
    fine = replace(opts, n_sub=2 * opts.n_sub)
    s2 = summarize(metrics(simulate(e0[idx], ed0[idx], gains, fine, ph[idx])))

    def recs(s: dict[str, np.ndarray], rows: Any) -> list[dict[str, Any]]:
        return [{"outcome": OUTCOMES[int(s["outcome"][j])],
                 **{k: float(s[k][j]) for k, _ in COLUMNS}} for j in rows]

    step = opts.dt / opts.n_sub
    return compare_cases(recs(summary, idx), recs(s2, range(len(idx))),
                         {k: Tol(atol=ATOL[k]) for k, _ in COLUMNS}, how="step halving",
                         base_label=f"RK4 step {step:g} s ({opts.n_sub} per sample)",
                         check_label=f"RK4 step {step / 2:g} s", cases=idx.tolist(),
                         total=len(e0))


def _render(con: Any, rows: list[dict[str, Any]], st: dict[str, Any]) -> None:
    from lgw.tuning.tables import fmt, result_table

    one = st["cases"] == 1
    title = ("seed 002 scenario" if st["source"] == "scenario" else
             f"seed 002, {st['cases']} cases (mean/max over tracked and horizon cases)")
    table = []
    for r in rows:
        cells = [fmt(r[k]["mean"]) if one else f"{fmt(r[k]['mean'])}/{fmt(r[k]['max'])}"
                 for k, _ in COLUMNS]
        table.append((r["variant"], *cells))
    result_table(con, title, ("variant", *(label for _, label in COLUMNS)), table)
    for r in rows:
        con.print(f"{r['variant']} outcomes: " + ", ".join(f"{k} {v}" for k, v in
                                                          r["outcomes"].items()), markup=False)


def plan(opts: Options, system: Any) -> SimulateJob:
    from lgw.sim.eros import laws as SL
    from lgw.sim.eros.batch import SimOptions
    from lgw.sim.eros.campaign import offsets
    from lgw.theory.eros import parameters as P
    from lgw.tuning.eros.gainset import resolve

    g = resolve(opts.gains)
    variants = SL.VARIANTS if opts.law == "all" else (SL.parse_variant(opts.law),)
    base = SimOptions(t_final=opts.t_max, dt=opts.dt, gravity=opts.gravity,
                      disturbance=opts.disturbance, reference=opts.cubic)
    if opts.initial_states is not None:
        from lgw.tuning.eros.options import read_offsets_csv

        states, source = read_offsets_csv(opts.initial_states), str(opts.initial_states)
    elif opts.cases is None:
        states = (P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], np.zeros(1))
        source = "scenario"
    else:
        states, source = offsets(opts.cases, opts.seed), "monte-carlo"
    settings = {"t_max": opts.t_max, "dt": opts.dt, "gravity": opts.gravity,
                "disturbance": opts.disturbance, "cubic": opts.cubic,
                "cases": len(states[0]), "source": source,
                "seed": opts.seed if opts.cases is not None else None}
    return SimulateJob(g, tuple(variants), states, base, settings,
                       opts.seed if opts.plot is not None else None)
