"""Seed 002's gain set as the shared commands see it: load, default, document, example
(``lgw.tuning.gainset``)."""

from __future__ import annotations

from lgw.theory.eros.gains import default_gains, gains_to_toml, load_gains
from lgw.tuning.gainset import GainSet


def _example() -> str:
    """A valid gain set other than the default (TOML), for the options test."""
    g = default_gains()
    return gains_to_toml(g.replace(k=g.k * 1.25, alpha=g.alpha * 1.1))


GAINS = GainSet(load=load_gains, default=default_gains, example=_example)
load, default, resolve, document, example = GAINS.parts()
