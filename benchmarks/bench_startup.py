"""Start-up of the command line per system, cold and warm, in one run (a script, not a test).

    python benchmarks/bench_startup.py [--systems mars lunar eros] [--lgw PATH] [--warmup]
                                       [--repeat N] [--before PATH]

For each system, with fresh temporary LGW_CACHE_DIR and NUMBA_CACHE_DIR (nothing compiled
yet), measures the wall time and the CPU time (user + system, of the process and its children)
of
  (1) a first ``lgw simulate SYSTEM ...`` (generates the kernel module, numba compiles it and
      stores the machine code): cold;
  (2) the same command again (imports the cached module, loads the machine code): warm;
and prints cold / warm, which aims to be <= 5.  ``lgw --help`` is timed once.  The
machine is shared (other processes compete for the cores): the CPU seconds are the steadier
number, the wall seconds what a user waits.

--lgw PATH: the ``lgw`` executable to time (e.g. another checkout's venv, for before / after
in one run); --warmup: also time ``lgw warmup SYSTEM`` on an empty cache, then the first
simulate after it; --repeat N: N cold / warm pairs per system (each on a fresh cache), a row
each, the ratio judged on the median pair (on a shared machine one pair can land on a burst of
someone else's load); --before PATH: another ``lgw`` executable (e.g. the previous commit's
venv) timed in the same run, its pair right before each pair of --lgw's, so that both see the
same load: rows labelled "before", and its own largest ratio at the end.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# the first command a user runs per system: a small campaign (mars, eros) or the paper's case
COMMANDS = {
    "mars": ["simulate", "mars", "--dispersion", "table2", "--cases", "100"],
    "lunar": ["simulate", "lunar"],
    "eros": ["simulate", "eros"],
}


def _lgw(path: str | None) -> list[str]:
    if path:
        return [path]
    exe = Path(sys.executable).with_name("lgw")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "lgw.tuning.cli"]


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd: list[str], args: list[str], env: dict[str, str]
          ) -> tuple[float, float, subprocess.CompletedProcess]:
    """(wall s, CPU s, the completed process) of ``cmd + args``."""
    c0 = _cpu()
    t = time.perf_counter()
    p = subprocess.run(cmd + args, env=env, capture_output=True, text=True, check=False)
    dt = time.perf_counter() - t
    if p.returncode != 0:
        raise SystemExit(f"lgw {' '.join(args)} failed ({p.returncode}):\n{p.stderr[-3000:]}")
    return dt, _cpu() - c0, p


def fresh_env(tmp: Path) -> dict[str, str]:
    for d in ("lgw", "numba"):
        shutil.rmtree(tmp / d, ignore_errors=True)
    return dict(os.environ, LGW_CACHE_DIR=str(tmp / "lgw"), NUMBA_CACHE_DIR=str(tmp / "numba"),
                LGW_COMPILE_NOTICE="1")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--systems", nargs="+", choices=tuple(COMMANDS), default=list(COMMANDS))
    ap.add_argument("--lgw", default=None, help="the lgw executable [default: this venv's]")
    ap.add_argument("--repeat", type=int, default=1, help="cold / warm pairs per system")
    ap.add_argument("--warmup", action="store_true",
                    help="also time `lgw warmup SYSTEM` and the simulate after it")
    ap.add_argument("--before", default=None,
                    help="another lgw executable timed in the same run (rows 'before')")
    args = ap.parse_args()
    cmd = _lgw(args.lgw)
    versions = ([("before", [args.before])] if args.before else []) + [("now", cmd)]
    tmp = Path(tempfile.mkdtemp(prefix="lgw-startup-"))
    print(f"lgw: {' '.join(cmd)}"
          + (f"; before: {args.before}" if args.before else "")
          + f"; cpu count {os.cpu_count()}, load average "
          f"{os.getloadavg()[0]:.2f} (shared machine: wall times are upper bounds)")
    try:
        t_help, c_help, _ = timed(cmd, ["--help"], fresh_env(tmp))
        print(f"lgw --help: {t_help:.2f} s wall, {c_help:.2f} s CPU")
        w = 15 if args.before else 8
        print(f"{'system':{w}} {'cold wall':>10} {'cold CPU':>9} {'warm wall':>10} "
              f"{'warm CPU':>9} {'cold/warm wall':>15} {'CPU':>6}   command")
        rows = []
        before_rows = []
        for name in args.systems:
            sim = COMMANDS[name]
            pairs: dict[str, list] = {label: [] for label, _ in versions}
            for _ in range(max(1, args.repeat)):
                for label, exe in versions:
                    env = fresh_env(tmp)
                    t1, c1, p1 = timed(exe, sim, env)
                    t2, c2, p2 = timed(exe, sim, env)
                    hit = not any("compiling" in line for line in p2.stderr.splitlines())
                    pairs[label].append((name, t1, c1, t2, c2))
                    tag = f"{name} ({label})" if args.before else name
                    print(f"{tag:{w}} {t1:9.1f}s {c1:8.1f}s {t2:9.1f}s {c2:8.1f}s "
                          f"{t1 / t2:14.1f}x {c1 / c2:5.1f}x   lgw {' '.join(sim)}  (load "
                          f"{os.getloadavg()[0]:.1f})"
                          + ("" if hit else "   (the warm run compiled: the cache did not hit)"),
                          flush=True)
            for label, got in pairs.items():
                got.sort(key=lambda r: r[1] / r[3])
                (before_rows if label == "before" else rows).append(got[len(got) // 2])
            if args.warmup:
                env = fresh_env(tmp)
                tw, cw, _ = timed(cmd, ["warmup", name], env)
                t3, c3, _ = timed(cmd, sim, env)
                print(f"{'':8} lgw warmup {name}: {tw:.1f} s wall, {cw:.1f} s CPU; then the "
                      f"first simulate {t3:.1f} s wall, {c3:.1f} s CPU")
        how = f"wall{', median pair' if args.repeat > 1 else ''}"
        if before_rows:
            worst = max(r[1] / r[3] for r in before_rows)
            print(f"before: largest cold/warm ({how}) {worst:.1f}x; per system: "
                  + ", ".join(f"{r[0]} {r[1] / r[3]:.1f}x" for r in before_rows))
        worst = max(r[1] / r[3] for r in rows)
        print(f"largest cold/warm ({how}) {worst:.1f}x: "
              f"{'meets' if worst <= 5 else 'MISSES'} the aim of <= 5x; per system: "
              + ", ".join(f"{r[0]} {r[1] / r[3]:.1f}x" for r in rows))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
