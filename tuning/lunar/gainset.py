"""Seed 001's gain set as the shared commands see it: load, default, document, example."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lgw.theory.lunar.gains import Gains, load, paper_gains


def default() -> Gains:
    return paper_gains()


def resolve(path: Path | None) -> Gains:
    """The gains of ``--gains`` (validated), or seed 001 Section 5's."""
    return paper_gains() if path is None else load(path)


def document(g: Gains) -> dict[str, Any]:
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


def example() -> str:
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


__all__ = ["default", "document", "example", "load", "resolve", "run_defaults"]
