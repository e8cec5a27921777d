"""``lgw report SYSTEM``, written once: the system builds the parts (claims judged for the gain
set, the report spec, the computed sections with their figures, the coverage table, and the
command that reproduces each refuted claim); this module renders Markdown, LaTeX, HTML and
claims.json from them (each opening with the findings: the paper's title and its refuted
statements), writes them with every figure as one atomic set, prints the verdict counts (the
paper's statements and the workbench's own, apart) or the claims as JSON.

``ReportJob.only``: report only the claims with these ids (a system's ``--claim ID``, the
command the findings give to reproduce one witness); an unknown id is a ParameterError naming
the valid ones.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

from lgw.theory.errors import ParameterError
from lgw.tuning import vocabulary as V
from lgw.tuning.system import Job, Outcome, resolve


@dataclass(frozen=True)
class ReportParts:
    """What a system's report builder returns."""

    claims: Sequence[Any]
    spec: Any  # lgw.theory.report.ReportSpec
    sections: Sequence[Any] = ()
    coverage: Sequence[Any] | None = None
    reproduce: Mapping[str, str] | None = None  # claim id -> command (default: see run)


@dataclass(frozen=True)
class ReportOptions(V.Outputs, out="report.md, report.tex, report.html, claims.json and the "
                                   "figures (needed unless --json)"):
    """The options every ``lgw report SYSTEM`` takes (a system adds its own).  A system gives
    as keywords of its class statement ``sim``: what --sim/--no-sim flies (declares the
    toggle, on by default), and ``claim``: a claim id for the options test (declares
    --claim).  ``NEEDS_SIM``: (option field, why) of the options that only apply with --sim,
    refused without it."""

    NEEDS_SIM: ClassVar[tuple[tuple[str, str], ...]] = ()

    def __init_subclass__(cls, *, sim: str | None = None, claim: str | None = None,
                          **kw: Any) -> None:
        super().__init_subclass__(**kw)
        if sim is not None:
            V.declare(cls, "sim", "bool", V.sim_toggle(True, sim), first=True)
        if claim is not None:
            V.declare(cls, "claim", "tuple", claim_option(claim))

    def check(self) -> None:
        super().check()
        if self.out is None and not self.json:
            raise ParameterError("--out", None, "give --out DIR, --json, or both")
        for name, why in self.NEEDS_SIM:
            self.refuse_unless(self.sim, name, f"needs --sim ({why})")


@dataclass(frozen=True)
class ReportJob(Job):
    """``builder``: import path of ``f(inputs, progress) -> ReportParts``; ``inputs``: the
    system's frozen inputs record (its gain set is ``inputs.gains``)."""

    builder: str
    inputs: Any
    render_documents: bool = True
    gains: Any = field(default=None, metadata={"fingerprint": False})
    only: tuple[str, ...] = ()
    # where a claim's reproduction command points (a system whose report takes --claim):
    # the gains file and whether the report flies its scenarios (--sim)
    gains_path: str = ""
    claim_option: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "gains", getattr(self.inputs, "gains", None))

    def run(self, progress: Any) -> Outcome:
        from lgw.theory import report as R

        parts: ReportParts = resolve(self.builder)(self.inputs, progress)
        claims = list(parts.claims)
        if self.only:
            known = [c.id for c in claims]
            bad = [x for x in self.only if x not in known]
            if bad:
                raise ParameterError("--claim", ", ".join(bad), "must be a claim id of this "
                                     "report: " + ", ".join(known))
            claims = [c for c in claims if c.id in self.only]
        system = self.builder.split(".")[2] if self.builder.count(".") >= 3 else ""
        reproduce = dict(parts.reproduce or {})
        for c in claims:
            reproduce.setdefault(c.id, one_claim_command(system, c, self.gains_path)
                                 if self.claim_option else
                                 f"lgw report {system} --json  (claim {c.id}: its witness)")
        spec = parts.spec
        if not getattr(spec, "paper_title", "") and system:
            from lgw.tuning.system import get_system
            spec = dataclasses.replace(spec, paper_title=get_system(system).title)
        text = R.claims_json(claims, reproduce)
        files: dict[str, Any] = {}
        if self.render_documents:
            progress.stage("rendering Markdown, LaTeX and HTML")
            cov = parts.coverage
            for name, fn in (("report.md", R.render_markdown), ("report.tex", R.render_latex),
                             ("report.html", R.render_html)):
                files[name] = fn(claims, spec, list(parts.sections), coverage=cov,
                                 reproduce=reproduce)
            files["claims.json"] = text
            for sec in parts.sections:
                for fig in getattr(sec, "figures", ()):
                    files[fig.file] = fig.png
        counts = statement_counts(claims)
        return Outcome(json.loads(text), render=lambda con: _render(con, counts),
                       files=files)


def plan_report(builder: str, inputs: Any, opts: ReportOptions) -> ReportJob:
    """The job of ``lgw report SYSTEM`` for a system whose report takes --claim: the report's
    documents when --out is given, only the claims of --claim, and each claim's reproduction
    command pointing at the --gains file."""
    return ReportJob(builder, inputs, opts.out is not None, only=tuple(opts.claim),
                     gains_path="" if opts.gains is None else str(opts.gains),
                     claim_option=True)


def one_claim_command(system: str, claim: Any, gains_path: str = "") -> str:
    """The command that recomputes one claim alone and prints it (its witness) as JSON: the
    claims on the paper's simulations need the scenarios flown (--sim), the others not."""
    gains = f" --gains {gains_path}" if gains_path else ""
    sim = "" if getattr(claim, "scope", "") == "scenario" else " --no-sim"
    return f"lgw report {system}{gains}{sim} --claim {claim.id} --json"


def claim_option(probe: str) -> Any:
    """The --claim option of ``lgw report SYSTEM`` (``probe``: a claim id of the system)."""
    from lgw.tuning.spec import option

    return option("--claim", None, (), "report only this claim (its id; the findings give the "
                  "command that reproduces each refuted claim's witness); repeatable",
                  multiple=True, metavar="ID", probe=(probe,))


def statement_counts(claims: Sequence[Any]) -> dict[str, dict[str, int]]:
    """Verdict counts of the paper's statements and of the workbench's own, apart."""
    out: dict[str, dict[str, int]] = {"paper": {}, "workbench": {}}
    for c in claims:
        d = out[getattr(c, "statement", "paper")]
        d[c.verdict] = d.get(c.verdict, 0) + 1
    return {k: dict(sorted(v.items())) for k, v in out.items()}


def _render(con: Any, counts: dict[str, dict[str, int]]) -> None:
    """The verdict counts of the paper's statements first (the summary), then the workbench's
    own (its corrections and its own laws), apart."""
    for who, c in counts.items():
        label = "the paper's statements" if who == "paper" else "the workbench's own"
        con.print(f"verdicts, {label}: " + (", ".join(f"{k} {v}" for k, v in c.items())
                                            or "none"), markup=False)
