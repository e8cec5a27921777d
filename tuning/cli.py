"""The ``lgw`` command line: ``lgw VERB SYSTEM [OPTIONS]``.

Each system package ``lgw.tuning.<system>`` registers the verbs it implements in its
``COMMANDS`` mapping (verb -> one-line help) and defines each as a click command named after the
system in its module ``cmd_<verb>``.  This shell reads the mappings without importing the
command modules (so ``lgw --help`` and argument errors answer at once, before SymPy, numba or
cvxpy load) and imports one module only when its command runs.  Every invalid parameter becomes
one line ``error: ...`` and exit code 2, without a traceback and without writing anything.
A dependency missing from a partial install is ``error: ...`` with exit 69, and a bug of lgw
itself one line ``internal error: ...`` with exit 70 (sysexits.h EX_UNAVAILABLE, EX_SOFTWARE);
``LGW_DEBUG=1`` re-raises it with its traceback.
"""

from __future__ import annotations

import importlib
import os
import sys
import traceback
from pathlib import Path

import click
from lgw import SYSTEMS
from lgw.theory.errors import MissingDependency, ParameterError

EXIT_UNAVAILABLE = 69  # a declared dependency is not installed
EXIT_SOFTWARE = 70  # an internal error of lgw

VERBS = {
    "bounds": "Settling-time, neighbourhood and landing-time bounds for a gain set.",
    "simulate": "Fly the closed loop: one case, a Monte Carlo campaign or a states file.",
    "verify": "Property campaign: observed behaviour against every proven bound.",
    "tune": "Design gains for a target time and an actuator limit, with a certificate.",
    "report": "Derive and judge every claim of the paper; write the report.",
    "optimal": "Offline fuel-optimal baseline (lossless convexification).",
    "compare": "The paper's comparison of laws on its own scenario.",
}


def system_commands(system: str) -> dict[str, str]:
    """verb -> help of the verbs ``system`` implements (its package's ``COMMANDS``)."""
    try:
        mod = importlib.import_module(f"lgw.tuning.{system}")
    except ModuleNotFoundError:
        return {}
    return dict(getattr(mod, "COMMANDS", {}))


def systems_for(verb: str) -> list[str]:
    return [s for s in SYSTEMS if verb in system_commands(s)]


class VerbGroup(click.Group):
    """``lgw VERB``: one subcommand per system that implements VERB, imported on use."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return systems_for(self.name)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        if name not in systems_for(self.name):
            return None
        mod = importlib.import_module(f"lgw.tuning.{name}.cmd_{self.name}")
        return mod.command

    def resolve_command(self, ctx: click.Context, args: list[str]):
        name = args[0] if args else ""
        if name.startswith("-") or name in systems_for(self.name):
            return super().resolve_command(ctx, args)
        valid = systems_for(self.name)
        other = [s for s in SYSTEMS if s not in valid]
        hint = f"{', '.join(other)}: not implemented for {self.name}" if other and \
            name in other else ""
        raise ParameterError("SYSTEM", name, f"lgw {self.name} takes one of "
                             f"{', '.join(valid)}", hint)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = [(s, system_commands(s)[self.name]) for s in self.list_commands(ctx)]
        if rows:
            with formatter.section("Systems"):
                formatter.write_dl(rows)


class Root(click.Group):
    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        rows = []
        for verb, text in VERBS.items():
            systems = systems_for(verb)
            if systems:
                rows.append((verb, f"{text} [{', '.join(systems)}]"))
        with formatter.section("Commands (lgw VERB SYSTEM --help for each)"):
            formatter.write_dl(rows)
        with formatter.section("Systems"):
            formatter.write_dl([("mars", "seed 000, Mars powered descent (fixed-time MSS)"),
                                ("lunar", "seed 001, lunar descent (adaptive backstepping)"),
                                ("eros", "seed 002, 433 Eros landing (fuzzy FTSMC)")])


@click.group(cls=Root, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="lgw")
def cli() -> None:
    """Landing-guidance workbench: derive, check, simulate and tune Lyapunov guidance laws."""


for _verb, _help in VERBS.items():
    cli.add_command(VerbGroup(_verb, help=_help,
                              context_settings={"help_option_names": ["-h", "--help"]}))


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
    except click.exceptions.Abort:
        click.echo("aborted", err=True)
        sys.exit(1)
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
    except KeyboardInterrupt:
        click.echo("interrupted", err=True)
        sys.exit(130)
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
