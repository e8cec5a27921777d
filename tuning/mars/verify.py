"""Property campaign for seed 000's proven bounds (``lgw verify mars``).

The same properties as ``tests/test_properties.py``, run on random initial states drawn from a
``numpy.random.SeedSequence`` and flown in batches through ``lgw.sim.mars.batch.simulate_batch``
with the
corrected law, no thrust limit and no drag (the bounds are stated for the plant without them):

  reaching-16    (16)/(18): on s2 = 0, s1 reaches eps by T(s1(0)) <= T1_exact <= T1_polyakov
  T2-26          (26): the first entry of |s2_i| <= eps is within T2_exact (no disturbance)
  landing-T2+T1  sound landing bound T2_exact + T1_exact: |s1_i| <= eps and never leaves after
  s2-39-40       (39)/(40): under |a_p,i| <= a_max (worst case and random), |s2_i| enters the
                 (39) neighbourhood within T2_practical_exact and never leaves
  s1-31-45       (31)/(45): |s1_i| enters the (31) neighbourhood within T2_practical_exact +
                 T1_practical_exact (landing_time_bound_disturbed) and never leaves

Tolerances come from the integrator, never from a fudge factor: an event is located to within
one step dt (times), and an explicit RK4 step leaves a chattering floor on s2 of about
0.85 dt^1.5 m/s (docs/sim.md, ``benchmarks/bench_sim.py --floor``: 9.0e-3 m/s at dt = 0.05 s);
at the edge of a band one step can overshoot it by one step's increment of s2, so the band
tolerance of s2 is tol2 = S2_FLOOR_COEF dt^1.5 + inc(c), inc(c) = dt (alpha1 c^g1 + alpha2 c^g2
+ a_max) the most one step of s2' of (25) can move at |s2| = c, c = band + floor + inc(band +
floor) (where RK4's stages can be); that of s1 is the growth of the
(31) band when its eta, the s2 band, grows by tol2, plus the s1 floor (1.4e-4 m at dt = 0.05 s,
fitted as 0.22 dt^2.46).  Entry into a band means |s| <= band + tolerance.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
from lgw.sim.mars.batch import simulate_batch
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import axis_bounds, neighborhood, reaching_time
from lgw.theory.mars.gains import Gains

# Measured chattering floors (docs/sim.md "Chattering floor and eps", Table I, RK4):
# max |s2| = 9.0e-3 m/s at dt = 0.05 s, fitted as 0.85 dt^1.5 over dt in [0.01, 0.2];
# max |s1| = 2.6e-6, 1.4e-4, 7.5e-4, 4.1e-3 m at dt = 0.01, 0.05, 0.1, 0.2 s: 0.22 dt^2.46
# (log-log fit through the end points; reproduces 1.35e-4 at 0.05 s).
S2_FLOOR_COEF = 0.85
S1_FLOOR_COEF = 0.22
S1_FLOOR_EXP = 2.46
M0 = 1905.0  # kg, Table III mass (irrelevant to the bounds: the law divides it out)

CLAIMS = {
    "reaching-16": "(16),(18)",
    "T2-26": "(26)",
    "landing-T2+T1": "T2*+T1*",
    "s2-39-40": "(39),(40)",
    "s1-31-45": "(31),(45)",
}


def s2_floor(dt: float) -> float:
    return S2_FLOOR_COEF * dt**1.5


def s1_floor(dt: float) -> float:
    return S1_FLOOR_COEF * dt**S1_FLOOR_EXP


@dataclass
class ClaimResult:
    """Outcome of one claim over a campaign; ratio = observed / bound (worst case)."""

    claim: str
    equation: str
    bound: float
    worst: float
    ratio: float
    margin: float
    verdict: str
    n_cases: int
    n_nonfinite: int
    n_unresolved: int
    closest: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


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


def sig(x: np.ndarray, p: float) -> np.ndarray:
    return np.sign(x) * np.abs(x) ** p


def surface2(r: np.ndarray, v: np.ndarray, g: Gains) -> np.ndarray:
    """s2 of seed 000 (21), per axis (last dimension 3): v + beta1 sig(r,q1) + beta2 sig(r,q2)."""
    return v + g.beta1 * sig(r, g.q1) + g.beta2 * sig(r, g.q2)


def on_surface2(r0: np.ndarray, g: Gains) -> np.ndarray:
    """The velocity that puts the state on s2 = 0 (21): then s1 obeys (16) alone."""
    return -(g.beta1 * sig(r0, g.q1) + g.beta2 * sig(r0, g.q2))


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
        self.nonfinite = dict.fromkeys(CLAIMS, 0)
        self.unresolved = dict.fromkeys(CLAIMS, 0)
        self.cases = dict.fromkeys(CLAIMS, 0)

    def _sc(self, claim: str) -> float:
        return self.scale.get(claim, 1.0)

    def _add(self, claim: str, ratio: np.ndarray, observed: np.ndarray, bound: np.ndarray,
             r0: np.ndarray, v0: np.ndarray, ok: tuple[np.ndarray, np.ndarray], offset: int,
             label: str = "") -> None:
        """ratio, observed (n, 3); ok = (finite, resolved) per case."""
        self.nonfinite[claim] += int((~ok[0]).sum())
        self.unresolved[claim] += int((ok[0] & ~ok[1]).sum())
        ok = ok[0] & ok[1]
        self.cases[claim] += len(ok)
        case = np.arange(len(ok)) + offset
        self.rows[claim].append((np.where(ok[:, None], ratio, -np.inf), observed,
                                 np.broadcast_to(bound, ratio.shape), r0, v0, case, label))

    def _sim(self, r0, v0, t_max, disturbance="none"):
        g = self.g
        res = simulate_batch(r0, v0, np.full(len(r0), M0), g, drag="none", dt=self.dt,
                             eps=self.eps, t_max=t_max, stop="t_max", disturbance=disturbance,
                             dist_amplitude=g.disturbance.a_max, seed=self.seed,
                             case_offset=self._offset, record=True)
        tr = res.trajectory
        a_max = 0.0 if disturbance == "none" else g.disturbance.a_max
        with np.errstate(all="ignore"):
            bad = unresolved(tr["r"], tr["v"], g, a_max, self.dt)
        return res, (~res.nonfinite, ~bad)

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
        res, ok = self._sim(r0, vs, float(np.max(t1)) + 2 * dt)
        t_ex = reaching_time(r0, g.beta1, g.beta2, g.q1, g.q2)  # exact T(s0) <= T1_exact
        assert np.all(t_ex <= b["T1_exact"] * (1 + 1e-9)) and np.all(
            b["T1_exact"] <= b["T1_polyakov"] * (1 + 1e-9))
        obs = np.nan_to_num(res.t_s1, nan=np.inf) - dt  # entry located within one step
        self._add("reaching-16", obs / t1, obs, t1, r0, vs, ok, offset)

    def _undisturbed(self, r0: np.ndarray, v0: np.ndarray) -> None:
        """T2 (26) and the landing bound, no disturbance."""
        b, dt, eps, offset = self.b, self.dt, self.eps, self._offset
        t2 = b["T2_exact"] * self._sc("T2-26")
        tl = b["landing_time_bound"] * self._sc("landing-T2+T1")
        res, ok = self._sim(r0, v0, float(max(np.max(tl), np.max(t2))) + 2 * dt)
        obs = np.nan_to_num(res.t_s2, nan=np.inf) - dt
        self._add("T2-26", obs / t2, obs, t2, r0, v0, ok, offset)
        obs = np.nan_to_num(res.t_s1, nan=np.inf) - dt
        # never leaves: a last exit after entry counts as never having entered for good
        left = np.isfinite(res.t_s1_last_exit)
        obs = np.where(left, np.maximum(obs, res.t_s1_last_exit - dt), obs)
        # at t_max >= the bound: |s1_i| <= eps and, by (21) with |s1|, |s2| <= eps,
        # |v_i| <= eps' = eps + beta1 eps^q1 + beta2 eps^q2 (else: left and never came back)
        g = self.g
        eps_v = eps + g.beta1 * eps**g.q1 + g.beta2 * eps**g.q2
        outside = (np.abs(res.y_end[:, :3]) > eps) | (np.abs(res.y_end[:, 3:6]) > eps_v)
        obs = np.where(outside, np.inf, obs)
        self._add("landing-T2+T1", obs / tl, obs, tl, r0, v0, ok, offset)

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
        self._add(claim, ratio, obs, tb, r0, v0, ok, offset, kind)

    def results(self) -> list[ClaimResult]:
        out = []
        for claim, eq in CLAIMS.items():
            rows = self.rows[claim]
            if not rows:
                continue
            ratio = np.concatenate([r[0] for r in rows])
            obs = np.concatenate([r[1] for r in rows])
            bnd = np.concatenate([r[2] for r in rows])
            r0 = np.concatenate([r[3] for r in rows])
            v0 = np.concatenate([r[4] for r in rows])
            case = np.concatenate([r[5] for r in rows])
            labels = np.concatenate([[r[6]] * len(r[5]) for r in rows])
            if not np.isfinite(ratio).any() and np.all(ratio == -np.inf):
                out.append(ClaimResult(claim, eq, math.nan, math.nan, math.nan, math.nan,
                                       "no finite case", self.cases[claim],
                                       self.nonfinite[claim], self.unresolved[claim]))
                continue
            i, ax = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
            w = float(ratio[i, ax])
            verdict = "holds" if w <= 1.0 else "VIOLATED"
            closest = {"case": int(case[i]), "axis": "xyz"[ax], "seed": self.seed,
                       "r0": [float(x) for x in r0[i]], "v0": [float(x) for x in v0[i]],
                       "disturbance": str(labels[i]) or "none"}
            out.append(ClaimResult(claim, eq, float(bnd[i, ax]), float(obs[i, ax]), w,
                                   float(bnd[i, ax] - obs[i, ax]), verdict, self.cases[claim],
                                   self.nonfinite[claim], self.unresolved[claim], closest))
        return out


def run_campaign(g: Gains, examples: int, seed: int, *, dt: float = 0.05, eps: float = 0.05,
                 scale: dict[str, float] | None = None, batch: int = 16,
                 progress=None) -> list[ClaimResult]:
    """Draw ``examples`` states from SeedSequence(seed), fly them in batches, check every claim.

    ``progress(done, total)`` is called after each batch."""
    if examples < 1:
        raise ParameterError("examples", examples, "must be >= 1")
    camp = Campaign(g, dt=dt, eps=eps, seed=seed, scale=scale, batch=batch)
    r0, v0, _ = sample_states(examples, seed)
    for start in range(0, examples, batch):
        sl = slice(start, min(start + batch, examples))
        camp.run_batch(r0[sl], v0[sl], offset=start)
        if progress is not None:
            progress(sl.stop, examples)
    return camp.results()


def exit_code(results: list[ClaimResult]) -> int:
    """1 when a proven bound is violated, else 0."""
    return int(any(r.verdict == "VIOLATED" for r in results))
