"""Render a system's claims and a gain set's numbers as Markdown, LaTeX and HTML.

What is particular to a system (title, gain rows, warnings, bound labels, per-axis columns,
references) arrives in a ``ReportSpec`` that the system's own report module builds.

Claims are ``lgw.theory.evidence.Claim`` objects: each step prints its (computed) status, the
evidence kind and summary, and a refuted claim its witness as a small table.  Claims are grouped
by scope: those that hold or fail whatever the gains, those about the paper's simulations, and
those judged for the report's gain set.  A coverage table (``coverage=``) maps every item of the
paper to its claims or says why it is not checkable.

Deterministic: the same gains give the same bytes (no timestamps, fixed float formats, claims
in a fixed order, counterexample searches seeded).
"""

from __future__ import annotations

import html
import json
from collections.abc import Sequence
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError, version
from typing import Any

from lgw.theory.evidence import VERDICTS, Claim, Step, Witness


@dataclass(frozen=True)
class ReportSpec:
    """What a system puts in its report around the claims: plain data, rendered here."""

    title: str  # e.g. "{spec.title}"
    gain_rows: tuple[tuple[str, str], ...]
    warnings: tuple[str, ...]
    bound_labels: tuple[tuple[str, str, str], ...]  # (key, label, unit)
    columns: tuple[str, ...]  # the per-axis (or per-channel) columns of the bounds table
    bounds: dict[str, dict[str, float]]  # column -> key -> value
    references: tuple[str, ...]
    bounds_note: str = ""


@dataclass(frozen=True)
class Section:
    """A table section computed outside ``theory`` (e.g. a simulated comparison) for the report.

    Plain strings only, so that ``theory`` renders it without importing the layers above."""

    title: str
    paragraphs: tuple[str, ...]
    columns: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    image: str | None = None  # path relative to the report


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


@dataclass(frozen=True)
class CoverageRow:
    """One item of a paper (equation, definition, hypothesis, lemma, theorem, remark or
    simulation statement) and the claims that check it, or why it is not checkable."""

    item: str
    kind: str
    claims: tuple[str, ...] = ()
    not_checkable: str = ""

    def text(self) -> str:
        return ", ".join(self.claims) if self.claims else "not checkable, because " + \
            self.not_checkable


def _witness_rows(w: Witness) -> list[tuple[str, str]]:
    rows = [(str(k), _short(val)) for k, val in w.point.items()]
    rows += [("margin", fmt(w.margin)), ("found by", w.method),
             ("re-checked margin", fmt(w.rechecked_margin)), ("re-checked by", w.recheck_method)]
    if w.seed is not None:
        rows.append(("seed", str(w.seed)))
    return rows


def _short(x: Any) -> str:
    if isinstance(x, float):
        return fmt(x)
    if isinstance(x, dict | list | tuple):
        return json.dumps(x, sort_keys=True, default=str)
    return str(x)


def _step_line(s: Step) -> str:
    return f"[{s.status}] {s.statement} — {s.evidence.kind}: {s.evidence.summary()}"


def verdict_counts(claims: Sequence[Claim]) -> dict[str, int]:
    """How many claims have each verdict (every verdict listed, strongest first)."""
    return {v: sum(c.verdict == v for c in claims) for v in VERDICTS}


def _by_scope(claims: Sequence[Claim]) -> list[tuple[str, list[Claim]]]:
    return [(title, [c for c in claims if c.scope == sc]) for sc, title in SCOPE_TITLES
            if any(c.scope == sc for c in claims)]


def claims_json(claims: Sequence[Claim]) -> str:
    """Machine-readable claims: per claim its id, equations, the paper's and the derived
    statement, scope, verdict, each step with its evidence kind and data, and the witness."""
    return json.dumps({"verdicts": verdict_counts(claims),
                       "claims": [c.to_dict() for c in claims]}, indent=1, sort_keys=True) + "\n"


def _md_sections(sections: Sequence[Section]) -> list[str]:
    L: list[str] = []
    for sec in sections:
        L += ["", f"## {sec.title}", ""]
        for row in (sec.columns, *sec.rows):
            L.append("| " + " | ".join(c.replace("|", "\\|") for c in row) + " |")
            if row is sec.columns:
                L.append("|" + "---|" * len(sec.columns))
        for par in sec.paragraphs:
            L += ["", par]
        if sec.image:
            L += ["", f"![{sec.title}]({sec.image})"]
    return L


def _md_table(columns: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    def cell(x: str) -> str:
        return x.replace("|", "\\|").replace("\n", " ")
    L = ["| " + " | ".join(cell(c) for c in columns) + " |", "|" + "---|" * len(columns)]
    return L + ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]


def render_markdown(claims: list[Claim], spec: ReportSpec,
                    sections: Sequence[Section] = (), *,
                    coverage: Sequence[CoverageRow] = ()) -> str:
    L = [f"# {spec.title}: derivation report", "",
         f"lgw {lgw_version()}.  Every statement below is derived from the guidance law itself "
         f"(SymPy) and checked; {VERDICT_LEGEND}.", "",
         "## Gain set", "", "| parameter | value |", "|---|---|"]
    L += [f"| {k} | {val} |" for k, val in spec.gain_rows]
    for w in spec.warnings:
        L += ["", f"> warning: {w}"]
    L += ["", "## Bounds for this gain set (per axis)", "",
          "| bound | unit | " + " | ".join(spec.columns) + " |",
          "|---|---|" + "---|" * len(spec.columns)]
    for key, label, unit in spec.bound_labels:
        if key in spec.bounds[spec.columns[0]]:
            L.append(f"| {label} (`{key}`) | {unit} | "
                     + " | ".join(fmt(spec.bounds[a][key]) for a in spec.columns) + " |")
    counts = verdict_counts(claims)
    L += ["", spec.bounds_note, "", "## Verdicts", "",
          "Summary: " + ", ".join(f"{v} {n}" for v, n in counts.items()) + "."]
    for title, group in _by_scope(claims):
        L += ["", f"### {title}", "", "| claim | equations | law | verdict |", "|---|---|---|---|"]
        L += [f"| [{c.id}](#{c.id}) | {c.equations} | {c.law or '-'} | **{c.verdict}** |"
              for c in group]
    for title, group in _by_scope(claims):
        L += ["", f"## {title}"]
        for c in group:
            L += ["", f"### {c.id}", "", f"**{c.title}** — equations {c.equations}"
                  + (f", law: {c.law}" if c.law else "") + f", scope: {c.scope}", "",
                  f"- Paper: {c.paper}", f"- Derived: {c.derived}",
                  f"- Verdict: **{c.verdict_text()}**", "", "Steps:", ""]
            L += [f"{i}. {_step_line(s)}" for i, s in enumerate(c.steps, 1)]
            if c.remarks:
                L += ["", "Remarks on the paper's own argument (not part of the verdict):", ""]
                L += [f"- {_step_line(s)}" for s in c.remarks]
            if c.counterexample:
                L += ["", "Counterexample:", ""] + _md_table(("", ""),
                                                              _witness_rows(c.counterexample))
            if c.numbers:
                L += ["", f"Numbers: `{json.dumps(c.numbers, sort_keys=True, default=str)}`"]
    if coverage:
        L += ["", "## Coverage of the paper", ""]
        L += _md_table(("item", "kind", "claims"), [(r.item, r.kind, r.text()) for r in coverage])
    L += _md_sections(sections)
    L += ["", "## References", ""] + [f"- {ref}" for ref in spec.references] + [""]
    return "\n".join(L)


_TEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
        "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\^{}", "<": r"$<$",
        ">": r"$>$", "|": r"$|$", "—": "---"}


def tex(s: str) -> str:
    return "".join(_TEX.get(ch, ch) for ch in s)


def render_latex(claims: list[Claim], spec: ReportSpec,
                 sections: Sequence[Section] = (), *,
                 coverage: Sequence[CoverageRow] = ()) -> str:
    L = [r"\documentclass[10pt]{article}", r"\usepackage[margin=2cm]{geometry}",
         r"\usepackage{longtable}", r"\usepackage{graphicx}", r"\begin{document}",
         r"\section*{" + tex(spec.title) + ": derivation report}",
         tex(f"lgw {lgw_version()}. {VERDICT_LEGEND}."),
         r"\subsection*{Gain set}", r"\begin{tabular}{ll}"]
    L += [tex(k) + " & " + tex(val) + r" \\" for k, val in spec.gain_rows]
    L += [r"\end{tabular}"] + [r"\paragraph{Warning.} " + tex(w) for w in spec.warnings]
    L += [r"\subsection*{Bounds (per axis)}", r"\begin{longtable}{ll" + "r" * len(spec.columns)
          + "}", "bound & unit & " + " & ".join(spec.columns) + r" \\ \hline"]
    for key, label, unit in spec.bound_labels:
        if key in spec.bounds[spec.columns[0]]:
            L.append(tex(label) + " & " + tex(unit) + " & "
                     + " & ".join(tex(fmt(spec.bounds[a][key])) for a in spec.columns) + r" \\")
    counts = verdict_counts(claims)
    L += [r"\end{longtable}", r"\subsection*{Verdicts}",
          tex("Summary: " + ", ".join(f"{v} {n}" for v, n in counts.items()) + ".")]
    for title, group in _by_scope(claims):
        L += [r"\paragraph{" + tex(title) + "}", r"\begin{longtable}{lp{5cm}lp{2cm}}",
              r"claim & equations & law & verdict \\ \hline"]
        L += [" & ".join(tex(x) for x in (c.id, c.equations, c.law or "-", c.verdict)) + r" \\"
              for c in group]
        L.append(r"\end{longtable}")
    for title, group in _by_scope(claims):
        L.append(r"\subsection*{" + tex(title) + "}")
        for c in group:
            L += [r"\subsubsection*{" + tex(f"{c.id}: {c.title} {c.equations}") + "}",
                  r"\textbf{Paper:} " + tex(c.paper) + r"\\",
                  r"\textbf{Derived:} " + tex(c.derived) + r"\\",
                  r"\textbf{Verdict:} \textbf{" + tex(c.verdict_text()) + "}",
                  r"\begin{enumerate}"]
            L += [r"\item " + tex(_step_line(s)) for s in c.steps]
            L.append(r"\end{enumerate}")
            for s in c.remarks:
                L.append(r"\paragraph{Remark.} " + tex(_step_line(s)))
            if c.counterexample:
                L += [r"\paragraph{Counterexample.}", r"{\scriptsize\begin{tabular}{lp{11cm}}"]
                L += [tex(k) + " & " + tex(val) + r" \\" for k, val in
                      _witness_rows(c.counterexample)]
                L.append(r"\end{tabular}}")
    if coverage:
        L += [r"\subsection*{Coverage of the paper}", r"{\scriptsize",
              r"\begin{longtable}{p{3cm}lp{10cm}}", r"item & kind & claims \\ \hline"]
        L += [" & ".join(tex(x) for x in (r.item, r.kind, r.text())) + r" \\" for r in coverage]
        L.append(r"\end{longtable}}")
    for sec in sections:
        L += [r"\subsection*{" + tex(sec.title) + "}", r"{\scriptsize",
              r"\begin{longtable}{" + "l" * len(sec.columns) + "}",
              " & ".join(tex(c) for c in sec.columns) + r" \\ \hline"]
        L += [" & ".join(tex(c) for c in row) + r" \\" for row in sec.rows]
        L += [r"\end{longtable}}"] + [tex(p) + "\n" for p in sec.paragraphs]
        if sec.image:
            L.append(r"\IfFileExists{" + sec.image + r"}{\includegraphics[width=\linewidth]{"
                     + sec.image + "}}{}")
    L += [r"\section*{References}", r"\begin{enumerate}"]
    L += [r"\item " + tex(ref) for ref in spec.references]
    L += [r"\end{enumerate}", r"\end{document}", ""]
    return "\n".join(L)


def render_html(claims: list[Claim], spec: ReportSpec,
                sections: Sequence[Section] = (), *,
                coverage: Sequence[CoverageRow] = ()) -> str:
    e = html.escape
    L = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'><title>"
         f"{e(spec.title)} derivation report</title>"
         "<style>body{font-family:sans-serif;max-width:60em;margin:auto}"
         "td,th{border:1px solid #ccc;padding:2px 6px}table{border-collapse:collapse}"
         ".refuted{color:#b00}.proved,.proved-given{color:#070}.checked{color:#850}"
         ".unproven{color:#666}</style></head><body>",
         f"<h1>{e(spec.title)}: derivation report</h1>",
         f"<p>lgw {e(lgw_version())}. {e(VERDICT_LEGEND)}.</p>", "<h2>Gain set</h2><table>"]
    L += [f"<tr><td>{e(k)}</td><td>{e(val)}</td></tr>" for k, val in spec.gain_rows]
    L.append("</table>")
    L += [f"<p><b>warning:</b> {e(w)}</p>" for w in spec.warnings]
    L.append("<h2>Bounds (per axis)</h2><table><tr><th>bound</th><th>unit</th>"
             + "".join(f"<th>{a}</th>" for a in spec.columns) + "</tr>")
    for key, label, unit in spec.bound_labels:
        if key in spec.bounds[spec.columns[0]]:
            L.append(f"<tr><td>{e(label)}</td><td>{e(unit)}</td>"
                     + "".join(f"<td>{e(fmt(spec.bounds[a][key]))}</td>"
                               for a in spec.columns) + "</tr>")
    counts = verdict_counts(claims)
    L.append("</table><h2>Verdicts</h2><p>Summary: "
             + e(", ".join(f"{v} {n}" for v, n in counts.items())) + ".</p>")
    for title, group in _by_scope(claims):
        L.append(f"<h3>{e(title)}</h3><table>")
        L += [f"<tr><td><a href='#{e(c.id)}'>{e(c.id)}</a></td><td>{e(c.equations)}</td>"
              f"<td>{e(c.law or '-')}</td><td class='{c.verdict}'>{c.verdict}</td></tr>"
              for c in group]
        L.append("</table>")
    for title, group in _by_scope(claims):
        L.append(f"<h2>{e(title)}</h2>")
        for c in group:
            L += [f"<h3 id='{e(c.id)}'>{e(c.id)}: {e(c.title)} {e(c.equations)}</h3>",
                  f"<p><b>Paper:</b> {e(c.paper)}</p><p><b>Derived:</b> {e(c.derived)}</p>",
                  f"<p><b>Verdict:</b> <span class='{c.verdict}'>{e(c.verdict_text())}</span>"
                  "</p><ol>"]
            L += [f"<li>[<span class='{s.status}'>{s.status}</span>] {e(s.statement)} — "
                  f"<i>{e(s.evidence.kind)}</i>: {e(s.evidence.summary())}</li>"
                  for s in c.steps]
            L.append("</ol>")
            L += [f"<p>Remark: [{s.status}] {e(s.statement)} — {e(s.evidence.summary())}</p>"
                  for s in c.remarks]
            if c.counterexample:
                L.append("<p>Counterexample:</p><table>")
                L += [f"<tr><td>{e(k)}</td><td>{e(val)}</td></tr>"
                      for k, val in _witness_rows(c.counterexample)]
                L.append("</table>")
    if coverage:
        L.append("<h2>Coverage of the paper</h2><table><tr><th>item</th><th>kind</th>"
                 "<th>claims</th></tr>")
        L += [f"<tr><td>{e(r.item)}</td><td>{e(r.kind)}</td><td>{e(r.text())}</td></tr>"
              for r in coverage]
        L.append("</table>")
    for sec in sections:
        L += [f"<h2>{e(sec.title)}</h2><table><tr>"
              + "".join(f"<th>{e(c)}</th>" for c in sec.columns) + "</tr>"]
        L += ["<tr>" + "".join(f"<td>{e(c)}</td>" for c in row) + "</tr>" for row in sec.rows]
        L.append("</table>")
        L += [f"<p>{e(p)}</p>" for p in sec.paragraphs]
        if sec.image:
            L.append(f"<p><img src='{e(sec.image)}' alt='{e(sec.title)}' width='100%'></p>")
    L += ["<h2>References</h2><ol>"] + [f"<li>{e(ref)}</li>" for ref in spec.references]
    L += ["</ol></body></html>", ""]
    return "\n".join(L)
