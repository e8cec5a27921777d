"""Seed 000 item by item: every numbered equation, definition, hypothesis, lemma, theorem,
remark and quantitative simulation statement, with the claims that check it or the reason it
cannot be checked here.  Read from the paper text in order (sections II to V).

A test (tests/mars/test_claims_coverage.py) checks that no row is empty and that every claim
id named here exists in ``lgw.theory.mars.claims.all_claims(gains)``.
"""

from __future__ import annotations

from lgw.theory.report import CoverageRow as R

_SIM = ("a simulation outcome with the paper's gains, which the paper does not print; "
        "the simulator reproduces the experiment with chosen gains")

COVERAGE: tuple[R, ...] = (
    # --- II.A: finite- and fixed-time stability
    R("(1)", "equation", not_checkable="it only names the system class x' = f(x) that "
      "Lemma 1, Lemma 2 and Theorem 1 speak of"),
    R("Lemma 1", "lemma", ("lemma1",)),
    R("Definition 1", "definition", ("theorem1",)),
    R("Lemma 2", "lemma", ("lemma2", "exact-bound")),
    R("(2)", "equation", ("lemma2", "exact-bound", "exact-time")),
    R("(3)", "equation", ("lemma2", "exact-bound")),
    # --- II.B: practical fixed-time stability
    R("Theorem 1", "theorem", ("theorem1",)),
    R("(4)", "equation", ("theorem1",)),
    R("(5)", "equation", ("theorem1",)),
    R("(6)", "equation", ("theorem1",)),
    R("(7)", "equation", ("theorem1",)),
    R("(8)", "equation", ("theorem1",)),
    R("(9)", "equation", ("theorem1",)),
    # --- III.A: the lander model
    R("initial distance 2000-5000 m, speed within 1000 m/s", "statement",
      not_checkable="it describes typical mission conditions; no result depends on it"),
    R("(10)", "equation", ("plant",)),
    R("(11)", "equation", ("plant",)),
    R("(12)", "equation", ("drag-12",)),
    R("(13)", "equation", ("mass-13-14",)),
    R("(14)", "equation", ("mass-13-14", "thrust-table1-printed@gains",
                           "thrust-table1-corrected@gains")),
    # --- III.B: the guidance
    R("(15)", "equation", ("surface2", "plant")),
    R("(16)", "equation", ("surface2", "V1dot", "T1", "exact-time")),
    R("(17)", "definition", not_checkable="it defines sgn (used through sig in "
      "lgw.theory.symbolic; sgn(0) = 0 as printed)"),
    R("Theorem 2", "theorem", ("T1",)),
    R("(18)", "equation", ("T1", "paper-numbers", "paper-numbers-part1@gains",
                           "tuning-rule@gains", "remark2")),
    R("(19)", "equation", ("V1dot", "V1dot-vector")),
    R("(20)", "equation", ("V1dot", "V1dot-vector")),
    R("(21)", "equation", ("surface2",)),
    R("(22)", "equation", ("s2dot",)),
    R("(23)", "equation", ("s2dot", "plant")),
    R("(24)", "equation", ("s2dot-24",)),
    R("Theorem 3", "theorem", ("T2-printed", "T2-corrected")),
    R("(25)", "equation", ("laws-agree", "V2dot-printed", "T2-printed",
                           "bounded-command-printed", "bounded-command-printed@gains",
                           "thrust-table1-printed@gains")),
    R("(25') corrected law (not in the paper)", "equation",
      ("laws-agree", "V2dot-corrected", "T2-corrected", "bounded-command-corrected",
       "thrust-table1-corrected@gains")),
    R("(26)", "equation", ("T2-printed", "T2-corrected", "paper-numbers",
                           "paper-numbers-part1@gains", "tuning-rule@gains")),
    R("(27)", "equation", ("V2dot-printed", "V2dot-corrected")),
    R("(28)", "equation", ("V2dot-printed", "V2dot-corrected")),
    R("(29)", "equation", ("V2dot-printed", "V2dot-corrected")),
    R("bounds independent of the initial state; landing within a pre-defined time",
      "statement", ("landing-time",)),
    R("tuning rule max_i (18)_i <= tf, max_i (26)_i <= tf", "statement",
      ("landing-time", "tuning-rule@gains")),
    R("Remark 1", "remark", ("remark1",)),
    R("Remark 2", "remark", ("remark2", "thrust-table1-printed@gains",
                             "thrust-table1-corrected@gains")),
    # --- III.C: robustness
    R("(30)", "equation", ("plant", "V2dot-disturbed-printed", "V2dot-disturbed-corrected")),
    R("Hypothesis 1", "hypothesis", ("hypothesis1-47", "practical-hypotheses@gains")),
    R("Theorem 4", "theorem", ("s1-neighborhood", "T3", "practical-hypotheses@gains")),
    R("(31)", "equation", ("s1-neighborhood", "paper-numbers-part2@gains", "theta-effect")),
    R("(32)", "equation", ("T3", "landing-time", "theta-effect")),
    R("(33)", "equation", ("plant", "V2dot-disturbed-corrected")),
    R("(34)", "equation", ("s2dot-24", "V2dot-disturbed-printed")),
    R("(35)", "equation", ("V2dot-disturbed-printed", "V2dot-disturbed-corrected")),
    R("(36)", "equation", ("V2dot-disturbed-printed", "V2dot-disturbed-corrected")),
    R("(37)", "equation", ("s2-neighborhood",)),
    R("(38)", "equation", ("s2-neighborhood",)),
    R("(39)", "equation", ("s2-neighborhood", "paper-numbers-part2@gains", "theta-effect")),
    R("(40)", "equation", ("T2-practical", "paper-numbers", "paper-numbers-part2@gains",
                           "theta-effect")),
    R("M_i (definition before (41))", "definition", ("s1-neighborhood",)),
    R("(41)", "equation", ("s1-neighborhood",)),
    R("(42)", "equation", ("s1-neighborhood",)),
    R("(43)", "equation", ("s1-neighborhood",)),
    R("(44)", "equation", ("s1-neighborhood",)),
    R("(45)", "equation", ("T1-practical", "paper-numbers", "paper-numbers-part2@gains")),
    R("T3i = max{T1i, T2i}", "statement", ("T3",)),
    R("large a_pMAX widens, large theta shrinks the neighbourhood and slows convergence",
      "statement", ("theta-effect",)),
    # --- IV.A Part 1
    R("Table I", "table", ("remark1", "thrust-table1-printed@gains",
                           "thrust-table1-corrected@gains")),
    R("terminal states r(tf) = 0, v(tf) = 0", "statement",
      not_checkable="it is the landing requirement itself; the simulator's landing criterion "
      "(|r|, |v| <= 0.1) is a parameter (lgw.theory.mars.parameters), judged by simulation"),
    R("Fig. 2: precise landing, no chattering", "simulation statement", not_checkable=_SIM),
    R("Fig. 2(c): command thrust below 4 x 10^4 N", "simulation statement",
      ("thrust-table1-printed@gains", "thrust-table1-corrected@gains")),
    R("tf = 30 s (GPOPS comparison)", "simulation statement", ("tuning-rule@gains",)),
    R("fuel 212.9067 kg (GPOPS) vs 238.2907 kg (proposed)", "simulation statement",
      not_checkable=_SIM + " (lgw compare mars)"),
    R("collision of the offline optimal guidance under a_p = sin t", "simulation statement",
      not_checkable=_SIM + " (lgw compare mars)"),
    R("(46) STSMG with B1, B2", "equation", not_checkable="the baseline law carries no "
      "stated property to check (its garbled form is read in lgw.theory.mars.supertwisting)"),
    R("STSMG: soft landing in 30 s, 277.1288 kg of fuel", "simulation statement",
      not_checkable=_SIM + " (lgw compare mars)"),
    R("T1 <= 74.5780 s, T2 <= 30.8217 s", "simulation statement",
      ("paper-numbers", "paper-numbers-part1@gains")),
    R("whole mission within 74.5780 s for any initial state", "simulation statement",
      ("landing-time",)),
    R("Fig. 6: s1x, s2x from s1x(0) = -8000 ... -1000 m within T1, T2", "simulation statement",
      ("T2-printed", "landing-time")),
    # --- IV.B Part 2
    R("Table II (300 Monte Carlo cases)", "table", not_checkable="it is a scenario "
      "distribution, not a statement; lgw simulate mars --dispersion table2 runs it"),
    R("(47)", "equation", ("hypothesis1-47", "practical-hypotheses@gains")),
    R("theta1 = 0.2, theta2 = 0.1", "parameter", ("paper-numbers",
                                                   "paper-numbers-part2@gains")),
    R("maximum final position error 23.8472 m per axis", "simulation statement",
      ("paper-numbers-part2@gains",)),
    R("touchdown at most 1.5 m/s (soft if < 3 m/s)", "simulation statement",
      not_checkable=_SIM + " (lgw simulate mars --disturbance sin)"),
    R("(39) = 26.5257 m and (40) = 131.5173 s, Fig. 9", "simulation statement",
      ("paper-numbers", "paper-numbers-part2@gains")),
    R("(31) = 23.8472 m and (45) = 85.8610 s, Fig. 10", "simulation statement",
      ("paper-numbers", "paper-numbers-part2@gains")),
    R("s1 within +-23.8472 after 9.76 s; s2 t = 7.89 s (Figs. 9-10)", "simulation statement",
      not_checkable=_SIM),
    # --- IV.C Part 3
    R("Table III (50 cases)", "table", not_checkable="it is a scenario distribution; "
      "lgw simulate mars --dispersion table3 --thrust-max 50000 runs it"),
    R("thrust limit 50000 N per axis", "parameter", ("thrust-table1-printed@gains",
                                                     "thrust-table1-corrected@gains")),
    R("Part 3: convergence always within 10 s", "simulation statement", not_checkable=_SIM),
    # --- V, abstract
    R("landing-time bound and maximum landing error computable in advance", "statement",
      ("landing-time", "s1-neighborhood", "T3")),
    # --- beyond the paper: the workbench's bounded law (lgw.theory.mars.bounded, issue 17)
    R("bounded law: derivative, finite command, reference shape, sliding time", "workbench law",
      ("bounded-derivative", "bounded-command-finite", "bounded-psi-monotone",
       "bounded-slide-time")),
    R("bounded law: practical fixed time, box invariants, saturated variant", "workbench law",
      ("bounded-fixed-time", "bounded-invariants", "bounded-sat-invariance")),
    R("bounded-sat law: outside deceleration, growth in Omega, box bounds (time, command)",
      "workbench law", ("bounded-sat-outside", "bounded-sat-growth", "bounded-sat-bounds")),
)


def coverage() -> tuple[R, ...]:
    """The coverage table of seed 000 (report order)."""
    return COVERAGE
