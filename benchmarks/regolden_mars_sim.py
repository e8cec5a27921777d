"""Re-make the `lgw simulate mars` golden files (tests/mars/golden/sim_*.json) after a
deliberate change, checking first that every pre-existing value is unchanged (1e-12 relative,
as tests/mars/test_golden.py) and listing the keys that were added.

Run from the repository root: ``python benchmarks/regolden_mars_sim.py`` (check only) or
``python benchmarks/regolden_mars_sim.py --write``.
"""

from __future__ import annotations

import json
import math
import re
import sys
from pathlib import Path

from click.testing import CliRunner
from lgw.tuning.cli import cli

GOLDEN = Path("tests/mars/golden")
CASES = [
    ("sim_t2_300.json", ["--dispersion", "table2", "--cases", "300", "--seed", "7"]),
    ("sim_t2_300_dopri5.json", ["--dispersion", "table2", "--cases", "300", "--seed", "7",
                                "--method", "dopri5"]),
    ("sim_t3_100_sin.json", ["--dispersion", "table3", "--cases", "100", "--seed", "3",
                             "--thrust-max", "50000", "--disturbance", "sin"]),
]


def contained(old, new, added: set[str], path: str = "") -> int:
    """Assert every value of ``old`` is in ``new`` unchanged; collect new keys; count leaves."""
    if isinstance(old, dict):
        for k in new:
            if k not in old:
                added.add(re.sub(r"\[\d+\]", "[]", f"{path}.{k}"))
        return sum(contained(old[k], new[k], added, f"{path}.{k}") for k in old)
    if isinstance(old, list):
        assert len(old) == len(new), path
        return sum(contained(a, b, added, f"{path}[{i}]")
                   for i, (a, b) in enumerate(zip(old, new, strict=True)))
    if isinstance(old, float) and isinstance(new, float):
        assert math.isclose(old, new, rel_tol=1e-12, abs_tol=1e-300), (path, old, new)
    else:
        assert old == new, (path, old, new)
    return 1


def main() -> None:
    added: set[str] = set()
    for name, args in CASES:
        res = CliRunner().invoke(cli, ["simulate", "mars", *args, "--json"],
                                 catch_exceptions=False)
        assert res.exit_code == 0, res.output
        n = contained(json.loads((GOLDEN / name).read_text()), json.loads(res.output), added)
        print(f"{name}: {n} pre-existing values unchanged")
        if "--write" in sys.argv:
            (GOLDEN / name).write_text(res.output)
    print("added keys:", ", ".join(sorted(added)) or "none")


if __name__ == "__main__":
    main()
