"""Floor 3: the ``lgw`` command line, gain design and certificates."""
