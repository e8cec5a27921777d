"""Claims with verdicts: the paper's statement, the derived one, the steps, and the evidence.

Verdicts, strongest first:
  proved     every step is a SymPy identity that reduced to zero, a SymPy assumption query that
             returned True, a SymPy integral, or an elementary lemma whose hypotheses were
             themselves checked by SymPy (each step says which);
  checked    a numerical search found no counterexample (method, domain and sample count given);
  refuted    a counterexample, given as numbers that reproduce it;
  unproven   none of the above.  A SymPy query that returns None is unproven, never a pass.
A claim cannot be ``proved`` unless all of its steps are (enforced in ``Claim.__post_init__``).
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

import sympy as sp

VERDICTS = ("proved", "checked", "refuted", "unproven")


@dataclass
class Step:
    statement: str  # what this step asserts (plain text / LaTeX-ish)
    method: str  # how it was established
    status: str  # one of VERDICTS
    detail: str = ""  # evidence: residual, counterexample, sample counts

    def __post_init__(self) -> None:
        if self.status not in VERDICTS:
            raise ValueError(f"bad step status {self.status!r}")


@dataclass
class Claim:
    id: str
    equations: str  # e.g. "(18)", "(26), (29)"
    title: str
    paper: str  # the statement as the paper makes it
    derived: str  # what the workbench derives
    steps: list[Step]
    verdict: str
    evidence: str
    law: str | None = None  # "printed" / "corrected" / None (law-independent)
    counterexample: dict[str, Any] | None = None
    numbers: dict[str, Any] = field(default_factory=dict)
    # Steps of the paper's own argument that fail where the workbench proves the statement by
    # another route: reported, but not part of the proof.
    remarks: list[Step] = field(default_factory=list)

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise ValueError(f"bad verdict {self.verdict!r}")
        if self.verdict == "proved" and any(s.status != "proved" for s in self.steps):
            raise ValueError(f"claim {self.id}: 'proved' needs every step proved")
        if self.verdict == "proved" and not self.steps:
            raise ValueError(f"claim {self.id}: 'proved' needs at least one step")
        if self.verdict == "refuted" and not self.counterexample:
            raise ValueError(f"claim {self.id}: 'refuted' needs a counterexample")

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def combine(steps: Iterable[Step]) -> str:
    """Verdict of a conclusion that needs every step: the weakest step decides."""
    statuses = [s.status for s in steps]
    if "refuted" in statuses:
        return "refuted"
    for v in ("unproven", "checked"):
        if v in statuses:
            return v
    return "proved" if statuses else "unproven"


# --- Provers -----------------------------------------------------------------------------

def _rational_point(symbols: Iterable[sp.Symbol], rng: random.Random,
                    ranges: Mapping[sp.Symbol, tuple[float, float]]) -> dict:
    pt = {}
    for s in symbols:
        lo, hi = ranges.get(s, (0.1, 3.0) if s.is_positive else (-3.0, 3.0))
        pt[s] = sp.Rational(round(rng.uniform(lo, hi), 3)).limit_denominator(1000)
        if pt[s] == 0:
            pt[s] = sp.Rational(1, 7)
    return pt


def prove_zero(expr: sp.Expr, statement: str, *, samples: int = 8, seed: int = 0,
               ranges: Mapping[sp.Symbol, tuple[float, float]] | None = None) -> Step:
    """Step asserting expr == 0 identically.

    proved if SymPy simplifies it to 0; refuted if it is nonzero at a rational point (evaluated
    to 30 digits, reported); otherwise unproven (a numerically-zero expression SymPy could not
    simplify is not a proof).
    """
    ranges = ranges or {}
    simp = sp.simplify(expr)
    if simp == 0:
        return Step(statement, "SymPy simplify: residual reduces to 0", "proved", "residual = 0")
    rng = random.Random(seed)
    syms = sorted(expr.free_symbols, key=lambda s: s.name)
    for _ in range(samples):
        pt = _rational_point(syms, rng, ranges)
        val = sp.N(expr.subs(pt), 30)
        if val.is_number and val.is_real and abs(val) > 1e-20:
            ce = {str(k): str(v) for k, v in pt.items()}
            return Step(statement, "SymPy: residual evaluated at a rational point", "refuted",
                        f"residual = {sp.N(val, 12)} at {ce}; residual = {sp.sstr(simp)}")
    return Step(statement, "SymPy simplify did not reach 0; zero at sampled points",
                "unproven", f"residual after simplify: {sp.sstr(simp)}")


def prove_nonneg(expr: sp.Expr, statement: str) -> Step:
    """Step asserting expr >= 0 under the symbols' assumptions, by SymPy's assumption system."""
    res = sp.simplify(expr).is_nonnegative
    if res is True:
        return Step(statement, "SymPy assumptions: is_nonnegative is True", "proved")
    if res is False:
        return Step(statement, "SymPy assumptions: is_nonnegative is False", "refuted",
                    f"{sp.sstr(expr)} is negative under the stated assumptions")
    return Step(statement, "SymPy assumptions returned None", "unproven", sp.sstr(expr))


def numeric_search(check: Callable[[random.Random], tuple[bool, dict]], statement: str,
                   method: str, domain: str, samples: int, seed: int = 0) -> Step:
    """Step checked by random search: ``check(rng)`` returns (holds, case).  The first failing
    case is the counterexample (reproducible from the seed)."""
    rng = random.Random(seed)
    for i in range(samples):
        ok, case = check(rng)
        if not ok:
            return Step(statement, method, "refuted",
                        f"counterexample at sample {i} (seed {seed}): {case}")
    return Step(statement, method, "checked",
                f"no counterexample in {samples} samples (seed {seed}) over {domain}")
