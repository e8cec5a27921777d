"""Checks shared by every system's figure tests (``tests/<system>/test_figures.py``): a figure
is a valid PNG of a readable size that is not a blank canvas, drawn to the same bytes and
caption twice; a report embeds every figure it writes as a data URI of exactly those bytes."""

from __future__ import annotations

import base64
import io
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def decode(png: bytes) -> np.ndarray:
    import matplotlib.image as mpimg

    return mpimg.imread(io.BytesIO(png), format="png")


def assert_deterministic_pngs(figs: Sequence[Any], again: Sequence[Any], files: Sequence[str],
                              min_size: tuple[int, int] = (300, 700)) -> None:
    """``figs`` (``Figure`` records) are ``files`` in order: valid PNGs larger than
    ``min_size`` (rows, columns of pixels), not blank, and the same bytes and captions as
    ``again`` (the same figures drawn a second time)."""
    assert tuple(f.file for f in figs) == tuple(files)
    for f, h in zip(figs, again, strict=True):
        assert f.png.startswith(PNG_SIGNATURE), f.file
        img = decode(f.png)
        assert img.ndim == 3 and img.shape[0] > min_size[0] and img.shape[1] > min_size[1], \
            f.file
        assert img.std() > 0.01, f.file  # not a blank canvas
        assert f.png == h.png, f"{f.file}: not the same bytes twice"
        assert f.caption == h.caption


def embedded_pngs(html: str) -> list[bytes]:
    """The PNGs a report's HTML embeds as data URIs, in order."""
    return [base64.b64decode(u)
            for u in re.findall(r"src='data:image/png;base64,([A-Za-z0-9+/=]+)'", html)]


def assert_report_embeds(folder: Path, files: Sequence[str], output: str) -> list[bytes]:
    """Every figure of ``files`` written in ``folder`` beside report.html is a PNG that the
    HTML embeds byte for byte and the command's ``output`` names; the HTML links nothing
    outside itself.  Returns the embedded PNGs."""
    html = (folder / "report.html").read_text()
    embedded = embedded_pngs(html)
    for name in files:
        png = (folder / name).read_bytes()
        assert png.startswith(PNG_SIGNATURE)
        assert png in embedded, name
        assert name in output
    assert "http:" not in html and "https:" not in html
    return embedded
