"""Ctrl-C during a z3 check interrupts the run: z3's own SIGINT handler cancels the check and
answers "unknown", which alone would let the run go on with an unproven step in place of a
proof, and exit 0."""

from __future__ import annotations

import os
import signal
import threading
import time

import pytest
import z3
from lgw.theory.provers import z3_check


def _hard_solver():
    x, y = z3.Ints("x y")
    s = z3.Solver()
    s.set("timeout", 20_000)
    # factor a 64-bit semiprime by nonlinear integer arithmetic: seconds of work for z3
    s.add(x * y == 18446744030759878681, x > 1, y > 1, x < y)
    return s


@pytest.mark.skipif(os.name != "posix", reason="SIGINT to the own process")
def test_sigint_during_a_check_raises_keyboard_interrupt():
    s = _hard_solver()
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            z3_check(s)
    finally:
        timer.cancel()
    assert time.monotonic() - t0 < 20.0  # not the timeout: the interrupt ended it
