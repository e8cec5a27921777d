"""Campaigns of seed 000: Table II dispersions, Table III envelope, CSV states; executors.

Initial states:
  ``table2_states(n, seed)``  seed 000 Table II: normal, mean Table I state (r, v, m0),
                              standard deviations 100 m, 10 m/s, 20 kg per component;
  ``table3_states(n, seed)``  seed 000 Table III: uniform in the box r in [-1000, 200] x
                              [0, 2000] x [1000, 1500] m, v in [-15, 45] x [-100, 0] x [-75, 0]
                              m/s; mass = Table I m0 (Table III gives no mass);
  ``read_states_csv(path)``   explicit states, columns rx, ry, rz, vx, vy, vz, m.
Executors (``run_campaign``): local in-process (numba threads over cases), or dask.distributed
on a cluster (``scheduler`` address) or a local cluster (``workers``).  Cases are cut into
chunks of a fixed size that does not depend on the number of workers, every case is
integrated independently, and a random disturbance is drawn from the case's own
SeedSequence(seed).spawn child, so the results are identical whatever the executor layout.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
from lgw.sim import executors
from lgw.sim.mars.batch import OUTCOMES_USED, BatchResult, simulate_batch
from lgw.sim.results import OUTCOMES, counts
from lgw.sim.stats import finite_stats
from lgw.theory.errors import ParameterError
from lgw.theory.inputs import read_csv_columns
from lgw.theory.mars.gains import Gains
from lgw.theory.mars.parameters import M0, M_DRY, R0, V0

TABLE2_STD_R = np.array([100.0, 100.0, 100.0])  # m, seed 000 Table II
TABLE2_STD_V = np.array([10.0, 10.0, 10.0])  # m/s, seed 000 Table II
TABLE2_STD_M = 20.0  # kg, seed 000 Table II
TABLE3_R_MIN = np.array([-1000.0, 0.0, 1000.0])  # m, seed 000 Table III
TABLE3_R_MAX = np.array([200.0, 2000.0, 1500.0])
TABLE3_V_MIN = np.array([-15.0, -100.0, -75.0])  # m/s, seed 000 Table III
TABLE3_V_MAX = np.array([45.0, 0.0, 0.0])
CSV_COLUMNS = ("rx", "ry", "rz", "vx", "vy", "vz", "m")
DEFAULT_CHUNK = 2048

States = tuple[np.ndarray, np.ndarray, np.ndarray]


def _check_n(n: int) -> int:
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
        raise ParameterError("cases", n, "must be an integer >= 1")
    return int(n)


def table2_states(n: int = 300, seed: int = 0) -> States:
    """Seed 000 Table II: (r0 (n,3), v0 (n,3), m0 (n,)) normal about the Table I state."""
    n = _check_n(n)
    rng = np.random.default_rng(seed)
    r0 = R0 + TABLE2_STD_R * rng.standard_normal((n, 3))
    v0 = V0 + TABLE2_STD_V * rng.standard_normal((n, 3))
    m0 = M0 + TABLE2_STD_M * rng.standard_normal(n)
    return r0, v0, m0


def table3_states(n: int = 50, seed: int = 0) -> States:
    """Seed 000 Table III: r0, v0 uniform in the printed box, m0 = Table I m0."""
    n = _check_n(n)
    rng = np.random.default_rng(seed)
    r0 = rng.uniform(TABLE3_R_MIN, TABLE3_R_MAX, (n, 3))
    v0 = rng.uniform(TABLE3_V_MIN, TABLE3_V_MAX, (n, 3))
    return r0, v0, np.full(n, M0)


def table1_state() -> States:
    return R0[None].copy(), V0[None].copy(), np.array([M0])


M0_MAX = 1e9  # kg: m0 x 2.2e-16 x the steps of a run stays below a gram of fuel


def read_states_csv(path: str | Path) -> States:
    """Read explicit initial states: a header with columns rx, ry, rz, vx, vy, vz, m (any order,
    extra columns ignored), one case per row; SI units (``lgw.theory.inputs.read_csv_columns``:
    regular UTF-8 files only, size and row caps, finite numbers).  m <= 0 is refused."""
    name = "--initial-states"
    cols = read_csv_columns(path, name, CSV_COLUMNS)
    data = np.column_stack([cols[c] for c in CSV_COLUMNS])
    bad = np.flatnonzero(~((data[:, 6] > 0) & (data[:, 6] <= M0_MAX)))
    if bad.size:
        raise ParameterError(f"{name} row {bad[0] + 2} column m", float(data[bad[0], 6]),
                             f"must be in (0, {M0_MAX:g}] kg (above, the propellant burnt "
                             "is lost in the rounding of the mass: 1e30 kg saturated at 50 kN "
                             "for 120 s would show 0 kg of fuel)")
    return data[:, :3], data[:, 3:6], data[:, 6]


def chunk_slices(n: int, chunk: int = DEFAULT_CHUNK) -> list[slice]:
    """Deterministic chunking (``lgw.sim.executors.chunk_slices``, seed 000's default size)."""
    return executors.chunk_slices(n, chunk)


def _run_chunk(r0, v0, m0, gains, start: int, opts: dict[str, Any]) -> BatchResult:
    # One chunk on one worker thread; case_offset keeps the per-case disturbance seeds global.
    return simulate_batch(r0, v0, m0, gains, case_offset=start, parallel=False, **opts)


def run_campaign(r0: np.ndarray, v0: np.ndarray, m0: np.ndarray, gains: Gains, *,
                 executor: str = "local", workers: int | None = None,
                 scheduler: str | None = None, processes: bool = True,
                 chunk: int = DEFAULT_CHUNK, progress: bool = False,
                 **opts: Any) -> BatchResult:
    """Run a campaign with ``lgw.sim.mars.batch.simulate_batch`` options ``opts``.

    executor="local": in-process, numba threads over cases.
    executor="dask": ``scheduler`` (address of a running dask scheduler) or a LocalCluster
      with ``workers`` single-threaded workers (``processes=False`` keeps them in-process).
    Both go through ``lgw.sim.executors`` (the same chunks, so the same results).
    """
    if executor == "local":
        return simulate_batch(r0, v0, m0, gains, progress=progress, chunk=chunk, **opts)
    if executor != "dask":
        raise ParameterError("executor", executor, "must be 'local' or 'dask'")
    executors.check_workers(workers)
    r0 = np.atleast_2d(np.asarray(r0, float))
    v0 = np.atleast_2d(np.asarray(v0, float))
    m0 = np.broadcast_to(np.asarray(m0, float), (r0.shape[0],)).copy()
    args = [(r0[sl], v0[sl], m0[sl], gains, sl.start, opts)
            for sl in chunk_slices(r0.shape[0], chunk)]
    parts = executors.map_dask(_run_chunk, args, workers=workers, scheduler=scheduler,
                               processes=processes, progress=progress)
    res = BatchResult.concat(parts)
    res.info["executor"] = executors.describe(scheduler, workers)
    return res


# --- summaries ------------------------------------------------------------------------------

def _stats(x: np.ndarray, include: np.ndarray | None = None) -> dict[str, float | int | None]:
    """min / mean / median / max over the finite values of the included cases, with how many
    were summarised (n) and how many left out (excluded: not included, or not finite), never
    an impossible aggregate (lgw.sim.stats.finite_stats)."""
    return finite_stats(x, include)


def summarize(res: BatchResult) -> dict[str, Any]:
    """Counts per outcome, and statistics over the cases of each quantity's outcome (landed
    cases for the landing numbers, crashed cases for the impact), with eps and dt.  Each
    statistic says how many cases it summarises and how many it leaves out."""
    code, _ = res.outcomes()
    landed = code == OUTCOMES.index("landed")
    crashed = code == OUTCOMES.index("crashed")
    ok = landed & ~res.nonfinite
    err = np.linalg.norm(res.r_land, axis=1)
    out: dict[str, Any] = {
        "cases": len(res), "landed": int(landed.sum()),
        "not_landed": int((~landed).sum()), "nonfinite": int(res.nonfinite.sum()),
        # the ground plane met before the outcome: "crashed", or a touchdown within the landing
        # tolerance (landed); below_surface: r_z(0) < 0, not flown
        "crashed": int(crashed.sum()), "below_surface": int(res.below_surface.sum()),
        "ground_contact": int(res.ground_contact.sum()),
        # the mass reached the dry mass before landing (lgw.sim.mars.batch: the case stops there)
        "fuel_exhausted": int(np.sum(res.fuel_exhausted & ~res.landed)),
        "m_dry": res.info.get("m_dry", M_DRY),
        # dopri5 only: the case needed more than max_steps attempts and stopped unfinished
        "step_limit": int(res.step_limit.sum()),
        # one outcome per case (lgw.sim.results: the first that happened), every outcome
        # listed; the flags above may overlap, these do not and sum to "cases"
        "outcomes": counts(code, OUTCOMES_USED),
        "landing_error_m": _stats(err, ok),
        "landing_speed_mps": _stats(np.linalg.norm(res.v_land, axis=1), ok),
        "landing_time_s": _stats(res.landing_time, ok),
        "fuel_kg": _stats(res.fuel, ok),
        # node peaks (the tuner's measure) and stage peaks (every rhs evaluation of the
        # accepted steps, >= the node peaks; lgw.sim.mars.batch), over landed cases
        "peak_thrust_N": {ax: _stats(res.peak_thrust[:, i], ok) for i, ax in enumerate("xyz")},
        "peak_thrust_stages_N": {ax: _stats(res.peak_thrust_stages[:, i], ok)
                                 for i, ax in enumerate("xyz")},
        "peak_thrust_unsat_stages_N": {ax: _stats(res.peak_thrust_unsat_stages[:, i], ok)
                                       for i, ax in enumerate("xyz")},
        # per axis, max |F_i| from its first node in the landing band on, over every case
        # whose axis got there ("arrived": how many did)
        "peak_thrust_after_arrival_N": {
            ax: {**_stats(res.peak_thrust_after_arrival[:, i]),
                 "arrived": int(np.sum(np.isfinite(res.peak_thrust_after_arrival[:, i])))}
            for i, ax in enumerate("xyz")},
        "time_saturated_s": _stats(res.time_saturated, ok),
        # over all cases, up to the outcome (negative: below ground, see ground_contact)
        "min_altitude_m": _stats(res.min_altitude),
        # the crashes: impact speed and time at the located contact
        "impact_speed_mps": _stats(res.impact_speed, crashed),
        "contact_time_s": _stats(res.contact_time, crashed),
        "eps": res.eps, "dt": res.dt,
    }
    out["settings"] = {k: v for k, v in res.info.items() if k != "refined_dt"}
    if res.nonfinite.any():
        idx = np.flatnonzero(res.nonfinite)
        out["nonfinite_cases"] = [{"case": int(i), "r0": res.r0[i].tolist(),
                                   "v0": res.v0[i].tolist(), "m0": float(res.m0[i]),
                                   "t_end": float(res.t_end[i])} for i in idx]
    return out


def _num(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def case_records(res: BatchResult, n: int | None = None) -> list[dict[str, Any]]:
    """One JSON-ready record per case (NaN -> null); the first ``n`` cases only if given."""
    return list(iter_case_records(res, n))


def iter_case_records(res: BatchResult, n: int | None = None) -> Iterator[dict[str, Any]]:
    """``case_records`` one at a time (a million cases in flat memory)."""
    code, t_out = res.outcomes()
    imp = res.impact_speed
    # the RK4 step of a case refined until its outcome settled (lgw.sim.mars.converged)
    refined = res.info.get("refined_dt", {})
    for i in range(len(res) if n is None else min(n, len(res))):
        yield {
            "case": i, "r0": res.r0[i].tolist(), "v0": res.v0[i].tolist(),
            "m0": float(res.m0[i]), "landed": bool(res.landed[i]),
            "landing_time": _num(res.landing_time[i]),
            "r_land": [_num(x) for x in res.r_land[i]], "v_land": [_num(x) for x in res.v_land[i]],
            "fuel": _num(res.fuel[i]), "peak_thrust": [_num(x) for x in res.peak_thrust[i]],
            "peak_thrust_unsat": [_num(x) for x in res.peak_thrust_unsat[i]],
            "peak_thrust_stages": [_num(x) for x in res.peak_thrust_stages[i]],
            "peak_thrust_unsat_stages": [_num(x) for x in res.peak_thrust_unsat_stages[i]],
            "peak_thrust_after_arrival": [_num(x) for x in res.peak_thrust_after_arrival[i]],
            "time_saturated": _num(res.time_saturated[i]),
            "min_altitude": _num(res.min_altitude[i]),
            "ground_contact": bool(res.ground_contact[i]),
            "t_s1": [_num(x) for x in res.t_s1[i]], "t_s2": [_num(x) for x in res.t_s2[i]],
            "t_s1_last_exit": [_num(x) for x in res.t_s1_last_exit[i]],
            "t_s2_last_exit": [_num(x) for x in res.t_s2_last_exit[i]],
            "nonfinite": bool(res.nonfinite[i]), "fuel_exhausted": bool(res.fuel_exhausted[i]),
            "step_limit": bool(res.step_limit[i]), "steps": int(res.steps[i]),
            "t_end": _num(res.t_end[i]),
            # the ground contact (lgw.sim.results): time, point and velocity at the crossing
            "contact_time": _num(res.contact_time[i]),
            "contact_point": [_num(x) for x in res.contact_point[i]],
            "impact_velocity": [_num(x) for x in res.impact_velocity[i]],
            "impact_speed": _num(imp[i]), "below_surface": bool(res.below_surface[i]),
            "refined_dt": refined.get(i),
            "eps": res.eps,
            # the case's one outcome (lgw.sim.results.OUTCOMES) and its time, s
            "outcome": OUTCOMES[code[i]], "outcome_time": _num(t_out[i]),
        }
