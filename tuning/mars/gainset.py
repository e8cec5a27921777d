"""Seed 000's gain set as the shared commands see it: load, default, document, example."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lgw.theory.mars.gains import Gains, default_gains, gains_from_dict, gains_to_toml, load_gains


def load(path: Path) -> Gains:
    return load_gains(path)


def default() -> Gains:
    return default_gains()


def resolve(path: Path | None) -> Gains:
    """The gain set of ``--gains`` (validated), or the built-in default."""
    return default_gains() if path is None else load_gains(path)


def document(g: Gains) -> dict[str, Any]:
    """The head of every JSON document: ``gains`` (and ``disturbance`` when the file has it)."""
    return g.to_dict()


def example() -> str:
    """A valid gain set other than the default (TOML), for the options test."""
    d = default_gains().to_dict()
    d["gains"]["beta1"] = [3.1, 2.8, 2.9]
    d["gains"]["alpha1"] = 0.6
    return gains_to_toml(gains_from_dict(d))
