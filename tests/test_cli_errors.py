"""What ``lgw`` does when something other than the input is wrong: a dependency missing from a
partial install (exit 69) or a bug of lgw itself (exit 70); one line on stderr, no traceback."""

from __future__ import annotations

import click
import pytest
from lgw.tuning import cli as cli_mod


def _run(monkeypatch, capsys, exc: BaseException, debug: bool = False):
    @click.command()
    def boom() -> None:
        raise exc

    monkeypatch.setattr(cli_mod, "cli", boom)
    if debug:
        monkeypatch.setenv("LGW_DEBUG", "1")
    else:
        monkeypatch.delenv("LGW_DEBUG", raising=False)
    with pytest.raises(SystemExit) as e:
        cli_mod.main([])
    return e.value.code, capsys.readouterr().err


def test_internal_error_is_one_line_exit_70(monkeypatch, capsys):
    code, err = _run(monkeypatch, capsys, ZeroDivisionError("float division by zero"))
    assert code == cli_mod.EXIT_SOFTWARE == 70
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("internal error: ZeroDivisionError: float division by zero")
    assert "test_cli_errors.py:" in err  # where it happened, for the bug report


def test_lgw_debug_reraises(monkeypatch, capsys):
    with pytest.raises(ZeroDivisionError):
        _run(monkeypatch, capsys, ZeroDivisionError("x"), debug=True)


def test_missing_slycot_is_named(monkeypatch, capsys):
    """The lunar bounds need python-control's linfnorm, which needs slycot: an old install
    without it gets the package's name and the install command, exit 69, nothing written."""
    import control

    def no_slycot(*a, **k):
        raise control.ControlSlycot("Can't find slycot module ab13dd")

    monkeypatch.setattr(control, "linfnorm", no_slycot)
    monkeypatch.delenv("LGW_DEBUG", raising=False)
    with pytest.raises(SystemExit) as e:
        cli_mod.main(["bounds", "lunar"])
    err = capsys.readouterr().err
    assert e.value.code == cli_mod.EXIT_UNAVAILABLE == 69
    assert err.count("\n") == 1 and "'slycot' is missing" in err and "pip install slycot" in err
