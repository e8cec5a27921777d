"""lgw.tuning.eros: seed 002's commands, scenario claims and gain design.

``COMMANDS`` maps each verb to a one-line help; ``lgw.tuning.cli`` reads it without importing
the command modules (``cmd_<verb>``)."""

COMMANDS = {
    "bounds": "settling (5)/(6) and reaching times, printed vs derived, for a gain set",
    "simulate": "the six controllers on the 15 s scenario or a Monte Carlo campaign",
    "verify": "Monte Carlo tracking times against the proven per-case reaching + sliding bound",
    "report": "the derivation report (Markdown, LaTeX, HTML) with every claim's verdict",
    "tune": "alpha, beta, p/q, k for a settling target and a control limit, with a certificate",
}
