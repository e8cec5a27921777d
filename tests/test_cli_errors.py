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


# --- outputs never destroy anything; inputs never hang; Ctrl-C is 130 --------------------------

import os  # noqa: E402
import signal  # noqa: E402
import stat  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

from tests.test_cli_conventions import assert_one_error, run_lgw  # noqa: E402


def _lgw_cmd() -> list[str]:
    return [sys.executable, "-c", "from lgw.tuning.cli import main; main()"]


@pytest.fixture
def char_device(tmp_path, monkeypatch):
    """A character device to write to: a null device node made in tmp_path (as root), else
    /dev/null itself with os.replace / os.rename guarded so that a regression cannot destroy
    it."""
    node = tmp_path / "null-device"
    try:
        os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
        return node
    except (PermissionError, OSError):
        real_replace, real_rename = os.replace, os.rename

        def guard(fn):
            def inner(src, dst, *a, **k):
                if os.path.realpath(dst) == "/dev/null":
                    raise AssertionError("lgw tried to replace /dev/null")
                return fn(src, dst, *a, **k)
            return inner

        monkeypatch.setattr(os, "replace", guard(real_replace))
        monkeypatch.setattr(os, "rename", guard(real_rename))
        return Path("/dev/null")


def _kind(p: Path) -> int:
    return stat.S_IFMT(os.stat(p).st_mode)


@pytest.mark.parametrize("args", [
    ["tune", "mars", "--tf", "90", "--thrust-max", "50000"],
    ["tune", "eros", "--ts", "10", "--thrust-max", "30"],
    ["bounds", "mars"],  # a folder --out
    ["optimal", "mars", "--n", "10"],
])
def test_out_that_is_a_device_or_fifo_is_refused_and_left_alone(args, char_device, tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for target in (char_device, fifo):
        before = os.stat(target)
        r = run_lgw([*args, "--out", str(target)])
        assert_one_error(r)
        assert "--out" in r.stderr and ("not a regular file" in r.stderr
                                        or "not a folder" in r.stderr), r.stderr
        after = os.stat(target)
        assert _kind(target) == stat.S_IFMT(before.st_mode) and after.st_ino == before.st_ino \
            and after.st_rdev == before.st_rdev
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["fifo"] + (["null-device"] if char_device.parent == tmp_path else []))


def test_out_that_is_an_input_file_is_refused_and_the_input_kept(tmp_path, monkeypatch):
    """tune mars --envelope env.csv --out env.csv; simulate mars --initial-states cases.csv
    --out . (and a folder holding the input); simulate eros the same; compare mars --tuned."""
    env = tmp_path / "env.csv"
    env.write_text("rx,ry,rz,vx,vy,vz,m\n-2000,1000,1500,100,-15,-75,1905\n")
    data = env.read_bytes()
    r = run_lgw(["tune", "mars", "--tf", "90", "--thrust-max", "50000", "--envelope", str(env),
                 "--out", str(env)])
    assert_one_error(r)
    assert "is the input file" in r.stderr and env.read_bytes() == data
    monkeypatch.chdir(tmp_path)
    cases = tmp_path / "cases.csv"
    cases.write_bytes(data)
    for out in (".", str(tmp_path)):
        r = run_lgw(["simulate", "mars", "--initial-states", "cases.csv", "--out", out])
        assert_one_error(r)
        assert cases.read_bytes() == data
    eros = tmp_path / "sub" / "e.csv"
    eros.parent.mkdir()
    eros.write_text("ex,ey,ez,vx,vy,vz\n5,-4,3,0.1,0.2,-0.1\n")
    r = run_lgw(["simulate", "eros", "--initial-states", str(eros), "--out", str(eros.parent)])
    assert_one_error(r)
    assert "holds the input file" in r.stderr and eros.exists()
    from lgw.tuning.mars.cmd_compare import probe_tuned_file

    tuned = probe_tuned_file(tmp_path / "sub")
    r = run_lgw(["compare", "mars", "--tuned", str(tuned), "--out", str(tuned.parent)])
    assert_one_error(r)
    assert tuned.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cases.csv", "env.csv", "sub"]


@pytest.mark.parametrize("kind", ["fifo", "/dev/zero", "folder"])
def test_gains_that_is_not_a_regular_file_is_refused_without_hanging(kind, tmp_path):
    """A FIFO nobody writes to would block a reader forever; /dev/zero never ends: refused at
    once (a real subprocess, with a timeout that fails the test instead of hanging it)."""
    if kind == "fifo":
        path = tmp_path / "gains.fifo"
        os.mkfifo(path)
    elif kind == "folder":
        path = tmp_path
    else:
        path = Path(kind)
    t0 = time.monotonic()
    p = subprocess.run([*_lgw_cmd(), "bounds", "mars", "--gains", str(path)],
                       capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    assert p.returncode == 2, p.stderr
    assert p.stderr.startswith("error: --gains") and p.stderr.count("\n") == 1, p.stderr
    assert ("FIFO" if kind == "fifo" else "device" if kind == "/dev/zero" else "folder") \
        in p.stderr
    print(f"\n--gains {kind}: refused in {time.monotonic() - t0:.1f} s: {p.stderr.strip()}")


def _sigint_ignored() -> str:
    """Whether this (test) process ignores SIGINT at the OS level (its children inherit it)."""
    try:
        line = next(x for x in Path("/proc/self/status").read_text().splitlines()
                    if x.startswith("SigIgn:"))
    except (OSError, StopIteration):
        return "SigIgn unknown"
    return f"test process SIGINT ignored: {bool(int(line.split()[1], 16) & (1 << 1))}"


@pytest.mark.parametrize("args", [
    ["report", "eros", "--no-sim"],  # pure Python (SymPy)
    pytest.param(["simulate", "mars", "--dispersion", "table2", "--cases", "200000"],
                 marks=pytest.mark.slow),  # numba
])
def test_ctrl_c_exits_130_and_writes_nothing(args, tmp_path):
    """SIGINT to a real ``lgw`` process once its work has started: exit 130 (never 1, which
    verify uses for "violated"), one line on stderr, nothing under --out, no temporary folder
    left beside it."""
    out = tmp_path / "out"
    env = {**os.environ, "LGW_PROGRESS": "always"}
    # as from a terminal: SIGINT at its default in the child (an ignored SIGINT is inherited
    # across exec, and a test worker's may have been left ignored by a library run earlier
    # in the same process; Python then never installs its Ctrl-C handler)
    proc = subprocess.Popen([*_lgw_cmd(), *args, "--out", str(out)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env,
                            stdin=subprocess.DEVNULL,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        line = ""
        deadline = time.monotonic() + 300
        while not line.startswith("lgw: ") and time.monotonic() < deadline:
            line = proc.stderr.readline()
            if not line and proc.poll() is not None:
                break
        assert line.startswith("lgw: "), f"no stage line: {line!r} (rc {proc.poll()})"
        # at once: the line is printed while its stage is current (a timer thread prints it
        # after a quiet spell, and not once the stage has ended), so the work is under way;
        # on a loaded machine that thread may print late, near the stage's end
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 130, (proc.returncode, err[-1000:], _sigint_ignored())
    assert "interrupted" in err and "Traceback" not in err, err[-1000:]
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == []


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_plot_location_is_checked_before_the_work(system, char_device, tmp_path):
    """--plot naming a device, or a folder holding other files, is refused before any work
    (nothing flown, nothing written)."""
    busy = tmp_path / "busy"
    busy.mkdir()
    (busy / "mine.txt").write_text("not lgw's")
    for target in (char_device, busy):
        r = run_lgw(["simulate", system, "--plot", str(target)])
        assert_one_error(r)
        assert "--plot" in r.stderr, r.stderr
    assert _kind(char_device) == stat.S_IFCHR
    assert [p.name for p in busy.iterdir()] == ["mine.txt"]
