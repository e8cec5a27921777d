"""lgw.tuning, floor 3: gain design, certificates, property checks and the ``lgw`` command line.

Sits on ``lgw.theory`` and ``lgw.sim``.  Shared machinery at this root (the CLI shell, options);
one subpackage per system (``mars``, ``lunar``, ``eros``) with its design problem and commands.
"""

if __name__ != "lgw.tuning":  # the folder tuning/ is installed as lgw.tuning only
    raise ImportError("this folder is the package lgw.tuning: import lgw.tuning, not "
                      f"{__name__}")
