"""Mathematics for the reports: SymPy objects as LaTeX and as presentation MathML.

``latex(expr)`` is ``sympy.latex`` with the signed power sig(x, q) = |x|^q sgn(x) printed as
the usual fixed-time notation ceil(x)floor^q (a left ceiling and a right floor bracket), and
``mathml(expr)`` is ``sympy.printing.mathml(expr, printer="presentation")`` with the same
notation, every named entity turned into a numeric character reference (so that each block is
well-formed XML and needs no DTD) and no namespace URL (HTML5 knows ``<math>``).  Browsers
render MathML natively (MathML Core), so the HTML needs neither network nor script.
"""

from __future__ import annotations

import html.entities
import re
from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.mathml import MathMLPresentationPrinter
from sympy.printing.pretty.pretty_symbology import greek_unicode

SIG_NOTE = "sig(x, q) = |x|^q sgn(x) is written with ceiling-floor brackets: [x]^q"


class _Latex(LatexPrinter):
    def _print_sig(self, e: sp.Basic) -> str:
        x, q = e.args
        return rf"\left\lceil {self._print(x)} \right\rfloor^{{{self._print(q)}}}"


# name suffixes SymPy's LaTeX printer shows as accents, and the accent character for MathML
# (all but the dot drawn as accents, accent="true", which keeps them close to the letter)
_ACCENTS = {"ddot": "\u00a8", "dot": "\u02d9", "bar": "\u00af", "hat": "\u02c6",
            "tilde": "\u02dc"}


class _MathML(MathMLPresentationPrinter):
    def _print_sig(self, e: sp.Basic):
        x, q = e.args
        sup = self.dom.createElement("msup")
        row = self.dom.createElement("mrow")
        for part in ("\u2308", x, "\u230b"):
            if isinstance(part, str):
                mo = self.dom.createElement("mo")
                mo.appendChild(self.dom.createTextNode(part))
                row.appendChild(mo)
            else:
                row.appendChild(self._print(part))
        sup.appendChild(row)
        sup.appendChild(self._print(q))
        return sup

    def _print_Symbol(self, sym: sp.Symbol, style: str = "plain"):
        # SymPy's LaTeX printer turns a name "Vdot_2" into a dotted V ("fbar_1" into a barred
        # f, "dhat" into a hatted d); its MathML one does not
        node = super()._print_Symbol(sym, style)
        nodes = [node] if node.tagName == "mi" else list(node.getElementsByTagName("mi"))
        for mi in nodes:
            text = mi.firstChild.nodeValue if mi.firstChild is not None else ""
            accent = next((a for a in _ACCENTS if len(text) > len(a) and text.endswith(a)), None)
            if accent is not None:
                over = self.dom.createElement("mover")
                if accent != "dot":
                    over.setAttribute("accent", "true")
                base = self.dom.createElement("mi")
                stem = text[:-len(accent)]
                base.appendChild(self.dom.createTextNode(greek_unicode.get(stem, stem)))
                dot = self.dom.createElement("mo")
                dot.appendChild(self.dom.createTextNode(_ACCENTS[accent]))
                over.appendChild(base)
                over.appendChild(dot)
                if mi is node:
                    return over
                mi.parentNode.replaceChild(over, mi)
        return node

    def _print_Function(self, e: sp.Basic):
        # SymPy lower-cases names it has no symbol for (V(t) would print as v(t)); keep its
        # translations (gamma as the capital Gamma, ...)
        tag = self.mathml_tag(e)
        name = type(e).__name__
        mi = self.dom.createElement("mi")
        mi.appendChild(self.dom.createTextNode(name if tag == name.lower() else tag))
        row = self.dom.createElement("mrow")
        row.appendChild(mi)
        row.appendChild(self._paren_comma_separated(*e.args))
        return row


_ENTITY = re.compile(r"&([A-Za-z][A-Za-z0-9]*);")


def _numeric_entities(s: str) -> str:
    def repl(m: re.Match) -> str:
        name = m.group(1)
        if name in ("amp", "lt", "gt", "quot", "apos"):
            return m.group(0)
        chars = html.entities.html5.get(name + ";")
        if chars is None:
            raise ValueError(f"unknown entity &{name};")
        return "".join(f"&#x{ord(c):X};" for c in chars)
    return _ENTITY.sub(repl, s)


def exprs(x: Any) -> tuple[sp.Basic, ...]:
    """A claim's ``paper_expr`` / ``derived_expr`` or a step's ``expr`` as a tuple of SymPy
    objects (one, several, or none); a relation between two zeros (``0 = 0``, what a step
    proving an already reduced residual holds) says nothing and is dropped."""
    if x is None:
        return ()
    items = (tuple(sp.sympify(e) for e in x)
             if isinstance(x, Sequence) and not isinstance(x, str | sp.Basic) else (x,))
    return tuple(e for e in items if not (isinstance(e, sp.core.relational.Relational)
                                          and e.lhs == 0 and e.rhs == 0))


def latex(expr: sp.Basic) -> str:
    """LaTeX of ``expr`` (math mode content)."""
    return _Latex().doprint(expr)


def latex_breakable(expr: sp.Basic, limit: int = 160) -> str:
    r"""LaTeX that TeX may break across lines: a long formula loses its \left/\right pairs
    (TeX cannot break inside them) so that inline math breaks after relations and operators."""
    s = latex(expr)
    if len(s) > limit:
        s = re.sub(r"\\left(?=[(\[|.]|\\[{|]|\\lceil)", "", s)
        s = re.sub(r"\\right(?=[)\]|.]|\\[}|]|\\rfloor)", "", s)
        s = s.replace(r"\left\lceil", r"\lceil").replace(r"\right\rfloor", r"\rfloor")
    return s


def mathml(expr: sp.Basic, display: bool = True) -> str:
    """A ``<math>`` element (presentation MathML) for ``expr``."""
    return f"<math display='{'block' if display else 'inline'}'>{mathml_body(expr)}</math>"


# --- long formulas: broken into lines at the terms of a sum --------------------------------

_REL_TEX = {"==": "=", "<=": r"\leq", "<": "<", ">=": r"\geq", ">": ">"}
_REL_MML = {"==": "=", "<=": "&#x2264;", "<": "&lt;", ">=": "&#x2265;", ">": "&gt;"}


def _terms(expr: sp.Expr) -> list[tuple[str, sp.Expr]]:
    """The terms of a sum in printing order, each as (sign, term without its sign)."""
    out = []
    for t in _Latex()._as_ordered_terms(expr, order=None):
        if t.could_extract_minus_sign():
            out.append(("-", -t))
        else:
            out.append(("+", t))
    return out


def visual_width(tex: str) -> int:
    """About how many glyphs a LaTeX string shows (commands count one, braces and scripts
    markers none): the measure for breaking lines."""
    s = re.sub(r"\\(left|right)\b", "", tex)
    s = re.sub(r"\\[A-Za-z]+", "x", s)
    return len(re.sub(r"[{}^_\s]", "", s))


def split_lines(expr: sp.Basic, width: int = 48) -> list[tuple[str, str]] | None:
    """A long relation or sum broken at the terms of its sum: one (LaTeX, MathML) pair per
    line.  None when the formula is short (``width`` LaTeX characters) or has no sum to break
    at (the callers then print it whole)."""
    if visual_width(latex(expr)) <= width:
        return None
    head_t = head_m = tail_t = tail_m = ""
    body = None
    if isinstance(expr, sp.core.relational.Relational):
        op = expr.rel_op
        if isinstance(expr.rhs, sp.Add) and len(latex(expr.rhs)) >= len(latex(expr.lhs)):
            head_t = latex(expr.lhs) + f" {_REL_TEX[op]} "
            head_m = mathml_body(expr.lhs) + f"<mo>{_REL_MML[op]}</mo>"
            body = expr.rhs
        elif isinstance(expr.lhs, sp.Add):
            tail_t = f" {_REL_TEX[op]} " + latex(expr.rhs)
            tail_m = f"<mo>{_REL_MML[op]}</mo>" + mathml_body(expr.rhs)
            body = expr.lhs
    elif isinstance(expr, sp.Add):
        body = expr
    if body is None:
        return None
    lines: list[tuple[str, str]] = []
    cur_t, cur_m = head_t, head_m
    for i, (sign, term) in enumerate(_terms(body)):
        t_tex, t_mml = latex(term), mathml_body(term)
        if i == 0 and sign == "+":
            piece_t, piece_m = t_tex, t_mml
        else:
            piece_t, piece_m = f" {sign} {t_tex}", f"<mo>{sign}</mo>{t_mml}"
        if visual_width(cur_t + piece_t) > width and cur_t.strip():
            lines.append((cur_t, cur_m))
            cur_t, cur_m = "", ""
        cur_t += piece_t
        cur_m += piece_m
    lines.append((cur_t + tail_t, cur_m + tail_m))
    return lines if len(lines) > 1 else None


def mathml_body(expr: sp.Basic) -> str:
    """The presentation MathML of ``expr`` without the ``<math>`` element."""
    body = _numeric_entities(_MathML().doprint(expr))
    # SymPy 1.14 writes strict relations unescaped (<mo><</mo>): not well-formed XML
    return body.replace("<mo><</mo>", "<mo>&lt;</mo>").replace("<mo>></mo>", "<mo>&gt;</mo>")


def mathml_lines(expr: sp.Basic, width: int = 48) -> str:
    """A ``<math>`` block; a long formula as a left-aligned table of lines (browsers do not
    break MathML lines themselves)."""
    lines = split_lines(expr, width)
    if lines is None:
        return mathml(expr)
    rows = "".join(f"<mtr><mtd><mrow>{m}</mrow></mtd></mtr>" for _, m in lines)
    return f"<math display='block'><mtable columnalign='left'>{rows}</mtable></math>"


# --- display-only functions: quantities the claims name but SymPy has no notation for ------

class Norm(sp.Function):
    """||x||, a norm (e.g. the L2[0, t] norm of seed 001 (18)-(21)), for display only: it does
    not evaluate."""

    nargs = 1

    def _latex(self, printer, exp: str | None = None) -> str:
        s = rf"\left\| {printer._print(self.args[0])} \right\|"
        return s if exp is None else f"{s}^{{{exp}}}"

    def _mathml_presentation(self, printer):
        row = printer.dom.createElement("mrow")
        for part in ("\u2016", self.args[0], "\u2016"):
            if isinstance(part, str):
                mo = printer.dom.createElement("mo")
                mo.appendChild(printer.dom.createTextNode(part))
                row.appendChild(mo)
            else:
                row.appendChild(printer._print(part))
        return row


class At(sp.Function):
    """x(p), the value of the quantity ``x`` (a symbol) at the point ``p`` (e.g. V_2(0), e(t_s)),
    for display only: it does not evaluate."""

    nargs = 2

    def _latex(self, printer, exp: str | None = None) -> str:
        x, p = self.args
        s = rf"{printer._print(x)}\left({printer._print(p)}\right)"
        return s if exp is None else rf"\left({s}\right)^{{{exp}}}"

    def _mathml_presentation(self, printer):
        x, p = self.args
        row = printer.dom.createElement("mrow")
        row.appendChild(printer._print(x))
        for part in ("(", p, ")"):
            if isinstance(part, str):
                mo = printer.dom.createElement("mo")
                mo.setAttribute("lspace", "0")
                mo.setAttribute("rspace", "0")
                mo.appendChild(printer.dom.createTextNode(part))
                row.appendChild(mo)
            else:
                row.appendChild(printer._print(part))
        return row
