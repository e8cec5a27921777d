"""Shared figure machinery for every system: one style, deterministic PNG bytes, limit lines.

Figures need simulation data, so they are made on the tuning floor (``lgw.tuning.<system>.
figures``) and handed to the report renderer (``lgw.theory.report.Figure``) as PNG bytes.

Deterministic: the Agg backend, a fixed style, a fixed dpi, and PNG metadata without the
matplotlib version string, so that the same data give the same bytes on the same installation.
"""

from __future__ import annotations

import io
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

DPI = 110
STYLE: dict[str, Any] = {
    "font.size": 10, "axes.titlesize": 10.5, "axes.labelsize": 10, "legend.fontsize": 8.5,
    "xtick.labelsize": 9, "ytick.labelsize": 9, "axes.grid": True, "grid.alpha": 0.3,
    "grid.linewidth": 0.6, "lines.linewidth": 1.3, "figure.dpi": DPI, "savefig.dpi": DPI,
    "axes.spines.top": False, "axes.spines.right": False, "legend.framealpha": 0.85,
    "path.simplify": True,
}
LIMIT_STYLE: dict[str, Any] = {"color": "#b00000", "ls": "--", "lw": 1.2}
BOUND_STYLES: tuple[dict[str, Any], ...] = (
    {"color": "#1b7837", "ls": "-", "lw": 1.4}, {"color": "#1b7837", "ls": ":", "lw": 1.6},
    {"color": "#762a83", "ls": "-", "lw": 1.4}, {"color": "#762a83", "ls": ":", "lw": 1.6})


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display, same output everywhere)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


@contextmanager
def styled() -> Iterator[Any]:
    """``with styled() as plt:`` makes figures in the shared style."""
    plt = pyplot()
    with plt.rc_context(STYLE):
        yield plt


def png_bytes(fig: Any, dpi: int = DPI) -> bytes:
    """The figure as PNG bytes (no version metadata: deterministic), then closed."""
    plt = pyplot()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def save_png(png: bytes, path: Path) -> Path:
    """Write a PNG atomically (temporary file, then rename: nothing half-written)."""
    from lgw.tuning.io import atomic_writer, make_out_dir

    make_out_dir(path.parent)
    with atomic_writer(path, "wb") as f:
        f.write(png)
    return path


def limit_line(ax: Any, y: float, label: str, *, both_signs: bool = False) -> None:
    """A horizontal limit (e.g. a thrust limit) drawn and labelled in the legend."""
    ax.axhline(y, label=label, **LIMIT_STYLE)
    if both_signs:
        ax.axhline(-y, **LIMIT_STYLE)


def shared_legend(fig: Any, axes: Sequence[Any], *, ncol: int = 3, bottom: float = 0.0) -> None:
    """One legend for the whole figure, below the panels, with every label of ``axes`` once."""
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            if lab not in labels and not lab.startswith("_"):
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=ncol, frameon=False,
               bbox_to_anchor=(0.5, bottom))
