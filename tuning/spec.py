"""Options objects: the one place where every command-line option is declared and validated.

Every verb of every system takes one frozen options object (a dataclass deriving from
``Options``).  Each field is declared with ``option(...)``: its flag, its type (a
``lgw.tuning.options`` parameter type: ``Number`` with its range and unit, ``Integer``,
``choice``, a path or a flag), its default and help.  The object validates itself on
construction, field by field with the same type objects the command line uses, then across
fields (``check``), so a library caller and the command line meet the same named errors.  The
click options of a command are derived from the fields (``click_params``): there is no second
list of options, types or ranges anywhere.

A command's options are planned into a ``Job`` (``lgw.tuning.system``): the inputs of the
computation and nothing else.  ``fingerprint`` reduces a job to a canonical string, so the
options test can show that every option changes what is computed or is refused.
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
from collections.abc import Iterator
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import click
from lgw.theory.errors import ParameterError

MISSING = dataclasses.MISSING


class _NoProbe:
    def __repr__(self) -> str:
        return "NO_PROBE"


NO_PROBE = _NoProbe()  # the options test cannot set this option alone (it names a resource)
DERIVE = None  # probe not declared: derived from the type


@dataclass(frozen=True)
class Opt:
    """How one options field appears on the command line.

    ``flag``: the long option (``--t-max``); ``type``: the click parameter type that also
    validates the value (None for flags and free text); ``probe``: a valid non-default value
    the options test sets to show the option matters (``MISSING``: derive one from the type);
    ``execution``: the option changes how or where results go (``--json``, ``--out``,
    ``--workers``), not what is computed; ``secondary``: the flag of a ``--x/--no-x`` pair;
    ``multiple``: repeatable (the field holds a tuple)."""

    flag: str
    type: Any = None
    help: str = ""
    probe: Any = DERIVE
    execution: bool = False
    secondary: str | None = None
    multiple: bool = False
    is_flag: bool = False
    hidden: bool = False
    metavar: str | None = None
    show_default: bool = True


def option(flag: str, type: Any = None, default: Any = None, help: str = "", *,
           probe: Any = DERIVE, execution: bool = False, secondary: str | None = None,
           multiple: bool = False, is_flag: bool = False, hidden: bool = False,
           metavar: str | None = None, show_default: bool = True) -> Any:
    """A dataclass field that is a command-line option (see ``Opt``)."""
    meta = Opt(flag, type, help, probe, execution, secondary, multiple, is_flag, hidden,
               metavar, show_default)
    if multiple:
        return field(default=tuple(default or ()), metadata={"lgw": meta})
    return field(default=default, metadata={"lgw": meta})


def opt_of(f: dataclasses.Field) -> Opt | None:
    return f.metadata.get("lgw")


def option_fields(cls_or_obj: Any) -> Iterator[tuple[dataclasses.Field, Opt]]:
    for f in fields(cls_or_obj):
        o = opt_of(f)
        if o is not None:
            yield f, o


@dataclass(frozen=True)
class Options:
    """Base of every options object: validates each option field with its own type, then
    calls ``check`` for rules across fields.  Unknown keywords are a TypeError (dataclass), as
    in python-control: a misspelled option is never silently ignored."""

    def __post_init__(self) -> None:
        for f, o in option_fields(self):
            v = getattr(self, f.name)
            if v is None or o.type is None:
                if o.is_flag and not isinstance(v, bool):
                    raise ParameterError(o.flag, v, "is a flag: true or false")
                continue
            if o.multiple:
                conv = tuple(o.type.convert(x, _Named(o.flag), None) for x in v)
            else:
                conv = o.type.convert(v, _Named(o.flag), None)
            object.__setattr__(self, f.name, conv)
        self.check()

    def check(self) -> None:
        """Rules across fields (override): raise ParameterError naming the option."""

    def replace(self, **changes: Any) -> Options:
        return dataclasses.replace(self, **changes)

    def given(self, name: str) -> bool:
        """Whether option ``name`` differs from its declared default."""
        f = {f.name: f for f in fields(self)}[name]
        default = f.default if f.default is not MISSING else None
        return getattr(self, name) != default

    def refuse_unless(self, condition: bool, name: str, why: str) -> None:
        """Refuse option ``name`` when it was given but ``condition`` (where it applies) is
        false: an accepted and ignored option is a defect."""
        if not condition and self.given(name):
            f = {f.name: f for f in fields(self)}[name]
            o = opt_of(f)
            raise ParameterError(o.flag if o else name, getattr(self, name), why)


class _Named:
    """Stands in for a click.Parameter so the parameter types name the option."""

    def __init__(self, flag: str) -> None:
        self.opts = [flag]
        self.name = flag.lstrip("-").replace("-", "_")


def click_params(cls: type[Options]) -> list[click.Parameter]:
    """The click options of an options class, in field order (the types are the fields')."""
    out: list[click.Parameter] = []
    # what is computed first, then where and how it goes (--json, --out, --workers, ...)
    ordered = sorted(option_fields(cls), key=lambda fo: fo[1].execution)
    for f, o in ordered:
        default = f.default if f.default is not MISSING else None
        decls = [o.flag if o.secondary is None else f"{o.flag}/{o.secondary}", f.name]
        kw: dict[str, Any] = {"help": o.help, "hidden": o.hidden}
        if o.is_flag or o.secondary is not None:
            kw.update(is_flag=True, default=default if o.secondary is not None else bool(default),
                      show_default=o.secondary is not None and default is not None)
        else:
            kw.update(default=default, multiple=o.multiple,
                      show_default=o.show_default and default not in (None, ()))
            if o.type is not None:  # the same type object converts again in the options
                kw["type"] = o.type
            if o.metavar:
                kw["metavar"] = o.metavar
        out.append(click.Option(decls, **kw))
    return out


def probe_value(f: dataclasses.Field, o: Opt) -> Any:
    """A valid value different from the default, for the options test."""
    if o.probe is not DERIVE:
        return o.probe
    default = f.default if f.default is not MISSING else None
    if o.is_flag or o.secondary is not None:
        return not bool(default)
    t = o.type
    choices = getattr(t, "choices", None)
    if choices:
        for c in choices:
            if c != default:
                return c
    lo, hi = getattr(t, "lo", None), getattr(t, "hi", None)
    if isinstance(default, int | float) and not isinstance(default, bool):
        cand = default * 1.5 if default else 1.0
        if isinstance(default, int) and not isinstance(t, type(None)) and \
                type(t).__name__ == "Integer":
            cand = default + 1
        if hi is not None and cand > hi:
            cand = (default + (lo if lo is not None else 0)) / 2
        return cand
    if lo is not None and hi is not None:
        return (lo + hi) / 2
    raise LookupError(f"{o.flag}: declare a probe value")


def fingerprint(obj: Any) -> str:
    """A canonical digest of a job (dataclasses, mappings, sequences, arrays, paths, numbers):
    equal inputs give equal digests, any difference another one."""
    h = hashlib.sha256()

    def feed(x: Any) -> None:
        import numpy as np

        if dataclasses.is_dataclass(x) and not isinstance(x, type):
            h.update(f"<{type(x).__qualname__}".encode())
            for f in fields(x):
                if f.metadata.get("fingerprint", True):
                    h.update(f.name.encode())
                    feed(getattr(x, f.name))
            h.update(b">")
        elif isinstance(x, dict):
            h.update(b"{")
            for k in sorted(x, key=str):
                feed(str(k))
                feed(x[k])
            h.update(b"}")
        elif isinstance(x, list | tuple):
            h.update(b"[")
            for v in x:
                feed(v)
            h.update(b"]")
        elif isinstance(x, np.ndarray):
            a = np.ascontiguousarray(x)
            h.update(f"a{a.dtype.str}{a.shape}".encode())
            h.update(a.tobytes())
        elif isinstance(x, float):
            h.update(b"f" + (repr(x) if math.isfinite(x) or math.isnan(x) else repr(x)).encode())
        elif isinstance(x, np.generic):
            feed(x.item())
        elif isinstance(x, Path):
            h.update(b"p" + str(x).encode())
        elif hasattr(x, "to_dict"):
            feed(x.to_dict())
        elif callable(x):
            h.update(f"c{getattr(x, '__module__', '')}.{getattr(x, '__qualname__', x)}"
                     .encode())
        else:
            h.update(f"{type(x).__name__}:{x!r}".encode())

    feed(obj)
    return h.hexdigest()
