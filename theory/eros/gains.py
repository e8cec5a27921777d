"""The gain set of seed 002's three controllers: parse and validate (TOML table [gains]).

Valid ranges are the hypotheses the derivations use:
  alpha, beta, lam > 0             surfaces (5), (6) and the PD surface
  p, q integers, 0 < p < q         seed 002 after (5) (the exponent p/q lies in (0, 1))
  k > 0                            switching gain of (18)
  N, M > 0                         fuzzy weights (22)
  phi > 0                          boundary layer of tanh(s/phi)
  e_floor > 0                      floor of |e| in |e|^(p/q - 1) (claim singular-term); an
                                   implementation parameter, not a gain of the paper: optional,
                                   default parameters.DEFAULT_GAINS["e_floor"] (docs/eros.md)
Parsing never evaluates user text: values must already be TOML numbers.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from lgw.theory.errors import ParameterError
from lgw.theory.inputs import load_toml

KEYS = ("alpha", "beta", "p", "q", "k", "lam", "N", "M", "phi", "e_floor")
_RANGES = {
    "alpha": "must be > 0 (1/s)", "beta": "must be > 0 (m^(1-p/q)/s)",
    "p": "must be an integer with 0 < p < q", "q": "must be an integer with q > p > 0",
    "k": "must be > 0 (m/s^2)", "lam": "must be > 0 (1/s)", "N": "must be > 0 (s/m)",
    "M": "must be > 0 (s/m)", "phi": "must be > 0 (m/s)", "e_floor": "must be > 0 (m)",
}


@dataclass(frozen=True)
class Gains:
    """Gains of seed 002's PD-SMC, FTSMC (19) and fuzzy FTSMC (20)-(22), the same on x, y, z."""

    alpha: float
    beta: float
    p: int
    q: int
    k: float
    lam: float
    N: float
    M: float
    phi: float
    e_floor: float

    @property
    def r(self) -> float:
        return self.p / self.q

    def to_dict(self) -> dict[str, Any]:
        return {"gains": asdict(self)}

    def replace(self, **kw: Any) -> Gains:
        d = asdict(self)
        d.update(kw)
        return gains_from_dict({"gains": d})


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(name, value, "must be a number; " + _RANGES[name])
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(name, value, "must be finite; " + _RANGES[name])
    return x


OPTIONAL = ("e_floor",)  # keys with a documented default (parameters.DEFAULT_GAINS)


def gains_from_dict(data: dict[str, Any]) -> Gains:
    """Validate a parsed gains document (table [gains]); every key but ``OPTIONAL`` required,
    none unknown."""
    g = data.get("gains")
    if not isinstance(g, dict):
        raise ParameterError("gains", g, "missing table [gains]")
    for key in g:
        if key not in KEYS:
            raise ParameterError(f"gains.{key}", g[key], f"unknown key; valid keys are "
                                 f"{', '.join(KEYS)}")
    if any(k not in g for k in OPTIONAL):
        from lgw.theory.eros.parameters import DEFAULT_GAINS

        g = {**{k: DEFAULT_GAINS[k] for k in OPTIONAL}, **g}
    for key in KEYS:
        if key not in g:
            raise ParameterError(f"gains.{key}", None, "missing; " + _RANGES[key])
    vals: dict[str, Any] = {}
    for key in KEYS:
        x = _number(key, g[key])
        if key in ("p", "q"):
            if x != int(x):
                raise ParameterError(key, g[key], _RANGES[key])
            x = int(x)
        if not x > 0:
            raise ParameterError(key, g[key], _RANGES[key])
        vals[key] = x
    if not vals["p"] < vals["q"]:
        raise ParameterError("p", vals["p"], f"must be < q = {vals['q']} (p/q in (0, 1))")
    return Gains(**vals)


def load_gains(path: str | Path) -> Gains:
    """Read and validate a gains TOML file (``lgw.theory.inputs``)."""
    return gains_from_dict(load_toml(path, "--gains"))


def default_gains() -> Gains:
    """The documented defaults (lgw.theory.eros.parameters.DEFAULT_GAINS)."""
    from lgw.theory.eros.parameters import DEFAULT_GAINS

    return gains_from_dict({"gains": dict(DEFAULT_GAINS)})


def gains_to_toml(g: Gains, header: str = "") -> str:
    lines = [f"# {ln}" for ln in header.splitlines()] if header else []
    lines.append("[gains]")
    lines += [f"{k} = {v!r}" for k, v in asdict(g).items()]
    return "\n".join(lines) + "\n"
