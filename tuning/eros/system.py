"""Seed 002 (probe landing on 433 Eros, fuzzy fast terminal sliding mode) as a ``System``."""

from lgw.tuning.system import NotApplicable, laid_out_system

SYSTEM = laid_out_system(
    "eros", "002",
    title="Fuzzy fast terminal sliding mode tracking of a probe landing on asteroid 433 Eros",
    summary="433 Eros landing (fuzzy FTSMC)",
    bounds="settling (5)/(6) and reaching times, printed vs derived, for a gain set",
    simulate="the six controllers on the 15 s scenario or a Monte Carlo campaign",
    verify="Monte Carlo tracking times against the proven per-case reaching + sliding bound",
    report="the derivation report (Markdown, LaTeX, HTML) with every claim's verdict",
    tune="alpha, beta, p/q, k for a settling target and a control limit, with a certificate",
    compare="the six controllers on Table 2's metrics and the tracking times, 15 s scenario "
            "(table, JSON, figure)",
    optimal=NotApplicable(
        "seed 002 has no separate offline baseline: its laws track the paper's own "
        "optimal trajectory (Table 1's boundary values, the descent profile), "
        "which simulate and compare fly; the lossless-convexification baseline is "
        "seed 000's Part 1 comparison"),
)
