"""Result tables of every verb: readable at 80 columns, never a number cut short.

``result_table(title, columns, rows)`` prints a rich table whose cells fold (wrap) instead of
being cut to "5.4/7…"; when even folded the table would not fit the console (a narrow
terminal), it is stacked instead: one block per row, ``column: value`` per line.  ``fmt``
formats numbers the same way everywhere ("-" for missing or non-finite).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

MIN_COL = 6  # a column narrower than this would split numbers into unreadable pieces


def fmt(x: Any, spec: str = ".4g") -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, int | float):
        if isinstance(x, float) and not math.isfinite(x):
            return "-" if math.isnan(x) else ("inf" if x > 0 else "-inf")
        return format(x, spec)
    return str(x)


def _natural_width(columns: Sequence[str], rows: Sequence[Sequence[str]]) -> int:
    widths = [max([len(c)] + [len(str(r[i])) for r in rows]) for i, c in enumerate(columns)]
    return sum(widths) + 3 * len(columns) + 1


def _longest_word(columns: Sequence[str], rows: Sequence[Sequence[str]]) -> list[int]:
    """Per column, the longest unbreakable token (numbers must never be split)."""
    out = []
    for i, c in enumerate(columns):
        words = c.split() + [w for r in rows for w in str(r[i]).split()]
        out.append(max([MIN_COL] + [len(w) for w in words]))
    return out


def result_table(con: Any, title: str, columns: Sequence[str],
                 rows: Sequence[Sequence[Any]], justify: Sequence[str] | None = None,
                 styles: Sequence[str | None] | None = None) -> None:
    """Print ``rows`` under ``columns`` on the rich console ``con``: a folded table when it
    fits ``con.width`` without splitting a token, else stacked blocks."""
    from rich.table import Table

    cells = [[fmt(v) if not isinstance(v, str) else v for v in r] for r in rows]
    width = getattr(con, "width", 80)
    fits = _natural_width(columns, cells) <= width or \
        sum(_longest_word(columns, cells)) + 3 * len(columns) + 1 <= width
    if not fits:
        con.print(title, markup=False, highlight=False, soft_wrap=True)
        for row in cells:
            con.print(f"- {columns[0]}: {row[0]}", markup=False, highlight=False, soft_wrap=True)
            for c, v in zip(columns[1:], row[1:], strict=True):
                con.print(f"    {c}: {v}", markup=False, highlight=False, soft_wrap=True)
        return
    t = Table(title=title, title_justify="left")
    mins = _longest_word(columns, cells)
    for i, c in enumerate(columns):
        t.add_column(c, justify=(justify[i] if justify else ("left" if i == 0 else "right")),
                     overflow="fold", min_width=min(mins[i], width // max(len(columns), 1)))
    for i, row in enumerate(cells):
        t.add_row(*row, style=(styles[i] if styles else None))
    con.print(t)
