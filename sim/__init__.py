"""lgw.sim, floor 2: integrators, generated laws, plants, campaigns and executors.

May import ``lgw.theory``; never ``lgw.tuning`` (tests/test_layering.py).  Shared machinery at
this root; one subpackage per system: ``mars`` (seed 000: plant, laws generated from
``lgw.theory.mars``, batched RK4 / dopri5, reference mode, campaigns, SOCP baseline),
``lunar`` (seed 001), ``eros`` (seed 002).
"""

if __name__ != "lgw.sim":  # the folder sim/ is installed as lgw.sim only
    raise ImportError(f"this folder is the package lgw.sim: import lgw.sim, not {__name__}")
