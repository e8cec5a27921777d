"""Seed 000 (Mars powered descent, fixed-time multiple sliding surfaces) as a ``System``."""

from lgw.tuning.system import System, Verb

_M = "lgw.tuning.mars"

SYSTEM = System(
    name="mars", seed="000",
    title="Mars powered-descent guidance based on (practical) fixed-time stabilization",
    summary="Mars powered descent (fixed-time MSS)",
    gains=f"{_M}.gainset", claims="lgw.theory.mars.claims:all_claims",
    interop="lgw.sim.mars.interop",
    kernels="lgw.sim.mars.batch:warmup_kernels",
    verbs={
        "bounds": Verb(f"{_M}.cmd_bounds", "every settling-time, neighbourhood and "
                         "landing-time bound for a gain set"),
        "simulate": Verb(f"{_M}.cmd_simulate", "batched simulation and Monte Carlo "
                           "campaigns of the closed loop"),
        "verify": Verb(f"{_M}.cmd_verify", "property campaign: observed times and "
                         "neighbourhoods against the proven bounds"),
        "tune": Verb(f"{_M}.cmd_tune", "gain design for a landing time and a thrust "
                       "limit, with a certificate"),
        "report": Verb(f"{_M}.cmd_report", "the derivation report (Markdown, LaTeX, "
                         "HTML) with every claim's verdict"),
        "compare": Verb(f"{_M}.cmd_compare", "the paper's Part 1 comparison on Table I "
                        "(table, JSON, figure)"),
        "optimal": Verb(f"{_M}.cmd_optimal", "the lossless-convexification fuel-optimal "
                        "baseline"),
        "warmup": Verb("lgw.tuning.cmd_warmup", "build and cache every compiled kernel in "
                       "one step"),
    },
)
