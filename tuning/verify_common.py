"""What every ``lgw verify SYSTEM`` run shares: validation of the run options.

Each system's frozen ``VerifyOptions`` calls ``check_run_options`` from its ``__post_init__``
(mars, lunar and eros alike), so a misspelled profile, a non-positive ``--min-cases`` or a bad
``--scale`` gets the same named error, exit 2, everywhere.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection, Iterable, Mapping
from typing import Any

from lgw.theory.errors import ParameterError


def check_run_options(opts: Any, profiles: Mapping[str, Any], claims: Collection[str]) -> None:
    """Validate ``opts.profile`` (a key of ``profiles``), ``opts.min_cases`` (>= 1),
    ``opts.examples`` (None or >= 1) and ``opts.scale`` (claim name -> finite factor > 0,
    names from ``claims``).  With ``opts.database`` set, ``opts.seed`` becomes None: Hypothesis
    uses no example database in a seeded (derandomised) run, so a database makes the run
    random (saved failures are replayed first, new ones saved)."""
    if opts.database is not None:
        object.__setattr__(opts, "seed", None)
    if opts.profile not in profiles:
        raise ParameterError("profile", opts.profile, f"one of {', '.join(profiles)}")
    if opts.min_cases < 1:
        raise ParameterError("min-cases", opts.min_cases, "must be >= 1")
    if opts.examples is not None and opts.examples < 1:
        raise ParameterError("examples", opts.examples, "must be >= 1")
    for k, v in opts.scale.items():
        if k not in claims:
            raise ParameterError("scale", k, f"a claim name: {', '.join(claims)}")
        if isinstance(v, bool) or not (isinstance(v, int | float) and math.isfinite(v)
                                       and v > 0):
            raise ParameterError("scale", v, "a finite factor > 0")


def print_claim_details(out: Any, results: Iterable[Any],
                        extra: Callable[[Any], Iterable[str]] | None = None) -> None:
    """Under a verify table, per claim: its exclusions with their reasons, why it is not
    ``holds``, ``extra(result)`` lines (mars: the search), the shrunk witness and the
    reproduction command, printed literally (``markup=False``: reasons and witnesses may hold
    brackets that rich would read as markup)."""
    for r in results:
        lines = [f"{r.claim}: {n} excluded: {why}" for why, n in r.excluded.items()]
        if r.why:
            lines.append(f"{r.claim}: {r.verdict}: {r.why}")
        if extra is not None:
            lines.extend(extra(r))
        if r.witness:
            lines.append(f"{r.claim}: shrunk witness {r.witness}")
        if r.reproduction:
            lines.append(f"{r.claim}: reproduce with\n{r.reproduction}")
        for line in lines:
            out.print(line, markup=False)
