"""Design alpha, beta, p/q and k of seed 002's FTSMC (19) (sign switching) so that the proven
reaching + sliding time meets --ts over the envelope of initial offsets and the control stays
under the actuator limit, and write them with a [certificate] (``lgw.tuning.eros.design``).

The actuator limit is a per-axis thrust in N (``--thrust-max``); the law commands an
acceleration, so the limit on u is thrust-max / m with m the probe mass of seed 002 Table 1.
Exit 0 feasible (file written); 3 infeasible (the reason on stderr, nothing written).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lgw.theory.errors import ParameterError
from lgw.tuning import vocabulary as V
from lgw.tuning.options import Integer, Number
from lgw.tuning.spec import Options, option
from lgw.tuning.system import EXIT_INFEASIBLE, Job, Outcome


@dataclass(frozen=True)
class Options(Options):
    ts: float | None = option("--ts", Number(0, 1e5, lo_open=True, unit="s"), None,
                              "time target: reaching + sliding, s [required]", probe=10.0)
    thrust_max: float | None = V.thrust_max(None, "per axis; the control limit is "
                                            "thrust-max / probe mass [required]")
    e_max: float = option("--e-max", Number(0, 1e5, lo_open=True, unit="m"), 10.0,
                          "envelope |e_i(0)|, m")
    v_max: float = option("--v-max", Number(0, 1e3, lo_open=True, unit="m/s"), 0.5,
                          "envelope |e_i'(0)|, m/s")
    dbar: float = option("--dbar", Number(0, 1e3, unit="m/s^2"), 0.0,
                         "unknown disturbance bound, m/s^2; 0: D known in u_eq (14)",
                         probe=0.1)
    fresh_cases: int = option("--fresh-cases", Integer(1, 10**6, "cases"), 200,
                              "cases of the fresh acceptance campaign flown with the tuned "
                              "gains", probe=50)
    seed: int = V.seed(7, "seed of the design, acceptance and validation campaigns")
    json: bool = V.json_flag()
    out: Path | None = V.out_file("the gains TOML with its [certificate] table", required=True)

    def check(self) -> None:
        super().check()
        for name, flag in (("ts", "--ts"), ("thrust_max", "--thrust-max"), ("out", "--out")):
            if getattr(self, name) is None:
                raise ParameterError(flag, None, "is required")


@dataclass(frozen=True)
class TuneJob(Job):
    request: Any  # lgw.tuning.eros.design.Request
    thrust_max: float
    probe_mass: float

    def run(self, progress: Any) -> Outcome:
        from lgw.theory.eros.gains import gains_to_toml
        from lgw.tuning.eros.design import tune

        req = self.request
        progress.stage("design, acceptance and validation campaigns")
        res = tune(req)
        if "infeasible" in res:
            return Outcome({"feasible": False, "reason": res["infeasible"]},
                           exit_code=EXIT_INFEASIBLE,
                           stderr=[f"infeasible: {res['infeasible']}", "nothing written"])
        g, bd, d, fr, va = (res["gains"], res["bound"], res["design"], res["fresh"],
                            res["validation"])
        cert = {"law": "ftsmc-sign", "ts_target": req.ts, "thrust_max": self.thrust_max,
                "probe_mass": self.probe_mass, "u_max": req.u_max, "e_max": req.e_max,
                "v_max": req.v_max, "dbar": req.dbar, "bound_t_total": bd["t_total"],
                "bound_t_reach": bd["t_reach"], "bound_t_slide": bd["t_slide"],
                "bound_evidence": "proven for the continuous-time law (claims reaching-sign, "
                                  "settling-ftsm); worst case at the envelope corner",
                "u_max_evidence": f"sampled, not proven: {d['cases']} design, {fr['cases']} "
                                  f"acceptance and {va['cases']} validation cases",
                "design_cases": d["cases"], "design_peak": d["peak"],
                "acceptance_cases": fr["cases"], "acceptance_seed": req.seed + 1000,
                "acceptance_peak": fr["peak"], "acceptance_t_track_max": fr["t_track_max"],
                "validation_cases": va["cases"], "validation_seed": req.seed + 2000,
                "validation_peak": va["peak"], "validation_t_track_max": va["t_track_max"],
                "validation_nonfinite": va["nonfinite"],
                "validation_meets": bool(va["peak"] <= req.u_max
                                         and va["t_track_max"] <= req.ts
                                         and va["nonfinite"] == 0),
                "candidates_tried": len(res["tried"])}
        text = gains_to_toml(g, "lgw tune eros: seed 002 FTSMC gains") + "\n[certificate]\n"
        text += "\n".join(f"{k} = {json.dumps(v)}" for k, v in cert.items()) + "\n"
        return Outcome({**g.to_dict(), "feasible": True, "tuned_gains": g.to_dict()["gains"],
                        "certificate": cert},
                       render=lambda con: _render(con, g, cert), files={"gains.toml": text})


def _render(con: Any, g: Any, cert: dict[str, Any]) -> None:
    from lgw.tuning.tables import result_table

    result_table(con, "tuned FTSMC gains (seed 002 (19))", ("gain", "value"),
                 [(k, f"{v:.6g}") for k, v in g.to_dict()["gains"].items()])
    p = lambda s: con.print(s, markup=False, highlight=False)  # noqa: E731
    p(f"bound reaching + sliding {cert['bound_t_total']:.4g} s <= ts {cert['ts_target']:g} s "
      f"({cert['bound_evidence']})")
    p(f"control peak {cert['validation_peak']:.4g} m/s^2 against u_max {cert['u_max']:.4g} "
      f"m/s^2 = {cert['thrust_max']:g} N / {cert['probe_mass']:g} kg ({cert['u_max_evidence']})")


def plan(opts: Options, system: Any) -> TuneJob:
    from lgw.theory.eros.parameters import DT_SAMPLE, PROBE_MASS, T_SCENARIO
    from lgw.tuning.eros.cmd_simulate import case_bytes
    from lgw.tuning.eros.design import Request
    from lgw.tuning.io import check_memory

    check_memory("--fresh-cases", opts.fresh_cases, case_bytes(T_SCENARIO, DT_SAMPLE))

    req = Request(ts=opts.ts, u_max=opts.thrust_max / PROBE_MASS, e_max=opts.e_max,
                  v_max=opts.v_max, dbar=opts.dbar, fresh_cases=opts.fresh_cases,
                  seed=opts.seed)
    return TuneJob(req, opts.thrust_max, PROBE_MASS)
