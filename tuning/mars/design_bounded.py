"""Gain design for the bounded cascade law (issue 17, ``lgw.theory.mars.bounded``).

Everything the certificate rests on is closed form: for a box of initial states the law's
bounds (``lgw.theory.mars.bounded.axis_box_bounds``) give, per axis and for all t >= 0,
a bound on |F_i| (``thrust_bound``: the command bound times the heaviest mass plus the drag
force at the largest speed) and a bound on the time to enter the landing set (T_s + T_r).
The closed loop is three decoupled axes (the law cancels g and a_m exactly and commands an
acceleration, so the mass drops out), so the design is three independent 5-parameter problems:

  minimise the proven landing-time bound T_land,i over (c1, delta, k1, k2, e1)
  subject to the proven thrust bound <= margin * thrust_max over every box of the envelope,

solved by Nelder-Mead in log coordinates from a few starts (each evaluation is a few closed
forms, ~0.3 ms).  No simulation decides anything about thrust: the bound covers every state of
the box, overshooting states and r_i = 0 included, so there is no keep-out.

If the proven time bound meets tf the certificate is fully proven.  Otherwise the request is
checked by simulation (``check_by_simulation``: the per-axis extreme states and a grid, packed
three axes per case since the axes are decoupled, plus Monte Carlo states) and the certificate
says "time: simulated"; the nearest tf the proven bound meets is reported either way.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import minimize

from lgw.sim.mars.parameters import CD_LANDER, H_MARS, RHO0_MARS
from lgw.theory.errors import ParameterError
from lgw.theory.mars import bounded as B
from lgw.theory.mars.parameters import AREA, AXES, G_MARS, LAND_POS_TOL, LAND_VEL_TOL

# Fixed design choices: e2 and p2 only matter far outside the envelope (fixed time from every
# state); c2 small enough that its terms are negligible on the envelope (they are in the bounds).
E2 = 1.5
P2 = 1.5
C2 = 1e-9
GROUND_SLACK = LAND_POS_TOL  # drag density factor is taken on r_z >= -GROUND_SLACK


def drag_force_coef() -> np.ndarray:
    """(1/2) rho0 C_D A_i exp(GROUND_SLACK/H) (N s^2/m^2): m |a_m,i| <= this * v_i^2 for the
    physical drag model of ``lgw.sim.mars.plant`` on r_z >= -GROUND_SLACK."""
    return 0.5 * RHO0_MARS * CD_LANDER * AREA * math.exp(GROUND_SLACK / H_MARS)


@dataclass(frozen=True)
class BoundedRequest:
    tf: float
    thrust_max: float
    limit: str = "axis"
    margin: float = 0.98  # accept proven thrust bounds up to margin * thrust_max

    def check(self) -> None:
        if not (np.isfinite(self.tf) and self.tf > 0):
            raise ParameterError("--tf", self.tf, "must be a finite number > 0 (s)")
        if not (np.isfinite(self.thrust_max) and self.thrust_max > 0):
            raise ParameterError("--thrust-max", self.thrust_max, "must be a finite number > 0 (N)")
        if self.limit not in ("axis", "norm"):
            raise ParameterError("--limit", self.limit, "must be one of axis, norm")

    def axis_budget(self) -> float:
        """Per-axis thrust budget: with a norm limit each axis gets thrust_max/sqrt(3), so that
        |F| <= sqrt(sum F_i^2) stays under the limit."""
        f = self.margin * self.thrust_max
        return f / math.sqrt(3.0) if self.limit == "norm" else f


def axis_boxes(boxes, i: int) -> list[B.AxisBox]:
    return [B.AxisBox(float(lo[i]), float(hi[i]), float(lo[3 + i]), float(hi[3 + i]))
            for lo, hi in boxes]


def axis_certificate(bg: B.BoundedGains, i: int, boxes, m_max: float) -> dict[str, float]:
    """The proven per-axis numbers over all boxes: thrust bound (N), T_land (s) and the parts."""
    worst: dict[str, float] = {}
    for b in axis_boxes(boxes, i):
        d = B.axis_box_bounds(bg, i, b, pos_tol=LAND_POS_TOL, vel_tol=LAND_VEL_TOL)
        d["F_b"] = float(m_max * (abs(G_MARS[i]) + d["u_b"]) + drag_force_coef()[i] * d["V_b"]**2)
        for k, x in d.items():
            worst[k] = max(worst.get(k, -np.inf), x)
    worst["T_global"] = B.global_time_bound(bg, i, LAND_POS_TOL, LAND_VEL_TOL)
    return worst


def _unpack(x: np.ndarray) -> dict[str, float]:
    c1, dl, k1, k2 = np.exp(x[:4])
    e1 = 0.05 + 0.9 / (1 + math.exp(-x[4]))  # e1 in (0.05, 0.95)
    return {"c1": c1, "delta": dl, "k1": k1, "k2": k2, "e1": e1}


def _gains_axis(p: dict[str, float], i: int, base: dict[str, Any]) -> B.BoundedGains:
    d = dict(base)
    for k in ("c1", "delta", "k1", "k2"):
        d[k] = list(d[k])
        d[k][i] = p[k]
    d["e1"] = p["e1"]
    return B.bounded_gains_from_dict(d)


STARTS = ((3.0, 300.0, 1.0, 1e-4, 0.0), (5.0, 1000.0, 2.0, 1e-3, -1.0),
          (2.0, 100.0, 2.0, 1e-5, -1.5))


def design_axis(i: int, boxes, m_max: float, budget: float, e1: float | None = None,
                maxiter: int = 400) -> tuple[dict[str, float], dict[str, float]]:
    """Minimise the proven T_land of axis i subject to the proven thrust bound <= budget.

    The exponent e1 is shared by the axes (a scalar of the [bounded] table): with ``e1`` given
    it is held fixed.  Returns (gains of the axis, its certificate numbers)."""
    base = {**B.DEFAULT_BOUNDED, "c2": C2, "p2": P2, "e2": E2}

    def cert(x: np.ndarray) -> dict[str, float] | None:
        p = _unpack(x)
        if e1 is not None:
            p["e1"] = e1
        try:
            return axis_certificate(_gains_axis(p, i, base), i, boxes, m_max)
        except (ParameterError, FloatingPointError, ValueError):
            return None

    def obj(x: np.ndarray) -> float:
        c = cert(x)
        if c is None or not np.isfinite(c["T_land"]) or not np.isfinite(c["F_b"]):
            return 1e9
        return c["T_land"] + 1e3 * max(c["F_b"] / budget - 1.0, 0.0)

    best = None
    with np.errstate(all="ignore"):
        for s in STARTS:
            x0 = np.r_[np.log(s[:4]), s[4]]
            res = minimize(obj, x0, method="Nelder-Mead",
                           options={"maxiter": maxiter, "xatol": 1e-3, "fatol": 1e-3})
            if best is None or res.fun < best.fun:
                best = res
    p = _unpack(best.x)
    if e1 is not None:
        p["e1"] = e1
    c = cert(best.x)
    return p, c


@dataclass
class BoundedTuneResult:
    feasible: bool
    time_proven: bool
    reason: str
    gains: B.BoundedGains | None
    axes: dict[str, dict[str, float]]
    T_proven: float
    F_proven: float
    sim: dict[str, Any] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)


def tune_bounded(req: BoundedRequest, boxes, m_max: float, *,
                 progress: Callable[[str], None] | None = None,
                 simulate: Callable[[B.BoundedGains], dict[str, Any]] | None = None,
                 e1_grid: tuple[float, ...] = (0.2, 0.3, 0.45, 0.6)) -> BoundedTuneResult:
    """Design the bounded law for ``req`` over ``boxes`` (list of (lo(7), hi(7)))."""
    req.check()
    say = progress or (lambda msg: None)
    t0 = time.perf_counter()
    budget = req.axis_budget()
    best: tuple[float, float, list, list] | None = None
    for e1 in e1_grid:  # e1 is shared by the axes: an outer loop
        parts, certs = [], []
        for i in range(3):
            p, c = design_axis(i, boxes, m_max, budget, e1=e1)
            parts.append(p)
            certs.append(c)
        T = max(c["T_land"] if c else np.inf for c in certs)
        F = max(c["F_b"] if c else np.inf for c in certs)
        say(f"e1 = {e1:g}: proven landing-time bound {T:.1f} s, thrust bound {F:.0f} N")
        if F <= budget * (1 + 1e-9) and (best is None or T < best[0]):
            best = (T, F, parts, certs)
    t_design = time.perf_counter() - t0
    if best is None:
        return BoundedTuneResult(False, False, f"no gain set found with a proven thrust bound "
                                 f"under {budget:.0f} N per axis", None, {}, np.inf, np.inf,
                                 timings={"design": t_design})
    T, F, parts, certs = best
    d = {**B.DEFAULT_BOUNDED, "c2": C2, "p2": P2, "e2": E2, "e1": parts[0]["e1"]}
    for k in ("c1", "delta", "k1", "k2"):
        d[k] = [float(_round(parts[i][k])) for i in range(3)]
    bg = B.bounded_gains_from_dict(d)
    axes = {ax: axis_certificate(bg, i, boxes, m_max) for i, ax in enumerate(AXES)}
    T = max(a["T_land"] for a in axes.values())
    F = max(a["F_b"] for a in axes.values())
    if F > req.thrust_max * (1 / math.sqrt(3) if req.limit == "norm" else 1.0):
        return BoundedTuneResult(False, False, "rounded gains exceed the thrust limit", bg, axes,
                                 T, F, timings={"design": t_design})
    if T <= req.tf:
        return BoundedTuneResult(True, True, "proven", bg, axes, T, F,
                                 timings={"design": t_design})
    say(f"proven bound {T:.1f} s > tf = {req.tf:g} s: checking tf by simulation")
    t1 = time.perf_counter()
    sim = simulate(bg) if simulate is not None else {}
    t_sim = time.perf_counter() - t1
    ok = bool(sim) and sim["all_landed"] and sim["max_landing_time"] <= req.tf \
        and sim["saturated"] == 0 and sim["below_ground"] == 0
    reason = ("time checked by simulation (not proven)" if ok else
              f"the proven bound is {T:.1f} s and the simulated latest landing is "
              f"{sim.get('max_landing_time', float('nan')):.1f} s")
    return BoundedTuneResult(ok, False, reason, bg, axes, T, F, sim,
                             timings={"design": t_design, "simulate": t_sim})


def _round(x: float) -> float:
    """Round to 4 significant digits *down* for gains where smaller is safer? No: the rounded
    gains are re-certified by ``axis_certificate`` (the certificate is for what is written)."""
    return float(f"{x:.4g}")


def extreme_axis_states(boxes, i: int, n_grid: int = 7) -> np.ndarray:
    """(k, 2) per-axis initial states (r0, v0): a n_grid x n_grid grid of each box (corners
    included) plus r0 = 0 where the box crosses it."""
    out = []
    for b in axis_boxes(boxes, i):
        rr = np.unique(np.r_[np.linspace(b.r_lo, b.r_hi, n_grid),
                             np.clip(0.0, b.r_lo, b.r_hi)])
        vv = np.linspace(b.v_lo, b.v_hi, n_grid)
        R, V = np.meshgrid(rr, vv)
        out.append(np.column_stack([R.ravel(), V.ravel()]))
    return np.concatenate(out)


def packed_states(boxes, m_max: float, n_grid: int = 7, n_mc: int = 256,
                  seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Initial states (r0, v0, m0) that fly every per-axis extreme state: axis i of case j is
    the j-th extreme state of axis i (cycled), since the axes are decoupled; plus n_mc uniform
    states of the boxes.  Mass m_max (the thrust bound's worst case)."""
    per = [extreme_axis_states(boxes, i, n_grid) for i in range(3)]
    n = max(len(p) for p in per)
    r0 = np.column_stack([np.resize(per[i][:, 0], n) for i in range(3)])
    v0 = np.column_stack([np.resize(per[i][:, 1], n) for i in range(3)])
    rng = np.random.default_rng(seed)
    k = rng.integers(len(boxes), size=n_mc)
    lo = np.array([boxes[j][0] for j in k])
    hi = np.array([boxes[j][1] for j in k])
    x = rng.uniform(lo, hi)
    r0 = np.vstack([r0, x[:, :3]])
    v0 = np.vstack([v0, x[:, 3:6]])
    return r0, v0, np.full(len(r0), m_max)
