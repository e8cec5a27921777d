"""The ``lgw`` command line.

Each subcommand lives in a module ``tuning/cmd_<name>.py`` that defines ``command`` (a click
command); this file gathers them and turns every invalid parameter into one clear message and
exit code 2, without a traceback and without writing anything.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys

import click

import tuning
from theory.errors import ParameterError


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="lgw")
def cli() -> None:
    """Landing-guidance workbench: derive, check, simulate and tune Lyapunov guidance laws."""


for _mod in sorted(m.name for m in pkgutil.iter_modules(tuning.__path__)):
    if _mod.startswith("cmd_"):
        cli.add_command(importlib.import_module(f"tuning.{_mod}").command)


def main() -> None:
    try:
        cli(standalone_mode=False)
    except ParameterError as e:
        click.echo(f"error: {e}", err=True)
        sys.exit(2)
    except click.exceptions.Abort:
        click.echo("aborted", err=True)
        sys.exit(1)
    except click.ClickException as e:
        e.show()
        sys.exit(2 if isinstance(e, click.UsageError | click.BadParameter) else e.exit_code)
    except SystemExit:
        raise
