"""Derived and printed settling times (5), (7), the reaching time and the reaching + sliding
bound of seed 002 for the scenario's initial error, per axis, for a gain set."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Number
from lgw.tuning.spec import option
from lgw.tuning.system import Call, Outcome


@dataclass(frozen=True)
class Options(V.BoundsOptions):
    dbar: float = option("--dbar", Number(0, 1e3, unit="m/s^2"), 0.0,
                         "bound on the unknown disturbance |D_i| (m/s^2); 0: D known as in "
                         "(14); must be < k", probe=0.5)


def bounds(gains: Any, progress: Any, dbar: float) -> Outcome:
    """Every bound per axis for the scenario's initial error (s), with the gain set's
    warnings; ``dbar``: the bound on the unknown disturbance, m/s^2."""
    from lgw.theory.eros.report import axis_bounds, gain_warnings

    b = axis_bounds(gains, dbar=dbar)
    warnings = gain_warnings(gains)
    return Outcome({**b, "warnings": warnings},
                   render=lambda con: _render(con, b, warnings),
                   files={"bounds.json": DOCUMENT})


def _render(con: Any, b: dict[str, Any], warnings: list[str]) -> None:
    from lgw.theory.eros.report import BOUND_LABELS
    from lgw.tuning.tables import result_table

    rows = [(f"{label} [{key}]", unit, *(f"{b[a][key]:.6g}" for a in "xyz"))
            for key, label, unit in BOUND_LABELS]
    result_table(con, "seed 002 bounds (per axis)", ("bound", "unit", "x", "y", "z"), rows)
    for w in warnings:
        con.print(f"warning: {w}", markup=False)


def plan(opts: Options, system: Any) -> Call:
    from lgw.theory.errors import ParameterError
    from lgw.tuning.eros.gainset import resolve

    g = resolve(opts.gains)
    if not opts.dbar < g.k:
        raise ParameterError("--dbar", opts.dbar, f"must lie in [0, k = {g.k}) m/s^2 (the "
                             "switching gain must dominate the disturbance, (18))")
    return Call("lgw.tuning.eros.cmd_bounds:bounds", g, {"dbar": opts.dbar})
