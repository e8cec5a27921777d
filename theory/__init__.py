"""Floor 1 of the workbench: symbolic laws, Lyapunov derivatives, bounds and checked claims.

This package imports neither ``sim`` nor ``tuning``.
"""
