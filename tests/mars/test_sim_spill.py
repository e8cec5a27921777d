"""A local campaign kept on disk is flown one spill chunk per thread (``lgw.sim.executors.
map_threads``): the same cases as one call over all of them, in case order."""

from __future__ import annotations

import numpy as np
from lgw.sim import integrate
from lgw.sim.mars import campaign as C
from lgw.sim.mars.batch import ARRAY_FIELDS
from lgw.theory.mars.gains import default_gains


def test_spilled_campaign_on_threads_is_the_campaign_in_memory(monkeypatch) -> None:
    """Chunks of 5 cases on 3 threads (more threads than cores is fine: each thread runs the
    nogil kernel on its own chunk), a random disturbance drawn per case number: every
    per-case array equals the one-call campaign's, case by case."""
    monkeypatch.setattr(C, "SPILL_CHUNK", 5)
    monkeypatch.setattr(integrate, "threads", lambda: 3)
    states = C.table2_states(37, seed=5)
    kw = dict(method="dopri5", disturbance="random", dist_amplitude=0.5, seed=3)
    mem = C.run_campaign(*states, default_gains(), **kw)
    disk = C.run_campaign(*states, default_gains(), spill=True, **kw)
    assert isinstance(disk, C.SpilledResult) and len(disk) == 37
    assert mem.landed.all() and len(np.unique(mem.landing_time)) == 37  # an order slip shows
    for k in (*ARRAY_FIELDS, "r0", "v0", "m0"):
        a, b = np.asarray(getattr(disk, k)), np.asarray(getattr(mem, k))
        assert a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), k
    disk.close()
