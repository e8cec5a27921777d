"""Options and loaders shared by the subcommands."""

from __future__ import annotations

from pathlib import Path

import click


def gains_option(f):
    return click.option("--gains", "gains_path", type=click.Path(dir_okay=False, path_type=Path),
                        default=None, help="gains TOML file (default: the built-in gain set)")(f)
