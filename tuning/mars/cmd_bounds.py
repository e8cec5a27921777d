"""``lgw bounds mars``: every seed 000 bound for a gain set."""

from __future__ import annotations

import json
from pathlib import Path

import click
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.parameters import AXES
from lgw.theory.mars.report import BOUND_LABELS, gain_warnings
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import gains_option
from rich.console import Console
from rich.table import Table


@click.command("mars")
@gains_option
@click.option("--json", "as_json", is_flag=True, help="print one JSON object, a key per axis")
def command(gains_path: Path | None, as_json: bool) -> None:
    """Settling times, neighbourhoods and landing-time bounds of seed 000 for a gain set.

    landing_time_bound is the workbench's sound bound without disturbance (T1* + T2*, corrected
    law); landing_time_bound_disturbed the sound bound to enter the (31) neighbourhood under
    |a_p,i| <= a_max (needs a [disturbance] table).
    """
    g = resolve_gains(gains_path)
    b = axis_bounds(g)
    if as_json:
        out = dict(b)
        out["notes"] = {
            "units": "seconds for times, metres for s1_bound, m/s for s2_bound and v_bound",
            "landing_time_bound": "sound, no disturbance, corrected law: T1_exact + T2_exact",
            "landing_time_bound_disturbed": "sound, |a_p,i| <= a_max, corrected law: time to "
            "enter |r_i| <= s1_bound, T2_practical_exact + T1_practical_exact",
            "T_whole_paper": "the paper's max{T1, T2}: unproven (claim landing-time)",
            "T3_paper": "(32) as printed: unproven (claim T3)",
            "warnings": gain_warnings(g),
        }
        click.echo(json.dumps(out, indent=2, sort_keys=False))
        return
    t = Table(title="seed 000 bounds (per axis)")
    t.add_column("bound")
    t.add_column("unit")
    for a in AXES:
        t.add_column(a, justify="right")
    for key, label, unit in BOUND_LABELS:
        if key in b["x"]:
            t.add_row(f"{label} [{key}]", unit, *(f"{b[a][key]:.6g}" for a in AXES))
    con = Console()
    con.print(t)
    con.print("landing_time_bound: sound (corrected law, no disturbance); "
              "landing_time_bound_disturbed: sound under |a_p,i| <= a_max.")
    for w in gain_warnings(g):
        con.print(f"[yellow]warning:[/] {w}")
