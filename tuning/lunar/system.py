"""Seed 001 (lunar descent, adaptive backstepping with saturation and failure) as a
``System``.

Its card, what ``lgw`` shows of it (seed, title, summary, each verb's help or why it does
not apply), is ``data/system.toml``; its parts are at the standard paths.
"""

from lgw.tuning.system import carded_system

SYSTEM = carded_system("lunar")
