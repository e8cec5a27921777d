"""A large ``lgw simulate mars`` campaign with ``--json``: the encoding of the case records
against the per-record baseline in the same run, then the command end to end (a script, not a
test; docs/sim.md, "Campaigns and executors").

    python benchmarks/bench_million.py [--encode-cases 20000] [--cli-cases 1000000]
                                       [--methods rk4 dopri5] [--out FILE] [--no-cli]
                                       [--no-encoding] [--stages]

encoding  one campaign (dopri5, Table II) flown once and kept on disk as the CLI keeps it;
          its case records encoded as the document's ``cases`` array by (a) the baseline, one
          ``json.dumps`` per record dict (``iter_case_records``), and (b) ``CaseJson``, column by
          column: seconds and cases/s of each, (b)/(a), and that the two parse to the same
          records;
cli       ``lgw simulate mars --dispersion table2 --cases N --json [--method M]`` > FILE under
          ``/usr/bin/time -v``: wall seconds, CPU seconds, peak resident memory, bytes written,
          with the load average before and after (a shared machine: the load says what the
          times mean);
stages    (``--stages``) the same command in a child process with a clock on each stage:
          start-up (imports, options), the flight, the convergence check, the summary, and
          the writing of the document (the case encoding's own share of it, which a writer
          thread overlaps with the writing), wall and CPU (user, system) seconds of each.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import tempfile
import time
from pathlib import Path


def encoding(n: int) -> None:
    from lgw.sim.mars.campaign import CaseJson, iter_case_records, run_campaign, table2_states
    from lgw.theory.mars.gains import default_gains

    res = run_campaign(*table2_states(n, seed=0), default_gains(), method="dopri5",
                       spill=True)
    t = time.process_time()  # CPU seconds: a shared machine's load matters less
    base = ",".join(json.dumps(rec, allow_nan=False) for rec in iter_case_records(res))
    ta = time.process_time() - t
    t = time.process_time()
    new = b",".join(CaseJson(res)).decode("ascii")
    tb = time.process_time() - t
    same = json.loads(f"[{base}]", object_pairs_hook=list) == json.loads(
        f"[{new}]", object_pairs_hook=list)
    print(f"encoding {n} case records (load {os.getloadavg()[0]:.2f}):")
    print(f"  (a) json.dumps per record   {ta:7.2f} s CPU  {n / ta:10.0f} cases/s  "
          f"{len(base) / n:6.0f} bytes/case")
    print(f"  (b) CaseJson, by column     {tb:7.2f} s CPU  {n / tb:10.0f} cases/s  "
          f"{len(new) / n:6.0f} bytes/case")
    print(f"  (b)/(a) = {ta / tb:.1f}x; same records when parsed: {same}", flush=True)
    res.close()


def cli(n: int, method: str, out: Path) -> None:
    cmd = ["lgw", "simulate", "mars", "--dispersion", "table2", "--cases", str(n), "--json"]
    if method != "rk4":
        cmd += ["--method", method]
    load0 = os.getloadavg()[0]
    with open(out, "w") as f:
        p = subprocess.run(["/usr/bin/time", "-v", *cmd], stdout=f, stderr=subprocess.PIPE,
                           text=True, check=False)
    load1 = os.getloadavg()[0]
    err = p.stderr
    wall = re.search(r"Elapsed \(wall clock\) time.*: (.*)", err).group(1)
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", err).group(1))
    cpu = sum(float(re.search(rf"{k} time \(seconds\): ([\d.]+)", err).group(1))
              for k in ("User", "System"))
    print(f"cli {' '.join(cmd)}: exit {p.returncode}, wall {wall}, CPU {cpu:.1f} s, peak "
          f"{rss / 1024:.0f} MB, {out.stat().st_size / 1e9:.2f} GB written (load "
          f"{load0:.2f} before, {load1:.2f} after)", flush=True)


STAGES = (("start-up", None), ("flight", ("lgw.sim.mars.campaign", "run_campaign")),
          ("convergence check", ("lgw.sim.mars.converged", "check")),
          ("summary", ("lgw.sim.mars.campaign", "summarize")),
          ("document written", ("lgw.tuning.io", "write_json_document")))


def _stages_child(args: list[str]) -> None:
    """Run ``lgw`` with ``args`` in this process, a clock around each stage (STAGES); the
    breakdown goes to stderr as one line per stage: name, wall, user, system seconds."""
    import functools
    import importlib
    import resource
    import sys

    t0 = time.perf_counter()
    marks: list[tuple[str, float, float, float]] = []

    def mark(name: str) -> None:
        ru = resource.getrusage(resource.RUSAGE_SELF)
        marks.append((name, time.perf_counter() - t0, ru.ru_utime, ru.ru_stime))

    from lgw.tuning import cli as lgw_cli

    def timed(label: str, f):
        @functools.wraps(f)
        def g(*a, **k):
            mark(label + " start")
            try:
                return f(*a, **k)
            finally:
                mark(label + " end")
        return g

    for label, where in STAGES[1:]:
        mod = importlib.import_module(where[0])
        setattr(mod, where[1], timed(label, getattr(mod, where[1])))
    from lgw.sim.mars import campaign

    enc = [0.0]
    orig = campaign.CaseJson.__iter__

    def encode(self):
        it = orig(self)
        while True:
            t = time.perf_counter()
            try:
                x = next(it)
            except StopIteration:
                return
            finally:
                enc[0] += time.perf_counter() - t
            yield x

    campaign.CaseJson.__iter__ = encode
    try:
        lgw_cli.main(args)
    except SystemExit as e:
        if e.code:
            raise
    mark("end")
    ru = resource.getrusage(resource.RUSAGE_SELF)
    first = dict((m[0], m) for m in marks)
    prev = (0.0, 0.0, 0.0)
    rows = []
    for label, _ in STAGES:
        end = first.get(f"{label} end") if label != "start-up" else \
            first.get(f"{STAGES[1][0]} start")
        if end is None:
            continue
        rows.append((label, end[1] - prev[0], end[2] - prev[1], end[3] - prev[2]))
        prev = end[1:]
    end = first["end"]
    rows.append(("rest (exit)", end[1] - prev[0], end[2] - prev[1], end[3] - prev[2]))
    for name, wall, user, system in rows:
        print(f"STAGE {name}|{wall:.2f}|{user:.2f}|{system:.2f}", file=sys.stderr)
    print(f"STAGE   of which case encoding (while writing)|{enc[0]:.2f}||", file=sys.stderr)
    print(f"STAGE total|{end[1]:.2f}|{ru.ru_utime:.2f}|{ru.ru_stime:.2f}|"
          f"{ru.ru_maxrss / 1024:.0f}", file=sys.stderr)


def stages(n: int, method: str, out: Path) -> None:
    import sys

    cmd = ["simulate", "mars", "--dispersion", "table2", "--cases", str(n), "--json"]
    if method != "rk4":
        cmd += ["--method", method]
    load0 = os.getloadavg()[0]
    with open(out, "w") as f:
        p = subprocess.run([sys.executable, __file__, "--stages-child", *cmd], stdout=f,
                           stderr=subprocess.PIPE, text=True, check=False)
    rows = [line[6:].split("|") for line in p.stderr.splitlines() if line.startswith("STAGE ")]
    print(f"stages of lgw {' '.join(cmd)} (exit {p.returncode}; load {load0:.2f} before, "
          f"{os.getloadavg()[0]:.2f} after):")
    print(f"  {'stage':46s} {'wall s':>8s} {'user s':>8s} {'sys s':>8s}")
    for r in rows:
        print(f"  {r[0]:46s} {r[1]:>8s} {r[2]:>8s} {r[3]:>8s}"
              + (f"   peak {r[4]} MB" if len(r) > 4 else ""))
    if p.returncode:
        print(p.stderr[-2000:])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--encode-cases", type=int, default=20000)
    ap.add_argument("--cli-cases", type=int, default=1_000_000)
    ap.add_argument("--methods", nargs="+", choices=("rk4", "dopri5"),
                    default=["rk4", "dopri5"])
    ap.add_argument("--out", type=Path, default=None, help="where the document goes "
                    "(default: a temporary file, removed)")
    ap.add_argument("--no-cli", action="store_true")
    ap.add_argument("--no-encoding", action="store_true")
    ap.add_argument("--stages", action="store_true", help="also the stage breakdown of the "
                    "command (a second run of it)")
    a = ap.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    if not a.no_encoding:
        encoding(a.encode_cases)
    with tempfile.TemporaryDirectory() as d:
        for m in a.methods:
            if not a.no_cli:
                cli(a.cli_cases, m, a.out or Path(d) / "cases.json")
            if a.stages:
                stages(a.cli_cases, m, a.out or Path(d) / "cases.json")


if __name__ == "__main__":
    import sys

    if sys.argv[1:2] == ["--stages-child"]:
        _stages_child(sys.argv[2:])
    else:
        main()
