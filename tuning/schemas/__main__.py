"""``python -m lgw.tuning.schemas --write docs/json.md`` (or ``--check``)."""

import sys

from lgw.tuning.schemas import main

sys.exit(main())
