"""The kernel cache keyed by the generated text (lgw.sim.kernel_cache, issue 14).

A process running while a hook's source file is edited can generate a wrong module (its
``inspect.getsource`` reads the new file with the old line numbers); keyed by the text itself,
that module lands in a file no correct process reads.  A corrupted or truncated cache file is
detected (its text is not the expected one) and rewritten before it is imported.
"""

from __future__ import annotations

import types

import pytest
from lgw.sim import kernel_cache


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path))
    monkeypatch.setattr(kernel_cache, "_LOADED", {})
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
