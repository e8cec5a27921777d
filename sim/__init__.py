"""Floor 2 of the workbench: simulation of seed 000's closed loop.

``sim`` may import ``theory``; it never imports ``tuning``.  Modules:

* ``sim.parameters``  sim-only constants (Martian atmosphere, drag coefficient, integrator
  defaults), each with its source or reasoning;
* ``sim.mars``        the plant, seed 000 (10)-(14), and the drag models (12);
* ``sim.laws``        the registry of guidance laws, compiled from the SymPy expressions of
  ``theory`` (numba);
* ``sim.disturbances`` the lumped disturbance a_p: none, A sin t (47), bounded random, worst case;
* ``sim.batch``       the batched fixed-step simulator (``simulate_batch``, ``BatchResult``);
* ``sim.reference``   the tight solve_ivp reference (``simulate_reference``);
* ``sim.campaign``    Table II / III dispersions, CSV states, local and dask executors;
* ``sim.interop``     the closed loop as a python-control ``nlsys``.
"""
