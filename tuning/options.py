"""Options and loaders shared by the subcommands."""

from __future__ import annotations

from pathlib import Path

import click

from theory.gains import Gains, default_gains, load_gains

PLANTS = ("mars",)


def plant_argument(f):
    return click.argument("plant", type=click.Choice(PLANTS))(f)


def gains_option(f):
    return click.option("--gains", "gains_path", type=click.Path(dir_okay=False, path_type=Path),
                        default=None, help="gains TOML file (default: the built-in gain set)")(f)


def resolve_gains(path: Path | None) -> Gains:
    return default_gains() if path is None else load_gains(path)
