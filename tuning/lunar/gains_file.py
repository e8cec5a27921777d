"""Write a tuned seed 001 design as TOML: [orbit], [attitude], [command_filter], [vehicle] and
[certificate] (read back by ``lgw.theory.lunar.gains.load``, which every verb uses)."""

from __future__ import annotations

import json
from typing import Any

from lgw.theory.lunar.gains import Gains


def _value(v: Any) -> str:
    """A TOML value (numbers, booleans, strings, flat lists) by JSON, which spells them the
    same way for these types; None is left out by the caller."""
    return json.dumps(v, allow_nan=False)


def gains_file_text(g: Gains, cert: dict[str, Any], header: str = "lgw tune lunar: seed 001 "
                    "design (gains, command filter, thrust limit) with its certificate") -> str:
    lines = [f"# {header}"]
    d = g.to_dict()
    for table in ("orbit", "attitude", "command_filter", "vehicle"):
        if table not in d:
            continue
        lines.append(f"[{table}]")
        lines += [f"{k} = {_value(v)}" for k, v in d[table].items()]
        lines.append("")
    lines.append("[certificate]")
    lines += [f"{k} = {_value(v)}" for k, v in cert.items() if v is not None]
    return "\n".join(lines) + "\n"
