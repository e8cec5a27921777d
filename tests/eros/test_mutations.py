"""Seed 002's verdicts follow the mathematics: each mutation of a law, a bound or a model
constant flips exactly the verdicts whose derivation uses it (``tests/mutation.py``).

Every claim is re-derived under the mutation (the caches cleared), and compared with the
unmutated verdicts: an expected flip that does not happen, a flip to another verdict, or any
other verdict that changes fails the test.
"""

from __future__ import annotations

from unittest import mock

import sympy as sp
from lgw.theory.eros import bounds as B
from lgw.theory.eros import laws as L
from lgw.theory.eros import parameters as P
from lgw.theory.eros.claims import all_claims, clear_caches

from tests.mutation import MutationSuite, maker


def _tsm_printed_as_derived(e0, beta, p, q):
    """The printed (5) time with p and q exchanged: the derived q/(beta(q-p))|e0|^((q-p)/q)."""
    return q / (beta * (q - p)) * abs(e0) ** ((q - p) / q)


def _ftsm_printed_as_derived(e0, alpha, beta, p, q):
    return q / (alpha * (q - p)) * B._log1p(alpha * abs(e0) ** ((q - p) / q) / beta)


def _surface_without_alpha():
    return L.ed + L.beta * L.sig(L.e, L.r)  # the terminal surface (5), not (6)


def _weights_b_one(d=L.dist):
    return sp.exp(-L.N * d), sp.Integer(1)  # b(D) = 1: the switching term never blended out


_m = maker(clear_caches)
MUTATIONS = (
    _m("bound: the printed (5) settling time made the derived one",
       {"settling-tsm": "checked", "growth-e0": "checked"},
       "the printed time then equals the closed form (and the ODE) over the range, is a "
       "nonnegative time, and grows with |e0|",
       mock.patch.object(B, "ts_tsm_printed", _tsm_printed_as_derived)),
    _m("bound: the printed (7) settling time made the derived one",
       {"settling-ftsm": "checked"},
       "(7) then equals the closed form over the range",
       mock.patch.object(B, "ts_ftsm_printed", _ftsm_printed_as_derived)),
    _m("law: the fast terminal surface (6) without its alpha term",
       {"sdot-11": "refuted", "ueq-14": "refuted", "singular-term": "refuted"},
       "(11) is no longer the derivative of the law's surface, the law's u_eq is no longer the "
       "printed (14), and e' on the surface loses its alpha|e|^r term; everything derived from "
       "the surface itself (s' = u_s, the fuzzy blend) still holds",
       mock.patch.object(L, "surface_ftsm", _surface_without_alpha)),
    _m("law: the fuzzy weight b(D) = 1",
       {"fuzzy-condition": "refuted"},
       "(1 - a)/b -> 0, not N/M, as D -> 0: the reaching condition's limits and supremum change",
       mock.patch.object(L, "fuzzy_weights", _weights_b_one)),
    _m("model constant: the sampling time 0.1 s",
       {"sampled-tanh": "refuted"},
       "k dt/phi = 4 > 2 at the default gains: the sampled boundary layer is a limit cycle",
       mock.patch.object(P, "DT_SAMPLE", 0.1)),
    _m("model constant: Table 1's mass and radius as measured",
       {"table1-constants": "checked"},
       "the printed mass is the measured 6.687e15 kg and the radius the volume-equivalent one",
       mock.patch.object(P, "MASS_PRINTED", P.MASS),
       mock.patch.object(P, "RADIUS_PRINTED", P.R_MEAN)),
)


class TestMutations(MutationSuite):
    compute = staticmethod(all_claims)
    clear = staticmethod(clear_caches)
    mutations = MUTATIONS
    default = 4  # the sampling time: no new SymPy derivation
