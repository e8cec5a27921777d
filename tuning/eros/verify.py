"""``lgw verify eros``: seed 002's proven per-axis times checked for one gain set by simulated
cases, never passing on missing evidence.

The law under check is the FTSMC (19) with sign switching, sampled at dt = 0.01 s with a
zero-order hold (``lgw.sim.eros.batch.simulate``: the paper's loop).  Per case and axis the
bounds are those of ``lgw.theory.eros.bounds.axis_time_bound`` at the case's own e0, e0':

  reaching-known    (15)-(18), D known (in u_eq (14), dbar = 0): s reaches 0 by
                    t_r = |s0| / k                        (seed 002 (18); claim reaching-sign)
  time-known        reaching + sliding on (6): |e_i| <= TRACK_TOL for good by
                    t_r + t_s(e_max),  t_s(e) = ln(1 + alpha e^(1-r)/beta) / (alpha (1-r))
                    (seed 002 (6)-(7) derived, claim settling-ftsm; e_max: e_max_reaching)
  reaching-unknown  the same with D not in u_eq, |D_i| <= dbar = DIST_AMP: t_r = |s0|/(k - dbar)
  time-unknown      reaching + sliding with that t_r

Observed (``lgw.sim.eros.batch.metrics``): t_reach, the first sample with |s_i| <= S_TOL or a
sign change of s_i; t_track, the first sample after which |e_i| <= TRACK_TOL = 1 cm to the end
of the run (never: +inf, a violation).  Tolerance: one sample dt, from the sampling alone (an
event between samples is seen at the next sample); the observed value minus dt is compared with
the bound.  Measured over 300 Monte Carlo cases, default gains: t_reach - bound <= 0.0089 s
(known D), so the reaching claims are tight to within that one sample.  The bounds are for the
continuous-time law; the loop flown (and re-flown by the reference route) is the sampled one,
so a violation means the 0.01 s sampled loop is slower than the continuous-time bound by more
than one sample (e.g. gains whose reaching rate k is large against 1/dt), not necessarily that
the continuous-time proof is wrong.

Evidence: Hypothesis draws batches of 1..16 initial states from the envelope
(``lgw.testing.eros.state_batches``: |e0_i| <= 10 m, |e0_i'| <= 0.5 m/s, a disturbance phase),
steers with ``target(observed/bound)`` and shrinks a violation.  A case the batched RK4 cannot
carry (nonfinite) is re-flown alone by ``reference_solve`` (DOP853, rtol = atol = 1e-11 between
samples); only a case neither carries is excluded, counted and shown.  A case that touches the
shape model (``crashed``) is excluded too (the plant (4) has no contact: the bounds
say nothing about it), counted and shown.  A violation found by RK4 is re-flown by the
reference route: confirmed there it is ``violated`` (exit 1, with the shrunk witness and a
ready-to-paste ``lgw simulate eros --initial-states`` reproduction); not confirmed, the claim is
``inconclusive`` (exit 4).  Fewer than ``min_cases`` checked cases: ``inconclusive``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim.eros.batch import OUTCOMES, SimOptions, metrics, reference_solve, simulate
from lgw.theory.eros import bounds as B
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains, gains_to_toml
from lgw.theory.errors import ParameterError
from lgw.tuning.verify_common import check_run_options

CLAIMS = {"reaching-known": "(15)-(18), D known", "time-known": "(6),(18), D known",
          "reaching-unknown": "(15)-(18), |D| <= dbar", "time-unknown": "(6),(18), |D| <= dbar"}
GROUPS = {"known": ("reaching-known", "time-known"),
          "unknown": ("reaching-unknown", "time-unknown")}
CLAIM_MODE = {c: m for m, cs in GROUPS.items() for c in cs}
DBAR = {"known": 0.0, "unknown": P.DIST_AMP}  # m/s^2, the bound's disturbance level per mode
NO_INTEGRATOR = "neither the batched RK4 nor DOP853 (reference_solve) carried it (nonfinite)"
CONTACT = "surface contact: the plant (4) has no contact model, the bounds do not apply"
# "holds" needs at least this many checked cases per claim (chosen, as lgw verify lunar: with
# 30 checked cases and no violation, a violating set covering 10 % of the envelope is missed
# with probability 0.9^30 < 5 %).
MIN_CASES = 30
# Profiles: Hypothesis examples (batches of 1..16 states) per claim group.  One batched
# simulation costs about 1.4 s on this machine whatever the batch size (numpy stand-in).
PROFILES = {"ci": {"examples": 8}, "thorough": {"examples": 60}}
BATCH = (1, 16)


@dataclass(frozen=True)
class VerifyOptions:
    """How ``lgw verify eros`` runs: profile (ci | thorough), seed (None: random, else a
    derandomised run), Hypothesis database folder (None: none), min checked cases per claim,
    Hypothesis examples per claim group (None: the profile's), bound scale factors (a
    self-test: < 1 shrinks a bound), and the initial-state envelope (m, m/s)."""

    profile: str = "ci"
    seed: int | None = 0
    database: Path | None = None
    min_cases: int = MIN_CASES
    examples: int | None = None
    scale: Mapping[str, float] = field(default_factory=dict)
    e_max: float = P.MC_POS
    v_max: float = P.MC_VEL

    def __post_init__(self) -> None:
        check_run_options(self, PROFILES, CLAIMS)
        for name in ("e_max", "v_max"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ParameterError(name, v, "must be a finite number > 0")


def case_bounds(e0: np.ndarray, ed0: np.ndarray, g: Gains, dbar: float
                ) -> tuple[np.ndarray, np.ndarray]:
    """(t_reach, t_total) bounds (s), each (N, 3), of ``axis_time_bound`` per case and axis;
    +inf where the bound does not exist (k <= dbar: seed 002 (18) needs k > dbar)."""
    tr = np.full(e0.shape, np.inf)
    tt = np.full(e0.shape, np.inf)
    if not g.k > dbar:
        return tr, tt
    for i in range(e0.shape[0]):
        for a in range(3):
            b = B.axis_time_bound(float(e0[i, a]), float(ed0[i, a]), g, dbar)
            tr[i, a], tt[i, a] = b["t_reach"], b["t_total"]
    return tr, tt


def _options(mode: str, t_final: float) -> SimOptions:
    return SimOptions(law="ftsmc", switch="sign", disturbance=mode, t_final=t_final)


def horizon(bound_total: np.ndarray, dt: float = P.DT_SAMPLE) -> float:
    """Simulated time (s): 1.2 x the largest unscaled bound + 1 s, a whole number of samples,
    so a case slower than its bound is seen as such (and one never tracked is +inf)."""
    t = 1.2 * float(np.max(bound_total, initial=0.0)) + 1.0
    return float(math.ceil(t / dt) * dt)


@dataclass
class Campaign:
    """Every case flown for one gain set, per claim: observed - tolerance, bound, per case and
    axis; counts of cases, checked, carried by the reference route, excluded (by reason)."""

    g: Gains
    scale: Mapping[str, float]
    rows: dict[str, list[dict[str, np.ndarray]]] = field(default_factory=dict)
    cases: dict[str, int] = field(default_factory=dict)
    checked: dict[str, int] = field(default_factory=dict)
    reference: dict[str, int] = field(default_factory=dict)
    excluded: dict[str, dict[str, int]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for c in CLAIMS:
            self.rows.setdefault(c, [])
            self.cases.setdefault(c, 0)
            self.checked.setdefault(c, 0)
            self.reference.setdefault(c, 0)
            self.excluded.setdefault(c, {})

    def run_batch(self, e0: np.ndarray, ed0: np.ndarray, ph: np.ndarray, mode: str) -> None:
        """Fly one batch in one disturbance mode and record both claims of the mode."""
        g, dt = self.g, P.DT_SAMPLE
        tr, tt = case_bounds(e0, ed0, g, DBAR[mode])
        t_reach, t_track, outcome, by_ref = fly(e0, ed0, ph, g, mode, horizon(
            np.where(np.isfinite(tt), tt, 0.0)))
        good = (outcome != OUTCOMES.index("nonfinite")) & (
            outcome != OUTCOMES.index("crashed"))
        reasons = {NO_INTEGRATOR: outcome == OUTCOMES.index("nonfinite"),
                   CONTACT: outcome == OUTCOMES.index("crashed")}
        for claim, obs, bnd in ((GROUPS[mode][0], t_reach, tr), (GROUPS[mode][1], t_track, tt)):
            bnd = bnd * self.scale.get(claim, 1.0)
            self.cases[claim] += len(e0)
            self.checked[claim] += int(good.sum())
            self.reference[claim] += int((good & by_ref).sum())
            for why, mask in reasons.items():
                if mask.any():
                    self.excluded[claim][why] = self.excluded[claim].get(why, 0) + int(mask.sum())
            self.rows[claim].append({"observed": obs - dt, "bound": bnd, "good": good,
                                     "e0": e0, "ed0": ed0, "phase": ph})


def fly(e0: np.ndarray, ed0: np.ndarray, ph: np.ndarray, g: Gains, mode: str, t_final: float
        ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(t_reach (N, 3), t_track (N, 3) with +inf for never, outcome index (N,), carried by the
    reference route (N,)): the batched RK4, and ``reference_solve`` for every case it could not
    carry (nonfinite)."""
    opts = _options(mode, t_final)
    m = metrics(simulate(e0, ed0, g, opts, ph))
    t_reach = np.where(np.isnan(m["t_reach"]), np.inf, m["t_reach"])
    t_track = np.where(np.isnan(m["t_track"]), np.inf, m["t_track"])
    outcome = np.asarray(m["outcome"]).copy()
    by_ref = np.zeros(len(e0), bool)
    for i in np.flatnonzero(outcome == OUTCOMES.index("nonfinite")):
        r = metrics(reference_solve(e0[i:i + 1], ed0[i:i + 1], g, opts, float(ph[i])))
        outcome[i] = int(r["outcome"][0])
        if outcome[i] != OUTCOMES.index("nonfinite"):
            by_ref[i] = True
            t_reach[i] = np.where(np.isnan(r["t_reach"][0]), np.inf, r["t_reach"][0])
            t_track[i] = np.where(np.isnan(r["t_track"][0]), np.inf, r["t_track"][0])
    return t_reach, t_track, outcome, by_ref


def ratio(observed: np.ndarray, bound: np.ndarray) -> np.ndarray:
    """(observed - tolerance) / bound; a zero bound gives 0 when observed <= 0, else +inf."""
    with np.errstate(divide="ignore", invalid="ignore"):
        r = observed / bound
    return np.where(bound > 0, r, np.where(observed <= 0, 0.0, np.inf))


# --- records --------------------------------------------------------------------------------

@dataclass
class ClaimResult:
    """One claim's outcome: worst case (ratio = (observed - dt)/bound), counts, the (shrunk)
    witness with its reproduction when violated, and ``points`` for the plot (not in JSON)."""

    claim: str
    equation: str
    verdict: str  # holds | violated | inconclusive
    bound: float
    worst: float
    ratio: float
    margin: float
    n_cases: int
    n_checked: int
    n_reference: int
    excluded: dict[str, int]
    min_cases: int
    closest: dict[str, Any] = field(default_factory=dict)
    witness: dict[str, Any] | None = None
    reproduction: str | None = None
    why: str = ""
    points: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def n_excluded(self) -> int:
        return sum(self.excluded.values())

    @property
    def n_adaptive(self) -> int:  # the plugin's explain() reads this name for every system
        return self.n_reference

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("points")
        d["n_excluded"] = self.n_excluded
        d["fraction_checked"] = self.n_checked / self.n_cases if self.n_cases else 0.0
        return d


def _points(camp: Campaign, claim: str) -> dict[str, np.ndarray]:
    rows = camp.rows[claim]
    if not rows:
        z = np.zeros((0, 3))
        return {"observed": z, "bound": z, "good": np.zeros(0, bool), "e0": z, "ed0": z,
                "phase": np.zeros(0)}
    return {k: np.concatenate([r[k] for r in rows]) for k in rows[0]}


def reproduction(g: Gains, e0, ed0, phase: float, mode: str, t_final: float) -> str:
    """A ready-to-paste shell snippet: the gain file, the state CSV, the ``lgw simulate eros``."""
    toml = gains_to_toml(g, "witness of lgw verify eros").rstrip("\n")
    row = ",".join(f"{float(x):.17g}" for x in (*e0, *ed0, phase))
    return (f"cat > witness_gains.toml <<'EOF'\n{toml}\nEOF\n"
            f"printf 'ex,ey,ez,vx,vy,vz,phase\\n{row}\\n' > witness_states.csv\n"
            f"lgw simulate eros --law ftsmc-sign --gains witness_gains.toml "
            f"--initial-states witness_states.csv --disturbance {mode} "
            f"--t-final {t_final:.6g} --json")


def _confirm(g: Gains, f: dict[str, Any]) -> dict[str, Any]:
    """Re-fly a simulated witness by the reference route (DOP853 between samples) and add its
    observed value and whether it confirms the violation."""
    mode = f["disturbance"]
    opts = _options(mode, f["t_final"])
    e0, ed0 = np.array([f["e0"]]), np.array([f["ed0"]])
    r = metrics(reference_solve(e0, ed0, g, opts, f["phase"]))
    a = "xyz".index(f["axis"])
    key = "t_reach" if f["claim"].startswith("reaching") else "t_track"
    obs = float(r[key][0, a])
    obs = math.inf if math.isnan(obs) else obs
    f["rechecked_observed"] = obs
    f["recheck_method"] = "reference_solve (DOP853, rtol = atol = 1e-11 between samples)"
    f["confirmed"] = bool(obs - P.DT_SAMPLE > f["bound"])
    return f


def _simulate_group(g: Gains, mode: str, opts: VerifyOptions, camp: Campaign, n_examples: int
                    ) -> dict[str, Any] | None:
    """Hypothesis over batches of states for one disturbance mode; the shrunk failing case (or
    None).  Every example is flown and counted in ``camp``."""
    from hypothesis import target
    from lgw.testing.engine import run_property
    from lgw.testing.eros import state_batches

    claims = GROUPS[mode]

    def check(example):
        e0, ed0, ph = example
        mark = {c: len(camp.rows[c]) for c in claims}
        camp.run_batch(e0, ed0, ph, mode)
        for c in claims:
            for row in camp.rows[c][mark[c]:]:
                rr = np.where(row["good"][:, None], ratio(row["observed"], row["bound"]),
                              -np.inf)
                fin = rr[np.isfinite(rr)]
                if fin.size:
                    target(float(np.max(fin)), label=c)
                if np.any(rr > 1.0):
                    i, ax = np.unravel_index(int(np.argmax(rr)), rr.shape)
                    tt = case_bounds(e0[i:i + 1], ed0[i:i + 1], g, DBAR[mode])[1]
                    return {"claim": c, "axis": "xyz"[ax], "e0": [float(x) for x in e0[i]],
                            "ed0": [float(x) for x in ed0[i]], "phase": float(ph[i]),
                            "disturbance": mode,
                            "observed": float(row["observed"][i, ax] + P.DT_SAMPLE),
                            "tolerance": P.DT_SAMPLE, "bound": float(row["bound"][i, ax]),
                            "ratio": float(rr[i, ax]),
                            "t_final": horizon(np.where(np.isfinite(tt), tt, 0.0)),
                            "source": "simulation (batched RK4, shrunk by Hypothesis)"}
        return None

    return run_property(state_batches(*BATCH, e_max=opts.e_max, v_max=opts.v_max), check,
                        examples=n_examples, seed=opts.seed, database=opts.database,
                        key=f"eros/{mode}")


def run_verify(g: Gains, opts: VerifyOptions = VerifyOptions(),
               progress: Callable[[str], None] | None = None) -> list[ClaimResult]:
    """Every claim of this module for the gain set; see the module docstring."""
    camp = Campaign(g, dict(opts.scale))
    n_ex = opts.examples or PROFILES[opts.profile]["examples"]
    fails: dict[str, dict[str, Any]] = {}
    for mode in GROUPS:
        if progress:
            progress(f"simulating D {mode}")
        f = _simulate_group(g, mode, opts, camp, n_ex)
        if f:
            fails[f["claim"]] = _confirm(g, f)
    out = []
    for claim, eq in CLAIMS.items():
        p = _points(camp, claim)
        rr = np.where(p["good"][:, None], ratio(p["observed"], p["bound"]), -np.inf)
        res = ClaimResult(claim, eq, "holds", math.nan, math.nan, math.nan, math.nan,
                          camp.cases[claim], camp.checked[claim], camp.reference[claim],
                          dict(camp.excluded[claim]), opts.min_cases)
        good = p["good"]
        res.points = {"observed": p["observed"][good].ravel(),
                      "bound": p["bound"][good].ravel(),
                      "violated": (rr[good] > 1.0).ravel()}
        if np.isfinite(rr).any() or np.any(rr == np.inf):
            i, ax = np.unravel_index(int(np.argmax(rr)), rr.shape)
            res.bound, res.worst = float(p["bound"][i, ax]), float(p["observed"][i, ax])
            res.ratio, res.margin = float(rr[i, ax]), res.bound - res.worst
            res.closest = {"axis": "xyz"[ax], "e0": p["e0"][i].tolist(),
                           "ed0": p["ed0"][i].tolist(), "phase": float(p["phase"][i])}
        mode = CLAIM_MODE[claim]
        if not g.k > DBAR[mode]:
            res.verdict = "inconclusive"
            res.why = (f"k = {g.k:g} <= dbar = {DBAR[mode]:g} m/s^2: seed 002 (18) needs "
                       f"k > dbar, so there is no bound to check")
        elif claim in fails:
            f = fails[claim]
            res.witness = f
            res.reproduction = reproduction(g, f["e0"], f["ed0"], f["phase"],
                                            f["disturbance"], f["t_final"])
            if f["confirmed"]:
                res.verdict = "violated"
                res.why = (f"simulated case over its bound on axis {f['axis']}: observed "
                           f"{f['observed']:.4g} s - dt > {f['bound']:.4g} s; the reference "
                           f"route gives {f['rechecked_observed']:.4g} s")
            else:
                res.verdict = "inconclusive"
                res.why = (f"RK4 saw {f['observed']:.4g} s - dt > {f['bound']:.4g} s on axis "
                           f"{f['axis']}, the reference route {f['rechecked_observed']:.4g} s "
                           f"(not confirmed)")
        elif res.n_checked < opts.min_cases:
            res.verdict = "inconclusive"
            res.why = (f"{res.n_checked} checked cases < --min-cases {opts.min_cases} "
                       f"({res.n_excluded} excluded)")
        out.append(res)
    return out


def exit_code(results: list[ClaimResult]) -> int:
    """1 when a bound is violated, else 4 when a claim is inconclusive, else 0."""
    if any(r.verdict == "violated" for r in results):
        return 1
    if any(r.verdict == "inconclusive" for r in results):
        return 4
    return 0


def plot_panels(results: list[ClaimResult]) -> list[dict[str, Any]]:
    """The panels of ``lgw.tuning.figures.observed_vs_bound`` (times in s)."""
    return [{"claim": r.claim, "equation": r.equation, "unit": "s", "excluded": r.n_excluded,
             **r.points} for r in results]
