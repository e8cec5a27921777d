"""Seed 000's simulation statements (Part 1 comparison, Parts 2 and 3), judged over what the
paper leaves open.

The paper states the super-twisting gains B1, B2 of (46) but not the gains of its guidance
(25), its Isp, its GPOPS settings or whether drag is flown.  A statement about (25) is
therefore judged over a box of the gains the paper does not fix and over its own campaign of
initial states, never on one chosen gain set:

  "reproduced at gains G (found by search)"           -> checked, the search's best point G;
  "not reproducible within box B (budget, best margin)" -> unproven, with the best margin;
  "refuted for the paper's stated gains"              -> refuted, with the witness re-checked
                                                          by a second integrator (dopri5).

Theory may not import the simulator: the report layer (``lgw.tuning.mars.report_scenarios``)
flies the cases and passes a plain record in; the margins, the search's verdict and the claims
are computed here from that record.  Record layout (every number plain):

  {"comparison": the report of ``lgw.tuning.mars.compare.run_comparison`` (rows per method
                 and disturbance, each with landed, fuel, landing_time, min_altitude,
                 vel_error, outcome and a "dopri5" re-flight),
   "search": {"law": the law flown for (25), "box": {gain: [lo, hi, scale]}, "budget": text,
              "seed": int, "method": text,
              "trials": [{"label", "gains": {...}, "part1": {...}, "part1_sin": {...},
                          "part2": {...}, "part3": {...}}, ...]}}

Without a record (``lgw report mars --no-sim``) every claim says so: unproven, with the
command that runs them.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

from lgw.theory.evidence import Claim, Search, Step, Unproven, Witness

# seed 000 Part 1-3 numbers, as printed
PAPER_FUEL_OPTIMAL = 212.9067  # kg, GPOPS
PAPER_FUEL_PROPOSED = 238.2907  # kg, guidance (25)
PAPER_FUEL_STSMG = 277.1288  # kg, (46)
PAPER_T_STSMG = 30.0  # s, "STSMG ... soft landing in 30 s"
PAPER_PART3_TIME = 10.0  # s, "the convergence time is always within 10 s"
PAPER_PART2_TOUCHDOWN = 1.5  # m/s, "1.5 (m/s) as its maximum velocity"
STSMG_GAINS = {"B1": [1200, 1000, 1000], "B2": [5500, 5000, 5000]}

NOT_RUN = ("the simulations were not run in this report (lgw report mars --no-sim); "
           "`lgw report mars --out DIR` flies them")


def _rows(comparison: Mapping[str, Any] | None, method: str, dist: str,
          amp: float | None = None) -> list[Mapping[str, Any]]:
    if not comparison:
        return []
    return [r for r in comparison["rows"] if r["method"] == method and r["disturbance"] == dist
            and (amp is None or r["dist_amplitude"] == amp)]


def _finite(x: Any) -> float:
    try:
        f = float(x)
    except (TypeError, ValueError):
        return math.nan
    return f


def _search_step(statement: str, search: Mapping[str, Any],
                 margin: Callable[[Mapping[str, Any]], float], what: str) -> Step:
    """A search over the gain box for a gain set that reproduces a statement: margin >= 0
    reproduces; the best margin is the largest found.  Checked ("reproduced at G") when it
    is >= 0, unproven ("not reproducible within the box") otherwise; never refuted (the
    statement is existential in the gains the paper does not state)."""
    best, best_pt, n = -math.inf, {}, 0
    for tr in search["trials"]:
        n += 1
        m = margin(tr)
        m = m if math.isfinite(m) else -math.inf
        if m > best:
            best, best_pt = m, {"trial": tr["label"], **tr["gains"]}
    found = ("reproduced at the gains of the best point (found by search)" if best >= 0
             else "not reproducible within the box (best margin below 0)")
    domain = {**{k: list(v) for k, v in search["box"].items()},
              "law": search["law"], "scenario": what}
    return Step(statement, Search(domain, f"{search['method']}; margin {what}: >= 0 "
                                  f"reproduces, the best margin is the largest found; {found}",
                                  max(n, 1), best if math.isfinite(best) else -1e300,
                                  best_pt, search.get("seed"), None, True,
                                  budget=search["budget"]))


def _not_run(statement: str) -> Step:
    return Step(statement, Unproven(NOT_RUN))


def _claim(cid: str, eq: str, title: str, paper: str, derived: str, steps: list[Step],
           numbers: Mapping[str, Any] | None = None, law: str = "printed") -> Claim:
    return Claim(cid, eq, title, paper, derived, steps, law=law, scope="scenario",
                 numbers=dict(numbers or {}))


def _fuel_margin(opt: float) -> Callable[[Mapping[str, Any]], float]:
    ratio = PAPER_FUEL_PROPOSED / PAPER_FUEL_OPTIMAL

    def m(tr: Mapping[str, Any]) -> float:
        p = tr["part1"]
        if not p["landed"]:
            return -1.0
        return (ratio - _finite(p["fuel"]) / opt) / ratio
    return m


def part1_fuel_claim(record: Mapping[str, Any] | None) -> Claim:
    ratio = PAPER_FUEL_PROPOSED / PAPER_FUEL_OPTIMAL
    statement = (f"(25) lands the Table I case with at most {ratio:.4f} x the fuel of the "
                 "offline optimum (the paper's 238.2907 / 212.9067 kg), no disturbance")
    opt_rows = _rows(record and record.get("comparison"), "optimal", "none")
    if not record or not opt_rows or not record.get("search"):
        steps = [_not_run(statement)]
        numbers = {}
    else:
        opt = _finite(opt_rows[0]["fuel"])
        steps = [_search_step(statement, record["search"], _fuel_margin(opt),
                              f"(ratio - fuel/optimum)/ratio, optimum {opt:.2f} kg")]
        numbers = {"optimum fuel (kg)": opt, "paper ratio": ratio}
    return _claim("part1-fuel", "Part 1, Fig. 4", "Fuel of the proposed guidance against the "
                  "offline optimum", "the offline optimal guidance consumes 212.9067 kg fuel and "
                  "the proposed guidance consumes 238.2907 kg fuel: an acceptable fuel usage",
                  "The printed kilograms need the paper's unstated Isp, GPOPS model and gains "
                  "(lgw compare mars explains why they are not reproducible); the checkable "
                  "part is the ratio to the optimum flown on the same plant, searched over the "
                  "gains of (25) the paper does not state.", steps, numbers)


def part1_collision_claim(record: Mapping[str, Any] | None) -> Claim:
    statement = ("with a_p,i = sin t the offline optimal guidance (open loop) collides while "
                 "(25) lands with the altitude positive throughout")
    comp = record and record.get("comparison")
    opt = _rows(comp, "optimal", "sin", 1.0)
    if not record or not opt or not record.get("search"):
        return _claim("part1-collision", "Part 1, Fig. 3(c)", "Collision of the offline "
                      "optimum under a_p = sin t", "the collision occurs with the offline "
                      "optimal guidance, while with the proposed guidance the altitude is "
                      "positive", "Judged on the flights of lgw compare mars.",
                      [_not_run(statement)])
    o = opt[0]
    collided = (not o["landed"]) and _finite(o["min_altitude"]) <= 0.0

    def m(tr: Mapping[str, Any]) -> float:
        p = tr["part1_sin"]
        if not collided:
            return -1.0
        if not p["landed"]:
            return -1.0
        return _finite(p["min_altitude"]) / 1000.0  # km above ground at the lowest point
    step = _search_step(statement, record["search"], m,
                        "the optimum collides (else -1) and (25) lands; the lowest altitude "
                        "of (25) in km")
    return _claim("part1-collision", "Part 1, Fig. 3(c)", "Collision of the offline optimum "
                  "under a_p = sin t", "the collision occurs with the offline optimal guidance, "
                  "while with the proposed guidance the altitude is positive",
                  f"The open-loop optimum under a_p,i = sin t: {o['outcome']} (lowest altitude "
                  f"{_finite(o['min_altitude']):.3g} m); (25) searched over its gains.", [step],
                  {"optimum under sin t": o["outcome"]})


def part1_stsmg_claim(record: Mapping[str, Any] | None) -> Claim:
    statement = ("(46) with the paper's stated B1 = (1200, 1000, 1000), B2 = (5500, 5000, "
                 "5000) lands the Table I case softly within 30 s")
    rows = _rows(record and record.get("comparison"), "super-twisting", "none")
    own = [r for r in rows if not math.isnan(_finite(r.get("paper_fuel")))] or rows
    if not own:
        steps = [_not_run(statement)]
        numbers: dict[str, Any] = {}
    else:
        r = own[0]
        landed = bool(r["landed"])
        t = _finite(r["landing_time"])
        margin = ((PAPER_T_STSMG - t) / PAPER_T_STSMG if landed
                  else -_finite(r["vel_error"]) / 3.0)  # touchdown speed against 3 m/s soft
        d5 = r.get("dopri5", {})
        d5_margin = ((PAPER_T_STSMG - _finite(d5.get("landing_time"))) / PAPER_T_STSMG
                     if d5.get("landed") else -1.0)
        point = {**STSMG_GAINS, "outcome (RK4)": r["outcome"],
                 "touchdown speed (m/s)": _finite(r["vel_error"]),
                 "dopri5 landed": bool(d5.get("landed"))}
        w = Witness(point, margin, "the RK4 simulator on Table I (lgw compare mars): (30 - "
                    "t_land)/30 if landed, else -(touchdown speed)/(3 m/s)", d5_margin,
                    "the adaptive dopri5 re-flight of the same case: (30 - t_land)/30 if it "
                    "lands, else -1") if margin < 0 else None
        steps = [Step(statement, Search({"gains": "the paper's stated B1, B2",
                                         "case": "Table I"},
                                        "one flight at the paper's stated gains", 1, margin,
                                        point, None, w, True,
                                        budget="one case, RK4 and dopri5"))]
        numbers = {"fuel (kg)": _finite(r["fuel"]), "paper fuel (kg)": PAPER_FUEL_STSMG,
                   "outcome": r["outcome"]}
    return _claim("part1-stsmg", "(46), Part 1, Fig. 5", "The super-twisting baseline with "
                  "the paper's gains", "STSMG can ensure the lander to achieve a soft landing "
                  "in 30 s ... 277.1288 (kg) fuel is used",
                  "The paper states (46)'s gains: judged at them, on the flights of lgw "
                  "compare mars (RK4, re-flown by dopri5).", steps, numbers,
                  law="super-twisting")


def part1_faster_claim(record: Mapping[str, Any] | None) -> Claim:
    statement = ("(25) lands the Table I case sooner than 30 s and with less than 277.1288 kg "
                 "(the paper's STSMG figures), no disturbance")

    def m(tr: Mapping[str, Any]) -> float:
        p = tr["part1"]
        if not p["landed"]:
            return -1.0
        return min((PAPER_T_STSMG - _finite(p["landing_time"])) / PAPER_T_STSMG,
                   (PAPER_FUEL_STSMG - _finite(p["fuel"])) / PAPER_FUEL_STSMG)
    steps = ([_search_step(statement, record["search"], m, "min of the relative time and fuel "
                           "margins against the STSMG figures")]
             if record and record.get("search") else [_not_run(statement)])
    return _claim("part1-faster", "Part 1, Fig. 5", "The proposed guidance against the "
                  "super-twisting baseline", "compared with STSMG, the proposed guidance has "
                  "a faster convergence speed but with less fuel consumption",
                  "The STSMG as printed does not land (claim part1-stsmg), so (25) is judged "
                  "against the paper's own STSMG figures (30 s, 277.1288 kg), searched over "
                  "the gains of (25).", steps)


def part2_touchdown_claim(record: Mapping[str, Any] | None) -> Claim:
    statement = ("every Table II case under a_p,i = 20 sin t (47) reaches the ground or lands "
                 f"at no more than {PAPER_PART2_TOUCHDOWN} m/s (-1 if a case does neither by the "
                 "horizon)")

    def m(tr: Mapping[str, Any]) -> float:
        p = tr.get("part2")
        if not p:
            return -math.inf
        v = _finite(p["max_touchdown_speed"])
        if not math.isfinite(v):  # a case neither landed nor reached the ground by the horizon
            return -1.0
        return (PAPER_PART2_TOUCHDOWN - v) / PAPER_PART2_TOUCHDOWN
    search = record and record.get("search")
    ok = bool(search) and any(tr.get("part2") for tr in search["trials"])
    steps = ([_search_step(statement, search, m, "(1.5 - max touchdown speed)/1.5 over the "
                           "campaign")] if ok else [_not_run(statement)])
    return _claim("part2-touchdown", "Part 2, Fig. 8", "Touchdown speed under the dust-storm "
                  "disturbance", "the lander crashes on the Martian surface with 1.5 (m/s) as "
                  "its maximum velocity ... a soft landing",
                  "Judged on a Table II campaign under (47), searched over the gains of (25).",
                  steps)


PAPER_S1_BAND, PAPER_S2_BAND = 23.8472, 26.5257  # m, m/s: (31), (39) with the paper's numbers


def part2_bands_claim(record: Mapping[str, Any] | None) -> Claim:
    statement = ("in every Table II case under (47), |s1,i| <= 23.8472 m after 9.76 s and "
                 "|s2,i| <= 26.5257 m/s after 7.89 s, on every axis")

    def m(tr: Mapping[str, Any]) -> float:
        p = tr.get("part2")
        if not p:
            return -math.inf
        return min((PAPER_S1_BAND - _finite(p["max_s1_after"])) / PAPER_S1_BAND,
                   (PAPER_S2_BAND - _finite(p["max_s2_after"])) / PAPER_S2_BAND)
    search = record and record.get("search")
    ok = bool(search) and any(tr.get("part2") for tr in search["trials"])
    steps = ([_search_step(statement, search, m, "the smaller relative margin of the two "
                           "bands over the campaign's recorded nodes")]
             if ok else [_not_run(statement)])
    return _claim("part2-bands", "Part 2, Figs. 9-10", "The surfaces inside the printed "
                  "neighbourhoods in the Monte Carlo runs",
                  "the system state s1i can be within a boundary, which is +-23.8472 after "
                  "9.76 s; s2 ... 26.5257 (t = 7.89 s)",
                  "Judged on a Table II campaign under (47), searched over the gains of (25).",
                  steps)


def part3_time_claim(record: Mapping[str, Any] | None) -> Claim:
    statement = (f"every Table III case lands within {PAPER_PART3_TIME:g} s with |F_i| <= "
                 "50 kN per axis")

    def m(tr: Mapping[str, Any]) -> float:
        p = tr.get("part3")
        if not p:
            return -math.inf
        if p["landed"] < p["cases"]:
            return -1.0
        return (PAPER_PART3_TIME - _finite(p["max_landing_time"])) / PAPER_PART3_TIME
    search = record and record.get("search")
    ok = bool(search) and any(tr.get("part3") for tr in search["trials"])
    steps = ([_search_step(statement, search, m, "(10 s - latest landing)/10 s over the "
                           "campaign (-1 if a case does not land)")]
             if ok else [_not_run(statement)])
    return _claim("part3-time", "Part 3, Figs. 11-12", "Landing time with the thrust limit",
                  "the proposed guidance can drive the lander to the target landing site with "
                  "any initial positions and the convergence time is always within 10 s",
                  "Judged on a Table III campaign with the 50 kN per-axis limit, searched over "
                  "the gains of (25).", steps)


def comparison_claims(record: Mapping[str, Any] | None) -> list[Claim]:
    """The claims on seed 000's simulation statements, from the report layer's record (None:
    not simulated in this report)."""
    return [part1_fuel_claim(record), part1_collision_claim(record), part1_stsmg_claim(record),
            part1_faster_claim(record), part2_touchdown_claim(record), part2_bands_claim(record),
            part3_time_claim(record)]
