"""Render seed 000's claims and a gain set's numbers as Markdown, LaTeX and HTML.

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

from theory.claims import Claim
from theory.gains import Gains
from theory.parameters import AXES

REFERENCES = [
    "Seed 000: Mars powered-descent phase guidance design based on fixed-time stabilization "
    "technique (the paper under review; equation numbers refer to it).",
    "A. Polyakov, Nonlinear feedback design for fixed-time stabilization of linear control "
    "systems, IEEE TAC 57(8), 2012 (the bound (3)).",
    "R. Aldana-Lopez, D. Gomez-Gutierrez, E. Jimenez-Rodriguez, J. D. Sanchez-Torres, "
    "M. Defoort, Enhancing the settling time estimation of a class of fixed-time stable "
    "systems, IJRNC 29(12), 2019 (the least upper bound T*).",
    "B. Acikmese, S. R. Ploen, Convex programming approach to powered descent guidance for "
    "Mars landing, JGCD 30(5), 2007 (the Table I lander, Isp = 225 s, dry mass).",
]

BOUND_LABELS = [
    ("T1_polyakov", "(18) T1, Polyakov", "s"), ("T1_exact", "T1*, exact", "s"),
    ("T2_polyakov", "(26) T2, Polyakov", "s"), ("T2_exact", "T2*, exact", "s"),
    ("T_whole_paper", "paper: max{T1, T2}", "s"),
    ("landing_time_bound", "landing bound T1* + T2* (no disturbance)", "s"),
    ("landing_time_bound_polyakov", "landing bound (18) + (26)", "s"),
    ("s2_bound", "(39) |s2| neighbourhood", "m/s"), ("T2_practical", "(40) time to (39)", "s"),
    ("T2_practical_exact", "time to (39), exact", "s"),
    ("s1_bound", "(31) |r| neighbourhood", "m"), ("T1_practical", "(45) time to (31)", "s"),
    ("T1_practical_exact", "time to (31), exact", "s"),
    ("T3_paper", "(32) as printed", "s"), ("v_bound", "|v| inside both neighbourhoods", "m/s"),
    ("landing_time_bound_disturbed", "landing bound under disturbance (40*)+(45*)", "s"),
]


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


def gain_warnings(g: Gains) -> list[str]:
    """Notes on a gain set that is valid for the bounds but risky for a law."""
    out = []
    if g.q1 < 0.5:
        out.append(f"q1 = {g.q1} < 1/2: the term |s1|^(2 q1 - 1) of the printed law (25) is "
                   "unbounded at s1 = 0; the bounds hold, the printed law's command does not "
                   "stay bounded.")
    elif g.q1 == 0.5:
        out.append("q1 = 1/2: the term |s1|^(2 q1 - 1) sgn(s1) of (25) is the discontinuous "
                   "sgn(s1).")
    return out


def _gain_rows(g: Gains) -> list[tuple[str, str]]:
    d = g.to_dict()
    rows = [(k, ", ".join(fmt(x) for x in val) if isinstance(val, list) else fmt(val))
            for k, val in d["gains"].items()]
    if "disturbance" in d:
        rows += [(k, fmt(val)) for k, val in d["disturbance"].items()]
    return rows


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


def render_markdown(claims: list[Claim], g: Gains, bounds: dict[str, dict[str, float]],
                    sections: Sequence[Section] = ()) -> str:
    L = ["# Seed 000: derivation report", "",
         f"lgw {lgw_version()}.  Every statement below is derived from the guidance law itself "
         "(SymPy) and checked; verdicts: proved / checked / refuted / unproven.", "",
         "## Gain set", "", "| parameter | value |", "|---|---|"]
    L += [f"| {k} | {val} |" for k, val in _gain_rows(g)]
    for w in gain_warnings(g):
        L += ["", f"> warning: {w}"]
    L += ["", "## Bounds for this gain set (per axis)", "",
          "| bound | unit | " + " | ".join(AXES) + " |", "|---|---|" + "---|" * len(AXES)]
    for key, label, unit in BOUND_LABELS:
        if key in bounds["x"]:
            L.append(f"| {label} (`{key}`) | {unit} | "
                     + " | ".join(fmt(bounds[a][key]) for a in AXES) + " |")
    L += ["", "The landing-time bounds are the workbench's own: sound for the corrected law; "
          "the printed law (25) has no proven bound (see claims V2dot-printed, T2-printed).", "",
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
    L += ["", "## References", ""] + [f"- {ref}" for ref in REFERENCES] + [""]
    return "\n".join(L)


_TEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
        "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\^{}", "<": r"$<$",
        ">": r"$>$", "|": r"$|$", "—": "---"}


def tex(s: str) -> str:
    return "".join(_TEX.get(ch, ch) for ch in s)


def render_latex(claims: list[Claim], g: Gains, bounds: dict[str, dict[str, float]],
                 sections: Sequence[Section] = ()) -> str:
    L = [r"\documentclass[10pt]{article}", r"\usepackage[margin=2cm]{geometry}",
         r"\usepackage{longtable}", r"\usepackage{graphicx}", r"\begin{document}",
         r"\section*{Seed 000: derivation report}",
         tex(f"lgw {lgw_version()}. Verdicts: proved / checked / refuted / unproven."),
         r"\subsection*{Gain set}", r"\begin{tabular}{ll}"]
    L += [tex(k) + " & " + tex(val) + r" \\" for k, val in _gain_rows(g)]
    L += [r"\end{tabular}"] + [r"\paragraph{Warning.} " + tex(w) for w in gain_warnings(g)]
    L += [r"\subsection*{Bounds (per axis)}", r"\begin{longtable}{llrrr}",
          r"bound & unit & x & y & z \\ \hline"]
    for key, label, unit in BOUND_LABELS:
        if key in bounds["x"]:
            L.append(tex(label) + " & " + tex(unit) + " & "
                     + " & ".join(tex(fmt(bounds[a][key])) for a in AXES) + r" \\")
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
    L += [r"\item " + tex(ref) for ref in REFERENCES]
    L += [r"\end{enumerate}", r"\end{document}", ""]
    return "\n".join(L)


def render_html(claims: list[Claim], g: Gains, bounds: dict[str, dict[str, float]],
                sections: Sequence[Section] = ()) -> str:
    e = html.escape
    L = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'><title>Seed 000 derivation report"
         "</title><style>body{font-family:sans-serif;max-width:60em;margin:auto}"
         "td,th{border:1px solid #ccc;padding:2px 6px}table{border-collapse:collapse}"
         ".refuted{color:#b00}.proved{color:#070}.checked{color:#850}.unproven{color:#666}"
         "</style></head><body>", "<h1>Seed 000: derivation report</h1>",
         f"<p>lgw {e(lgw_version())}</p>", "<h2>Gain set</h2><table>"]
    L += [f"<tr><td>{e(k)}</td><td>{e(val)}</td></tr>" for k, val in _gain_rows(g)]
    L.append("</table>")
    L += [f"<p><b>warning:</b> {e(w)}</p>" for w in gain_warnings(g)]
    L.append("<h2>Bounds (per axis)</h2><table><tr><th>bound</th><th>unit</th>"
             + "".join(f"<th>{a}</th>" for a in AXES) + "</tr>")
    for key, label, unit in BOUND_LABELS:
        if key in bounds["x"]:
            L.append(f"<tr><td>{e(label)}</td><td>{e(unit)}</td>"
                     + "".join(f"<td>{e(fmt(bounds[a][key]))}</td>" for a in AXES) + "</tr>")
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
    L += ["<h2>References</h2><ol>"] + [f"<li>{e(ref)}</li>" for ref in REFERENCES]
    L += ["</ol></body></html>", ""]
    return "\n".join(L)


def citation() -> str:
    """The references behind the bounds and claims, for users to cite."""
    return "\n".join(REFERENCES)
