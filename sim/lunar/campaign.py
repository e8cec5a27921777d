"""Seed 001 campaigns in flat memory: the cases flown ``CHUNK`` at a time.

A lunar case's summary (``lgw.sim.lunar.scenario.summarize``: saturation times, largest errors,
adaptive estimates, L2 norms) is computed from its recorded signals, and the recording is large
(every ``record_every``-th RK4 node of 30 states and the auxiliary signals: about 1 MB per case
at the default dt over the Section 5 horizon).  Flying N cases at once held N recordings and N
summary dicts.  Here each chunk is flown, summarised case by case, its records written to a
temporary file as JSON text, and its recording dropped; what stays in memory is one chunk's
recording, the outcome counts, the first ``keep`` records (the terminal table) and the first
chunk's run (figures show case 0).  Every case is integrated on its own (``lgw.sim.integrate``),
so a case's record does not depend on the chunking; its case index in ``flagged`` is the
campaign's, not the chunk's.
"""

from __future__ import annotations

import json
import shutil
import tempfile
import weakref
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

CHUNK = 64  # cases flown and recorded at a time


class Campaign:
    """The records of a campaign on disk (``iter_json``), with what the command shows."""

    def __init__(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="lgw-lunar-"))
        self._finalizer = weakref.finalize(self, shutil.rmtree, str(self.folder), True)
        self.path = self.folder / "records.jsonl"
        self.n = 0
        self.outcomes: dict[str, int] = {}
        self.first_records: list[dict[str, Any]] = []
        self.first_run: tuple[Any, Any] | None = None  # (BatchResult, Context) of chunk 0

    def add(self, records: list[dict[str, Any]], outcomes: dict[str, int], keep: int) -> None:
        with open(self.path, "a", encoding="utf-8") as f:
            f.write(",".join(json.dumps(r, allow_nan=False) for r in records) + "\n")
        for k, v in outcomes.items():
            self.outcomes[k] = self.outcomes.get(k, 0) + v
        self.first_records += records[:max(0, keep - len(self.first_records))]
        self.n += len(records)

    def __iter__(self) -> Iterator[str]:
        """The records as JSON text, one chunk at a time (items of a JSON array joined by
        ","), read from disk afresh at each iteration: ``Stream(encoded=campaign)`` may be
        written twice (--json and --out)."""
        with open(self.path, encoding="utf-8") as f:
            for line in f:
                yield line.rstrip("\n")

    def close(self) -> None:
        self._finalizer()


def fly(ref: Any, gains: Any, opts: Any, states: tuple[np.ndarray, np.ndarray, np.ndarray],
        *, record_every: int, keep: int, chunk: int = CHUNK) -> Campaign:
    """Fly the cases ``states`` = (dh (N,), dv (3, N), Q0 (4, N)) with the run options
    ``opts`` (``lgw.sim.lunar.closed_loop.RunOptions``) and one gain set, ``chunk`` at a time;
    each case's record is its summary and its kernel results (``case_record``)."""
    from lgw.sim.lunar.batch import rk4_batch
    from lgw.sim.lunar.closed_loop import initial_state, make_context
    from lgw.sim.lunar.outcomes import case_record, counts, json_safe
    from lgw.sim.lunar.scenario import summarize

    dh, dv, q0 = states
    camp = Campaign()
    for a in range(0, len(dh), chunk):
        sl = slice(a, min(a + chunk, len(dh)))
        k = sl.stop - sl.start
        ctx = make_context(ref, [gains] * k, opts)
        x0 = initial_state(ref, dh[sl], dv[:, sl], q0[:, sl], np.zeros((3, k)), [gains] * k)
        res = rk4_batch(ctx, x0, record_every=record_every)
        records = []
        for i in range(k):
            num = dict(summarize(res, ctx, i).numbers)
            num["flagged"] = [(a + f[0], *f[1:]) for f in num["flagged"]]
            records.append(json_safe({**num, **case_record(res.cases, i)}))
        camp.add(records, counts(res.cases["outcome"]), keep)
        if camp.first_run is None:
            camp.first_run = (res, ctx)
    return camp
