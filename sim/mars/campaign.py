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

import math
import mmap
import shutil
import tempfile
import weakref
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import orjson
from lgw.sim import executors, integrate
from lgw.sim.mars.batch import ARRAY_FIELDS, OUTCOMES_USED, BatchResult, simulate_batch
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
                 chunk: int = DEFAULT_CHUNK, progress: bool = False, spill: bool = False,
                 **opts: Any) -> BatchResult | SpilledResult:
    """Run a campaign with ``lgw.sim.mars.batch.simulate_batch`` options ``opts``.

    executor="local": in-process, numba threads over cases.
    executor="dask": ``scheduler`` (address of a running dask scheduler) or a LocalCluster
      with ``workers`` single-threaded workers (``processes=False`` keeps them in-process).
    Both go through ``lgw.sim.executors`` (the same chunks, so the same results).
    spill=True (local executor): the per-case results go to disk SPILL_CHUNK cases at a time,
      a ``SpilledResult`` (flat memory in the number of cases; the same results).
    """
    if executor == "local":
        if spill:
            return _run_spilled(r0, v0, m0, gains, chunk=chunk, progress=progress, **opts)
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


def summarize(res: BatchResult | SpilledResult) -> dict[str, Any]:
    """Counts per outcome, and statistics over the cases of each quantity's outcome (landed
    cases for the landing numbers, crashed cases for the impact), with eps and dt.  Each
    statistic says how many cases it summarises and how many it leaves out.  From a
    ``SpilledResult`` each per-case array is read when it is used and dropped after: a million
    cases hold a few columns at a time (8-24 bytes per case each)."""
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
        r0, v0, m0, t_end = (take(res, k, idx) for k in ("r0", "v0", "m0", "t_end"))
        out["nonfinite_cases"] = [{"case": int(i), "r0": r0[j].tolist(), "v0": v0[j].tolist(),
                                   "m0": float(m0[j]), "t_end": float(t_end[j])}
                                  for j, i in enumerate(idx)]
    return out


# the case record's keys, in order: "case", the per-case arrays (RECORD_ARRAYS, "impact_speed"
# and "below_surface" among them), then the run's and the outcome's
RECORD_ARRAYS = ("r0", "v0", "m0", "landed", "landing_time", "r_land", "v_land", "fuel",
                 "peak_thrust", "peak_thrust_unsat", "peak_thrust_stages",
                 "peak_thrust_unsat_stages", "peak_thrust_after_arrival", "time_saturated",
                 "min_altitude", "ground_contact", "t_s1", "t_s2", "t_s1_last_exit",
                 "t_s2_last_exit", "nonfinite", "fuel_exhausted", "step_limit", "steps",
                 "t_end",
                 # the ground contact (lgw.sim.results): time, point and velocity at the
                 # crossing, |velocity| there
                 "contact_time", "contact_point", "impact_velocity", "impact_speed",
                 "below_surface")
RECORD_CHUNK = 4096  # cases turned into records at a time


def _listed(a: np.ndarray) -> list:
    """``a.tolist()`` (nested for (n, 3)) with every non-finite value None (JSON null)."""
    if a.dtype.kind == "f":
        bad = ~np.isfinite(a)
        if bad.any():
            o = a.astype(object)
            o[bad] = None
            return o.tolist()
    return a.tolist()


def case_records(res: BatchResult | SpilledResult, n: int | None = None
                 ) -> list[dict[str, Any]]:
    """One JSON-ready record per case (NaN -> null); the first ``n`` cases only if given."""
    return list(iter_case_records(res, n))


def iter_case_records(res: BatchResult | SpilledResult, n: int | None = None
                      ) -> Iterator[dict[str, Any]]:
    """``case_records`` one at a time, made RECORD_CHUNK cases at a time from whole columns
    (``tolist``, not one numpy scalar per value); from a ``SpilledResult`` in flat memory."""
    total = len(res) if n is None else min(n, len(res))
    # the RK4 step of a case refined until its outcome settled (lgw.sim.mars.converged)
    refined = res.info.get("refined_dt", {})
    for a in range(0, total, RECORD_CHUNK):
        part = result_rows(res, slice(a, min(a + RECORD_CHUNK, total)))
        code, t_out = part.outcomes()
        cols = [_listed(np.asarray(getattr(part, k))) for k in RECORD_ARRAYS]
        outcome = [OUTCOMES[k] for k in code.tolist()]
        t_out = _listed(t_out)
        eps = part.eps
        for j, vals in enumerate(zip(*cols, strict=True)):
            rec = {"case": a + j}
            rec.update(zip(RECORD_ARRAYS, vals, strict=True))
            rec["refined_dt"] = refined.get(a + j)
            rec["eps"] = eps
            # the case's one outcome (lgw.sim.results.OUTCOMES) and its time, s
            rec["outcome"] = outcome[j]
            rec["outcome_time"] = t_out[j]
            yield rec


Extra = Callable[[int, int], dict[str, list[Any]]]


def _items(text: bytes, vector: bool) -> list[bytes]:
    """The items of a JSON array ``text`` of n values (or, ``vector``, of n 3-lists: each
    item is then the list's inside, "a,b,c") as encoded text."""
    if text in (b"[]", b"[[]]"):
        return []
    return text[2:-2].split(b"],[") if vector else text[1:-1].split(b",")


def _encode_column(a: Any) -> list[bytes] | bytes:
    """Each case's value of the per-case column ``a`` (n,) or (n, 3) as strict JSON text,
    non-finite floats as null: orjson encodes the whole column in C (shortest round-trip
    floats, ~30 ns each against ~1 us for ``json.dumps``' ``float.__repr__``).  A column whose
    values are all the same bits (e.g. every case landed, no contact: false, null) is the one
    text of its first value (bytes, not a list): the same text for every case, made once."""
    vector = False
    if isinstance(a, np.ndarray):  # else a list of JSON-ready values
        a = np.ascontiguousarray(a)
        vector = a.ndim == 2
        if len(a) > 1 and _constant(a):
            return _items(orjson.dumps(a[:1], option=orjson.OPT_SERIALIZE_NUMPY), vector)[0]
    return _items(orjson.dumps(a, option=orjson.OPT_SERIALIZE_NUMPY), vector)


def _constant(a: np.ndarray) -> bool:
    """Every row of ``a`` has the bits of the first (so the same text: -0.0 and 0.0, or two
    NaN payloads, count as different, which only costs the shortcut)."""
    bits = a.view(np.uint8).reshape(len(a), -1)
    return bool((bits == bits[0]).all())


class CaseJson:
    """The case records of ``res`` (the first ``n``) as JSON text (ASCII bytes), RECORD_CHUNK
    records at a time joined by "," (items of a JSON array, strict JSON: non-finite values are
    null), for
    ``lgw.tuning.io.Stream(encoded=...)``: the same keys, order and values as
    ``iter_case_records``, encoded column by column (each column of a chunk in one orjson
    call, the records assembled by one join), never one Python object per value: a million
    cases in seconds, in flat memory.  ``extra(a, b)`` returns further keys for cases a..b-1
    (name -> one JSON-ready value per case), added after the record's own.  Each iteration
    starts afresh (a document may be written twice: --out and stdout)."""

    def __init__(self, res: BatchResult | SpilledResult, n: int | None = None,
                 extra: Extra | None = None) -> None:
        self.res, self.n, self.extra = res, n, extra

    def __iter__(self) -> Iterator[bytes]:
        res = self.res
        total = len(res) if self.n is None else min(self.n, len(res))
        refined = res.info.get("refined_dt", {})
        for a in range(0, total, RECORD_CHUNK):
            b = min(a + RECORD_CHUNK, total)
            part = result_rows(res, slice(a, b))
            code, t_out = part.outcomes()
            cols: list[tuple[str, list[bytes] | bytes, bool]] = [
                ("case", _encode_column(np.arange(a, b, dtype=np.int64)), False)]
            for k in RECORD_ARRAYS:
                col = np.asarray(getattr(part, k))
                cols.append((k, _encode_column(col), col.ndim == 2))
            cols.append(("refined_dt", _encode_column([refined.get(i) for i in range(a, b)])
                         if refined else [b"null"] * (b - a), False))
            cols.append(("eps", [orjson.dumps(part.eps)] * (b - a), False))
            names = [orjson.dumps(o) for o in OUTCOMES]
            cols.append(("outcome", [names[k] for k in code.tolist()], False))
            cols.append(("outcome_time", _encode_column(t_out), False))
            if self.extra is not None:
                cols += [(k, _encode_column(v), False) for k, v in self.extra(a, b).items()]
            yield _assemble(cols, b - a)


def _assemble(cols: list[tuple[str, list[bytes] | bytes, bool]], n: int) -> bytes:
    """n JSON objects joined by ",", the key of each column before its values.  The record is
    a template of constant texts (the keys, and the columns whose value is the same in every
    case of the chunk, e.g. null or false) between the varying columns; the varying values
    are interleaved with the constants by extended-slice assignment into one list, joined
    once."""
    if n < 1:
        return b""
    consts: list[bytes] = [b""]  # consts[k] comes before varying column k (and after the last)
    varying: list[list[bytes]] = []
    close = b""  # what ends the previous value: "]" after a 3-list
    for j, (key, vals, vector) in enumerate(cols):
        consts[-1] += (b"{" if j == 0 else close + b",") + orjson.dumps(key) + b":" + (
            b"[" if vector else b"")
        if isinstance(vals, bytes):  # the same text in every case (_encode_column)
            consts[-1] += vals
        elif n > 1 and vals.count(vals[0]) == n:
            consts[-1] += vals[0]
        else:
            varying.append(vals)
            consts.append(b"")
        close = b"]" if vector else b""
    consts[-1] += close + b"},"
    stride = 2 * len(varying) + 1
    pieces: list[bytes] = [b""] * (n * stride)
    for k, vals in enumerate(varying):
        pieces[2 * k::stride] = [consts[k]] * n
        pieces[2 * k + 1::stride] = vals
    pieces[stride - 1::stride] = [consts[-1]] * n
    pieces[-1] = consts[-1][:-1]  # the last record ends without ","
    return b"".join(pieces)


# --- campaigns kept on disk -----------------------------------------------------------------

SPILL_CHUNK = 4096  # cases flown on one thread, then written to disk, at a time (~2.5 MB)
_SPILLED = tuple(dict.fromkeys((*ARRAY_FIELDS, "r0", "v0", "m0")))


class SpilledResult:
    """A campaign's per-case results on disk, one raw file per array (``SPILL_CHUNK`` cases
    are in memory at a time while it is flown), in a temporary folder removed with the object.

    It reads as a ``BatchResult``: every per-case array is an attribute (the file mapped at
    each access, copy on write: a summary reads one or a few whole columns at a time, never all
    of them; code that takes case i of an array reads its page, not the column), ``len``,
    ``outcomes()``, ``crashed``, ``impact_speed``, ``eps``, ``dt``, ``info``, ``with_rows``
    (in place: a copy would double the campaign on disk); ``rows(sl)`` and ``take(idx)`` are
    the ``BatchResult`` of some cases.  So a million cases take a few columns of memory (8-24
    bytes per case each) instead of every array of every case (~600 bytes per case)."""

    trajectory = None

    def __init__(self, folder: str | Path | None = None) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="lgw-campaign-", dir=folder))
        self._finalizer = weakref.finalize(self, shutil.rmtree, str(self.folder), True)
        self._n = 0
        self._layout: dict[str, tuple[np.dtype, tuple[int, ...]]] = {}
        self.eps = math.nan
        self.dt = math.nan
        self.info: dict[str, Any] = {}

    def append(self, part: BatchResult) -> None:
        """Write the cases of ``part`` after those already held."""
        if not self._layout:
            self.eps, self.dt, self.info = part.eps, part.dt, dict(part.info)
            self._layout = {k: (getattr(part, k).dtype, getattr(part, k).shape[1:])
                            for k in _SPILLED}
        for k in _SPILLED:
            a = np.ascontiguousarray(getattr(part, k), dtype=self._layout[k][0])
            with open(self.folder / k, "ab") as f:
                a.tofile(f)
        self._n += len(part)

    def __len__(self) -> int:
        return self._n

    def _map(self, name: str, mode: str = "r") -> np.memmap:
        dtype, tail = self._layout[name]
        return np.memmap(self.folder / name, dtype=dtype, mode=mode, shape=(self._n, *tail))

    def _view(self, name: str) -> np.ndarray:
        """The array ``name`` mapped copy on write (as ``_map(name, "c")``, without
        ``np.memmap``'s ~0.1 ms of path handling per access: a check that reads one number of
        each of a thousand cases maps the file thousands of times); unmapped when the array
        and its views are dropped."""
        dtype, tail = self._layout[name]
        with open(self.folder / name, "rb") as f:
            m = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_COPY)
        return np.frombuffer(m, dtype=dtype).reshape((self._n, *tail))

    def column(self, name: str, sl: slice = slice(None)) -> np.ndarray:
        """Cases ``sl`` (step 1) of the array ``name``, read from disk."""
        dtype, tail = self._layout[name]
        a, b, _ = sl.indices(self._n)
        b = max(a, b)
        per = int(np.prod(tail, dtype=np.int64)) if tail else 1
        out = np.fromfile(self.folder / name, dtype=dtype, count=(b - a) * per,
                          offset=a * per * dtype.itemsize)
        return out.reshape((b - a, *tail))

    def __getattr__(self, name: str) -> np.ndarray:
        if name.startswith("_") or name not in self.__dict__.get("_layout", {}):
            raise AttributeError(name)
        if not self._n:
            return self.column(name)
        # mapped, copy on write: a whole-column operation reads the column, an element or a
        # row (res.t_s2[i]: a view) reads its page only and does not hold the column in memory
        return self._view(name)

    def rows(self, sl: slice) -> BatchResult:
        """The cases ``sl`` as a ``BatchResult`` (in memory)."""
        kw = {k: self.column(k, sl) for k in _SPILLED}
        return BatchResult(eps=self.eps, dt=self.dt, info=self.info, **kw)

    def take(self, name: str, idx: np.ndarray) -> np.ndarray:
        """The cases ``idx`` of the array ``name`` (only their rows are read)."""
        if not self._n:
            return self.column(name)[np.asarray(idx, np.int64)]
        return np.array(self._map(name)[np.asarray(idx, np.int64)])

    def with_rows(self, idx: np.ndarray, other: BatchResult) -> SpilledResult:
        """``BatchResult.with_rows`` on disk: cases ``idx`` replaced by the cases of ``other``
        (in order), ``info["replaced"]`` lists them; in place, and returns self."""
        idx = np.asarray(idx, dtype=np.int64)
        if len(idx) != len(other):
            raise ValueError(f"with_rows: {len(idx)} indices for {len(other)} cases")
        if len(idx):
            for k in ARRAY_FIELDS:
                m = self._map(k, "r+")
                m[idx] = getattr(other, k)
                m.flush()
                del m
        self.info = dict(self.info)
        self.info["replaced"] = sorted({*self.info.get("replaced", []), *idx.tolist()})
        return self

    outcomes = BatchResult.outcomes  # classify on the columns, as BatchResult does
    crashed = BatchResult.crashed
    impact_speed = BatchResult.impact_speed

    def close(self) -> None:
        """Remove the folder now (it is removed anyway when the object is collected)."""
        self._finalizer()


def result_rows(res: BatchResult | SpilledResult, sl: slice) -> BatchResult:
    """The cases ``sl`` of a campaign result, as a ``BatchResult``."""
    if isinstance(res, SpilledResult):
        return res.rows(sl)
    kw = {k: getattr(res, k)[sl] for k in _SPILLED}
    return BatchResult(eps=res.eps, dt=res.dt, info=res.info, **kw)


def take(res: BatchResult | SpilledResult, name: str, idx: np.ndarray) -> np.ndarray:
    """The cases ``idx`` of the per-case array ``name`` of a campaign result."""
    if isinstance(res, SpilledResult):
        return res.take(name, idx)
    return getattr(res, name)[np.asarray(idx, np.int64)]


def _run_spilled(r0, v0, m0, gains: Gains, *, chunk: int, progress: bool,
                 **opts: Any) -> SpilledResult:
    """``run_campaign`` (local) flown SPILL_CHUNK cases at a time into a ``SpilledResult``;
    each case is the same as in one call over all cases (its disturbance is drawn from its own
    case index: ``case_offset``)."""
    for k in ("record", "dist_spec", "case_offset"):
        if opts.get(k):
            raise ParameterError(k, opts[k], "cannot be given to a campaign kept on disk "
                                 "(spill=True)")
    r0 = np.atleast_2d(np.asarray(r0, float))
    v0 = np.atleast_2d(np.asarray(v0, float))
    m0 = np.broadcast_to(np.asarray(m0, float), (r0.shape[0],))
    out = SpilledResult()
    # one spill chunk per thread, each flown on that one thread (the kernel is nogil): no
    # thread waits for the other between the kernel's pieces, and the writing of a flown
    # chunk to disk overlaps the flight of the next
    threads = integrate.threads() if opts.get("parallel", True) else 1
    one = {**opts, "parallel": False}

    def fly(sl: slice) -> BatchResult:
        return simulate_batch(r0[sl], v0[sl], m0[sl], gains, case_offset=sl.start,
                              chunk=chunk, **one)
    executors.map_threads(fly, r0.shape[0], SPILL_CHUNK, out.append, threads=threads,
                          progress=progress)
    return out
