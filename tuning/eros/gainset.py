"""Seed 002's gain set as the shared commands see it: load, default, document, example."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lgw.theory.eros.gains import Gains, default_gains, gains_to_toml, load_gains


def load(path: Path) -> Gains:
    return load_gains(path)


def default() -> Gains:
    return default_gains()


def resolve(path: Path | None) -> Gains:
    """The gain set of ``--gains`` (validated), or the built-in default."""
    return default_gains() if path is None else load_gains(path)


def document(g: Gains) -> dict[str, Any]:
    return g.to_dict()


def example() -> str:
    """A valid gain set other than the default (TOML), for the options test."""
    g = default_gains()
    return gains_to_toml(g.replace(k=g.k * 1.25, alpha=g.alpha * 1.1))
