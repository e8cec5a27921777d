"""Robustness-guided falsification: minimise a margin over a box, shrink and re-check a witness.

A quantitative claim "observed <= bound" is turned into a margin function m(point) = bound -
observed (or (bound - observed)/bound when ``relative``), m < 0 being a violation.  ``falsify``
minimises m over a box of initial states and parameters:

  1. global search: ``scipy.optimize.differential_evolution`` (best1bin, Latin-hypercube
     initial population) on the unit cube, seeded; it stops early once a margin below
     ``Budget.stop_below`` is found (a violation is a violation, however it was reached);
  2. local refinement: Nelder-Mead from the best point, with a fixed evaluation budget;
  3. if the best margin is negative, the witness is shrunk: coordinate by coordinate the value is
     rounded to 1, 2, ... significant digits and the simplest rounding that keeps the margin
     negative is kept (passes repeat until nothing changes);
  4. the shrunk witness is re-checked by the caller's independent route (``Problem.recheck``,
     e.g. a tight LSODA integration against a closed form); it refutes only if both margins
     are negative (``lgw.theory.evidence.Witness.confirmed``).

The result is a ``lgw.theory.evidence.Search``: domain, method and budget, the exact number of
margin evaluations, the best margin and the point attaining it, the seed, and the witness.  The
same problem, budget and seed give the same result (scipy's DE and Nelder-Mead are
deterministic given the seed).

A margin evaluation that raises or returns NaN is never counted as "no violation" silently: it
is scored +inf for the optimiser (it cannot steer there) but counted, and the count is part of
the method text and of the domain record ("failed_evaluations").
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from lgw.theory.evidence import Search, Witness
from scipy.optimize import differential_evolution, minimize

SCALES = ("linear", "log", "signed-log")


@dataclass(frozen=True)
class Dim:
    """One coordinate of the search box.

    scale "linear": uniform in [lo, hi]; "log": 10^u, u uniform in [log10 lo, log10 hi]
    (0 < lo < hi); "signed-log": +-10^u with the same magnitudes, both signs (0 < lo < hi).
    """

    name: str
    lo: float
    hi: float
    scale: str = "linear"

    def __post_init__(self) -> None:
        if self.scale not in SCALES:
            raise ValueError(f"dim {self.name}: scale must be one of {SCALES}")
        if not (math.isfinite(self.lo) and math.isfinite(self.hi) and self.lo < self.hi):
            raise ValueError(f"dim {self.name}: need finite lo < hi")
        if self.scale != "linear" and not self.lo > 0:
            raise ValueError(f"dim {self.name}: a {self.scale} range needs lo > 0")

    def from_unit(self, u: float) -> float:
        """Map u in [0, 1] to the coordinate."""
        u = min(max(float(u), 0.0), 1.0)
        if self.scale == "linear":
            return self.lo + u * (self.hi - self.lo)
        a, b = math.log10(self.lo), math.log10(self.hi)
        if self.scale == "log":
            return 10.0 ** (a + u * (b - a))
        t = 2.0 * u - 1.0  # signed: [-1, 1], magnitude from |t|
        return math.copysign(10.0 ** (a + abs(t) * (b - a)), t if t != 0 else 1.0)

    def contains(self, x: float) -> bool:
        if self.scale == "signed-log":
            return self.lo <= abs(x) <= self.hi
        return self.lo <= x <= self.hi

    def describe(self) -> list[Any]:
        return [self.lo, self.hi, self.scale]


@dataclass(frozen=True)
class Problem:
    """A margin to minimise: ``margin(point) < 0`` violates the claim.

    ``recheck(point)`` computes the same margin by an independent route (named by
    ``recheck_method``); ``route`` names the fast route.  ``valid(point)`` may reject points
    outside the claim's hypotheses that a box cannot exclude (scored +inf, counted apart).
    ``fixed`` holds coordinates that are not searched (passed to both routes)."""

    name: str
    dims: tuple[Dim, ...]
    margin: Callable[[Mapping[str, float]], float]
    recheck: Callable[[Mapping[str, float]], float]
    route: str
    recheck_method: str
    relative: bool = True
    fixed: Mapping[str, float] = field(default_factory=dict)
    valid: Callable[[Mapping[str, float]], bool] | None = None
    # re-check every negative fast-route margin at once and keep the independent route's
    # value when it is not negative (a fast route with false alarms then cannot stop the
    # search on a point that is no violation)
    confirm_negatives: bool = False

    def point(self, u: Sequence[float]) -> dict[str, float]:
        p = {d.name: d.from_unit(x) for d, x in zip(self.dims, u, strict=True)}
        p.update(self.fixed)
        return p

    def domain(self) -> dict[str, Any]:
        out: dict[str, Any] = {d.name: d.describe() for d in self.dims}
        out.update({k: float(v) for k, v in self.fixed.items()})
        return out


@dataclass(frozen=True)
class Budget:
    """The search budget: DE population ``popsize`` x dims per generation for ``maxiter``
    generations, then ``local_evals`` Nelder-Mead evaluations; the global phase stops once the
    margin is below ``stop_below``."""

    popsize: int = 10
    maxiter: int = 30
    local_evals: int = 150
    seed: int = 0
    stop_below: float = -1e-3

    def describe(self) -> str:
        return (f"scipy differential_evolution (best1bin, Latin hypercube, popsize {self.popsize}"
                f", maxiter {self.maxiter}) + Nelder-Mead ({self.local_evals} evaluations)")


class _Counted:
    """The margin on the unit cube, with evaluation and failure counts and the best point."""

    def __init__(self, problem: Problem) -> None:
        self.p = problem
        self.n = 0
        self.failed = 0
        self.invalid = 0
        self.disagreed = 0
        self.best = (math.inf, None)

    def value(self, point: Mapping[str, float]) -> float:
        self.n += 1
        if self.p.valid is not None and not self.p.valid(point):
            self.invalid += 1
            return math.inf
        try:
            m = float(self.p.margin(point))
        except (ArithmeticError, ValueError, RuntimeError):
            m = math.nan
        if not math.isfinite(m):
            self.failed += 1
            return math.inf
        if m < 0 and self.p.confirm_negatives:
            try:
                m_re = float(self.p.recheck(point))
            except (ArithmeticError, ValueError, RuntimeError):
                m_re = math.nan
            if not (math.isfinite(m_re) and m_re < 0):
                self.disagreed += 1
                if not math.isfinite(m_re):
                    self.failed += 1
                    return math.inf
                m = m_re
        if m < self.best[0]:
            self.best = (m, dict(point))
        return m

    def __call__(self, u: np.ndarray) -> float:
        return self.value(self.p.point(u))


def _roundings(x: float) -> list[float]:
    """Simpler values for x, simplest first: 1, 2, ... 6 significant digits (and 0)."""
    if x == 0 or not math.isfinite(x):
        return []
    out = [0.0]
    for digits in range(1, 7):
        y = float(f"{x:.{digits - 1}e}")
        if y not in out and y != x:
            out.append(y)
    return out


def shrink(problem: Problem, point: Mapping[str, float], margin: float,
           evaluate: Callable[[Mapping[str, float]], float] | None = None,
           max_passes: int = 3) -> tuple[dict[str, float], float]:
    """Round the witness's coordinates to the simplest values that keep the violation.

    A rounding is kept when the margin stays at or below half the original (negative) margin,
    so a shrunk witness is never a crumb at the edge of the violation that an independent
    route's own error could erase.  Returns the shrunk point and its margin (always < 0).
    Coordinates stay inside the box and the claim's hypotheses."""
    ev = evaluate or problem.margin
    keep = 0.5 * margin
    best = dict(point)
    m_best = margin
    dims = {d.name: d for d in problem.dims}
    for _ in range(max_passes):
        changed = False
        for name, d in dims.items():
            for y in _roundings(best[name]):
                if not d.contains(y):
                    continue
                trial = {**best, name: y}
                if problem.valid is not None and not problem.valid(trial):
                    continue
                try:
                    m = float(ev(trial))
                except (ArithmeticError, ValueError, RuntimeError):
                    continue
                if math.isfinite(m) and m < 0 and m <= keep:
                    best, m_best, changed = trial, m, True
                    break
        if not changed:
            break
    return best, m_best


def falsify(problem: Problem, budget: Budget = Budget(),
            starts: Sequence[Mapping[str, float]] = ()) -> Search:
    """Search for a violation of ``problem``'s claim; see the module docstring.

    ``starts``: known hard points (e.g. the worst points of an earlier run) added to the
    initial population, so a re-run begins where the last one ended."""
    f = _Counted(problem)
    nd = len(problem.dims)
    rng = np.random.default_rng(budget.seed)
    npop = max(5, budget.popsize * nd)
    # Latin hypercube on the unit cube, drawn from the seed, then the given starts
    init = (rng.permuted(np.tile(np.arange(npop), (nd, 1)), axis=1).T
            + rng.random((npop, nd))) / npop
    for i, s in enumerate(starts[:npop]):
        init[i] = _to_unit(problem, s)

    def stop(xk, convergence=None) -> bool:  # noqa: ARG001 - scipy's callback signature
        return f.best[0] < budget.stop_below

    if f.best[0] >= budget.stop_below:
        differential_evolution(f, [(0.0, 1.0)] * nd, maxiter=budget.maxiter, init=init,
                               seed=budget.seed, polish=False, tol=0.0, atol=0.0,
                               callback=stop, updating="immediate")
    if f.best[1] is not None and budget.local_evals > 0 and f.best[0] >= budget.stop_below:
        x0 = _to_unit(problem, f.best[1])
        minimize(f, x0, method="Nelder-Mead",
                 options={"maxfev": budget.local_evals, "xatol": 1e-10, "fatol": 0.0,
                          "initial_simplex": _simplex(x0, 0.05)})
    method = budget.describe() + f" on the fast route ({problem.route})"
    if f.failed or f.invalid:
        method += (f"; {f.failed} evaluations failed and {f.invalid} fell outside the "
                   "hypotheses (scored as no information, not as holding)")
    if f.disagreed:
        method += (f"; {f.disagreed} fast-route violations not reproduced by the independent "
                   "route were replaced by its margin")
    domain = problem.domain()
    domain["failed_evaluations"] = f.failed
    if f.best[1] is None:
        raise RuntimeError(f"{problem.name}: every one of {f.n} margin evaluations failed")
    m_best, p_best = f.best
    counter = None
    if m_best < 0:
        p_w, m_w = shrink(problem, p_best, m_best, evaluate=f.value)
        try:
            m_re = float(problem.recheck(p_w))
        except (ArithmeticError, ValueError, RuntimeError):
            m_re = math.nan
        counter = Witness(point=p_w, margin=m_w, method=f"{problem.route}, shrunk",
                          rechecked_margin=m_re if math.isfinite(m_re) else None,
                          recheck_method=problem.recheck_method, seed=budget.seed)
    spent = (f"population {npop} x {budget.maxiter} generations (at most) + "
             f"{budget.local_evals} Nelder-Mead evaluations, stop below margin "
             f"{budget.stop_below:g}" + (f"; {min(len(starts), npop)} known hard points in the "
                                         "initial population" if len(starts) else ""))
    return Search(domain=domain, method=method, evaluations=f.n,
                  best_margin=m_best, best_point=p_best, seed=budget.seed, counter=counter,
                  relative=problem.relative, budget=spent)


def _to_unit(problem: Problem, point: Mapping[str, float]) -> np.ndarray:
    u = []
    for d in problem.dims:
        x = float(point[d.name])
        if d.scale == "linear":
            u.append((x - d.lo) / (d.hi - d.lo))
            continue
        a, b = math.log10(d.lo), math.log10(d.hi)
        t = (math.log10(max(abs(x), d.lo)) - a) / (b - a)
        u.append(t if d.scale == "log" else 0.5 + math.copysign(t, x) / 2)
    return np.clip(np.array(u), 0.0, 1.0)


def _simplex(x0: np.ndarray, h: float) -> np.ndarray:
    """A Nelder-Mead start simplex inside the unit cube (steps of h toward the interior)."""
    pts = [x0]
    for i in range(len(x0)):
        y = x0.copy()
        y[i] = y[i] + h if y[i] + h <= 1.0 else y[i] - h
        pts.append(y)
    return np.array(pts)
