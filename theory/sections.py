"""What the layers above hand to the report renderer: figures and computed sections.

Plain strings and bytes only (no SymPy), so that every layer can build them cheaply and
``theory`` renders them without importing the layers above.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Figure:
    """A figure made outside ``theory``: ``file`` is its name beside the report (Markdown and
    LaTeX link it), ``png`` its bytes (the HTML embeds them as a data URI)."""

    file: str
    caption: str
    png: bytes = b""


@dataclass(frozen=True)
class Section:
    """A section computed outside ``theory`` (e.g. a simulated comparison, figures) for the
    report: a table (``columns`` may be empty), paragraphs and figures.

    Plain strings and bytes only, so that ``theory`` renders it without importing the layers
    above.  ``image`` (a file name beside the report) is the older one-figure form; the HTML
    embeds it only when ``render_html(..., asset_dir=)`` can read it."""

    title: str
    paragraphs: tuple[str, ...]
    columns: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    image: str | None = None
    figures: tuple[Figure, ...] = ()
