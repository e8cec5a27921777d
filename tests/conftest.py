"""Hypothesis profiles: ``ci`` (derandomized, loaded when CI=true), ``dev`` (default) and
``thorough`` (randomized, many examples: ``pytest --hypothesis-profile=thorough``).

The session starts with ``lgw warmup``: every compiled kernel of every system is built (or
loaded, when the kernel cache already has it) before the first test, in parallel processes
(one per CPU, at most one per system), so that no test pays for numba and the cores work
together on the one cold build.  ``LGW_TEST_WARMUP=0`` skips it (a test then builds what it
needs on first use).  The cache is ``$LGW_CACHE_DIR`` (docs/sim.md: keep it between CI runs).
"""

import os
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile("ci", derandomize=True, max_examples=30, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow], print_blob=True)
settings.register_profile("dev", max_examples=30, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=1000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow], print_blob=True)
settings.load_profile("ci" if os.environ.get("CI", "").lower() == "true" else "dev")

# Progress lines go to stderr, which click's CliRunner mixes into ``result.output``: the tests
# read documents from stdout, and the progress tests set LGW_PROGRESS themselves.
os.environ.setdefault("LGW_PROGRESS", "never")
# The tests read lgw's output as a pipe or a CI log gets it (lgw.tuning.io.console: PIPE_WIDTH
# columns); pytest-xdist's workers inherit a COLUMNS of 80 that would wrap tables and paths.
os.environ.pop("COLUMNS", None)

# The systems' warm-up, in this many groups run side by side (the cold build of mars, with a
# kernel per law, is about as long as lunar's and eros's together).
WARMUP_GROUPS = (("mars",), ("lunar", "eros"))


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session: pytest.Session) -> None:
    """``lgw warmup`` for every system before the first test (module docstring).  Under
    pytest-xdist it runs once, in the controller, before the workers start (its own
    sessionstart is trylast): the workers then only load the kernels."""
    config = session.config
    if (os.environ.get("LGW_TEST_WARMUP", "1") == "0" or hasattr(config, "workerinput")
            or config.option.collectonly):
        return
    env = dict(os.environ, LGW_COMPILE_NOTICE="0", LGW_PROGRESS="never")
    groups = WARMUP_GROUPS if (os.cpu_count() or 1) > 1 else (sum(WARMUP_GROUPS, ()),)
    script = ("import sys\nfrom lgw.tuning.cli import main\n"
              "for s in sys.argv[1:]:\n"
              "    try:\n        main(['warmup', s])\n"
              "    except SystemExit as e:\n"
              "        if e.code:\n            raise\n")
    procs = [subprocess.Popen([sys.executable, "-c", script, *g], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
             for g in groups]
    failed = [(p.args[3:], out) for p in procs for out in [p.communicate()[0]] if p.returncode]
    if failed:
        pytest.exit(f"lgw warmup failed: {failed}", returncode=3)
