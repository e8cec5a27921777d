"""Seed 001's own comparison on its Section 5 case: with and without the failure (26) and the
saturations (24), (28), ideal pointing (the thrust along the command: the paper's orbit loop
(22) with u_o as its input) against coupled pointing (the thrust along the simulated body axis,
through the attitude loop (27) and the command filter), every number checked against the run
at dt/4; and the command filter's bandwidth swept on the Section 5 case (--sweep).  Table,
JSON (--json), figures (--plot: the tracking errors of the eight runs and the bandwidth sweep).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Number
from lgw.tuning.spec import option
from lgw.tuning.system import Job, Outcome


@dataclass(frozen=True)
class Options(V.Outputs, gains=" (a tuned file also sets --cmd-wn and --thrust-max)",
              out="compare.json (the --json document) and the figures",
              plot="lunar_compare.png (tracking errors of the eight runs) and "
                   "lunar_bandwidth.png (the sweep)"):
    cmd_wn: float | None = option("--cmd-wn", Number(0, 1e3, lo_open=True, unit="rad/s"), None,
                                  "command filter natural frequency of the coupled runs, rad/s "
                                  "[default: the --gains file's, else "
                                  "lgw.sim.lunar.parameters.CMD_WN]", probe=16.0)
    thrust_max: float | None = V.thrust_max(None, "T_max of (24) in the saturated runs "
                                            "[default: the --gains file's, else the paper's]")
    dt: float | None = V.dt(None, 0.1, "RK4 step of the eight runs (each checked at dt/4) and "
                            "of the sweep (checked at dt/2) [default: lgw.sim.lunar.parameters"
                            ".DT and DT_CAMPAIGN]")
    sweep: bool = option("--sweep", None, True, "sweep the command filter's bandwidth on the "
                         "Section 5 case (coupled, at dt and dt/2)", secondary="--no-sweep")


@dataclass(frozen=True)
class CompareJob(Job):
    gains: Any
    base: Any  # lgw.sim.lunar.closed_loop.RunOptions
    sweep: bool
    sweep_dt: float

    def run(self, progress: Any) -> Outcome:
        from dataclasses import replace

        from lgw.theory.sections import Figure
        from lgw.tuning.lunar.compare import findings, run_conditions
        from lgw.tuning.lunar.figures import bandwidth_figure, compare_figure

        rows = run_conditions(self.gains, self.base, progress)
        doc: dict[str, Any] = {"options": _opts_doc(self.base),
                               "rows": [r.to_dict() for r in rows]}
        figs = [Figure("lunar_compare.png",
                       "Tracking errors of the Section 5 case under each condition, coupled "
                       f"(solid) and ideal (dashed) pointing, RK4 dt = {self.base.dt:g} s, "
                       f"command filter wn = {self.base.cmd_wn:g} rad/s.",
                       compare_figure([(r.condition, r.pointing, r.res) for r in rows],
                                      "Seed 001 Section 5: conditions and pointing"))]
        flags = [line for r in rows for line in r.convergence.flags(
            f"{r.condition}, {r.pointing}")]
        bw = None
        if self.sweep:
            from lgw.tuning.lunar.design import select_bandwidth

            progress.stage("command-filter bandwidth sweep (Section 5, coupled, dt and dt/2)")
            bw = select_bandwidth(self.gains, replace(self.base, dt=self.sweep_dt),
                                  progress=progress)
            ideal = next(r.numbers for r in rows if r.pointing == "ideal"
                         and r.condition.startswith("failure and"))
            doc["bandwidth_sweep"] = bw.to_dict()
            figs.append(Figure("lunar_bandwidth.png", _sweep_caption(bw, self.base),
                               bandwidth_figure(bw, ideal, "Seed 001 Section 5: the command "
                                                "filter's bandwidth (coupled pointing)",
                                                chosen=self.base.cmd_wn)))
        doc["findings"] = findings(rows)
        return Outcome(doc, render=lambda con: _render(con, rows, bw, doc["findings"]),
                       files={"compare.json": DOCUMENT, **{f.file: f.png for f in figs}},
                       figures=figs, flags=flags)


def _opts_doc(o: Any) -> dict[str, Any]:
    from lgw.sim.lunar.outcomes import json_safe

    return json_safe(dict(o.__dict__))


def _sweep_caption(bw: Any, base: Any) -> str:
    band = (f"robust band {bw.band[0]:g}-{bw.band[1]:g} rad/s, the rule's choice "
            f"{bw.wn:g} rad/s" if bw.band else "no robust band")
    return ("Final errors and the time the torque saturation ends against the command "
            f"filter's natural frequency, Section 5 case, coupled pointing, RK4 at dt = "
            f"{base.dt:g} s (filled) "
            f"and dt/2 (open); {band}; the vertical line is the wn flown in the comparison "
            f"({base.cmd_wn:g} rad/s); crosses at the top: runs that stopped (surface contact).")


def _render(con: Any, rows: list[Any], bw: Any, notes: list[str]) -> None:
    from lgw.tuning.tables import fmt, result_table

    table = [(r.condition, r.pointing, fmt(r.numbers["eh_final_m"]),
              fmt(r.numbers["ev_final_norm_m_s"]), fmt(r.numbers["max_abs_eh_m"]),
              fmt(r.numbers["orbit_saturated_after_failure_s"]),
              fmt(r.numbers["torque_saturated_initial_s"]),
              fmt(r.numbers["torque_saturation_end_s"]), r.numbers["outcome"],
              "yes" if r.convergence.converged else "NO") for r in rows]
    result_table(con, "seed 001 Section 5: failure and saturation, ideal and coupled pointing",
                 ("condition", "pointing", "e_h(t_f) m", "|e_v(t_f)| m/s", "max|e_h| m",
                  "sat after failure s", "torque sat from 0 s", "torque sat ends s", "outcome",
                  "dt/4 agrees"), table)
    if bw is not None:
        result_table(con, "command-filter bandwidth, Section 5, coupled"
                     + (f": robust band {fmt(bw.band[0])}-{fmt(bw.band[1])} rad/s, choice "
                        f"{fmt(bw.wn)}" if bw.band else ": no robust band"),
                     bw.COLUMNS, bw.rows(fmt))
    for n in notes:
        con.print(n, markup=False, highlight=False)


def plan(opts: Options, system: Any) -> CompareJob:
    from dataclasses import replace

    from lgw.sim.lunar.closed_loop import RunOptions
    from lgw.tuning.lunar.cmd_simulate import check_filter_step
    from lgw.tuning.lunar.gainset import resolve, run_defaults

    g = resolve(opts.gains)
    changes = run_defaults(g)
    changes.update({k: v for k, v in (("cmd_wn", opts.cmd_wn), ("thrust_max", opts.thrust_max),
                                      ("dt", opts.dt)) if v is not None})
    base = replace(RunOptions(), **changes)
    check_filter_step(base, opts.cmd_wn is not None)
    from lgw.sim.lunar import parameters as SP

    return CompareJob(g, base, opts.sweep, SP.DT_CAMPAIGN if opts.dt is None else opts.dt)
