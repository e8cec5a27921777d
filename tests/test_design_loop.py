"""docs/design-loop.md as a user runs it: every command of each system's block, in a fresh
folder, through the shell with the installed ``lgw`` on PATH.  A line ending in ``# exit N:
TEXT`` must exit N and print TEXT (the named promise a broken certificate fails on); any other
line must exit 0.  After the block, the report of the tuned file is about the tuned gains and
judges claims of scope gain-set.

eros (38 s under load) is the default suite's representative; lunar and mars are slow (their tuners
and the mars report of all 69 claims take minutes on a 2-core machine)."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

DOC = Path(__file__).parents[1] / "docs" / "design-loop.md"
EXPECT = re.compile(r"\s+#\s*exit (\d+)(?::\s*(.*))?$")


def blocks() -> dict[str, list[str]]:
    """System -> the command lines of the ```sh block under its ``## system`` heading."""
    out: dict[str, list[str]] = {}
    system, inside = None, False
    for line in DOC.read_text().splitlines():
        if line.startswith("## "):
            system = line[3:].split(":")[0].strip()
        elif line.startswith("```sh"):
            inside = True
            out[system] = []
        elif line.startswith("```"):
            inside = False
        elif inside and line.strip() and not line.lstrip().startswith("#"):
            out[system].append(line)
    return out


def _run(line: str, cwd: Path) -> tuple[str, int, str | None, subprocess.CompletedProcess]:
    m = EXPECT.search(line)
    cmd = line[:m.start()] if m else line
    code, text = (int(m.group(1)), m.group(2)) if m else (0, None)
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}"
           f"{os.environ.get('PATH', '')}", "COLUMNS": "200"}
    r = subprocess.run(["bash", "-c", cmd], cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=1800)
    return cmd, code, text, r


def _report_is_about_the_tuned_gains(cwd: Path, system: str) -> None:
    tuned = tomllib.loads((cwd / f"{system}.toml").read_text())
    doc = json.loads((cwd / f"{system}-report.json").read_text())
    assert doc["command"] == f"report {system}"
    for table in ("gains", "orbit", "attitude"):
        if table in tuned:
            shown = doc["gains"] if table == "gains" else doc["gains"][table]
            assert {k: shown[k] for k in tuned[table]} == tuned[table], table
    judged = [c for c in doc["claims"] if c["scope"] == "gain-set"]
    assert judged and all(c["verdict"] for c in judged)


def test_every_system_has_a_block_with_tune_verify_a_broken_file_and_report():
    b = blocks()
    assert set(b) == {"mars", "lunar", "eros"}
    for system, lines in b.items():
        verbs = [ln.split()[1] for ln in lines if ln.startswith("lgw ")]
        assert verbs[0] == "tune" and "verify" in verbs and verbs[-1] == "report", system
        assert any(EXPECT.search(ln) for ln in lines), f"{system}: no broken certificate"


@pytest.mark.parametrize("system", [
    "eros",
    pytest.param("lunar", marks=pytest.mark.slow),
    pytest.param("mars", marks=pytest.mark.slow),
])
def test_the_loop_runs_as_written(system, tmp_path):
    for line in blocks()[system]:
        cmd, code, text, r = _run(line, tmp_path)
        out = r.stdout + r.stderr
        assert r.returncode == code, f"{cmd}: exit {r.returncode}, expected {code}\n{out}"
        assert "Traceback" not in out, cmd
        if text:
            assert text in " ".join(out.split()), f"{cmd}: {text!r} not printed\n{out}"
    _report_is_about_the_tuned_gains(tmp_path, system)
