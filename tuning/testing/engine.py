"""The Hypothesis engine behind ``lgw verify lunar`` and ``lgw verify eros`` (system-neutral).

``run_property(strategy, check, ...)`` lets Hypothesis draw examples (batches of initial states)
and calls ``check(example)``, which flies them, records every case it judged in the caller's
campaign, and returns a failing record (a dict: the case, observed, bound) or None.  A failing
example is shrunk by Hypothesis (to fewer and simpler states); the record of the last failing
call, which is Hypothesis' final replay of the minimal example, is returned.  ``--seed`` makes
the run derandomised (the same examples every time); ``--database DIR`` keeps Hypothesis'
example database there, so an earlier failure is replayed first on the next run.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from lgw.theory.errors import ParameterError


def hypothesis_or_error():
    """The hypothesis module, or the named error saying how to install it."""
    try:
        import hypothesis
    except ImportError:
        raise ParameterError("hypothesis", "not installed",
                             'needed by lgw verify: pip install "lgw[verify]"') from None
    return hypothesis


def run_property(strategy: Any, check: Callable[[Any], dict[str, Any] | None], *,
                 examples: int, seed: int | None, database: Path | None,
                 key: str) -> dict[str, Any] | None:
    """Run ``check`` on ``examples`` Hypothesis examples of ``strategy``; see the module
    docstring.  ``key`` names the example database's sub-folder (system/claim group), so
    different checks never replay each other's examples."""
    hyp = hypothesis_or_error()
    from hypothesis import HealthCheck, given, settings
    from hypothesis.database import DirectoryBasedExampleDatabase

    failing: dict[str, Any] = {}
    db = DirectoryBasedExampleDatabase(str(Path(database) / key)) if database is not None \
        else None

    @settings(max_examples=examples, deadline=None, database=db, derandomize=False,
              suppress_health_check=list(HealthCheck), print_blob=False)
    @given(example=strategy)
    def prop(example: Any) -> None:
        rec = check(example)
        if rec is not None:
            failing.clear()
            failing.update(rec)
            raise AssertionError(f"{rec.get('claim', 'a claim')} violated")

    if seed is not None:
        prop = hyp.seed(seed)(prop)
    try:
        prop()
    except AssertionError:
        return dict(failing) if failing else None
    return None
