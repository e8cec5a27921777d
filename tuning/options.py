"""Options and parameter types shared by the subcommands (one name, one style).

Every numeric option is a ``Number`` or ``Integer``: finite, inside its documented range, or a
``ParameterError`` naming the option, the value and the range (one line ``error: ...``, exit 2
through ``lgw.tuning.cli.main``).  Every choice option is a ``click.Choice`` (``choice``), so
``--help`` lists the values and a wrong one is an ``error:`` line with exit 2 as well.

``--out`` means one thing everywhere: where the command's output goes.  Commands that write
several files take a folder (created if missing: ``out_dir_option``); a command that writes one
file takes that file's path (``out_file_option``: ``lgw tune``).  Either is checked before any
work and written atomically (``lgw.tuning.io``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import click
from lgw.theory.errors import ParameterError

SEED_MAX = 2**64 - 1  # SeedSequence entropy: 64 bits is more than any campaign needs


def _opt_name(param: click.Parameter | None) -> str:
    if param is None:
        return "value"
    opts = [o for o in getattr(param, "opts", []) if o.startswith("--")]
    return opts[0] if opts else (param.name or "value")


def _num(x: float) -> str:
    return str(x) if isinstance(x, int) else f"{x:g}"


def _range_text(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    if lo is not None and hi is not None:
        return f"in {'(' if lo_open else '['}{_num(lo)}, {_num(hi)}{')' if hi_open else ']'}"
    if lo is not None:
        return f"{'>' if lo_open else '>='} {_num(lo)}"
    if hi is not None:
        return f"{'<' if hi_open else '<='} {_num(hi)}"
    return ""


class Number(click.ParamType):
    """A finite float, optionally in [lo, hi] (open ends with lo_open / hi_open), with a unit."""

    name = "number"

    def __init__(self, lo: float | None = None, hi: float | None = None, *,
                 lo_open: bool = False, hi_open: bool = False, unit: str = "") -> None:
        self.lo, self.hi, self.lo_open, self.hi_open, self.unit = lo, hi, lo_open, hi_open, unit
        rng = _range_text(lo, hi, lo_open, hi_open)
        self.valid = ("must be a finite number" + (f" {rng}" if rng else "")
                      + (f" ({unit})" if unit else ""))

    def get_metavar(self, param: click.Parameter, ctx: click.Context | None = None) -> str:
        return "FLOAT"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> float:
        try:
            x = float(value)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError(_opt_name(param), value, self.valid) from None
        ok = math.isfinite(x)
        if ok and self.lo is not None:
            ok = x > self.lo if self.lo_open else x >= self.lo
        if ok and self.hi is not None:
            ok = x < self.hi if self.hi_open else x <= self.hi
        if not ok:
            raise ParameterError(_opt_name(param), value, self.valid)
        return x


class Integer(click.ParamType):
    """An integer in [lo, hi]."""

    name = "integer"

    def __init__(self, lo: int | None = None, hi: int | None = None, what: str = "") -> None:
        self.lo, self.hi = lo, hi
        rng = _range_text(lo, hi, False, False)
        self.valid = "must be an integer" + (f" {rng}" if rng else "") + (
            f" ({what})" if what else "")

    def get_metavar(self, param: click.Parameter, ctx: click.Context | None = None) -> str:
        return "INTEGER"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> int:
        if isinstance(value, bool):
            raise ParameterError(_opt_name(param), value, self.valid)
        if isinstance(value, int):
            n = value
        else:
            s = str(value).strip()
            if not s.lstrip("+-").isdigit() or len(s) > 40:
                raise ParameterError(_opt_name(param), value, self.valid)
            n = int(s)
        if (self.lo is not None and n < self.lo) or (self.hi is not None and n > self.hi):
            raise ParameterError(_opt_name(param), value, self.valid)
        return n


class Choice(click.Choice):
    """``click.Choice`` (``--help`` lists the values) whose wrong value is lgw's error: a
    ParameterError naming the option and the valid values, like every other bad input."""

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> Any:
        try:
            return super().convert(value, param, ctx)
        except click.BadParameter:
            raise ParameterError(_opt_name(param), value,
                                 f"must be one of {', '.join(map(str, self.choices))}") from None


def choice(values: Sequence[str]) -> Choice:
    return Choice(tuple(values), case_sensitive=True)


SEED = Integer(0, SEED_MAX, "a numpy SeedSequence seed")


def gains_option(f):
    return click.option("--gains", "gains_path",
                        type=click.Path(dir_okay=False, path_type=Path), default=None,
                        help="gains TOML file (UTF-8; the keys of the system, see its docs) "
                             "[default: the system's built-in gain set]")(f)


def seed_option(help_text: str = "random seed (numpy SeedSequence)"):
    def deco(f):
        return click.option("--seed", type=SEED, default=0, show_default=True,
                            help=f"{help_text}; integer in [0, 2^64 - 1]")(f)
    return deco


def out_dir_option(files: str, dest: str = "out"):
    """``--out DIR``: a folder (created if missing) for the files ``files``."""
    def deco(f):
        return click.option("--out", dest, type=click.Path(path_type=Path), default=None,
                            help=f"output folder (created if missing) for {files}; checked "
                                 "before any work, files written atomically")(f)
    return deco


SCHEDULER_TIMEOUT = 10.0  # s, default of --scheduler-timeout


def check_scheduler(address: str, timeout: float = SCHEDULER_TIMEOUT) -> dict[str, Any]:
    """Fail fast on ``--scheduler``: connect to ``address`` within ``timeout`` seconds, ask for
    its identity and require a dask scheduler to answer.  Anything else (a closed port, an HTTP
    server that never answers the dask handshake, garbage that would make the comm allocate
    exabytes, a worker's address) is one ParameterError, bounded by about 2 x ``timeout``."""
    import asyncio

    from distributed.comm import connect

    async def probe() -> Any:
        comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
        try:
            await asyncio.wait_for(comm.write({"op": "identity", "reply": True}), timeout)
            return await asyncio.wait_for(comm.read(), timeout)
        finally:
            comm.abort()

    what = f"the address of a running dask scheduler (e.g. tcp://host:8786), answering within " \
           f"{timeout:g} s"
    try:
        ident = asyncio.run(asyncio.wait_for(probe(), 2 * timeout))
    except TimeoutError:
        raise ParameterError("--scheduler", address, what,
                             "no dask handshake: not a dask scheduler, or unreachable") from None
    except Exception as e:  # noqa: BLE001 - any failure to talk dask is the same user error
        msg = " ".join(str(e).split())[:160]
        raise ParameterError("--scheduler", address, what,
                             f"{type(e).__name__}: {msg}") from None
    if not (isinstance(ident, dict) and ident.get("type") == "Scheduler"):
        kind = ident.get("type") if isinstance(ident, dict) else type(ident).__name__
        raise ParameterError("--scheduler", address, what, f"it answered as {kind!r}")
    return ident


class PathArg(click.ParamType):
    """A file or folder path given on the command line (existence and kind are checked by the
    command before any work: inputs by ``lgw.theory.inputs``, outputs by ``lgw.tuning.io``)."""

    name = "path"

    def __init__(self, kind: str = "file") -> None:
        self.kind = kind  # "file" | "dir"

    def get_metavar(self, param: click.Parameter, ctx: click.Context | None = None) -> str:
        return "FILE" if self.kind == "file" else "DIR"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> Path:
        if isinstance(value, Path):
            return value
        if not isinstance(value, str) or not value.strip() or "\x00" in value:
            raise ParameterError(_opt_name(param), value, f"must be a {self.kind} path")
        return Path(value)


class ScaleItem(click.ParamType):
    """``CLAIM=FACTOR``: a claim name and a finite factor > 0 (bound scaling, the checker's
    self-test), converted to a (name, factor) pair."""

    name = "scale"

    def get_metavar(self, param: click.Parameter, ctx: click.Context | None = None) -> str:
        return "CLAIM=FACTOR"

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None
                ) -> tuple[str, float]:
        if isinstance(value, tuple) and len(value) == 2:
            name, val = value
        else:
            name, sep, val = str(value).partition("=")
            if not sep or not name:
                raise ParameterError(_opt_name(param), value, "must be CLAIM=FACTOR")
        try:
            x = float(val)
        except (TypeError, ValueError):
            raise ParameterError(_opt_name(param), value, "FACTOR must be a number") from None
        if not (math.isfinite(x) and x > 0):
            raise ParameterError(_opt_name(param), value, "FACTOR must be finite and > 0")
        return (str(name), x)


FILE = PathArg("file")
DIR = PathArg("dir")
