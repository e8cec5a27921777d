"""Every ``lgw VERB SYSTEM ...`` command line in docs/*.md is one the current CLI accepts, so the
docs cannot drift from the options.

Command lines are taken from the code blocks whose first line is a command (``lgw ...``,
``$ lgw ...``, ``python ...`` or a ``#`` comment; continuation lines are the more-indented lines
after a command) and from inline code spans that start with ``lgw``.  Program output quoted in
a block that starts otherwise (a pytest session, a table) is not a command line.

* A concrete line (no ``[ ]``, no ``a|b`` alternatives, no ``...``, no upper-case placeholder
  such as ``FILE`` or ``SECONDS``) is parsed by the command's own click parser and its options
  object is built: every option, value and rule across options is checked (the same named errors
  as the command line), and nothing is run.  Paths need not exist (inputs and outputs are
  checked by the command before its work, which is not run here).
* A synopsis line (``lgw simulate lunar [--gains FILE] [--pointing coupled|ideal]``) must name
  only options of its command (``--x/--no-x`` both), every alternative or literal value of a
  choice option must be one of its choices, and every literal value of a numeric option must be
  in its range.
* An inline code span in prose (`` `lgw tune lunar` ``, `` `lgw tune mars --tf 1000` ``) is a
  fragment: an option it does not name but the command requires is filled in (with the options
  test's probe value) before the options object is built; what it does name must be right.
* A line meant to fail carries a trailing comment with ``exits 2``: it must be refused.

``SYSTEM`` may be ``mars|lunar|eros`` (each is checked).  Lines naming no system
(``lgw verify SYSTEM``, ``lgw tune``) are not command lines.
"""

from __future__ import annotations

import re
import shlex
from dataclasses import dataclass
from pathlib import Path

import click
import pytest
from lgw.theory.errors import NotApplicableError, ParameterError
from lgw.tuning.commands import make_command
from lgw.tuning.options import PathArg
from lgw.tuning.spec import option_fields, probe_value
from lgw.tuning.system import VERBS, NotApplicable, get_system, system_names

ROOT = Path(__file__).resolve().parents[1]
DOCS = sorted((ROOT / "docs").glob("*.md"))
EXPECT_REFUSAL = "exits 2"
PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_/.=-]*$")  # FILE, DIR, N, M/S, CLAIM=FACTOR, ...
COMMAND_START = ("lgw ", "$ lgw ", "python ", "#", "$ ")


@dataclass(frozen=True)
class DocCommand:
    where: str  # file:line
    text: str  # the command line, continuation lines joined, comment removed
    comment: str
    fragment: bool = False  # an inline span: required options it leaves out are filled in

    @property
    def tokens(self) -> list[str]:
        return self.text.split()

    @property
    def synopsis(self) -> bool:
        if any(s in self.text for s in ("[", "]", "|", "...", "\u2026")):
            return True
        return any(PLACEHOLDER.match(t) for t in self.tokens[3:])

    @property
    def refused(self) -> bool:
        return EXPECT_REFUSAL in self.comment


def _split_comment(line: str) -> tuple[str, str]:
    m = re.search(r"\s#", line)
    return (line[:m.start()], line[m.end():].strip()) if m else (line, "")


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip(" "))


def _blocks(lines: list[str]) -> list[list[tuple[int, str]]]:
    """Code blocks: fenced (```) or indented by 4 spaces after a blank line."""
    blocks: list[list[tuple[int, str]]] = []
    i, n = 0, len(lines)
    while i < n:
        line = lines[i]
        if line.lstrip().startswith("```"):
            j = i + 1
            block = []
            while j < n and not lines[j].lstrip().startswith("```"):
                block.append((j + 1, lines[j]))
                j += 1
            blocks.append(block)
            i = j + 1
            continue
        if _indent(line) >= 4 and line.strip() and (i == 0 or not lines[i - 1].strip()):
            j = i
            block = []
            while j < n and (not lines[j].strip() or _indent(lines[j]) >= 4):
                block.append((j + 1, lines[j]))
                j += 1
            blocks.append(block)
            i = j
            continue
        i += 1
    return blocks


def _block_commands(path: Path, block: list[tuple[int, str]]) -> list[DocCommand]:
    body = [(k, ln) for k, ln in block if ln.strip()]
    if not body or not body[0][1].lstrip().startswith(COMMAND_START):
        return []  # program output, a table, TOML, ...: not a command block
    out = []
    i = 0
    while i < len(body):
        k, ln = body[i]
        s = ln.strip()
        if s.startswith("$ "):
            s = s[2:]
        if not s.startswith("lgw "):
            i += 1
            continue
        text, comment = _split_comment(s)
        j = i + 1
        while j < len(body) and _indent(body[j][1]) > _indent(ln) and not \
                body[j][1].lstrip().startswith(COMMAND_START):
            more, c = _split_comment(body[j][1].strip())
            text += " " + more
            comment = " ".join(x for x in (comment, c) if x)
            j += 1
        # the shell's part of a line (a redirection, a following command) is not lgw's
        text = re.split(r"\s(?:\d?>>?|&&|;)\s", text)[0]
        out.append(DocCommand(f"{path.name}:{k}", " ".join(text.split()), comment))
        i = j
    return out


def _inline_commands(path: Path, text: str) -> list[DocCommand]:
    out = []
    for m in re.finditer(r"(?<!`)`(lgw [^`]+)`(?!`)", text):
        line = text.count("\n", 0, m.start()) + 1
        out.append(DocCommand(f"{path.name}:{line}", " ".join(m.group(1).split()), "",
                              fragment=True))
    return out


def doc_commands() -> list[DocCommand]:
    """Every ``lgw VERB SYSTEM`` command line of docs/*.md."""
    found = []
    for path in DOCS:
        text = path.read_text(encoding="utf-8")
        lines = text.splitlines()
        for block in _blocks(lines):
            found += _block_commands(path, block)
        found += _inline_commands(path, text)
    out = []
    for c in found:
        t = c.tokens
        if len(t) >= 3 and t[1] in VERBS and all(s in system_names() for s in
                                                 t[2].split("|")):
            out.append(c)
    return out


COMMANDS = doc_commands()


def _params(verb: str, system: str) -> tuple[click.Command, dict[str, click.Parameter]]:
    cmd = make_command(get_system(system), verb)
    flags: dict[str, click.Parameter] = {"--help": None, "-h": None}
    for p in cmd.params:
        for o in (*p.opts, *getattr(p, "secondary_opts", ())):
            flags[o] = p
    return cmd, flags


def parse(verb: str, system: str, args: list[str], fragment: bool = False):
    """The options object ``lgw VERB SYSTEM ARGS`` builds (nothing is run): raises the
    command line's error (ParameterError, NotApplicableError, click.UsageError) otherwise.
    ``fragment``: an option the arguments do not name that the command requires (an error
    naming it) is filled in and the line parsed again."""
    v = get_system(system).verbs.get(verb)
    if isinstance(v, NotApplicable):
        raise NotApplicableError(verb, system, v.reason)
    cmd, flags = _params(verb, system)
    mod = v.load()
    args = list(args)
    named = {a.split("=")[0] for a in args if a.startswith("-")}
    for _ in range(len(flags) + 1):
        ctx = cmd.make_context(f"lgw {verb} {system}", list(args))
        try:
            return mod.Options(**ctx.params)
        except ParameterError as e:
            if not fragment or e.name in named or e.name not in flags:
                raise
            named.add(e.name)
            args += _filler(mod.Options, e.name)
    raise AssertionError(f"lgw {verb} {system} {args}: cannot complete the fragment")


def _filler(cls, flag: str) -> list[str]:
    """Arguments that set option ``flag`` to a valid value (a fragment's missing option)."""
    for f, o in option_fields(cls):
        if o.flag != flag:
            continue
        if o.is_flag:
            return [flag]
        if o.flag == "--out":
            return [flag, "out.toml" if getattr(o.type, "kind", "") == "file" else "out"]
        if isinstance(o.type, PathArg):  # a path: not read here
            return [flag, "x.toml" if o.type.kind == "file" else "x"]
        return [flag, str(probe_value(f, o))]
    raise AssertionError(f"{flag}: not an option of {cls.__module__}")


def check_synopsis(verb: str, system: str, tokens: list[str]) -> list[str]:
    """What a synopsis names that the command does not take (empty: it is right)."""
    _, flags = _params(verb, system)
    problems = []
    toks = [t.strip("[]()") for t in tokens]
    for i, tok in enumerate(toks):
        for flag in re.findall(r"(?<![\w-])--?[a-z][a-z0-9-]*", tok):
            if flag not in flags:
                problems.append(f"{flag}: no such option")
                continue
            p = flags[flag]
            if p is None or getattr(p, "is_flag", False) or "/" in tok or i + 1 >= len(toks):
                continue
            nxt = toks[i + 1]
            if not nxt or nxt.startswith("-"):
                continue
            values = [x for x in nxt.split("|") if x and x not in ("...", "\u2026")]
            for val in values:
                if PLACEHOLDER.match(val):
                    continue
                try:
                    p.type.convert(val, p, None)
                except (ParameterError, click.BadParameter) as e:
                    problems.append(f"{flag} {val}: {e}")
    return problems


def _ids(c: DocCommand) -> str:
    return f"{c.where} {' '.join(c.tokens[1:3])}"


def test_docs_have_command_lines():
    """The extraction finds command lines of every verb the docs show (a broken extractor
    would pass everything)."""
    assert len(COMMANDS) >= 60, len(COMMANDS)
    verbs = {c.tokens[1] for c in COMMANDS}
    assert {"bounds", "simulate", "verify", "tune", "report", "compare", "optimal"} <= verbs
    assert any(not c.synopsis for c in COMMANDS) and any(c.synopsis for c in COMMANDS)
    print(f"\ndocs command lines: {len(COMMANDS)} ({sum(not c.synopsis for c in COMMANDS)} "
          f"parsed, {sum(c.synopsis for c in COMMANDS)} synopses, "
          f"{sum(c.refused for c in COMMANDS)} meant to fail)")


def test_docs_show_every_verb_of_every_system():
    """Every applicable verb of every system has a command line in the docs, outside
    docs/json.md (whose generated table lists every command whatever the docs say)."""
    shown = {(c.tokens[1], system) for c in COMMANDS if not c.where.startswith("json.md:")
             for system in c.tokens[2].split("|")}
    missing = sorted(f"lgw {verb} {s}" for s in system_names()
                     for verb, v in get_system(s).verbs.items()
                     if not isinstance(v, NotApplicable) and (verb, s) not in shown)
    assert not missing, f"no command line in docs/*.md for {missing}"


@pytest.mark.parametrize("cmd", COMMANDS, ids=_ids)
def test_doc_command_line_is_accepted(cmd: DocCommand):
    verb = cmd.tokens[1]
    for system in cmd.tokens[2].split("|"):
        if cmd.synopsis:
            problems = check_synopsis(verb, system, cmd.tokens[3:])
            if cmd.refused:
                assert problems, f"{cmd.where}: `{cmd.text}` is marked '{EXPECT_REFUSAL}' " \
                    "but its synopsis is valid"
            else:
                assert not problems, f"{cmd.where}: `{cmd.text}` ({system}): " + \
                    "; ".join(problems)
            continue
        try:
            opts = parse(verb, system, shlex.split(cmd.text)[3:], cmd.fragment)
        except (ParameterError, NotApplicableError, click.ClickException) as e:
            msg = e.format_message() if isinstance(e, click.ClickException) else str(e)
            assert cmd.refused, f"{cmd.where}: `{cmd.text}` is refused: {msg}"
            continue
        assert not cmd.refused, f"{cmd.where}: `{cmd.text}` is marked '{EXPECT_REFUSAL}' but " \
            f"is accepted"
        assert {f.name for f, _ in option_fields(opts)}


# --- the checker's own tests --------------------------------------------------------------------

def test_extractor_and_checker_catch_drift(tmp_path):
    """A renamed option, a wrong choice, an out-of-range value and an unknown option in a
    synopsis are all caught; a valid line and a line marked to fail are handled."""
    doc = tmp_path / "x.md"
    doc.write_text("Intro `lgw simulate eros --t-final 8000` and\n`lgw tune eros --ts 10\n"
                   "--thrust-max 30 --out g.toml`.\n\n"
                   "```\nlgw simulate lunar [--pointing coupled|sideways] [--bogus N]\n"
                   "                   [--t-max 15]\n"
                   "lgw bounds lunar --eq0-min 2   # exits 2\n"
                   "lgw optimal eros  # exits 2\n```\n\n"
                   "    test.py::x PASSED\n    lgw verify mars /tmp/g.toml:\n")
    text = doc.read_text()
    found = _inline_commands(doc, text)
    for block in _blocks(text.splitlines()):
        found += _block_commands(doc, block)
    by = {c.text.split(" [")[0].split(" --")[0] + (" S" if c.synopsis else ""): c
          for c in found}
    assert sorted(by) == ["lgw bounds lunar", "lgw optimal eros", "lgw simulate eros",
                          "lgw simulate lunar S", "lgw tune eros"], sorted(by)
    with pytest.raises(click.UsageError, match="--t-final"):
        parse("simulate", "eros", shlex.split(by["lgw simulate eros"].text)[3:])
    assert parse("tune", "eros", shlex.split(by["lgw tune eros"].text)[3:]).ts == 10.0
    syn = by["lgw simulate lunar S"]
    assert "[--t-max 15]" in syn.text  # the continuation line is joined
    problems = check_synopsis("simulate", "lunar", syn.tokens[3:])
    assert any("sideways" in p for p in problems) and any("--bogus" in p for p in problems)
    assert len(problems) == 2, problems
    assert check_synopsis("simulate", "lunar", ["[--dt", "5]"])  # out of range
    assert by["lgw bounds lunar"].refused
    with pytest.raises(ParameterError, match="--eq0-min"):
        parse("bounds", "lunar", ["--eq0-min", "2"])
    with pytest.raises(NotApplicableError):
        parse("optimal", "eros", [])
