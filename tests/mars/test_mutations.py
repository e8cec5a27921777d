"""Seed 000's mutation harness (``tests/mutation.py``): change one object the verdicts are
computed from (a law, a bound, a model constant, a gain) and require exactly the listed
verdict flips, and no other verdict change, over every claim of ``all_claims(gains)``.

Each mutation says why each flip follows from the mathematics.  Every claim is rebuilt under
the mutation (the memoised claims, laws and searches are cleared before and after), so a claim
whose verdict was typed in, or that reads a copy of the law instead of the law, fails here.

The full harness recomputes every claim (about 45 s of CPU each) and is marked slow; the
fast test below rebuilds only the claims the first mutation touches.
"""

from __future__ import annotations

import contextlib
import dataclasses
from collections.abc import Iterator

import pytest
from lgw.theory.mars.gains import default_gains

from tests.mutation import Mutation, check_mutation, verdicts

GAINS = [default_gains()]  # the gain set the claims are judged for (a mutation may swap it)


MODULES = ("lgw.theory.mars.claims", "lgw.theory.mars.bounded_claims", "lgw.theory.mars.mss",
           "lgw.theory.mars.searches", "lgw.theory.settling_proofs")


def clear_caches() -> None:
    """Forget every memoised claim, law, closed loop and search of seed 000."""
    from lgw.theory.symbolic import clear_module_caches

    clear_module_caches(MODULES)


@pytest.fixture(autouse=True)
def _unmutated_derivation_kept():
    """Each mutation derives afresh; afterwards the unmutated derivation that was memoised
    before it is back (a worker's other claim tests do not pay seed 000's derivation again)."""
    from lgw.theory.symbolic import kept_module_caches

    with kept_module_caches(MODULES):
        yield


def compute():
    from lgw.theory.mars.claims import all_claims

    clear_caches()
    return all_claims(GAINS[0])


@contextlib.contextmanager
def patched(*changes: tuple[object, str, object]) -> Iterator[None]:
    """Set ``obj.name = value`` for each change (caches cleared on entry and exit)."""
    old = [(obj, name, getattr(obj, name)) for obj, name, _ in changes]
    try:
        for obj, name, value in changes:
            setattr(obj, name, value)
        clear_caches()
        yield
    finally:
        for obj, name, value in old:
            setattr(obj, name, value)
        clear_caches()


def _printed_is_corrected():
    import lgw.theory.mars.mss as MM
    return patched((MM, "law_printed", MM.law_corrected))


def _corrected_is_printed():
    import lgw.theory.mars.mss as MM
    return patched((MM, "law_corrected", MM.law_printed))


def _t1_halved():
    import lgw.theory.mars.bounds as BD
    orig = BD.t1_polyakov
    return patched((BD, "t1_polyakov", lambda g: 0.5 * orig(g)))


def _thrust_limit(value: float):
    import lgw.theory.mars.claims as MC
    import lgw.theory.mars.parameters as PM
    return patched((PM, "THRUST_MAX_AXIS", value), (MC, "THRUST_MAX_AXIS", value))


def _q1(value: float):
    return _gains(dataclasses.replace(GAINS[0], q1=value))


@contextlib.contextmanager
def _gains(g) -> Iterator[None]:
    old = GAINS[0]
    GAINS[0] = g
    try:
        clear_caches()
        yield
    finally:
        GAINS[0] = old
        clear_caches()


def _sat_u_b_halved():
    import lgw.theory.mars.bounded_sat as BS
    orig = BS.axis_box_bounds_sat

    def half(*a, **k):
        d = dict(orig(*a, **k))
        d["u_b"] *= 0.5
        return d
    return patched((BS, "axis_box_bounds_sat", half))


def _slide_time_halved():
    import lgw.theory.mars.bounded as BB
    orig = BB.slide_time
    return patched((BB, "slide_time", lambda *a, **k: 0.5 * orig(*a, **k)))


MUTATIONS = [
    Mutation("printed law (25) := corrected law", _printed_is_corrected, {
        # (29) and (36) are computed from the law: with exact cancellation they hold
        "V2dot-printed": "proved", "V2dot-disturbed-printed": "proved",
        # Theorem 3 then rests on a proved (29) and Lemma 2; the Fig. 6 flight lands
        "T2-printed": "proved-given",
        # the two laws no longer differ by the bracket times s2
        "laws-agree": "refuted",
        # the command now holds |s1|^(q1-1) v: a negative exponent for every admissible q1
        "bounded-command-printed": "refuted", "bounded-command-printed@gains": "refuted",
        # Theorem 4 for (25): its proof rested on (36) for (25), now proved
        "s2-neighborhood": "proved-given", "T2-practical": "proved-given",
        "s1-neighborhood": "proved-given", "T1-practical": "proved-given"},
        "the example of the issue"),
    Mutation("corrected law := printed law (25)", _corrected_is_printed, {
        "V2dot-corrected": "refuted", "V2dot-disturbed-corrected": "refuted",
        "laws-agree": "refuted",
        # their proofs rest on (29) / (36) for the corrected law: unproven
        "T2-corrected": "unproven", "landing-time-corrected": "unproven",
        "s2-neighborhood-corrected": "unproven", "T2-practical-corrected": "unproven",
        "s1-neighborhood-corrected": "unproven", "T1-practical-corrected": "unproven",
        "T3-corrected": "unproven",
        # the searches' reduced loops take exact cancellation, which this law lacks: not run
        "landing-time": "unproven", "T3": "unproven",
        # the printed command is bounded near s1 = 0 for q1 = 7/10: the witness is gone
        "bounded-command-corrected": "checked"}),
    Mutation("(18) computed at half its value", _t1_halved, {
        # the full-domain search flies (16) against lgw.theory.mars.bounds, which now
        # promises half the time: a re-checked violation
        "T1": "refuted",
        # the sound landing bound T2 + T1 uses T1 as a lemma: refuted lemma, unproven step
        "landing-time-corrected": "unproven"}),
    Mutation("per-axis thrust limit 50 kN -> 15 kN", lambda: _thrust_limit(15e3), {
        # Table I's first command with the default gains: 1905 kg x 13.06 m/s^2 = 24.9 kN
        # (printed), 1905 kg x 17.02 m/s^2 = 32.4 kN (corrected), both above 15 kN at t = 0
        "thrust-table1-printed@gains": "refuted", "thrust-table1-corrected@gains": "refuted"}),
    Mutation("gain set with q1 = 0.4 < 1/2", lambda: _q1(0.4), {
        # the printed command's |s1|^(2 q1 - 1) has a negative exponent at this gain set
        "bounded-command-printed@gains": "refuted"}),
    Mutation("bounded-sat command bound u_b halved", _sat_u_b_halved, {
        # the flights of the saturated law exceed the halved bound (re-checked by Radau)
        "bounded-sat-bounds": "refuted"}),
    Mutation("bounded sliding-time closed form halved", _slide_time_halved, {
        # the quadrature of int dx/psi exceeds it (re-checked by mpmath), and the flights of
        # both bounded laws land later than the halved T_land
        "bounded-invariants": "refuted", "bounded-sat-bounds": "refuted"}),
]


@pytest.fixture(scope="module")
def base() -> dict[str, str]:
    return verdicts(compute())


@pytest.mark.slow
@pytest.mark.parametrize("mutation", MUTATIONS, ids=[m.name for m in MUTATIONS])
def test_mutation_flips_exactly(mutation: Mutation, base: dict[str, str]) -> None:
    check_mutation(compute, mutation, base)


def test_printed_law_fixed_flips_its_claims_fast() -> None:
    """The first mutation on the claims it touches only (the default suite's guard): each is
    rebuilt from the law in force, so fixing the printed law fixes exactly these."""
    import lgw.theory.mars.claims as C

    fns = {"V2dot-printed": lambda: C.v2dot_claim("printed"),
           "V2dot-disturbed-printed": lambda: C.v2dot_disturbed_claim("printed"),
           "T2-printed": lambda: C.t2_claim("printed"), "laws-agree": C.laws_agree_claim,
           "bounded-command-printed": lambda: C.bounded_command_claim("printed"),
           "s2-neighborhood": lambda: C.s2_neighborhood_claim("printed"),
           "T1-practical": lambda: C.t1_practical_claim("printed"),
           "s2dot-24": C.s2dot24_claim, "V2dot-corrected": lambda: C.v2dot_claim("corrected")}
    clear_caches()
    before = {k: f().verdict for k, f in fns.items()}
    with _printed_is_corrected():
        after = {k: f().verdict for k, f in fns.items()}
        witnesses = [f().counterexample for f in fns.values()]
    want = {k: v for k, v in MUTATIONS[0].flips.items() if k in fns}
    assert {k: after[k] for k in want} == want, after
    assert all(before[k] != want[k] for k in want), before
    unrelated = set(fns) - set(want)
    assert {k: after[k] for k in unrelated} == {k: before[k] for k in unrelated}
    # the refutation of laws-agree is drawn inside the hypotheses (0 < q1 < 1 < q2, ...)
    for w in filter(None, witnesses):
        for name, (lo, hi) in {"q1": (0, 1), "g1": (0, 1), "q2": (1, 1e9),
                               "g2": (1, 1e9)}.items():
            if name in w.point:
                from fractions import Fraction
                assert lo < Fraction(str(w.point[name])) < hi, (name, w.point)
