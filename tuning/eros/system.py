"""Seed 002 (probe landing on 433 Eros, fuzzy fast terminal sliding mode) as a ``System``."""

from lgw.tuning.system import NotApplicable, System, Verb

_M = "lgw.tuning.eros"

SYSTEM = System(
    name="eros", seed="002",
    title="Fuzzy fast terminal sliding mode tracking of a probe landing on asteroid 433 Eros",
    summary="433 Eros landing (fuzzy FTSMC)",
    gains=f"{_M}.gainset", claims="lgw.theory.eros.claims:all_claims",
    interop="lgw.sim.eros.interop",
    kernels="lgw.sim.eros.batch:warmup_kernels",
    verbs={
        "bounds": Verb(f"{_M}.cmd_bounds", "settling (5)/(6) and reaching times, printed "
                         "vs derived, for a gain set"),
        "simulate": Verb(f"{_M}.cmd_simulate", "the six controllers on the 15 s scenario "
                           "or a Monte Carlo campaign"),
        "verify": Verb(f"{_M}.cmd_verify", "Monte Carlo tracking times against the proven "
                         "per-case reaching + sliding bound"),
        "report": Verb(f"{_M}.cmd_report", "the derivation report (Markdown, LaTeX, "
                         "HTML) with every claim's verdict"),
        "tune": Verb(f"{_M}.cmd_tune", "alpha, beta, p/q, k for a settling target and a "
                       "control limit, with a certificate"),
        "compare": Verb(f"{_M}.cmd_compare", "the six controllers on Table 2's metrics and "
                          "the tracking times, 15 s scenario (table, JSON, figure)"),
        "optimal": NotApplicable(
            "seed 002 has no separate offline baseline: its laws track the paper's own "
            "optimal trajectory (Table 1's boundary values, the descent profile), "
            "which simulate and compare fly; the lossless-convexification baseline is "
            "seed 000's Part 1 comparison"),
        "warmup": Verb("lgw.tuning.cmd_warmup", "build and cache every compiled kernel in "
                       "one step"),
    },
)
