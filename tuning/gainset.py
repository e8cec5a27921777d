"""A system's gain set as the shared commands see it, written once: load a ``--gains`` file,
the built-in default, the ``gains`` head of every JSON document, and an example gain set.

Each system's ``lgw.tuning.<name>.gainset`` module parametrises one ``GainSet`` with its own
loader, default and example, and exposes its parts as module functions (the ``System``'s
``gains`` module: ``load``, ``default``, ``resolve``, ``document``, ``example``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any


def to_dict(g: Any) -> dict[str, Any]:
    """The gain set's own dictionary as the document's head."""
    return g.to_dict()


@dataclass(frozen=True)
class GainSet:
    """``load(path)``: the validated gain set of a file (named errors); ``default()``: the
    built-in one; ``example()``: a valid gain set other than the default (TOML), for the
    options test; ``document(g)``: the head of every JSON document (``gains`` and what else
    the file holds)."""

    load: Callable[[Path], Any]
    default: Callable[[], Any]
    example: Callable[[], str]
    document: Callable[[Any], dict[str, Any]] = to_dict

    def resolve(self, path: Path | None) -> Any:
        """The gain set of ``--gains`` (validated), or the built-in default."""
        return self.default() if path is None else self.load(path)

    def parts(self) -> tuple[Callable[..., Any], ...]:
        """``load, default, resolve, document, example``: the functions of a gains module."""
        return self.load, self.default, self.resolve, self.document, self.example
