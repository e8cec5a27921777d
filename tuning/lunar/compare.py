"""Seed 001's own comparison: the Section 5 case with and without the failure (26) and the
saturations (24), (28), each with the thrust along the command (ideal pointing, the paper's
orbit loop (22) with u_o as its input) and along the simulated body axis (coupled pointing,
through the attitude loop (27) and the command filter), every number checked against the run
at dt/4; and the command filter's bandwidth swept (``lgw.tuning.lunar.design``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from lgw.sim.lunar.closed_loop import RunOptions

UNSATURATED = 1e9  # N and N m: limits no command of these runs reaches ("no saturation")
# (label, failure, saturated)
CONDITIONS = (("no failure, no saturation", "none", False),
              ("failure (26) only", "atan", False),
              ("saturation (24), (28) only", "none", True),
              ("failure and saturation (Section 5)", "atan", True))
POINTINGS = ("ideal", "coupled")
NUMBERS = ("eh_final_m", "ev_final_norm_m_s", "max_abs_eh_m", "max_abs_ev_m_s",
           "orbit_saturated_s", "orbit_saturated_after_failure_s",
           "thrust_cmd_max_after_failure_N", "torque_saturated_initial_s",
           "torque_saturation_end_s", "min_abs_eq0",
           "d0e_attitude_final", "outcome", "t_outcome_s")


@dataclass
class Row:
    condition: str
    pointing: str
    opts: RunOptions
    numbers: dict
    convergence: Any  # lgw.sim.lunar.convergence.Convergence
    res: Any  # recorded run (for the figure)

    def to_dict(self) -> dict[str, Any]:
        from lgw.sim.lunar.outcomes import json_safe

        return json_safe({"condition": self.condition, "pointing": self.pointing,
                          "failure": self.opts.failure,
                          "thrust_max_N": self.opts.thrust_max,
                          "torque_max_N_m": self.opts.torque_max,
                          "cmd_wn_rad_s": self.opts.cmd_wn, "dt_s": self.opts.dt,
                          **{k: self.numbers.get(k) for k in NUMBERS},
                          "converged": self.convergence.converged,
                          "convergence": self.convergence.to_dict()})


def run_conditions(gains: Any, base: RunOptions, progress: Any = None) -> list[Row]:
    """The eight runs (four conditions x two pointings), each with its convergence check."""
    from lgw.sim.lunar.scenario import fly_section5

    rows = []
    for label, failure, saturated in CONDITIONS:
        for pointing in POINTINGS:
            o = replace(base, failure=failure, thrust_pointing=pointing,
                        thrust_max=base.thrust_max if saturated else UNSATURATED,
                        torque_max=base.torque_max if saturated else UNSATURATED)
            if progress is not None:
                progress.stage(f"{label}, {pointing} pointing (and at dt/4)")
            f = fly_section5(gains, o, record_every_s=0.5)
            rows.append(Row(label, pointing, o, dict(f.summary.numbers), f.convergence,
                            f.res))
    return rows


def findings(rows: list[Row]) -> list[str]:
    """What the comparison shows, computed from the rows (one sentence each)."""
    out = []
    by = {(r.condition, r.pointing): r for r in rows}
    s5 = CONDITIONS[3][0]
    for p in POINTINGS:
        r = by[(s5, p)]
        n = r.numbers
        out.append(f"Section 5 ({p} pointing): e_h(t_f) = {n['eh_final_m']:.4g} m, "
                   f"|e_v(t_f)| = {n['ev_final_norm_m_s']:.4g} m/s, outcome {n['outcome']}; "
                   f"the thrust saturates {n['orbit_saturated_after_failure_s']:.4g} s after "
                   "the failure")
    for p in POINTINGS:
        a, b = by[(CONDITIONS[0][0], p)], by[(s5, p)]
        out.append(f"{p} pointing: the failure and the saturations move |e_v(t_f)| from "
                   f"{a.numbers['ev_final_norm_m_s']:.4g} to {b.numbers['ev_final_norm_m_s']:.4g}"
                   " m/s")
    bad = [f"{r.condition} / {r.pointing}" for r in rows if not r.convergence.converged]
    out.append("every number converged to 1 % against dt/4" if not bad else
               "not converged to 1 % against dt/4: " + "; ".join(bad))
    return out
