"""``lgw verify mars``: seed 000's proven bounds checked for one gain set, never passing on
missing evidence.

Two kinds of evidence per claim, both reported:

* **search**: the falsification engine (``lgw.theory.falsify``) on the exact reduced per-axis
  loop (``lgw.theory.mars.searches``) with the gain set fixed, minimising the margin (bound
  minus observed) over the initial surfaces s1(0), s2(0) (magnitudes 1e-3 .. 1e9, both signs).
  This reaches the regimes random states do not (e.g. |s2(0)| large enough for the landing
  time to approach T2* + T1*), so a bound made a few percent too small, or the paper's
  max{T1, T2} in place of the sum, is found and shrunk to a simple witness, re-checked by a
  tight LSODA integration;
* **simulation**: Hypothesis draws batches of initial states (``lgw.testing.mars``) and flies
  them through ``lgw.sim.mars.batch.simulate_batch`` (corrected law, no thrust limit, no drag:
  the plant of the bounds), steering with ``hypothesis.target(observed/bound)`` and shrinking
  any violation to a minimal state; its example database (``--database``) replays earlier
  failures first.

Claims:
  reaching-16    (16)/(18): on s2 = 0, s1 reaches eps by T(s1(0)) <= T1_exact <= T1_polyakov
  T2-26          (26): the first entry of |s2_i| <= eps is within T2_exact (no disturbance)
  landing-T2+T1  sound landing bound T2_exact + T1_exact: |s1_i| <= eps and never leaves after
  s2-39-40       (39)/(40): under |a_p,i| <= a_max (worst case and random), |s2_i| enters the
                 (39) neighbourhood within T2_practical_exact and never leaves
  s1-31-45       (31)/(45): |s1_i| enters the (31) neighbourhood within T2_practical_exact +
                 T1_practical_exact (landing_time_bound_disturbed) and never leaves

Verdicts: ``holds`` (no violation, and at least ``min_cases`` simulated cases checked),
``violated`` (a confirmed search witness or a simulated case over its bound: exit 1, with the
shrunk witness and a ready-to-paste ``lgw simulate mars`` reproduction), ``inconclusive`` (fewer
than ``min_cases`` checked: exit 4).  A case RK4 cannot carry (nonfinite, or a step over the
s1 = 0 singularity of the command) is re-flown on the adaptive dopri5 path (max_step = dt);
only what no integrator carries is excluded, counted and shown with its reason.  The disturbed
claims need a recorded trajectory (the band check), which dopri5 does not record: their RK4
failures are excluded and shown, and those claims rest on their search too.

Tolerances come from the integrator, never from a fudge factor: an event is located to within
one step dt (times), and an explicit RK4 step leaves a chattering floor on s2 of about
0.85 dt^1.5 m/s (docs/sim.md, ``benchmarks/bench_sim.py --floor``: 9.0e-3 m/s at dt = 0.05 s);
at the edge of a band one step can overshoot it by one step's increment of s2, so the band
tolerance of s2 is tol2 = S2_FLOOR_COEF dt^1.5 + inc(c), inc(c) = dt (alpha1 c^g1 + alpha2 c^g2
+ a_max) the most one step of s2' of (25) can move at |s2| = c, c = band + floor + inc(band +
floor) (where RK4's stages can be); that of s1 is the growth of the (31) band when its eta, the
s2 band, grows by tol2, plus the s1 floor (1.4e-4 m at dt = 0.05 s, fitted as 0.22 dt^2.46).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim.mars.batch import simulate_batch
from lgw.theory.errors import ParameterError
from lgw.theory.evidence import Search
from lgw.theory.falsify import Budget, Problem, falsify
from lgw.theory.mars import searches as S
from lgw.theory.mars.bounds import axis_bounds, landing_time_bound, neighborhood, reaching_time
from lgw.theory.mars.gains import Gains, gains_to_toml
from lgw.theory.mars.mss import surfaces_numeric
from lgw.theory.mars.parameters import (
    M0,  # Table I mass (the bounds do not depend on it: the law divides it out)
)
from lgw.theory.symbolic import np_sig
from lgw.tuning.verify_common import check_run_options

# Measured chattering floors (docs/sim.md "Chattering floor and eps", Table I, RK4):
# max |s2| = 9.0e-3 m/s at dt = 0.05 s, fitted as 0.85 dt^1.5 over dt in [0.01, 0.2];
# max |s1| = 2.6e-6, 1.4e-4, 7.5e-4, 4.1e-3 m at dt = 0.01, 0.05, 0.1, 0.2 s: 0.22 dt^2.46
# (log-log fit through the end points; reproduces 1.35e-4 at 0.05 s).
S2_FLOOR_COEF = 0.85
S1_FLOOR_COEF = 0.22
S1_FLOOR_EXP = 2.46

CLAIMS = {
    "reaching-16": "(16),(18)",
    "T2-26": "(26)",
    "landing-T2+T1": "T2*+T1*",
    "s2-39-40": "(39),(40)",
    "s1-31-45": "(31),(45)",
}
GROUPS = {"reaching": ("reaching-16",), "undisturbed": ("T2-26", "landing-T2+T1"),
          "disturbed": ("s2-39-40", "s1-31-45")}
NO_INTEGRATOR = "neither RK4 nor dopri5 carried it (nonfinite or step limit)"
NO_RECORD = "RK4 stepped over s1 = 0 and the band check needs a recorded trajectory"
MIN_CASES = 10  # default --min-cases: checked simulated cases per claim for "holds"

# Profiles: Hypothesis examples (batches of 1..3 states) per claim group, and the search budget
# per axis and claim (the problems have 1 or 2 free coordinates once the gains are fixed).
PROFILES = {
    "ci": {"examples": 20, "budget": Budget(popsize=10, maxiter=8, local_evals=40, seed=0)},
    "thorough": {"examples": 150,
                 "budget": Budget(popsize=20, maxiter=30, local_evals=200, seed=0)},
}


@dataclass(frozen=True)
class VerifyOptions:
    """How ``lgw verify mars`` runs: profile (ci | thorough), seed (None: random, else a
    derandomised run), Hypothesis database folder (None: none), min checked cases, RK4 step
    and band, bound scale factors (a self-test: < 1 shrinks a bound), and whether to run the
    simulation and search phases."""

    profile: str = "ci"
    seed: int | None = 0
    database: Path | None = None
    min_cases: int = MIN_CASES
    dt: float = 0.05
    eps: float = 0.05
    scale: Mapping[str, float] = field(default_factory=dict)
    examples: int | None = None
    simulate: bool = True
    search: bool = True

    def __post_init__(self) -> None:
        check_run_options(self, PROFILES, CLAIMS)
        for name in ("dt", "eps"):
            if not getattr(self, name) > 0:
                raise ParameterError(name, getattr(self, name), "must be > 0")


def s2_floor(dt: float) -> float:
    return S2_FLOOR_COEF * dt**1.5


def s1_floor(dt: float) -> float:
    return S1_FLOOR_COEF * dt**S1_FLOOR_EXP


def sample_states(n: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """n initial states from SeedSequence(seed): |r_i| log-uniform in [1e-6, 1e5] m, |v_i| in
    [1e-6, 1e3] m/s, random signs, ~10 % exact zeros per velocity component."""
    rng = np.random.default_rng(np.random.SeedSequence(seed))

    def comp(lo: float, hi: float, zeros: bool) -> np.ndarray:
        x = 10 ** rng.uniform(lo, hi, (n, 3)) * rng.choice([-1.0, 1.0], (n, 3))
        if zeros:
            x[rng.random((n, 3)) < 0.1] = 0.0
        return x

    # no exact zeros in r: lgw.sim.mars.batch flags r_i = 0 at t = 0 nonfinite (0 * inf in the
    # command)
    return comp(-6, 5, False), comp(-6, 3, True), np.full(n, M0)


def surface2(r: np.ndarray, v: np.ndarray, g: Gains) -> np.ndarray:
    """s2 of seed 000 (21), per axis (last dimension 3), from the SymPy surface
    (``lgw.theory.mars.mss.surfaces_numeric``)."""
    return surfaces_numeric()[1](r, v, g.beta1, g.beta2, g.q1, g.q2)


def on_surface2(r0: np.ndarray, g: Gains) -> np.ndarray:
    """The velocity that puts the state on s2 = 0 (21): then s1 obeys (16) alone."""
    return -(g.beta1 * np_sig(r0, g.q1) + g.beta2 * np_sig(r0, g.q2))


def unresolved(r: np.ndarray, v: np.ndarray, g: Gains, a_max: float, dt: float) -> np.ndarray:
    """(N,) cases with a step the integrator did not resolve: for the corrected law s2 obeys
    s2' = -alpha1 sig(s2,g1) - alpha2 sig(s2,g2) + a_p exactly (claim V2dot-corrected), so one
    step can move s2 by at most dt (alpha1|s2|^g1 + alpha2|s2|^g2 + a_max) (|s2| at the larger
    end) plus twice the chattering floor (from +floor to -floor).  Measured with the default
    gains, dt = 0.05: resolved steps reach <= 0.9 of this, unresolved ones 20x to 350x.
    A larger jump is RK4 stepping over the s1 = 0 singularity
    of the command with v != 0 (|s1|^(q1-1) v), not the closed loop: such cases are skipped
    and counted, like the simulator's nonfinite cases."""
    s2 = surface2(r, v, g)
    a = np.maximum(np.abs(s2[:, 1:]), np.abs(s2[:, :-1]))
    rate = g.alpha1 * a**g.g1 + g.alpha2 * a**g.g2 + a_max
    jump = np.abs(np.diff(s2, axis=1))
    bad = jump > dt * rate + 2 * s2_floor(dt)
    return np.any(bad & np.isfinite(jump), axis=(1, 2))


def _bound_arrays(g: Gains) -> dict[str, np.ndarray]:
    b = axis_bounds(g)
    return {k: np.array([b[a][k] for a in ("x", "y", "z")]) for k in b["x"]}


def _entry_and_stay(s: np.ndarray, band: np.ndarray, tol, t: np.ndarray,
                    start: np.ndarray | None = None):
    """Per (case, axis): first node time (at or after node ``start``) with |s| <= band + tol,
    and max |s|/(band + tol) from then on.  The tolerance tol is the integrator's floor: a band
    narrower than the floor cannot be resolved by the fixed step."""
    lim = (band + tol)[None, None, :]
    idx = np.arange(s.shape[1])[None, :, None]
    if start is None:
        start = np.zeros(s.shape[::2], int)
    inside = (np.abs(s) <= lim) & (idx >= start[:, None, :])
    first = np.where(inside.any(axis=1), inside.argmax(axis=1), -1)  # (N, 3)
    t_in = np.where(first >= 0, t[np.maximum(first, 0)], np.inf)
    after = np.where(idx >= first[:, None, :], np.abs(s), 0.0)
    after = np.where(first[:, None, :] >= 0, after, np.inf)
    stay = np.max(after, axis=1) / lim[0]
    return t_in, stay, first


class Campaign:
    """Runs the claims for one gain set; ``scale`` multiplies a claim's bound (tests inject a
    deliberately wrong, too small bound through it)."""

    def __init__(self, g: Gains, *, dt: float = 0.05, eps: float = 0.05, seed: int = 0,
                 scale: dict[str, float] | None = None, batch: int = 16) -> None:
        if g.disturbance is None:
            raise ParameterError("disturbance", None, "a [disturbance] table is needed for the "
                                 "practical bounds (39)-(45)")
        if not 0.5 < g.q1 < 1.0:
            raise ParameterError("q1", g.q1, "must lie in (0.5, 1) for the simulated corrected "
                                 "law (its |s1|^(2 q1 - 1) term blows up below)")
        self.g, self.dt, self.eps, self.seed, self.batch = g, dt, eps, seed, batch
        self.scale = dict(scale or {})
        for k in self.scale:
            if k not in CLAIMS:
                raise ParameterError("scale", k, f"a claim name: {', '.join(CLAIMS)}")
        self.b = _bound_arrays(g)
        self.rows: dict[str, list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]] = {
            k: [] for k in CLAIMS}
        self.excluded: dict[str, dict[str, int]] = {k: {} for k in CLAIMS}
        self.adaptive = dict.fromkeys(CLAIMS, 0)
        self.cases = dict.fromkeys(CLAIMS, 0)
        self.checked = dict.fromkeys(CLAIMS, 0)
        self._offset = 0

    def _sc(self, claim: str) -> float:
        return self.scale.get(claim, 1.0)

    def _add(self, claim: str, ratio: np.ndarray, observed: np.ndarray, bound: np.ndarray,
             r0: np.ndarray, v0: np.ndarray, ok: tuple[np.ndarray, np.ndarray], offset: int,
             label: str = "", adaptive: np.ndarray | None = None,
             reason: str = "not integrable") -> None:
        """ratio, observed (n, 3); ok = (carried, resolved) per case; adaptive marks the cases
        that the dopri5 path carried after RK4 could not; the rest of the not-ok cases are
        excluded (counted under ``reason``)."""
        good = ok[0] & ok[1]
        n_bad = int((~good).sum())
        if n_bad:
            self.excluded[claim][reason] = self.excluded[claim].get(reason, 0) + n_bad
        if adaptive is not None:
            self.adaptive[claim] += int((adaptive & good).sum())
        self.cases[claim] += len(good)
        self.checked[claim] += int(good.sum())
        case = np.arange(len(good)) + offset
        self.rows[claim].append((np.where(good[:, None], ratio, -np.inf), observed,
                                 np.broadcast_to(bound, ratio.shape), r0, v0, case, label))

    def _sim(self, r0, v0, t_max, disturbance="none"):
        g = self.g
        res = simulate_batch(r0, v0, np.full(len(r0), M0), g, drag="none", dt=self.dt,
                             eps=self.eps, t_max=t_max, stop="t_max", disturbance=disturbance,
                             dist_amplitude=g.disturbance.a_max, seed=self.seed,
                             case_offset=self._offset, record=True, blowup_accel=np.inf)
        tr = res.trajectory
        a_max = 0.0 if disturbance == "none" else g.disturbance.a_max
        with np.errstate(all="ignore"):
            bad = unresolved(tr["r"], tr["v"], g, a_max, self.dt)
        return res, (~res.nonfinite, ~bad)

    def _sim_times(self, r0, v0, t_max):
        """Band times without disturbance: RK4, and for every case RK4 cannot carry (nonfinite,
        or a step over the s1 = 0 singularity) the adaptive dopri5 path of simulate_batch with
        max_step = dt (its nodes are then as close as RK4's, so the one-step tolerance holds).
        Returns (t_s1, t_s2, t_s1_last_exit, y_end, ok (carried, resolved), adaptive)."""
        res, ok = self._sim(r0, v0, t_max)
        good = ok[0] & ok[1]
        out = [res.t_s1.copy(), res.t_s2.copy(), res.t_s1_last_exit.copy(), res.y_end.copy()]
        adaptive = np.zeros(len(r0), bool)
        if not good.all():
            idx = np.flatnonzero(~good)
            ad = simulate_batch(r0[idx], v0[idx], np.full(len(idx), M0), self.g, drag="none",
                                dt=self.dt, eps=self.eps, t_max=t_max, stop="t_max",
                                method="dopri5", max_step=self.dt, seed=self.seed,
                                case_offset=self._offset, blowup_accel=np.inf)
            carried = ~ad.nonfinite & ~ad.step_limit
            for arr, new in zip(out, (ad.t_s1, ad.t_s2, ad.t_s1_last_exit, ad.y_end),
                                strict=True):
                arr[idx] = new
            good = good.copy()
            good[idx] = carried
            adaptive[idx] = carried
        return (*out, (good, np.ones(len(r0), bool)), adaptive)

    def run_batch(self, r0: np.ndarray, v0: np.ndarray, offset: int = 0,
                  claims: tuple[str, ...] = tuple(CLAIMS)) -> None:
        """Fly one batch for the given claims (each group of claims is one simulate_batch)."""
        self._offset = offset
        if "reaching-16" in claims:
            self._reaching(r0)
        if "T2-26" in claims or "landing-T2+T1" in claims:
            self._undisturbed(r0, v0)
        if "s2-39-40" in claims or "s1-31-45" in claims:
            self._disturbed(r0, v0)

    def _reaching(self, r0: np.ndarray) -> None:
        g, b, dt = self.g, self.b, self.dt
        offset = self._offset
        # reaching law (16) alone: start on s2 = 0
        vs = on_surface2(r0, g)
        t1 = b["T1_exact"] * self._sc("reaching-16")
        t_s1, _, _, _, ok, ad = self._sim_times(r0, vs, float(np.max(t1)) + 2 * dt)
        t_ex = reaching_time(r0, g.beta1, g.beta2, g.q1, g.q2)  # exact T(s0) <= T1_exact
        assert np.all(t_ex <= b["T1_exact"] * (1 + 1e-9)) and np.all(
            b["T1_exact"] <= b["T1_polyakov"] * (1 + 1e-9))
        obs = np.nan_to_num(t_s1, nan=np.inf) - dt  # entry located within one step
        self._add("reaching-16", obs / t1, obs, t1, r0, vs, ok, offset, adaptive=ad,
                  reason=NO_INTEGRATOR)

    def _undisturbed(self, r0: np.ndarray, v0: np.ndarray) -> None:
        """T2 (26) and the landing bound, no disturbance."""
        b, dt, eps, offset = self.b, self.dt, self.eps, self._offset
        t2 = b["T2_exact"] * self._sc("T2-26")
        tl = b["landing_time_bound"] * self._sc("landing-T2+T1")
        t_s1, t_s2, t_exit, y_end, ok, ad = self._sim_times(
            r0, v0, float(max(np.max(tl), np.max(t2))) + 2 * dt)
        obs = np.nan_to_num(t_s2, nan=np.inf) - dt
        self._add("T2-26", obs / t2, obs, t2, r0, v0, ok, offset, adaptive=ad,
                  reason=NO_INTEGRATOR)
        obs = np.nan_to_num(t_s1, nan=np.inf) - dt
        # never leaves: a last exit after entry counts as never having entered for good
        left = np.isfinite(t_exit)
        obs = np.where(left, np.maximum(obs, t_exit - dt), obs)
        # at t_max >= the bound: |s1_i| <= eps and, by (21) with |s1|, |s2| <= eps,
        # |v_i| <= eps' = eps + beta1 eps^q1 + beta2 eps^q2 (else: left and never came back)
        g = self.g
        eps_v = eps + g.beta1 * eps**g.q1 + g.beta2 * eps**g.q2
        outside = (np.abs(y_end[:, :3]) > eps) | (np.abs(y_end[:, 3:6]) > eps_v)
        obs = np.where(outside, np.inf, obs)
        self._add("landing-T2+T1", obs / tl, obs, tl, r0, v0, ok, offset, adaptive=ad,
                  reason=NO_INTEGRATOR)

    def _disturbed(self, r0: np.ndarray, v0: np.ndarray) -> None:
        """(39)/(40) and (31)/(45) under the worst-case and a random disturbance."""
        g, b, dt, offset = self.g, self.b, self.dt, self._offset
        d = g.disturbance
        t2p = b["T2_practical_exact"] * self._sc("s2-39-40")
        t1p = b["landing_time_bound_disturbed"] * self._sc("s1-31-45")
        # a fixed step can overshoot the s2 band by one step's increment of s2 at the band
        # edge, dt |s2'| <= dt (alpha1 c^g1 + alpha2 c^g2 + a_max) (c = band + floor), on top
        # of the measured floor
        # (evaluated at c = band + floor + one increment: RK4's stages see |s2| up to there)
        def step(c):
            return dt * (g.alpha1 * c**g.g1 + g.alpha2 * c**g.g2 + d.a_max)

        c = b["s2_bound"] + s2_floor(dt)
        tol2 = s2_floor(dt) + step(c + step(c))
        # s1's band (31) is (44) with eta = the s2 band; with s2 up to tol2 beyond it the same
        # formula gives the s1 band the integrator can hold, plus the s1 floor
        tol1 = (neighborhood(b["s2_bound"] + tol2, g.beta1, g.beta2, g.q1, g.q2, d.theta2)
                - b["s1_bound"] + s1_floor(dt))
        for kind in ("worst", "random"):
            t_end = float(max(np.max(t1p), np.max(t2p))) * 1.1 + 2 * dt
            res, ok = self._sim(r0, v0, t_end, kind)
            tr = res.trajectory
            t, r, v = tr["t"], tr["r"], tr["v"]
            s2 = np.nan_to_num(surface2(r, v, g), nan=np.inf)
            # (39)/(40): s2 enters its band and, the band being invariant, never leaves
            t_in, stay, k2 = _entry_and_stay(s2, b["s2_bound"], tol2, t)
            self._practical("s2-39-40", t_in, stay, t2p, r0, v0, ok, offset, kind)
            # (31)/(45): once s2 is in (39), the (31) band of s1 is invariant ((44)); before
            # that s1 may leave it, so entry and stay are measured from s2's entry on
            start = np.where(k2 >= 0, k2, r.shape[1])
            t_in, stay, _ = _entry_and_stay(np.nan_to_num(r, nan=np.inf), b["s1_bound"], tol1,
                                            t, start)
            self._practical("s1-31-45", t_in, stay, t1p, r0, v0, ok, offset, kind)

    def _practical(self, claim, t_in, stay, tb, r0, v0, ok, offset, kind) -> None:
        obs = t_in - self.dt  # node-sampled entry: within one step
        # leaving the band (beyond the floor) is a violation: count it as ratio > 1
        ratio = np.where(stay > 1.0, np.maximum(obs / tb, stay), obs / tb)
        self._add(claim, ratio, obs, tb, r0, v0, ok, offset, kind, reason=NO_RECORD)


# --- records --------------------------------------------------------------------------------

@dataclass
class ClaimResult:
    """One claim's outcome: the worst simulated case (ratio = observed / bound), counts, the
    search evidence, and the (shrunk) witness with its reproduction when violated."""

    claim: str
    equation: str
    verdict: str  # holds | violated | inconclusive
    bound: float
    worst: float
    ratio: float
    margin: float
    n_cases: int
    n_checked: int
    n_adaptive: int
    excluded: dict[str, int]
    min_cases: int
    search: list[dict[str, Any]] = field(default_factory=list)
    closest: dict[str, Any] = field(default_factory=dict)
    witness: dict[str, Any] | None = None
    reproduction: str | None = None
    why: str = ""
    points: dict[str, Any] = field(default_factory=dict, repr=False)  # for --plot, not JSON

    @property
    def n_excluded(self) -> int:
        return sum(self.excluded.values())

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("points")
        d["n_excluded"] = self.n_excluded
        return d


def _points(camp: Campaign, claim: str) -> dict[str, np.ndarray]:
    """Every checked (case, axis) of a claim: bound, observed (minus the one-step tolerance)
    and whether it violates (ratio > 1, which for the band claims includes leaving the band)."""
    rows = camp.rows[claim]
    if not rows:
        return {"bound": np.zeros(0), "observed": np.zeros(0), "violated": np.zeros(0, bool)}
    ratio = np.concatenate([r[0] for r in rows])
    good = ratio != -np.inf
    return {"bound": np.concatenate([r[2] for r in rows])[good],
            "observed": np.concatenate([r[1] for r in rows])[good],
            "violated": ratio[good] > 1.0}


def plot_panels(results: list[ClaimResult]) -> list[dict[str, Any]]:
    """The panels of ``lgw.tuning.figures.observed_vs_bound`` (times in s)."""
    return [{"claim": r.claim, "equation": r.equation, "unit": "s", "excluded": r.n_excluded,
             **r.points} for r in results]


def _sim_summary(camp: Campaign, claim: str) -> dict[str, Any]:
    rows = camp.rows[claim]
    out = {"bound": math.nan, "worst": math.nan, "ratio": math.nan, "margin": math.nan,
           "closest": {}}
    if not rows:
        return out
    ratio = np.concatenate([r[0] for r in rows])
    if not np.isfinite(ratio).any() and np.all(ratio == -np.inf):
        return out
    obs = np.concatenate([r[1] for r in rows])
    bnd = np.concatenate([r[2] for r in rows])
    r0 = np.concatenate([r[3] for r in rows])
    v0 = np.concatenate([r[4] for r in rows])
    labels = np.concatenate([[r[6]] * len(r[5]) for r in rows])
    i, ax = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    out.update(bound=float(bnd[i, ax]), worst=float(obs[i, ax]), ratio=float(ratio[i, ax]),
               margin=float(bnd[i, ax] - obs[i, ax]),
               closest={"axis": "xyz"[ax], "r0": [float(x) for x in r0[i]],
                        "v0": [float(x) for x in v0[i]], "disturbance": str(labels[i]) or "none"})
    return out


def reproduction(g: Gains, r0, v0, *, t_max: float, disturbance: str = "none",
                 method: str = "rk4", dt: float = 0.05) -> str:
    """A ready-to-paste shell snippet: the gain file, the state CSV, the ``lgw simulate``."""
    toml = gains_to_toml(g, "witness of lgw verify mars").rstrip("\n")
    row = ",".join(f"{float(x):.17g}" for x in (*r0, *v0, M0))
    cmd = (f"lgw simulate mars --gains witness_gains.toml --initial-states witness_states.csv "
           f"--drag none --t-max {t_max:.6g} --disturbance {disturbance}")
    if disturbance != "none" and g.disturbance is not None:
        cmd += f" --dist-amplitude {g.disturbance.a_max:.17g}"
    cmd += " --method dopri5" if method == "dopri5" else f" --dt {dt:g}"
    return (f"cat > witness_gains.toml <<'EOF'\n{toml}\nEOF\n"
            f"printf 'rx,ry,rz,vx,vy,vz,m\\n{row}\\n' > witness_states.csv\n{cmd}")

# --- search phase: the engine on the reduced per-axis loop, this gain set -----------------

def _fix(pr: Problem, values: Mapping[str, float]) -> Problem:
    from dataclasses import replace
    return replace(pr, dims=tuple(d for d in pr.dims if d.name not in values),
                   fixed={**pr.fixed, **values})


def claim_problems(claim: str, g: Gains, axis: int, scale: float = 1.0) -> list[Problem]:
    """The search problems of a claim for axis ``axis`` of the gain set (gains fixed; the
    initial surfaces free).  ``scale`` multiplies the claim's time bound, as in Campaign."""
    vals: dict[str, float] = dict(g.axis(axis))
    if g.disturbance is not None:
        d = g.disturbance
        vals.update(a_max=d.a_max, theta1=d.theta1, theta2=d.theta2)
    if claim == "reaching-16":
        prs = [S._reaching_problem("T1*", "T1_exact", "s1", scale)]
    elif claim == "T2-26":
        prs = [S._reaching_problem("T2*", "T2_exact", "s2", scale)]
    elif claim == "landing-T2+T1":
        prs = [S._landing_problem("T1* + T2*", lambda p: S._sum_exact(p) * scale)]
    elif claim == "s2-39-40":
        prs = [S._s2_band_problem(), S._t2_practical_problem("T2_practical_exact", scale)]
    elif claim == "s1-31-45":
        prs = [S._s1_band_problem(),
               S._disturbed_landing_problem("(40) + (45) exact", lambda p: S._t3_sum(p) * scale)]
    else:
        raise ParameterError("claim", claim, f"one of {', '.join(CLAIMS)}")
    return [_fix(p, vals) for p in prs]


def _evaluate_once(pr: Problem) -> Search:
    """A problem with nothing left to search (the sup over states is a closed form at this
    gain set, e.g. the equilibrium band): one exact evaluation, re-checked if negative."""
    from lgw.theory.evidence import Witness
    p = pr.point([])
    m = float(pr.margin(p))
    w = None
    if m < 0:
        w = Witness(point=p, margin=m, method=pr.route, rechecked_margin=float(pr.recheck(p)),
                    recheck_method=pr.recheck_method)
    return Search(domain=pr.domain(), method=f"exact evaluation ({pr.route})", evaluations=1,
                  best_margin=m, best_point=p, counter=w, relative=pr.relative)


def search_claim(claim: str, g: Gains, budget: Budget, scale: float = 1.0
                 ) -> list[tuple[int, Search]]:
    """(axis, Search) for each axis with distinct gains and each problem of the claim."""
    out = []
    seen: list[dict] = []
    for axis in range(3):
        key = g.axis(axis)
        if key in seen:
            continue
        seen.append(key)
        for pr in claim_problems(claim, g, axis, scale):
            out.append((axis, falsify(pr, budget) if pr.dims else _evaluate_once(pr)))
    return out


def _search_witness(g: Gains, claim: str, axis: int, s: Search, dt: float) -> tuple[dict, str]:
    """The witness as a state of the full simulator and its reproduction."""
    p = dict(s.counter.point)
    ax = g.axis(axis)
    s1 = float(p.get("s1_0", p.get("s0", p.get("s1_e", 1.0))))
    s2 = float(p.get("s2_0", 0.0 if claim == "reaching-16" else p.get("s0", 0.0)))
    if claim == "T2-26":
        s1, s2 = 1.0, float(p["s0"])
    r = s1
    v = s2 - (ax["beta1"] * np.sign(r) * abs(r) ** ax["q1"] + ax["beta2"] * np.sign(r)
              * abs(r) ** ax["q2"])
    r0 = [r, r, r]
    v0 = [float(v)] * 3
    t_b = max(b[k] for b in axis_bounds(g).values()
              for k in ("landing_time_bound",)) * 1.5
    dist = "worst" if claim in GROUPS["disturbed"] else "none"
    if dist != "none":
        t_b = max(b["landing_time_bound_disturbed"] for b in axis_bounds(g).values()) * 1.5
    wit = {"source": "search (reduced per-axis loop)", "axis": "xyz"[axis],
           "point": {k: float(x) for k, x in p.items()}, "margin": s.counter.margin,
           "rechecked_margin": s.counter.rechecked_margin,
           "recheck_method": s.counter.recheck_method, "r0": r0, "v0": v0,
           "confirmed": s.counter.confirmed}
    return wit, reproduction(g, r0, v0, t_max=t_b, disturbance=dist, method="dopri5", dt=dt)


# --- simulation phase: Hypothesis drives the states ---------------------------------------

def _simulate_group(g: Gains, group: str, opts: VerifyOptions, camp: Campaign,
                    n_examples: int) -> dict[str, Any] | None:
    """Hypothesis over batches of states for one claim group; returns the shrunk failing
    case (or None).  Every example is flown and counted in ``camp``."""
    try:
        from hypothesis import HealthCheck, given, settings, target
        from hypothesis import seed as hseed
        from hypothesis.database import DirectoryBasedExampleDatabase
        from lgw.testing.mars import state_batches
    except ImportError:
        raise ParameterError("hypothesis", "not installed",
                             'needed by lgw verify: pip install "lgw[verify]"') from None
    claims = GROUPS[group]
    failing: dict[str, Any] = {}
    db = (DirectoryBasedExampleDatabase(str(Path(opts.database) / "mars" / group))
          if opts.database is not None else None)

    @settings(max_examples=n_examples, deadline=None, database=db, derandomize=False,
              suppress_health_check=list(HealthCheck), print_blob=False)
    @given(states=state_batches(1, 3))
    def prop(states):
        r0, v0 = states
        mark = {c: len(camp.rows[c]) for c in claims}
        camp.run_batch(r0, v0, offset=0, claims=claims)
        for c in claims:
            new = camp.rows[c][mark[c]:]
            fin = np.concatenate([r[0][np.isfinite(r[0])] for r in new]) if new else []
            if len(fin):
                target(float(np.max(fin)), label=c)  # once per label and example
            for ratio, obs, bnd, rr, vv, _case, label in new:
                if np.any(ratio > 1.0):
                    i, ax = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
                    failing.clear()
                    failing.update(claim=c, axis="xyz"[ax], r0=[float(x) for x in rr[i]],
                                   v0=[float(x) for x in vv[i]], disturbance=label or "none",
                                   observed=float(obs[i, ax]), bound=float(bnd[i, ax]),
                                   ratio=float(ratio[i, ax]), source="simulation "
                                   "(simulate_batch, shrunk by Hypothesis)")
                    raise AssertionError(f"{c} violated")

    if opts.seed is not None:
        prop = hseed(opts.seed)(prop)
    try:
        prop()
    except AssertionError:
        return dict(failing) if failing else None
    return None


def run_verify(g: Gains, opts: VerifyOptions = VerifyOptions(),
               progress: Callable[[str], None] | None = None) -> list[ClaimResult]:
    """Every claim of this module for the gain set; see the module docstring."""
    camp = Campaign(g, dt=opts.dt, eps=opts.eps, seed=opts.seed or 0, scale=dict(opts.scale))
    prof = PROFILES[opts.profile]
    budget = prof["budget"] if opts.seed is None else Budget(
        **{**asdict(prof["budget"]), "seed": opts.seed})
    n_ex = opts.examples or prof["examples"]
    sim_fail: dict[str, dict] = {}
    if opts.simulate:
        for group in GROUPS:
            if progress:
                progress(f"simulating {group}")
            f = _simulate_group(g, group, opts, camp, n_ex)
            if f:
                sim_fail[f["claim"]] = f
    out = []
    for claim, eq in CLAIMS.items():
        if progress:
            progress(f"searching {claim}")
        searches = (search_claim(claim, g, budget, opts.scale.get(claim, 1.0))
                    if opts.search else [])
        summ = _sim_summary(camp, claim)
        res = ClaimResult(claim, eq, "holds", summ["bound"], summ["worst"], summ["ratio"],
                          summ["margin"], camp.cases[claim], camp.checked[claim],
                          camp.adaptive[claim], dict(camp.excluded[claim]), opts.min_cases,
                          search=[{"axis": "xyz"[a], **s.to_dict(), "status": s.status}
                                  for a, s in searches], closest=summ["closest"])
        res.points = _points(camp, claim)
        refuting = [(a, s) for a, s in searches if s.status == "refuted"]
        if refuting:
            a, s = refuting[0]
            res.verdict = "violated"
            res.witness, res.reproduction = _search_witness(g, claim, a, s, opts.dt)
            res.why = f"search witness on axis {'xyz'[a]}: margin {s.counter.margin:.4g}"
        elif claim in sim_fail:
            f = sim_fail[claim]
            res.verdict = "violated"
            res.witness = f
            t_max = f["bound"] * 1.2 + 2 * opts.dt
            res.reproduction = reproduction(g, f["r0"], f["v0"], t_max=t_max,
                                            disturbance=f["disturbance"], dt=opts.dt)
            res.why = (f"simulated case over its bound: observed {f['observed']:.4g} s > "
                       f"{f['bound']:.4g} s")
        elif res.n_checked < opts.min_cases:
            res.verdict = "inconclusive"
            res.why = (f"{res.n_checked} checked simulated cases < --min-cases "
                       f"{opts.min_cases} ({res.n_excluded} excluded)")
        out.append(res)
    return out


def certificate_scale(g: Gains) -> dict[str, float]:
    """A gains file's [certificate] promises ``landing_time_bound`` (s, max over axes): when
    it is smaller than the bound the workbench derives, the promise is what is checked (the
    bound scaled by promise / derived)."""
    cert = g.extra.get("certificate") if g.extra else None
    if not isinstance(cert, dict) or "landing_time_bound" not in cert:
        return {}
    promised = float(cert["landing_time_bound"])
    derived = landing_time_bound(g)
    return {"landing-T2+T1": promised / derived} if promised < derived else {}


def exit_code(results: list[ClaimResult]) -> int:
    """1 when a bound is violated, else 4 when a claim is inconclusive, else 0."""
    if any(r.verdict == "violated" for r in results):
        return 1
    if any(r.verdict == "inconclusive" for r in results):
        return 4
    return 0
