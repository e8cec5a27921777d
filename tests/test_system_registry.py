"""The registry of systems: every system is laid out alike (its parts at the standard paths,
each verb implemented or not applicable with a reason), described by a card shipped as package
data, and a card or a registration that is wrong is refused by name."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest
from lgw.theory.errors import ParameterError
from lgw.tuning.system import (
    VERBS,
    NotApplicable,
    all_systems,
    check_consistent,
    laid_out_system,
    resolve,
    system_of_card,
)

ROOT = Path(__file__).resolve().parents[1]


def test_every_system_is_consistent_and_laid_out_alike():
    assert check_consistent() == []
    for s in all_systems():
        assert list(s.verbs) == [v for v in VERBS if v in s.verbs]
        assert s.gains == f"lgw.tuning.{s.name}.gainset"
        for part in (s.claims, s.interop, s.kernels):
            assert resolve(part) is not None
        for verb, v in s.verbs.items():
            if isinstance(v, NotApplicable):
                assert v.reason
            elif verb != "warmup":
                assert v.module == f"lgw.tuning.{s.name}.cmd_{verb}" and v.help


def test_cards_are_shipped_as_package_data():
    setup = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    for s in all_systems():
        card = ROOT / "tuning" / s.name / "data" / "system.toml"
        assert card.is_file()
        assert f"lgw.tuning.{s.name}" in setup["packages"]
        assert "data/*.toml" in setup["package-data"][f"lgw.tuning.{s.name}"]


CARD = {"seed": "009", "title": "t", "summary": "s", "verbs": {"bounds": "b"},
        "not_applicable": {"optimal": "why"}}


def test_a_card_describes_its_system():
    s = system_of_card("toy", CARD, "toy card")
    assert s.verbs["bounds"].module == "lgw.tuning.toy.cmd_bounds"
    assert s.verbs["optimal"] == NotApplicable("why")
    assert s.verbs["warmup"].module == "lgw.tuning.cmd_warmup"


@pytest.mark.parametrize("card, name", [
    ({**CARD, "titel": "typo"}, "titel"),
    ({**CARD, "not_applicable": {"bounds": "why"}}, "bounds"),
    ({**CARD, "verbs": {"bound": "b"}}, "bound"),
])
def test_a_wrong_card_is_refused_by_name(card, name):
    with pytest.raises(ParameterError, match=name):
        system_of_card("toy", card, "toy card")


def test_an_unknown_verb_is_refused():
    with pytest.raises(ParameterError, match="simulat"):
        laid_out_system("toy", "009", "t", "s", simulat="typo")
