"""``lgw verify SYSTEM``, written once: observed behaviour against the proven bounds, per claim.

A system supplies only what is its own (``lgw.tuning.<system>.verify`` and the claim records of
``lgw.tuning.<system>.cmd_verify``): its claims (what is observed, the bound function it is
checked against, when a case can violate it), its state variables with the default envelope
and the whole domain, and ``judge``, which flies a batch of initial states and returns, per
claim, observed and bound values (``Judged``).  Everything else is here, the same for every
system: the options, the Hypothesis campaign over the envelope, the margins, the counts, the
verdicts, the re-check of a violation, the failure message and its reproduction, the table,
the JSON document and the figure.

Margin.  One convention everywhere: ``margin = (bound - observed) / bound``, negative = a
violation.  ``observed`` is the measurement less the check's stated tolerance (an event located
on a time grid is credited one step); a claim whose bound is 0 gives its own denominator
(``Judged.reference``).  A measurement that never happened (never entered the band) is
``observed = inf``, margin ``-inf``.

Evidence that informs.  A case counts toward ``--min-cases`` only when it can violate the
claim (``Judged.informative``: e.g. it starts outside the band it must reach); the others are
excluded with that reason, like the cases no integrator could carry.  The verdict is computed:

* ``not-applicable``: the gain set does not give the claim's inputs (the reason is shown;
  exit 0 when nothing else fails);
* ``violated``: a case over its bound whose violation an independent route confirms (the
  system's finer re-flight, or a search re-checked by a second integrator); exit 1;
* ``inconclusive``: a violation the re-check does not confirm, fewer informative cases than
  ``--min-cases``, or an excluded share above ``--max-excluded``; exit 4;
* ``holds``: none of these.  Never on missing evidence.

Every failure names what was observed against which bound, at which state, axis and gains, and
prints one public command, ``lgw verify SYSTEM --claim C --witness STATE ...``, that flies that
state alone through the same check and exits 1 again.

Two kinds of claim.  A "campaign" claim is judged per initial state (above).  A "computed"
claim is judged once, by the system's ``compute`` (e.g. a certificate's promise re-derived by
its proof, or re-flown on the certificate's own campaign): a ``Computed`` record with the
observed value, the bound, its evidence word ("proven": the proof re-done; "sampled": a
campaign of ``cases`` cases, which counts toward ``--min-cases``), a violation's re-check by an
independent route, and the flags that make ``lgw verify SYSTEM --claim C ...`` reproduce it.
Every row of the table and every claim of the JSON document carries its evidence word.
"""

from __future__ import annotations

import importlib
import math
import shlex
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.tuning import vocabulary as V
from lgw.tuning.options import FILE, Number, choice
from lgw.tuning.spec import NO_PROBE, option
from lgw.tuning.system import VERIFY_EXIT, Job, Outcome

VERDICTS = ("holds", "violated", "inconclusive", "not-applicable")
DOMAINS = ("envelope", "whole")
MAX_EXCLUDED = 0.5  # default --max-excluded: above half of the cases excluded, no "holds"
SCALES = ("linear", "signed-log")
NONFINITE = "non-finite observation or bound (the run or the bound did not give a number)"


# --- what a system declares ------------------------------------------------------------------

@dataclass(frozen=True)
class Claim:
    """One checked claim: ``observed`` (what is measured, with its unit and tolerance),
    ``bound`` (the bound and the function that computes it), ``uninformative`` (why a case
    cannot violate it: such cases are excluded from the evidence), ``group`` (claims judged on
    the same flights)."""

    name: str
    equation: str
    group: str
    observed: str
    bound: str
    unit: str
    uninformative: str
    tolerance: str = ""
    kind: str = "campaign"  # "campaign": judged per state by ``judge``; "computed": ``compute``


@dataclass(frozen=True)
class Var:
    """One coordinate of an initial state (a column of ``Judged.states`` and of a witness).
    ``nonzero``: the simulator cannot start at exactly 0 (then 0 is never drawn)."""

    name: str
    unit: str
    text: str = ""
    nonzero: bool = False


@dataclass(frozen=True)
class Extra:
    """A witness field that is not a state coordinate (e.g. which disturbance was flown):
    ``kind`` is "int" or a tuple of names."""

    name: str
    kind: Any
    text: str = ""


@dataclass(frozen=True)
class Envelope:
    """The initial states searched: a union of boxes over ``variables`` (lo, hi per box).
    ``scales`` per variable: "linear" (uniform in [lo, hi]) or "signed-log" (0, or a magnitude
    log-uniform in [lo, hi] of either sign: the whole domain's decades)."""

    name: str
    variables: tuple[str, ...]
    boxes: tuple[tuple[tuple[float, ...], tuple[float, ...]], ...]
    scales: tuple[str, ...] = ()
    source: str = ""

    def __post_init__(self) -> None:
        n = len(self.variables)
        if not self.boxes:
            raise ParameterError(f"envelope {self.name}", "no box", "needs at least one box")
        for lo, hi in self.boxes:
            if len(lo) != n or len(hi) != n:
                raise ParameterError(f"envelope {self.name}", (lo, hi), "a box gives [lo, hi] "
                                     f"for each of {', '.join(self.variables)}")
            for v, a, b in zip(self.variables, lo, hi, strict=True):
                if not (math.isfinite(a) and math.isfinite(b) and a <= b):
                    raise ParameterError(f"envelope {self.name} {v}", [a, b],
                                         "must be finite numbers with lo <= hi")
        if self.scales and len(self.scales) != n:
            raise ValueError("one scale per variable")

    def scale(self, i: int) -> str:
        return self.scales[i] if self.scales else "linear"

    def contains(self, row: Sequence[float]) -> bool:
        """Whether a state lies in one of the boxes (the whole domain: within the magnitudes
        or 0)."""
        for lo, hi in self.boxes:
            ok = True
            for i, x in enumerate(row):
                if self.scale(i) == "signed-log":
                    ok = ok and (x == 0.0 or lo[i] <= abs(x) <= hi[i])
                else:
                    ok = ok and lo[i] <= x <= hi[i]
            if ok:
                return True
        return False

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "source": self.source, "variables": list(self.variables),
                "boxes": [{"lo": list(lo), "hi": list(hi)} for lo, hi in self.boxes],
                "scales": [self.scale(i) for i in range(len(self.variables))]}

    def describe(self) -> str:
        parts = []
        for lo, hi in self.boxes:
            cells = []
            for i, v in enumerate(self.variables):
                if self.scale(i) == "signed-log":
                    cells.append(f"|{v}| in {{0}} u [{lo[i]:g}, {hi[i]:g}]")
                elif lo[i] == hi[i]:
                    cells.append(f"{v} = {lo[i]:g}")
                else:
                    cells.append(f"{v} in [{lo[i]:g}, {hi[i]:g}]")
            parts.append(", ".join(cells))
        return " or ".join(f"({p})" for p in parts) if len(parts) > 1 else parts[0]


def read_envelope(path: Path, variables: Sequence[Var], default: Envelope) -> Envelope:
    """An envelope file (TOML): ``[envelope]`` with ``name`` and, per state variable,
    ``VAR = [lo, hi]`` (one box; a variable left out keeps the default envelope's range), or
    several boxes as ``[[envelope.box]]`` tables of the same form.  Every value is checked by
    name (a string, list of the wrong length or non-finite number is a ParameterError)."""
    from lgw.theory.inputs import load_toml, number

    data = load_toml(path, "--envelope")
    shown = str(path)
    env = data.get("envelope")
    if not isinstance(env, dict):
        raise ParameterError("--envelope", shown, "needs a table [envelope] (docs/verify.md)")
    unknown = set(data) - {"envelope"}
    if unknown:
        k = sorted(unknown)[0]
        raise ParameterError(f"--envelope {k}", data[k], "unknown table; the file holds "
                             "[envelope]")
    names = [v.name for v in variables]
    d_lo, d_hi = default.boxes[0]
    lo_d = {n: d_lo[default.variables.index(n)] for n in names}
    hi_d = {n: d_hi[default.variables.index(n)] for n in names}

    def box(t: dict[str, Any], where: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
        lo, hi = dict(lo_d), dict(hi_d)
        for k, v in t.items():
            if k in ("name", "box"):
                continue
            if k not in names:
                raise ParameterError(f"{where}.{k}", v, f"unknown variable; valid: "
                                     f"{', '.join(names)}")
            if not (isinstance(v, list) and len(v) == 2):
                raise ParameterError(f"{where}.{k}", v, "must be [lo, hi] (two numbers)")
            a = number(f"{where}.{k}[0]", v[0])
            b = number(f"{where}.{k}[1]", v[1])
            if not a <= b:
                raise ParameterError(f"{where}.{k}", v, "must have lo <= hi")
            lo[k], hi[k] = a, b
        return tuple(lo[n] for n in names), tuple(hi[n] for n in names)

    name = env.get("name", path.name)
    if not isinstance(name, str):
        raise ParameterError("envelope.name", name, "must be a string")
    if "box" in env:
        boxes = env["box"]
        if not (isinstance(boxes, list) and boxes and all(isinstance(b, dict) for b in boxes)):
            raise ParameterError("envelope.box", boxes, "must be [[envelope.box]] tables")
        bx = tuple(box(b, f"envelope.box[{i}]") for i, b in enumerate(boxes))
    else:
        bx = (box(env, "envelope"),)
    return Envelope(name, tuple(names), bx, source=shown)


def state_batches(env: Envelope, variables: Sequence[Var], n_min: int, n_max: int) -> Any:
    """Hypothesis strategy: (N, n_vars) arrays of initial states of ``env``, N in [n_min,
    n_max] (no subnormal numbers: a witness is a state a person can read and type)."""
    from hypothesis import strategies as st

    def coord(i: int, lo: float, hi: float) -> Any:
        nz = variables[i].nonzero
        if env.scale(i) == "signed-log":
            mag = st.floats(math.log10(lo), math.log10(hi)).map(lambda u: float(10.0 ** u))
            signed = st.tuples(st.sampled_from([1.0, -1.0]), mag).map(lambda t: t[0] * t[1])
            return signed if nz else st.one_of(st.just(0.0), signed)
        if lo == hi:
            return st.just(float(lo))
        s = st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)
        return s.filter(lambda x: x != 0.0) if nz and lo <= 0.0 <= hi else s

    boxes = [st.tuples(*(coord(i, lo[i], hi[i]) for i in range(len(env.variables))))
             for lo, hi in env.boxes]
    row = boxes[0] if len(boxes) == 1 else st.one_of(*boxes)
    return st.lists(row, min_size=n_min, max_size=n_max).map(
        lambda rows: np.array(rows, dtype=float).reshape(len(rows), len(env.variables)))


# --- a witness: one state (and its extra fields), parsed without eval -----------------------

@dataclass(frozen=True)
class Witness:
    row: tuple[float, ...]
    extra: Mapping[str, Any] = field(default_factory=dict)


def parse_witness(text: str, variables: Sequence[Var], extras: Sequence[Extra] = ()
                  ) -> Witness:
    """``NAME=VALUE,NAME=VALUE,...`` with every state variable given once (and the optional
    extra fields); numbers are parsed by ``float`` (never evaluated), named errors otherwise."""
    names = [v.name for v in variables]
    kinds = {e.name: e.kind for e in extras}
    valid = ", ".join(names + [f"{e.name} (optional)" for e in extras])
    vals: dict[str, Any] = {}
    for item in str(text).split(","):
        item = item.strip()
        if not item:
            continue
        k, sep, v = item.partition("=")
        k, v = k.strip(), v.strip()
        if not sep or (k not in names and k not in kinds):
            raise ParameterError("--witness", item, f"NAME=VALUE items, NAME one of {valid}")
        if k in vals:
            raise ParameterError("--witness", item, f"{k} is given twice")
        kind = kinds.get(k, "float")
        if isinstance(kind, tuple):
            if v not in kind:
                raise ParameterError(f"--witness {k}", v, f"one of {', '.join(kind)}")
            vals[k] = v
            continue
        try:
            x = int(v) if kind == "int" else float(v)
        except ValueError:
            raise ParameterError(f"--witness {k}", v, "must be a number") from None
        if kind != "int" and not math.isfinite(x):
            raise ParameterError(f"--witness {k}", v, "must be a finite number")
        if kind == "int" and x < 0:
            raise ParameterError(f"--witness {k}", v, "must be an integer >= 0")
        vals[k] = x
    missing = [n for n in names if n not in vals]
    if missing:
        raise ParameterError("--witness", text, f"gives every state variable: missing "
                             f"{', '.join(missing)}")
    return Witness(tuple(float(vals[n]) for n in names),
                   {k: vals[k] for k in kinds if k in vals})


def format_witness(row: Sequence[float], extra: Mapping[str, Any],
                   variables: Sequence[Var]) -> str:
    """The ``--witness`` text of a state: exact (repr) numbers, so the reproduction flies the
    same state."""
    items = [f"{v.name}={float(x)!r}" for v, x in zip(variables, row, strict=True)]
    items += [f"{k}={v}" for k, v in extra.items()]
    return ",".join(items)


def state_text(row: Sequence[float], variables: Sequence[Var]) -> str:
    return ", ".join(f"{v.name} = {float(x):.6g} {v.unit}"
                     for v, x in zip(variables, row, strict=True))


# --- what a system's judge returns ------------------------------------------------------------

@dataclass
class Judged:
    """n judged cases of one claim, k values per case (axes; 1 for a scalar claim).

    ``observed`` is the measurement less ``tolerance`` (inf: never happened), ``bound`` the
    unscaled bound, ``informative`` whether the value can violate the claim, ``excluded`` per
    case why it could not be judged (None: judged), ``states`` the initial states flown
    (``extras``: their witness extras), ``fallback`` the cases a fallback integrator carried,
    ``reference`` the denominators where a bound is 0, ``notes`` why a value is a violation
    beyond the numbers (e.g. it left an invariant band)."""

    states: np.ndarray
    observed: np.ndarray
    bound: np.ndarray
    informative: np.ndarray
    excluded: Sequence[str | None]
    tolerance: float = 0.0
    extras: Sequence[Mapping[str, Any]] | None = None
    fallback: np.ndarray | None = None
    reference: np.ndarray | None = None
    notes: np.ndarray | None = None


@dataclass
class Computed:
    """A computed claim's record (module docstring): ``observed`` against ``bound`` (margin
    (bound - observed)/bound, over ``reference`` where the bound is 0), ``evidence`` "proven"
    or "sampled" with ``detail`` (how, over what), ``cases`` the sample size (0 for a proof),
    ``confirmed`` whether a violation is confirmed by ``recheck`` (an independent route; a
    proof re-done is its own confirmation), ``flags`` the extra arguments of the reproducing
    command, ``case`` the failing case's description (sampled evidence)."""

    observed: float
    bound: float
    evidence: str
    detail: str
    cases: int = 0
    confirmed: bool = True
    recheck: str = ""
    flags: tuple[str, ...] = ()
    case: str = ""
    reference: float | None = None

    def margin(self) -> float:
        ref = None if self.reference is None else np.array(self.reference)
        return float(margins(np.array(self.observed), np.array(self.bound), ref))

    def to_dict(self) -> dict[str, Any]:
        def num(x: float) -> float | None:
            return float(x) if x is not None and math.isfinite(x) else None

        return {"observed": num(self.observed), "bound": num(self.bound),
                "observed_infinite": bool(self.observed is not None
                                          and math.isinf(self.observed)),
                "margin": num(self.margin()), "evidence": self.evidence, "detail": self.detail,
                "cases": self.cases, "confirmed": self.confirmed, "recheck": self.recheck,
                "case": self.case}


def capped(bound: np.ndarray, cap: float | None) -> np.ndarray:
    return bound if cap is None else np.minimum(bound, cap)


def margins(observed: np.ndarray, bound: np.ndarray, reference: np.ndarray | None = None
            ) -> np.ndarray:
    """(bound - observed) / bound; where the bound is 0, over ``reference`` (or -inf / +inf
    by the sign of bound - observed when there is none); NaN where either is not a number."""
    obs = np.asarray(observed, float)
    bnd = np.asarray(bound, float)
    den = np.abs(bnd)
    if reference is not None:
        den = np.where(bnd != 0, den, np.abs(np.asarray(reference, float)))
    with np.errstate(divide="ignore", invalid="ignore"):
        m = (bnd - obs) / den
        m = np.where(den > 0, m, np.where(obs <= bnd, np.inf, -np.inf))
    m = np.where(np.isposinf(obs) & np.isfinite(bnd), -np.inf, m)
    return np.where(np.isnan(obs) | np.isnan(bnd) | np.isinf(bnd), np.nan, m)


@dataclass
class Tally:
    """Every case of one claim: counts, the worst informative margin, the worst violation,
    the points of the figure."""

    claim: Claim
    axes: tuple[str, ...]
    total: int = 0
    informative: int = 0
    fallback: int = 0
    excluded: dict[str, int] = field(default_factory=dict)
    examples: dict[str, list[float]] = field(default_factory=dict)  # a state per reason
    worst: dict[str, Any] | None = None
    violation: dict[str, Any] | None = None
    points: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = field(default_factory=list)

    def add(self, j: Judged, factor: float, cap: float | None = None
            ) -> tuple[float | None, dict[str, Any] | None]:
        """Count a batch (the bound multiplied by ``factor``, and at most ``cap``: a
        certificate's promise); returns its least informative margin (None: none) and its
        worst violation record (None: none)."""
        n = len(j.states)
        bnd = capped(np.asarray(j.bound, float).reshape(n, -1) * factor, cap)
        obs = np.asarray(j.observed, float).reshape(n, -1)
        ref = None if j.reference is None else np.asarray(j.reference, float).reshape(n, -1)
        m = margins(obs, bnd, ref)
        judged = np.array([e is None for e in j.excluded], bool)
        nonfinite = judged & np.any(np.isnan(m), axis=1)
        inf_ = np.asarray(j.informative, bool).reshape(n, -1)
        violating = judged[:, None] & (m < 0)
        useful = (inf_ & judged[:, None] & ~np.isnan(m)) | violating
        case_useful = useful.any(axis=1) & ~nonfinite
        self.total += n
        self.informative += int(case_useful.sum())
        if j.fallback is not None:
            self.fallback += int((np.asarray(j.fallback, bool) & judged).sum())
        for i in range(n):
            why = j.excluded[i]
            if why is None and nonfinite[i]:
                why = NONFINITE
            elif why is None and not case_useful[i]:
                why = f"cannot violate: {self.claim.uninformative}"
            if why is not None:
                self.excluded[why] = self.excluded.get(why, 0) + 1
                self.examples.setdefault(why, [float(x) for x in j.states[i]])
        sel = useful & case_useful[:, None]
        if sel.any():
            self.points.append((bnd[sel], obs[sel], m[sel] < 0))
        least = None
        if sel.any():
            i, a = np.unravel_index(int(np.argmin(np.where(sel, m, np.inf))), m.shape)
            least = float(m[i, a])
            rec = self._record(j, i, a, obs, bnd, m)
            if self.worst is None or least < self.worst["margin"]:
                self.worst = rec
        bad = None
        if violating.any():
            i, a = np.unravel_index(int(np.argmin(np.where(violating, m, np.inf))), m.shape)
            bad = self._record(j, i, a, obs, bnd, m)
            if self.violation is None or bad["margin"] < self.violation["margin"]:
                self.violation = bad
        return least, bad

    def _record(self, j: Judged, i: int, a: int, obs, bnd, m) -> dict[str, Any]:
        note = None if j.notes is None else np.asarray(j.notes, object).reshape(
            len(j.states), -1)[i, a]
        return {"claim": self.claim.name, "row": [float(x) for x in j.states[i]],
                "extra": dict(j.extras[i]) if j.extras is not None else {},
                "axis": self.axes[a] if len(self.axes) > 1 else None,
                "observed": float(obs[i, a]), "measured": float(obs[i, a]) + j.tolerance,
                "tolerance": j.tolerance, "bound": float(bnd[i, a]), "margin": float(m[i, a]),
                "note": note}

    def plot_points(self) -> dict[str, np.ndarray]:
        if not self.points:
            return {"bound": np.zeros(0), "observed": np.zeros(0), "violated": np.zeros(0, bool)}
        return {k: np.concatenate([p[i] for p in self.points])
                for i, k in enumerate(("bound", "observed", "violated"))}


# --- the record of one claim's outcome --------------------------------------------------------

@dataclass
class ClaimResult:
    """One claim's outcome, the same record for every system (the rows of the table, the
    ``claims`` of the JSON document, what the pytest plugin reports)."""

    claim: str
    equation: str
    observed: str
    bound: str
    unit: str
    verdict: str
    why: str = ""
    total: int = 0
    informative: int = 0
    excluded: dict[str, int] = field(default_factory=dict)
    excluded_examples: dict[str, list[float]] = field(default_factory=dict)
    min_cases: int = 0
    max_excluded: float = MAX_EXCLUDED
    margin: float | None = None
    worst: dict[str, Any] | None = None
    fallback: int = 0
    scale: float = 1.0
    promise: dict[str, Any] | None = None
    search: list[dict[str, Any]] = field(default_factory=list)
    witness: dict[str, Any] | None = None
    reproduction: str | None = None
    message: str = ""
    points: dict[str, Any] = field(default_factory=dict, repr=False)
    evidence: str = "sampled"  # how this row is known: "sampled" (a campaign), "proven"
    check: dict[str, Any] | None = None  # a computed claim's record (Computed.to_dict)

    @property
    def n_excluded(self) -> int:
        return sum(self.excluded.values())

    @property
    def excluded_share(self) -> float:
        return self.n_excluded / self.total if self.total else 0.0

    @property
    def search_margin(self) -> float | None:
        vals = [s["best_margin"] for s in self.search if s.get("best_margin") is not None]
        return min(vals) if vals else None

    def explain(self) -> str:
        """Why the claim is not ``holds``, in a few lines (a failure's message names the
        observed value, the bound, the state, the gains and the reproduction)."""
        if self.message:
            return self.message
        lines = [f"{self.claim} {self.equation}: {self.verdict}: {self.why}"]
        lines += [f"  {n} of {self.total} excluded: {why}" for why, n in self.excluded.items()]
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        return {"claim": self.claim, "equation": self.equation, "verdict": self.verdict,
                "why": self.why, "observed": self.observed, "bound": self.bound,
                "unit": self.unit, "cases": {"total": self.total,
                                             "informative": self.informative,
                                             "excluded": self.n_excluded,
                                             "excluded_reasons": dict(self.excluded),
                                             "excluded_examples": dict(self.excluded_examples),
                                             "fallback": self.fallback},
                "min_cases": self.min_cases, "max_excluded": self.max_excluded,
                "margin": self.margin, "worst": self.worst, "scale": self.scale,
                "promise": self.promise, "search": self.search, "witness": self.witness,
                "reproduction": self.reproduction, "message": self.message,
                "evidence": self.evidence, "check": self.check}


def decide(r: ClaimResult, na: str | None, found: dict[str, Any] | None,
           search_refuted: bool) -> None:
    """Set ``r.verdict`` and ``r.why`` from the evidence (see the module docstring)."""
    if na is not None:
        r.verdict, r.why = "not-applicable", f"not applicable, because {na}"
    elif search_refuted or (found is not None and found.get("confirmed")):
        r.verdict = "violated"
        r.why = r.why or "a confirmed case over its bound"
    elif found is not None:
        r.verdict = "inconclusive"
        r.why = (f"a violation at the campaign's resolution (margin {found['margin']:.4g}) "
                 f"that the re-check does not confirm ({found.get('recheck_method', '')}: "
                 f"margin {_g(found.get('rechecked_margin'))})")
    elif r.informative < r.min_cases:
        r.verdict = "inconclusive"
        r.why = (f"{r.informative} informative cases < --min-cases {r.min_cases} "
                 f"({r.n_excluded} of {r.total} excluded)")
    elif r.excluded_share > r.max_excluded:
        r.verdict = "inconclusive"
        r.why = (f"{r.n_excluded} of {r.total} cases excluded ({r.excluded_share:.0%} > "
                 f"--max-excluded {r.max_excluded:.0%})")
    else:
        r.verdict = "holds"
        r.why = ""


def exit_code(results: Sequence[ClaimResult]) -> int:
    """1 when a claim is violated, else 4 when one is inconclusive, else 0."""
    found = {r.verdict for r in results}
    for v in ("violated", "inconclusive"):
        if v in found:
            return VERIFY_EXIT[v]
    return VERIFY_EXIT["holds"]


SIMPLIFY_FLIGHTS = 40  # most flights spent on rounding a witness


def _u(claim: Claim) -> str:
    return f" {claim.unit}" if claim.unit else ""


def _g(x: Any, spec: str = ".4g") -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return format(x, spec) if isinstance(x, int | float) else str(x)


# --- the options every lgw verify SYSTEM takes --------------------------------------------------

def claim_option(names: Sequence[str]) -> Any:
    return option("--claim", choice(tuple(names)), (), "check only this claim (repeatable) "
                  "[default: every claim]", multiple=True, probe=(tuple(names)[0],))


def scale_option(names: Sequence[str]) -> Any:
    """``--scale`` of the vocabulary, with this system's claims in the help and a probe."""
    from lgw.tuning.options import ScaleItem

    return option("--scale", ScaleItem(), (), "CLAIM=FACTOR: multiply a claim's bound (the "
                  f"checker's self-test; repeatable; CLAIM one of {', '.join(names)}) "
                  "[default: none]", multiple=True, probe=((tuple(names)[0], 0.5),))


def witness_option(variables: Sequence[Var], extras: Sequence[Extra], probe: str) -> Any:
    fields_ = ", ".join(f"{v.name} ({v.unit})" for v in variables)
    more = "".join(f"; optional {e.name}: {e.text}" for e in extras)
    return option("--witness", None, None, f"fly this one initial state instead of a campaign "
                  f"(how a failure is reproduced): NAME=VALUE,... with {fields_}{more}",
                  probe=probe, metavar="STATE")


@dataclass(frozen=True)
class VerifyOptions(V.VerifyRun):
    """The options of every ``lgw verify SYSTEM``: the shared run options
    (``vocabulary.VerifyRun``), the gain set, the domain searched, the exclusion limit and the
    outputs.  A system's subclass adds ``claim`` and ``witness`` (``claim_option``,
    ``witness_option``), its own settings, and the class attributes below."""

    SPEC: ClassVar[str] = ""  # import path of the system's judge (lgw.tuning.<s>.verify)
    CLAIMS: ClassVar[Mapping[str, Claim]] = {}
    VARIABLES: ClassVar[tuple[Var, ...]] = ()
    EXTRAS: ClassVar[tuple[Extra, ...]] = ()
    PROFILES: ClassVar[Mapping[str, int]] = {"ci": 10, "thorough": 60}  # examples per group
    SETTINGS: ClassVar[tuple[str, ...]] = ()  # the system's own fields that set the check

    gains: Path | None = V.gains()
    domain: str = option("--domain", choice(DOMAINS), "envelope",
                         "envelope: the initial states of the envelope (--envelope, the gains "
                         "file's certificate, or the paper's); whole: the whole domain the "
                         "simulator carries (decades of magnitudes, both signs)")
    envelope: Path | None = option("--envelope", FILE, None, "envelope TOML ([envelope] with "
                                   "VAR = [lo, hi] per state variable, docs/verify.md) "
                                   "[default: the gains file's certificate, else the paper's]",
                                   probe=NO_PROBE)
    max_excluded: float = option("--max-excluded", Number(0, 1), MAX_EXCLUDED,
                                 "largest share of excluded cases (not judged, or unable to "
                                 "violate the claim) that still allows 'holds'")
    json: bool = V.json_flag()
    plot: Path | None = V.plot_dir("verify_<system>.png, observed against bound, one point "
                                   "per informative case and axis")

    def check(self) -> None:
        super().check()
        for name, _f in self.scale:
            if name not in self.CLAIMS:
                raise ParameterError("--scale", name, f"CLAIM=FACTOR with CLAIM one of "
                                     f"{', '.join(self.CLAIMS)}")
        if len({n for n, _ in self.scale}) != len(self.scale):
            raise ParameterError("--scale", dict(self.scale), "one factor per claim")
        w = getattr(self, "witness", None)
        if w is not None:
            parse_witness(w, self.VARIABLES, self.EXTRAS)
            why = "does not apply with --witness (that one state is flown, nothing is drawn)"
            for name in ("profile", "examples", "random", "database", "domain", "envelope"):
                self.refuse_unless(False, name, why)
            self.refuse_unless(False, "seed", why)
        self.refuse_unless(self.domain == "envelope", "envelope",
                           "does not apply with --domain whole (the whole domain is searched)")

    def settings(self) -> dict[str, Any]:
        return {k: getattr(self, k) for k in self.SETTINGS}


def verify_options(spec: str, claims: Mapping[str, Claim], variables: Sequence[Var],
                   witness: str, profiles: Mapping[str, int], extras: Sequence[Extra] = (),
                   module: str = __name__) -> type[VerifyOptions]:
    """A system's verify options class: ``VerifyOptions`` with its judge (``spec``, import
    path), claims (``--claim``, ``--scale``), state variables and witness extras
    (``--witness``; ``witness`` a valid one, for the options test) and Hypothesis examples
    per profile.  A system with settings of its own subclasses the result."""
    ns: dict[str, Any] = {
        "__module__": module, "__qualname__": "Options",
        "__annotations__": {"claim": "tuple", "scale": "tuple", "witness": "str | None"},
        "SPEC": spec, "CLAIMS": claims, "VARIABLES": tuple(variables),
        "EXTRAS": tuple(extras), "PROFILES": dict(profiles),
        "claim": claim_option(claims), "scale": scale_option(claims),
        "witness": witness_option(variables, extras, witness)}
    return dataclass(frozen=True)(type("Options", (VerifyOptions,), ns))


# --- plan: options -> job --------------------------------------------------------------------

def plan(opts: VerifyOptions, system: Any) -> VerifyJob:
    """Resolve the options into the inputs of the computation (shared by every system)."""
    from lgw.theory.inputs import load_toml

    spec = importlib.import_module(opts.SPEC)
    gains = system.gains_module().resolve(opts.gains)
    shown = str(opts.gains) if opts.gains is not None else "the built-in gain set"
    cert = None if opts.gains is None else certificate(load_toml(opts.gains, "--gains"), shown)
    if opts.gains is None and hasattr(spec, "builtin_gains"):  # e.g. the eros descent's own
        gains = spec.builtin_gains(opts.settings()) or gains
    promises = spec.promises(gains, cert, shown)
    na = dict(spec.not_applicable(gains, cert, opts.settings()))
    if opts.domain == "whole":
        env = spec.whole_domain()
    elif opts.envelope is not None:
        env = read_envelope(opts.envelope, opts.VARIABLES, spec.default_envelope(None, None))
    else:
        env = spec.default_envelope(gains, cert)
    witness = getattr(opts, "witness", None)
    # a system may offer a subset by its settings (eros: the tracking or the descent claims)
    offered = spec.claims_for(opts.settings()) if hasattr(spec, "claims_for") else opts.CLAIMS
    chosen = set(getattr(opts, "claim", ()) or offered)
    claims = tuple(c for c in opts.CLAIMS if c in chosen)
    examples = opts.examples or opts.PROFILES[opts.profile]
    flags = []
    for f in opts.SETTINGS:
        if opts.given(f):
            flag = next(o.flag for fl, o in _fields(opts) if fl.name == f)
            val = getattr(opts, f)
            flags.append(f"{flag} {val!r}" if isinstance(val, float) else f"{flag} {val}")
    return VerifyJob(system=system.name, spec=opts.SPEC, gains=gains,
                     gains_path=None if opts.gains is None else str(opts.gains),
                     settings=opts.settings(), certificate=cert, claims=claims,
                     not_applicable=na,
                     promises=promises, scale=dict(opts.scale), domain=opts.domain,
                     envelope=env,
                     witness=None if witness is None else parse_witness(
                         witness, opts.VARIABLES, opts.EXTRAS),
                     examples=examples, seed=opts.run_seed, database=opts.database,
                     min_cases=opts.min_cases, max_excluded=opts.max_excluded,
                     profile=opts.profile, repro_flags=tuple(flags), plot=opts.plot is not None)


def _fields(opts: Any) -> Any:
    from lgw.tuning.spec import option_fields

    return option_fields(opts)


@dataclass(frozen=True)
class Context:
    """What a system's judge and search see: the gain set, the system's settings, the bound
    factors of --scale (a judge sizes its horizons with them), the campaign seed, and ``fine``
    (the re-check: the system's finer, independent route)."""

    gains: Any
    settings: Mapping[str, Any]
    factors: Mapping[str, float]
    seed: int
    fine: bool = False
    certificate: Mapping[str, Any] | None = None
    caps: Mapping[str, float] = field(default_factory=dict)  # a certificate's promises

    def replace(self, **kw: Any) -> Context:
        from dataclasses import replace

        return replace(self, **kw)


@dataclass(frozen=True)
class VerifyJob(Job):
    system: str
    spec: str
    gains: Any
    gains_path: str | None
    settings: Mapping[str, Any]
    certificate: Mapping[str, Any] | None
    claims: tuple[str, ...]
    not_applicable: Mapping[str, str]
    promises: Mapping[str, Mapping[str, Any]]
    scale: Mapping[str, float]
    domain: str
    envelope: Envelope
    witness: Witness | None
    examples: int
    seed: int | None
    database: Path | None
    min_cases: int
    max_excluded: float
    profile: str
    repro_flags: tuple[str, ...] = ()
    plot: bool = field(default=False, metadata={"fingerprint": False})

    def factor(self, claim: str) -> float:
        return float(self.scale.get(claim, 1.0))

    def cap(self, claim: str) -> float | None:
        p = self.promises.get(claim)
        return None if p is None else float(p["value"])

    def run(self, progress: Any) -> Outcome:
        results, timings = self.check(progress)
        return self._outcome(importlib.import_module(self.spec), results, timings)

    def check(self, progress: Any) -> tuple[list[ClaimResult], dict[str, float]]:
        """Every selected claim's ``ClaimResult`` and the seconds each phase took."""
        spec = importlib.import_module(self.spec)
        claims: Mapping[str, Claim] = spec.CLAIMS
        active = [c for c in self.claims if c not in self.not_applicable
                  and claims[c].kind == "campaign"]
        computed = [c for c in self.claims if c not in self.not_applicable
                    and claims[c].kind == "computed"]
        ctx = Context(self.gains, self.settings, {c: self.factor(c) for c in claims},
                      self.seed or 0, certificate=self.certificate,
                      caps={c: v for c in claims if (v := self.cap(c)) is not None})
        tallies = {c: Tally(claims[c], spec.AXES) for c in active}
        found: dict[str, dict[str, Any]] = {}
        groups = [g for g in dict.fromkeys(claims[c].group for c in active)]
        timings: dict[str, float] = {}
        t_start = time.perf_counter()
        for group in groups:
            t0 = time.perf_counter()
            if self.witness is not None:
                progress.stage(f"flying the witness ({group})")
                X = np.array([self.witness.row], float)
                judged = spec.judge(ctx, group, X, [dict(self.witness.extra)])
                for c, j in judged.items():
                    if c in tallies:
                        _, bad = tallies[c].add(j, self.factor(c), self.cap(c))
                        if bad is not None and c not in found:
                            found[c] = bad
            else:
                progress.stage(f"simulating {group}: {self.examples} Hypothesis examples")
                rec = self._campaign(spec, ctx, group, tallies)
                if rec is not None:
                    found[rec["claim"]] = rec
                # Hypothesis shrinks one failure per group; another claim's violation seen on
                # the way is kept as flown (and rounded by _simplify)
                for c in claims:
                    if claims[c].group == group and c in tallies and c not in found and \
                            tallies[c].violation is not None:
                        found[c] = tallies[c].violation
            timings[f"simulate {group}"] = round(time.perf_counter() - t0, 2)
        searches: dict[str, list[dict[str, Any]]] = {}
        if self.witness is None and hasattr(spec, "search"):
            for c in active:
                t0 = time.perf_counter()
                progress.stage(f"searching {c}")
                searches[c] = spec.search(ctx, c, None if self.domain == "whole"
                                          else self.envelope, self.profile)
                timings[f"search {c}"] = round(time.perf_counter() - t0, 2)
        records: dict[str, Computed] = {}
        if computed:
            t0 = time.perf_counter()
            progress.stage(f"computing {', '.join(computed)}")
            records = dict(spec.compute(ctx, computed, progress))
            timings["compute"] = round(time.perf_counter() - t0, 2)
        results = []
        for c in self.claims:
            if claims[c].kind == "computed":
                results.append(self._computed(spec, claims[c], records.get(c)))
                continue
            t0 = time.perf_counter()
            results.append(self._result(spec, ctx, claims[c], tallies.get(c), found.get(c),
                                        searches.get(c, []), progress))
            if c in found or any(s.get("status") == "refuted" for s in searches.get(c, [])):
                timings[f"re-check {c}"] = round(time.perf_counter() - t0, 2)
        timings["total"] = round(time.perf_counter() - t_start, 2)
        return results, timings

    def _campaign(self, spec: Any, ctx: Context, group: str, tallies: dict[str, Tally]
                  ) -> dict[str, Any] | None:
        from hypothesis import target
        from lgw.testing.engine import run_property

        def check(example: np.ndarray) -> dict[str, Any] | None:
            judged = spec.judge(ctx, group, np.asarray(example, float))
            worst = None
            for c, j in judged.items():
                if c not in tallies:
                    continue
                least, bad = tallies[c].add(j, self.factor(c), self.cap(c))
                if least is not None and math.isfinite(least):
                    target(-least, label=c)
                if bad is not None and (worst is None or bad["margin"] < worst["margin"]):
                    worst = bad
            return worst

        strategy = state_batches(self.envelope, spec.VARIABLES, *spec.BATCH)
        return run_property(strategy, check, examples=self.examples, seed=self.seed,
                            database=self.database, key=f"{self.system}/{group}")

    def _result(self, spec: Any, ctx: Context, claim: Claim, tally: Tally | None,
                found: dict[str, Any] | None, search: list[dict[str, Any]],
                progress: Any) -> ClaimResult:
        na = self.not_applicable.get(claim.name)
        r = ClaimResult(claim.name, claim.equation, claim.observed, claim.bound, claim.unit,
                        "inconclusive", min_cases=self.min_cases,
                        max_excluded=self.max_excluded,
                        scale=float(self.scale.get(claim.name, 1.0)),
                        promise=dict(self.promises[claim.name])
                        if claim.name in self.promises else None, search=search)
        if tally is not None:
            r.total, r.informative, r.fallback = tally.total, tally.informative, tally.fallback
            r.excluded = dict(tally.excluded)
            r.excluded_examples = dict(tally.examples)
            r.worst = tally.worst
            r.margin = tally.worst["margin"] if tally.worst else None
            r.points = tally.plot_points()
        refuted = [s for s in search if s.get("status") == "refuted"]
        if na is None and found is not None:
            progress.stage(f"simplifying the witness of {claim.name}")
            found = self._simplify(spec, ctx, claim, found)
            progress.stage(f"re-checking the witness of {claim.name}")
            fine = self._fly(spec, ctx.replace(fine=True), claim, found["row"],
                             found["extra"], axis=found["axis"])
            found["rechecked_margin"] = None if fine is None else fine["margin"]
            found["rechecked_observed"] = None if fine is None else fine["observed"]
            found["recheck_method"] = spec.RECHECK
            found["confirmed"] = bool(fine is not None and fine["margin"] < 0)
            r.witness = found
            r.reproduction = self._reproduction(claim.name, found["row"], found["extra"])
            r.why = (f"observed {_g(found['observed'], '.6g')}{_u(claim)} > bound "
                     f"{_g(found['bound'], '.6g')}{_u(claim)} (margin {found['margin']:.4g});"
                     f" re-checked by {spec.RECHECK}: margin {_g(found['rechecked_margin'])}")
            if refuted:
                r.why += f"; the search refutes it too (best margin {r.search_margin:.4g})"
            r.message = self._message(spec, claim, found, r)
        elif na is None and refuted:
            s = refuted[0]
            w = s["witness"]
            progress.stage(f"flying the search witness of {claim.name}")
            sim = self._fly(spec, ctx, claim, w["row"], w.get("extra", {}), axis=w["axis"])
            r.witness = {**w, "simulated": sim}
            r.reproduction = self._reproduction(claim.name, w["row"], w.get("extra", {}))
            r.why = (f"search witness on axis {s.get('axis')}: margin {w['margin']:.4g} on "
                     f"{s.get('route', 'the fast route')}, re-checked "
                     f"{_g(w['rechecked_margin'])} by {w['recheck_method']}")
            resolved = sim is not None and sim["margin"] < 0
            r.message = self._message(
                spec, claim, sim if sim is not None else {**w, "observed": None}, r,
                extra_line=None if resolved else "the simulator does not show this violation "
                "at this step (it is within the check's tolerance, or needs the search's "
                "disturbance a_p = +a_max sgn(s2)): the reduced-loop search and its re-check "
                "found it")
        decide(r, na, found, bool(refuted) and na is None)
        if r.verdict == "not-applicable":
            r.evidence = ""
        if r.verdict == "inconclusive" and found is not None and not found.get("confirmed"):
            r.message = r.message or r.why
        return r

    def _computed(self, spec: Any, claim: Claim, comp: Computed | None) -> ClaimResult:
        """A computed claim's ClaimResult from its record (module docstring)."""
        from dataclasses import replace

        na = self.not_applicable.get(claim.name)
        r = ClaimResult(claim.name, claim.equation, claim.observed, claim.bound, claim.unit,
                        "inconclusive", min_cases=self.min_cases,
                        max_excluded=self.max_excluded, scale=self.factor(claim.name),
                        evidence="")
        if na is not None or comp is None:
            decide(r, na or "the system computed nothing for it", None, False)
            return r
        if r.scale != 1.0:
            comp = replace(comp, bound=comp.bound * r.scale)
        m = comp.margin()
        r.evidence, r.check = comp.evidence, comp.to_dict()
        r.total = r.informative = comp.cases if comp.evidence == "sampled" else 1
        r.margin = None if math.isnan(m) else m
        r.worst = {"observed": r.check["observed"], "bound": r.check["bound"], "margin": r.margin,
                   "case": comp.case}
        r.reproduction = self._reproduction(claim.name, None, {}, comp.flags)
        if math.isnan(m):
            r.why = NONFINITE
        elif m < 0:
            r.verdict = "violated" if comp.confirmed else "inconclusive"
            r.why = (f"observed {_g(comp.observed, '.6g')}{_u(claim)} > bound "
                     f"{_g(comp.bound, '.6g')}{_u(claim)} (margin {m:.4g}), {comp.evidence}"
                     + (f"; re-checked: {comp.recheck}" if comp.recheck else "")
                     + ("" if comp.confirmed else "; the re-check does not confirm it"))
            r.message = self._computed_message(spec, claim, comp, r, m)
        elif comp.evidence == "sampled" and comp.cases < self.min_cases:
            r.why = f"{comp.cases} cases < --min-cases {self.min_cases}"
        else:
            r.verdict, r.why = "holds", ""
        return r

    def _computed_message(self, spec: Any, claim: Claim, comp: Computed, r: ClaimResult,
                          m: float) -> str:
        sc = f" x {r.scale:g} (--scale)" if r.scale != 1.0 else ""
        lines = [f"{claim.name} {claim.equation}: {r.why}",
                 f"  observed: {claim.observed} = {_g(comp.observed, '.6g')}{_u(claim)}",
                 f"  bound: {claim.bound}{sc} = {_g(comp.bound, '.6g')}{_u(claim)}; margin "
                 f"(bound - observed)/bound = {m:.4g}",
                 f"  evidence: {comp.evidence}: {comp.detail}"]
        if comp.case:
            lines.append(f"  case: {comp.case}")
        lines.append(f"  gains: {self.gains_path or 'the built-in gain set'} ("
                     f"{spec.gains_text(self.gains, None)})")
        lines.append(f"  reproduce: {r.reproduction}")
        return "\n".join(lines)

    def _fly(self, spec: Any, ctx: Context, claim: Claim, row: Sequence[float],
             extra: Mapping[str, Any], axis: str | None = None) -> dict[str, Any] | None:
        """One state through the system's judge: its record for ``claim`` on ``axis`` (None:
        its worst axis); None if the case could not be judged."""
        j = spec.judge(ctx, claim.group, np.array([row], float), [dict(extra)])[claim.name]
        if j.excluded[0] is not None:
            return None
        obs = np.asarray(j.observed, float).reshape(1, -1)
        bnd = capped(np.asarray(j.bound, float).reshape(1, -1) * self.factor(claim.name),
                     self.cap(claim.name))
        ref = None if j.reference is None else np.asarray(j.reference, float).reshape(1, -1)
        m = margins(obs, bnd, ref)
        if np.isnan(m).all():
            return None
        a = list(spec.AXES).index(axis) if axis is not None and len(spec.AXES) > 1 else \
            int(np.nanargmin(m[0]))
        return Tally(claim, spec.AXES)._record(j, 0, a, obs, bnd, m)

    def _simplify(self, spec: Any, ctx: Context, claim: Claim, rec: dict[str, Any],
                  budget: int = SIMPLIFY_FLIGHTS) -> dict[str, Any]:
        """Round the witness's coordinates to the simplest values (0, then 1, 2, ... significant
        digits) that keep the violation at or below half its margin, inside the envelope: what
        Hypothesis' capped shrinking leaves (a 2.1e-119 on an axis that plays no part) becomes
        a state a person reads and types.  At most ``budget`` flights."""
        from lgw.theory.falsify import _roundings as roundings  # the falsifier's rounding

        if self.witness is not None:
            return rec
        keep = 0.5 * rec["margin"]
        best = dict(rec)
        flights = 0
        for i, var in enumerate(spec.VARIABLES):
            for y in roundings(best["row"][i]):
                if flights >= budget:
                    return best
                if (var.nonzero and y == 0.0) or self.domain == "envelope" and not \
                        self.envelope.contains(best["row"][:i] + [y] + best["row"][i + 1:]):
                    continue
                row = list(best["row"])
                row[i] = y
                flights += 1
                got = self._fly(spec, ctx, claim, row, best["extra"])
                if got is not None and got["margin"] < 0 and got["margin"] <= keep:
                    best = {**rec, **got}
                    break
        return best

    def _reproduction(self, claim: str, row: Sequence[float] | None,
                      extra: Mapping[str, Any], flags: Sequence[str] = ()) -> str:
        """``lgw verify SYSTEM [--gains F] --claim C`` with the witness state (campaign
        claims; None: a computed claim), the scale, the settings given and ``flags``."""
        spec = importlib.import_module(self.spec)
        parts = ["lgw", "verify", self.system]
        if self.gains_path is not None:
            parts += ["--gains", self.gains_path]
        parts += ["--claim", claim]
        if row is not None:
            parts += ["--witness", format_witness(row, extra, spec.VARIABLES)]
        parts += list(flags)
        for name, f in self.scale.items():
            if name == claim:
                parts += ["--scale", f"{name}={f!r}"]
        cmd = " ".join(shlex.quote(p) for p in parts)
        for fl in self.repro_flags:
            flag, _, val = fl.partition(" ")
            if flag not in flags:  # a computed claim's flags give their own value
                cmd += f" {flag} {shlex.quote(val)}"
        return cmd

    def _message(self, spec: Any, claim: Claim, rec: Mapping[str, Any], r: ClaimResult,
                 extra_line: str | None = None) -> str:
        ax = f" on axis {rec['axis']}" if rec.get("axis") else ""
        lines = [f"{claim.name} {claim.equation}: {r.why}"]
        if rec.get("observed") is not None:
            tol = (f" (measured {_g(rec['measured'], '.6g')} less the tolerance "
                   f"{_g(rec['tolerance'], '.3g')}: {claim.tolerance})"
                   if rec.get("tolerance") else "")
            lines.append(f"  observed: {claim.observed} = {_g(rec['observed'], '.6g')}"
                         f"{_u(claim)}{tol}{ax}")
            sc = f" x {r.scale:g} (--scale)" if r.scale != 1.0 else ""
            src = (f", capped by the certificate's promise {r.promise['text']}" if r.promise
                   else "")
            lines.append(f"  bound: {claim.bound}{sc}{src} = {_g(rec['bound'], '.6g')}"
                         f"{_u(claim)}; margin (bound - observed)/bound = {rec['margin']:.4g}")
        if rec.get("note"):
            lines.append(f"  {rec['note']}")
        lines.append(f"  state: {state_text(rec['row'], spec.VARIABLES)}"
                     + "".join(f", {k} = {v}" for k, v in dict(rec.get("extra", {})).items()))
        lines.append(f"  gains: {self.gains_path or 'the built-in gain set'} ("
                     f"{spec.gains_text(self.gains, rec.get('axis'))})")
        if extra_line:
            lines.append(f"  note: {extra_line}")
        lines.append(f"  reproduce: {r.reproduction}")
        return "\n".join(lines)

    # --- output ---------------------------------------------------------------------------

    def _outcome(self, spec: Any, results: list[ClaimResult], timings: dict[str, float]
                 ) -> Outcome:
        code = exit_code(results)
        doc = {"profile": self.profile if self.witness is None else None,
               "seed": self.seed if self.witness is None else None,
               "examples": self.examples if self.witness is None else None,
               "domain": self.domain if self.witness is None else "witness",
               "envelope": self.envelope.to_dict() if self.witness is None else None,
               "witness": None if self.witness is None else format_witness(
                   self.witness.row, self.witness.extra, spec.VARIABLES),
               "settings": dict(self.settings), "min_cases": self.min_cases,
               "max_excluded": self.max_excluded, "scale": dict(self.scale),
               "margin": "(bound - observed) / bound; negative: violated",
               "claims": [r.to_dict() for r in results],
               "verdicts": {v: sum(r.verdict == v for r in results) for v in VERDICTS},
               "seconds": timings, "exit_code": code}
        figures = []
        if self.plot:
            from lgw.tuning.figures import observed_vs_bound
            from lgw.tuning.system import Figure

            panels = [{"claim": r.claim, "equation": r.equation, "unit": r.unit,
                       "excluded": r.n_excluded, **r.points}
                      for r in results if r.verdict != "not-applicable" and r.points]
            if panels:
                png = observed_vs_bound(panels, self._title())
                figures.append(Figure(f"verify_{self.system}.png",
                                      f"lgw verify {self.system}: observed against bound", png))
        return Outcome(doc, render=lambda con: self._render(con, results, timings),
                       figures=figures, exit_code=code)

    def _title(self) -> str:
        if self.witness is not None:
            return f"lgw verify {self.system}: one witness state"
        seed = "random" if self.seed is None else f"seed {self.seed}"
        return (f"lgw verify {self.system}: profile {self.profile}, {seed}, "
                f"{self.examples} examples per group, domain {self.domain}")

    def _render(self, con: Any, results: list[ClaimResult], timings: dict[str, float]) -> None:
        from lgw.tuning.tables import result_table

        spec_vars = importlib.import_module(self.spec).VARIABLES
        def p(s: str) -> None:
            con.print(s, markup=False, highlight=False, soft_wrap=True)

        with_search = any(r.search for r in results)
        cols = ["claim", "eq.", "evidence", "informative", "excluded", "total", "worst margin"]
        cols += ["search margin"] if with_search else []
        cols += ["verdict"]
        rows, styles = [], []
        for r in results:
            row = [r.claim, r.equation, r.evidence or "-", str(r.informative),
                   str(r.n_excluded), str(r.total), _g(r.margin)]
            row += [_g(r.search_margin)] if with_search else []
            rows.append(row + [r.verdict])
            styles.append({"holds": None, "violated": "red", "not-applicable": "dim"}.get(
                r.verdict, "yellow"))
        result_table(con, self._title(), cols, rows, styles=styles)
        if self.witness is None and any(r.check is None and r.verdict != "not-applicable"
                                        for r in results):  # a campaign flew the envelope
            p(f"envelope: {self.envelope.name}: {self.envelope.describe()}")
        p(f"margin = (bound - observed)/bound, < 0 violates; holds needs >= {self.min_cases} "
          f"informative cases (a case that can violate the claim) and at most "
          f"{self.max_excluded:.0%} excluded")
        for r in results:
            for why, n in r.excluded.items():
                ex = r.excluded_examples.get(why)
                p(f"{r.claim}: {n} excluded: {why}"
                  + (f" (e.g. {state_text(ex, spec_vars)})" if ex is not None else ""))
            if r.fallback:
                p(f"{r.claim}: {r.fallback} cases carried by the fallback integrator")
            if r.search:
                best = min(r.search, key=lambda s: s["best_margin"])
                bad = sum(s["status"] == "refuted" for s in r.search)
                p(f"{r.claim}: search: {len(r.search)} runs (axis x box x problem), "
                  f"{sum(s['evaluations'] for s in r.search)} evaluations, best margin "
                  f"{_g(best['best_margin'])} (axis {best.get('axis')}, "
                  f"{best.get('domain_name', '')}), " + (f"{bad} refuted" if bad else
                                                          "none refuted"))
            if r.promise:
                p(f"{r.claim}: checked against the certificate's promise {r.promise['text']}")
            if r.check is not None and not r.message:
                p(f"{r.claim}: {r.evidence}: {r.check['detail']}")
            if r.message:
                p(r.message)
            elif r.verdict == "not-applicable":
                p(f"{r.claim}: {r.why}")
            elif r.why:
                p(f"{r.claim}: {r.verdict}: {r.why}")
        parts = ", ".join(f"{k} {v:.1f} s" for k, v in timings.items() if k != "total")
        p(f"{timings.get('total', 0.0):.1f} s" + (f" ({parts})" if parts else ""))


# --- certificates: every value verify reads is checked by name ------------------------------

def certificate(document: Mapping[str, Any] | None, shown: str) -> dict[str, Any] | None:
    """The [certificate] table of a gains document (None: none); a non-table is a named
    error."""
    cert = (document or {}).get("certificate")
    if cert is None:
        return None
    if not isinstance(cert, dict):
        raise ParameterError(f"--gains {shown} certificate", cert, "must be a table "
                             "[certificate]")
    return cert


def cert_number(cert: Mapping[str, Any], key: str, shown: str, valid: str = "a finite "
                "number > 0", lo: float = 0.0, lo_open: bool = True) -> float | None:
    """``cert[key]`` as a float (None when absent); a string, list, bool or non-finite value,
    or one outside the range, is a ParameterError naming ``certificate.KEY``."""
    if key not in cert:
        return None
    v = cert[key]
    name = f"--gains {shown} certificate.{key}"
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise ParameterError(name, v, f"must be {valid}")
    x = float(v)
    if not math.isfinite(x) or (x <= lo if lo_open else x < lo):
        raise ParameterError(name, v, f"must be {valid}")
    return x


def cert_list(cert: Mapping[str, Any], key: str, shown: str, length: int | None = None
              ) -> list[Any] | None:
    if key not in cert:
        return None
    v = cert[key]
    if not isinstance(v, list) or (length is not None and len(v) != length):
        raise ParameterError(f"--gains {shown} certificate.{key}", v,
                             "must be a list" + (f" of {length} items" if length else ""))
    return v


# --- the library entry point (lgw.testing and the pytest plugin) --------------------------------

def run_checks(system: str, gains: Any = None, **options: Any) -> list[ClaimResult]:
    """``lgw verify SYSTEM``'s checks from Python: ``gains`` a path (str or Path), a gain-set
    object of the system, or None (the built-in set); ``options`` the fields of the system's
    verify options (``profile``, ``seed``, ``examples``, ``min_cases``, ``max_excluded``,
    ``database``, ``domain``, ``envelope``, ``claim`` (a name or a sequence), ``witness``,
    ``scale`` (a mapping claim -> factor), and the system's own settings).  Returns the
    ``ClaimResult`` records ``lgw verify`` prints; bad options are a ParameterError."""
    from dataclasses import replace

    from lgw.tuning.progress import Silent

    sysobj, mod, opts = _options(system, gains, options)
    obj = None if gains is None or isinstance(gains, str | Path) else gains
    job = mod.plan(opts, sysobj)
    if obj is not None:  # a gain set given as an object: no file, no certificate
        spec = importlib.import_module(job.spec)
        env = job.envelope if opts.domain == "whole" or opts.envelope is not None else \
            spec.default_envelope(obj, None)
        job = replace(job, gains=obj, not_applicable=dict(spec.not_applicable(
            obj, None, opts.settings())), promises=spec.promises(obj, None, "<gains object>"),
            envelope=env)
    return job.check(Silent())[0]


def _options(system: str, gains: Any, options: Mapping[str, Any]) -> tuple[Any, Any, Any]:
    """(the system, its verify module, its Options) from Python values (``run_checks``)."""
    from lgw.tuning.system import get_system

    sysobj = get_system(system)
    mod = sysobj.verb("verify").load()
    kw = dict(options)
    if isinstance(kw.get("scale"), Mapping):
        kw["scale"] = tuple(kw["scale"].items())
    if isinstance(kw.get("claim"), str):
        kw["claim"] = (kw["claim"],)
    for k in ("database", "envelope"):
        if kw.get(k) is not None:
            kw[k] = Path(kw[k])
    obj = None if gains is None or isinstance(gains, str | Path) else gains
    path = None if gains is None or obj is not None else Path(gains)
    try:
        opts = mod.Options(gains=path, **kw)
    except TypeError as e:
        raise ParameterError(f"lgw verify {system} option", sorted(kw), str(e)) from None
    return sysobj, mod, opts


def offered_claims(system: str, **options: Any) -> list[str]:
    """The claims ``run_checks(system, **options)`` returns, in order: those ``claim`` names,
    else the system's default selection for these options (``claims_for``: e.g. the eros
    scenario's)."""
    _, mod, opts = _options(system, None, options)
    spec = importlib.import_module(opts.SPEC)
    if getattr(opts, "claim", ()):
        chosen = set(opts.claim)
        return [c for c in opts.CLAIMS if c in chosen]
    offered = spec.claims_for(opts.settings()) if hasattr(spec, "claims_for") else opts.CLAIMS
    return [c for c in opts.CLAIMS if c in set(offered)]
