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


def observed_vs_bound(panels: Sequence[dict[str, Any]], title: str) -> bytes:
    """``lgw verify SYSTEM --plot``: one panel per claim, one point per checked case (and axis)
    at (bound, observed), the bound as the line y = x (a point above it violates), violations
    drawn as red crosses, the excluded cases counted in the panel title.

    Each panel: ``claim``, ``equation``, ``bound`` and ``observed`` (1-D arrays, same length;
    the observed value already minus the check's tolerance, so y <= x is the claim),
    ``violated`` (bool array), ``excluded`` (int), ``unit`` (axis label unit, e.g. "s"), and
    optionally ``ylabel`` (default "observed - tolerance").  Axes are logarithmic when every
    point is positive and they span more than two decades (else linear)."""
    import numpy as np

    n = max(len(panels), 1)
    ncol = min(n, 3)
    nrow = -(-n // ncol)
    with styled() as plt:
        fig, axes = plt.subplots(nrow, ncol, figsize=(4.1 * ncol, 3.6 * nrow + 0.5),
                                 squeeze=False)
        for ax in axes.flat[len(panels):]:
            ax.set_visible(False)
        for ax, p in zip(axes.flat, panels, strict=False):
            b = np.asarray(p["bound"], float)
            o = np.asarray(p["observed"], float)
            bad = np.asarray(p["violated"], bool)
            fin = np.isfinite(b) & np.isfinite(o)
            ok = fin & ~bad
            ax.scatter(b[ok], o[ok], s=9, color="#2166ac", alpha=0.6, lw=0,
                       label=f"checked case ({int(ok.sum())})")
            if bad.any():
                # a violation with an infinite observation (never reached) is drawn at the top
                top = np.where(np.isfinite(o), o, np.nanmax(np.where(fin, np.maximum(o, b),
                                                                     0.0), initial=1.0) * 1.1)
                ax.scatter(b[bad], top[bad], s=36, marker="x", color="#d6000f", lw=1.6,
                           label=f"violation ({int(bad.sum())})", zorder=3)
            vals = np.concatenate([b[fin], o[fin]]) if fin.any() else np.array([0.0, 1.0])
            lo, hi = float(np.min(vals)), float(np.max(vals))
            log = lo > 0 and hi / lo > 100
            if log:
                ends = [lo / 1.3, hi * 1.3]
                ax.set_xscale("log")
                ax.set_yscale("log")
            else:
                pad = 0.05 * (hi - lo or 1.0)
                ends = [lo - pad, hi + pad]
                ax.locator_params(nbins=5)
            ax.plot(ends, ends, label="bound (y = x)", **BOUND_STYLES[0])
            u = p.get("unit", "")
            ylab = p.get("ylabel", "observed - tolerance")
            ax.set_xlabel(f"proven bound ({u})" if u else "proven bound")
            ax.set_ylabel(f"{ylab} ({u})" if u else ylab)
            name = p["claim"] if p["equation"] in p["claim"] else f"{p['claim']} {p['equation']}"
            ax.set_title(f"{name}\n{int(fin.sum())} points, "
                         f"{int(p.get('excluded', 0))} cases excluded")
            ax.legend(loc="upper left")
        fig.suptitle(title)
        fig.tight_layout()
        return png_bytes(fig)


def write_verify_plot(plot_dir: Path, system: str, panels: Sequence[dict[str, Any]],
                      title: str) -> Path:
    """Write ``verify_<system>.png`` (observed against bound) atomically into ``plot_dir``
    (checked before any work by ``lgw.tuning.io.check_out_dir``)."""
    return save_png(observed_vs_bound(panels, title), Path(plot_dir) / f"verify_{system}.png")
