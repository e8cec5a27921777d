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


__all__ = ["default", "document", "example", "load", "resolve"]
