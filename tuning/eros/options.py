"""Seed 002's command-line helpers."""

from __future__ import annotations

from pathlib import Path

from lgw.theory.eros.gains import Gains, default_gains, load_gains


def resolve_gains(path: Path | None) -> Gains:
    """The gain set of ``--gains`` (validated), or the built-in default."""
    return default_gains() if path is None else load_gains(path)


STATE_COLUMNS = ("ex", "ey", "ez", "vx", "vy", "vz")  # m, m/s: e(0), e'(0) of each case


def read_offsets_csv(path: Path):
    """Initial errors from a CSV with a header ex, ey, ez, vx, vy, vz (m, m/s) and an optional
    phase (rad, the case's disturbance phase; default 0), any order, one case per row
    (``lgw.theory.inputs.read_csv_columns``).  Returns (e0 (N, 3), ed0 (N, 3), phase (N,))."""
    import numpy as np
    from lgw.theory.inputs import read_csv_columns

    cols = read_csv_columns(path, "--initial-states", STATE_COLUMNS, ("phase",))
    n = len(cols["ex"])
    e0 = np.column_stack([cols[c] for c in STATE_COLUMNS[:3]])
    ed0 = np.column_stack([cols[c] for c in STATE_COLUMNS[3:]])
    return e0, ed0, cols.get("phase", np.zeros(n))
