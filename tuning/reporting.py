"""``lgw report SYSTEM``, written once: the system builds the parts (claims judged for the gain
set, the report spec, the computed sections with their figures, the coverage table); this
module renders Markdown, LaTeX, HTML and claims.json from them, writes them with every figure
as one atomic set, prints the verdict counts (the paper's statements and the workbench's
own, apart) or the claims as JSON.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lgw.theory.errors import ParameterError
from lgw.tuning import vocabulary as V
from lgw.tuning.spec import Options
from lgw.tuning.system import Job, Outcome, resolve


@dataclass(frozen=True)
class ReportParts:
    """What a system's report builder returns."""

    claims: Sequence[Any]
    spec: Any  # lgw.theory.report.ReportSpec
    sections: Sequence[Any] = ()
    coverage: Sequence[Any] | None = None


@dataclass(frozen=True)
class ReportOptions(Options):
    """The options every ``lgw report SYSTEM`` takes (a system adds its own)."""

    gains: Path | None = V.gains()
    json: bool = V.json_flag()
    out: Path | None = V.out_dir("report.md, report.tex, report.html, claims.json and the "
                                 "figures (needed unless --json)")

    def check(self) -> None:
        super().check()
        if self.out is None and not self.json:
            raise ParameterError("--out", None, "give --out DIR, --json, or both")


@dataclass(frozen=True)
class ReportJob(Job):
    """``builder``: import path of ``f(inputs, progress) -> ReportParts``; ``inputs``: the
    system's frozen inputs record (its gain set is ``inputs.gains``)."""

    builder: str
    inputs: Any
    render_documents: bool = True
    gains: Any = field(default=None, metadata={"fingerprint": False})

    def __post_init__(self) -> None:
        object.__setattr__(self, "gains", getattr(self.inputs, "gains", None))

    def run(self, progress: Any) -> Outcome:
        from lgw.theory import report as R

        parts: ReportParts = resolve(self.builder)(self.inputs, progress)
        claims = list(parts.claims)
        text = R.claims_json(claims)
        files: dict[str, Any] = {}
        if self.render_documents:
            progress.stage("rendering Markdown, LaTeX and HTML")
            cov = parts.coverage
            for name, fn in (("report.md", R.render_markdown), ("report.tex", R.render_latex),
                             ("report.html", R.render_html)):
                files[name] = fn(claims, parts.spec, list(parts.sections), coverage=cov)
            files["claims.json"] = text
            for sec in parts.sections:
                for fig in getattr(sec, "figures", ()):
                    files[fig.file] = fig.png
        counts = statement_counts(claims)
        return Outcome(json.loads(text), render=lambda con: _render(con, counts),
                       files=files)


def statement_counts(claims: Sequence[Any]) -> dict[str, dict[str, int]]:
    """Verdict counts of the paper's statements and of the workbench's own, apart."""
    out: dict[str, dict[str, int]] = {"paper": {}, "workbench": {}}
    for c in claims:
        d = out[getattr(c, "statement", "paper")]
        d[c.verdict] = d.get(c.verdict, 0) + 1
    return {k: dict(sorted(v.items())) for k, v in out.items()}


def _render(con: Any, counts: dict[str, dict[str, int]]) -> None:
    total: dict[str, int] = {}
    for c in counts.values():
        for k, v in c.items():
            total[k] = total.get(k, 0) + v
    con.print("verdicts: " + ", ".join(f"{k} {v}" for k, v in sorted(total.items())),
              markup=False)
    for who, c in counts.items():
        if c:
            label = "the paper's statements" if who == "paper" else "the workbench's own"
            con.print(f"verdicts, {label}: " + ", ".join(f"{k} {v}" for k, v in c.items()),
                      markup=False)
