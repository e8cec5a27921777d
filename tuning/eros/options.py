"""Seed 002's command-line helpers."""

from __future__ import annotations

from pathlib import Path

from lgw.theory.eros.gains import Gains, default_gains, load_gains


def resolve_gains(path: Path | None) -> Gains:
    """The gain set of ``--gains`` (validated), or the built-in default."""
    return default_gains() if path is None else load_gains(path)
