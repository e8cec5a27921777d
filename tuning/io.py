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
* ``console()`` is the rich console of every table: the terminal's width on a TTY, else
  ``COLUMNS`` or 120 columns; tables fold or stack to fit (``lgw.tuning.tables``), so headers
  and cells are never truncated.
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

PIPE_WIDTH = 120  # columns of a console that is not a terminal (COLUMNS overrides): tables
# fold or stack to fit (lgw.tuning.tables), so nothing is ever cut


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
    try:
        width = max(40, int(os.environ.get("COLUMNS", PIPE_WIDTH)))
    except ValueError:
        width = PIPE_WIDTH
    return Console(width=width, soft_wrap=False, force_terminal=False, color_system=None)


# --- output sets: every file of one run lands together, or none does -------------------------

MARKER = ".lgw-output.json"  # written into every output folder: lgw may replace this folder
MAX_SWAP_TRIES = 20


class Stream:
    """Content produced piece by piece (flat memory for a million cases): ``write(f)`` writes
    text into the open file ``f``.  In a JSON document, a ``Stream`` of items (``items``:
    an iterable of JSON values) is written as an array, one item at a time; ``items`` may be
    a function returning a fresh iterator, so that one document can be written twice (to
    stdout and into ``--out``) without holding its items in memory.  Or, given ``encoded``
    (an iterable of texts, str or ASCII bytes, each one or more array items already encoded
    as strict JSON and joined by ","), the texts are written as they are (no per-value walk:
    the producer answers for strict JSON; a function returning a fresh iterable as for
    ``items``; ``write_encoded``)."""

    def __init__(self, items: Any = None, write: Any = None, encoded: Any = None) -> None:
        self.items, self.write, self.encoded = items, write, encoded


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def _inside(child: Path, parent: Path) -> bool:
    try:
        child.resolve().relative_to(parent.resolve())
        return True
    except (ValueError, OSError):
        return False


def check_output_dir(path: Path | None, name: str, inputs: list[Path] = ()) -> Path | None:
    """Check an output folder before any work.  It is new (its nearest existing ancestor is a
    writable folder), or an existing folder that is empty or was written by lgw (it holds
    ``MARKER``): such a folder is replaced as a whole when the run ends.  Refused: a file or
    device of that name, a folder holding other files, the current folder or one of its
    ancestors, and a folder holding one of the run's input files."""
    if path is None:
        return None
    p = Path(path)
    if p.is_symlink() and not p.exists():
        raise ParameterError(name, str(p), "is a dangling symbolic link")
    for inp in inputs:
        if inp is not None and _inside(Path(inp), p):
            raise ParameterError(name, str(p), f"holds the input file {inp}; an output folder "
                                 "is replaced as a whole, so it may not hold an input")
    if p.exists():
        if not p.is_dir():
            raise ParameterError(name, str(p), "must be a folder (this command writes several "
                                 "files); something that is not a folder has that name")
        cwd = Path.cwd()
        if _inside(cwd, p):
            raise ParameterError(name, str(p), "is the current folder or holds it; give a "
                                 "subfolder (e.g. out/): the folder is replaced as a whole")
        entries = [e.name for e in os.scandir(p)] if os.access(p, os.R_OK) else ["?"]
        if entries and MARKER not in entries:
            raise ParameterError(name, str(p), "exists and holds files lgw did not write; "
                                 "give a new or empty folder (lgw replaces its output folder "
                                 "as a whole)")
        _writable_dir(name, p.absolute().parent, shown=p)
        return p
    anc = p.absolute().parent
    while not anc.exists():
        anc = anc.parent
    if not anc.is_dir():
        raise ParameterError(name, str(p), f"cannot be created: {anc} is not a folder")
    _writable_dir(name, anc, shown=p)
    return p


def check_output_file(path: Path | None, name: str, inputs: list[Path] = ()) -> Path | None:
    """Check an output file before any work: not a folder, not a device, FIFO or other
    non-regular file, not one of the run's inputs; its folder exists and is writable."""
    if path is None:
        return None
    p = Path(path)
    if p.is_dir():
        raise ParameterError(name, str(p), "must be a file path (this command writes one "
                             "file); it is a folder")
    if p.exists() or p.is_symlink():
        import stat as _stat

        try:
            mode = os.stat(p).st_mode
        except OSError:
            raise ParameterError(name, str(p), "is a dangling symbolic link") from None
        if not _stat.S_ISREG(mode):
            raise ParameterError(name, str(p), "exists and is not a regular file (a device, "
                                 "FIFO or socket); lgw replaces regular files only")
        for inp in inputs:
            if inp is not None and _same_file(p, Path(inp)):
                raise ParameterError(name, str(p), f"is the input file {inp}; write the "
                                     "output elsewhere")
    parent = p.absolute().parent
    if not parent.is_dir():
        raise ParameterError(name, str(p), f"its folder {parent} does not exist")
    _writable_dir(name, parent, shown=p)
    return p


def _write_content(path: Path, content: Any) -> None:
    if isinstance(content, Stream):
        with open(path, "w", encoding="utf-8") as f:
            content.write(f)
            f.flush()
            os.fsync(f.fileno())
        return
    data = content.encode("utf-8") if isinstance(content, str) else bytes(content)
    with open(path, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())


def write_output_set(folder: Path, files: dict[str, Any], command: str,
                     name: str = "--out") -> list[Path]:
    """Write ``files`` (name -> text, bytes or ``Stream``) as one set into ``folder``: into a
    temporary folder beside it first, then renamed into place (an existing lgw folder is
    swapped out and removed).  A reader, a crash, a full disk or a second run at the same time
    sees the old set or the new one, never a mix; a failure leaves the old folder untouched."""
    import shutil

    folder = Path(folder)
    parent = folder.absolute().parent
    parent.mkdir(parents=True, exist_ok=True)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{folder.name}.lgw-tmp-", dir=parent))
    except OSError as e:
        raise ParameterError(name, str(folder), f"cannot be written ({e.strerror})") from e
    try:
        for fname, content in files.items():
            if "/" in fname or fname.startswith("."):
                raise ValueError(f"output file name {fname!r}")
            _write_content(tmp / fname, content)
        _write_content(tmp / MARKER, json.dumps({"lgw_version": lgw_version(),
                                                 "command": command,
                                                 "files": sorted(files)}, indent=1) + "\n")
        os.chmod(tmp, 0o777 & ~_umask())
        for _ in range(MAX_SWAP_TRIES):
            try:
                os.rename(tmp, folder)  # atomic when folder does not exist (or is empty)
                break
            except OSError:
                if not folder.exists():
                    continue
            old = Path(tempfile.mkdtemp(prefix=f".{folder.name}.lgw-old-", dir=parent))
            try:
                os.rename(folder, old / "set")
            except FileNotFoundError:  # another run swapped it out first: try again
                shutil.rmtree(old, ignore_errors=True)
                continue
            try:
                os.rename(tmp, folder)
            except OSError:  # another run put its set in meanwhile: it wins, ours goes too
                shutil.rmtree(old, ignore_errors=True)
                continue
            shutil.rmtree(old, ignore_errors=True)
            break
        else:
            raise ParameterError(name, str(folder), "could not be replaced (other runs keep "
                                 "writing it)")
    except OSError as e:
        shutil.rmtree(tmp, ignore_errors=True)
        raise ParameterError(name, str(folder), f"cannot be written ({e.strerror}); nothing "
                             "was changed") from e
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return [folder / f for f in files]


def _stream_json(value: Any, out: Any, flag: list[bool]) -> None:
    if isinstance(value, Stream) and value.encoded is not None:
        out.write("[")
        write_encoded(value.encoded() if callable(value.encoded) else value.encoded, out)
        out.write("]")
    elif isinstance(value, Stream):
        out.write("[")
        items = value.items() if callable(value.items) else value.items
        for i, item in enumerate(items):
            clean, bad = finite_or_null(item)
            flag[0] = flag[0] or bad
            out.write(("," if i else "") + json.dumps(clean, allow_nan=False))
        out.write("]")
    elif isinstance(value, dict):
        out.write("{")
        for i, (k, v) in enumerate(value.items()):
            out.write(("," if i else "") + json.dumps(str(k)) + ":")
            _stream_json(v, out, flag)
        out.write("}")
    else:
        clean, bad = finite_or_null(value)
        flag[0] = flag[0] or bad
        out.write(json.dumps(clean, allow_nan=False))


ENCODED_AHEAD = 2  # encoded texts waiting for the writer thread (a few MB each)


def write_encoded(texts: Any, out: Any) -> None:
    """The encoded array items ``texts`` (str or ASCII bytes, each one or more items joined
    by ",") into the text file ``out``, joined by ",".  Into a file with a binary ``buffer``
    (a real file, stdout), bytes go straight to the buffer from a writer thread: the next
    text is made while the last one is written (a write call releases the GIL), and nothing
    is decoded and re-encoded.  Otherwise (e.g. a StringIO) the texts are written as str."""
    raw = getattr(out, "buffer", None)
    if raw is None:
        first = True
        for text in texts:
            if text:
                text = text.decode("ascii") if isinstance(text, bytes) else text
                out.write(text if first else "," + text)
                first = False
        return
    import queue
    import threading

    out.flush()  # what the text layer holds goes first
    todo: queue.Queue = queue.Queue(maxsize=ENCODED_AHEAD)
    failed: list[BaseException] = []

    def writer() -> None:
        while (data := todo.get()) is not None:
            if not failed:  # after an error, drain the queue so the producer never blocks
                try:
                    raw.write(data)
                except BaseException as e:  # noqa: BLE001  (re-raised in the caller)
                    failed.append(e)

    thread = threading.Thread(target=writer, name="lgw-json-writer", daemon=True)
    thread.start()
    try:
        first = True
        for text in texts:
            if failed:
                break
            if text:
                if not first:
                    todo.put(b",")
                todo.put(text.encode("ascii") if isinstance(text, str) else text)
                first = False
    finally:
        todo.put(None)
        thread.join()
    if failed:
        raise failed[0]


def has_stream(value: Any) -> bool:
    if isinstance(value, Stream):
        return True
    if isinstance(value, dict):
        return any(has_stream(v) for v in value.values())
    return False


def write_json_document(payload: dict[str, Any], out: Any, indent: int | None = 2) -> None:
    """A command's JSON document into the text file ``out``: ``lgw_version`` first, strict
    JSON, ``"nonfinite_replaced": true`` last when a non-finite value became null.  A payload
    holding a ``Stream`` is written compactly, item by item (flat memory)."""
    if not has_stream(payload):
        out.write(json_document(payload, indent=indent))
        out.write("\n")
        return
    flag = [False]
    out.write("{" + json.dumps("lgw_version") + ":" + json.dumps(lgw_version()))
    for k, v in payload.items():
        out.write("," + json.dumps(str(k)) + ":")
        _stream_json(v, out, flag)
    if flag[0]:
        out.write(',"nonfinite_replaced":true')
    out.write("}\n")


def json_stream(payload: dict[str, Any], indent: int | None = 2) -> Stream:
    """The JSON document as file content for an output set."""
    return Stream(write=lambda f: write_json_document(payload, f, indent))


# --- memory: estimated before a campaign allocates -------------------------------------------

MEMORY_FRACTION = 0.5  # a run may use at most this share of the available memory


def available_memory() -> int | None:
    """Available memory in bytes (Linux /proc/meminfo ``MemAvailable``), or None when
    unknown."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def check_memory(flag: str, n: int, bytes_per_case: float, what: str = "the per-case "
                 "results", value: Any = None) -> None:
    """Refuse, before anything is allocated, a run of ``n`` cases whose arrays (an estimate:
    ``bytes_per_case`` each) would not fit in ``MEMORY_FRACTION`` of the available memory: a
    ParameterError naming ``flag`` (with ``value``, default ``n``) and the largest number of
    cases that fits, never a MemoryError."""
    need = float(n) * float(bytes_per_case)
    avail = available_memory()
    if avail is None or need <= MEMORY_FRACTION * avail:
        return
    fits = int(MEMORY_FRACTION * avail / max(bytes_per_case, 1.0))
    hint = (f"at most about {fits} cases here (split the run, or shorten it)" if fits >= 1
            else "not even one case fits (shorten the run or take a longer step)")
    raise ParameterError(flag, n if value is None else value, f"needs about "
                         f"{need / 2**30:.3g} GiB for {what}; this machine has "
                         f"{avail / 2**30:.3g} GiB available: {hint}")
