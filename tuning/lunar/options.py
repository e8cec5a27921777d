"""Seed 001's command-line helpers."""

from __future__ import annotations

from pathlib import Path

from lgw.theory.lunar.gains import Gains, load, paper_gains


def resolve_gains(path: Path | None) -> Gains:
    """The gains of ``--gains`` (validated), or seed 001 Section 5's."""
    return paper_gains() if path is None else load(path)
