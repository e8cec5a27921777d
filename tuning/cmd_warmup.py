"""Build and cache every compiled kernel of a system in one step (without SYSTEM: of every
system), so that no later command waits for numba.

Each kernel is built through the very entry point the commands use (one short case), so its
machine code is the one they load.  A kernel already in the cache is only loaded (a second
warm-up takes about a second).  The cache directory is $LGW_CACHE_DIR/kernels (default
~/.cache/lgw/kernels); to keep it between CI runs, cache that directory keyed by the lgw,
numba and Python versions, and run ``lgw warmup`` before the tests (docs/sim.md).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from lgw.tuning import vocabulary as V
from lgw.tuning.spec import Options
from lgw.tuning.system import Job, Outcome, System, resolve


@dataclass(frozen=True)
class Options(Options):
    json: bool = V.json_flag()


class _Compiles:
    """Counts numba compilations (``numba:compile`` events) while active."""

    def __init__(self) -> None:
        self.count = 0

    def __enter__(self) -> _Compiles:
        from numba.core import event

        outer = self

        class Listener(event.Listener):
            def on_start(self, e: Any) -> None:
                outer.count += 1

            def on_end(self, e: Any) -> None:
                pass

        self._listener = Listener()
        event.register("numba:compile", self._listener)
        return self

    def __exit__(self, *exc: Any) -> None:
        from numba.core import event

        event.unregister("numba:compile", self._listener)


@dataclass(frozen=True)
class WarmupJob(Job):
    system: str
    kernels: str  # import path of the system's ``warmup_kernels``

    def run(self, progress: Any) -> Outcome:
        from lgw.sim.kernel_cache import cache_dir

        rows = []
        for name, build in resolve(self.kernels)():
            progress.stage(f"building the {name} kernel")
            t0 = time.perf_counter()
            with _Compiles() as c:
                build()
            rows.append({"kernel": name, "seconds": round(time.perf_counter() - t0, 2),
                         "compiled": c.count > 0})
        doc = {"cache": str(cache_dir()), "kernels": rows}
        return Outcome(doc, render=lambda con: _render(con, self.system, doc))


def _render(con: Any, system: str, doc: dict[str, Any]) -> None:
    from lgw.tuning.tables import result_table

    result_table(con, f"{system} kernels", ("kernel", "seconds", "built"),
                 [(r["kernel"], f"{r['seconds']:.1f}", "compiled" if r["compiled"] else
                   "loaded from the cache") for r in doc["kernels"]])
    con.print(f"cache: {doc['cache']}", markup=False, highlight=False)


def plan(opts: Options, system: System) -> WarmupJob:
    return WarmupJob(system.name, system.kernels)
