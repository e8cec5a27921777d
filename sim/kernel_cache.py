"""Compiled kernels cached on disk: generated modules in a cache directory, numba-cached.

numba's ``cache=True`` needs a function defined in a real source file whose global names are
importable; lambdify-generated code and closures have neither.  So each kernel (a system's
generated law, its hooks and the integrator, see ``lgw.sim.integrate``) is written as a module
``<cache>/<system>_<law>_<key>.py`` and imported from there; its functions carry
``cache=True``, so numba stores the machine code next to it (``__pycache__``, or under
``NUMBA_CACHE_DIR`` if set).  A second process in the same environment imports the module and
loads the machine code instead of compiling (seconds instead of ~30 s).

The file name carries a hash of the full generated module text itself, the lgw version and
the source of the modules the text imports compiled helpers from (``module_for``; numba
validates only the generated file's own stamp, not its imports).  Two different texts never
share a file: a process that generates a wrong text (e.g. one running while a hook's source
file is edited, where ``inspect.getsource`` reads the new file with the old line numbers) writes
it under a name no correct process computes.  The helpers' sources are read once per process,
when the kernel module asks for them at its own import (``imported_sources``), so an edit made
while a process runs does not re-key that process's stale code as current.  An existing file
is imported only if its text is exactly the expected one; a corrupted, truncated or foreign
file is rewritten (atomically: a temporary file in the same directory, then ``os.replace``),
and numba, whose stamp is the file's mtime and size, recompiles it.

Cache directory: ``$LGW_CACHE_DIR`` if set, else ``~/.cache/lgw`` (``$XDG_CACHE_HOME/lgw`` when
that is set).  If it cannot be created or written, a warning says so and a temporary directory
is used for this process (everything still works, nothing persists).
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import tempfile
import time
import warnings
from collections.abc import Callable, Iterable
from pathlib import Path
from types import ModuleType

ENV_VAR = "LGW_CACHE_DIR"
NOTICE_VAR = "LGW_COMPILE_NOTICE"
_FALLBACK: Path | None = None


def cache_dir() -> Path:
    """The kernel cache directory (created if needed; a temporary one if not writable)."""
    global _FALLBACK
    env = os.environ.get(ENV_VAR)
    if env:
        d = Path(env).expanduser()
    else:
        base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
        d = Path(base) / "lgw"
    d = d / "kernels"
    try:
        d.mkdir(parents=True, exist_ok=True)
        probe = d / f".probe-{os.getpid()}"
        probe.write_text("")
        probe.unlink()
        return d
    except OSError as e:
        if _FALLBACK is None:
            _FALLBACK = Path(tempfile.mkdtemp(prefix="lgw-kernels-"))
            warnings.warn(f"lgw: kernel cache {d} is not writable ({e.strerror}); compiled "
                          f"kernels are kept in {_FALLBACK} for this process only (set "
                          f"{ENV_VAR} to a writable directory)", RuntimeWarning, stacklevel=2)
        return _FALLBACK


def key(parts: Iterable[str]) -> str:
    """A short stable hash of the given texts."""
    h = hashlib.sha256()
    for p in parts:
        h.update(p.encode())
        h.update(b"\0")
    return h.hexdigest()[:16]


def source_of(*modules: ModuleType) -> list[str]:
    """The source text of modules, as on disk now."""
    return [Path(m.__file__).read_text() for m in modules]


_IMPORTED: dict[str, str] = {}


def imported_sources(*modules: ModuleType) -> list[str]:
    """The source text of modules as first read in this process (then kept: an edit made
    while the process runs does not change what it keys its kernels by)."""
    out = []
    for m in modules:
        f = str(Path(m.__file__).resolve())
        if f not in _IMPORTED:
            _IMPORTED[f] = Path(f).read_text()
        out.append(_IMPORTED[f])
    return out


_LOADED: dict[str, ModuleType] = {}


def _write_atomic(path: Path, text: str) -> None:
    """``text`` into ``path`` via a temporary file in the same directory and ``os.replace``
    (a concurrent reader sees the old file or the new one, never a part)."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _read(path: Path) -> str | None:
    """The file's text, or None if it is missing or not UTF-8 (a corrupted entry)."""
    try:
        return path.read_bytes().decode("utf-8")
    except (OSError, UnicodeDecodeError):
        return None


def _import(stem: str, path: Path) -> ModuleType:
    name = f"lgw_kernel_{stem}"  # top-level: numba re-imports it by name from its cache
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    _LOADED[stem] = mod
    return mod


def text_key(prefix: str, text: str, deps: Iterable[str] = ()) -> str:
    """The file stem of a generated module: ``<prefix>_<hash>``, the hash of the lgw version,
    the module text and ``deps`` (the sources of what it imports)."""
    import lgw
    return f"{prefix}_{key([lgw.__version__, text, *deps])}"


def module_for(prefix: str, text: str, deps: Iterable[str] = ()) -> ModuleType:
    """Import the generated module ``text`` from ``<cache>/<text_key(...)>.py``, writing it
    first if the file is missing or its text is not exactly ``text`` (corrupted, truncated)."""
    stem = text_key(prefix, text, deps)
    if stem in _LOADED:
        return _LOADED[stem]
    path = cache_dir() / f"{stem}.py"
    if _read(path) != text:
        _write_atomic(path, text)
    return _import(stem, path)


def load_module(stem: str, source: Callable[[], str]) -> ModuleType:
    """Write ``source()`` as ``<cache>/<stem>.py`` (if not there yet) and import it.

    For callers whose stem is already a hash of the text (tests, tools): an existing file is
    taken as is, without calling ``source``.  Kernels use ``module_for``, which checks it."""
    if stem in _LOADED:
        return _LOADED[stem]
    path = cache_dir() / f"{stem}.py"
    if not path.exists():
        _write_atomic(path, source())
    return _import(stem, path)


def is_cached(dispatcher) -> bool:
    """True if numba has an index of machine code for this function (numba's own cache
    files: ``Dispatcher._cache._cache_file._index_path``, numba internals); False if not or
    unknown (then the notice is printed: a spurious notice is harmless)."""
    try:
        return Path(dispatcher._cache._cache_file._index_path).exists()
    except AttributeError:
        return False


def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


class CompileNotice:
    """Says on stderr that a kernel is being compiled, and how long it took.

    ``with CompileNotice(fn, "the mars/corrected kernel"): fn(...)`` prints the notice before
    the first call when numba has no cached code for fn yet, if stderr is a terminal or
    ``$LGW_COMPILE_NOTICE`` is 1 (a notice inside captured output, e.g. click's CliRunner,
    which merges stderr into the output the tests parse as JSON, would corrupt it; 0 silences
    it on a terminal too)."""

    def __init__(self, dispatcher, what: str, expected: str = "~30 s") -> None:
        flag = os.environ.get(NOTICE_VAR)
        wanted = flag == "1" if flag in ("0", "1") else _isatty(sys.stderr)
        self.show = wanted and not is_cached(dispatcher)
        self.what = what
        self.expected = expected
        self.t0 = 0.0

    def __enter__(self) -> CompileNotice:
        if self.show:
            print(f"compiling {self.what} (first run in this environment, {self.expected})...",
                  file=sys.stderr, flush=True)
        self.t0 = time.perf_counter()
        return self

    def __exit__(self, *exc) -> None:
        if self.show and exc[0] is None:
            print(f"compiled {self.what} in {time.perf_counter() - self.t0:.0f} s (cached in "
                  f"{cache_dir()})", file=sys.stderr, flush=True)
