"""The project's tests use the installed strategies of ``lgw.testing.mars`` (one copy)."""

from lgw.testing.mars import (  # noqa: F401
    gain_dicts,
    gain_sets,
    log_uniform,
    nonzero_surfaces,
    open_interval,
    per_axis,
    positions,
    signed_magnitude,
    sim_positions,
    state_batches,
    surfaces,
    velocities,
)
