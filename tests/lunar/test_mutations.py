"""Seed 001's verdicts follow the mathematics: each mutation of a law, a bound or a model
constant flips exactly the verdicts whose derivation uses it (``tests/mutation.py``).

Every claim is re-derived under the mutation (the caches cleared), and compared with the
unmutated verdicts: an expected flip that does not happen, a flip to another verdict, or any
other verdict that changes fails the test.
"""

from __future__ import annotations

from unittest import mock

import sympy as sp
from lgw.theory.lunar import bounds as B
from lgw.theory.lunar import gains as G
from lgw.theory.lunar import law as L
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.claims import clear_caches, theory_claims

from tests.mutation import MutationSuite, maker


def _orbit_f1_up(full: bool = False) -> L.GeneralSystem:
    S = _ORBIT(full)
    return L.GeneralSystem(S.x1, S.x2, -S.f1, S.f2, S.B0, S.K1, S.F2, name="orbit")


def _attitude_f1_nonsingular(f2=None) -> L.GeneralSystem:
    S = _ATTITUDE(f2)
    eq0, eq, _ = L.attitude_symbols()
    return L.GeneralSystem(S.x1, S.x2, S.f1.subs(eq0, 1), S.f2, S.B0, S.K1, S.F2, aux=S.aux,
                           name="attitude")


_ORBIT, _ATTITUDE = L.orbit_system, L.attitude_system
_Z_L2, _V2_0 = B.z_l2_bounds, B.v2_initial
_LAMBDA = B.lambda_gain_bounds


def _z_l2_printed_is_derived(v20, f1bar, f2bar, f3, printed=False):
    return _Z_L2(v20, f1bar, f2bar, f3, printed=False)


def _v2_printed_is_derived(z1_0, z2_0, d0e0=0.0, D=0.0, q=1.0, printed=False):
    return _V2_0(z1_0, z2_0, d0e0, D, q, printed=False)


def _lambda_18b_without_the_half(f1bar, f2bar):
    c1, _ = _LAMBDA(f1bar, f2bar)
    return c1, 1 / B._sqrt(2 * f2bar)


def _make_loop_unchecked(loop: str, d: dict) -> G.LoopGains:
    """The gains loader without its range checks (so a gain set can break a hypothesis)."""
    return G.LoopGains(G._matrix(f"{loop}.K1", d["K1"]), G._matrix(f"{loop}.F2", d["F2"]),
                       float(d["f3"]), float(d["d0e0"]), float(d["q"]))


_m = maker(clear_caches)
MUTATIONS = (
    _m("law: the command (7) without its adaptive term Phi",
       {"V2dot-bound": "refuted", "smooth-7": "proved", "B0-rank": "refuted",
        "L2-19-20-derived": "unproven", "transient-21-derived": "unproven"},
       "V2' no longer has (13)'s form (the residual identities fail at exact points), so the "
       "corrected (13) and what rests on it fall; without the sign-like term the command is "
       "continuous at z2 = 0; the projection identity of B0-rank contains Phi",
       mock.patch.object(L.GeneralSystem, "Phi", property(lambda S: sp.zeros(S.n2, 1)))),
    _m("bound: (19)-(20) as printed made the derived ones",
       {"L2-19-20": "checked", "transient-21": "checked"},
       "the printed (19b) constant and (20)'s V2(0) equal the integrated (13): the scalar "
       "instance no longer exceeds them, and (21a) as printed inherits them",
       mock.patch.object(B, "z_l2_bounds", _z_l2_printed_is_derived),
       mock.patch.object(B, "v2_initial", _v2_printed_is_derived)),
    _m("law: the orbit loop's f1 = a_h with the wrong sign",
       {"orbit-22-23": "refuted"},
       "(22a) e_h' = a_h e_v fails; the general derivations hold for any f1 and the filter's "
       "gains are invariant under the sign",
       mock.patch.object(L, "orbit_system", _orbit_f1_up)),
    _m("law: the attitude f1 with eq0 replaced by 1 (never singular)",
       {"attitude-27a": "refuted", "attitude-F1": "unproven", "attitude-F1-bound": "refuted"},
       "(27a) is no longer the error kinematics; F1 is no longer singular at eq0 = 0 (no "
       "witness), and det(2 f1) = eq0 (...) fails",
       mock.patch.object(L, "attitude_system", _attitude_f1_nonsingular)),
    _m("model constant: T_a = 1 (no thrust failure)",
       {"failure-26": "proved", "failure-26-model": "unproven"},
       "the characteristic is then constant and (26) equals it; the failure no longer persists",
       mock.patch.object(P, "T_A", 1.0)),
    _m("bound: (18b) printed as 1/sqrt(2 f2bar)",
       {"L2-18": "refuted", "L2-18-hinf": "unproven", "transient-21-derived": "refuted"},
       "the (18b) constant is no longer the integrated (17b) (nor (21b)'s term), and the "
       "orbit filter's true L2 gain 1 exceeds 1/sqrt(2)",
       mock.patch.object(B, "lambda_gain_bounds", _lambda_18b_without_the_half)),
    _m("gains: orbit f3 = 1.2 > f2bar = 1 (the loader's check bypassed)",
       {"L2-19-20-derived": "unproven", "transient-21-derived": "unproven"},
       "the hypothesis f2bar > f3bar of the integrated (13) fails for the gains in use: the "
       "derived (19b) does not apply (unproven, not refuted); LaSalle-14 was unproven already",
       mock.patch.object(G, "make_loop", _make_loop_unchecked),
       mock.patch.dict(G.ORBIT_GAINS, {"f3": 1.2})),
)


class TestMutations(MutationSuite):
    compute = staticmethod(theory_claims)
    clear = staticmethod(clear_caches)
    mutations = MUTATIONS
    default = 1  # the printed (19)-(20): cheap, no new SymPy derivation
