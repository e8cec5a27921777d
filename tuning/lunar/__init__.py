"""lgw.tuning.lunar: seed 001's commands.

``COMMANDS`` maps each verb to a one-line help; ``lgw.tuning.cli`` reads it without importing
the command modules."""

COMMANDS = {
    "bounds": "the (18) constants beside the true filter L2 gains, and (19)-(21) for a case",
    "simulate": "fly the Section 5 scenario (or random cases): errors, thrust, torque, d0e, V2",
    "verify": "property campaign: V2 (13), (18), (19), (21a) against measured runs",
    "report": "the derivation report (Markdown, LaTeX, HTML) with every claim's verdict",
    "tune": "gains, command filter and thrust redundancy for a tracking target, certified",
    "compare": "Section 5 with and without failure and saturation, ideal against coupled",
}
