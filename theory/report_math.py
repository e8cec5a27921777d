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

SIG_NOTE = "sig(x, q) = |x|^q sgn(x) is written with ceiling-floor brackets: [x]^q"


class _Latex(LatexPrinter):
    def _print_sig(self, e: sp.Basic) -> str:
        x, q = e.args
        return rf"\left\lceil {self._print(x)} \right\rfloor^{{{self._print(q)}}}"


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
        # SymPy's LaTeX printer turns a name "Vdot_2" into a dotted V; its MathML one does not
        node = super()._print_Symbol(sym, style)
        nodes = [node] if node.tagName == "mi" else list(node.getElementsByTagName("mi"))
        for mi in nodes:
            text = mi.firstChild.nodeValue if mi.firstChild is not None else ""
            if len(text) > 3 and text.endswith("dot"):
                over = self.dom.createElement("mover")
                base = self.dom.createElement("mi")
                base.appendChild(self.dom.createTextNode(text[:-3]))
                dot = self.dom.createElement("mo")
                dot.appendChild(self.dom.createTextNode("\u02d9"))
                over.appendChild(base)
                over.appendChild(dot)
                if mi is node:
                    return over
                mi.parentNode.replaceChild(over, mi)
        return node

    def _print_Function(self, e: sp.Basic):
        # SymPy lower-cases function names (V(t) would print as v(t))
        mi = self.dom.createElement("mi")
        mi.appendChild(self.dom.createTextNode(type(e).__name__))
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
    body = _numeric_entities(_MathML().doprint(expr))
    # SymPy 1.14 writes strict relations unescaped (<mo><</mo>): not well-formed XML
    body = body.replace("<mo><</mo>", "<mo>&lt;</mo>").replace("<mo>></mo>", "<mo>&gt;</mo>")
    return f"<math display='{'block' if display else 'inline'}'>{body}</math>"
