"""Verdicts computed from evidence: evidence kinds, steps, claims and how verdicts combine.

A step never carries a status of its own: its status is computed from the evidence object a
prover made, and a claim's verdict is computed from its steps.  There is no way to pass a bare
status string (``Step`` and ``Claim`` have no such field), so a verdict is only as strong as
the evidence behind it.  The kinds, and the status each can give:

  Identity    a SymPy residual (kept): ``proved`` when it is exactly 0; ``refuted`` when it is
              nonzero at an exact (rational) point, kept as the witness; else ``unproven``.
  Inequality  ``expr >= 0`` (or ``> 0``) decided by a named prover (z3 on a polynomial form,
              an Arb interval enclosure over a stated box, a sum-of-squares certificate, or
              SymPy's assumption system), with the certificate kept: ``proved`` / ``refuted``
              (with a witness) / ``unproven`` as the prover answered (a SymPy ``None`` is
              ``unproven``).
  Search      a falsification run over a stated domain with a stated budget: ``refuted`` only
              with a witness whose negative margin was re-checked by an independent route;
              otherwise ``checked`` (never ``proved``), with the best margin found.
  Search      (continued) ``checked`` needs the best margin to clear the stated tolerance
              (``best_margin >= -tolerance``; the tolerance is 0 unless the step states one,
              e.g. an integrator's error); a best margin below it is ``unproven``.
  Cited       a published lemma (comparison principle, LaSalle-Yoshizawa, ...) with its
              reference, whose hypotheses are themselves steps: ``cited`` when every
              hypothesis is proved or cited; otherwise the weakest hypothesis decides.
  FromClaim   another claim of the workbench used as a lemma: its verdict carries over
              (proved -> proved, proved-given -> cited, checked -> checked), and a lemma the
              workbench refutes or leaves unproven makes the step ``unproven``, never proved.
  Unproven    a named gap: why no prover could decide (always ``unproven``).

Combination (a conclusion needs every step): refuted > unproven > checked > cited > proved,
i.e. the weakest step decides.  A claim whose steps are proved except for cited lemmas is
"proved, given [refs]" (verdict ``proved-given``).

Falsification searches of a claim's statement itself (``Claim.searches``) are a second,
independent route: a confirmed counterexample refutes the claim whatever its proof steps say;
a search that finds none supports the claim as ``checked`` only where the proof steps do not
decide it (they are unproven, or there are none).  A proof is never weakened by a search that
found nothing, so fixing a law turns a refuted claim into a proved one, not a checked one.

Whose statement: a claim judges either the paper's statement as printed (``statement =
"paper"``, the default) or the workbench's own (``"workbench"``); a workbench claim that
corrects a paper claim names it (``corrects``).  A printed formula is judged as printed and
keeps its witness beside its correction.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import sympy as sp

STEP_STATUSES = ("proved", "cited", "checked", "unproven", "refuted")
VERDICTS = ("proved", "proved-given", "checked", "unproven", "refuted")
# weakest first: the first status present among a claim's steps decides
_ORDER = ("refuted", "unproven", "checked", "cited", "proved")
_TO_VERDICT = {"proved": "proved", "cited": "proved-given", "checked": "checked",
               "unproven": "unproven", "refuted": "refuted"}


def _jsonable(x: Any) -> Any:
    """Plain JSON data (strict: non-finite floats become None)."""
    if isinstance(x, sp.Basic):
        return sp.sstr(x)
    if isinstance(x, Mapping):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, bool | int | str) or x is None:
        return x
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    try:
        f = float(x)
    except (TypeError, ValueError):
        return str(x)
    return f if math.isfinite(f) else None


@dataclass(frozen=True)
class Witness:
    """A reproducible counterexample: the point (state and parameters), the margin there
    (bound minus observed, or the residual), how it was found, and the independent re-check.

    ``rechecked_margin`` is the margin by ``recheck_method`` (a different route: exact
    arithmetic, a tight reference integration); a witness refutes only if both are < 0."""

    point: Mapping[str, Any]
    margin: float
    method: str
    rechecked_margin: float | None = None
    recheck_method: str = ""
    seed: int | None = None
    # the claim is strict (x > 0, "positive definite"): a margin of exactly 0 violates it too,
    # so both margins <= 0 confirm (an exact 0 needs exact routes: no rounding can make it)
    strict: bool = False

    def __getitem__(self, key: str) -> Any:
        """The point's coordinate ``key`` (a witness reads like the case it describes)."""
        return self.point[key]

    @property
    def confirmed(self) -> bool:
        if self.strict:
            return (self.margin <= 0 and self.rechecked_margin is not None
                    and self.rechecked_margin <= 0)
        return (self.margin < 0 and self.rechecked_margin is not None
                and self.rechecked_margin < 0)

    def to_dict(self) -> dict[str, Any]:
        d = {"point": dict(self.point), "margin": self.margin, "method": self.method,
             "rechecked_margin": self.rechecked_margin, "recheck_method": self.recheck_method,
             "seed": self.seed}
        if self.strict:  # only when set: the records of non-strict witnesses are unchanged
            d["strict"] = True
        return _jsonable(d)


class Evidence:
    """Base of the evidence kinds; ``status`` is computed from the data."""

    kind: ClassVar[str] = ""

    @property
    def status(self) -> str:  # pragma: no cover - every kind overrides it
        raise NotImplementedError

    @property
    def witness(self) -> Witness | None:
        return None

    def summary(self) -> str:
        raise NotImplementedError

    def to_dict(self) -> dict[str, Any]:
        raise NotImplementedError


@dataclass(frozen=True)
class Identity(Evidence):
    """``expr == 0`` identically: the residual after the named simplification."""

    kind: ClassVar[str] = "identity"
    residual: sp.Expr
    method: str = "sympy.simplify"
    point_witness: Witness | None = None  # nonzero at an exact point

    @property
    def status(self) -> str:
        if sp.sympify(self.residual) == 0:
            return "proved"
        if self.point_witness is not None and self.point_witness.confirmed:
            return "refuted"
        return "unproven"

    @property
    def witness(self) -> Witness | None:
        return self.point_witness if self.status == "refuted" else None

    def summary(self) -> str:
        if self.status == "proved":
            return f"{self.method}: residual reduces to 0"
        if self.status == "refuted":
            return (f"{self.method}: residual {sp.sstr(self.residual)} is "
                    f"{self.point_witness.margin:.6g} at {dict(self.point_witness.point)}")
        return f"{self.method}: residual {sp.sstr(self.residual)} not shown to be 0"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "method": self.method, "residual": sp.sstr(self.residual),
                "witness": self.point_witness.to_dict() if self.point_witness else None}


@dataclass(frozen=True)
class Inequality(Evidence):
    """``expr >= 0`` (or > 0 when ``strict``) decided by ``prover``.

    prover: "z3" (``answer`` is z3's result on the negation: "unsat" proves), "arb" (an
    interval enclosure over ``box``: ``lower`` is the enclosure's lower end; proved when
    lower >= 0, or > 0 if strict), "sos" (a sum-of-squares certificate in ``certificate``;
    ``answer`` "feasible" proves), "sympy" (SymPy assumptions: ``answer`` True / False /
    None).  A refutation needs a confirmed witness."""

    kind: ClassVar[str] = "inequality"
    expr: sp.Expr
    prover: str
    answer: Any = None
    box: Mapping[str, tuple[float, float]] | None = None
    lower: float | None = None
    strict: bool = False
    certificate: Any = None
    counter: Witness | None = None

    PROVERS: ClassVar[tuple[str, ...]] = ("z3", "arb", "sos", "sympy")

    def __post_init__(self) -> None:
        if self.prover not in self.PROVERS:
            raise ValueError(f"Inequality prover must be one of {self.PROVERS}")

    @property
    def status(self) -> str:
        if self.counter is not None and self.counter.confirmed:
            return "refuted"
        ok = False
        if self.prover == "z3":
            ok = self.answer == "unsat"
        elif self.prover == "arb":
            ok = self.lower is not None and (self.lower > 0 if self.strict else self.lower >= 0)
        elif self.prover == "sos":
            ok = self.answer == "feasible" and self.certificate is not None
        elif self.prover == "sympy":
            ok = self.answer is True
        return "proved" if ok else "unproven"

    @property
    def witness(self) -> Witness | None:
        return self.counter if self.status == "refuted" else None

    def summary(self) -> str:
        rel = ">" if self.strict else ">="
        s = f"{self.prover}: {sp.sstr(self.expr)} {rel} 0"
        if self.prover == "arb" and self.box is not None:
            s += f" on {dict(self.box)} (enclosure lower end {self.lower})"
        elif self.prover in ("z3", "sos", "sympy"):
            s += f" (answer {self.answer})"
        return s + f": {self.status}"

    def to_dict(self) -> dict[str, Any]:
        return _jsonable({"kind": self.kind, "prover": self.prover, "expr": self.expr,
                          "strict": self.strict, "answer": self.answer,
                          "box": dict(self.box) if self.box else None, "lower": self.lower,
                          "certificate": self.certificate,
                          "witness": self.counter.to_dict() if self.counter else None})


@dataclass(frozen=True)
class Search(Evidence):
    """A falsification run: the margin (bound minus observed; < 0 violates) minimised over
    ``domain`` by ``method`` with ``evaluations`` evaluations.  ``best_point`` attains
    ``best_margin``.  Refutes only with a confirmed witness; otherwise ``checked``."""

    kind: ClassVar[str] = "search"
    domain: Mapping[str, Any]
    method: str
    evaluations: int
    best_margin: float
    best_point: Mapping[str, Any]
    seed: int | None = None
    counter: Witness | None = None
    relative: bool = False  # best_margin relative to the bound

    tolerance: float = 0.0  # the margin a "checked" needs: best_margin >= -tolerance
    budget: str = ""  # the budget as stated (population, generations, grid, ...); "" = evaluations

    def __post_init__(self) -> None:
        if self.evaluations < 1:
            raise ValueError("a Search needs at least one evaluation")
        if not (math.isfinite(self.tolerance) and self.tolerance >= 0):
            raise ValueError("a Search tolerance must be finite and >= 0")

    @property
    def status(self) -> str:
        if self.counter is not None and self.counter.confirmed:
            return "refuted"
        m = self.best_margin
        return "checked" if isinstance(m, int | float) and math.isfinite(m) and \
            m >= -self.tolerance else "unproven"

    @property
    def witness(self) -> Witness | None:
        return self.counter if self.status == "refuted" else None

    def summary(self) -> str:
        kind = "relative margin" if self.relative else "margin"
        s = (f"{self.method}, {self.evaluations} evaluations over {dict(self.domain)} "
             f"(seed {self.seed}" + (f"; budget {self.budget}" if self.budget else "")
             + f"): best {kind} {self.best_margin:.6g}")
        if self.tolerance:
            s += f" (tolerance {self.tolerance:.3g})"
        if self.status == "refuted":
            s += f"; counterexample re-checked by {self.counter.recheck_method}"
        elif self.status == "unproven":
            s += "; below the tolerance, not re-checked into a counterexample: unproven"
        return s

    def to_dict(self) -> dict[str, Any]:
        return _jsonable({"kind": self.kind, "domain": dict(self.domain),
                          "method": self.method, "evaluations": self.evaluations,
                          "best_margin": self.best_margin, "relative": self.relative,
                          "best_point": dict(self.best_point), "seed": self.seed,
                          "tolerance": self.tolerance, "budget": self.budget,
                          "witness": self.counter.to_dict() if self.counter else None})


@dataclass(frozen=True)
class Cited(Evidence):
    """A published result applied here; its hypotheses are steps checked by the workbench."""

    kind: ClassVar[str] = "cited"
    reference: str
    result: str
    hypotheses: tuple[Step, ...] = ()

    @property
    def status(self) -> str:
        weakest = _weakest(h.status for h in self.hypotheses)
        return "cited" if weakest in ("proved", "cited") else weakest

    def summary(self) -> str:
        return f"{self.result} [{self.reference}]" + (
            f", hypotheses: {', '.join(h.status for h in self.hypotheses)}"
            if self.hypotheses else "")

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "reference": self.reference, "result": self.result,
                "hypotheses": [h.to_dict() for h in self.hypotheses]}


@dataclass(frozen=True)
class Unproven(Evidence):
    """A named gap: what would be needed and why no prover decided it."""

    kind: ClassVar[str] = "unproven"
    reason: str

    @property
    def status(self) -> str:
        return "unproven"

    def summary(self) -> str:
        return self.reason

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "reason": self.reason}


@dataclass(frozen=True)
class FromClaim(Evidence):
    """Another claim of the workbench used as a lemma (``claim``, a ``Claim``): its verdict is
    this step's status, except that a refuted or unproven lemma gives ``unproven`` (the step
    rests on something not shown), and proved-given gives ``cited``."""

    kind: ClassVar[str] = "claim"
    claim: Any  # Claim (defined below)

    _MAP: ClassVar[dict[str, str]] = {"proved": "proved", "proved-given": "cited",
                                      "checked": "checked", "unproven": "unproven",
                                      "refuted": "unproven"}

    @property
    def status(self) -> str:
        return self._MAP[self.claim.verdict]

    def summary(self) -> str:
        return f"rests on claim {self.claim.id} ({self.claim.verdict})"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "claim": self.claim.id, "verdict": self.claim.verdict}


EVIDENCE_KINDS = (Identity, Inequality, Search, Cited, Unproven, FromClaim)


@dataclass(frozen=True)
class Step:
    """One step of a derivation: what it asserts and the evidence; its status is computed.

    ``expr`` optionally holds the statement as a SymPy object (relation or expression) for
    rendering (LaTeX, MathML)."""

    statement: str
    evidence: Evidence
    expr: sp.Basic | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.evidence, EVIDENCE_KINDS):
            raise TypeError(f"step {self.statement!r}: evidence must be one of "
                            f"{', '.join(k.__name__ for k in EVIDENCE_KINDS)}, "
                            f"not {type(self.evidence).__name__}")

    @property
    def status(self) -> str:
        return self.evidence.status

    @property
    def witness(self) -> Witness | None:
        return self.evidence.witness

    def to_dict(self) -> dict[str, Any]:
        return {"statement": self.statement, "status": self.status,
                "expr": sp.sstr(self.expr) if self.expr is not None else None,
                "summary": self.evidence.summary(), "evidence": self.evidence.to_dict()}


def _weakest(statuses: Iterable[str]) -> str:
    st = set(statuses)
    for s in _ORDER:
        if s in st:
            return s
    return "unproven"  # no step: nothing shown


def combine(steps: Iterable[Step]) -> str:
    """The verdict of a conclusion that needs every step: the weakest step decides."""
    return _TO_VERDICT[_weakest(s.status for s in steps)]


def verdict_of(steps: Iterable[Step], searches: Iterable[Step] = ()) -> str:
    """A claim's verdict from its proof ``steps`` and its falsification ``searches``: a
    refuted search refutes; otherwise the steps decide (``combine``), except that where they
    leave the claim unproven (or there are none) searches that found no violation make it
    ``checked``."""
    steps, searches = list(steps), list(searches)
    if any(s.status == "refuted" for s in searches):
        return "refuted"
    proof = combine(steps)
    if proof == "unproven" and searches and combine(searches) == "checked":
        return "checked"
    return proof


SCOPES = ("all-gains", "gain-set", "scenario")
STATEMENTS = ("paper", "workbench")


@dataclass(frozen=True)
class Claim:
    """A claim of a paper: its statement, what the workbench derives, the steps and (computed)
    verdict.  ``scope``: "all-gains" (holds or fails whatever the valid gains), "gain-set"
    (judged for the gain set the report was made for), "scenario" (a statement about the
    paper's simulations).  ``remarks`` are steps of the paper's own argument that fail where
    the workbench proves the statement another way: reported, not part of the verdict.

    ``statement``: whose statement is judged.  "paper": the paper's statement as printed (the
    summary counts and the findings page count these).  "workbench": a statement the
    workbench derives itself; when it corrects a paper statement, ``corrects`` is that paper
    claim's id, so a printed formula is judged as printed (refuted, with its witness) beside
    its correction (proved).

    ``searches``: falsification searches of the statement itself (see the module docstring):
    a confirmed counterexample refutes the claim; otherwise they count only where the proof
    steps do not decide it."""

    id: str
    equations: str
    title: str
    paper: str
    derived: str
    steps: tuple[Step, ...]
    law: str | None = None
    scope: str = "all-gains"
    numbers: Mapping[str, Any] = field(default_factory=dict)
    remarks: tuple[Step, ...] = ()
    paper_expr: sp.Basic | None = None
    derived_expr: sp.Basic | None = None
    statement: str = "paper"
    corrects: str | None = None
    searches: tuple[Step, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "steps", tuple(self.steps))
        object.__setattr__(self, "remarks", tuple(self.remarks))
        object.__setattr__(self, "searches", tuple(self.searches))
        if self.scope not in SCOPES:
            raise ValueError(f"claim {self.id}: scope must be one of {SCOPES}")
        if self.statement not in STATEMENTS:
            raise ValueError(f"claim {self.id}: statement must be one of {STATEMENTS}")
        if self.corrects is not None and self.statement != "workbench":
            raise ValueError(f"claim {self.id}: only a workbench statement corrects another")
        for s in self.steps + self.remarks + self.searches:
            if not isinstance(s, Step):
                raise TypeError(f"claim {self.id}: steps must be Step objects")

    @property
    def verdict(self) -> str:
        return verdict_of(self.steps, self.searches)

    @property
    def counterexample(self) -> Witness | None:
        """The witness of the first refuted search, else of the first refuted step (None
        unless the claim is refuted)."""
        for s in self.searches + self.steps:
            if s.status == "refuted":
                return s.witness
        return None

    @property
    def references(self) -> list[str]:
        """The published results the verdict rests on (for "proved, given [refs]")."""
        out: list[str] = []

        def walk(steps: Iterable[Step]) -> None:
            for s in steps:
                if isinstance(s.evidence, Cited):
                    if s.evidence.reference not in out:
                        out.append(s.evidence.reference)
                    walk(s.evidence.hypotheses)
                elif isinstance(s.evidence, FromClaim) and s.status == "cited":
                    out.extend(r for r in s.evidence.claim.references if r not in out)
        walk(self.steps)
        return out

    def verdict_text(self) -> str:
        if self.verdict == "proved-given":
            return "proved, given " + "; ".join(self.references)
        return self.verdict

    def to_dict(self) -> dict[str, Any]:
        ce = self.counterexample
        return _jsonable({
            "id": self.id, "equations": self.equations, "title": self.title,
            "paper": self.paper, "derived": self.derived, "law": self.law,
            "scope": self.scope, "statement": self.statement, "corrects": self.corrects,
            "verdict": self.verdict, "verdict_text": self.verdict_text(),
            "steps": [s.to_dict() for s in self.steps],
            "searches": [s.to_dict() for s in self.searches],
            "remarks": [s.to_dict() for s in self.remarks],
            "witness": ce.to_dict() if ce else None, "numbers": dict(self.numbers),
            "paper_expr": self.paper_expr, "derived_expr": self.derived_expr})
