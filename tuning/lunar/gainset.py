"""Seed 001's gain set as the shared commands see it: load, default (Section 5's), document,
example (``lgw.tuning.gainset``)."""

from __future__ import annotations

from typing import Any

from lgw.theory.lunar.gains import Gains, load, paper_gains
from lgw.tuning.gainset import GainSet


def _document(g: Gains) -> dict[str, Any]:
    return {"gains": g.to_dict()}


def run_defaults(g: Gains) -> dict[str, float]:
    """The run options a tuned file fixes (``lgw.sim.lunar.closed_loop.RunOptions`` field ->
    value): its [command_filter] wn and its [vehicle] thrust_max.  The command line's
    --cmd-wn / --thrust-max override them."""
    out = {}
    if "command_filter" in g.extra:
        out["cmd_wn"] = g.extra["command_filter"]["wn"]
    if "vehicle" in g.extra:
        out["thrust_max"] = g.extra["vehicle"]["thrust_max"]
    return out


def _example() -> str:
    """A valid gain set other than the paper's (TOML), for the options test."""
    d = paper_gains().to_dict()
    lines = []
    for loop, t in d.items():
        lines.append(f"[{loop}]")
        for k, v in t.items():
            if k == "F2":
                v = [[x * 1.2 for x in row] for row in v]
            lines.append(f"{k} = {v!r}")
    return "\n".join(lines) + "\n"


GAINS = GainSet(load=load, default=paper_gains, example=_example, document=_document)
load, default, resolve, document, example = GAINS.parts()

__all__ = ["GAINS", "default", "document", "example", "load", "resolve", "run_defaults"]
