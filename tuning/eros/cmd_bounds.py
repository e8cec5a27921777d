"""``lgw bounds eros``: settling and reaching times of seed 002 for a gain set."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.theory.eros.report import BOUND_LABELS, axis_bounds, gain_warnings
from lgw.tuning.eros.options import resolve_gains
from lgw.tuning.io import console, json_document
from lgw.tuning.options import Number, gains_option
from rich.table import Table


@click.command("eros")
@gains_option
@click.option("--dbar", type=Number(0, unit="m/s^2"), default=0.0, show_default=True,
              help="bound on the unknown disturbance |D_i| (m/s^2); 0: D known as in (14)")
@click.option("--json", "as_json", is_flag=True, help="print one JSON object, a key per axis")
def command(gains_path: Path | None, dbar: float, as_json: bool) -> None:
    """Derived and printed settling times (5), (7), reaching time and the reaching + sliding
    bound for the scenario's initial error, per axis."""
    from lgw.theory.errors import ParameterError

    g = resolve_gains(gains_path)
    if not (0.0 <= dbar < g.k):
        raise ParameterError("--dbar", dbar, f"must lie in [0, k = {g.k}) m/s^2")
    b = axis_bounds(g, dbar=dbar)
    if as_json:
        click.echo(json_document({"command": "bounds eros", "gains": g.to_dict(), **b,
                                  "warnings": gain_warnings(g)}, indent=2))
        return
    t = Table(title="seed 002 bounds (per axis)")
    for col in ("bound", "unit", "x", "y", "z"):
        t.add_column(col, justify="right" if col in "xyz" else "left")
    for key, label, unit in BOUND_LABELS:
        t.add_row(f"{label} [{key}]", unit, *(f"{b[a][key]:.6g}" for a in "xyz"))
    con = console()
    con.print(t)
    for w in gain_warnings(g):
        con.print(f"[yellow]warning:[/] {w}")
