"""Fly seed 002's closed loop (sampled-data, zero-order hold).

``--scenario tracking`` (default): the six controllers on the paper's 15 s scenario, a Monte
Carlo campaign over the initial-offset envelope, or the states of a CSV file; print the Table 2
analogue per variant: reaching and tracking times, IAE (sum over the samples and axes of
|e_i|), control peak, effort and chattering (total variation of u).  Campaign rows give mean /
max over the cases that flew to the horizon or tracked; cases that touched the body or became
non-finite are counted apart, never in a statistic.

``--scenario descent``: the whole descent from Table 1's start to touchdown on the shape model
(lgw.sim.eros.descent): polyhedral gravity in the plant, the two-point model in the controller,
a thrust-limited probe burning propellant, SRP (and optionally the paper's sinusoid) unknown to
the controller, optional navigation errors; per variant the outcome (landed / crashed with the
impact speed / ...), touchdown time, speed and its normal component, the contact point, the
fuel, the tracking error and the thrust saturation, each with its convergence check (the same
cases re-flown with the RK4 step halved).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Number, choice
from lgw.tuning.spec import option
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
SCENARIOS = ("tracking", "descent")
DESCENT_COLUMNS = (("t_outcome", "t s"), ("speed", "speed m/s"), ("v_normal", "v_n m/s"),
                   ("fuel", "fuel kg"), ("e_max", "|e| max m"), ("sat", "sat %"))
DESCENT_COUNTED = ("landed", "crashed")  # outcomes with a touchdown
MAX_SAMPLES = 10**8  # per case: t_max/dt beyond this would run for hours (a mistyped --dt)


def case_bytes(t_max: float, dt: float) -> float:
    """Memory one case of a tracking run takes (bytes, an estimate): the histories of
    ``lgw.sim.eros.batch.Result`` (e, ed, s, u: 12 float64 per sample) and as much again for
    the metrics computed from them."""
    return 2 * 12 * 8 * (t_max / dt + 2)


@dataclass(frozen=True)
class Options(V.Outputs,
              gains="[default: the paper scenario's defaults; the descent's own for "
                    "--scenario descent]",
              out="simulate.json (the --json document)",
              plot="the variants' tracking errors per axis, control and chattering (case 0); "
                   "a campaign: also the reaching and tracked times of every case; the "
                   "descent: trajectory over the shape model, altitude and speed, thrust "
                   "against its limit"):
    scenario: str = option("--scenario", choice(SCENARIOS), "tracking",
                           "tracking: the paper's 15 s run; descent: the whole descent from "
                           "Table 1's start to touchdown on the shape model")
    law: str = option("--law", choice((*VARIANT_NAMES, "all")), "all",
                      "controller variant, or all six")
    cases: int | None = V.cases(None, "Monte Carlo cases over the initial-offset envelope "
                                "[default: the paper's scenario / the descent from Table 1's "
                                "start]")
    initial_states: Path | None = V.initial_states("ex, ey, ez, vx, vy, vz [, phase] (m, m/s, "
                                                   "rad), e.g. a witness of lgw verify eros")
    seed: int = V.seed(1, "seed of the Monte Carlo offsets and disturbance phases")
    t_max: float | None = V.t_max(None, "simulated time [default: 15 s; the descent: to "
                                  "touchdown + 600 s]", hi=1e5)
    dt: float | None = V.dt(None, 10.0, "sampling time of the controller (zero-order hold) "
                            "[default: 0.01 s; the descent: 1 s]")
    gravity: str | None = option("--gravity", choice(("two-point", "polyhedron",
                                                      "polyhedron-exact", "none")), None,
                                 "plant gravity [default: two-point; the descent: polyhedron]; "
                                 "tracking's polyhedron is slow (single cases); the descent's "
                                 "is re-evaluated every 10 m, polyhedron-exact at every "
                                 "evaluation (descent only)", probe="none")
    disturbance: str | None = option("--disturbance", choice(("known", "unknown", "none")),
                                     None, "the paper's sinusoid D: known (in u_eq, (14)), "
                                     "unknown (bounded, not in u_eq) or none [default: known; "
                                     "the descent: none (its SRP is always there, unknown)]",
                                     probe="unknown")
    cubic: str = option("--cubic", choice(("exact", "printed")), "exact",
                        "reference cubic (8)-(10): the exact coefficients or the printed ones")
    thrust_max: float | None = V.thrust_max(None, "descent only, per axis or on the norm "
                                            "(--limit) [default: 22 N]")
    limit: str = option("--limit", choice(("axis", "norm")), "axis",
                        "descent only: the thrust limit per axis or on the norm")
    isp: float | None = V.isp(None, "descent only: specific impulse, s [default: 225 s, "
                                    "hydrazine]")
    srp: float | None = option("--srp", Number(0, 1.0, unit="m/s^2"), None,
                               "descent only: solar radiation pressure, m/s^2 [default: 7.3e-8]")
    nav: bool = option("--nav", None, False, "descent only: navigation errors (Gauss-Markov, "
                       "1 m / 5 mm/s, 100 s) in what the controller sees", secondary="--no-nav")

    def check(self) -> None:
        super().check()
        from lgw.theory.errors import ParameterError

        self.refuse_unless(self.initial_states is None, "cases",
                           "does not apply with --initial-states (the file gives the cases)")
        self.refuse_unless(self.cases is not None or self.nav, "seed", "only applies with "
                           "--cases or --nav (the scenario and a states file draw nothing)")
        descent = self.scenario == "descent"
        for name in ("thrust_max", "limit", "isp", "srp", "nav"):
            self.refuse_unless(descent, name, "only applies with --scenario descent")
        if not descent and self.gravity == "polyhedron-exact":
            raise ParameterError("--gravity", self.gravity, "polyhedron-exact is the descent's "
                                 "(--scenario descent); tracking takes two-point, polyhedron "
                                 "or none")
        if descent and self.disturbance == "known":
            raise ParameterError("--disturbance", self.disturbance, "the descent's controller "
                                 "does not know D: unknown or none")
        if self.dt is not None and self.t_max is not None and self.dt > self.t_max:
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


def plan(opts: Options, system: Any) -> Job:
    if opts.scenario == "descent":
        return plan_descent(opts)
    from lgw.sim.eros import laws as SL
    from lgw.sim.eros.batch import SimOptions
    from lgw.sim.eros.campaign import offsets
    from lgw.theory.eros import parameters as P
    from lgw.tuning.eros.gainset import resolve

    g = resolve(opts.gains)
    variants = SL.VARIANTS if opts.law == "all" else (SL.parse_variant(opts.law),)
    t_max = P.T_SCENARIO if opts.t_max is None else opts.t_max
    dt = P.DT_SAMPLE if opts.dt is None else opts.dt
    gravity = opts.gravity or "two-point"
    dist = opts.disturbance or "known"
    if dt > t_max:
        from lgw.theory.errors import ParameterError

        raise ParameterError("--dt", dt, f"must be <= --t-max = {t_max} s (at least one "
                             "sample)")
    if t_max / dt > MAX_SAMPLES:
        from lgw.theory.errors import ParameterError

        raise ParameterError("--dt", dt, f"gives t_max/dt = {t_max / dt:.3g} samples per case; "
                             f"at most {MAX_SAMPLES:.0e} (raise --dt or lower --t-max)")
    from lgw.tuning.io import check_memory
    base = SimOptions(t_final=t_max, dt=dt, gravity=gravity, disturbance=dist,
                      reference=opts.cubic)
    if opts.initial_states is not None:
        from lgw.tuning.eros.options import read_offsets_csv

        states, source = read_offsets_csv(opts.initial_states), str(opts.initial_states)
        check_memory("--initial-states", len(states[0]), case_bytes(t_max, dt))
    elif opts.cases is None:
        check_memory("--t-max", 1, case_bytes(t_max, dt), "the case's histories at dt = "
                     f"{dt:g} s", value=t_max)
        states = (P.SCENARIO_OFFSET[None], P.SCENARIO_VOFFSET[None], np.zeros(1))
        source = "scenario"
    else:
        check_memory("--cases", opts.cases, case_bytes(t_max, dt))
        states, source = offsets(opts.cases, opts.seed), "monte-carlo"
    settings = {"scenario": "tracking", "t_max": t_max, "dt": dt, "gravity": gravity,
                "disturbance": dist, "cubic": opts.cubic,
                "cases": len(states[0]), "source": source,
                "seed": opts.seed if opts.cases is not None else None}
    return SimulateJob(g, tuple(variants), states, base, settings,
                       opts.seed if opts.plot is not None else None)


# --- the whole descent -----------------------------------------------------------------------

@dataclass(frozen=True)
class DescentJob(Job):
    gains: Any
    variants: tuple[tuple[str, str], ...]
    inputs: dict[str, Any]  # e0, ed0, srp, case_phase, nav_ids (per case)
    base: Any  # lgw.sim.eros.descent.DescentOptions
    settings: dict[str, Any]
    figures: bool

    def run(self, progress: Any) -> Outcome:
        from dataclasses import replace

        from lgw.sim.eros import laws as SL
        from lgw.sim.eros.descent import OUTCOMES, convergence, simulate_descent
        from lgw.tuning.stats import finite_stats, outcome_counts

        inp = self.inputs
        n = len(inp["e0"])
        kw = {k: inp[k] for k in ("srp", "case_phase", "nav_ids")}
        rows, flags, runs = [], [], {}
        for lw, sw in self.variants:
            name = SL.variant_name(lw, sw)
            progress.stage(f"{name}: the descent, {n} case{'s' if n > 1 else ''}")
            opts = replace(self.base, law=lw, switch=sw)
            res = simulate_descent(inp["e0"], inp["ed0"], self.gains, opts, **kw)
            progress.stage(f"{name}: convergence (RK4 step halved)")
            conv = convergence(res, inp["e0"], inp["ed0"], **kw)
            if self.figures:  # case 0 again, with its histories
                one = {k: v[:1] for k, v in kw.items()}
                runs[name] = simulate_descent(inp["e0"][:1], inp["ed0"][:1], self.gains,
                                              replace(opts, stride=1), **one)
            values = descent_values(res)
            touched = np.isin(res.outcome, [OUTCOMES.index(o) for o in DESCENT_COUNTED])
            row: dict[str, Any] = {"variant": name, "cases": n,
                                   "outcomes": outcome_counts(res.outcome, OUTCOMES),
                                   "converged": int(conv["converged"].sum()),
                                   "convergence_check": conv["check"],
                                   "max_relative_change": {
                                       k: float(np.max(v)) for k, v in
                                       conv["relative_change"].items()}}
            for k, _ in DESCENT_COLUMNS:
                row[k] = finite_stats(values[k], touched if k in ("speed", "v_normal")
                                      else None)
            if n <= CASE_RECORDS:
                row["case_records"] = [dict(res.case(i), converged=bool(conv["converged"][i]))
                                       for i in range(n)]
            rows.append(row)
            if not conv["converged"].all():
                flags.append(f"{name}: {int((~conv['converged']).sum())} case(s) not converged "
                             f"to {conv['tolerance']:.0%} under {conv['check']} (flagged in "
                             "the JSON)")
        figures = []
        if self.figures:
            progress.stage("figures")
            from lgw.tuning.eros.figures import descent_figures

            figures = descent_figures(runs)
        doc = {"settings": self.settings, "rows": rows,
               "notes": {"outcomes": DESCENT_NOTE, "statistics": "speed and v_normal over the "
                         "cases that touched down (landed or crashed); the others over every "
                         "case with a finite value", "convergence": "each case re-flown with "
                         "the RK4 step halved: outcome, time, touchdown speed and fuel within "
                         "1 %"}}
        return Outcome(doc, render=lambda con: _render_descent(con, rows, self.settings),
                       files={"simulate.json": DOCUMENT}, figures=figures, flags=flags)


CASE_RECORDS = 20  # per-case records in the JSON up to this many cases
DESCENT_NOTE = ("one per case, the first that happened: landed (contact with the shape model "
                "at <= land_speed relative to the surface), crashed (faster; speed = impact "
                "speed), propellant_exhausted, nonfinite, step_limit, horizon; t_outcome in s")


def descent_values(res: Any) -> dict[str, np.ndarray]:
    """Per case: the outcome time, touchdown speed and its normal component, fuel, the largest
    true position error and the fraction of samples at the thrust limit (%)."""
    s = res.summary
    with np.errstate(invalid="ignore", divide="ignore"):
        sat = 100.0 * s["saturated"] / s["samples"]
    return {"t_outcome": res.t_outcome, "speed": res.touchdown["speed"],
            "v_normal": res.touchdown["v_normal"], "fuel": res.fuel, "e_max": s["e_max"],
            "sat": sat}


def _render_descent(con: Any, rows: list[dict[str, Any]], st: dict[str, Any]) -> None:
    from lgw.tuning.tables import fmt, result_table

    one = st["cases"] == 1
    title = ("seed 002, the whole descent" + (" (one case)" if one else
             f", {st['cases']} cases (mean/max)") + f": plant {st['gravity']}, thrust "
             f"{st['thrust_max']:g} N ({st['limit']}), nav {'on' if st['nav'] else 'off'}")
    table = []
    spec = {"t_outcome": ".1f"}
    for r in rows:
        cells = [fmt(r[k]["mean"], spec.get(k, ".4g")) if one else
                 f"{fmt(r[k]['mean'], spec.get(k, '.4g'))}/{fmt(r[k]['max'], spec.get(k, '.4g'))}"
                 for k, _ in DESCENT_COLUMNS]
        out = (r["case_records"][0]["outcome"] if one and "case_records" in r else
               ", ".join(f"{k} {v}" for k, v in r["outcomes"].items() if v))
        table.append((r["variant"], out, *cells, f"{r['converged']}/{r['cases']}"))
    result_table(con, title, ("variant", "outcome", *(lb for _, lb in DESCENT_COLUMNS),
                              "converged"), table)
    if one:
        for r in rows:
            c = r["case_records"][0]
            td = c["touchdown"]
            if np.isfinite(td["speed"]):
                pt = ", ".join(f"{x:.3f}" for x in td["point_m"])
                con.print(f"{r['variant']}: contact at lat {td['lat_deg']:.4f} deg, lon "
                          f"{td['lon_deg']:.4f} deg, r = ({pt}) m (face {int(td['face'])}, "
                          f"{td['site_distance_m']:.3f} m from the site), v_t "
                          f"{td['v_tangential']:.4f} m/s", markup=False)


def plan_descent(opts: Options) -> DescentJob:
    from lgw.sim.eros import laws as SL
    from lgw.sim.eros.descent import (
        DescentOptions,
        Environment,
        Navigation,
        Probe,
        descent_gains,
        dispersions,
    )
    from lgw.theory.eros import parameters as P
    from lgw.theory.eros.gains import load_gains

    g = descent_gains() if opts.gains is None else load_gains(opts.gains)
    variants = SL.VARIANTS if opts.law == "all" else (SL.parse_variant(opts.law),)
    probe = Probe(thrust_max=P.THRUST_MAX if opts.thrust_max is None else opts.thrust_max,
                  limit=opts.limit, isp=P.ISP if opts.isp is None else opts.isp)
    dist = opts.disturbance or "none"
    env = Environment(srp=P.SRP_ACCEL if opts.srp is None else opts.srp,
                      amp=P.DIST_AMP if dist == "unknown" else 0.0)
    nav = Navigation.typical(opts.seed) if opts.nav else Navigation()
    base = DescentOptions(dt=P.DESCENT_DT if opts.dt is None else opts.dt,
                          gravity=opts.gravity or "polyhedron", probe=probe, env=env, nav=nav,
                          cubic=opts.cubic, t_max=opts.t_max, stride=0)
    if opts.initial_states is not None:
        from lgw.tuning.eros.options import read_offsets_csv

        e0, ed0, ph = read_offsets_csv(opts.initial_states)
        n = len(e0)
        inputs = {"e0": e0, "ed0": ed0, "case_phase": ph, "srp": np.full(n, env.srp),
                  "nav_ids": np.arange(n, dtype=np.int64)}
        source = str(opts.initial_states)
    elif opts.cases is None:
        inputs = {"e0": np.zeros((1, 3)), "ed0": np.zeros((1, 3)), "case_phase": np.zeros(1),
                  "srp": np.array([env.srp]), "nav_ids": np.zeros(1, np.int64)}
        source = "Table 1's start"
    else:
        inputs = dispersions(opts.cases, opts.seed)
        if opts.srp is not None:
            inputs["srp"] = np.full(opts.cases, opts.srp)
        source = "monte-carlo"
    settings = {"scenario": "descent", "dt": base.dt, "gravity": base.gravity,
                "controller_gravity": base.controller_gravity, "disturbance": dist,
                "srp": env.srp, "thrust_max": probe.thrust_max, "limit": probe.limit,
                "isp": probe.isp, "mass": probe.mass, "propellant": probe.propellant,
                "nav": opts.nav, "cubic": opts.cubic, "t_max": base.t_end,
                "touchdown_reference_s": base.profile().t_touchdown,
                "land_speed": base.land_speed, "cases": len(inputs["e0"]), "source": source,
                "seed": opts.seed if (opts.cases is not None or opts.nav) else None}
    return DescentJob(g, tuple(variants), inputs, base, settings, opts.plot is not None)
