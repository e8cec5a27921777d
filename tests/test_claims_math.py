"""Every claim of every system shows its mathematics as formulas.

A claim renders at least one SymPy formula (its ``paper_expr``, ``derived_expr`` or a step's
``expr``) unless it is listed below as prose-only with the reason; every formula prints with
``sympy.latex`` and ``sympy.printing.mathml`` (content and presentation), and through the
report's own printers (``lgw.theory.report_math``) as well-formed MathML, with no NaN or
complex infinity in it.  The claim lists are every ``lgw.theory.<system>.claims.all_claims``
(systems found as in ``tests/test_claims_walk``), with the system's default gain set where it
takes one (``gains``), so the gain-set claims are checked too; most claims are memoised, so in
a full run this adds little to the walk that builds them anyway.
"""

from __future__ import annotations

import importlib
import inspect
import xml.dom.minidom
from collections.abc import Iterator

import pytest
import sympy as sp
from lgw.theory import report_math as RM
from lgw.theory.evidence import Cited, Claim, Step
from sympy.printing.mathml import mathml

from tests.test_claims_walk import systems

# with pytest-xdist (--dist loadgroup), on the worker that derives seed 000's claims once
pytestmark = pytest.mark.xdist_group("mars-claims")

# Claims whose statement is not a formula (or whose formula is not attached yet), per system,
# each with the reason.  An entry whose claim does render a formula fails the test (stale).
PROSE_ONLY: dict[str, dict[str, str]] = {
    "mars": {
        "thrust-table1-printed@gains": "peak command of a simulated run against the 50 kN "
                                       "limit: numbers from the scenario",
        "thrust-table1-corrected@gains": "peak command of a simulated run against the 50 kN "
                                         "limit: numbers from the scenario",
        "exact-time": "formula not attached yet (theory/mars and settling_proofs are outside "
                      "the lunar/eros part of that work)",
        "plant": "formula not attached yet (theory/mars is outside the lunar/eros part of "
                 "that work)",
        "s2dot": "formula not attached yet (theory/mars is outside the lunar/eros part of "
                 "that work)",
        "bounded-command-corrected": "formula not attached yet (theory/mars is outside the "
                                     "lunar/eros part of that work)",
        # the paper's simulation statements (lgw.theory.mars.scenario_claims)
        "part1-fuel": "fuel of simulated flights against the optimum: numbers",
        "part1-collision": "altitudes of simulated flights: numbers",
        "part1-stsmg": "outcome of the simulated (46) at the paper's gains: numbers",
        "part1-faster": "landing time and fuel of simulated flights: numbers",
        "part2-touchdown": "touchdown speeds of a simulated campaign: numbers",
        "part2-bands": "surfaces of a simulated campaign against printed bands: numbers",
        "part3-time": "landing times of a simulated campaign: numbers",
    },
    "lunar": {
        # Section 5 claims, built by lgw.sim.lunar.scenario (not in theory's list)
        "s5-no-saturation": "simulated thrust of the Section 5 run against T_max: numbers",
        "s5-d0e": "the estimate d0e of the Section 5 run against ||d||: numbers",
        "s5-tracking": "tracking errors of the Section 5 run: numbers",
    },
    "eros": {
        "table1-constants": "Table 1's mass and radius against measured constants: numbers",
        "reference-shape": "turning times and accelerations along the reference path: numbers",
        "landing-point": "altitude of Table 1's landing point above the shape model: numbers",
        # scenario claims, built by lgw.tuning.eros.scenario (not in theory's list)
        "tracked-times": "simulated tracking times: numbers",
        "fastest-sign": "ranking of simulated tracking times: numbers",
        "fastest-tanh": "ranking of simulated tracking times: numbers",
        "abs-error-sign": "ranking of simulated absolute errors (Table 2): numbers",
        "abs-error-tanh": "ranking of simulated absolute errors (Table 2): numbers",
        "chatter-fuzzy": "total variation of simulated commands: numbers",
        "chatter-tanh": "total variation of simulated commands: numbers",
    },
}


def claims_of(system: str) -> list[Claim]:
    """The system's claim list as its report builds it from theory (with the default gains
    when ``all_claims`` takes ``gains``)."""
    fn = importlib.import_module(f"lgw.theory.{system}.claims").all_claims
    if "gains" in inspect.signature(fn).parameters:
        return fn(importlib.import_module(f"lgw.theory.{system}.gains").default_gains())
    return fn()


def _steps(steps: tuple[Step, ...]) -> Iterator[Step]:
    for s in steps:
        yield s
        if isinstance(s.evidence, Cited):
            yield from _steps(s.evidence.hypotheses)


def formulas(c: Claim) -> list[sp.Basic]:
    """Every formula the report renders for ``c`` (claim, steps, remarks, cited hypotheses)."""
    out = list(RM.exprs(c.paper_expr)) + list(RM.exprs(c.derived_expr))
    for s in _steps(c.steps + c.remarks):
        out += RM.exprs(s.expr)
    return out


_CACHE: dict[str, list[Claim]] = {}


@pytest.fixture(scope="module", params=systems())
def system_claims(request) -> tuple[str, list[Claim]]:
    if request.param not in _CACHE:
        _CACHE[request.param] = claims_of(request.param)
    return request.param, _CACHE[request.param]


def test_every_claim_has_a_formula_or_a_reason(system_claims):
    system, claims = system_claims
    prose = PROSE_ONLY.get(system, {})
    missing = [c.id for c in claims if not formulas(c) and c.id not in prose]
    assert not missing, f"{system}: claims without any formula and not listed as prose-only: " \
                        f"{missing}"
    stale = [c.id for c in claims if c.id in prose and formulas(c)]
    assert not stale, f"{system}: listed as prose-only but they render a formula: {stale}"
    assert all(r.strip() for r in prose.values())


def test_every_formula_renders(system_claims):
    system, claims = system_claims
    for c in claims:
        for e in formulas(c):
            where = f"{system} {c.id}: {sp.sstr(e)[:80]}"
            assert not e.has(sp.nan, sp.zoo), where
            assert not isinstance(e, sp.logic.boolalg.BooleanAtom), where  # True/False shown
            assert sp.latex(e), where
            assert mathml(e), where
            assert mathml(e, printer="presentation"), where
            assert RM.latex(e) and RM.latex_breakable(e), where
            for block in (RM.mathml(e), RM.mathml_lines(e)):
                xml.dom.minidom.parseString(block)  # well-formed: one element, no DTD needed


def test_prose_only_ids_exist():
    """Every prose-only id names a claim of its system: one of the theory list, or a
    scenario claim the simulator layer builds (lunar: lgw.sim.lunar.scenario; eros:
    tests/eros/test_claims.SCENARIO_IDS)."""
    from tests.eros.test_claims import SCENARIO_IDS

    scenario = {"lunar": {"s5-no-saturation", "s5-d0e", "s5-tracking"}, "eros": SCENARIO_IDS,
                "mars": set()}
    for system, prose in PROSE_ONLY.items():
        known = {c.id for c in _CACHE.get(system) or claims_of(system)} | scenario[system]
        assert set(prose) <= known, (system, set(prose) - known)


@pytest.mark.parametrize("name, tex, accent", [
    ("fbar_1", r"\bar{f}", "&#175;"), ("dhat_0", r"\hat{d}", "&#710;"),
    ("Vdot_2", r"\dot{V}", "&#729;"), ("xddot", r"\ddot{x}", "&#168;"),
    ("etilde", r"\tilde{e}", "&#732;"), ("omegadot", r"\dot{\omega}", "&#729;"),
    ("lambdabar_1", r"\bar{\lambda}", "&#175;")])
def test_mathml_accents_match_latex(name, tex, accent):
    """A symbol name SymPy's LaTeX printer shows with an accent (fbar_1 as a barred f) gets the
    same accent in the report's MathML, not the letters 'bar' (lgw.theory.report_math)."""
    sym = sp.Symbol(name)
    assert tex in RM.latex(sym)
    m = RM.mathml(sym)
    assert f"<mo>{accent}</mo></mover>" in m, m
    assert not any(w in m for w in ("bar<", "hat<", "dot<", "tilde<", "omega", "lambda")), m
