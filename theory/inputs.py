"""One loader for every file a user hands to lgw: TOML (gains, envelopes, certificates) and CSV
(initial states), for every system.

What it guarantees, whatever the file:

* only a regular file is read: a FIFO, a device, a socket or a folder is refused before it is
  opened for reading (a FIFO would block forever, /dev/zero read without end);
* at most ``max_bytes`` are read (a larger file is refused, never read whole);
* the text is UTF-8 (a byte-order mark is accepted); binary content (a NUL byte) and other
  encodings are refused with the offset of the first bad byte;
* TOML: the syntax, duplicate keys, nesting deeper than ``MAX_DEPTH``, arrays longer than
  ``MAX_ITEMS``, integers outside the float range and non-finite floats are refused, each
  naming the key path;
* CSV: the header holds each required column once; every row has the header's length; every
  cell of a used column is a finite number; at most ``max_rows`` rows.

Every refusal is a ``ParameterError`` naming the option and the file (one line, exit 2).
"""

from __future__ import annotations

import csv
import math
import os
import stat
import tomllib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError

MAX_BYTES = 4 * 2**20  # a gains, envelope or certificate file: 4 MiB is generous
MAX_CSV_BYTES = 256 * 2**20  # a states file: about two million rows of seven numbers
MAX_DEPTH = 6  # tables and arrays: the deepest lgw file is [table.sub] = [[a, b], [c, d]]
MAX_ITEMS = 10_000  # elements of one TOML array
MAX_ROWS = 2_000_000  # CSV data rows
FLOAT_MAX = 1.7976931348623157e308


def read_user_bytes(path: str | Path, name: str, max_bytes: int = MAX_BYTES) -> bytes:
    """The bytes of a regular file of at most ``max_bytes``; anything else is refused."""
    p = Path(path)
    shown = str(p)
    try:
        st = os.stat(p)
    except FileNotFoundError:
        raise ParameterError(name, shown, "does not exist") from None
    except OSError as e:
        raise ParameterError(name, shown, f"cannot be read ({e.strerror})") from None
    if stat.S_ISDIR(st.st_mode):
        raise ParameterError(name, shown, "is a folder; give a file")
    if not stat.S_ISREG(st.st_mode):
        kind = ("a FIFO" if stat.S_ISFIFO(st.st_mode) else "a device"
                if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
                else "a socket" if stat.S_ISSOCK(st.st_mode) else "not a regular file")
        raise ParameterError(name, shown, f"is {kind}; lgw reads regular files only")
    if st.st_size > max_bytes:
        raise ParameterError(name, shown, f"is {st.st_size} bytes; at most {max_bytes} "
                             "(is it the right file?)")
    try:
        # O_NONBLOCK: if the path was swapped for a FIFO after the check, open does not block
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as e:
        raise ParameterError(name, shown, f"cannot be read ({e.strerror})") from None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise ParameterError(name, shown, "is not a regular file; lgw reads regular "
                                 "files only")
        with os.fdopen(fd, "rb", closefd=False) as f:
            raw = f.read(max_bytes + 1)
    except OSError as e:
        raise ParameterError(name, shown, f"cannot be read ({e.strerror})") from None
    finally:
        os.close(fd)
    if len(raw) > max_bytes:
        raise ParameterError(name, shown, f"is larger than {max_bytes} bytes")
    return raw


def decode_text(raw: bytes, name: str, shown: str) -> str:
    """UTF-8 text of a user file (a leading byte-order mark dropped); binary or other encodings
    are a ParameterError naming the option ``name`` and the file ``shown``."""
    if b"\x00" in raw:
        raise ParameterError(name, shown, "is a binary file (it contains NUL bytes), not text")
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise ParameterError(name, shown, f"is not UTF-8 text (byte 0x{raw[e.start]:02x} at "
                             f"offset {e.start})") from None


def check_toml_values(data: Any, name: str, shown: str, where: str = "", depth: int = 0
                      ) -> None:
    """Refuse TOML content no lgw file can mean: too deep, too long, a number outside the
    float range, a non-finite float (``nan``, ``inf``)."""
    if depth > MAX_DEPTH:
        raise ParameterError(f"{name} {where}".strip(), shown,
                             f"nests tables or arrays deeper than {MAX_DEPTH} levels")
    if isinstance(data, dict):
        for k, v in data.items():
            check_toml_values(v, name, shown, f"{where}.{k}" if where else str(k), depth + 1)
    elif isinstance(data, list):
        if len(data) > MAX_ITEMS:
            raise ParameterError(f"{name} {where}", f"{len(data)} items",
                                 f"an array of at most {MAX_ITEMS} items")
        for i, v in enumerate(data):
            check_toml_values(v, name, shown, f"{where}[{i}]", depth + 1)
    elif isinstance(data, bool):
        return
    elif isinstance(data, int):
        if abs(data) > FLOAT_MAX:
            raise ParameterError(where or name, f"{str(data)[:20]}... ({len(str(data))} "
                                 "digits)", "must be a number within the float range "
                                 "(|x| < 1.8e308): too large for a double")
    elif isinstance(data, float):
        if not math.isfinite(data):
            raise ParameterError(where or name, data, "must be a finite number")
    elif isinstance(data, str) and len(data) > 10_000:
        raise ParameterError(where or name, f"{data[:20]}...", "a string of at most 10000 "
                             "characters")


def parse_toml_bytes(raw: bytes, name: str = "--gains", shown: str = "<text>",
                     allow_nonfinite: bool = False) -> dict[str, Any]:
    """Parse a TOML document from bytes; every failure (encoding, syntax, duplicate keys,
    nesting, out-of-range numbers) is a ParameterError.  ``allow_nonfinite``: ``inf`` is a
    meaningful value of this file (a certificate's 'no limit')."""
    text = decode_text(raw, name, shown)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ParameterError(name, shown, f"is not valid TOML ({e})") from None
    except RecursionError:
        raise ParameterError(name, shown, "is not valid TOML (arrays or tables nested too "
                             "deeply)") from None
    if allow_nonfinite:
        _check_structure(data, name, shown)
    else:
        check_toml_values(data, name, shown)
    return data


def _check_structure(data: Any, name: str, shown: str, depth: int = 0) -> None:
    if depth > MAX_DEPTH:
        raise ParameterError(name, shown, f"nests deeper than {MAX_DEPTH} levels")
    if isinstance(data, dict):
        for v in data.values():
            _check_structure(v, name, shown, depth + 1)
    elif isinstance(data, list):
        if len(data) > MAX_ITEMS:
            raise ParameterError(name, shown, f"has an array of more than {MAX_ITEMS} items")
        for v in data:
            _check_structure(v, name, shown, depth + 1)
    elif isinstance(data, int) and not isinstance(data, bool) and abs(data) > FLOAT_MAX:
        raise ParameterError(name, shown, "holds an integer outside the float range")


def load_toml(path: str | Path, name: str = "--gains", max_bytes: int = MAX_BYTES,
              allow_nonfinite: bool = False) -> dict[str, Any]:
    """A user TOML file, read and checked (see the module docstring)."""
    return parse_toml_bytes(read_user_bytes(path, name, max_bytes), name, str(path),
                            allow_nonfinite)


def number(where: str, value: Any, valid: str = "must be a finite number") -> float:
    """A finite float from a TOML value (bools and strings refused) or a ParameterError."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(where, value, valid)
    try:
        x = float(value)
    except OverflowError:
        raise ParameterError(where, f"{str(value)[:20]}...", valid) from None
    if not math.isfinite(x):
        raise ParameterError(where, value, valid)
    return x


def read_csv_columns(path: str | Path, name: str, required: Sequence[str],
                     optional: Sequence[str] = (), max_bytes: int = MAX_CSV_BYTES,
                     max_rows: int = MAX_ROWS) -> dict[str, np.ndarray]:
    """The named numeric columns of a user CSV file (header row, one case per row, any column
    order, extra columns ignored): column name -> float array.  An optional column that is
    absent is left out of the result."""
    shown = str(path)
    text = decode_text(read_user_bytes(path, name, max_bytes), name, shown)
    try:
        table = [r for r in csv.reader(text.splitlines()) if any(c.strip() for c in r)]
    except csv.Error as e:
        raise ParameterError(name, shown, f"is not valid CSV ({e})") from None
    if not table:
        raise ParameterError(name, shown, f"is empty; needs a header {','.join(required)} and "
                             "one row per case")
    header = [h.strip() for h in table[0]]
    cols = (*required, *optional)
    dup = sorted({h for h in header if h in cols and header.count(h) > 1})
    if dup:
        raise ParameterError(name, shown, f"has duplicated columns {', '.join(dup)} (which one "
                             "is meant is ambiguous)")
    missing = [c for c in required if c not in header]
    if missing:
        raise ParameterError(name, shown, f"needs columns {', '.join(required)}; missing "
                             f"{', '.join(missing)} (header: {','.join(header)[:200]})")
    rows = table[1:]
    if not rows:
        raise ParameterError(name, shown, "has no data rows")
    if len(rows) > max_rows:
        raise ParameterError(name, shown, f"has {len(rows)} rows; at most {max_rows}")
    use = [c for c in cols if c in header]
    idx = [header.index(c) for c in use]
    data = np.empty((len(rows), len(use)))
    for i, row in enumerate(rows):
        if len(row) != len(header):
            raise ParameterError(f"{name} row {i + 2}", len(row),
                                 f"must have {len(header)} fields like the header")
        for j, (c, k) in enumerate(zip(use, idx, strict=True)):
            cell = row[k].strip()
            try:
                x = float(cell)
            except ValueError:
                raise ParameterError(f"{name} row {i + 2} column {c}", cell[:100],
                                     "must be a number") from None
            if not math.isfinite(x):
                raise ParameterError(f"{name} row {i + 2} column {c}", cell[:100],
                                     "must be finite")
            data[i, j] = x
    return {c: data[:, j] for j, c in enumerate(use)}
