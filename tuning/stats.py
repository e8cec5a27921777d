"""Campaign statistics that are never impossible: ``lgw.sim.stats`` (where the simulators' own
summaries can use them too), re-exported for the command layer."""

from lgw.sim.stats import finite_stats, outcome_counts

__all__ = ["finite_stats", "outcome_counts"]
