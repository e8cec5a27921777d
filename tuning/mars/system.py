"""Seed 000 (Mars powered descent, fixed-time multiple sliding surfaces) as a ``System``."""

from lgw.tuning.system import laid_out_system

SYSTEM = laid_out_system(
    "mars", "000",
    title="Mars powered-descent guidance based on (practical) fixed-time stabilization",
    summary="Mars powered descent (fixed-time MSS)",
    bounds="every settling-time, neighbourhood and landing-time bound for a gain set",
    simulate="batched simulation and Monte Carlo campaigns of the closed loop",
    verify="property campaign: observed times and neighbourhoods against the proven bounds",
    tune="gain design for a landing time and a thrust limit, with a certificate",
    report="the derivation report (Markdown, LaTeX, HTML) with every claim's verdict",
    compare="the paper's Part 1 comparison on Table I (table, JSON, figure)",
    optimal="the lossless-convexification fuel-optimal baseline",
)
