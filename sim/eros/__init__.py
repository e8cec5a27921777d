"""lgw.sim.eros: seed 002's plant (rotating frame of 433 Eros, two-point or polyhedral gravity),
the six generated controllers and the batched sampled-data simulator."""
