"""Render a system's claims and a gain set's numbers as Markdown, LaTeX and HTML.

What is particular to a system (title, gain rows, warnings, bound labels, per-axis columns,
references) arrives in a ``ReportSpec`` that the system's own report module builds.

Claims are ``lgw.theory.evidence.Claim`` objects: each step prints its (computed) status, the
evidence kind and its data, and a refuted claim its witness as a small table.  Every formula
held as a SymPy object (a claim's ``paper_expr`` / ``derived_expr``, a step's ``expr``, an
identity's residual, an inequality's expression) is rendered from that object
(``lgw.theory.report_math``): LaTeX in the ``.tex``, presentation MathML in the HTML, ``$$...$$``
in the Markdown; the paper's printed form stands beside the derived one.  Plain-text
statements stay text, escaped for each format.

The HTML is one self-contained file: images embedded as base64 data URIs, no ``http:`` /
``https:`` reference, a table of contents, a verdict summary linking to each claim and back,
witnesses as small tables, evidence in ``<details>`` (opened for printing), print CSS.

Claims are grouped by scope: those that hold or fail whatever the gains, those about the
paper's simulations, and those judged for the report's gain set.  A coverage table
(``coverage=``) maps every item of the paper to its claims or says why it is not checkable.
Figures are made above ``theory`` (they need simulation data) and arrive in ``Section``s as
PNG bytes; ``theory`` only embeds them.

Findings first: every report opens with the paper's title and a table of the paper's
statements the workbench refutes, one line each with its witness and the command that
reproduces it (``reproduce``: claim id -> command, given by the report layer).  Summary counts
and the findings count the paper's statements; the workbench's own (its corrections, its own
laws) are counted apart.  A workbench claim that corrects a paper claim links to it and back.

Deterministic: the same inputs give the same bytes (no timestamps, fixed float formats, claims
in a fixed order, counterexample searches seeded).
"""

from __future__ import annotations

import base64
import dataclasses
import html
import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

import sympy as sp
from lgw.theory import report_math as RM
from lgw.theory.evidence import (
    VERDICTS,
    Cited,
    Claim,
    FromClaim,
    Identity,
    Inequality,
    Search,
    Step,
    Unproven,
    Witness,
)
from lgw.theory.sections import Figure, Section  # noqa: F401  (re-exported)


@dataclass(frozen=True)
class ReportSpec:
    """What a system puts in its report around the claims: plain data, rendered here."""

    title: str  # e.g. "Seed 000"
    gain_rows: tuple[tuple[str, str], ...]
    warnings: tuple[str, ...]
    bound_labels: tuple[tuple[str, str, str], ...]  # (key, label, unit)
    columns: tuple[str, ...]  # the per-axis (or per-channel) columns of the bounds table
    bounds: dict[str, dict[str, float]]  # column -> key -> value
    references: tuple[str, ...]
    bounds_note: str = ""
    paper_title: str = ""  # the paper's own title (the findings page opens with it)


def lgw_version() -> str:
    try:
        return version("lgw")
    except PackageNotFoundError:
        return "unknown"


def fmt(x: Any) -> str:
    if isinstance(x, float):
        return f"{x:.6g}"
    return str(x)


SCOPE_TITLES = (("all-gains", "Claims that hold or fail whatever the gains"),
                ("scenario", "Claims about the paper's models and simulation scenarios"),
                ("gain-set", "Claims judged for this gain set"))
VERDICT_LEGEND = ("verdicts, strongest first: proved (every step proved by a prover) / "
                  "proved-given (proved, given the cited published lemmas) / checked (rests on "
                  "a search that found no violation over a stated domain and budget) / "
                  "unproven / refuted (a counterexample, re-checked by an independent route)")
SEARCHES_NOTE = ("Falsification searches of the statement itself (a re-checked counterexample "
                 "refutes it; a search that finds none supports it only where the steps above "
                 "do not decide it):")
NOTATION = ("Notation in the formulas: the signed power |x|^q sgn(x) of the paper (sig(x, q) "
            "in the code) is written \u2308x\u230b^q; s1 = r per axis, and the axis subscript "
            "i is dropped in per-axis formulas.")


NOT_CHECKABLE = "not checkable, because "


@dataclass(frozen=True)
class CoverageRow:
    """One item of a paper (equation, definition, hypothesis, lemma, theorem, remark or
    simulation statement) and the claims that check it, or why it is not checkable."""

    item: str
    kind: str
    claims: tuple[str, ...] = ()
    not_checkable: str = ""

    def text(self) -> str:
        return ", ".join(self.claims) if self.claims else NOT_CHECKABLE + self.not_checkable

    @classmethod
    def of(cls, item: str, kind: str, claims: Sequence[str], note: str) -> CoverageRow:
        """The row of a system's coverage table entry: its claims, or (none) the note saying
        why it is not checkable (written ``"not checkable, because ..."``)."""
        if claims:
            return cls(item, kind, tuple(claims))
        return cls(item, kind, (), note.removeprefix(NOT_CHECKABLE))


def verdict_counts(claims: Sequence[Claim], statement: str | None = "paper") -> dict[str, int]:
    """How many claims have each verdict (every verdict listed, strongest first), counting
    the paper's statements (``statement="paper"``), the workbench's own (``"workbench"``) or
    all (None)."""
    mine = [c for c in claims if statement is None or c.statement == statement]
    return {v: sum(c.verdict == v for c in mine) for v in VERDICTS}


def _counts_text(claims: Sequence[Claim]) -> str:
    paper, own = verdict_counts(claims), verdict_counts(claims, "workbench")
    return ("the paper's statements: " + ", ".join(f"{v} {n}" for v, n in paper.items())
            + "; the workbench's own (corrections and its own laws, not counted above): "
            + ", ".join(f"{v} {n}" for v, n in own.items()) + ".")


@dataclass(frozen=True)
class Finding:
    """One refuted paper statement on the findings page."""

    id: str
    equations: str
    statement: str
    witness: str
    command: str
    corrected_by: str


def witness_text(w: Witness, limit: int = 8) -> str:
    """A witness in one line: its first ``limit`` coordinates (a mapping's entries inline),
    the margin and the independent re-check."""
    items = list(w.point.items())
    pts = "; ".join(f"{k} = {_short(v)[:120]}" for k, v in items[:limit])
    if len(items) > limit:
        pts += f"; ... ({len(items) - limit} more)"
    return ((pts + "; " if pts else "") + f"margin {fmt(w.margin)}, re-checked "
            f"{fmt(w.rechecked_margin)} ({w.recheck_method})")


def findings(claims: Sequence[Claim], reproduce: Mapping[str, str] | None = None
             ) -> list[Finding]:
    """The paper's statements the workbench refutes, in report order, with their witnesses,
    the command that reproduces each and the workbench claim that corrects it."""
    fixes = _corrections(claims)
    out = []
    for c in claims:
        if c.statement != "paper" or c.verdict != "refuted":
            continue
        w = c.counterexample
        out.append(Finding(c.id, c.equations, c.paper, witness_text(w) if w else "",
                           (reproduce or {}).get(c.id, ""), ", ".join(fixes.get(c.id, ()))))
    return out


def _corrections(claims: Sequence[Claim]) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for c in claims:
        if c.corrects:
            out.setdefault(c.corrects, []).append(c.id)
    return out


def _whose(c: Claim, fixes: Mapping[str, Sequence[str]]) -> str:
    """Whose statement a claim judges, and its link to its correction or to what it corrects."""
    if c.statement == "workbench":
        return "the workbench's statement" + (f", correcting {c.corrects}" if c.corrects
                                              else "")
    return "the paper's statement" + (f", corrected by {', '.join(fixes[c.id])}"
                                      if c.id in fixes else "")


def _by_scope(claims: Sequence[Claim]) -> list[tuple[str, str, list[Claim]]]:
    return [(sc, title, [c for c in claims if c.scope == sc]) for sc, title in SCOPE_TITLES
            if any(c.scope == sc for c in claims)]


def claims_json(claims: Sequence[Claim], reproduce: Mapping[str, str] | None = None) -> str:
    """Machine-readable claims: per claim its id, equations, the paper's and the derived
    statement, scope, verdict, each step with its evidence kind and data, and the witness;
    the verdict counts of the paper's statements (``verdicts``) and of the workbench's own
    (``verdicts_workbench``), and the findings (refuted paper statements)."""
    return json.dumps({"verdicts": verdict_counts(claims),
                       "verdicts_workbench": verdict_counts(claims, "workbench"),
                       "findings": [dataclasses.asdict(f) for f in findings(claims, reproduce)],
                       "claims": [c.to_dict() for c in claims]}, indent=1, sort_keys=True) + "\n"


def anchor(claim_id: str) -> str:
    """The HTML / Markdown / LaTeX anchor of a claim (letters, digits and '-' only)."""
    return "claim-" + re.sub(r"[^A-Za-z0-9-]", "-", claim_id)


def _summary_anchor(claim_id: str) -> str:
    return "sum-" + anchor(claim_id)[6:]


# --- the data every format shows ------------------------------------------------------------

def _short(x: Any) -> str:
    """A value in a table cell: floats to 6 digits, mappings as "k = v; ...", lists joined."""
    if isinstance(x, float):
        return fmt(x)
    if isinstance(x, Mapping):
        return "; ".join(f"{k} = {_short(v)}" for k, v in x.items())
    if isinstance(x, list | tuple):
        return "[" + ", ".join(_short(v) for v in x) + "]"
    if isinstance(x, sp.Basic):
        return sp.sstr(x)
    return str(x)


def _witness_rows(w: Witness) -> list[tuple[str, str]]:
    rows = [(str(k), _short(val)) for k, val in w.point.items()]
    rows += [("margin", fmt(w.margin)), ("found by", w.method),
             ("re-checked margin", fmt(w.rechecked_margin)), ("re-checked by", w.recheck_method)]
    if w.seed is not None:
        rows.append(("seed", str(w.seed)))
    return rows


@dataclass(frozen=True)
class _EvidenceView:
    """An evidence object laid out for rendering: a one-line head, optional formulas (SymPy),
    a small key/value table, nested steps (a cited lemma's hypotheses) and a witness."""

    head: str
    formulas: tuple[sp.Basic, ...] = ()
    formula_note: str = ""
    rows: tuple[tuple[str, str], ...] = ()
    hypotheses: tuple[Step, ...] = ()
    witness: Witness | None = None


def _evidence_view(ev: Any) -> _EvidenceView:
    if isinstance(ev, Identity):
        res = sp.sympify(ev.residual)
        if ev.status == "proved":
            return _EvidenceView(f"identity, {ev.method}: the residual reduces to 0")
        w = ev.point_witness
        return _EvidenceView(f"identity, {ev.method}: the residual is not shown to be 0"
                             + (f"; it is {w.margin:.6g} at an exact point" if w else ""),
                             (res,), "residual:", witness=w)
    if isinstance(ev, Inequality):
        rel = sp.StrictGreaterThan if ev.strict else sp.GreaterThan
        rows: list[tuple[str, str]] = [("prover", ev.prover), ("answer", _short(ev.answer))]
        if ev.box is not None:
            rows += [(f"box {k}", _short(list(v))) for k, v in ev.box.items()]
            rows.append(("enclosure lower end", _short(ev.lower)))
        return _EvidenceView(f"inequality by {ev.prover}: {ev.status}",
                             (rel(ev.expr, 0, evaluate=False),), "", tuple(rows),
                             witness=ev.counter)
    if isinstance(ev, Search):
        kind = "relative margin" if ev.relative else "margin"
        rows = [("method", ev.method), ("evaluations", str(ev.evaluations)),
                ("budget", ev.budget or f"{ev.evaluations} evaluations"),
                ("seed", _short(ev.seed)), (f"best {kind}", fmt(ev.best_margin)),
                ("tolerance", fmt(ev.tolerance)), ("status", ev.status)]
        rows += [(f"domain: {k}", _short(v)) for k, v in ev.domain.items()]
        rows += [(f"best point: {k}", _short(v)) for k, v in ev.best_point.items()]
        head = (f"search, {ev.evaluations} evaluations: best {kind} {ev.best_margin:.6g}"
                + {"refuted": "; counterexample re-checked",
                   "checked": f" (clears the tolerance {ev.tolerance:g}: checked)",
                   "unproven": f" (below the tolerance {ev.tolerance:g}, not re-checked into a "
                               "counterexample: unproven)"}[ev.status])
        return _EvidenceView(head, rows=tuple(rows), witness=ev.counter)
    if isinstance(ev, Cited):
        return _EvidenceView(f"cited: {ev.result} [{ev.reference}]",
                             hypotheses=tuple(ev.hypotheses))
    if isinstance(ev, Unproven):
        return _EvidenceView(f"unproven: {ev.reason}")
    if isinstance(ev, FromClaim):
        return _EvidenceView(f"rests on claim {ev.claim.id} (verdict {ev.claim.verdict}; a "
                             "refuted or unproven lemma leaves this step unproven)")
    return _EvidenceView(f"{ev.kind}: {ev.summary()}")  # pragma: no cover


def _claim_formulas(c: Claim) -> tuple[tuple[sp.Basic, ...], tuple[sp.Basic, ...]]:
    return RM.exprs(c.paper_expr), RM.exprs(c.derived_expr)


def _same(a: tuple[sp.Basic, ...], b: tuple[sp.Basic, ...]) -> bool:
    return len(a) == len(b) and all(x == y for x, y in zip(a, b, strict=True))


# --- Markdown -------------------------------------------------------------------------------

def _md_cell(x: str) -> str:
    return x.replace("|", "\\|").replace("\n", " ")


def _md_table(columns: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    L = ["| " + " | ".join(_md_cell(c) for c in columns) + " |", "|" + "---|" * len(columns)]
    return L + ["| " + " | ".join(_md_cell(c) for c in row) + " |" for row in rows]


def _md_math(e: sp.Basic, indent: str = "") -> list[str]:
    return [f"{indent}$${RM.latex(e)}$$"]


def _view(ev: Any, shown: tuple[sp.Basic, ...] = ()) -> _EvidenceView:
    """The evidence view without the formulas the step already shows (same LaTeX)."""
    vw = _evidence_view(ev)
    seen = {RM.latex(e) for e in shown}
    keep = tuple(f for f in vw.formulas if RM.latex(f) not in seen)
    if keep == vw.formulas:
        return vw
    return _EvidenceView(vw.head, keep, vw.formula_note if keep else "", vw.rows,
                         vw.hypotheses, vw.witness)


def _md_evidence(ev: Any, indent: str, shown: tuple[sp.Basic, ...] = ()) -> list[str]:
    vw = _view(ev, shown)
    L = [f"{indent}*{vw.head}*"]
    for f in vw.formulas:
        L += [""] + ([f"{indent}{vw.formula_note}", ""] if vw.formula_note else [])
        L += _md_math(f, indent)
    if vw.rows:
        L += [""] + [indent + x for x in _md_table(("item", "value"), vw.rows)]
    for j, h in enumerate(vw.hypotheses, 1):
        L += ["", *_md_step(h, f"hypothesis {j}", indent + "   ")]
    if vw.witness is not None:
        rows = _md_table(("item", "value"), _witness_rows(vw.witness))
        L += ["", f"{indent}witness:", ""] + [indent + x for x in rows]
    return L


def _md_step(s: Step, label: str, indent: str = "") -> list[str]:
    L = [f"{indent}{label}. [{s.status}] {s.statement}"]
    sub = indent + "   "
    for e in RM.exprs(s.expr):
        L += [""] + _md_math(e, sub)
    return L + [""] + _md_evidence(s.evidence, sub, RM.exprs(s.expr))


def _md_sections(sections: Sequence[Section]) -> list[str]:
    L: list[str] = []
    for sec in sections:
        L += ["", f"## {sec.title}", ""]
        if sec.columns:
            L += _md_table(sec.columns, sec.rows)
        for par in sec.paragraphs:
            L += ["", par]
        if sec.image:
            L += ["", f"![{sec.title}]({sec.image})"]
        for fig in sec.figures:
            L += ["", f"![{fig.caption}]({fig.file})", "", f"*{fig.caption}*"]
    return L


def _md_findings(claims: Sequence[Claim], spec: ReportSpec,
                 reproduce: Mapping[str, str] | None) -> list[str]:
    fs = findings(claims, reproduce)
    L = ["## Findings", "", f"Paper: *{spec.paper_title or spec.title}*.", "",
         f"{len(fs)} of the paper's {sum(c.statement == 'paper' for c in claims)} statements "
         "judged here are refuted, each by a witness re-checked by an independent route; "
         "verdicts of " + _counts_text(claims), ""]
    if fs:
        L += _md_table(("claim", "equations", "the paper's statement", "witness",
                        "reproduce", "corrected by"),
                       [(f"[{f.id}](#{anchor(f.id)})", f.equations, f.statement, f.witness,
                         f"`{f.command}`" if f.command else "-", f.corrected_by or "-")
                        for f in fs])
    return L


def render_markdown(claims: list[Claim], spec: ReportSpec,
                    sections: Sequence[Section] = (), *,
                    coverage: Sequence[CoverageRow] = (),
                    reproduce: Mapping[str, str] | None = None) -> str:
    groups = _by_scope(claims)
    fixes = _corrections(claims)
    toc = ["findings", "gain set", "bounds", "verdicts"] + [t for _, t, _ in groups]
    toc += (["coverage of the paper"] if coverage else []) + [s.title for s in sections]
    L = [f"# {spec.title}: derivation report", "",
         *_md_findings(claims, spec, reproduce), "",
         f"lgw {lgw_version()}.  Every statement below is derived from the guidance law itself "
         f"(SymPy) and checked; {VERDICT_LEGEND}.", "", NOTATION, "",
         "Contents: " + "; ".join(toc + ["references"]) + ".", "",
         "## Gain set", ""]
    L += _md_table(("parameter", "value"), spec.gain_rows)
    for w in spec.warnings:
        L += ["", f"> warning: {w}"]
    L += ["", "## Bounds for this gain set (per axis)", ""]
    L += _md_table(("bound", "unit", *spec.columns), _bound_rows(spec))
    L += ["", spec.bounds_note, "", "## Verdicts", "",
          "Summary, " + _counts_text(claims)]
    for _, title, group in groups:
        L += ["", f"### {title}", "", "| claim | equations | law | whose | verdict |",
              "|---|---|---|---|---|"]
        L += [f"| <a id=\"{_summary_anchor(c.id)}\"></a>[{c.id}](#{anchor(c.id)}) | "
              f"{_md_cell(c.equations)} | {c.law or '-'} | {c.statement} | **{c.verdict}** |"
              for c in group]
    for _, title, group in groups:
        L += ["", f"## {title}"]
        for c in group:
            paper, derived = _claim_formulas(c)
            L += ["", f"### {c.id}", "", f"<a id=\"{anchor(c.id)}\"></a>",
                  f"**{c.title}** — equations {c.equations}"
                  + (f", law: {c.law}" if c.law else "") + f", scope: {c.scope}; "
                  f"{_whose(c, fixes)} "
                  f"([back to the summary](#{_summary_anchor(c.id)}))", "",
                  f"- Paper: {c.paper}"]
            for e in paper:
                L += ["", *_md_math(e, "  ")]
            L.append(f"- Derived: {c.derived}")
            for e in derived:
                L += ["", *_md_math(e, "  ")]
            if paper and derived and _same(paper, derived):
                L.append("  (the derived form is the printed one)")
            L += [f"- Verdict: **{c.verdict_text()}**", "", "Steps:" if c.steps else
                  "Steps: none (no proof; the searches below decide).", ""]
            for i, s in enumerate(c.steps, 1):
                L += [*_md_step(s, str(i)), ""]
            if c.searches:
                L += [SEARCHES_NOTE, ""]
                for i, s in enumerate(c.searches, 1):
                    L += [*_md_step(s, f"S{i}"), ""]
            if c.remarks:
                L += ["Remarks on the paper's own argument (not part of the verdict):", ""]
                for i, s in enumerate(c.remarks, 1):
                    L += [*_md_step(s, f"R{i}"), ""]
            if c.counterexample:
                L += ["Counterexample:", ""] + _md_table(("item", "value"),
                                                         _witness_rows(c.counterexample))
            if c.numbers:
                L += ["", "Numbers:", ""] + _md_table(
                    ("item", "value"), [(str(k), _short(v)) for k, v in c.numbers.items()])
    if coverage:
        L += ["", "## Coverage of the paper", ""]
        L += _md_table(("item", "kind", "claims"), [(r.item, r.kind, r.text()) for r in coverage])
    L += _md_sections(sections)
    L += ["", "## References", ""] + [f"- {ref}" for ref in spec.references] + [""]
    return "\n".join(L)


def _bound_rows(spec: ReportSpec) -> list[tuple[str, ...]]:
    return [(f"{label} ({key})", unit, *(fmt(spec.bounds[a][key]) for a in spec.columns))
            for key, label, unit in spec.bound_labels if key in spec.bounds[spec.columns[0]]]


# --- LaTeX ----------------------------------------------------------------------------------

_TEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
        "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
        "<": r"\textless{}", ">": r"\textgreater{}", "|": r"\textbar{}", "—": "---",
        "\u2264": r"\ensuremath{\leq}", "\u2265": r"\ensuremath{\geq}",
        "\u2308": r"\ensuremath{\lceil}", "\u230b": r"\ensuremath{\rfloor}"}


def tex(s: str) -> str:
    """Plain text for LaTeX's text mode (every special character escaped, no math mode)."""
    return "".join(_TEX.get(ch, ch) for ch in s)


def _tex_math(e: sp.Basic) -> str:
    lines = RM.split_lines(e, 80)
    if lines is not None:  # a long sum: one line per group of terms
        return (r"\begin{multline*}" + r" \\ ".join(t for t, _ in lines)
                + r"\end{multline*}")
    s = RM.latex_breakable(e)
    if RM.visual_width(s) <= 80:
        return r"\[" + s + r"\]"
    # long, without a sum to break at: inline display-style math in its own paragraph,
    # which TeX breaks at relations and operators
    return r"\par{\small\noindent$\displaystyle " + s + r"$\par}"


def _tex_kv(rows: Sequence[tuple[str, str]]) -> list[str]:
    L = [r"{\footnotesize\begin{longtable}{@{}p{4.2cm}p{11.5cm}@{}}"]
    L += [tex(k) + " & " + tex(v) + r" \\" for k, v in rows]
    return L + [r"\end{longtable}}"]


def _tex_evidence(ev: Any, shown: tuple[sp.Basic, ...] = ()) -> list[str]:
    vw = _view(ev, shown)
    L = [r"\emph{" + tex(vw.head) + "}"]
    if vw.formula_note:
        L.append(tex(" " + vw.formula_note))
    L += [_tex_math(f) for f in vw.formulas]
    if vw.rows:
        L += _tex_kv(vw.rows)
    if vw.hypotheses:
        L.append(r"\begin{enumerate}")
        for h in vw.hypotheses:
            L += _tex_step(h)
        L.append(r"\end{enumerate}")
    if vw.witness is not None:
        L += [r"\par\noindent Witness:"] + _tex_kv(_witness_rows(vw.witness))
    return L


def _tex_step(s: Step) -> list[str]:
    L = [r"\item \textbf{[" + tex(s.status) + "]} " + tex(s.statement)]
    L += [_tex_math(e) for e in RM.exprs(s.expr)]
    return L + [r"\par\noindent"] + _tex_evidence(s.evidence, RM.exprs(s.expr))


def _tex_label(claim_id: str) -> str:
    return anchor(claim_id).replace("-", ":")


def _tex_findings(claims: Sequence[Claim], spec: ReportSpec,
                  reproduce: Mapping[str, str] | None) -> list[str]:
    fs = findings(claims, reproduce)
    L = [r"\section*{Findings}", r"\noindent Paper: \emph{" + tex(spec.paper_title or spec.title)
         + r"}.\par", tex(f"{len(fs)} of the paper's {sum(c.statement == 'paper' for c in claims)}"
                          " statements judged here are refuted, each by a witness re-checked by "
                          "an independent route; verdicts of " + _counts_text(claims)) + r"\par"]
    if fs:
        L += [r"{\scriptsize\begin{longtable}{p{2.2cm}p{1.6cm}p{3.6cm}p{5cm}p{2.6cm}}",
              r"claim & equations & the paper's statement & witness & reproduce \\ \hline"]
        L += [r"\hyperref[" + _tex_label(f.id) + "]{" + tex(f.id) + "}"
              + (r" (corrected by " + tex(f.corrected_by) + ")" if f.corrected_by else "")
              + " & " + " & ".join(tex(x) for x in (f.equations, f.statement, f.witness,
                                                    f.command or "-")) + r" \\"
              for f in fs]
        L.append(r"\end{longtable}}")
    return L


def render_latex(claims: list[Claim], spec: ReportSpec,
                 sections: Sequence[Section] = (), *,
                 coverage: Sequence[CoverageRow] = (),
                 reproduce: Mapping[str, str] | None = None) -> str:
    groups = _by_scope(claims)
    fixes = _corrections(claims)
    L = [r"\documentclass[10pt]{article}", r"\usepackage[margin=2cm]{geometry}",
         r"\usepackage[T1]{fontenc}", r"\usepackage{lmodern}", r"\usepackage{textcomp}",
         r"\usepackage{amsmath,amssymb}", r"\usepackage{longtable}", r"\usepackage{graphicx}",
         r"\usepackage[hidelinks]{hyperref}", r"\setcounter{secnumdepth}{2}",
         r"\setcounter{tocdepth}{2}", r"\sloppy", r"\begin{document}",
         r"\title{" + tex(spec.title) + ": derivation report}",
         r"\author{lgw " + tex(lgw_version()) + "}", r"\date{}", r"\maketitle",
         *_tex_findings(claims, spec, reproduce),
         tex(f"{VERDICT_LEGEND}.") + r"\par", tex(NOTATION), r"\tableofcontents",
         r"\section{Gain set}", r"\begin{tabular}{ll}"]
    L += [tex(k) + " & " + tex(val) + r" \\" for k, val in spec.gain_rows]
    L += [r"\end{tabular}"] + [r"\paragraph{Warning.} " + tex(w) for w in spec.warnings]
    L += [r"\section{Bounds for this gain set (per axis)}",
          r"{\small\begin{longtable}{p{6.5cm}l" + "r" * len(spec.columns) + "}",
          "bound & unit & " + " & ".join(tex(c) for c in spec.columns) + r" \\ \hline"]
    L += [" & ".join(tex(x) for x in row) + r" \\" for row in _bound_rows(spec)]
    L += [r"\end{longtable}}", tex(spec.bounds_note), r"\section{Verdicts}",
          tex("Summary, " + _counts_text(claims))]
    for _, title, group in groups:
        L += [r"\paragraph{" + tex(title) + "}",
              r"{\small\begin{longtable}{p{4.5cm}p{4.5cm}lll}",
              r"claim & equations & law & whose & verdict \\ \hline"]
        L += [r"\hyperref[" + _tex_label(c.id) + "]{" + tex(c.id) + "}"
              + r"\label{" + _tex_label(c.id).replace("claim:", "sum:") + "} & "
              + " & ".join(tex(x) for x in (c.equations, c.law or "-", c.statement))
              + r" & \textbf{" + tex(c.verdict) + r"} \\" for c in group]
        L.append(r"\end{longtable}}")
    for _, title, group in groups:
        L.append(r"\section{" + tex(title) + "}")
        for c in group:
            paper, derived = _claim_formulas(c)
            L += [r"\subsection{" + tex(f"{c.id}: {c.title}") + "}" + r"\label{"
                  + _tex_label(c.id) + "}",
                  r"\noindent Equations " + tex(c.equations) + (", law: " + tex(c.law)
                                                                if c.law else "")
                  + ", scope: " + tex(c.scope) + "; " + tex(_whose(c, fixes)) + r" (\hyperref["
                  + _tex_label(c.id).replace("claim:", "sum:") + r"]{back to the summary})."
                  r"\par\medskip", r"\noindent\textbf{Paper (as printed):} " + tex(c.paper)]
            L += [_tex_math(e) for e in paper]
            L += [r"\par\noindent\textbf{Derived:} " + tex(c.derived)]
            L += [_tex_math(e) for e in derived]
            L += [r"\par\noindent\textbf{Verdict:} \textbf{" + tex(c.verdict_text()) + "}",
                  r"\begin{enumerate}"]
            for s in c.steps:
                L += _tex_step(s)
            if not c.steps:
                L.append(r"\item " + tex("no proof steps: the searches below decide"))
            L.append(r"\end{enumerate}")
            if c.searches:
                L += [r"\paragraph{" + tex(SEARCHES_NOTE.rstrip(":")) + ".}",
                      r"\begin{enumerate}"]
                for s in c.searches:
                    L += _tex_step(s)
                L.append(r"\end{enumerate}")
            if c.remarks:
                L += [r"\paragraph{Remarks on the paper's own argument (not part of the "
                      r"verdict).}", r"\begin{enumerate}"]
                for s in c.remarks:
                    L += _tex_step(s)
                L.append(r"\end{enumerate}")
            if c.counterexample:
                L += [r"\paragraph{Counterexample.}"] + _tex_kv(_witness_rows(c.counterexample))
            if c.numbers:
                L += [r"\paragraph{Numbers.}"] + _tex_kv(
                    [(str(k), _short(v)) for k, v in c.numbers.items()])
    if coverage:
        L += [r"\section{Coverage of the paper}", r"{\scriptsize",
              r"\begin{longtable}{p{3cm}lp{10cm}}", r"item & kind & claims \\ \hline"]
        L += [" & ".join(tex(x) for x in (r.item, r.kind, r.text())) + r" \\" for r in coverage]
        L.append(r"\end{longtable}}")
    for sec in sections:
        L.append(r"\section{" + tex(sec.title) + "}")
        if sec.columns:
            n = len(sec.columns)
            width = rf"\dimexpr(\linewidth-{2 * n}\tabcolsep)/{n}\relax"
            L += [r"{\scriptsize\begin{longtable}{" + ("p{" + width + "}") * len(sec.columns)
                  + "}", " & ".join(tex(c) for c in sec.columns) + r" \\ \hline"]
            L += [" & ".join(tex(c) for c in row) + r" \\" for row in sec.rows]
            L.append(r"\end{longtable}}")
        L += [tex(p) + "\n" for p in sec.paragraphs]
        images = ([(sec.image, sec.title)] if sec.image else [])
        images += [(f.file, f.caption) for f in sec.figures]
        for file, caption in images:
            L += [r"\begin{figure}[htbp]\centering",
                  r"\IfFileExists{" + file + r"}{\includegraphics[width=\linewidth]{" + file
                  + r"}}{\fbox{" + tex(file) + " not found beside the report}}",
                  r"\caption{" + tex(caption) + r"}\end{figure}"]
    L += [r"\section*{References}", r"\begin{enumerate}"]
    L += [r"\item " + tex(ref) for ref in spec.references]
    L += [r"\end{enumerate}", r"\end{document}", ""]
    return "\n".join(L)


# --- HTML -----------------------------------------------------------------------------------

_CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;line-height:1.45;
 max-width:62em;margin:0 auto;padding:0 1.2em 3em;color:#111}
h1{font-size:1.7em;margin-top:1em}h2{border-bottom:2px solid #ddd;padding-bottom:.2em;
 margin-top:2em}h3{margin-top:1.6em}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 7px;
 vertical-align:top;text-align:left}th{background:#f3f3f3}
td.num{text-align:right;font-variant-numeric:tabular-nums}
.refuted{color:#b00;font-weight:600}.proved,.proved-given,.cited{color:#070;font-weight:600}
.checked{color:#850;font-weight:600}.unproven{color:#666;font-weight:600}
td.proved,td.proved-given,td.checked,td.unproven,td.refuted{white-space:nowrap}
.claim{border:1px solid #ddd;border-radius:6px;padding:.2em 1em .8em;margin:1.2em 0}
.claim h3{margin-top:.6em}.meta{color:#555;font-size:.92em}
.forms{width:100%;table-layout:fixed}.forms th{width:8.5em;text-align:left}
.eq{overflow-x:auto;overflow-y:hidden;padding:.15em 0;max-width:100%}
math[display=block]{margin:.2em 0}
details{margin:.2em 0 .4em}summary{cursor:pointer;color:#333}
.ev{font-size:.92em;background:#fafafa;border-left:3px solid #ddd;padding:.2em .7em}
.kv td:first-child{color:#444;white-space:nowrap}.kv{font-size:.9em}
nav.toc{background:#f7f7f7;border:1px solid #e3e3e3;padding:.3em 1.2em;border-radius:6px}
nav.toc ol{margin:.3em 0}figure{margin:1em 0}figure img{max-width:100%;height:auto;
 border:1px solid #eee}figcaption{font-size:.92em;color:#333}
a.back{font-size:.85em}
@media print{body{max-width:none;font-size:10pt}nav.toc,a.back{display:none}
 .claim{break-inside:auto;border:none;padding:0}h2,h3{break-after:avoid}
 figure{break-inside:avoid}a{color:inherit;text-decoration:none}summary{list-style:none}
 .eq{overflow:visible}}
"""
# open every <details> for printing (the evidence is folded on screen only)
_JS = ("window.addEventListener('beforeprint',function(){document.querySelectorAll('details')"
       ".forEach(function(d){d.open=true;});});")


def _h(s: str) -> str:
    return html.escape(s, quote=True)


def _html_math(e: sp.Basic) -> str:
    return f"<div class='eq'>{RM.mathml_lines(e)}</div>"


def _html_kv(rows: Sequence[tuple[str, str]]) -> str:
    return ("<table class='kv'>" + "".join(f"<tr><td>{_h(k)}</td><td>{_h(v)}</td></tr>"
                                          for k, v in rows) + "</table>")


def _html_evidence(ev: Any, shown: tuple[sp.Basic, ...] = ()) -> str:
    vw = _view(ev, shown)
    parts = [f"<div class='ev'><p>{_h(vw.head)}</p>"]
    if vw.formula_note:
        parts.append(f"<p>{_h(vw.formula_note)}</p>")
    parts += [_html_math(f) for f in vw.formulas]
    if vw.rows:
        parts.append(_html_kv(vw.rows))
    if vw.hypotheses:
        parts.append("<p>hypotheses:</p><ol>" + "".join(_html_step(h) for h in vw.hypotheses)
                     + "</ol>")
    if vw.witness is not None:
        parts.append("<p>witness:</p>" + _html_kv(_witness_rows(vw.witness)))
    if isinstance(ev, FromClaim):
        parts.append(f"<p><a href='#{anchor(ev.claim.id)}'>claim {_h(ev.claim.id)}</a></p>")
    return "".join(parts) + "</div>"


def _html_step(s: Step) -> str:
    kind = s.evidence.kind
    return (f"<li><span class='{s.status}'>[{s.status}]</span> {_h(s.statement)}"
            + "".join(_html_math(e) for e in RM.exprs(s.expr))
            + f"<details><summary>evidence: {_h(kind)}</summary>"
            + _html_evidence(s.evidence, RM.exprs(s.expr)) + "</details></li>")


def _html_whose(c: Claim, fixes: Mapping[str, Sequence[str]], ids: set[str]) -> str:
    def link(x: str) -> str:
        return f"<a href='#{anchor(x)}'>{_h(x)}</a>" if x in ids else _h(x)
    if c.statement == "workbench":
        return "the workbench's statement" + (f", correcting {link(c.corrects)}"
                                              if c.corrects else "")
    return "the paper's statement" + (", corrected by " + ", ".join(link(x) for x in fixes[c.id])
                                      if c.id in fixes else "")


def _img_src(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def _html_figures(sec: Section, asset_dir: Path | None) -> list[str]:
    out = []
    items = [(sec.image, sec.title, b"")] if sec.image else []
    items += [(f.file, f.caption, f.png) for f in sec.figures]
    for file, caption, png in items:
        if not png and asset_dir is not None and (asset_dir / file).is_file():
            png = (asset_dir / file).read_bytes()
        if png:
            fid = "fig-" + re.sub(r"[^A-Za-z0-9-]", "-", Path(file).stem)
            out.append(f"<figure id='{fid}'><img src='{_img_src(png)}' alt='{_h(caption)}'>"
                       f"<figcaption>{_h(caption)} ({_h(file)})</figcaption></figure>")
        else:
            out.append(f"<p>Figure {_h(file)} ({_h(caption)}): not embedded (no image data "
                       "given to the renderer).</p>")
    return out


def _section_id(i: int) -> str:
    return f"sec-{i}"


def _html_findings(claims: Sequence[Claim], spec: ReportSpec,
                   reproduce: Mapping[str, str] | None) -> list[str]:
    fs = findings(claims, reproduce)
    L = ["<section id='findings'><h2>Findings</h2>",
         f"<p>Paper: <i>{_h(spec.paper_title or spec.title)}</i>.</p>",
         f"<p>{len(fs)} of the paper's {sum(c.statement == 'paper' for c in claims)} statements "
         "judged here are refuted, each by a witness re-checked by an independent route; "
         f"verdicts of {_h(_counts_text(claims))}</p>"]
    if fs:
        L.append("<table><tr><th>claim</th><th>equations</th><th>the paper's statement</th>"
                 "<th>witness</th><th>reproduce</th><th>corrected by</th></tr>")
        L += [f"<tr><td><a href='#{anchor(f.id)}'>{_h(f.id)}</a></td><td>{_h(f.equations)}</td>"
              f"<td>{_h(f.statement)}</td><td>{_h(f.witness)}</td>"
              f"<td><code>{_h(f.command or '-')}</code></td><td>"
              + (", ".join(f"<a href='#{anchor(x)}'>{_h(x)}</a>"
                           for x in f.corrected_by.split(", ")) if f.corrected_by else "-")
              + "</td></tr>" for f in fs]
        L.append("</table>")
    return L + ["</section>"]


def render_html(claims: list[Claim], spec: ReportSpec,
                sections: Sequence[Section] = (), *,
                coverage: Sequence[CoverageRow] = (), asset_dir: Path | None = None,
                reproduce: Mapping[str, str] | None = None) -> str:
    """One self-contained HTML page (no external reference; figures embedded).

    ``asset_dir``: where a ``Section.image`` file is read from (figures given as
    ``Section.figures`` carry their bytes)."""
    groups = _by_scope(claims)
    fixes = _corrections(claims)
    ids = {c.id for c in claims}
    toc = [("findings", "Findings"), ("gains", "Gain set"),
           ("bounds", "Bounds for this gain set"), ("verdicts", "Verdict summary")]
    toc += [(f"scope-{sc}", title) for sc, title, _ in groups]
    toc += [("coverage", "Coverage of the paper")] if coverage else []
    toc += [(_section_id(i), s.title) for i, s in enumerate(sections)]
    toc.append(("references", "References"))
    L = ["<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>",
         "<meta name='viewport' content='width=device-width, initial-scale=1'>",
         f"<title>{_h(spec.title)}: derivation report</title>",
         f"<style>{_CSS}</style><script>{_JS}</script></head><body>",
         f"<h1>{_h(spec.title)}: derivation report</h1>",
         *_html_findings(claims, spec, reproduce),
         f"<p class='meta'>lgw {_h(lgw_version())}. {_h(VERDICT_LEGEND)}.</p>",
         f"<p class='meta'>{_h(NOTATION)}</p>",
         "<nav class='toc'><b>Contents</b><ol>"
         + "".join(f"<li><a href='#{i}'>{_h(t)}</a></li>" for i, t in toc) + "</ol></nav>",
         "<h2 id='gains'>Gain set</h2><table><tr><th>parameter</th><th>value</th></tr>"]
    L += [f"<tr><td>{_h(k)}</td><td class='num'>{_h(val)}</td></tr>" for k, val in spec.gain_rows]
    L.append("</table>")
    L += [f"<p><b>warning:</b> {_h(w)}</p>" for w in spec.warnings]
    L.append("<h2 id='bounds'>Bounds for this gain set (per axis)</h2><table><tr><th>bound</th>"
             "<th>unit</th>" + "".join(f"<th>{_h(a)}</th>" for a in spec.columns) + "</tr>")
    for row in _bound_rows(spec):
        L.append(f"<tr><td>{_h(row[0])}</td><td>{_h(row[1])}</td>"
                 + "".join(f"<td class='num'>{_h(x)}</td>" for x in row[2:]) + "</tr>")
    L.append("</table>" + (f"<p>{_h(spec.bounds_note)}</p>" if spec.bounds_note else ""))
    counts, own = verdict_counts(claims), verdict_counts(claims, "workbench")
    L.append("<section id='verdicts'><h2>Verdict summary</h2><p>The paper's statements: "
             + ", ".join(f"<span class='{v}'>{v}</span> {n}" for v, n in counts.items())
             + ".  The workbench's own (corrections and its own laws, not counted above): "
             + ", ".join(f"<span class='{v}'>{v}</span> {n}" for v, n in own.items())
             + ".</p>")
    for _sc, title, group in groups:
        L.append(f"<h3>{_h(title)}</h3><table><tr><th>claim</th><th>title</th>"
                 "<th>equations</th><th>law</th><th>whose</th><th>verdict</th></tr>")
        L += [f"<tr id='{_summary_anchor(c.id)}'><td><a href='#{anchor(c.id)}'>{_h(c.id)}</a>"
              f"</td><td>{_h(c.title)}</td><td>{_h(c.equations)}</td><td>{_h(c.law or '-')}"
              f"</td><td>{_h(c.statement)}</td>"
              f"<td class='{c.verdict}'>{_h(c.verdict)}</td></tr>" for c in group]
        L.append("</table>")
    L.append("</section>")
    for sc, title, group in groups:
        L.append(f"<h2 id='scope-{sc}'>{_h(title)}</h2>")
        for c in group:
            paper, derived = _claim_formulas(c)
            L += [f"<section class='claim' id='{anchor(c.id)}'>",
                  f"<h3>{_h(c.id)}: {_h(c.title)}</h3>",
                  f"<p class='meta'>equations {_h(c.equations)}"
                  + (f"; law: {_h(c.law)}" if c.law else "") + f"; scope: {_h(c.scope)}; "
                  + _html_whose(c, fixes, ids) + ". "
                  f"<a class='back' href='#{_summary_anchor(c.id)}'>back to the summary</a></p>",
                  "<table class='forms'><tr><th>the paper (as printed)</th>"
                  f"<td>{_h(c.paper)}" + "".join(_html_math(e) for e in paper) + "</td></tr>"
                  f"<tr><th>derived by the workbench</th><td>{_h(c.derived)}"
                  + "".join(_html_math(e) for e in derived)
                  + ("<p class='meta'>(the derived form is the printed one)</p>"
                     if paper and derived and _same(paper, derived) else "")
                  + "</td></tr></table>",
                  f"<p><b>Verdict:</b> <span class='{c.verdict}'>{_h(c.verdict_text())}</span>"
                  "</p><ol>"]
            L += [_html_step(s) for s in c.steps]
            if not c.steps:
                L.append("<li>no proof steps: the searches below decide</li>")
            L.append("</ol>")
            if c.searches:
                L.append(f"<p>{_h(SEARCHES_NOTE)}</p><ol>"
                         + "".join(_html_step(s) for s in c.searches) + "</ol>")
            if c.remarks:
                L.append("<p>Remarks on the paper's own argument (not part of the verdict):</p>"
                         "<ol>" + "".join(_html_step(s) for s in c.remarks) + "</ol>")
            if c.counterexample:
                L.append("<p><b>Counterexample:</b></p>"
                         + _html_kv(_witness_rows(c.counterexample)))
            if c.numbers:
                L.append("<p>Numbers:</p>" + _html_kv([(str(k), _short(v))
                                                       for k, v in c.numbers.items()]))
            L.append("</section>")
    if coverage:
        L.append("<h2 id='coverage'>Coverage of the paper</h2><table><tr><th>item</th>"
                 "<th>kind</th><th>claims</th></tr>")
        L += [f"<tr><td>{_h(r.item)}</td><td>{_h(r.kind)}</td><td>"
              + (", ".join(f"<a href='#{anchor(x)}'>{_h(x)}</a>" if x in ids else _h(x)
                           for x in r.claims)
                 if r.claims else _h(r.text())) + "</td></tr>" for r in coverage]
        L.append("</table>")
    for i, sec in enumerate(sections):
        L.append(f"<h2 id='{_section_id(i)}'>{_h(sec.title)}</h2>")
        if sec.columns:
            L.append("<table><tr>" + "".join(f"<th>{_h(c)}</th>" for c in sec.columns) + "</tr>")
            L += ["<tr>" + "".join(f"<td>{_h(c)}</td>" for c in row) + "</tr>"
                  for row in sec.rows]
            L.append("</table>")
        L += [f"<p>{_h(p)}</p>" for p in sec.paragraphs]
        L += _html_figures(sec, asset_dir)
    L += ["<h2 id='references'>References</h2><ol>"]
    L += [f"<li>{_h(ref)}</li>" for ref in spec.references]
    L += ["</ol></body></html>", ""]
    return "\n".join(L)
