"""Design gains of seed 002's laws and write them with a [certificate] (``lgw.tuning.eros.design``).

``--scenario tracking`` (default): alpha, beta, p/q, k and the floor e_floor of the FTSMC (19)
(sign switching) so that the proven tracking time meets --ts over the envelope of initial
offsets and the command stays under the actuator limit: proven over the whole envelope
(``--u-limit proven``, the default: ``lgw.theory.eros.floored``) or only sampled
(``--u-limit sampled``: the certificate says so, with the sample size and the best margin).
The actuator limit is a per-axis thrust in N (``--thrust-max``); the law commands an
acceleration, so the limit on u is thrust-max / m with m the probe mass of seed 002 Table 1.

``--scenario descent``: alpha (= lam), k and phi of a descent law (default the paper's
recommended fuzzy-tanh) for the whole descent to touchdown on the shape model
(``tune_descent``): k between the theory's floor and the thrust, the least propellant among
the candidates that land every design case (navigation errors on by default), a fresh
acceptance campaign; the landing promise is sampled evidence and the certificate says so.

Exit 0 feasible (file written); 3 infeasible (the reason on stderr, nothing written).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lgw.theory.errors import ParameterError
from lgw.tuning import vocabulary as V
from lgw.tuning.options import Integer, Number, choice
from lgw.tuning.spec import Options, option
from lgw.tuning.system import EXIT_INFEASIBLE, Job, Outcome

SCENARIOS = ("tracking", "descent")
DESCENT_LAWS = ("pdsmc-tanh", "ftsmc-tanh", "fuzzy-sign", "fuzzy-tanh", "pdsmc-sign",
                "ftsmc-sign")
TRACKING_ONLY = ("ts", "e_max", "v_max", "dbar", "u_limit")
DESCENT_ONLY = ("land_speed", "law", "nav", "design_cases")


@dataclass(frozen=True)
class Options(Options):
    scenario: str = option("--scenario", choice(SCENARIOS), "tracking",
                           "tracking: the FTSMC on the paper's tracking scenario (proven time "
                           "and command bounds); descent: a law for the whole descent to "
                           "touchdown on the shape model (sampled)")
    ts: float | None = option("--ts", Number(0, 1e5, lo_open=True, unit="s"), None,
                              "tracking: time target (|e_i| <= 1 cm for good), s [required]",
                              probe=10.0)
    thrust_max: float | None = V.thrust_max(None, "per axis; tracking: the control limit is "
                                            "thrust-max / probe mass [required]; descent: "
                                            "[default: 22 N]")
    u_limit: str = option("--u-limit", choice(("proven", "sampled")), "proven",
                          "tracking: how the control limit must be known: proven over the "
                          "whole envelope (the floored law's command bound), or sampled only")
    e_max: float = option("--e-max", Number(0, 1e5, lo_open=True, unit="m"), 10.0,
                          "tracking: envelope |e_i(0)|, m")
    v_max: float = option("--v-max", Number(0, 1e3, lo_open=True, unit="m/s"), 0.5,
                          "tracking: envelope |e_i'(0)|, m/s")
    dbar: float = option("--dbar", Number(0, 1e3, unit="m/s^2"), 0.0,
                         "tracking: unknown disturbance bound, m/s^2; 0: D known in u_eq (14)",
                         probe=0.1)
    land_speed: float | None = option("--land-speed", Number(0, 100, lo_open=True, unit="m/s"),
                                      None, "descent: the touchdown speed every case must "
                                      "not exceed, m/s [default: 0.5]", probe=0.4)
    law: str | None = option("--law", choice(DESCENT_LAWS), None,
                             "descent: the law variant [default: fuzzy-tanh, the paper's "
                             "recommended one]")
    nav: bool = option("--nav", None, True, "descent: navigation errors in the campaigns "
                       "(the design must survive them)", secondary="--no-nav")
    design_cases: int | None = option("--design-cases", Integer(1, 10**4, "cases"), None,
                                      "descent: design campaign cases per candidate "
                                      "[default: 8]", probe=2)
    fresh_cases: int | None = option("--fresh-cases", Integer(1, 10**6, "cases"), None,
                                     "cases of the fresh acceptance campaign flown with the "
                                     "tuned gains [default: tracking 200, descent 16]",
                                     probe=5)
    seed: int = V.seed(7, "seed of the design, acceptance and validation campaigns")
    json: bool = V.json_flag()
    out: Path | None = V.out_file("the gains TOML with its [certificate] table", required=True)

    def check(self) -> None:
        super().check()
        tracking = self.scenario == "tracking"
        for name in TRACKING_ONLY:
            self.refuse_unless(tracking, name, "only applies with --scenario tracking")
        for name in DESCENT_ONLY:
            self.refuse_unless(not tracking, name, "only applies with --scenario descent")
        need = (("ts", "--ts"), ("thrust_max", "--thrust-max")) if tracking else ()
        for name, flag in (*need, ("out", "--out")):
            if getattr(self, name) is None:
                raise ParameterError(flag, None, "is required" + (" (--scenario tracking)"
                                                                  if name != "out" else ""))


def _toml(g: Any, header: str, cert: dict[str, Any]) -> str:
    from lgw.theory.eros.gains import gains_to_toml

    text = gains_to_toml(g, header) + "\n[certificate]\n"
    return text + "\n".join(f"{k} = {json.dumps(v)}" for k, v in cert.items()) + "\n"


def _infeasible(why: str, extra: dict[str, Any] | None = None) -> Outcome:
    return Outcome({"feasible": False, "reason": why, **(extra or {})},
                   exit_code=EXIT_INFEASIBLE, stderr=[f"infeasible: {why}", "nothing written"])


@dataclass(frozen=True)
class TuneJob(Job):
    request: Any  # lgw.tuning.eros.design.Request
    thrust_max: float
    probe_mass: float

    def run(self, progress: Any) -> Outcome:
        from lgw.tuning.eros.design import certificate, tune

        req = self.request
        progress.stage("proofs over the grid, then design, acceptance and validation "
                       "campaigns")
        res = tune(req)
        if "infeasible" in res:
            return _infeasible(res["infeasible"])
        g = res["gains"]
        cert = certificate(res, req, self.thrust_max, self.probe_mass)
        text = _toml(g, "lgw tune eros: seed 002 FTSMC gains (e_floor designed)", cert)
        return Outcome({**g.to_dict(), "feasible": True, "tuned_gains": g.to_dict()["gains"],
                        "certificate": cert},
                       render=lambda con: _render(con, g, cert), files={"gains.toml": text})


def _render(con: Any, g: Any, cert: dict[str, Any]) -> None:
    from lgw.tuning.tables import result_table

    result_table(con, "tuned FTSMC gains (seed 002 (19), |e| floored at e_floor)",
                 ("gain", "value"), [(k, f"{v:.6g}") for k, v in g.to_dict()["gains"].items()])
    p = lambda s: con.print(s, markup=False, highlight=False)  # noqa: E731
    p(f"tracking by {cert['bound_t_total']:.4g} s <= ts {cert['ts_target']:g} s "
      f"(reaching {cert['bound_t_reach']:.4g} + sliding {cert['bound_t_slide']:.4g}): "
      f"{cert['bound_evidence']}")
    p(f"command |u_i| <= u_max {cert['u_max']:.4g} m/s^2 = {cert['thrust_max']:g} N / "
      f"{cert['probe_mass']:g} kg: {cert['u_max_evidence']}")


@dataclass(frozen=True)
class DescentJob(Job):
    request: Any  # lgw.tuning.eros.design.DescentRequest

    def run(self, progress: Any) -> Outcome:
        from lgw.tuning.eros.design import descent_certificate, tune_descent

        req = self.request
        progress.stage(f"descent design campaigns ({req.law}, {req.design_cases} cases per "
                       f"candidate), then {req.fresh_cases} fresh cases")
        res = tune_descent(req)
        if "infeasible" in res:
            return _infeasible(res["infeasible"], {"floor": res.get("floor")})
        if not res["fresh_meets"]:
            f = res["fresh"]
            return _infeasible(f"the chosen design (alpha = {res['gains'].alpha:g}, k = "
                               f"{res['gains'].k:.4g}) landed {f['landed']} of {f['cases']} "
                               f"fresh cases at most {f['speed_max']:.4g} m/s (limit "
                               f"{req.land_speed:g} m/s)", {"fresh": f})
        g = res["gains"]
        cert = descent_certificate(res, req)
        text = _toml(g, f"lgw tune eros --scenario descent: seed 002 {req.law} gains for the "
                     "whole descent", cert)
        return Outcome({**g.to_dict(), "feasible": True, "tuned_gains": g.to_dict()["gains"],
                        "certificate": cert},
                       render=lambda con: _render_descent(con, g, cert),
                       files={"gains.toml": text})


def _render_descent(con: Any, g: Any, cert: dict[str, Any]) -> None:
    from lgw.tuning.tables import result_table

    result_table(con, f"tuned descent gains ({cert['law']})", ("gain", "value"),
                 [(k, f"{v:.6g}") for k, v in g.to_dict()["gains"].items()])
    p = lambda s: con.print(s, markup=False, highlight=False)  # noqa: E731
    p(f"k = {g.k:.4g} m/s^2 above the floor {cert['k_floor']:.4g} m/s^2 (the controller's "
      f"unknown acceleration and drift), below u_max {cert['u_max']:.4g} m/s^2")
    p(f"landing at <= {cert['land_speed']:g} m/s: {cert['landing_evidence']}")
    p(f"propellant: {cert['fresh_fuel_mean_kg']:.4g} kg mean, {cert['fresh_fuel_max_kg']:.4g} "
      "kg max (fresh campaign)")


def plan(opts: Options, system: Any) -> Job:
    from lgw.theory.eros import parameters as P
    from lgw.theory.eros.parameters import DT_SAMPLE, PROBE_MASS, T_SCENARIO
    from lgw.tuning.eros.cmd_simulate import case_bytes
    from lgw.tuning.eros.design import DescentRequest, Request
    from lgw.tuning.io import check_memory

    if opts.scenario == "descent":
        return DescentJob(DescentRequest(
            thrust_max=P.THRUST_MAX if opts.thrust_max is None else opts.thrust_max,
            land_speed=P.LAND_SPEED_MAX if opts.land_speed is None else opts.land_speed,
            law=opts.law or "fuzzy-tanh", nav=opts.nav,
            design_cases=opts.design_cases or 8, fresh_cases=opts.fresh_cases or 16,
            seed=opts.seed))
    fresh = opts.fresh_cases or 200
    check_memory("--fresh-cases", fresh, case_bytes(T_SCENARIO, DT_SAMPLE))
    req = Request(ts=opts.ts, u_max=opts.thrust_max / PROBE_MASS, e_max=opts.e_max,
                  v_max=opts.v_max, dbar=opts.dbar, fresh_cases=fresh, seed=opts.seed,
                  u_limit=opts.u_limit)
    return TuneJob(req, opts.thrust_max, PROBE_MASS)
