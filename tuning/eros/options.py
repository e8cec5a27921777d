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
    phase (rad, the case's disturbance phase; default 0), any order, one case per row, UTF-8.
    Missing or duplicated columns, rows of the wrong length, non-numbers, NaN/inf and files
    without rows are ParameterErrors naming the file, row and column.  Returns (e0 (N, 3),
    ed0 (N, 3), phase (N,))."""
    import csv
    import math

    import numpy as np
    from lgw.theory.errors import ParameterError

    name = "--initial-states"
    try:
        text = Path(path).read_bytes().decode("utf-8-sig")
    except OSError as e:
        raise ParameterError(name, str(path), f"cannot be read ({e.strerror})") from e
    except UnicodeDecodeError:
        raise ParameterError(name, str(path), "is not UTF-8 text") from None
    try:
        table = [r for r in csv.reader(text.splitlines()) if any(c.strip() for c in r)]
    except csv.Error as e:
        raise ParameterError(name, str(path), f"is not valid CSV ({e})") from None
    cols = (*STATE_COLUMNS, "phase")
    header = [h.strip() for h in table[0]] if table else []
    missing = [c for c in STATE_COLUMNS if c not in header]
    dup = sorted({h for h in header if h in cols and header.count(h) > 1})
    if missing or dup:
        raise ParameterError(name, str(path), f"needs a header with {', '.join(STATE_COLUMNS)} "
                             "(and optionally phase) once each; "
                             + (f"missing {', '.join(missing)}" if missing
                                else f"duplicated {', '.join(dup)}"))
    if len(table) < 2:
        raise ParameterError(name, str(path), "has no data rows")
    use = [c for c in cols if c in header]
    data = np.zeros((len(table) - 1, 7))
    for i, row in enumerate(table[1:]):
        if len(row) != len(header):
            raise ParameterError(f"{name} row {i + 2}", len(row),
                                 f"must have {len(header)} fields like the header")
        for c in use:
            cell = row[header.index(c)].strip()
            try:
                x = float(cell)
            except ValueError:
                raise ParameterError(f"{name} row {i + 2} {c}", cell, "must be a number") \
                    from None
            if not math.isfinite(x):
                raise ParameterError(f"{name} row {i + 2} {c}", cell, "must be finite")
            data[i, cols.index(c)] = x
    return data[:, :3], data[:, 3:6], data[:, 6]
