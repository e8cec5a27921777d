"""CLI conventions: one error style, click.Choice everywhere, defaults and units in
the help, one name per concept, tables that never truncate in a pipe.

``run_lgw`` runs ``lgw`` in-process through ``lgw.tuning.cli.main`` (its error handling, exit
codes and stderr), which the fuzz tests and ``tests/mars/test_inputs.py`` share.
"""

from __future__ import annotations

import importlib
import re
import subprocess
import sys
from dataclasses import dataclass

import click
import numpy as np
import pytest
from click.testing import CliRunner
from lgw.tuning.cli import cli, main
from lgw.tuning.commands import all_commands
from lgw.tuning.options import Choice


@dataclass
class Run:
    code: int
    stdout: str
    stderr: str
    exception: BaseException | None


@click.command(context_settings={"ignore_unknown_options": True, "allow_extra_args": True,
                                 "help_option_names": []})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def _shell(args: tuple[str, ...]) -> None:
    main(list(args))


def run_lgw(args: list[str]) -> Run:
    """``lgw ARGS`` in-process: exit code, stdout, stderr, and any exception that escaped
    ``main`` (which would have been a traceback)."""
    res = CliRunner().invoke(_shell, args, catch_exceptions=True)
    exc = res.exception if not isinstance(res.exception, SystemExit) else None
    return Run(res.exit_code, res.stdout, res.stderr, exc)


def assert_one_error(r: Run) -> None:
    """Exit 2, exactly one line on stderr and it starts with ``error:``, no traceback."""
    assert r.exception is None, f"escaped main: {r.exception!r}"
    assert r.code == 2, (r.code, r.stderr)
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert "Traceback" not in r.stderr and "Usage:" not in r.stderr


COMMANDS = all_commands()
CHOICE_OPTIONS = [(v, s, p) for v, s, c in COMMANDS for p in c.params
                  if isinstance(p, click.Option) and isinstance(p.type, click.Choice)]
# commands other engineers own: their options are checked by the lead after the merge
OWNED_ELSEWHERE = {"report"}


def test_there_are_choice_options_everywhere_expected():
    names = {(v, p.opts[0]) for v, _, p in CHOICE_OPTIONS}
    for need in [("simulate", "--law"), ("simulate", "--disturbance"), ("simulate", "--limit"),
                 ("simulate", "--drag"), ("simulate", "--method"), ("simulate", "--dispersion"),
                 ("simulate", "--guidance-drag"), ("tune", "--limit"), ("tune", "--bound"),
                 ("tune", "--objective"), ("optimal", "--limit"), ("optimal", "--drag"),
                 ("compare", "--drag")]:
        assert need in names, need


@pytest.mark.parametrize("verb, system, opt", [(v, s, p.opts[0]) for v, s, p in CHOICE_OPTIONS],
                         ids=lambda x: str(x))
def test_every_choice_rejects_a_wrong_value_in_lgw_style(tmp_path, verb, system, opt):
    from lgw.tuning.spec import option_fields, probe_value
    from lgw.tuning.system import get_system

    out = tmp_path / "out"
    args = [verb, system, opt, "no-such-value"]
    cmd = next(c for v, s, c in COMMANDS if (v, s) == (verb, system))
    # the command's other required options (tune mars: --tf, --thrust-max; tune eros: --ts,
    # --thrust-max) at valid values, so that the wrong choice is the one error
    required = {p.opts[0] for p in cmd.params if isinstance(p, click.Option) and p.required}
    for f, o in option_fields(get_system(system).verbs[verb].load().Options):
        if o.flag in required and o.flag not in (opt, "--out"):
            args += [o.flag, str(probe_value(f, o))]
    takes_out = any("--out" in p.opts for p in cmd.params)
    args += ["--out", str(out)] if takes_out else []
    r = run_lgw(args)
    assert_one_error(r)
    assert opt in r.stderr and "no-such-value" in r.stderr
    assert not out.exists()


def test_choices_are_lgw_choices_in_owned_commands():
    for verb, _, p in CHOICE_OPTIONS:
        if verb not in OWNED_ELSEWHERE:
            assert isinstance(p.type, Choice), (verb, p.opts)


@pytest.mark.parametrize("verb, system, cmd", [c for c in COMMANDS if c[0] not in OWNED_ELSEWHERE],
                         ids=lambda x: str(x) if isinstance(x, str) else "")
def test_every_option_has_help_and_defaults_are_shown(verb, system, cmd):
    for p in cmd.params:
        if not isinstance(p, click.Option) or p.hidden or p.is_flag:
            continue
        assert p.help, (verb, p.opts)
        if p.default is not None and not p.required:
            assert p.show_default or "default" in p.help, (verb, p.opts)


def test_numeric_options_say_their_unit_or_range():
    from lgw.tuning.options import Integer, Number

    for verb, _, cmd in COMMANDS:
        if verb in OWNED_ELSEWHERE:
            continue
        for p in cmd.params:
            if isinstance(p, click.Option) and not p.hidden:
                plain = click.types.FloatParamType | click.types.IntParamType
                assert not isinstance(p.type, plain), (verb, p.opts, "use Number / Integer")
                if isinstance(p.type, Number | Integer):
                    assert p.type.valid.startswith("must be")


def test_one_name_for_the_disturbance_amplitude():
    mars = {v: c for v, s, c in COMMANDS if s == "mars"}
    sim = {o for p in mars["simulate"].params for o in p.opts}
    cmp_cmd = mars["compare"]
    visible = {o for p in cmp_cmd.params if not getattr(p, "hidden", False) for o in p.opts}
    assert "--dist-amplitude" in sim and "--dist-amplitude" in visible
    assert "--amplitude" not in visible  # kept only as a hidden deprecated alias
    r = run_lgw(["compare", "mars", "--amplitude", "nan"])
    assert_one_error(r)


@pytest.mark.parametrize("args", [["simulate", "mars", "--bogus"], ["simulate", "mars", "--dt"],
                                  ["tune", "mars"], ["bounds", "nowhere"], ["nope"],
                                  ["simulate", "mars", "--cases", "x"]])
def test_click_usage_errors_print_as_lgw_errors(args):
    assert_one_error(run_lgw(args))


@pytest.mark.parametrize("args", [[], ["simulate"]])
def test_no_arguments_show_the_help(args):
    r = run_lgw(args)
    assert r.code == 2 and r.exception is None and "Usage: lgw" in r.stdout and not r.stderr


def test_help_exits_0():
    r = run_lgw(["simulate", "mars", "--help"])
    assert r.code == 0 and "--dist-amplitude" in r.stdout and "[default: 20" in r.stdout


def test_exit_2_in_a_real_process():
    p = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                        "simulate", "mars", "--law", "nope"], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 2 and p.stderr.startswith("error: --law")
    assert len(p.stderr.strip().splitlines()) == 1


def test_result_tables_never_cut_a_header_or_number_at_80_columns():
    """A table printed by lgw.tuning.tables.result_table through lgw.tuning.io.console() to a
    pipe of 80 columns keeps every header and every number whole: folded, or stacked."""
    code = ("from lgw.tuning.io import console\nfrom lgw.tuning.tables import result_table\n"
            "cols = [f'a_long_column_header_{i}' for i in range(12)]\n"
            "rows = [[f'{1234.5678 * (i + 1):.7g}/{i}' for i in range(12)]]\n"
            "result_table(console(), 'wide', cols, rows)\n"
            "result_table(console(), 'narrow', ['q', 'x'], [['peak', '5.4/7.25']])\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                       env={"PATH": "/usr/bin:/bin", "COLUMNS": "80"})
    assert p.returncode == 0, p.stderr
    assert max(len(line) for line in p.stdout.splitlines()) <= 80
    for i in range(12):
        assert f"a_long_column_header_{i}" in p.stdout
        assert f"{1234.5678 * (i + 1):.7g}/{i}" in p.stdout
    assert "5.4/7.25" in p.stdout and "\u2026" not in p.stdout


def test_bounds_table_untruncated_in_a_pipe():
    p = subprocess.run([sys.executable, "-c", "from lgw.tuning.cli import main; main()",
                        "bounds", "mars"], capture_output=True, text=True, timeout=120,
                       env={"PATH": "/usr/bin:/bin", "COLUMNS": "40"})
    assert p.returncode == 0, p.stderr
    for label in ("landing bound under disturbance (40*)+(45*)", "[T1_practical_exact]",
                  "time to (39), exact"):
        assert label in p.stdout
    assert "…" not in p.stdout


def test_verify_headers_untruncated_in_a_pipe():
    """In-process (CliRunner's stdout is not a terminal, like a pipe or a CI log); the claims
    that do not apply to a tuned file without [disturbance] (nothing flown), so the table is the
    real one at once."""
    from pathlib import Path

    tuned = str(Path(__file__).parents[1] / "tuning" / "mars" / "data" / "tuned_tf90_50kN.toml")
    r = run_lgw(["verify", "mars", "--gains", tuned, "--claim", "s2-39-40"])
    assert r.exception is None and r.code == 0, r.stderr
    header = next(ln for ln in r.stdout.splitlines() if "claim" in ln and "verdict" in ln)
    for col in ("claim", "eq.", "informative", "excluded", "total", "worst margin",
                "verdict"):
        assert col in header, header
    assert "…" not in r.stdout


def test_cli_group_builds():
    assert isinstance(cli, click.Group) and re.match(r"\d", importlib.import_module(
        "lgw").__version__)


def _fake_result(n: int):
    """A BatchResult of n cases without flying (numpy only): case i lands at t = i s except
    cases 7 (non-finite) and 40 (out of propellant)."""
    from lgw.sim.mars.batch import ARRAY_FIELDS, VECTOR_FIELDS, BatchResult

    vec = set(VECTOR_FIELDS)
    kw = {}
    for k in ARRAY_FIELDS:
        shape = (n, 3) if k in vec else (n, 7) if k == "y_end" else (n,)
        kw[k] = np.zeros(shape, bool if k in ("landed", "ground_contact", "nonfinite",
                                               "fuel_exhausted", "step_limit") else float)
    kw["steps"] = np.ones(n, np.int64)
    kw["landed"][:] = True
    kw["landing_time"] = np.arange(n, dtype=float)
    for i, flag in ((7, "nonfinite"), (40, "fuel_exhausted")):
        kw["landed"][i] = False
        kw[flag][i] = True
        kw["landing_time"][i] = np.nan
    return BatchResult(eps=0.05, dt=0.05, r0=np.zeros((n, 3)), v0=np.zeros((n, 3)),
                       m0=np.full(n, 1905.0), info={}, **kw)


def test_per_case_table_shows_flagged_then_worst_and_counts_the_hidden():
    from lgw.tuning.mars.cmd_simulate import (
        PER_CASE_ROWS,
        _print_cases,
        case_flags,
        select_cases,
        shown_cases,
    )
    from rich.console import Console

    res = _fake_result(20_000)
    idx = shown_cases(res)
    assert len(idx) == PER_CASE_ROWS
    assert idx[:2].tolist() == [7, 40]  # flagged first
    assert idx[2:5].tolist() == [19_999, 19_998, 19_997]  # then the latest landings
    recs = select_cases(res, idx)
    assert [r["case"] for r in recs[:3]] == [7, 40, 19_999]
    con = Console(width=400, record=True)
    _print_cases(recs, len(res), int(case_flags(res).sum()), con)
    text = con.export_text()
    assert f"{20_000 - PER_CASE_ROWS} more cases not shown" in text
    assert f"{PER_CASE_ROWS} of 20000 shown" in text and "2 flagged" in text
    assert "NONFINITE" in text and "DRY" in text
