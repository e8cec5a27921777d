"""``lgw bounds mars``: every seed 000 bound for a gain set."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.parameters import AXES
from lgw.theory.mars.report import BOUND_LABELS, gain_warnings
from lgw.tuning.io import atomic_write_text, check_out_dir, console, json_document, make_out_dir
from lgw.tuning.mars.options import resolve_gains
from lgw.tuning.options import gains_option, out_dir_option
from rich.table import Table


@click.command("mars")
@gains_option
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object, a key per axis (schema: docs/json.md)")
@out_dir_option("bounds.json")
def command(gains_path: Path | None, as_json: bool, out: Path | None) -> None:
    """Settling times, neighbourhoods and landing-time bounds of seed 000 for a gain set.

    landing_time_bound is the workbench's sound bound without disturbance (T1* + T2*, corrected
    law); landing_time_bound_disturbed the sound bound to enter the (31) neighbourhood under
    |a_p,i| <= a_max (needs a [disturbance] table).
    """
    check_out_dir(out)
    g = resolve_gains(gains_path)
    b = axis_bounds(g)
    if as_json or out is not None:
        doc: dict = {"command": "bounds mars", **g.to_dict(), **b}
        doc["notes"] = {
            "units": "seconds for times, metres for s1_bound, m/s for s2_bound and v_bound",
            "landing_time_bound": "sound, no disturbance, corrected law: T1_exact + T2_exact",
            "landing_time_bound_disturbed": "sound, |a_p,i| <= a_max, corrected law: time to "
            "enter |r_i| <= s1_bound, T2_practical_exact + T1_practical_exact",
            "T_whole_paper": "the paper's max{T1, T2}: unproven (claim landing-time)",
            "T3_paper": "(32) as printed: unproven (claim T3)",
            "warnings": gain_warnings(g),
        }
        text = json_document(doc, indent=2)
        if out is not None:
            atomic_write_text(make_out_dir(out) / "bounds.json", text + "\n")
        if as_json:
            click.echo(text)
            return
    t = Table(title="seed 000 bounds (per axis)")
    t.add_column("bound")
    t.add_column("unit")
    for a in AXES:
        t.add_column(a, justify="right")
    for key, label, unit in BOUND_LABELS:
        if key in b["x"]:
            t.add_row(f"{label} [{key}]", unit, *(f"{b[a][key]:.6g}" for a in AXES))
    con = console()
    con.print(t)
    con.print("landing_time_bound: sound (corrected law, no disturbance); "
              "landing_time_bound_disturbed: sound under |a_p,i| <= a_max.")
    for w in gain_warnings(g):
        con.print(f"[yellow]warning:[/] {w}")
