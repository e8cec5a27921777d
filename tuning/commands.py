"""Every verb, written once: ``lgw VERB SYSTEM`` for every registered ``System``.

A command is built from the system's verb module (``Options`` and ``plan``): its click options
are the options class's fields (``lgw.tuning.spec.click_params``).  Running it is the same for
every verb and system:

1. the options object is built (the only validation: named errors, exit 2);
2. every output location (``--out``, ``--plot``, ``--database``) is checked before any work,
   and no output may replace one of the run's input files;
3. ``plan(options, system)`` resolves the options into a ``Job`` (the inputs of the
   computation), and ``job.run(progress)`` computes an ``Outcome``;
4. library warnings raised during the run are caught and translated into one line each;
5. ``--json`` prints the JSON document (``lgw_version``, ``command``, ``gains`` first;
   streamed when it holds a ``Stream``), otherwise the outcome's tables are printed;
6. ``--out`` and ``--plot`` are written, each as one atomic set;
7. the exit code is the outcome's (0, 1 violated, 3 infeasible, 4 inconclusive).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path
from typing import Any

import click
from lgw.theory.errors import NotApplicableError, ParameterError
from lgw.tuning.spec import click_params, option_fields
from lgw.tuning.system import VERBS, NotApplicable, Outcome, System, get_system

DOCUMENT = object()  # in Outcome.files: "the command's JSON document goes here"


def _first_line(text: str | None) -> str:
    return (text or "").strip().splitlines()[0] if text and text.strip() else ""


def make_command(system: System, verb: str) -> click.Command:
    """The click command ``lgw VERB SYSTEM``."""
    v = system.verbs.get(verb)
    if v is None or isinstance(v, NotApplicable):
        reason = v.reason if v is not None else "not a verb of this system"

        def refuse() -> None:
            raise NotApplicableError(verb, system.name, reason)

        return click.Command(system.name, callback=refuse,
                             help=f"Not applicable to {system.name}: {reason}",
                             short_help=f"not applicable: {reason}")
    mod = v.load()
    params = click_params(mod.Options)

    def callback(**kw: Any) -> int:
        opts = mod.Options(**kw)
        return run(system, verb, mod, opts)

    doc = (mod.__doc__ or v.help).strip()
    return click.Command(system.name, params=params, callback=callback, help=doc,
                         short_help=v.help, context_settings={"max_content_width": 100})


def output_locations(opts: Any) -> dict[str, Any]:
    """The options that name outputs: flag -> value (``--out``, ``--plot``, ``--database``)."""
    out = {}
    for f, o in option_fields(opts):
        if o.flag in ("--out", "--plot", "--database") and getattr(opts, f.name) is not None:
            out[o.flag] = (getattr(opts, f.name), o.type)
    return out


def input_files(opts: Any, mod: Any) -> list[Path]:
    """The files a run reads: every file-typed option except outputs, and ``mod.inputs``."""
    from lgw.tuning.options import PathArg

    paths = []
    for f, o in option_fields(opts):
        val = getattr(opts, f.name)
        if o.flag in ("--out", "--plot", "--database") or val is None:
            continue
        if isinstance(o.type, PathArg):
            paths.extend(val if o.multiple else [val])
    if hasattr(mod, "inputs"):
        paths.extend(mod.inputs(opts))
    return [Path(p) for p in paths]


def check_outputs(opts: Any, mod: Any) -> dict[str, Path]:
    """Check every output location before any work (see ``lgw.tuning.io``)."""
    from lgw.tuning.io import check_output_dir, check_output_file
    from lgw.tuning.options import PathArg

    inputs = input_files(opts, mod)
    checked = {}
    for flag, (val, typ) in output_locations(opts).items():
        if flag == "--database":
            from lgw.tuning.io import check_out_dir

            checked[flag] = check_out_dir(val, flag)
        elif isinstance(typ, PathArg) and typ.kind == "file":
            checked[flag] = check_output_file(val, flag, inputs)
        else:
            checked[flag] = check_output_dir(val, flag, inputs)
    return checked


def translate_warning(w: warnings.WarningMessage) -> str:
    """One line in lgw's words for a warning a library raised during the run."""
    msg = " ".join(str(w.message).split())
    src = Path(w.filename).parts
    lib = next((p for p in ("scipy", "numpy", "numba", "cvxpy", "sympy", "control", "dask",
                            "distributed", "matplotlib", "hypothesis") if p in src), "")
    known = (("lsoda", "scipy's LSODA (the tight reference integrator) reported repeated "
              "convergence failures; it shrinks its step and retries, and a case it cannot "
              "carry is reported as failed by its own status"),
             ("overflow", "a computation overflowed to inf; the affected cases are counted "
              "apart as non-finite"),
             ("invalid value", "a computation produced NaN; the affected cases are counted "
              "apart as non-finite"),
             ("divide by zero", "a division by zero produced inf; the affected cases are "
              "counted apart as non-finite"),
             ("solution may be inaccurate", "the convex solver reported an inaccurate "
              "solution; the result is re-checked by the bound functions"))
    for key, text in known:
        if key in msg.lower():
            return f"note: {text} ({lib or w.category.__name__}: {msg[:160]})"
    return f"note: {lib or 'a library'} warned: {w.category.__name__}: {msg[:200]}"


def run(system: System, verb: str, mod: Any, opts: Any) -> int:
    """Run one verb of one system with validated options; see the module docstring."""
    from lgw.tuning.io import console, json_stream, write_json_document, write_output_set
    from lgw.tuning.progress import Progress

    outputs = check_outputs(opts, mod)
    command = f"{verb} {system.name}"
    progress = Progress()
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            job = mod.plan(opts, system)
            outcome: Outcome = job.run(progress)
    finally:
        progress.close()
    seen: dict[str, int] = {}
    for w in caught:
        if not issubclass(w.category, DeprecationWarning):
            line = translate_warning(w)
            seen[line] = seen.get(line, 0) + 1
    notes = [line + (f" [{n} times]" if n > 1 else "") for line, n in seen.items()]
    head: dict[str, Any] = {"command": command}
    gains = getattr(job, "gains", None)
    if gains is not None:
        head.update(system.gains_module().document(gains))
    else:  # every document carries gains: a job that flies none (optimal) says null, a
        head["gains"] = None  # tuner puts the gains it designed in its document
    doc = {**head, **outcome.document}
    if notes:
        doc["library_warnings"] = notes
    as_json = bool(getattr(opts, "json", False))
    out_dir = outputs.get("--out")
    plot_dir = outputs.get("--plot")
    written: list[Path] = []
    sets: dict[Path, dict[str, Any]] = {}
    single = getattr(_field_type(opts, "--out"), "kind", "dir") == "file"
    for line in outcome.stderr:
        click.echo(line, err=True)
    if out_dir is not None and (outcome.files or not single):
        files = {n: (json_stream(doc) if c is DOCUMENT else c)
                 for n, c in outcome.files.items()}
        if not files:  # a verb with nothing else to write writes its document
            files = {f"{verb}.json": json_stream(doc)}
        if single:
            from lgw.tuning.io import atomic_writer

            (name, content), = files.items()
            with atomic_writer(out_dir, "w") as f:
                if hasattr(content, "write") and content.write is not None:
                    content.write(f)
                else:
                    f.write(content if isinstance(content, str) else content.decode())
            written.append(out_dir)
        else:
            sets[out_dir.absolute()] = dict(files)
    if plot_dir is not None and outcome.figures:
        sets.setdefault(plot_dir.absolute(), {}).update({f.file: f.png
                                                         for f in outcome.figures})
    for folder, files in sets.items():
        flag = "--out" if out_dir is not None and folder == out_dir.absolute() else "--plot"
        written += write_output_set(folder, files, f"lgw {command}", flag)
    if as_json:
        write_json_document(doc, sys.stdout)
    else:
        con = console()
        if outcome.render is not None:
            outcome.render(con)
        for line in outcome.flags:
            con.print(f"warning: {line}", markup=False, highlight=False)
        for line in notes:
            con.print(line, markup=False, highlight=False)
        if written:
            con.print("wrote " + ", ".join(str(p) for p in written), markup=False,
                      highlight=False)
    return outcome.exit_code


def _field_type(opts: Any, flag: str) -> Any:
    for _f, o in option_fields(opts):
        if o.flag == flag:
            return o.type
    return None


class VerbGroup(click.Group):
    """``lgw VERB``: one subcommand per system, built on use."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        from lgw.tuning.system import system_names

        return list(system_names())

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        from lgw.tuning.system import system_names

        if name not in system_names():
            return None
        return make_command(get_system(name), self.name)

    def resolve_command(self, ctx: click.Context, args: list[str]):
        from lgw.tuning.system import system_names

        name = args[0] if args else ""
        if name.startswith("-") or name in system_names():
            return super().resolve_command(ctx, args)
        raise ParameterError("SYSTEM", name, f"lgw {self.name} takes one of "
                             f"{', '.join(system_names())}")

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = []
        for s in self.list_commands(ctx):
            v = get_system(s).verbs.get(self.name)
            text = v.help if not isinstance(v, NotApplicable) and v is not None else \
                f"not applicable: {v.reason if v else 'no such verb'}"
            rows.append((s, text))
        with formatter.section("Systems"):
            formatter.write_dl(rows)


def verb_groups() -> list[VerbGroup]:
    return [VerbGroup(verb, context_settings={"help_option_names": ["-h", "--help"]},
                      **{"help": text, **_every_system(verb)})
            for verb, text in VERBS.items()]


def _every_system(verb: str) -> dict[str, Any]:
    """For a verb of ``EVERY_SYSTEM_VERBS``: ``lgw VERB`` without SYSTEM runs it for every
    system in turn, with its default options; the exit code is the largest."""
    from lgw.tuning.system import EVERY_SYSTEM_VERBS

    if verb not in EVERY_SYSTEM_VERBS:
        return {}

    def every_system() -> int:
        from lgw.tuning.system import system_names

        ctx = click.get_current_context()
        if ctx.invoked_subcommand is not None:
            return 0
        rc = 0
        for name in system_names():
            rc = max(rc, ctx.invoke(make_command(get_system(name), verb)) or 0)
        return rc

    return {"invoke_without_command": True, "callback": every_system,
            "subcommand_metavar": "[SYSTEM] [OPTIONS]",
            "help": f"{VERBS[verb]} Without SYSTEM: every system in turn."}


def first_line(text: str | None) -> str:
    return _first_line(text)


def all_commands() -> list[tuple[str, str, click.Command]]:
    """(verb, system, command) of every applicable verb of every system."""
    from lgw.tuning.system import all_systems

    out = []
    for s in all_systems():
        for verb in VERBS:
            v = s.verbs.get(verb)
            if v is None or isinstance(v, NotApplicable):
                continue
            out.append((verb, s.name, make_command(s, verb)))
    return out
