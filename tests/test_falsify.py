"""The falsification engine (lgw.theory.falsify): finds a planted violation, reports ``checked``
with its best margin on a true bound, reproduces from its seed, and shrinks witnesses without
losing the violation."""

from __future__ import annotations

import math

import pytest
from lgw.theory.evidence import Step
from lgw.theory.falsify import Budget, Dim, Problem, falsify, shrink

# A planted violation: a small diamond around (0.7317, -2.13) in a box where random sampling
# rarely lands (area 0.005 of 20).
CENTRE = (0.7317, -2.13)


def _planted(p):
    return abs(p["x"] - CENTRE[0]) + abs(p["y"] - CENTRE[1]) - 0.05


def _planted_recheck(p):  # the same margin by another route: the max of four half-planes
    dx, dy = p["x"] - CENTRE[0], p["y"] - CENTRE[1]
    return max(dx + dy, dx - dy, -dx + dy, -dx - dy) - 0.05


BOX = (Dim("x", -2.0, 3.0), Dim("y", -3.0, 1.0))
PLANTED = Problem("planted", BOX, _planted, _planted_recheck, route="abs",
                  recheck_method="max of half-planes", relative=False)
# A true bound: x^2 + y^2 + 0.5 >= 0 with least margin 0.5 at the origin.
TRUE = Problem("true", BOX, lambda p: p["x"] ** 2 + p["y"] ** 2 + 0.5,
               lambda p: math.hypot(p["x"], p["y"]) ** 2 + 0.5, route="polynomial",
               recheck_method="hypot", relative=False)
SMALL = Budget(popsize=8, maxiter=25, local_evals=80, seed=3)


def test_finds_planted_violation_and_confirms_it():
    s = falsify(PLANTED, SMALL)
    assert s.status == "refuted"
    w = s.witness
    assert w is not None and w.confirmed
    assert w.margin < 0 and w.rechecked_margin < 0
    assert abs(w.point["x"] - CENTRE[0]) + abs(w.point["y"] - CENTRE[1]) < 0.05
    assert s.evaluations >= 1 and s.best_margin < 0
    assert Step("planted", s).status == "refuted"


def test_true_bound_is_checked_with_best_margin():
    s = falsify(TRUE, SMALL)
    assert s.status == "checked" and s.witness is None
    assert 0.5 <= s.best_margin < 0.5 + 1e-4  # found the least margin, at the origin
    assert abs(s.best_point["x"]) < 1e-2 and abs(s.best_point["y"]) < 1e-2
    assert s.evaluations > SMALL.popsize * 2 * 10  # the whole budget was spent
    assert "best margin" in s.summary() and "'x': [-2.0, 3.0, 'linear']" in s.summary()


def test_witness_reproduces_from_seed():
    a = falsify(PLANTED, SMALL)
    b = falsify(PLANTED, SMALL)
    assert a.to_dict() == b.to_dict()
    c = falsify(PLANTED, Budget(popsize=8, maxiter=25, local_evals=80, seed=4))
    assert c.status == "refuted" and c.seed == 4 and c.witness.seed == 4


def test_shrinking_keeps_margin_negative_and_simplifies():
    p = {"x": 0.731234567, "y": -2.1298765}
    m0 = _planted(p)
    q, m = shrink(PLANTED, p, m0)
    assert m < 0 and _planted(q) == m
    digits = [len(f"{abs(v):.12g}".replace(".", "").strip("0")) for v in q.values()]
    assert max(digits) <= 3, q  # e.g. (0.73, -2.1): two or three significant digits
    s = falsify(PLANTED, SMALL)
    assert s.witness.margin < 0  # the reported (shrunk) witness is still a violation


def test_unconfirmed_witness_does_not_refute():
    """A violation the independent route does not reproduce does not refute; and a best
    margin below the stated tolerance (0 here) is not "checked" either: it is ``unproven``
    ("checked" needs the best margin to clear the tolerance)."""
    p = Problem("route-disagrees", BOX, _planted, lambda q: 1.0, route="abs",
                recheck_method="always positive", relative=False)
    s = falsify(p, SMALL)
    assert s.best_margin < 0 and s.counter is not None and not s.counter.confirmed
    assert s.tolerance == 0.0 and s.status == "unproven"
    # the same evidence with a tolerance the margin clears is checked; one it does not, not
    import dataclasses
    assert dataclasses.replace(s, tolerance=-2 * s.best_margin).status == "checked"
    assert dataclasses.replace(s, tolerance=-0.5 * s.best_margin).status == "unproven"


def test_failures_are_counted_not_hidden():
    def flaky(q):
        if q["x"] > 2.0:
            raise ValueError("cannot evaluate")
        return q["x"] ** 2 + 1.0
    s = falsify(Problem("flaky", BOX, flaky, flaky, route="r", recheck_method="r",
                        relative=False), Budget(popsize=5, maxiter=5, local_evals=10))
    assert s.domain["failed_evaluations"] > 0 and "failed" in s.method


def test_bad_box_is_rejected():
    with pytest.raises(ValueError):
        Dim("x", 1.0, 0.0)
    with pytest.raises(ValueError):
        Dim("x", 0.0, 1.0, "log")


def test_confirm_negatives_keeps_false_alarms_from_stopping_the_search():
    """A fast route with false alarms (here: everywhere inside the diamond): with
    confirm_negatives the independent route's margin replaces them, and it is said so."""
    p = Problem("false-alarm", BOX, _planted, lambda q: 1.0 + q["x"] ** 2, route="abs",
                recheck_method="positive", relative=False, confirm_negatives=True)
    s = falsify(p, SMALL)
    assert s.status == "checked" and s.best_margin > 0 and s.counter is None
    assert "not reproduced by the independent route" in s.method
