"""Seed 001 campaigns flown a chunk at a time (lgw.sim.lunar.campaign): the records do not
depend on the chunking, case indices stay the campaign's, and the records on disk can be read
any number of times (a document written to --out and to stdout)."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
from lgw.sim.lunar import campaign
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.sim.lunar.reference import reference
from lgw.theory.lunar.gains import paper_gains
from lgw.tuning.lunar.cmd_simulate import random_cases


def _records(camp: campaign.Campaign) -> list[dict]:
    return json.loads("[" + ",".join(t for t in camp if t) + "]")


def _close(a, b, path="") -> None:
    """Equal, floats to 1e-12 relative: the L2 norms (lgw.sim.lunar.batch.l2_norm) are numpy
    reductions over the cases flown together, whose summation order depends on how many there
    are (pairwise along a contiguous axis): the last bit moves with the chunk."""
    if isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            _close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _close(x, y, f"{path}[{i}]")
    elif isinstance(a, float):
        assert math.isclose(a, b, rel_tol=1e-12), (path, a, b)
    else:
        assert a == b, (path, a, b)


def test_records_do_not_depend_on_the_chunk() -> None:
    ref = reference()
    # 3 kg of propellant: every case runs dry and is flagged (its index is checked)
    opts = replace(RunOptions(), t_end=6.0, m_dry=float(ref.state(0.0)[4]) - 3.0)
    states = random_cases(5, 4)
    one = campaign.fly(ref, paper_gains(), opts, states, record_every=2, keep=3, chunk=64)
    two = campaign.fly(ref, paper_gains(), opts, states, record_every=2, keep=3, chunk=2)
    a, b = _records(one), _records(two)
    assert len(a) == len(b) == 5 == one.n == two.n
    _close(a, b)
    assert _records(two) == b  # read again: the same records
    assert one.outcomes == two.outcomes and sum(one.outcomes.values()) == 5
    assert two.first_records == b[:3]
    for i, rec in enumerate(b):
        assert all(f[0] == i for f in rec["flagged"]), rec["flagged"]
    assert all(rec["flagged"] for rec in b), "a case that ran dry is not flagged"
    res, _ctx = two.first_run
    assert res.out["eh"].shape[-1] == 2  # the first chunk only is kept
    assert np.isfinite(res.out["eh"][:, 0]).all()
