"""``lgw compare eros``: the six controllers on Table 2's metrics against the printed numbers,
the ranking judged per switching function, every metric against the dopri5 reference."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from lgw.tuning.commands import make_command
from lgw.tuning.eros import compare as C
from lgw.tuning.system import get_system


def test_rankings_follow_the_numbers():
    class R:
        def __init__(self, law, sw, tt, iae):
            self.law, self.switch, self.numbers = law, sw, {"t_track_all": tt, "iae": iae}

    rows = [R("pdsmc", sw, 8.0, 300.0) for sw in ("sign", "tanh")]
    rows += [R("ftsmc", sw, 5.0, 200.0) for sw in ("sign", "tanh")]
    rows += [R("fuzzy", "sign", 4.0, 250.0), R("fuzzy", "tanh", 6.0, 100.0)]
    got = {(k["metric"], k["switch"]): k for k in C.rankings(rows)}
    assert got[("t_track_all", "sign")]["holds"] and got[("iae", "tanh")]["holds"]
    assert not got[("iae", "sign")]["holds"]  # fuzzy 250 > FTSMC 200
    assert got[("iae", "sign")]["margin"] == -50.0
    assert not got[("t_track_all", "tanh")]["holds"]


@pytest.mark.slow
def test_cli_six_variants_with_printed_numbers():
    """12 runs of 15 s (RK4 and the dopri5 reference at 1e-10 for six variants)."""
    cmd = make_command(get_system("eros"), "compare")
    r = CliRunner().invoke(cmd, ["--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert list(doc)[:3] == ["lgw_version", "command", "gains"]
    assert doc["command"] == "compare eros"
    names = [row["variant"] for row in doc["rows"]]
    assert names == ["pdsmc-sign", "pdsmc-tanh", "ftsmc-sign", "ftsmc-tanh", "fuzzy-sign",
                     "fuzzy-tanh"]
    row = doc["rows"][4]
    assert row["paper_abs_error"] == 113.4074 and row["paper_tracked_s"] == 4.0
    assert row["iae"] > 0 and row["iae_int"] > 0 and "iae_converged" in row
    assert len(doc["rankings"]) == 4
