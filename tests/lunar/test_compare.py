"""``lgw compare lunar``: the paper's comparison (failure and saturation on and off, ideal
against coupled pointing), each run checked at dt/4, with its JSON document."""

from __future__ import annotations

import json

from click.testing import CliRunner
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.commands import make_command
from lgw.tuning.lunar import compare as C
from lgw.tuning.system import get_system


def test_conditions_change_what_is_flown():
    rows = C.run_conditions(paper_gains(), RunOptions(dt=1 / 160, t_end=30.0))
    assert len(rows) == 8
    by = {(r.condition, r.pointing): r for r in rows}
    s5 = C.CONDITIONS[3][0]
    free = C.CONDITIONS[0][0]
    # without the saturations the command is never limited; with them it is at the start
    assert by[(free, "ideal")].numbers["orbit_saturated_s"] == 0.0
    assert by[(s5, "ideal")].numbers["orbit_saturated_s"] > 0.0
    assert by[(free, "ideal")].opts.thrust_max == C.UNSATURATED
    assert by[(s5, "coupled")].opts.thrust_pointing == "coupled"
    for r in rows:
        d = r.to_dict()
        assert d["convergence"]["refined_dt"] == r.opts.dt / 4
    assert any("Section 5" in f for f in C.findings(rows))


def test_cli_json_document_head():
    cmd = make_command(get_system("lunar"), "compare")
    r = CliRunner().invoke(cmd, ["--no-sweep", "--dt", "0.0125", "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert list(doc)[:3] == ["lgw_version", "command", "gains"]
    assert doc["command"] == "compare lunar" and len(doc["rows"]) == 8
    assert {"condition", "pointing", "eh_final_m", "converged"} <= set(doc["rows"][0])
