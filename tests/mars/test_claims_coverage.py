"""The coverage table of seed 000: no empty row, every claim it names exists, every claim is
named by some row, and every numbered equation of the paper has a row."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from lgw.theory.mars.claims import all_claims
from lgw.theory.mars.coverage import coverage
from lgw.theory.mars.gains import default_gains

# with pytest-xdist (--dist loadgroup), on the worker that derives seed 000's claims once
pytestmark = pytest.mark.xdist_group("mars-claims")

# the papers sit in shared/ beside the repository (../shared/seeds from its root)
SEEDS = Path(__file__).resolve().parents[3] / "shared" / "seeds"
SEED = next(iter(sorted(SEEDS.glob("000_*.txt"))), None) if SEEDS.exists() else None


def test_no_row_is_empty_and_every_claim_exists():
    ids = {c.id for c in all_claims(default_gains())}
    for row in coverage():
        assert row.item and row.kind, row
        assert bool(row.claims) != bool(row.not_checkable), row  # one or the other, not both
        for cid in row.claims:
            assert cid in ids, (row.item, cid)


def test_every_claim_is_covered():
    named = {cid for row in coverage() for cid in row.claims}
    missing = {c.id for c in all_claims(default_gains())} - named
    # claims not printed in the paper are covered through the rows they sharpen
    assert not missing, missing


def test_every_numbered_equation_has_a_row():
    items = " ".join(r.item for r in coverage())
    for n in range(1, 48):
        assert f"({n})" in items, n
    if SEED is not None:  # and no equation number beyond those the paper has
        text = SEED.read_text()
        assert "(47)" in text and "(48)" not in text
    assert re.search(r"Remark 1\b", items) and "Remark 2" in items
    for name in ("Lemma 1", "Lemma 2", "Theorem 1", "Theorem 2", "Theorem 3", "Theorem 4",
                 "Definition 1", "Hypothesis 1", "Table I", "Table II", "Table III"):
        assert name in items, name
