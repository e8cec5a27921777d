"""The ``lgw`` command line: ``lgw VERB SYSTEM [OPTIONS]``.

Every verb is written once (``lgw.tuning.commands``) over the registered systems
(``lgw.tuning.system``); each system's verb modules are imported only when their command is
built, and import nothing heavy at module level, so ``lgw --help`` and argument errors answer
at once, before SymPy, numba or cvxpy load.  Every invalid parameter becomes
one line ``error: ...`` and exit code 2, without a traceback and without writing anything.
A dependency missing from a partial install is ``error: ...`` with exit 69, and a bug of lgw
itself one line ``internal error: ...`` with exit 70 (sysexits.h EX_UNAVAILABLE, EX_SOFTWARE);
``LGW_DEBUG=1`` re-raises it with its traceback.
"""

from __future__ import annotations

import os
import sys
import traceback
from pathlib import Path

import click
from lgw.theory.errors import MissingDependency, ParameterError
from lgw.tuning.commands import verb_groups

EXIT_UNAVAILABLE = 69  # a declared dependency is not installed
EXIT_SOFTWARE = 70  # an internal error of lgw


class Root(click.Group):
    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        from lgw.tuning.system import VERBS, NotApplicable, all_systems

        systems = all_systems()
        rows = []
        for verb, text in VERBS.items():
            na = [s.name for s in systems if isinstance(s.verbs.get(verb), NotApplicable)]
            rows.append((verb, text + (f" [not for {', '.join(na)}]" if na else "")))
        with formatter.section("Commands (lgw VERB SYSTEM --help for each)"):
            formatter.write_dl(rows)
        with formatter.section("Systems"):
            formatter.write_dl([(s.name, f"seed {s.seed}, {s.summary}") for s in systems])
        with formatter.section("Exit codes"):
            formatter.write_dl([("0", "done (verify: every claim holds)"),
                                ("1", "verify: a claim is violated"),
                                ("2", "bad input: nothing computed, nothing written"),
                                ("3", "tune: no gain set meets the target"),
                                ("4", "verify: inconclusive (not enough informative cases)"),
                                ("69", "a declared dependency is missing"),
                                ("70", "internal error of lgw (a bug: please report it)"),
                                ("130", "interrupted (Ctrl-C)")])


@click.group(cls=Root, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="lgw")
def cli() -> None:
    """Landing-guidance workbench: derive, check, simulate and tune Lyapunov guidance laws."""


for _group in verb_groups():
    cli.add_command(_group)


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def main(args: list[str] | None = None) -> None:
    """Run ``lgw``: every invalid input (lgw's ParameterError and click's usage errors alike)
    is one line ``error: ...`` on stderr and exit code 2, with no traceback."""
    try:
        rc = cli(args=args, prog_name="lgw", standalone_mode=False)
    except ParameterError as e:
        click.echo(f"error: {_one_line(e)}", err=True)
        sys.exit(2)
    except (click.exceptions.Abort, KeyboardInterrupt):  # click turns Ctrl-C into Abort
        click.echo("interrupted", err=True)
        sys.exit(130)
    except click.exceptions.NoArgsIsHelpError as e:  # `lgw`, `lgw simulate`: show the help
        click.echo(e.format_message())
        sys.exit(2)
    except click.UsageError as e:  # includes BadParameter, NoSuchOption, MissingParameter
        hint = ""
        if e.ctx is not None:
            hint = f" (see {e.ctx.command_path} --help)"
        click.echo(f"error: {_one_line(e.format_message())}{hint}", err=True)
        sys.exit(2)
    except click.ClickException as e:
        click.echo(f"error: {_one_line(e.format_message())}", err=True)
        sys.exit(e.exit_code)
    except BrokenPipeError:  # `lgw ... | head`: the reader left; not an error of lgw
        sys.stderr.close()
        sys.exit(0)
    except MissingDependency as e:
        click.echo(f"error: {_one_line(e)}", err=True)
        sys.exit(EXIT_UNAVAILABLE)
    except Exception as e:  # a bug of lgw, not of the input: one line, the traceback on request
        if os.environ.get("LGW_DEBUG"):
            raise
        where = traceback.extract_tb(e.__traceback__)[-1]
        click.echo(f"internal error: {type(e).__name__}: {_one_line(e)} (at "
                   f"{Path(where.filename).name}:{where.lineno}; rerun with LGW_DEBUG=1 for the "
                   "traceback, and please report it)", err=True)
        sys.exit(EXIT_SOFTWARE)
    if isinstance(rc, int) and rc:
        sys.exit(rc)


if __name__ == "__main__":  # python -m lgw.tuning.cli: the same as the lgw executable
    main()
