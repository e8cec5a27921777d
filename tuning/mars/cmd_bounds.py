"""Settling times, neighbourhoods and landing-time bounds of seed 000 for a gain set.

landing_time_bound is the workbench's sound bound without disturbance (T1* + T2*, corrected
law); landing_time_bound_disturbed the sound bound to enter the (31) neighbourhood under
|a_p,i| <= a_max (needs a [disturbance] table).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.system import Call, Outcome


@dataclass(frozen=True)
class Options(V.BoundsOptions):
    """--gains, --json, --out: nothing else decides seed 000's bounds."""


def bounds(gains: Any, progress: Any) -> Outcome:
    """Every settling-time, neighbourhood and landing-time bound per axis (s, m, m/s), with
    the gain set's warnings."""
    from lgw.theory.mars.bounds import axis_bounds
    from lgw.theory.mars.report import gain_warnings

    b = axis_bounds(gains)
    warnings = gain_warnings(gains)
    doc = {**b, "notes": {
        "units": "seconds for times, metres for s1_bound, m/s for s2_bound and v_bound",
        "landing_time_bound": "sound, no disturbance, corrected law: T1_exact + T2_exact",
        "landing_time_bound_disturbed": "sound, |a_p,i| <= a_max, corrected law: time to "
        "enter |r_i| <= s1_bound, T2_practical_exact + T1_practical_exact",
        "T_whole_paper": "the paper's max{T1, T2}: unproven (claim landing-time)",
        "T3_paper": "(32) as printed: unproven (claim T3)",
        "warnings": warnings}}
    return Outcome(doc, render=lambda con: _render(con, b, warnings),
                   files={"bounds.json": DOCUMENT})


def _render(con: Any, b: dict[str, Any], warnings: list[str]) -> None:
    from lgw.theory.mars.parameters import AXES
    from lgw.theory.mars.report import BOUND_LABELS
    from lgw.tuning.tables import result_table

    rows = [(f"{label} [{key}]", unit, *(f"{b[a][key]:.6g}" for a in AXES))
            for key, label, unit in BOUND_LABELS if key in b["x"]]
    result_table(con, "seed 000 bounds (per axis)", ("bound", "unit", *AXES), rows)
    con.print("landing_time_bound: sound (corrected law, no disturbance); "
              "landing_time_bound_disturbed: sound under |a_p,i| <= a_max.", markup=False)
    for w in warnings:
        con.print(f"warning: {w}", markup=False)


def plan(opts: Options, system: Any) -> Call:
    from lgw.tuning.mars.gainset import resolve

    return Call("lgw.tuning.mars.cmd_bounds:bounds", resolve(opts.gains))
