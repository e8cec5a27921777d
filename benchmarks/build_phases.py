"""Where a cold kernel build goes, per compiled function and per numba pass (a script, not a test).

    python benchmarks/build_phases.py [--system mars|lunar|eros] [--top N]

Runs the first ``lgw simulate SYSTEM`` of ``bench_startup.py`` in this process, with fresh
temporary LGW_CACHE_DIR and NUMBA_CACHE_DIR (nothing compiled yet), and prints

  * the CPU seconds of the whole command and of numba's compilation in it;
  * each compiled function's own CPU seconds (its ``numba:compile`` event minus the ones
    nested in it: a callee numba compiles while typing its caller is the callee's), largest
    first;
  * the kernel's numba passes, from ``overloads[sig].metadata["pipeline_times"]`` (these
    include the callees compiled inside a pass, e.g. during type inference).

With ``--system mars --law printed`` after a run of the default law, the shared hooks are
already cached and the kernel's passes are its own (the first build's include the hooks).
The machine is shared: single numbers vary by +-25 %; compare within one run.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import tempfile
import time
from collections import defaultdict
from pathlib import Path

COMMANDS = {
    "mars": ["simulate", "mars", "--dispersion", "table2", "--cases", "100"],
    "lunar": ["simulate", "lunar"],
    "eros": ["simulate", "eros"],
}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--system", choices=tuple(COMMANDS), default="mars")
    ap.add_argument("--law", default=None, help="mars: the law (a second law's kernel alone: "
                    "run it with --cache DIR after the default law)")
    ap.add_argument("--cache", default=None, help="an existing cache directory to start from")
    ap.add_argument("--top", type=int, default=15, help="functions listed")
    args = ap.parse_args()
    tmp = Path(args.cache or tempfile.mkdtemp(prefix="lgw-phases-"))
    os.environ["LGW_CACHE_DIR"] = str(tmp / "lgw")
    os.environ["NUMBA_CACHE_DIR"] = str(tmp / "numba")

    import numba  # after the cache directories are set
    from numba.core import event

    made: dict[str, object] = {}
    njit = numba.njit

    def recording_njit(*a, **k):  # the dispatchers by name, for their pass timers
        d = njit(*a, **k)
        if a and callable(a[0]):
            made[a[0].__name__] = d
        return d

    numba.njit = recording_njit
    own: dict[str, float] = defaultdict(float)
    stack: list[list] = []

    class Listener(event.Listener):
        def on_start(self, ev):
            d = ev.data.get("dispatcher")
            stack.append([getattr(getattr(d, "py_func", None), "__qualname__", str(d)),
                          time.process_time(), 0.0])

        def on_end(self, ev):
            name, t0, nested = stack.pop()
            dt = time.process_time() - t0
            own[name] += dt - nested
            if stack:
                stack[-1][2] += dt

    event.register("numba:compile", Listener())
    from lgw.tuning.cli import main as lgw

    argv = COMMANDS[args.system] + (["--law", args.law] if args.law else [])
    t = time.process_time()
    try:
        with contextlib.redirect_stdout(io.StringIO()):  # the command's own output
            lgw(argv)
    except SystemExit as e:
        if e.code not in (0, None):
            raise
    total = time.process_time() - t
    print(f"lgw {' '.join(argv)}: {total:.2f} s CPU in process, numba's compilation "
          f"{sum(own.values()):.2f} s of it (cache {tmp})")
    for name, s in sorted(own.items(), key=lambda x: -x[1])[:args.top]:
        print(f"  {s:6.2f} s  {name}")
    kernel = made.get("kernel")
    for ov in getattr(kernel, "overloads", {}).values():
        for pipe, passes in ov.metadata.get("pipeline_times", {}).items():
            times = sorted(((v.init + v.run + v.finalize, k.split("_", 1)[1])
                            for k, v in passes.items()), reverse=True)
            print(f"kernel, {pipe} pipeline: {sum(x for x, _ in times):.2f} s; "
                  + ", ".join(f"{k} {x:.2f}" for x, k in times[:8]))


if __name__ == "__main__":
    main()
