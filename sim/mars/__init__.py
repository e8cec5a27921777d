"""lgw.sim.mars: simulation of seed 000's closed loop.  Modules:

* ``parameters``   sim-only constants (Martian atmosphere, drag coefficient, integrator
  defaults), each with its source or reasoning;
* ``plant``        the plant, seed 000 (10)-(14), and the drag models (12);
* ``laws``         the registry of guidance laws, compiled from the SymPy expressions of
  ``lgw.theory.mars`` (numba);
* ``disturbances`` the lumped disturbance a_p: none, A sin t (47), bounded random, worst case;
* ``batch``        the batched simulator (``simulate_batch``, ``BatchResult``);
* ``reference``    the tight solve_ivp reference (``simulate_reference``);
* ``campaign``     Table II / III dispersions, CSV states, local and dask executors;
* ``interop``      the closed loop as a python-control ``nlsys``;
* ``optimal``      the lossless-convexification fuel-optimal baseline (SOCP).
* ``arrival``      thrust spikes after arrival (peak |F_i| once axis i is in its landing
  band), from a recorded trajectory.
"""
