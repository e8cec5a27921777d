"""The adversarial agreement figure (benchmarks/adversarial_agreement.py): written, and the counts
drawn on it are the table's (RK4 rows against dopri5 columns, before and after refinement)."""

from __future__ import annotations

import importlib.util
from collections import Counter
from pathlib import Path

import numpy as np

BENCH = Path(__file__).resolve().parents[1] / "benchmarks" / "adversarial_agreement.py"


def _bench():
    spec = importlib.util.spec_from_file_location("adversarial_agreement", BENCH)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _tiny() -> dict:
    """Seven cases: two disagree at the default step, one of them settles by refinement."""
    rk = np.array(["landed", "landed", "crashed", "numerical", "landed", "crashed", "horizon"],
                  dtype=object)
    dp = np.array(["landed", "crashed", "crashed", "landed", "landed", "crashed", "horizon"],
                  dtype=object)
    fin = rk.copy()
    fin[1] = "crashed"  # case 1 refined to dopri5's class; case 3 stays different
    t_rk = np.array([10.0, 20.0, 2.0, 0.01, 11.0, 3.0, 50.0])
    t_dp = np.array([10.1, 2.5, 2.0, 12.0, 11.0, 3.1, 50.0])
    t_fin = t_rk.copy()
    t_fin[1] = 2.45
    return {"system": "tiny", "n": 7, "dt": 0.01,
            "before": int(np.sum(rk == dp)), "after": int(np.sum(fin == dp)),
            "per_case": {"rk4": rk, "dopri5": dp, "refined": fin, "t_rk4": t_rk,
                         "t_dopri5": t_dp, "t_refined": t_fin,
                         "refined_cases": np.array([1, 3])}}


def test_figure_written_with_the_tables_counts(tmp_path):
    mod = _bench()
    r = _tiny()
    path = tmp_path / "sub" / "agreement_tiny.png"
    drawn = mod.agreement_figure(r, 7, path)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 10_000
    lab = drawn["labels"]
    pc = r["per_case"]
    for key, rows in (("before", pc["rk4"]), ("after", pc["refined"])):
        M = drawn[key]
        pairs = Counter(zip(rows, pc["dopri5"], strict=True))
        got = {(lab[i], lab[j]): int(M[i, j]) for i, j in zip(*np.nonzero(M), strict=True)}
        assert got == dict(pairs), key  # every drawn count is the table's pair count
        assert int(np.trace(M)) == r[key]  # the diagonal is the printed agreement
    assert (r["before"], r["after"]) == (5, 6)
