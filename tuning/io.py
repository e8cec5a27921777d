"""Output helpers shared by every command: check ``--out`` first, write atomically, strict JSON.

* ``check_out_dir(path)`` / ``check_out_file(path)`` run before any work: the folder (or the
  file's folder) exists or can be created, and is writable.  A bad ``--out`` is a
  ``ParameterError`` (one line ``error: ...``, exit 2) before a campaign runs, never a traceback
  after it.
* ``atomic_write_text`` / ``atomic_write_bytes`` / ``atomic_writer`` write a temporary file in
  the destination's own folder and ``os.replace`` it onto the destination, so a reader sees the
  old file or the whole new one, never half of it, and a failure leaves nothing behind.
* ``strict_json(obj)`` is ``json.dumps(..., allow_nan=False)`` after replacing every non-finite
  float by ``null``; ``json_document`` adds ``lgw_version`` and, when any value was replaced,
  ``"nonfinite_replaced": true`` (documented in docs/json.md).
* ``console()`` is the rich console of every table: as wide as the content when stdout is not
  a terminal (a pipe or a CI log), so headers and cells are never truncated to 80 columns.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError

PIPE_WIDTH = 10_000  # columns of a console that is not a terminal: wide enough for any table


def _writable_dir(name: str, d: Path, shown: Path | None = None) -> None:
    """Probe that files can be created in folder ``d`` (a real temporary file, removed at once:
    permission bits say nothing for root, read-only mounts or /proc)."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".lgw-probe-", dir=d)
    except OSError as e:
        what = "is not a writable folder" if shown is None else f"cannot be created in {d}"
        raise ParameterError(name, str(shown or d), f"{what} ({e.strerror})") from None
    os.close(fd)
    os.unlink(tmp)


def check_out_dir(path: str | Path | None, name: str = "--out") -> Path | None:
    """Check an output folder before any work: it is a folder, or does not exist yet and can be
    created (its nearest existing ancestor is a writable folder).  Creates nothing."""
    if path is None:
        return None
    p = Path(path)
    if p.exists():
        if not p.is_dir():
            raise ParameterError(name, str(p), "must be a folder (this command writes several "
                                 "files into it); a file of that name exists")
        _writable_dir(name, p)
        return p
    anc = p.absolute().parent
    while not anc.exists():
        anc = anc.parent
    if not anc.is_dir():
        raise ParameterError(name, str(p), f"cannot be created: {anc} is not a folder")
    _writable_dir(name, anc, shown=p)
    return p


def check_out_file(path: str | Path | None, name: str = "--out") -> Path | None:
    """Check an output file before any work: not a folder, and its folder exists and is
    writable (or, if the file exists, it can be replaced)."""
    if path is None:
        return None
    p = Path(path)
    if p.is_dir():
        raise ParameterError(name, str(p), "must be a file path (this command writes one "
                             "file); it is a folder")
    parent = p.absolute().parent
    if not parent.is_dir():
        raise ParameterError(name, str(p), f"its folder {parent} does not exist")
    _writable_dir(name, parent, shown=p)
    return p


def make_out_dir(path: Path) -> Path:
    """Create a folder checked by ``check_out_dir`` (a race that removed the permission still
    gives a named error)."""
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise ParameterError("--out", str(path), f"cannot be created ({e.strerror})") from e
    return path


@contextlib.contextmanager
def atomic_writer(path: str | Path, mode: str = "w") -> Iterator[Any]:
    """A file object whose content replaces ``path`` only when the block ends without error."""
    p = Path(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.absolute().parent)
    except OSError as e:
        raise ParameterError("--out", str(p), f"cannot be written ({e.strerror})") from e
    try:
        with os.fdopen(fd, mode, **({} if "b" in mode else {"encoding": "utf-8"})) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, p)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _umask() -> int:
    m = os.umask(0)
    os.umask(m)
    return m


def atomic_write_text(path: str | Path, text: str) -> None:
    with atomic_writer(path, "w") as f:
        f.write(text)


def atomic_write_bytes(path: str | Path, data: bytes) -> None:
    with atomic_writer(path, "wb") as f:
        f.write(data)


def finite_or_null(obj: Any) -> tuple[Any, bool]:
    """``obj`` with every non-finite float (NaN, +-inf) replaced by None, and whether any was.
    numpy scalars and arrays become plain Python numbers and lists."""
    flag = False

    def conv(x: Any) -> Any:
        nonlocal flag
        if isinstance(x, bool | np.bool_):
            return bool(x)
        if isinstance(x, int | np.integer):
            return int(x)
        if isinstance(x, float | np.floating):
            x = float(x)
            if math.isfinite(x):
                return x
            flag = True
            return None
        if isinstance(x, dict):
            return {str(k): conv(v) for k, v in x.items()}
        if isinstance(x, list | tuple):
            return [conv(v) for v in x]
        if isinstance(x, np.ndarray):
            return [conv(v) for v in x.tolist()]
        if isinstance(x, Path):
            return str(x)
        return x

    return conv(obj), flag


def strict_json(obj: Any, indent: int | None = None) -> str:
    """JSON that strict parsers accept: non-finite floats become null (never NaN/Infinity)."""
    clean, _ = finite_or_null(obj)
    return json.dumps(clean, indent=indent, allow_nan=False)


def lgw_version() -> str:
    from lgw import __version__

    return __version__


def json_document(payload: dict[str, Any], indent: int | None = None) -> str:
    """A command's JSON output: ``lgw_version`` first, then ``payload``; strict, with
    ``"nonfinite_replaced": true`` when a non-finite value was written as null."""
    clean, flag = finite_or_null(payload)
    doc = {"lgw_version": lgw_version(), **clean}
    if flag:
        doc["nonfinite_replaced"] = True
    return json.dumps(doc, indent=indent, allow_nan=False)


def console() -> Any:
    """The rich console for tables: terminal width on a TTY, ``PIPE_WIDTH`` otherwise (a pipe or
    a CI log), so rich never shrinks a table to 80 columns and truncates its headers."""
    from rich.console import Console

    if sys.stdout.isatty():
        return Console()
    return Console(width=PIPE_WIDTH, soft_wrap=True)
