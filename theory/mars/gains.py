"""The gain set of seed 000's guidance (25) and its disturbance parameters: parse and validate.

The valid ranges are the hypotheses of the theorems they feed:
  beta1, beta2 > 0, 0 < q1 < 1 < q2        seed 000, reaching law (16) / Theorem 2
  alpha1, alpha2 > 0, 0 < g1 < 1 < g2      seed 000, guidance (25) / Theorem 3
  a_max > 0, 0 < theta1, theta2 < 1        seed 000, Hypothesis 1 / Theorem 4
Per-axis gains are a number (the same on x, y, z) or a list of three; exponents are scalars, as in
the paper.  Parsing never evaluates user text: values must already be TOML numbers.

Beyond the hypotheses, the closed forms must be evaluable in double precision:
  q1, g1 <= 1 - EXP_GAP and q2, g2 >= 1 + EXP_GAP: the bounds grow like 1/(1 - q1) and
    1/(q2 - 1), and the exponent is known to 1e-16 absolute, so within EXP_GAP = 1e-9 of 1 the
    bound would carry fewer than 7 correct digits (and one ulp from 1 the Lemma 2 route (18)/(26),
    p = (q1 + 1)/2, rounds to exactly 1);
  q2, g2 <= EXP_MAX = 2046: the route evaluates 2^((q2 + 1)/2), which overflows a double for
    q2 >= 2047;
  every bound of ``lgw.theory.mars.bounds.axis_bounds`` finite (< 1.8e308): checked by
    ``lgw.theory.mars.bounds.check_evaluable``, which names the gains of the surface at fault
    (e.g. beta1 = 1e-308 makes T1 ~ 1/beta1 overflow).
Files are UTF-8 text (a UTF-8 byte-order mark is accepted); binary files, other encodings,
duplicate keys and integers too large for a double are named errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.inputs import load_toml, parse_toml_bytes

AXIS_GAINS = ("beta1", "beta2", "alpha1", "alpha2")
EXPONENTS = ("q1", "q2", "g1", "g2")
DISTURBANCE_KEYS = ("a_max", "theta1", "theta2")
EXP_GAP = 1e-9  # closest an exponent may come to 1 (see the module docstring)
EXP_MAX = 2046.0  # largest q2, g2: 2^((q2 + 1)/2) overflows a double from q2 = 2047
_LOW = f"must lie in (0, {1 - EXP_GAP!r}] (0 < q < 1, at least {EXP_GAP:g} from 1)"
_HIGH = f"must lie in [{1 + EXP_GAP!r}, {EXP_MAX:g}] (q > 1, at least {EXP_GAP:g} from 1)"
_RANGES = {
    "beta1": "must be > 0 (a number or a list of three)",
    "beta2": "must be > 0 (a number or a list of three)",
    "alpha1": "must be > 0 (a number or a list of three)",
    "alpha2": "must be > 0 (a number or a list of three)",
    "q1": _LOW,
    "g1": _LOW,
    "q2": _HIGH,
    "g2": _HIGH,
    "a_max": "must be > 0 (m/s^2, per-axis bound on the disturbance)",
    "theta1": "must lie in (0, 1)",
    "theta2": "must lie in (0, 1)",
}


@dataclass(frozen=True)
class Disturbance:
    """Hypothesis 1 of seed 000 with the Theorem 4 splitting constants.

    Departure from the paper: Hypothesis 1 bounds the norm |a_p| <= a_max, but the per-axis
    derivation (37)-(44) only uses |a_p,i| <= a_max, and the paper's own test (47),
    a_p,i = 20 sin t on every axis, satisfies the per-axis bound with a_max = 20 but not the norm
    bound.  The workbench reads a_max as the per-axis bound (the weaker hypothesis).
    """

    a_max: float
    theta1: float
    theta2: float


@dataclass(frozen=True)
class Gains:
    """Gains of seed 000's surfaces (15), (21), reaching law (16) and guidance (25)."""

    beta1: np.ndarray
    beta2: np.ndarray
    alpha1: np.ndarray
    alpha2: np.ndarray
    q1: float
    q2: float
    g1: float
    g2: float
    disturbance: Disturbance | None = None
    extra: dict[str, Any] = field(default_factory=dict, compare=False)

    def axis(self, i: int) -> dict[str, float]:
        """The scalar gains of axis i (0, 1, 2)."""
        return {
            "beta1": float(self.beta1[i]),
            "beta2": float(self.beta2[i]),
            "alpha1": float(self.alpha1[i]),
            "alpha2": float(self.alpha2[i]),
            "q1": self.q1,
            "q2": self.q2,
            "g1": self.g1,
            "g2": self.g2,
        }

    def to_dict(self) -> dict[str, Any]:
        gains: dict[str, Any] = {k: [float(x) for x in getattr(self, k)] for k in AXIS_GAINS}
        gains.update({k: float(getattr(self, k)) for k in EXPONENTS})
        out: dict[str, Any] = {"gains": gains}
        if self.disturbance is not None:
            d = self.disturbance
            out["disturbance"] = {"a_max": d.a_max, "theta1": d.theta1, "theta2": d.theta2}
        return out

    def with_disturbance(self, d: Disturbance | None) -> Gains:
        """The same gain set (``extra`` tables included) with disturbance ``d``."""
        return replace(self, disturbance=d)


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(name, value, "must be a number; " + _RANGES[name])
    try:
        x = float(value)
    except OverflowError:  # a TOML integer beyond the double range
        raise ParameterError(name, value, "is too large for a double; " + _RANGES[name]) \
            from None
    if not math.isfinite(x):
        raise ParameterError(name, value, "must be finite; " + _RANGES[name])
    return x


def _check_range(name: str, x: float) -> None:
    ok = {
        "q1": 0.0 < x <= 1.0 - EXP_GAP, "g1": 0.0 < x <= 1.0 - EXP_GAP,
        "q2": 1.0 + EXP_GAP <= x <= EXP_MAX, "g2": 1.0 + EXP_GAP <= x <= EXP_MAX,
        "theta1": 0.0 < x < 1.0, "theta2": 0.0 < x < 1.0,
    }.get(name, x > 0.0)
    if not ok:
        raise ParameterError(name, x, _RANGES[name])


def _axis_value(name: str, value: Any) -> np.ndarray:
    if isinstance(value, list):
        if len(value) != 3:
            raise ParameterError(name, value, "a list must hold exactly three values (x, y, z)")
        arr = np.array([_number(name, v) for v in value])
    else:
        arr = np.full(3, _number(name, value))
    for x in arr:
        _check_range(name, float(x))
    return arr


def _check_keys(section: str, table: dict[str, Any], allowed: tuple[str, ...],
                required: tuple[str, ...]) -> None:
    for key in table:
        if key not in allowed:
            raise ParameterError(f"{section}.{key}", table[key],
                                 f"unknown key; valid keys are {', '.join(allowed)}")
    for key in required:
        if key not in table:
            raise ParameterError(f"{section}.{key}", None, "missing; " + _RANGES[key])


def gains_from_dict(data: dict[str, Any]) -> Gains:
    """Validate a parsed gains document (the TOML tables [gains] and optional [disturbance]).

    Other top-level tables (e.g. a tuner's [certificate]) are kept in ``extra`` untouched.
    """
    if "gains" not in data or not isinstance(data["gains"], dict):
        raise ParameterError("gains", None, "missing table [gains]")
    g = data["gains"]
    keys = AXIS_GAINS + EXPONENTS
    _check_keys("gains", g, keys, keys)
    vals: dict[str, Any] = {k: _axis_value(k, g[k]) for k in AXIS_GAINS}
    for k in EXPONENTS:
        x = _number(k, g[k])
        _check_range(k, x)
        vals[k] = x
    dist = None
    if "disturbance" in data:
        d = data["disturbance"]
        if not isinstance(d, dict):
            raise ParameterError("disturbance", d, "must be a table [disturbance]")
        _check_keys("disturbance", d, DISTURBANCE_KEYS, DISTURBANCE_KEYS)
        dv = {k: _number(k, d[k]) for k in DISTURBANCE_KEYS}
        for k, x in dv.items():
            _check_range(k, x)
        dist = Disturbance(**dv)
    extra = {k: v for k, v in data.items() if k not in ("gains", "disturbance")}
    out = Gains(disturbance=dist, extra=extra, **vals)
    from lgw.theory.mars.bounds import check_evaluable  # bounds imports this module

    check_evaluable(out)
    return out


def load_gains(path: str | Path) -> Gains:
    """Read and validate a gains TOML file (``lgw.theory.inputs``: regular files only, size
    cap, UTF-8, nesting and number ranges)."""
    return gains_from_dict(load_toml(path, "--gains"))


def gains_from_toml_text(text: str) -> Gains:
    return gains_from_dict(parse_toml_bytes(text.encode("utf-8"), "gains", "<text>"))


def default_gains() -> Gains:
    """The documented default gain set (lgw.theory.mars.parameters.DEFAULT_GAINS)."""
    from lgw.theory.mars.parameters import DEFAULT_GAINS

    return gains_from_dict(DEFAULT_GAINS)


def gains_to_toml(g: Gains, header: str = "") -> str:
    """Write the [gains] and [disturbance] tables (and a header comment) as TOML text."""
    lines = [f"# {ln}" for ln in header.splitlines()] if header else []
    d = g.to_dict()
    for table, values in d.items():
        lines.append(f"[{table}]")
        for k, val in values.items():
            if isinstance(val, list):
                val = val[0] if len(set(val)) == 1 else "[" + ", ".join(repr(x) for x in val) + "]"
            lines.append(f"{k} = {val!r}" if not isinstance(val, str) else f"{k} = {val}")
        lines.append("")
    return "\n".join(lines)
