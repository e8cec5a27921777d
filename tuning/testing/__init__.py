"""``lgw.testing``: property-based verification of a gain set inside a user's own test suite.

Installed with the package; needs Hypothesis (``pip install "lgw[verify]"``).

* ``lgw.testing.mars``: Hypothesis strategies for seed 000's gain sets and initial states, and
  property helpers (``check_bounds``, ``check_landing_within_bound``) that return the same
  records ``lgw verify mars`` prints (``lgw.tuning.verifying.ClaimResult``);
* ``lgw.testing.lunar`` and ``lgw.testing.eros``: the same for seed 001 (orbit-loop gains,
  initial errors of the general system (5)) and seed 002 (FTSMC gains, initial offsets);
* ``lgw.testing.engine``: the Hypothesis driver of every ``lgw verify SYSTEM``;
* ``lgw.testing.plugin``: a pytest plugin (entry point ``pytest11``: ``lgw``) with the marker
  ``@pytest.mark.lgw_gains(path, system="mars" | "lunar" | "eros")`` and the fixtures
  ``lgw_claim`` (one test per claim: pass, skip when not applicable, one clean failure) and
  ``lgw_verify`` (the whole file); see docs/verify.md for the ten-line test file.
"""

SYSTEMS = ("mars", "lunar", "eros")


def checker(system: str):
    """``check_bounds(gains=None, *, claims=None, **options)`` of ``system``: run ``lgw verify
    SYSTEM``'s checks on a gain set (an object of the system, a TOML path, or None for the
    built-in one) and return the ``lgw.tuning.verifying.ClaimResult`` records it prints;
    ``claims`` restricts them, ``options`` as ``lgw.tuning.verifying.run_checks``."""

    def check_bounds(gains=None, *, claims=None, **options) -> list:
        from lgw.tuning.verifying import run_checks

        return run_checks(system, gains, **({"claim": claims} if claims else {}), **options)

    check_bounds.__doc__ = (
        f"Run ``lgw verify {system}``'s checks on a gain set (an object of the system, a TOML "
        "path, or None for the built-in one) and return the ``lgw.tuning.verifying."
        "ClaimResult`` records it prints; ``claims`` restricts them, ``options`` as "
        "``lgw.tuning.verifying.run_checks``.")
    return check_bounds
