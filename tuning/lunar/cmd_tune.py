"""Design what seed 001 leaves open, for a target tracking error and the thrust limit with the
failure: the orbit gains, the command-filter bandwidth of the desired attitude, and the thrust
redundancy (T_max against the demand after the failure), and write them with a
[certificate] (``lgw.tuning.lunar.design``).

Without targets it designs for the paper's Section 5 scenario: |e_h(t_f)| <= 10 m, |e_v(t_f)|
<= 2 m/s (the "tracking is maintained" tolerances), the failure (26) at t_f/2 to 70 %, the
initial errors within the box whose corner is the paper's.  Without --thrust-max it sizes
T_max; with it, a limit below the demand after the failure is infeasible.  The certificate
says "proven" only for what is proven (the redundancy in exact arithmetic, the hypotheses and
the L2 gains of (18)) and "sampled" with sample size and best margin for the rest.
Exit 0 feasible (file written); 3 infeasible (the reason on stderr, nothing written).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lgw.theory.errors import ParameterError
from lgw.tuning import vocabulary as V
from lgw.tuning.options import Integer, Number, choice
from lgw.tuning.spec import Options, option
from lgw.tuning.system import EXIT_INFEASIBLE, Job, Outcome

ENVELOPES = ("section5", "campaign")


@dataclass(frozen=True)
class Options(Options):
    eh_max: float = option("--eh-max", Number(0, 1e5, lo_open=True, unit="m"), 10.0,
                           "target |e_h(t_f)|, m (the paper's scenario: 10 m)", probe=20.0)
    ev_max: float = option("--ev-max", Number(0, 1e4, lo_open=True, unit="m/s"), 2.0,
                           "target |e_v(t_f)|, m/s (the paper's scenario: 2 m/s)", probe=3.0)
    thrust_max: float | None = V.thrust_max(None, "orbit-thrust limit T_max of (24); "
                                            "[default: sized: 5 % above T_d / T_a,min]")
    envelope: str = option("--envelope", choice(ENVELOPES), "section5",
                           "section5: the paper's failure (t_f/2, 70 %) and initial errors "
                           "within the box whose corner is its case (the attitude error a "
                           "roll about the thrust axis, as the paper's); campaign: the Monte "
                           "Carlo envelope of lgw simulate lunar (failure at 25-75 % of t_f, "
                           "60-80 % thrust left, errors to 200 m, 10 m/s, 60 deg)")
    pointing: str = option("--pointing", choice(("ideal", "coupled")), "ideal",
                           "whose flights the promises are about: ideal (the thrust along the "
                           "command: the paper's orbit loop (22)) or coupled (through the "
                           "attitude loop and the command filter); an ideal design also flies "
                           "and reports the coupled campaign")
    cases: int = option("--cases", Integer(1, 10_000, "cases"), 24,
                        "acceptance campaign cases (plus the nominal case)", probe=4)
    seed: int = V.seed(0, "seed of the acceptance campaign (drawn with seed + 1000)")
    dt: float | None = V.dt(None, 0.1, "RK4 step of the design runs [default: "
                            "lgw.sim.lunar.parameters.DT_CAMPAIGN]")
    json: bool = V.json_flag()
    out: Path | None = V.out_file("the gains TOML with its [certificate] table", required=True)

    def check(self) -> None:
        super().check()
        if self.out is None:
            raise ParameterError("--out", None, "is required")


def command_line(opts: Options) -> str:
    """The ``lgw tune lunar`` command that reproduces this run (recorded in the certificate)."""
    from dataclasses import fields

    from lgw.tuning.spec import opt_of

    parts = ["lgw tune lunar"]
    for f in fields(opts):
        o = opt_of(f)
        if o is None or o.flag in ("--json", "--out") or not opts.given(f.name):
            continue
        v = getattr(opts, f.name)
        parts.append(o.flag if o.is_flag else f"{o.flag} {v:g}" if isinstance(v, float)
                     else f"{o.flag} {v}")
    return " ".join(parts + ["--out FILE"])


@dataclass(frozen=True)
class TuneJob(Job):
    request: Any  # lgw.tuning.lunar.design.Request
    command: str

    def run(self, progress: Any) -> Outcome:
        from lgw.tuning.lunar.design import certificate, tune
        from lgw.tuning.lunar.gains_file import gains_file_text

        res = tune(self.request, progress)
        if not res.feasible:
            return Outcome({"feasible": False, "reason": res.reason,
                            "redundancy": res.redundancy, "tried": res.tried},
                           exit_code=EXIT_INFEASIBLE,
                           stderr=[f"infeasible: {res.reason}", "nothing written"])
        cert = certificate(res, self.request, self.command)
        text = gains_file_text(res.gains, cert)
        # gains: the designed set, as every tuner's document (tune mars, tune eros)
        doc = {"gains": res.gains.to_dict(), "feasible": True,
               "tuned_gains": res.gains.to_dict(), "certificate": cert,
               "bandwidth_sweep": res.bandwidth.to_dict(), "tried": res.tried}
        return Outcome(doc, render=lambda con: _render(con, res, cert),
                       files={"gains.toml": text})


def _band(cert: dict[str, Any], fmt: Any) -> str:
    """The robust band of the certificate's sweep, or why the wn flown is not from one."""
    band = cert["cmd_band_rad_s"]
    if band:
        return f"robust band {fmt(band[0])}-{fmt(band[1])}"
    return "no robust band: " + cert["cmd_wn_evidence"]


def _render(con: Any, res: Any, cert: dict[str, Any]) -> None:
    from lgw.tuning.tables import fmt, result_table

    g = res.gains
    rows = [("orbit F2 (diag)", ", ".join(fmt(x) for x in g.orbit.F2.diagonal())),
            ("orbit K1 (diag)", ", ".join(fmt(x) for x in g.orbit.K1.diagonal())),
            ("orbit f3, q, d0e(0)", f"{fmt(g.orbit.f3)}, {fmt(g.orbit.q)}, {fmt(g.orbit.d0e0)}"),
            ("attitude K1, F2 (diag)", f"{fmt(g.attitude.K1[0, 0])}, {fmt(g.attitude.F2[0, 0])}"),
            ("command filter wn", f"{fmt(cert['cmd_wn_rad_s'])} rad/s ({_band(cert, fmt)})"),
            ("T_max", f"{fmt(cert['thrust_max_N'])} N "
             f"({'sized' if cert['thrust_sized'] else 'given'}; needed "
             f"{fmt(cert['thrust_required_N'])} N)")]
    result_table(con, "tuned seed 001 design", ("quantity", "value"), rows)
    p = lambda s: con.print(s, markup=False, highlight=False)  # noqa: E731
    p(f"redundancy: T_max T_a,min - T_d = {cert['redundancy_margin_N']:.6g} N "
      f"({cert['redundancy_evidence']})")
    p(f"(18): lambda1 gain {cert['lambda1_hinf']:.4g} <= {cert['lambda1_gain_18a']:.4g}, "
      f"lambda2 gain {cert['lambda2_hinf']:.4g} <= {cert['lambda2_gain_18b']:.4g} (proven)")
    p(f"tracking: |e_h(t_f)| <= {cert['eh_final_max_m']:.4g} m of {cert['eh_max_m']:g}, "
      f"|e_v(t_f)| <= {cert['ev_final_max_m_s']:.4g} m/s of {cert['ev_max_m_s']:g} "
      f"({cert['tracking_evidence']})")
    p(f"thrust after the failure <= {cert['thrust_cmd_after_failure_max_N']:.6g} N of "
      f"{cert['thrust_max_N']:g} ({cert['no_saturation_after_failure_evidence']})")
    p(f"coupled pointing: {cert['coupled_completed']} of {cert['coupled_cases']} cases "
      f"completed ({cert['coupled_evidence']})")


def plan(opts: Options, system: Any) -> TuneJob:
    from lgw.sim.lunar import parameters as SP
    from lgw.sim.lunar.campaign import ENVELOPES as ENV
    from lgw.tuning.lunar.design import Request

    req = Request(eh_max=opts.eh_max, ev_max=opts.ev_max, thrust_max=opts.thrust_max,
                  envelope=ENV[opts.envelope], cases=opts.cases, seed=opts.seed,
                  dt=SP.DT_CAMPAIGN if opts.dt is None else opts.dt, pointing=opts.pointing)
    return TuneJob(req, command_line(opts))
