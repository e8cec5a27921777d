"""Seed 000's gain set as the shared commands see it: load, default, document, example
(``lgw.tuning.gainset``).  The document's head is ``gains``, and ``disturbance`` when the file
has it (``Gains.to_dict``)."""

from __future__ import annotations

from lgw.theory.mars.gains import default_gains, gains_from_dict, gains_to_toml, load_gains
from lgw.tuning.gainset import GainSet


def _example() -> str:
    """A valid gain set other than the default (TOML), for the options test."""
    d = default_gains().to_dict()
    d["gains"]["beta1"] = [3.1, 2.8, 2.9]
    d["gains"]["alpha1"] = 0.6
    return gains_to_toml(gains_from_dict(d))


GAINS = GainSet(load=load_gains, default=default_gains, example=_example)
load, default, resolve, document, example = GAINS.parts()
