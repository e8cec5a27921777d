"""``lgw bounds lunar``: the (18) constants beside the true L2 gains of the filter (11)."""

from __future__ import annotations

from pathlib import Path

import click
from lgw.theory.errors import ParameterError
from lgw.theory.lunar.bounds import attitude_bounds, orbit_bounds
from lgw.tuning.io import console, json_document
from lgw.tuning.lunar.options import resolve_gains
from lgw.tuning.options import Number, gains_option
from rich.table import Table


@click.command("lunar")
@gains_option
@click.option("--eq0-min", type=Number(0, 1, lo_open=True, unit="quaternion scalar part"),
              default=1.0, show_default=True,
              help="smallest |eq0| assumed along the run (attitude f1bar = lambda_min(K1) "
                   "eq0^2/4); the attitude filter is frozen there for its H-infinity gain")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (strict, with lgw_version and the gains)")
def command(gains_path: Path | None, eq0_min: float, as_json: bool) -> None:
    """f1bar, f2bar, the (18) constants and the true H-infinity gains of (11) per loop."""
    if not 0.0 < eq0_min <= 1.0:
        raise ParameterError("--eq0-min", eq0_min, "must lie in (0, 1]")
    g = resolve_gains(gains_path)
    b = {"orbit": orbit_bounds(g.orbit).to_dict(),
         "attitude": attitude_bounds(g.attitude, eq0_min).to_dict()}
    if as_json:
        b["notes"] = {"norms": "L2 over [0, t]; gains dimensionless (input B0 du, output "
                      "lambda)", "attitude": f"frozen at eq0 = {eq0_min}"}
        click.echo(json_document({"command": "bounds lunar", "gains": g.to_dict(), **b},
                                 indent=2))
        return
    t = Table(title="seed 001 (18) and the true filter gains")
    t.add_column("quantity")
    t.add_column("orbit", justify="right")
    t.add_column("attitude", justify="right")
    for k in b["orbit"]:
        t.add_row(k, f"{b['orbit'][k]:.6g}", f"{b['attitude'][k]:.6g}")
    console().print(t)
