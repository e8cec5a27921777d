"""lgw.tuning.mars: seed 000's gain design, certificates, property checks and commands.

``COMMANDS`` maps each verb the system implements to its module (``cmd_<verb>``) and a one-line
help; ``lgw.tuning.cli`` reads it without importing the modules, so ``lgw --help`` stays fast.
"""

COMMANDS = {
    "bounds": "every settling-time, neighbourhood and landing-time bound for a gain set",
    "simulate": "batched simulation and Monte Carlo campaigns of the closed loop",
    "verify": "property campaign: observed times and neighbourhoods against the proven bounds",
    "tune": "gain design for a landing time and a thrust limit, with a certificate",
    "report": "the derivation report (Markdown, LaTeX, HTML) with every claim's verdict",
    "optimal": "the lossless-convexification fuel-optimal baseline",
    "compare": "the paper's Part 1 comparison on Table I (table, JSON, figure)",
}
