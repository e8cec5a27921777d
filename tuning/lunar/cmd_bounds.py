"""f1bar, f2bar, the (18) constants and the true H-infinity gains of the filter (11) per loop
(seed 001) for a gain set."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import Number
from lgw.tuning.spec import option
from lgw.tuning.system import Call, Outcome

EQ0_MIN = 1e-3  # linfnorm of the frozen attitude filter fails below ~1e-7 (f1bar ~ 1e-14)


@dataclass(frozen=True)
class Options(V.BoundsOptions):
    eq0_min: float = option("--eq0-min", Number(EQ0_MIN, 1, unit="quaternion scalar part"),
                            1.0, "smallest |eq0| assumed along the run (attitude f1bar = "
                            "lambda_min(K1) eq0^2/4); the attitude filter is frozen there for "
                            f"its H-infinity gain; >= {EQ0_MIN:g} (an attitude error of "
                            "179.9 degrees): below, the frozen filter's H-infinity norm is "
                            "not computable (f1bar underflows)", probe=0.8)


def bounds(gains: Any, progress: Any, eq0_min: float) -> Outcome:
    """The (18) constants and the filters' true L2 gains per loop, the attitude filter
    frozen at ``eq0_min`` (the smallest quaternion scalar part assumed)."""
    from lgw.theory.lunar.bounds import attitude_bounds, orbit_bounds

    progress.stage("L2 gains of the filters (python-control linfnorm)")
    b = {"orbit": orbit_bounds(gains.orbit).to_dict(),
         "attitude": attitude_bounds(gains.attitude, eq0_min).to_dict()}
    doc = {**b, "notes": {"norms": "L2 over [0, t]; gains dimensionless (input B0 du, "
                          "output lambda)", "attitude": f"frozen at eq0 = {eq0_min}"}}
    return Outcome(doc, render=lambda con: _render(con, b), files={"bounds.json": DOCUMENT})


def _render(con: Any, b: dict[str, Any]) -> None:
    from lgw.tuning.tables import result_table

    rows = [(k, f"{b['orbit'][k]:.6g}", f"{b['attitude'][k]:.6g}") for k in b["orbit"]]
    result_table(con, "seed 001 (18) and the true filter gains", ("quantity", "orbit",
                                                                  "attitude"), rows)


def plan(opts: Options, system: Any) -> Call:
    from lgw.tuning.lunar.gainset import resolve

    return Call("lgw.tuning.lunar.cmd_bounds:bounds", resolve(opts.gains),
                {"eq0_min": opts.eq0_min})
