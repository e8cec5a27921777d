"""Render a system's claims and a gain set's numbers as Markdown, LaTeX and HTML.

What is particular to a system (title, gain rows, warnings, bound labels, per-axis columns,
references) arrives in a ``ReportSpec`` that the system's own report module builds.

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

from lgw.theory.claims import Claim


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


def _ce(c: Claim) -> str:
    return json.dumps(c.counterexample, sort_keys=True, default=str) if c.counterexample else ""


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


def render_markdown(claims: list[Claim], spec: ReportSpec,
                    sections: Sequence[Section] = ()) -> str:
    L = [f"# {spec.title}: derivation report", "",
         f"lgw {lgw_version()}.  Every statement below is derived from the guidance law itself "
         "(SymPy) and checked; verdicts: proved / checked / refuted / unproven.", "",
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
    L += ["", spec.bounds_note, "",
          "## Verdicts", "", "| claim | equations | law | verdict |", "|---|---|---|---|"]
    L += [f"| [{c.id}](#{c.id}) | {c.equations} | {c.law or '-'} | **{c.verdict}** |"
          for c in claims]
    for c in claims:
        L += ["", f"## {c.id}", "", f"**{c.title}** — equations {c.equations}"
              + (f", law: {c.law}" if c.law else ""), "",
              f"- Paper: {c.paper}", f"- Derived: {c.derived}",
              f"- Verdict: **{c.verdict}** ({c.evidence})", "", "Steps:", ""]
        L += [f"{i}. [{s.status}] {s.statement} — *{s.method}*"
              + (f" — {s.detail}" if s.detail else "") for i, s in enumerate(c.steps, 1)]
        if c.remarks:
            L += ["", "Remarks on the paper's own argument:", ""]
            L += [f"- [{s.status}] {s.statement} — {s.detail}" for s in c.remarks]
        if c.counterexample:
            L += ["", f"Counterexample: `{_ce(c)}`"]
        if c.numbers:
            L += ["", f"Numbers: `{json.dumps(c.numbers, sort_keys=True, default=str)}`"]
    L += _md_sections(sections)
    L += ["", "## References", ""] + [f"- {ref}" for ref in spec.references] + [""]
    return "\n".join(L)


_TEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
        "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\^{}", "<": r"$<$",
        ">": r"$>$", "|": r"$|$", "—": "---"}


def tex(s: str) -> str:
    return "".join(_TEX.get(ch, ch) for ch in s)


def render_latex(claims: list[Claim], spec: ReportSpec,
                 sections: Sequence[Section] = ()) -> str:
    L = [r"\documentclass[10pt]{article}", r"\usepackage[margin=2cm]{geometry}",
         r"\usepackage{longtable}", r"\usepackage{graphicx}", r"\begin{document}",
         r"\section*{" + tex(spec.title) + ": derivation report}",
         tex(f"lgw {lgw_version()}. Verdicts: proved / checked / refuted / unproven."),
         r"\subsection*{Gain set}", r"\begin{tabular}{ll}"]
    L += [tex(k) + " & " + tex(val) + r" \\" for k, val in spec.gain_rows]
    L += [r"\end{tabular}"] + [r"\paragraph{Warning.} " + tex(w) for w in spec.warnings]
    L += [r"\subsection*{Bounds (per axis)}", r"\begin{longtable}{ll" + "r" * len(spec.columns)
          + "}", "bound & unit & " + " & ".join(spec.columns) + r" \\ \hline"]
    for key, label, unit in spec.bound_labels:
        if key in spec.bounds[spec.columns[0]]:
            L.append(tex(label) + " & " + tex(unit) + " & "
                     + " & ".join(tex(fmt(spec.bounds[a][key])) for a in spec.columns) + r" \\")
    L += [r"\end{longtable}", r"\subsection*{Verdicts}", r"\begin{longtable}{lllp{2cm}}",
          r"claim & equations & law & verdict \\ \hline"]
    L += [" & ".join(tex(x) for x in (c.id, c.equations, c.law or "-", c.verdict)) + r" \\"
          for c in claims]
    L.append(r"\end{longtable}")
    for c in claims:
        L += [r"\subsection*{" + tex(f"{c.id}: {c.title} {c.equations}") + "}",
              r"\textbf{Paper:} " + tex(c.paper) + r"\\",
              r"\textbf{Derived:} " + tex(c.derived) + r"\\",
              r"\textbf{Verdict:} \textbf{" + tex(c.verdict) + "} (" + tex(c.evidence) + ")",
              r"\begin{enumerate}"]
        L += [r"\item [" + tex(s.status) + "] " + tex(s.statement) + r" --- \emph{"
              + tex(s.method) + "}" + (" --- " + tex(s.detail) if s.detail else "")
              for s in c.steps]
        L.append(r"\end{enumerate}")
        for s in c.remarks:
            L.append(r"\paragraph{Remark.} [" + tex(s.status) + "] " + tex(s.statement) + " --- "
                     + tex(s.detail))
        if c.counterexample:
            L.append(r"\paragraph{Counterexample.} \texttt{" + tex(_ce(c)) + "}")
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
                sections: Sequence[Section] = ()) -> str:
    e = html.escape
    L = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'><title>"
         f"{e(spec.title)} derivation report</title>"
         "<style>body{font-family:sans-serif;max-width:60em;margin:auto}"
         "td,th{border:1px solid #ccc;padding:2px 6px}table{border-collapse:collapse}"
         ".refuted{color:#b00}.proved{color:#070}.checked{color:#850}.unproven{color:#666}"
         "</style></head><body>", f"<h1>{e(spec.title)}: derivation report</h1>",
         f"<p>lgw {e(lgw_version())}</p>", "<h2>Gain set</h2><table>"]
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
    L.append("</table><h2>Verdicts</h2><table>")
    L += [f"<tr><td><a href='#{e(c.id)}'>{e(c.id)}</a></td><td>{e(c.equations)}</td>"
          f"<td>{e(c.law or '-')}</td><td class='{c.verdict}'>{c.verdict}</td></tr>"
          for c in claims]
    L.append("</table>")
    for c in claims:
        L += [f"<h2 id='{e(c.id)}'>{e(c.id)}: {e(c.title)} {e(c.equations)}</h2>",
              f"<p><b>Paper:</b> {e(c.paper)}</p><p><b>Derived:</b> {e(c.derived)}</p>",
              f"<p><b>Verdict:</b> <span class='{c.verdict}'>{c.verdict}</span> "
              f"({e(c.evidence)})</p><ol>"]
        L += [f"<li>[<span class='{s.status}'>{s.status}</span>] {e(s.statement)} — "
              f"<i>{e(s.method)}</i>" + (f" — {e(s.detail)}" if s.detail else "") + "</li>"
              for s in c.steps]
        L.append("</ol>")
        L += [f"<p>Remark: [{s.status}] {e(s.statement)} — {e(s.detail)}</p>" for s in c.remarks]
        if c.counterexample:
            L.append(f"<p>Counterexample: <code>{e(_ce(c))}</code></p>")
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
