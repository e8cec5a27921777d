"""Compiled kernels cached on disk: generated modules in a cache directory, numba-cached.

numba's ``cache=True`` needs a function defined in a real source file whose global names are
importable; lambdify-generated code and closures have neither.  So each kernel (a system's
generated law, its hooks and the integrator, see ``lgw.sim.integrate``) is written as a module
``<cache>/<prefix>_<key>.py``; its functions carry ``cache=True``, so numba stores their
machine code next to it (``<cache>/__pycache__``, or under ``NUMBA_CACHE_DIR`` if set).  A
second process finds the module and loads the machine code instead of compiling.

Keys.  A module's file name carries a hash of its full text, the lgw version and the sources of
the modules the text imports compiled helpers from (``module_for``; numba validates only the
generated file's own stamp, not its imports): two different texts never share a file.  Making
the text can cost seconds (SymPy builds, simplifies and prints the laws), so
``generated_module`` first looks the module up by its inputs (the lgw, SymPy and Python
versions, every source file of ``lgw.theory`` and ``lgw.sim``, and what the caller adds, such
as a law's expression) and makes the text only when that lookup misses.  A process whose own
package sources changed after it started (an edit while it runs) never records such a lookup,
so a text made from stale code is never found by its inputs.

Trust (docs/sim.md).  The cache holds code that is executed: numba's index and data files are
pickles, and the generated modules are Python.  Hence:

* the cache directory, and numba's directory for it, must be owned by the user and writable by
  nobody else (no parent writable by others unless sticky, like /tmp; parents owned by the user
  or root).  A directory that is not is refused with a warning: nothing in it is read, and the
  kernels of this process are compiled into a private temporary directory instead;
* a generated module is never imported from disk: the text lgw generates (or finds by its
  inputs and checks against its hash) is compiled and executed, and the file is only (re)written
  for numba's source stamp and for people to read;
* numba's index and data files are loaded only if their SHA-256 is the one lgw recorded in the
  module's manifest (``<stem>.sums.json``, JSON) when numba saved them, and the file is the
  user's and not writable by others.  Anything else (corrupt, truncated, foreign, another
  numba's) is dropped and the function is compiled again; an error while numba loads an entry
  drops it too.  A lock file per module serialises these checks and numba's saves between
  processes.

Cache directory: ``$LGW_CACHE_DIR/kernels`` if set, else ``~/.cache/lgw/kernels``
(``$XDG_CACHE_HOME/lgw/kernels`` when that is set), created private (0700).  If it cannot be
created or written, or is refused, a warning says so and a private temporary directory is used
for this process (everything still works, nothing persists).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import stat
import sys
import tempfile
import threading
import time
import warnings
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from types import ModuleType

ENV_VAR = "LGW_CACHE_DIR"
NOTICE_VAR = "LGW_COMPILE_NOTICE"
_FALLBACK: Path | None = None
_WARNED: set[str] = set()
_IMPORT_TIME = time.time()


# --- trust -------------------------------------------------------------------------------

def _uid() -> int | None:
    return os.getuid() if hasattr(os, "getuid") else None


def trust_problem(path: Path) -> str | None:
    """Why lgw must not read compiled code from directory ``path``, or None if it may: the
    directory must be the user's and writable by nobody else; each parent must be the user's
    or root's and not writable by others unless sticky (/tmp).  Not checked where the
    platform has no owners (Windows)."""
    uid = _uid()
    if uid is None:
        return None
    p = Path(path).resolve()
    try:
        st = os.stat(p)
    except OSError as e:
        return f"cannot be read ({e.strerror})"
    if not stat.S_ISDIR(st.st_mode):
        return "is not a directory"
    if st.st_uid != uid:
        return f"is owned by another user (uid {st.st_uid})"
    if st.st_mode & 0o022:
        return f"is writable by {'others' if st.st_mode & 0o002 else 'group'} (mode " \
               f"{stat.S_IMODE(st.st_mode):o})"
    for parent in p.parents:
        try:
            ps = os.stat(parent)
        except OSError as e:
            return f"has a parent {parent} that cannot be read ({e.strerror})"
        if ps.st_uid not in (uid, 0):
            return f"is inside {parent}, owned by another user (uid {ps.st_uid})"
        if ps.st_mode & stat.S_IWOTH and not ps.st_mode & stat.S_ISVTX:
            return f"is inside {parent}, writable by anyone"
    return None


def _file_ok(path: Path) -> bool:
    """A regular file of the user's, writable by nobody else (not following a symlink)."""
    try:
        st = os.lstat(path)
    except OSError:
        return False
    uid = _uid()
    return (stat.S_ISREG(st.st_mode) and not st.st_mode & 0o022
            and (uid is None or st.st_uid == uid))


def _warn_once(msg: str) -> None:
    if msg not in _WARNED:
        _WARNED.add(msg)
        warnings.warn(msg, RuntimeWarning, stacklevel=3)


def _make_private(d: Path) -> None:
    """Create ``d`` (and missing parents) with mode 0700."""
    missing = []
    p = d
    while not p.exists():
        missing.append(p)
        p = p.parent
    for q in reversed(missing):
        with contextlib.suppress(FileExistsError):
            q.mkdir(mode=0o700)


def _configured() -> Path:
    env = os.environ.get(ENV_VAR)
    if env:
        return Path(env).expanduser() / "kernels"
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "lgw" / "kernels"


def cache_dir() -> Path:
    """The kernel cache directory (created if needed; a private temporary one for this
    process if it cannot be written or is not trusted, with a warning)."""
    global _FALLBACK
    d = _configured()
    try:
        _make_private(d)
        problem = trust_problem(d)
        if problem is None:
            # one name per thread: two threads' first kernels probed the same file, and the
            # one that found it gone fell back to a temporary cache with a warning
            probe = d / f".probe-{os.getpid()}-{threading.get_ident()}"
            probe.write_text("")
            probe.unlink()
            return d
        why = f"{problem}: refused (compiled code in it could have been written by someone " \
              f"else; make it yours with `chmod go-w` / `chown`, or set {ENV_VAR} to a " \
              "directory of your own)"
    except OSError as e:
        why = f"is not writable ({e.strerror}; set {ENV_VAR} to a writable directory)"
    if _FALLBACK is None:
        _FALLBACK = Path(tempfile.mkdtemp(prefix="lgw-kernels-"))
    _warn_once(f"lgw: kernel cache {d} {why}; compiled kernels are kept in {_FALLBACK} for "
               "this process only")
    return _FALLBACK


# --- keys ----------------------------------------------------------------------------------

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


def text_key(prefix: str, text: str, deps: Iterable[str] = ()) -> str:
    """The file stem of a generated module: ``<prefix>_<hash>``, the hash of the lgw version,
    the module text and ``deps`` (the sources of what it imports)."""
    import lgw
    return f"{prefix}_{key([lgw.__version__, text, *deps])}"


def _process_start() -> float:
    """When this process started (s since the epoch; Linux), else when this module loaded."""
    try:
        with open("/proc/self/stat") as f:
            ticks = int(f.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/stat") as f:
            btime = next(int(line.split()[1]) for line in f if line.startswith("btime"))
        return btime + ticks / os.sysconf("SC_CLK_TCK") - 1.0
    except (OSError, ValueError, IndexError, StopIteration, AttributeError):
        return _IMPORT_TIME


_PACKAGE: tuple[str, float] | None = None


def package_fingerprint() -> tuple[str, float]:
    """(hash of every file of ``lgw.theory`` and ``lgw.sim`` with the lgw, SymPy and Python
    versions, the newest file's mtime), read once per process."""
    global _PACKAGE
    if _PACKAGE is None:
        from importlib.metadata import PackageNotFoundError, version

        import lgw.sim
        import lgw.theory
        h = hashlib.sha256()
        try:
            sympy_version = version("sympy")
        except PackageNotFoundError:
            sympy_version = "?"
        h.update(f"{lgw.__version__}\0{sympy_version}\0{sys.version}\0".encode())
        newest = 0.0
        for pkg in (lgw.theory, lgw.sim):
            root = Path(pkg.__file__).resolve().parent
            for f in sorted(root.rglob("*")):
                if "__pycache__" in f.parts or not f.is_file() or f.suffix == ".pyc":
                    continue
                h.update(str(f.relative_to(root)).encode() + b"\0" + f.read_bytes() + b"\0")
                newest = max(newest, f.stat().st_mtime)
        _PACKAGE = (h.hexdigest()[:16], newest)
    return _PACKAGE


# --- generated modules ----------------------------------------------------------------------

_LOADED: dict[str, ModuleType] = {}
_LOCK = threading.RLock()


def _write_atomic(path: Path, text: str) -> None:
    """``text`` into ``path`` (mode 0600) via a temporary file in the same directory and
    ``os.replace`` (a concurrent reader sees the old file or the new one, never a part)."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _read(path: Path) -> str | None:
    """The file's text if it is the user's, not writable by others and UTF-8; else None."""
    if not _file_ok(path):
        return None
    try:
        return path.read_bytes().decode("utf-8")
    except (OSError, UnicodeDecodeError):
        return None


def _load(stem: str, path: Path, text: str) -> ModuleType:
    """Execute ``text`` (exactly what lgw generated) as module ``lgw_kernel_<stem>`` whose file
    is ``path`` (written with that text), and guard its numba caches (``_guard``)."""
    name = f"lgw_kernel_{stem}"  # top-level: numba rebuilds cached code by the module's name
    mod = ModuleType(name)
    mod.__file__ = str(path)
    sys.modules[name] = mod
    try:
        (path.parent / "__pycache__").mkdir(mode=0o700, exist_ok=True)
        exec(compile(text, str(path), "exec"), mod.__dict__)  # noqa: S102 (generated by lgw)
    except BaseException:
        sys.modules.pop(name, None)
        raise
    for obj in list(vars(mod).values()):
        if getattr(getattr(obj, "py_func", None), "__module__", None) == name:
            _guard(obj, stem, path.parent)
    _LOADED[stem] = mod
    return mod


def _module(stem: str, text: str) -> ModuleType:
    with _LOCK:
        if stem in _LOADED:
            return _LOADED[stem]
        path = cache_dir() / f"{stem}.py"
        if _read(path) != text:
            with _locked(path.parent, stem):
                _write_atomic(path, text)
        return _load(stem, path, text)


def module_for(prefix: str, text: str, deps: Iterable[str] = ()) -> ModuleType:
    """The generated module ``text``, as ``<cache>/<text_key(...)>.py`` (the file is written
    if it is missing or its text is not exactly ``text``: corrupted, truncated, foreign)."""
    return _module(text_key(prefix, text, deps), text)


def load_module(stem: str, source: Callable[[], str]) -> ModuleType:
    """The generated module ``source()`` as ``<cache>/<stem>.py``, for callers whose stem is
    already a hash of the text (tests, tools); a file whose text differs is rewritten."""
    with _LOCK:
        if stem in _LOADED:
            return _LOADED[stem]
    return _module(stem, source())


_STEM = re.compile(r"[A-Za-z0-9_]+_[0-9a-f]{16}")


def generated_module(prefix: str, make_text: Callable[[], str], deps: Iterable[str] = (),
                     inputs: Iterable[str] = ()) -> ModuleType:
    """``module_for(prefix, make_text(), deps)``, without making the text when a process of
    the same package sources (``package_fingerprint``) and ``inputs`` made it before: the
    pointer ``<prefix>.<inputs key>.stem`` names that module, whose file is used only if its
    text still hashes to its name."""
    deps = list(deps)
    fp, newest = package_fingerprint()
    ikey = key([fp, prefix, *inputs])
    d = cache_dir()
    pointer = d / f"{prefix}.{ikey}.stem"
    stem = (_read(pointer) or "").strip()
    if _STEM.fullmatch(stem) and stem.startswith(prefix + "_"):
        with _LOCK:
            if stem in _LOADED:
                return _LOADED[stem]
        text = _read(d / f"{stem}.py")
        if text is not None and text_key(prefix, text, deps) == stem:
            with contextlib.suppress(ImportError):  # e.g. a module it imports is gone
                return _module(stem, text)
    mod = module_for(prefix, make_text(), deps)
    if newest < _process_start():  # the sources this process runs are the ones hashed
        _write_atomic(pointer, mod.__name__.removeprefix("lgw_kernel_"))
    return mod


# --- numba's files: trusted, hashed, dropped when wrong ---------------------------------------

@contextlib.contextmanager
def _locked(d: Path, stem: str) -> Iterator[None]:
    """An exclusive lock on ``<d>/<stem>.lock`` between processes (POSIX), and in process."""
    with _LOCK:
        try:
            import fcntl
        except ImportError:  # pragma: no cover - Windows
            yield
            return
        fd = os.open(d / f"{stem}.lock", os.O_RDWR | os.O_CREAT, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            yield
        finally:
            os.close(fd)


def _sha256(path: Path) -> str | None:
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except OSError:
        return None


class _Entry:
    """One dispatcher's numba files (index and data) and the module's manifest of them."""

    def __init__(self, stem: str, home: Path, cache) -> None:
        self.stem = stem
        self.home = home  # the generated module's directory: the manifest and the lock
        self.dir = Path(cache._cache_path)
        cf = cache._cache_file
        self.index = cf._index_name
        self.data = re.compile(re.escape(cf._data_name_pattern.split("{")[0]) + r"\d+\.nbc")
        fn = getattr(cache, "_py_func", None)
        self.what = f"{fn.__module__}.{fn.__qualname__}" if fn is not None else cache._name
        self.verified = False

    @property
    def manifest(self) -> Path:
        return self.home / f"{self.stem}.sums.json"

    def files(self) -> list[Path]:
        try:
            names = os.listdir(self.dir)
        except OSError:
            return []
        return [self.dir / n for n in names if n == self.index or self.data.fullmatch(n)]

    def sums(self) -> dict[str, str]:
        text = _read(self.manifest)
        try:
            sums = json.loads(text) if text else {}
        except ValueError:
            return {}
        return sums if isinstance(sums, dict) else {}

    def verify(self) -> None:
        """Drop this function's numba files unless each is the user's, not writable by
        others, and has the SHA-256 the manifest recorded."""
        self.verified = True
        files = self.files()
        if not files:
            return
        sums = self.sums()
        bad = [f.name for f in files if not _file_ok(f) or sums.get(f.name) != _sha256(f)]
        if bad:
            self.drop(f"not as lgw saved: {', '.join(sorted(bad))}")

    def drop(self, why: str) -> None:
        for f in self.files():
            with contextlib.suppress(OSError):
                f.unlink()
        self.seal()
        _warn_once(f"lgw: dropped the cached machine code of {self.what} in {self.dir} ({why}); "
                   "it is compiled again")

    def seal(self) -> None:
        """Record the SHA-256 of this function's files in the manifest (and make them 0600)."""
        sums = self.sums()
        for name in [n for n in sums if n == self.index or self.data.fullmatch(n)]:
            del sums[name]
        for f in self.files():
            with contextlib.suppress(OSError):
                os.chmod(f, 0o600)
            digest = _sha256(f)
            if digest is not None:
                sums[f.name] = digest
        _write_atomic(self.manifest, json.dumps(sums, indent=0, sort_keys=True))


def _guard(dispatcher, stem: str, home: Path) -> None:
    """Make ``dispatcher``'s numba cache trusted and self-healing (module docstring): its
    directory checked once, its files checked against the manifest before numba first loads
    them, a failed load dropped, and every save recorded.  Where numba's cache internals are
    not the ones this was written for, or its directory is refused, the function is simply
    not cached (compiled in each process)."""
    from numba.core.caching import NullCache

    cache = getattr(dispatcher, "_cache", None)
    if cache is None or isinstance(cache, NullCache):
        return
    try:
        entry = _Entry(stem, home, cache)
        load0, save0 = cache.load_overload, cache.save_overload
    except AttributeError:
        dispatcher._cache = NullCache()
        return
    problem = trust_problem(entry.dir)
    if problem is not None:
        _warn_once(f"lgw: numba's cache directory {entry.dir} {problem}: refused, kernels are "
                   "not cached (compiled in each process; make it yours, or unset "
                   "NUMBA_CACHE_DIR)")
        dispatcher._cache = NullCache()
        return

    def load_overload(sig, target_context):
        with _locked(home, stem):
            if not entry.verified:
                entry.verify()
            try:
                return load0(sig, target_context)
            except Exception as e:  # a corrupt entry: never a broken run
                entry.drop(f"it could not be loaded: {type(e).__name__}")
                return None

    def save_overload(sig, data):
        with _locked(home, stem):
            save0(sig, data)
            entry.seal()

    cache.load_overload = load_overload
    cache.save_overload = save_overload


def numba_files(module: ModuleType) -> list[Path]:
    """The numba index and data files of a generated module's functions (for tests, tools)."""
    out = []
    for obj in vars(module).values():
        cache = getattr(obj, "_cache", None)
        if getattr(getattr(obj, "py_func", None), "__module__", None) == module.__name__ \
                and hasattr(cache, "_cache_file"):
            out += _Entry("", Path(), cache).files()
    return sorted(set(out))


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

    def __init__(self, dispatcher, what: str, expected: str = "~10-30 s") -> None:
        flag = os.environ.get(NOTICE_VAR)
        wanted = flag == "1" if flag in ("0", "1") else _isatty(sys.stderr)
        self.show = wanted and not is_cached(dispatcher)
        self.what = what
        self.expected = expected
        self.t0 = 0.0

    def __enter__(self) -> CompileNotice:
        if self.show:
            print(f"compiling {self.what} (first run in this environment, {self.expected}; "
                  "`lgw warmup` builds every kernel ahead)...", file=sys.stderr, flush=True)
        self.t0 = time.perf_counter()
        return self

    def __exit__(self, *exc) -> None:
        if self.show and exc[0] is None:
            print(f"compiled {self.what} in {time.perf_counter() - self.t0:.0f} s (cached in "
                  f"{cache_dir()})", file=sys.stderr, flush=True)
