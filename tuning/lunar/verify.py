"""Seed 001's property campaign on the general system (5) (orbit-instance form, ||d|| = D
constant, saturation per axis): measured behaviour against (13), (18), (19), (21a).

``margins`` is the one check used by ``lgw verify lunar`` and tests/lunar/test_properties.py.
Margins are relative (bound - observed) / bound; negative violates.  The chattering band of
the sign-like term of (7) (claim smooth-7) is excluded from the step-wise V2 check and stated.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim.lunar.batch import l2_norm
from lgw.sim.lunar.closed_loop import gain_arrays
from lgw.sim.lunar.general import GeneralCase, fly
from lgw.theory.errors import ParameterError
from lgw.theory.lunar.bounds import lambda_gain_bounds, transient_bounds, v2_initial, z_l2_bounds
from lgw.theory.lunar.gains import LoopGains, make_loop
from lgw.tuning.verify_common import check_run_options

BAND = 3.0  # chattering band: ||z2|| <= BAND dt (d0e + D)


def margins(t: np.ndarray, o: dict, g: LoopGains, case: GeneralCase, x1_0: float,
            dt: float, i: int = 0, pairs: dict | None = None) -> dict[str, float]:
    """Relative margins (bound - observed) / bound of case ``i`` (< 0 violates); when ``pairs``
    is a dict it receives claim -> (bound, observed) for the observed-against-bound plot (the
    V2 claim: bound 0 on the largest step of V2 outside the band, relative to V2(0))."""
    V2 = o["V2"][:, i]
    band = BAND * dt * (o["d0e"][:-1, i] + case.D)
    outside = o["nz"][:-1, i] > band
    dV = np.diff(V2)
    f1b, f2b = float(g.K1[2, 2]), g.f2bar
    w = float(l2_norm(t, o["B0du"][..., i:i + 1])[0])
    c1, c2 = lambda_gain_bounds(f1b, f2b)
    v20 = v2_initial(np.array([x1_0]), o["z2"][0, :, i], g.d0e0, case.D, g.q)
    b1, b2 = z_l2_bounds(v20, f1b, f2b, g.f3)
    _, b2p = z_l2_bounds(v20, f1b, f2b, g.f3, printed=True)
    x1b, _ = transient_bounds(v20, w, f1b, f2b, g.f3, float(np.linalg.norm(g.K1[:, 2])))

    def rel(bound, obs):
        return (bound - obs) / bound if bound > 0 else (0.0 if obs <= 0 else -np.inf)

    n = lambda k: float(l2_norm(t, o[k][..., i:i + 1])[0])  # noqa: E731
    step = float(np.max(dV[outside], initial=-np.inf) / V2[0]) if V2[0] > 0 else 0.0
    pair = {"V2_step_outside_band": (0.0, step), "(18a)": (c1 * w, n("l1")),
            "(18b)": (c2 * w, n("l2")), "(19a)": (b1, n("z1") ** 2),
            "(19b) derived": (b2, n("z2") ** 2), "(19b) printed": (b2p, n("z2") ** 2),
            "(21a)": (x1b, n("x1"))}
    if pairs is not None:
        pairs.update({k: (float(b), float(v)) for k, (b, v) in pair.items()})
    return {
        "V2_step_outside_band": -step,
        "V2_max_rise_inside_band": float(np.max(dV[~outside], initial=0.0) / V2[0])
        if V2[0] > 0 else 0.0,
        "(18a)": rel(c1 * w, n("l1")) if w > 0 else -n("l1"),
        "(18b)": rel(c2 * w, n("l2")) if w > 0 else -n("l2"),
        "(19a)": rel(b1, n("z1") ** 2), "(19b) derived": rel(b2, n("z2") ** 2),
        "(19b) printed": rel(b2p, n("z2") ** 2), "(21a)": rel(x1b, n("x1")),
    }


def random_loop_gains(rng: np.random.Generator) -> LoopGains:
    k = rng.uniform(0.05, 1.0)
    F2 = rng.uniform(0.6, 5.0, 3)
    return make_loop("orbit", {"K1": [k, k, k], "F2": F2.tolist(),
                               "f3": float(rng.uniform(0.05, 0.95) * F2.min()), "d0e0": 0.0,
                               "q": float(rng.uniform(0.005, 1.0))})


def campaign(n: int, seed: int, t_end: float = 5.0, dt: float = 0.02,
             u_max: float = 2000.0, D: float = 0.5) -> list[dict]:
    """n random cases (gains and initial errors), flown together; margins per case."""
    rng = np.random.default_rng(seed)
    gs = [random_loop_gains(rng) for _ in range(n)]
    X0 = np.zeros((9, n))
    X0[0] = rng.uniform(-100, 100, n)
    X0[1:4] = rng.uniform(-5, 5, (3, n))
    case = GeneralCase(D=D, u_max=u_max)
    t, o = fly(X0, gain_arrays(gs), case, t_end, dt)
    return [margins(t, o, gs[i], case, float(X0[0, i]), dt, i) for i in range(n)]


# --- per-claim verdicts with checked / excluded counts (issue 19) ---------------------------

# The claims ``margins`` measures (the band statistic V2_max_rise_inside_band is stated, not a
# claim) and the equation each comes from.
CLAIMS = {"V2_step_outside_band": "(13)", "(18a)": "(18a)", "(18b)": "(18b)",
          "(19a)": "(19a)", "(19b) derived": "(19b)", "(19b) printed": "(19b) as printed",
          "(21a)": "(21a)"}
SCALABLE = tuple(k for k in CLAIMS if k != "V2_step_outside_band")
# "holds" needs at least this many checked cases (chosen): with 30 checked cases and no
# violation, a violating set that covers 10% of the sampled domain is missed with
# probability 0.9^30 < 5%.
MIN_CASES = 30
RESULTS = ("holds", "violated", "inconclusive")
EXIT_CODES = {"holds": 0, "violated": 1, "inconclusive": 4}


def _exclusion(claim: str, m: float) -> str | None:
    """Why a case's margin does not count as a check of the claim (None: it counts)."""
    if np.isnan(m):
        return "non-finite run or bound (NaN margin)"
    if np.isposinf(m):
        return ("no step outside the chattering band (nothing to check)"
                if claim == "V2_step_outside_band" else "infinite margin")
    if np.isneginf(m):
        return "bound 0 with a positive observation (-inf margin)"
    return None


def _scaled(m: float, f: float) -> float:
    """The relative margin (b - o) / b with the bound b multiplied by f."""
    return 1.0 - (1.0 - m) / f


def claim_result(evidence, checked: int, min_cases: int) -> str:
    """holds / violated / inconclusive, computed: violated only with a re-checked witness
    (``evidence.status == "refuted"``), holds only on at least ``min_cases`` checked cases."""
    if evidence is not None and evidence.status == "refuted":
        return "violated"
    return "holds" if evidence is not None and checked >= min_cases else "inconclusive"


def verify(n: int, seed: int, t_end: float = 5.0, dt: float = 0.02, u_max: float = 2000.0,
           D: float = 0.5, min_cases: int = MIN_CASES,
           scale: dict[str, float] | None = None) -> list[dict]:
    """Per claim: checked and excluded cases (with reasons), violations, the worst margin and
    its case, a re-checked witness for the worst violation (the case re-flown alone at dt / 2),
    the ``Search`` evidence and the computed result.  ``scale``: claim -> factor on its bound
    (a self-test of the checker: a shrunk bound must be reported violated)."""
    from lgw.theory.evidence import Search, Witness

    scale = scale or {}
    rng = np.random.default_rng(seed)
    gs = [random_loop_gains(rng) for _ in range(n)]
    X0 = np.zeros((9, n))
    X0[0] = rng.uniform(-100, 100, n)
    X0[1:4] = rng.uniform(-5, 5, (3, n))
    case = GeneralCase(D=D, u_max=u_max)
    with np.errstate(all="ignore"):
        t, o = fly(X0, gain_arrays(gs), case, t_end, dt)
        rows = [margins(t, o, gs[i], case, float(X0[0, i]), dt, i) for i in range(n)]

    def point(i: int) -> dict:
        g = gs[i]
        return {"case": i, "seed": seed, "x1_0": float(X0[0, i]), "x2_0": X0[1:4, i].tolist(),
                "K1": float(g.K1[0, 0]), "F2": np.diag(g.F2).tolist(), "f3": g.f3, "q": g.q,
                "u_max": u_max, "D": D, "t_end": t_end}

    def refly(i: int, claim: str) -> float:
        with np.errstate(all="ignore"):
            tt, oo = fly(X0[:, i:i + 1], gain_arrays([gs[i]]), case, t_end, dt / 2)
            m = margins(tt, oo, gs[i], case, float(X0[0, i]), dt / 2, 0)[claim]
        return _scaled(m, scale[claim]) if claim in scale else m

    out = []
    domain = {"x1_0": "U(-100, 100)", "x2_0": "U(-5, 5)^3", "K1": "U(0.05, 1) I",
              "F2": "diag U(0.6, 5)", "f3": "U(0.05, 0.95) min F2", "q": "U(0.005, 1)",
              "u_max": u_max, "D": D, "t_end": t_end}
    for claim, eq in CLAIMS.items():
        ms = np.array([r[claim] for r in rows], float)
        if claim in scale:
            ms = _scaled(ms, scale[claim])
        reasons: dict[str, int] = {}
        ok = np.ones(n, bool)
        for i, m in enumerate(ms):
            why = _exclusion(claim, m)
            if why is not None:
                ok[i] = False
                reasons[why] = reasons.get(why, 0) + 1
        checked = int(ok.sum())
        viol = int(np.sum(ms[ok] < 0))
        ev = None
        worst = None
        if checked:
            iw = int(np.flatnonzero(ok)[np.argmin(ms[ok])])
            worst = float(ms[iw])
            counter = None
            if worst < 0:
                counter = Witness(point(iw), worst, f"RK4 dt = {dt} s, batch of {n}",
                                  refly(iw, claim), f"the case re-flown alone at dt = {dt / 2} s",
                                  seed=seed)
            ev = Search(domain, f"random cases, RK4 dt = {dt} s", checked, worst, point(iw),
                        seed=seed, counter=counter, relative=True)
        res = claim_result(ev, checked, min_cases)
        out.append({"claim": claim, "equation": eq, "cases": n, "checked": checked,
                    "excluded": n - checked, "excluded_reasons": reasons,
                    "fraction_checked": checked / n, "violations": viol,
                    "worst_margin": worst, "min_cases": min_cases,
                    "bound_scale": scale.get(claim, 1.0), "result": res,
                    "witness": ev.witness.to_dict() if ev is not None and ev.witness else None,
                    "evidence": ev.to_dict() if ev is not None else None})
    return out


def exit_code(results: list[dict]) -> int:
    """1 if a claim is violated, else 4 if one is inconclusive, else 0."""
    found = {r["result"] for r in results}
    return 1 if "violated" in found else (4 if "inconclusive" in found else 0)


# --- lgw verify lunar for one gain set: Hypothesis drives the initial errors ---------------

PROFILES = {"ci": {"examples": 16}, "thorough": {"examples": 120}}
BATCH = (1, 8)  # states per Hypothesis example (one batched RK4 flight)


@dataclass(frozen=True)
class VerifyOptions:
    """How ``lgw verify lunar`` runs for one orbit-loop gain set: profile (ci | thorough),
    seed (None: random, else derandomised), Hypothesis database folder, min checked cases per
    claim, examples per run (None: the profile's), bound scale factors (claim -> factor, a
    self-test), flight time t_end (s), RK4 step dt (s), per-axis saturation u_max (N) and the
    disturbance norm D (m/s^2) of the general system (5)."""

    profile: str = "ci"
    seed: int | None = 0
    database: Path | None = None
    min_cases: int = MIN_CASES
    examples: int | None = None
    scale: Mapping[str, float] = field(default_factory=dict)
    t_end: float = 5.0
    dt: float = 0.02
    u_max: float = 2000.0
    D: float = 0.5

    def __post_init__(self) -> None:
        check_run_options(self, PROFILES, SCALABLE)
        if not 0 < self.t_end <= 600:
            raise ParameterError("t-end", self.t_end, "must lie in (0, 600] s")
        if not 0 < self.dt <= 0.1:
            raise ParameterError("dt", self.dt, "must lie in (0, 0.1] s")
        if not self.u_max > 0:
            raise ParameterError("u-max", self.u_max, "must be > 0 N")


@dataclass
class ClaimResult:
    """One claim's outcome for the gain set (the records ``lgw verify lunar`` prints): counts,
    the worst relative margin (bound - observed)/bound and its case, the shrunk witness
    (re-checked at dt/2) with a reproduction, and ``points`` for the plot (not in JSON)."""

    claim: str
    equation: str
    verdict: str
    worst_margin: float
    n_cases: int
    n_checked: int
    excluded: dict[str, int]
    min_cases: int
    bound_scale: float = 1.0
    closest: dict[str, Any] = field(default_factory=dict)
    witness: dict[str, Any] | None = None
    reproduction: str | None = None
    why: str = ""
    points: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def n_excluded(self) -> int:
        return sum(self.excluded.values())

    @property
    def n_adaptive(self) -> int:  # read by the plugin for every system: lunar has no fallback
        return 0

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("points")
        d["n_excluded"] = self.n_excluded
        d["fraction_checked"] = self.n_checked / self.n_cases if self.n_cases else 0.0
        return d


def _fly_cases(g: LoopGains, x1: np.ndarray, x2: np.ndarray, opts: VerifyOptions,
               dt: float) -> tuple[list[dict], list[dict]]:
    """Margins and (bound, observed) pairs of each case, all flown in one RK4 batch."""
    n = len(x1)
    X0 = np.zeros((9, n))
    X0[0], X0[1:4], X0[8] = x1, x2.T, g.d0e0
    case = GeneralCase(D=opts.D, u_max=opts.u_max)
    with np.errstate(all="ignore"):
        t, o = fly(X0, gain_arrays([g] * n), case, opts.t_end, dt)
        ms, ps = [], []
        for i in range(n):
            p: dict = {}
            ms.append(margins(t, o, g, case, float(x1[i]), dt, i, pairs=p))
            ps.append(p)
    return ms, ps


def reproduction(g: LoopGains, x1_0: float, x2_0, opts: VerifyOptions, claim: str) -> str:
    """A ready-to-paste snippet that flies the witness alone (the general system (5) has no
    ``lgw simulate`` front: ``lgw simulate lunar`` flies the Section 5 closed loop) and prints
    its margin for the claim, with the bound multiplied by the run's scale factor if any."""
    f = float(opts.scale.get(claim, 1.0))
    x2 = ", ".join(f"{float(v):.17g}" for v in x2_0)
    gd = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in g.to_dict().items()}
    return ("python - <<'EOF'\n"
            "import numpy as np\n"
            "from lgw.theory.lunar.gains import make_loop\n"
            "from lgw.tuning.lunar.verify import VerifyOptions, _fly_cases\n"
            f"g = make_loop('orbit', {gd!r})\n"
            f"opts = VerifyOptions(t_end={opts.t_end!r}, u_max={opts.u_max!r}, D={opts.D!r})\n"
            f"m, p = _fly_cases(g, np.array([{float(x1_0):.17g}]), np.array([[{x2}]]), opts, "
            f"{opts.dt!r})\n"
            f"b, o = p[0][{claim!r}]\n"
            f"print('bound x {f!r}', b * {f!r}, 'observed', o, 'margin', 1 - o / (b * {f!r}))\n"
            "EOF")


def run_verify(g: LoopGains, opts: VerifyOptions = VerifyOptions()) -> list[ClaimResult]:
    """Every claim of ``CLAIMS`` for one orbit-loop gain set: Hypothesis draws batches of
    initial errors (``lgw.testing.lunar.state_batches``), each batch is flown by RK4 and every
    case judged per claim (``_exclusion``: undefined margins are excluded, counted and shown);
    a negative margin is shrunk by Hypothesis and the shrunk case re-flown alone at dt/2: a
    confirmed negative margin is ``violated``, an unconfirmed one ``inconclusive``; fewer than
    ``min_cases`` checked cases is ``inconclusive``."""
    from hypothesis import target
    from lgw.testing.engine import run_property
    from lgw.testing.lunar import state_batches

    scale = dict(opts.scale)
    rec: dict[str, dict[str, Any]] = {c: {"m": [], "b": [], "o": [], "x1": [], "x2": [],
                                          "cases": 0, "reasons": {}} for c in CLAIMS}

    def check(example):
        x1, x2 = example
        ms, ps = _fly_cases(g, x1, x2, opts, opts.dt)
        worst = None
        for c in CLAIMS:
            f = scale.get(c, 1.0)
            r = rec[c]
            r["cases"] += len(x1)
            fin = []
            for i, (m, p) in enumerate(zip(ms, ps, strict=True)):
                m = _scaled(m[c], f) if c in scale else m[c]
                why = _exclusion(c, m)
                if why is not None:
                    r["reasons"][why] = r["reasons"].get(why, 0) + 1
                    continue
                r["m"].append(m)
                r["b"].append(p[c][0] * f)
                r["o"].append(p[c][1])
                r["x1"].append(float(x1[i]))
                r["x2"].append([float(v) for v in x2[i]])
                fin.append(m)
                if m < 0 and (worst is None or m < worst["margin"]):
                    worst = {"claim": c, "margin": float(m), "x1_0": float(x1[i]),
                             "x2_0": [float(v) for v in x2[i]], "bound": p[c][0] * f,
                             "observed": p[c][1],
                             "source": f"RK4 dt = {opts.dt} s, shrunk by Hypothesis"}
            if fin:
                target(-float(min(fin)), label=c)
        return worst

    n_ex = opts.examples or PROFILES[opts.profile]["examples"]
    fail = run_property(state_batches(*BATCH), check, examples=n_ex, seed=opts.seed,
                        database=opts.database, key="lunar/orbit")
    if fail is not None:
        c = fail["claim"]
        ms, _ = _fly_cases(g, np.array([fail["x1_0"]]), np.array([fail["x2_0"]]), opts,
                           opts.dt / 2)
        m2 = _scaled(ms[0][c], scale[c]) if c in scale else ms[0][c]
        fail.update(rechecked_margin=float(m2),
                    recheck_method=f"the case re-flown alone at dt = {opts.dt / 2} s",
                    confirmed=bool(m2 < 0))
    out = []
    for c, eq in CLAIMS.items():
        r = rec[c]
        m = np.array(r["m"], float)
        res = ClaimResult(c, eq, "holds", float(m.min()) if m.size else math.nan, r["cases"],
                          int(m.size), dict(r["reasons"]), opts.min_cases, scale.get(c, 1.0))
        res.points = {"bound": np.array(r["b"]), "observed": np.array(r["o"]),
                      "violated": m < 0}
        if m.size:
            i = int(np.argmin(m))
            res.closest = {"x1_0": r["x1"][i], "x2_0": r["x2"][i]}
        if fail is not None and fail["claim"] == c:
            res.witness = fail
            res.reproduction = reproduction(g, fail["x1_0"], fail["x2_0"], opts, c)
            res.verdict = "violated" if fail["confirmed"] else "inconclusive"
            res.why = (f"margin {fail['margin']:.4g} at dt = {opts.dt} s, re-checked "
                       f"{fail['rechecked_margin']:.4g} at dt/2"
                       + ("" if fail["confirmed"] else " (not confirmed)"))
        elif res.n_checked < opts.min_cases:
            res.verdict = "inconclusive"
            res.why = (f"{res.n_checked} checked cases < --min-cases {opts.min_cases} "
                       f"({res.n_excluded} excluded)")
        out.append(res)
    return out


def result_exit_code(results: list[ClaimResult]) -> int:
    """1 when a claim is violated, else 4 when one is inconclusive, else 0."""
    found = {r.verdict for r in results}
    return 1 if "violated" in found else (4 if "inconclusive" in found else 0)


def plot_panels(results: list[ClaimResult]) -> list[dict[str, Any]]:
    """The panels of ``lgw.tuning.figures.observed_vs_bound``: L2 norms (squared for (19))
    against their bounds; for (13) the largest V2 step outside the band over V2(0), bound 0."""
    def unit(c: str) -> str:
        return ("V2 step / V2(0)" if c == "V2_step_outside_band" else
                "squared L2 norm" if c.startswith("(19") else "L2 norm")

    return [{"claim": r.claim, "equation": r.equation, "excluded": r.n_excluded,
             "unit": unit(r.claim), "ylabel": "observed", **r.points} for r in results]
