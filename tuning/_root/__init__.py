"""lgw, the landing-guidance workbench: derive, check, simulate and tune Lyapunov landing laws.

The distribution installs one import package, ``lgw``, whose floors live in the repository's
top-level folders (``pyproject.toml`` maps them): ``lgw.theory`` (``theory/``: SymPy laws,
Lyapunov derivatives, bounds, claims with evidence, reports), ``lgw.sim`` (``sim/``:
integrators, generated laws, plants, campaigns) and ``lgw.tuning`` (``tuning/``: gain design,
certificates, property checks and the ``lgw`` command line).  Each floor holds its shared
machinery at its root and one subpackage per system: ``mars`` (seed 000), ``lunar`` (seed 001),
``eros`` (seed 002).  This file is ``tuning/_root/__init__.py`` in the repository.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("lgw")
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"

SYSTEMS = ("mars", "lunar", "eros")

__all__ = ["SYSTEMS", "__version__"]
