"""Start-up of the command line, in one run, in a fresh environment (a script, not a test).

    python benchmarks/bench_startup.py [--cases 100]

With fresh temporary LGW_CACHE_DIR and NUMBA_CACHE_DIR (nothing compiled yet), measures the
wall time of
  (1) ``lgw --help``;
  (2) a first ``lgw simulate mars --dispersion table2 --cases N`` (generates the kernel module,
      numba compiles it and stores the machine code);
  (3) the same command again (imports the cached module, loads the machine code);
and prints the ratio (2)/(3), which issue 12 asks to be >= 5.  The compile notice of (2) is
shown (LGW_COMPILE_NOTICE=1: stderr is captured here, not a terminal).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def _lgw() -> list[str]:
    exe = Path(sys.executable).with_name("lgw")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "lgw.tuning.cli"]


def timed(args: list[str], env: dict[str, str]) -> tuple[float, subprocess.CompletedProcess]:
    t = time.perf_counter()
    p = subprocess.run(_lgw() + args, env=env, capture_output=True, text=True, check=False)
    dt = time.perf_counter() - t
    if p.returncode != 0:
        raise SystemExit(f"lgw {' '.join(args)} failed ({p.returncode}):\n{p.stderr}")
    return dt, p


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=100)
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="lgw-startup-"))
    env = dict(os.environ, LGW_CACHE_DIR=str(tmp / "lgw"), NUMBA_CACHE_DIR=str(tmp / "numba"),
               LGW_COMPILE_NOTICE="1")
    sim = ["simulate", "mars", "--dispersion", "table2", "--cases", str(args.cases)]
    try:
        t_help, _ = timed(["--help"], env)
        t_first, p1 = timed(sim, env)
        t_second, p2 = timed(sim, env)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"fresh caches under {tmp} (removed afterwards); cpu count {os.cpu_count()}")
    print(f"lgw --help                      {t_help:7.2f} s")
    print(f"lgw {' '.join(sim)} (first)  {t_first:7.2f} s")
    for line in p1.stderr.splitlines():
        if "compil" in line:
            print(f"    stderr: {line}")
    print(f"lgw {' '.join(sim)} (second) {t_second:7.2f} s")
    if any("compiling" in line for line in p2.stderr.splitlines()):
        print("    stderr of the second run says it compiled: the cache did not hit")
    ratio = t_first / t_second
    print(f"first / second = {ratio:.1f}x ({'meets' if ratio >= 5 else 'MISSES'} the >= 5x "
          "of issue 12)")


if __name__ == "__main__":
    main()
