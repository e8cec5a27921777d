"""Seed 002's claims: every verdict computed, every refutation carries a confirmed witness, and
the coverage table names only existing claims."""

from __future__ import annotations

from lgw.theory.eros.claims import all_claims
from lgw.theory.eros.coverage import COVERAGE
from lgw.theory.evidence import VERDICTS

SCENARIO_IDS = {"tracked-times", "fastest-sign", "fastest-tanh", "abs-error-sign",
                "abs-error-tanh", "chatter-fuzzy", "chatter-tanh"}


def test_claims_have_computed_verdicts_and_witnesses():
    claims = all_claims()
    ids = [c.id for c in claims]
    assert len(ids) == len(set(ids))
    for c in claims:
        assert c.verdict in VERDICTS
        assert c.steps, c.id
        if c.verdict == "refuted":
            w = c.counterexample
            assert w is not None and w.confirmed, c.id
        c.to_dict()  # serialisable


def test_coverage_names_existing_claims():
    known = {c.id for c in all_claims()} | SCENARIO_IDS
    for item, _what, ids, note in COVERAGE:
        assert ids or note.startswith("not checkable, because"), item
        for n in ids:
            assert n in known, (item, n)
    # every claim is covered somewhere
    covered = {n for _i, _w, ids, _n in COVERAGE for n in ids}
    assert known <= covered, known - covered
