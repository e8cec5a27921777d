"""The Hypothesis engine behind every ``lgw verify SYSTEM`` (``lgw.tuning.verifying``).

``run_property(strategy, check, ...)`` lets Hypothesis draw examples (batches of initial states)
and calls ``check(example)``, which flies them, records every case it judged in the caller's
campaign, and returns a failing record (a dict: the case, observed, bound) or None.  A failing
example is shrunk by Hypothesis (to fewer and simpler states); the record of the last failing
call, which is Hypothesis' final replay of the minimal example, is returned.  ``--seed`` makes
the run derandomised (the same examples every time); ``--database DIR`` keeps Hypothesis'
example database there, so an earlier failure is replayed first on the next run.

Shrinking is capped: after ``shrink_budget`` checks past the first failure, a candidate is
passed unflown unless it is the last failing example itself (so Hypothesis' final replay still
fails and reproduces it), which keeps a violated run to seconds of shrinking instead of
Hypothesis' own limit of minutes; the witness is then the smallest failure found within the
budget.
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
                 key: str, shrink_budget: int = 30) -> dict[str, Any] | None:
    """Run ``check`` on ``examples`` Hypothesis examples of ``strategy``; see the module
    docstring.  ``key`` names the example database's sub-folder (system/claim group), so
    different checks never replay each other's examples."""
    hyp = hypothesis_or_error()
    from hypothesis import HealthCheck, given, settings
    from hypothesis.database import DirectoryBasedExampleDatabase

    failing: dict[str, Any] = {}
    state: dict[str, Any] = {"after": -1, "last": None}
    db = DirectoryBasedExampleDatabase(str(Path(database) / key)) if database is not None \
        else None

    @settings(max_examples=examples, deadline=None, database=db, derandomize=False,
              suppress_health_check=list(HealthCheck), print_blob=False)
    @given(example=strategy)
    def prop(example: Any) -> None:
        if state["after"] >= shrink_budget:  # budget spent: only the last failure fails
            failed = _same(example, state["last"])
        else:
            if state["after"] >= 0:
                state["after"] += 1
            rec = check(example)
            failed = rec is not None
            if failed:
                failing.clear()
                failing.update(rec)
                state["after"] = max(state["after"], 0)
                state["last"] = _copy(example)
        if failed:  # one raise site: Hypothesis sees one distinct failure
            raise AssertionError(f"{failing.get('claim', 'a claim')} violated")

    if seed is not None:
        prop = hyp.seed(seed)(prop)
    try:
        prop()
    except (AssertionError, BaseExceptionGroup):
        if not failing:
            raise
        return dict(failing)
    return None


def _copy(x: Any) -> Any:
    import numpy as np

    if isinstance(x, tuple | list):
        return type(x)(_copy(v) for v in x)
    return np.array(x, copy=True) if isinstance(x, np.ndarray) else x


def _same(a: Any, b: Any) -> bool:
    """Value equality of examples (tuples of arrays and numbers)."""
    import numpy as np

    if isinstance(a, tuple | list) and isinstance(b, tuple | list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return bool(np.shape(a) == np.shape(b) and np.array_equal(a, b, equal_nan=True))
    return a == b
