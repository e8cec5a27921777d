"""Monte Carlo campaigns of seed 001: the failure time and level and the initial state drawn
over an envelope, flown on the compiled kernel in chunks, per-case numbers in flat arrays
(no records), streamed one record at a time (statistics: ``lgw.tuning.stats``, over the
finite values of the cases whose outcome is in ``COUNTED``).

The envelope (``Envelope``; defaults ``lgw.sim.lunar.parameters.MC_*``, chosen around seed
001 Section 5, which gives one case and no dispersion):
  failure time   uniform in [f_lo, f_hi] t_f  (the paper: t_f / 2);
  thrust left    T_a uniform in [ta_lo, ta_hi] (the paper: 0.7);
  height error   uniform in [dh_lo, dh_hi] m  (the paper: 100 m);
  velocity error uniform in [-dv_i, dv_i] m/s on axis i (the paper: [2, 3, 5]);
  attitude error a rotation of up to att_deg about a uniformly random axis, or about the
                 body x axis (the thrust axis: a roll, no pointing error) with
                 att_axis = "x" (the paper: 53.1 deg about x), body rates 0 (the paper's).
What is drawn: "all", "states" (the failure as the run options give it) or "failure" (the
Section 5 initial errors).  Each case draws from its own child of SeedSequence(seed), so a
case's draw does not depend on the number of cases.

Convergence: the first ``CHECK_CASES`` cases are re-flown at dt / 2 and every number the
campaign prints statistics of (``NUMBERS`` that are quoted, ``lgw.sim.lunar.convergence.QUOTED``)
and the outcomes compared; the campaign's statistics are flagged when any of them differs by
more than 1 % (or its floor).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from lgw.sim.lunar import parameters as SP
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.theory.errors import ParameterError
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.gains import Gains

DISPERSIONS = ("all", "states", "failure")
CHUNK = 512  # cases per kernel call (memory ~ 2 kB per case)
CHECK_CASES = 8  # cases re-flown at dt / 2 for the convergence check
# memory a campaign holds per case, bytes (for the estimate before the run): the spawned
# SeedSequence of each case (~420 B, measured with tracemalloc), its 9 uniforms and the draw
# with its temporaries (~300 B), the NUMBERS arrays and the outcome code (~120 B), rounded up
BYTES_PER_CASE = 1024
# per-case numbers of a campaign (lgw.sim.lunar.scenario.case_numbers) kept as arrays
NUMBERS = ("eh_final_m", "ev_final_norm_m_s", "max_abs_eh_m", "max_abs_ev_m_s",
           "max_abs_eh_after_failure_m", "orbit_saturated_s",
           "orbit_saturated_after_failure_s", "thrust_cmd_max_after_failure_N",
           "torque_saturated_initial_s", "torque_saturation_end_s", "d0e_orbit_final",
           "d0e_attitude_final", "min_abs_eq0",
           "mass_final_kg", "t_outcome_s")
UNITS = {"eh_final_m": "m", "ev_final_norm_m_s": "m/s", "max_abs_eh_m": "m",
         "max_abs_ev_m_s": "m/s", "max_abs_eh_after_failure_m": "m", "orbit_saturated_s": "s",
         "orbit_saturated_after_failure_s": "s", "thrust_cmd_max_after_failure_N": "N",
         "torque_saturated_initial_s": "s", "torque_saturation_end_s": "s",
         "d0e_orbit_final": "m/s^2",
         "d0e_attitude_final": "rad/s^2", "min_abs_eq0": "1", "mass_final_kg": "kg",
         "t_outcome_s": "s"}
COUNTED = ("completed",)  # outcomes whose cases enter the statistics


@dataclass(frozen=True)
class Envelope:
    """The box a campaign draws from (see the module docstring; units s-fractions, -, m, m/s,
    deg)."""

    t_fail_fraction: tuple[float, float] = SP.MC_T_FAIL_FRACTION
    ta: tuple[float, float] = SP.MC_TA
    dh: tuple[float, float] = SP.MC_DH
    dv: tuple[float, float, float] = (SP.MC_DV, SP.MC_DV, SP.MC_DV)
    att_deg: float = SP.MC_ATT_DEG
    name: str = "campaign"
    att_axis: str = "random"

    def __post_init__(self) -> None:
        def box(name: str, lo: float, hi: float, vmin: float, vmax: float) -> None:
            if not (np.isfinite(lo) and np.isfinite(hi) and vmin <= lo <= hi <= vmax):
                raise ParameterError(f"envelope.{name}", [lo, hi], f"must be [lo, hi] with "
                                     f"{vmin:g} <= lo <= hi <= {vmax:g}")

        box("t_fail_fraction", *self.t_fail_fraction, 0.0, 1.0)
        box("ta", *self.ta, 1e-6, 1.0)
        box("dh", *self.dh, -1e4, 1e4)
        if len(self.dv) != 3:
            raise ParameterError("envelope.dv", self.dv, "three half-widths, m/s")
        for k, x in enumerate(self.dv):
            box(f"dv[{k}]", 0.0, x, 0.0, 1e3)
        box("att_deg", 0.0, self.att_deg, 0.0, 180.0)
        if self.att_axis not in ("random", "x"):
            raise ParameterError("envelope.att_axis", self.att_axis, "random or x")

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "t_fail_fraction_of_tf": list(self.t_fail_fraction),
                "ta": list(self.ta),
                "dh_m": list(self.dh), "dv_half_width_m_s": list(self.dv),
                "attitude_error_deg": self.att_deg, "attitude_error_axis": self.att_axis}


# the paper's Section 5 scenario as an envelope: its failure exactly (t_f / 2, T_a = 0.7), its
# initial errors as the corner of a box (height error within +-100 m, velocity error within
# +-[2, 3, 5] m/s, attitude error a roll about the thrust axis of up to its 53.13 deg)
SECTION5 = Envelope(t_fail_fraction=(0.5, 0.5), ta=(P.T_A, P.T_A), dh=(-P.DH0, P.DH0),
                    dv=tuple(float(x) for x in P.DV0),
                    att_deg=float(np.degrees(2 * np.arccos(P.Q0[0]))), name="section5",
                    att_axis="x")
CAMPAIGN = Envelope()
ENVELOPES = {"section5": SECTION5, "campaign": CAMPAIGN}


@dataclass(frozen=True)
class Draw:
    """A campaign's cases: initial errors dh (N,) m, dv (3, N) m/s, Q0 (4, N), omega0 (3, N)
    rad/s, and the failure per case: T_a (N,), t_fail (N,) s."""

    dh: np.ndarray
    dv: np.ndarray
    Q0: np.ndarray
    w0: np.ndarray
    ta: np.ndarray
    t_fail: np.ndarray

    def __len__(self) -> int:
        return int(self.dh.shape[0])

    def take(self, sl: slice) -> Draw:
        return Draw(self.dh[sl], self.dv[:, sl], self.Q0[:, sl], self.w0[:, sl], self.ta[sl],
                    self.t_fail[sl])


def draw(n: int, seed: int, tf: float, opts: RunOptions, env: Envelope = Envelope(),
         dispersion: str = "all") -> Draw:
    """N cases over the envelope (module docstring); each case from its own child of
    SeedSequence(seed)."""
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
        raise ParameterError("cases", n, "must be an integer >= 1")
    if dispersion not in DISPERSIONS:
        raise ParameterError("dispersion", dispersion, f"one of {', '.join(DISPERSIONS)}")
    u = np.empty((n, 9))
    for i, child in enumerate(np.random.SeedSequence(seed).spawn(n)):
        u[i] = np.random.default_rng(child).random(9)
    states = dispersion in ("all", "states")
    failure = dispersion in ("all", "failure")
    if states:
        dh = env.dh[0] + (env.dh[1] - env.dh[0]) * u[:, 0]
        dv = (np.asarray(env.dv) * (2 * u[:, 1:4] - 1)).T
        if env.att_axis == "x":
            axis = np.tile([[1.0], [0.0], [0.0]], (1, n))
        else:
            axis = np.stack([np.cos(2 * np.pi * u[:, 4]) * np.sqrt(1 - (2 * u[:, 5] - 1) ** 2),
                             np.sin(2 * np.pi * u[:, 4]) * np.sqrt(1 - (2 * u[:, 5] - 1) ** 2),
                             2 * u[:, 5] - 1])
        ang = np.radians(env.att_deg) * u[:, 6]
        Q0 = np.vstack([np.cos(ang / 2), np.sin(ang / 2) * axis])
    else:
        dh = np.full(n, P.DH0)
        dv = np.tile(P.DV0[:, None], (1, n))
        Q0 = np.tile(P.Q0[:, None], (1, n))
    if failure:
        lo, hi = env.t_fail_fraction
        t_fail = tf * (lo + (hi - lo) * u[:, 7])
        ta = env.ta[0] + (env.ta[1] - env.ta[0]) * u[:, 8]
    else:
        t_fail = np.full(n, tf / 2 if opts.t_fail is None else opts.t_fail)
        ta = np.full(n, opts.Ta)
    return Draw(dh, dv, Q0, np.zeros((3, n)), ta, t_fail)


@dataclass
class CampaignResult:
    """Per-case numbers (``numbers``: name -> (N,) array; ``outcome`` codes (N,)), the draw,
    and the convergence re-check of the first cases."""

    draw: Draw
    numbers: dict[str, np.ndarray]
    outcome: np.ndarray
    opts: RunOptions
    envelope: Envelope
    dispersion: str
    seed: int
    convergence: list[Any]

    def __len__(self) -> int:
        return len(self.draw)


def fly(gains: Gains, opts: RunOptions, d: Draw, progress: Any = None,
        chunk: int = CHUNK) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Fly the draw's cases (chunked) with one gain set; per-case numbers and outcome codes."""
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.closed_loop import initial_state, make_context
    from lgw.sim.lunar.reference import reference
    from lgw.sim.lunar.scenario import case_numbers

    ref = reference()
    n = len(d)
    out = {k: np.full(n, np.nan) for k in NUMBERS}
    codes = np.zeros(n, np.int64)
    for a in range(0, n, chunk):
        b = min(n, a + chunk)
        part = d.take(slice(a, b))
        m = b - a
        ctx = make_context(ref, [gains] * m, opts)
        X0 = initial_state(ref, part.dh, part.dv, part.Q0, part.w0, [gains] * m)
        res = simulate(ctx, X0, record=False, failures=(part.ta, part.t_fail))
        for j in range(m):
            nums = case_numbers(res.cases, ctx, j)
            for k in NUMBERS:
                out[k][a + j] = nums[k]
        codes[a:b] = res.cases["outcome"]
        if progress is not None:
            progress.advance(b, n)
    return out, codes


def run(gains: Gains, opts: RunOptions, n: int, seed: int, env: Envelope = Envelope(),
        dispersion: str = "all", progress: Any = None, check_cases: int = CHECK_CASES
        ) -> CampaignResult:
    """A campaign of n cases (module docstring), with the first ``check_cases`` re-flown at
    dt / 2."""
    from lgw.sim.lunar import convergence as CV
    from lgw.sim.lunar.outcomes import OUTCOMES
    from lgw.sim.lunar.reference import reference

    d = draw(n, seed, reference().tf, opts, env, dispersion)
    nums, codes = fly(gains, opts, d, progress)
    checks = []
    k = min(n, check_cases)
    if k:
        fine_opts = replace(opts, dt=opts.dt / CV.REFINE_CAMPAIGN)
        fnums, fcodes = fly(gains, fine_opts, d.take(slice(0, k)))
        for i in range(k):
            checks.append(CV.compare({q: nums[q][i] for q in NUMBERS},
                                     {q: fnums[q][i] for q in NUMBERS}, opts.dt,
                                     fine_opts.dt, OUTCOMES[codes[i]], OUTCOMES[fcodes[i]],
                                     {q: CV.QUOTED[q] for q in NUMBERS if q in CV.QUOTED}))
    return CampaignResult(d, nums, codes, opts, env, dispersion, seed, checks)


def iter_case_records(res: CampaignResult) -> Iterator[dict[str, Any]]:
    """One JSON-ready record per case (flat memory: built on demand)."""
    from lgw.sim.lunar.outcomes import OUTCOMES, json_safe

    d = res.draw
    for i in range(len(res)):
        rec = {"case": i, "dh0_m": float(d.dh[i]), "dv0_m_s": d.dv[:, i].tolist(),
               "Q0": d.Q0[:, i].tolist(), "t_fail_s": float(d.t_fail[i]),
               "ta": float(d.ta[i]), "outcome": OUTCOMES[int(res.outcome[i])]}
        rec.update({k: float(res.numbers[k][i]) for k in NUMBERS})
        yield json_safe(rec)
