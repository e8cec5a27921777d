"""A large ``lgw simulate mars`` campaign with ``--json``: the encoding of the case records
against the per-record baseline in the same run, then the command end to end (a script, not a
test; docs/sim.md, "Campaigns and executors").

    python benchmarks/bench_million.py [--encode-cases 20000] [--cli-cases 1000000]
                                       [--methods rk4 dopri5] [--out FILE] [--no-cli]

encoding  one campaign (dopri5, Table II) flown once and kept on disk as the CLI keeps it;
          its case records encoded as the document's ``cases`` array by (a) the baseline, one
          ``json.dumps`` per record dict (``iter_case_records``), and (b) ``CaseJson``, column by
          column: seconds and cases/s of each, (b)/(a), and that the two parse to the same
          records;
cli       ``lgw simulate mars --dispersion table2 --cases N --json [--method M]`` > FILE under
          ``/usr/bin/time -v``: wall seconds, peak resident memory, bytes written, with the
          load average before and after (a shared machine: the load says what the times mean).
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--encode-cases", type=int, default=20000)
    ap.add_argument("--cli-cases", type=int, default=1_000_000)
    ap.add_argument("--methods", nargs="+", choices=("rk4", "dopri5"),
                    default=["rk4", "dopri5"])
    ap.add_argument("--out", type=Path, default=None, help="where the document goes "
                    "(default: a temporary file, removed)")
    ap.add_argument("--no-cli", action="store_true")
    a = ap.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}")
    encoding(a.encode_cases)
    if a.no_cli:
        return
    with tempfile.TemporaryDirectory() as d:
        for m in a.methods:
            cli(a.cli_cases, m, a.out or Path(d) / "cases.json")


if __name__ == "__main__":
    main()
