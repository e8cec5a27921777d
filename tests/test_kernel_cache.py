"""The kernel cache (lgw.sim.kernel_cache): keyed by the generated text, found by its inputs,
trusted only where the user alone can write, and self-healing.

A process running while a hook's source file is edited can generate a wrong module (its
``inspect.getsource`` reads the new file with the old line numbers); keyed by the text itself,
that module lands in a file no correct process reads.  A corrupted or truncated cache file is
detected (its text is not the expected one) and rewritten before it is used.  numba's index and
data files (pickles) are loaded only from a trusted directory and only as lgw saved them: a
corrupt, foreign or crafted entry is dropped and compiled again, never a broken run, never
executed.
"""

from __future__ import annotations

import os
import pickle
import sys
import time
import types
import warnings
from pathlib import Path

import numba
import pytest
from lgw.sim import kernel_cache


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path))
    monkeypatch.setattr(kernel_cache, "_LOADED", {})
    monkeypatch.setattr(kernel_cache, "_FALLBACK", None)
    monkeypatch.setattr(kernel_cache, "_WARNED", set())
    return tmp_path / "kernels"


def _text(value: int) -> str:
    return f"# generated for a test\nVALUE = {value}\n"


def test_two_texts_never_share_a_file(cache) -> None:
    a = kernel_cache.module_for("test_text", _text(1))
    b = kernel_cache.module_for("test_text", _text(2))
    assert a.__file__ != b.__file__ and (a.VALUE, b.VALUE) == (1, 2)
    assert len(list(cache.glob("test_text_*.py"))) == 2
    # the same text again: the same file, the module already loaded
    assert kernel_cache.module_for("test_text", _text(1)) is a
    # and the deps (sources of the imported helpers) are part of the key too
    assert (kernel_cache.text_key("p", _text(1), ["x = 1"])
            != kernel_cache.text_key("p", _text(1), ["x = 2"]))


@pytest.mark.parametrize("damage", ["truncated", "foreign", "binary", "empty"])
def test_a_damaged_file_is_detected_and_rebuilt(cache, monkeypatch, damage) -> None:
    text = _text(7)
    path = cache / f"{kernel_cache.text_key('test_damage', text)}.py"
    cache.mkdir(parents=True, exist_ok=True)
    if damage == "truncated":
        path.write_text(text[: len(text) // 2])
    elif damage == "foreign":
        path.write_text(_text(8))  # a wrong module under this text's name
    elif damage == "binary":
        path.write_bytes(b"\xff\xfe\x00garbage")
    else:
        path.write_text("")
    mod = kernel_cache.module_for("test_damage", text)
    assert mod.VALUE == 7 and path.read_text() == text
    assert not list(cache.glob("*.tmp"))  # the atomic write left no temporary behind


def test_imported_sources_are_read_once(tmp_path, monkeypatch) -> None:
    """An edit made while the process runs does not change what it keys its kernels by."""
    monkeypatch.setattr(kernel_cache, "_IMPORTED", {})
    f = tmp_path / "helper.py"
    f.write_text("X = 1\n")
    mod = types.SimpleNamespace(__file__=str(f))
    assert kernel_cache.imported_sources(mod) == ["X = 1\n"]
    f.write_text("X = 2\n")
    assert kernel_cache.imported_sources(mod) == ["X = 1\n"]
    assert kernel_cache.source_of(mod) == ["X = 2\n"]


def test_the_mars_kernel_file_is_its_generated_text() -> None:
    """The cached kernel module's file holds exactly the text its name is the hash of."""
    from pathlib import Path

    from lgw.sim.mars import kernel
    from lgw.sim.mars.laws import get_law
    spec = get_law("corrected")
    mod = kernel.kernel_module("corrected")
    text = kernel.kernel_text(spec)
    assert Path(mod.__file__).read_text() == text
    assert Path(mod.__file__).stem == kernel_cache.text_key(kernel._prefix("kernel", spec.name),
                                                            text, kernel._deps())


# --- numba's files: corrupt, foreign, crafted; untrusted directories ---------------------------

JIT = """# generated for a test
import numba


def f(x):
    return 2.0 * x + {k}


f = numba.njit(f, cache=True)
"""


def _fresh(prefix: str, k: float = 1.0) -> types.ModuleType:
    """The module as a new process would get it: a new dispatcher, numba's files on disk."""
    kernel_cache._LOADED.clear()
    for name in [n for n in sys.modules if n.startswith(f"lgw_kernel_{prefix}_")]:
        del sys.modules[name]
    return kernel_cache.module_for(prefix, JIT.format(k=k))


def _hits(mod) -> tuple[int, int]:
    st = mod.f.stats
    return sum(st.cache_hits.values()), sum(st.cache_misses.values())


def _compiled_and_saved(prefix: str) -> types.ModuleType:
    mod = _fresh(prefix)
    assert mod.f(1.0) == 3.0 and _hits(mod) == (0, 1)  # compiled, saved
    files = kernel_cache.numba_files(mod)
    assert {p.suffix for p in files} == {".nbi", ".nbc"}
    sums = Path(mod.__file__).with_suffix(".sums.json")
    assert sums.exists() and all(p.name in sums.read_text() for p in files)
    again = _fresh(prefix)
    assert again.f(1.0) == 3.0 and _hits(again) == (1, 0)  # a new process loads it
    return again


class Crafted:
    """A pickle that runs os.mkdir(path) when loaded: what a planted cache entry can do."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __reduce__(self):
        return (os.mkdir, (str(self.path),))


def _plant(path: Path, marker: Path) -> None:
    """A numba index file (the version header numba checks, then the payload it unpickles)
    whose payload is ``Crafted``."""
    path.write_bytes(pickle.dumps(numba.__version__) + pickle.dumps(Crafted(marker)))


@pytest.mark.parametrize("damage", ["index", "data"])
def test_a_corrupt_numba_entry_is_dropped_and_rebuilt(cache, damage) -> None:
    mod = _compiled_and_saved("test_corrupt")
    (target,) = [p for p in kernel_cache.numba_files(mod)
                 if p.suffix == (".nbi" if damage == "index" else ".nbc")]
    target.write_bytes(b"\x80\x04garbage" + os.urandom(64))
    with pytest.warns(RuntimeWarning, match="dropped the cached machine code"):
        mod = _fresh("test_corrupt")
        assert mod.f(2.0) == 5.0
    assert _hits(mod) == (0, 1)  # compiled again, and saved again
    mod = _fresh("test_corrupt")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert mod.f(2.0) == 5.0 and _hits(mod) == (1, 0)


def test_an_entry_that_fails_to_load_is_dropped(cache, monkeypatch) -> None:
    """Whatever numba raises while loading an entry (here: its index as a valid pickle of the
    wrong shape, re-sealed as if lgw had saved it) drops it: no broken run."""
    mod = _compiled_and_saved("test_shape")
    (index,) = [p for p in kernel_cache.numba_files(mod) if p.suffix == ".nbi"]
    index.write_bytes(pickle.dumps(numba.__version__) + pickle.dumps("not a tuple"))
    mod = _fresh("test_shape")
    entry = kernel_cache._Entry(mod.__name__.removeprefix("lgw_kernel_"), cache, mod.f._cache)
    entry.seal()  # the manifest now vouches for the bad file: numba itself fails on it
    with pytest.warns(RuntimeWarning, match="could not be loaded"):
        assert mod.f(1.0) == 3.0
    assert _hits(mod) == (0, 1)


def test_a_crafted_pickle_is_never_loaded(cache, tmp_path, monkeypatch) -> None:
    mod = _compiled_and_saved("test_crafted")
    (index,) = [p for p in kernel_cache.numba_files(mod) if p.suffix == ".nbi"]
    marker = tmp_path / "executed"
    _plant(index, marker)
    with pytest.warns(RuntimeWarning, match="dropped"):
        mod = _fresh("test_crafted")
        assert mod.f(1.0) == 3.0
    assert not marker.exists()
    # the threat is real: numba itself, without lgw's check, executes the planted pickle
    _plant(index, marker)
    monkeypatch.setattr(kernel_cache, "_guard", lambda *a: None)
    mod = _fresh("test_crafted")
    with pytest.raises(Exception):  # noqa: B017 (whatever numba makes of the payload)
        mod.f(1.0)
    assert marker.is_dir()


def test_a_foreign_entry_without_a_record_is_dropped(cache) -> None:
    """numba files lgw did not save (no manifest: copied in, or left by another tool)."""
    mod = _compiled_and_saved("test_foreign")
    Path(mod.__file__).with_suffix(".sums.json").unlink()
    with pytest.warns(RuntimeWarning, match="not as lgw saved"):
        mod = _fresh("test_foreign")
        assert mod.f(1.0) == 3.0
    assert _hits(mod) == (0, 1)


@pytest.mark.parametrize("how", ["world-writable", "group-writable", "foreign owner",
                                 "open parent"])
def test_an_untrusted_cache_directory_is_refused(cache, tmp_path, monkeypatch, how) -> None:
    """Nothing is read from it (a planted pickle stays unexecuted); a private temporary
    directory serves this process, and a warning says why."""
    _compiled_and_saved("test_refused")
    marker = tmp_path / "executed"
    for p in cache.glob("__pycache__/*.nbi"):
        _plant(p, marker)
    if how == "world-writable":
        cache.chmod(0o777)
    elif how == "group-writable":
        cache.chmod(0o770)
    elif how == "foreign owner":  # as if another user owned it (os.getuid cannot be changed)
        monkeypatch.setattr(kernel_cache, "_uid", lambda: os.getuid() + 1)
    else:
        tmp_path.chmod(0o777)  # a parent anyone may write to, and not sticky
    try:
        why = {"world-writable": "writable by others", "group-writable": "writable by group",
               "foreign owner": "owned by another user", "open parent": "writable by anyone"}
        with pytest.warns(RuntimeWarning, match=why[how]):
            d = kernel_cache.cache_dir()
        assert d != cache and cache not in d.parents
        with warnings.catch_warnings():  # "another user" (simulated) owns the fallback too
            warnings.simplefilter("ignore")
            mod = _fresh("test_refused")
        assert mod.f(1.0) == 3.0 and Path(mod.__file__).parent == d
        assert not marker.exists()
    finally:
        cache.chmod(0o700)
        tmp_path.chmod(0o700)


def test_an_untrusted_numba_directory_is_not_used(cache, tmp_path, monkeypatch) -> None:
    """NUMBA_CACHE_DIR pointing to a directory anyone may write to: numba's files for lgw's
    kernels are neither read nor written there (compiled in each process instead)."""
    shared = tmp_path / "numba-shared"
    shared.mkdir()
    shared.chmod(0o777)
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(shared))
    with pytest.warns(RuntimeWarning, match="numba's cache directory"):
        mod = _fresh("test_numba_dir")
    assert mod.f(1.0) == 3.0
    assert not [p for p in shared.rglob("*") if p.is_file()]


def test_the_text_is_found_by_its_inputs(cache, monkeypatch) -> None:
    """generated_module makes the text once per inputs; a pointer to a text that does not
    hash to its name (tampered) is not followed; a process whose sources changed after it
    started records no pointer."""
    calls = []
    monkeypatch.setattr(kernel_cache, "_process_start", lambda: time.time() + 1.0)

    def make(v: int):
        def text() -> str:
            calls.append(v)
            return _text(v)
        return text

    a = kernel_cache.generated_module("test_inputs", make(1), inputs=["one"])
    kernel_cache._LOADED.clear()
    b = kernel_cache.generated_module("test_inputs", make(1), inputs=["one"])
    assert calls == [1] and b.VALUE == 1 and b.__file__ == a.__file__
    kernel_cache.generated_module("test_inputs", make(2), inputs=["two"])
    assert calls == [1, 2]
    Path(a.__file__).write_text(_text(666))  # same name, another text
    kernel_cache._LOADED.clear()
    c = kernel_cache.generated_module("test_inputs", make(1), inputs=["one"])
    assert calls == [1, 2, 1] and c.VALUE == 1
    monkeypatch.setattr(kernel_cache, "_process_start", lambda: 0.0)  # sources are newer
    kernel_cache.generated_module("test_inputs", make(3), inputs=["three"])
    kernel_cache._LOADED.clear()
    kernel_cache.generated_module("test_inputs", make(3), inputs=["three"])
    assert calls == [1, 2, 1, 3, 3]


def test_the_generated_module_is_never_imported_from_disk(cache) -> None:
    """What runs is the text lgw generated, even if the file (or a bytecode file beside it)
    says otherwise between the check and the use."""
    mod = kernel_cache.module_for("test_exec", _text(5))
    Path(mod.__file__).write_text(_text(6))
    kernel_cache._LOADED.clear()
    again = kernel_cache.module_for("test_exec", _text(5))
    assert again.VALUE == 5 and Path(again.__file__).read_text() == _text(5)


def test_threads_probing_the_cache_at_once_all_keep_it(tmp_path, monkeypatch):
    """Two threads' first kernels check the cache directory at the same time: each must get
    the configured directory, not a temporary fallback (the probe file is per thread)."""
    import threading

    from lgw.sim import kernel_cache as KC

    monkeypatch.setenv(KC.ENV_VAR, str(tmp_path))
    got, start = [], threading.Barrier(8)

    def probe():
        start.wait()
        for _ in range(200):
            got.append(KC.cache_dir())

    threads = [threading.Thread(target=probe) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert set(got) == {tmp_path / "kernels"}
