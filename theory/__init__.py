"""lgw.theory, floor 1: SymPy laws, Lyapunov derivatives, bounds, claims with evidence, reports.

Imports neither ``lgw.sim`` nor ``lgw.tuning`` (tests/test_layering.py).  Shared machinery at
this root (claims and evidence, settling-time results, symbolic helpers, report rendering);
one subpackage per system: ``mars`` (seed 000), ``lunar`` (seed 001), ``eros`` (seed 002).
"""

if __name__ != "lgw.theory":  # the folder theory/ is installed as lgw.theory only
    raise ImportError("this folder is the package lgw.theory: import lgw.theory, not "
                      f"{__name__}")
