"""Hypothesis profiles: ``ci`` (derandomized, loaded when CI=true), ``dev`` (default) and
``thorough`` (randomized, many examples: ``pytest --hypothesis-profile=thorough``)."""

import os

from hypothesis import HealthCheck, settings

settings.register_profile("ci", derandomize=True, max_examples=30, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow], print_blob=True)
settings.register_profile("dev", max_examples=30, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=1000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow], print_blob=True)
settings.load_profile("ci" if os.environ.get("CI", "").lower() == "true" else "dev")

# Progress lines go to stderr, which click's CliRunner mixes into ``result.output``: the tests
# read documents from stdout, and the progress tests set LGW_PROGRESS themselves.
os.environ.setdefault("LGW_PROGRESS", "never")
