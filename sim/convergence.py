"""Convergence measured, never assumed: every simulated number a command prints is checked.

A run is flown again with a finer integration (``refinement``: RK4 at half the step, dopri5 at
a tenth of its tolerances; or the reference integrator) and every quoted number of every
checked case is compared with a stated tolerance (``Tol``: |a - b| <= atol + rtol max(|a|, |b|),
default rtol = 1 %); a case whose outcome changes is counted apart, its numbers are not
compared (a different outcome makes them different quantities).  ``compare_cases`` returns a
``ConvergenceRecord``: what was compared with what, how many cases, which numbers did not
converge, with the worst case of each; ``flags()`` gives the warning lines a command prints and
``to_dict()`` the JSON record.  The record is system-agnostic: a system supplies its per-case
records (the dicts its JSON prints) for the two runs.

A campaign is checked on at most ``CHECK_CASES`` cases (``check_indices``: evenly spread, the
record says how many of how many), so the check costs at most that many extra cases.

``refine_outcomes``: the fixed-step outcome made step-independent.  Cases whose outcome
changes when the RK4 step is halved are flown again at dt/4, dt/8, ... until two successive
steps give the same outcome (at most ``REFINE_HALVINGS`` halvings); the system replaces those
cases by their refined flights and marks them refined (the step each was flown at).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

RTOL = 0.01  # the stated tolerance: 1 % (the quoted numbers of the paper's scenarios)
CHECK_CASES = 1000  # at most this many cases of a campaign are flown again
REFINE_HALVINGS = 5  # dt/2 ... dt/32 at most
DOPRI_TIGHTEN = 10.0  # dopri5 is checked at rtol/10, atol/10


RELATIVE_TO = ("larger", "check")


@dataclass(frozen=True)
class Tol:
    """|a - b| <= atol + rtol scale(a, b); atol in the quantity's unit (the resolution below
    which a difference means nothing, e.g. 1e-3 s on a time).  scale(a, b) = max(|a|, |b|)
    (``relative_to`` "larger", the default) or |b|, the finer run's value (``relative_to``
    "check"), and at least ``floor``, the quantity's own scale below which a relative
    difference means nothing (rtol x floor is then the absolute tolerance of a number near
    zero).  ``difference(a, b)`` = |a - b| / scale(a, b), the number a check prints."""

    rtol: float = RTOL
    atol: float = 0.0
    floor: float = 0.0
    relative_to: str = "larger"

    def __post_init__(self) -> None:
        if self.relative_to not in RELATIVE_TO:
            raise ValueError(f"relative_to must be one of {RELATIVE_TO}")

    def scale(self, a: float, b: float) -> float:
        ref = max(abs(a), abs(b)) if self.relative_to == "larger" else abs(b)
        return max(ref, self.floor)

    def difference(self, a: float, b: float) -> float:
        """|a - b| / scale(a, b); 0 when both are the same non-finite value (or both NaN), inf
        when only one is finite or the scale is 0 with a difference."""
        if (math.isnan(a) and math.isnan(b)) or (not math.isfinite(a) and a == b):
            return 0.0
        if not (math.isfinite(a) and math.isfinite(b)):
            return math.inf
        d = abs(a - b)
        sc = self.scale(a, b)
        return d / sc if sc > 0 else (0.0 if d == 0 else math.inf)

    def ok(self, a: float, b: float) -> bool:
        if math.isnan(a) and math.isnan(b):  # undefined in both (e.g. no landing time)
            return True
        if not (math.isfinite(a) and math.isfinite(b)):
            return a == b
        return abs(a - b) <= self.atol + self.rtol * self.scale(a, b)


def refinement(method: str, dt: float | None = None, rtol: float | None = None,
               atol: float | None = None) -> tuple[str, dict[str, float]]:
    """(how, the changed integration settings) of the check of a run: RK4 at dt/2, dopri5 at
    rtol/10 and atol/10."""
    if method == "rk4":
        if dt is None:
            raise ValueError("RK4 is checked by halving its step: dt is needed")
        return "step halving", {"dt": dt / 2}
    if method == "dopri5":
        if rtol is None or atol is None:
            raise ValueError("dopri5 is checked by tightening rtol, atol: both are needed")
        return "tolerance tightened", {"rtol": rtol / DOPRI_TIGHTEN, "atol": atol / DOPRI_TIGHTEN}
    raise ValueError(f"no refinement for method {method!r}")


def check_indices(n: int, limit: int = CHECK_CASES) -> np.ndarray:
    """Indices of the cases a campaign of n is checked on: all of them up to ``limit``, else
    ``limit`` evenly spread ones (the first and the last included)."""
    if n <= limit:
        return np.arange(n)
    return np.unique(np.round(np.linspace(0, n - 1, limit)).astype(np.int64))


def _values(x: Any) -> list[float]:
    if x is None:
        return [math.nan]
    if isinstance(x, list | tuple | np.ndarray):
        return [math.nan if v is None else float(v) for v in np.ravel(np.asarray(x, object))]
    return [float(x)]


@dataclass
class MetricCheck:
    """One quoted number over the checked cases."""

    name: str
    tol: Tol
    checked: int = 0
    unconverged: list[int] = field(default_factory=list)  # case numbers
    worst: dict[str, Any] | None = None  # the largest relative difference among them

    def to_dict(self) -> dict[str, Any]:
        return {"rtol": self.tol.rtol, "atol": self.tol.atol, "checked": self.checked,
                "unconverged": len(self.unconverged),
                "unconverged_cases": self.unconverged[:20], "worst": self.worst}


@dataclass
class ConvergenceRecord:
    """The check of one run (module docstring)."""

    how: str  # "step halving", "tolerance tightened", "reference"
    base: str  # the run checked, e.g. "RK4 dt = 0.05 s"
    check: str  # the finer run, e.g. "RK4 dt = 0.025 s"
    cases_total: int
    cases_checked: int
    outcome_changed: list[int]  # case numbers whose outcome differs
    metrics: dict[str, MetricCheck]
    case_ok: dict[int, bool]  # per checked case: outcome and every number converged
    # fixed-step cases whose outcome changed and were refined (refine_outcomes): the step each
    # settled at (None: it did not settle), and the check of their refined flights
    refined: dict[int, float | None] = field(default_factory=dict)
    refined_check: ConvergenceRecord | None = None

    @property
    def unresolved(self) -> list[int]:
        """Cases whose outcome changed and did not settle under refinement."""
        return [c for c in self.outcome_changed if self.refined.get(c) is None]

    @property
    def converged(self) -> bool:
        return (not self.unresolved and all(not m.unconverged for m in self.metrics.values())
                and (self.refined_check is None or self.refined_check.converged))

    def with_refinement(self, refined: dict[int, float | None],
                        check: ConvergenceRecord | None) -> ConvergenceRecord:
        """This record with the outcome changes resolved by refinement: ``refined`` maps each
        refined case to the step its outcome settled at (None: not settled), ``check`` is the
        check of the refined flights themselves (each at half its step)."""
        for c, ok in (check.case_ok.items() if check is not None else ()):
            self.case_ok[c] = ok
        self.refined = dict(refined)
        self.refined_check = check
        return self

    def flags(self, what: str = "") -> list[str]:
        """Warning lines for what did not converge (none when everything did)."""
        pre = f"{what}: " if what else ""
        cmp = f"{self.base} against {self.check} ({self.how})"
        out = []
        if self.unresolved:
            out.append(f"{pre}UNCONVERGED outcome of {len(self.unresolved)} of "
                       f"{self.cases_checked} checked cases, {cmp}"
                       + (" and refined down to the finest step" if self.refined else "")
                       + f": cases {_cases(self.unresolved)}")
        for m in self.metrics.values():
            if m.unconverged:
                w = m.worst or {}
                out.append(f"{pre}UNCONVERGED {m.name} in {len(m.unconverged)} of {m.checked} "
                           f"checked cases, {cmp}, tolerance {m.tol.rtol:.0%} + {m.tol.atol:g}"
                           f": worst case {w.get('case')}: {_num(w.get('value'))} against "
                           f"{_num(w.get('check'))}")
        if self.refined_check is not None:
            out += self.refined_check.flags((what + ", " if what else "") + "refined cases")
        return out

    def notes(self) -> list[str]:
        """What was checked, in one line (and the refined cases, if any)."""
        s = (f"convergence: {self.cases_checked} of {self.cases_total} cases checked, "
             f"{self.base} against {self.check} ({self.how}), every quoted number within its "
             f"tolerance (default {RTOL:.0%}): " + ("converged" if self.converged
                                                   else "NOT converged (see the warnings)"))
        out = [s]
        settled = {c: h for c, h in self.refined.items() if h is not None}
        if settled:
            out.append(f"refined: the outcome of {len(settled)} case(s) changed when the step "
                       f"was halved; re-flown at smaller steps until two successive steps "
                       f"agreed (cases {_cases(list(settled))}; steps "
                       f"{', '.join(sorted({f'{h:g} s' for h in settled.values()}))})")
        return out

    def to_dict(self) -> dict[str, Any]:
        return {"converged": self.converged, "how": self.how, "base": self.base,
                "check": self.check, "cases": self.cases_total,
                "cases_checked": self.cases_checked,
                "outcome_changed": len(self.outcome_changed),
                "outcome_changed_cases": self.outcome_changed[:20],
                "metrics": {k: m.to_dict() for k, m in self.metrics.items()},
                "refined": {"cases": len(self.refined),
                            "settled": sum(h is not None for h in self.refined.values()),
                            "dt": {str(c): h for c, h in list(self.refined.items())[:50]},
                            "check": (None if self.refined_check is None
                                      else self.refined_check.to_dict())}}


def _num(x: Any) -> str:
    if x is None:
        return "-"
    return "/".join(f"{v:.6g}" for v in _values(x))


def _cases(idx: list[int], k: int = 10) -> str:
    s = ", ".join(str(i) for i in idx[:k])
    return s + (f" and {len(idx) - k} more" if len(idx) > k else "")


def compare_cases(base: Sequence[Mapping[str, Any]], check: Sequence[Mapping[str, Any]],
                  tolerances: Mapping[str, Tol], *, how: str, base_label: str,
                  check_label: str, outcome_key: str = "outcome",
                  cases: Sequence[int] | None = None, total: int | None = None
                  ) -> ConvergenceRecord:
    """Compare the per-case records of a run (``base``) with those of its finer flight
    (``check``, the same cases in the same order): the outcome (``outcome_key``) and every
    number named in ``tolerances`` (a scalar, or a list compared element by element; None /
    NaN: undefined, which must be undefined in both).  ``cases``: the case numbers of the
    records (default 0, 1, ...); ``total``: the campaign's size (default len(base))."""
    if len(base) != len(check):
        raise ValueError(f"{len(base)} base records against {len(check)} check records")
    cases = list(range(len(base))) if cases is None else [int(c) for c in cases]
    metrics = {k: MetricCheck(k, t) for k, t in tolerances.items()}
    changed: list[int] = []
    case_ok: dict[int, bool] = {}
    for c, a, b in zip(cases, base, check, strict=True):
        if a.get(outcome_key) != b.get(outcome_key):
            changed.append(c)
            case_ok[c] = False
            continue
        ok = True
        for k, m in metrics.items():
            va, vb = _values(a.get(k)), _values(b.get(k))
            m.checked += 1
            good = len(va) == len(vb) and all(m.tol.ok(x, y) for x, y in zip(va, vb,
                                                                             strict=True))
            if not good:
                ok = False
                m.unconverged.append(c)
                d = max((abs(x - y) / max(abs(x), abs(y), 1e-300)
                         if math.isfinite(x) and math.isfinite(y) else math.inf)
                        for x, y in zip(va, vb, strict=False)) if va and vb else math.inf
                if m.worst is None or d > m.worst["rel_diff"]:
                    m.worst = {"case": c, "value": a.get(k), "check": b.get(k),
                               "rel_diff": d if math.isfinite(d) else None}
                    if m.worst["rel_diff"] is None:
                        m.worst["rel_diff"] = math.inf
        case_ok[c] = ok
    for m in metrics.values():  # JSON: no inf
        if m.worst is not None and not math.isfinite(m.worst["rel_diff"]):
            m.worst["rel_diff"] = None
    return ConvergenceRecord(how, base_label, check_label,
                             len(base) if total is None else int(total), len(base), changed,
                             metrics, case_ok)


@dataclass
class Refinement:
    """The outcome of ``refine_outcomes``: per refined case, the step it settled at."""

    cases: np.ndarray  # case numbers re-flown (their outcome changed under halving)
    dt: np.ndarray  # the step of each one's final flight
    settled: np.ndarray  # bool: two successive steps agreed (else the finest step is kept)
    codes: np.ndarray  # the outcome code of each one's final flight
    results: list[tuple[np.ndarray, float, Any]]  # (positions into cases, dt, fly's result)

    def to_dict(self) -> dict[str, Any]:
        return {"refined": int(len(self.cases)), "settled": int(self.settled.sum()),
                "cases": self.cases[:50].tolist(), "dt": self.dt[:50].tolist()}


def refine_outcomes(fly: Callable[[np.ndarray, float], tuple[np.ndarray, Any]],
                    codes: np.ndarray, codes_half: np.ndarray, dt: float, *,
                    halvings: int = REFINE_HALVINGS) -> Refinement:
    """Re-fly the cases whose outcome differs between step dt (``codes``) and dt/2
    (``codes_half``) at dt/4, dt/8, ... until two successive steps agree (module docstring).
    ``fly(idx, h)`` flies cases ``idx`` at step h and returns (their outcome codes, a result
    the caller merges).  The last flight of each case is kept (its position in ``results``)."""
    codes = np.asarray(codes)
    idx = np.flatnonzero(codes != np.asarray(codes_half))
    last = np.asarray(codes_half)[idx].copy()
    step = np.full(len(idx), dt / 2)
    settled = np.zeros(len(idx), bool)
    results: list[tuple[np.ndarray, float, Any]] = []
    pending = np.arange(len(idx))
    h = dt / 2
    for _ in range(max(0, halvings - 1)):
        if not len(pending):
            break
        h /= 2
        new, res = fly(idx[pending], h)
        new = np.asarray(new)
        results.append((pending.copy(), h, res))
        same = new == last[pending]
        settled[pending[same]] = True
        last[pending] = new
        step[pending] = h
        pending = pending[~same]
    return Refinement(idx, step, settled, last, results)
