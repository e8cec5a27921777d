"""Gains of seed 001's adaptive backstepping law (7)-(11), per loop (orbit, attitude): parse and
validate.

The valid ranges are the hypotheses the derivation of (13) and (17) needs (seed 001 Section 3):
  F2 symmetric positive definite with minimum eigenvalue f2bar > 1/2     (13), (17b)
  0 < f3 < f2bar                                                          (13)
  q > 0                                                                   (8), (12)
  d0e(0) >= 0 (keeps d0e >= 0, needed for the remainder sign of (13))    (8)
  K1 making F1 = f1 K1 f1^T positive definite:                            (10)
    orbit, f1 = a_h = [0, 0, -1]:  F1 = K1_zz > 0
    attitude, f1 = (eq0 I + S(eq))/2: F1 is positive definite at every eq0 != 0 exactly when
    the symmetric part of K1 is positive definite (f1 is then nonsingular); at eq0 = 0 F1 is
    singular whatever K1 (claim attitude-F1).
A matrix gain is a list of 3 numbers (the diagonal) or a 3x3 nested list.  Parsing never
evaluates user text: values must already be TOML numbers.

Optional tables a tuned file carries (``lgw tune lunar``), kept in ``Gains.extra``:
  [command_filter] wn     natural frequency of the desired-attitude command filter, rad/s, > 0
  [vehicle] thrust_max    the orbit-thrust limit T_max of (24) the design was sized for, N, > 0
  [certificate]           what the tuner promises and how it knows (validated by name in
                          ``lgw.tuning.lunar.design``); kept untouched here.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.inputs import load_toml
from lgw.theory.lunar.parameters import ATTITUDE_GAINS, ORBIT_GAINS

LOOPS = ("orbit", "attitude")
KEYS = ("K1", "F2", "f3", "d0e0", "q")
# optional tables: name -> {key: (lo, hi) open below, closed above}
DESIGN_TABLES = {"command_filter": {"wn": (0.0, 1e3)}, "vehicle": {"thrust_max": (0.0, 1e9)}}
EXTRA_TABLES = (*DESIGN_TABLES, "certificate")
A_H = np.array([[0.0, 0.0, -1.0]])  # f1 of the orbit loop, seed 001 (22a)


@dataclass(frozen=True)
class LoopGains:
    """K1 (3x3), F2 (3x3), f3 (= f3bar of (7), (13)), d0e0 (= d0e(0)), q of (8)."""

    K1: np.ndarray
    F2: np.ndarray
    f3: float
    d0e0: float
    q: float

    @property
    def f2bar(self) -> float:
        """Minimum eigenvalue of F2 (seed 001, below (7))."""
        return float(np.linalg.eigvalsh(0.5 * (self.F2 + self.F2.T)).min())

    def to_dict(self) -> dict[str, Any]:
        return {"K1": self.K1.tolist(), "F2": self.F2.tolist(), "f3": self.f3,
                "d0e0": self.d0e0, "q": self.q}


@dataclass(frozen=True)
class Gains:
    orbit: LoopGains
    attitude: LoopGains
    extra: dict = field(default_factory=dict, compare=False)  # optional tables (docstring)

    def to_dict(self) -> dict[str, Any]:
        d = {"orbit": self.orbit.to_dict(), "attitude": self.attitude.to_dict()}
        d.update({k: dict(v) for k, v in self.extra.items() if k in DESIGN_TABLES})
        return d


def _num(name: str, x: Any) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float) or not np.isfinite(x):
        raise ParameterError(name, x, "must be a finite number")
    return float(x)


def _matrix(name: str, x: Any) -> np.ndarray:
    if isinstance(x, list) and len(x) == 3 and all(not isinstance(r, list) for r in x):
        return np.diag([_num(f"{name}[{i}]", v) for i, v in enumerate(x)])
    if (isinstance(x, list) and len(x) == 3 and all(isinstance(r, list) and len(r) == 3
                                                     for r in x)):
        return np.array([[_num(f"{name}[{i}][{j}]", v) for j, v in enumerate(r)]
                         for i, r in enumerate(x)])
    raise ParameterError(name, x, "must be a list of 3 numbers (diagonal) or a 3x3 nested list")


def make_loop(loop: str, d: dict[str, Any]) -> LoopGains:
    """Validate one loop's gains (see the module docstring for each range)."""
    unknown = set(d) - set(KEYS)
    if unknown:
        k = sorted(unknown)[0]
        raise ParameterError(f"{loop}.{k}", d[k], f"unknown key; valid keys: {', '.join(KEYS)}")
    for k in KEYS:
        if k not in d:
            raise ParameterError(f"{loop}.{k}", None, "missing")
    K1 = _matrix(f"{loop}.K1", d["K1"])
    F2 = _matrix(f"{loop}.F2", d["F2"])
    f3, d0e0, q = (_num(f"{loop}.{k}", d[k]) for k in ("f3", "d0e0", "q"))
    if not np.allclose(F2, F2.T, rtol=0, atol=1e-12):
        raise ParameterError(f"{loop}.F2", F2.tolist(), "must be symmetric (seed 001 (7))")
    f2bar = float(np.linalg.eigvalsh(F2).min())
    if not f2bar > 0.5:
        raise ParameterError(f"{loop}.F2", F2.tolist(), "must be positive definite with minimum "
                             f"eigenvalue > 1/2 (seed 001 (7), (17b)); it is {f2bar:.6g}")
    if not 0.0 < f3 < f2bar:
        raise ParameterError(f"{loop}.f3", f3, f"must lie in (0, f2bar) = (0, {f2bar:.6g}) "
                             "(seed 001 (7), (13))")
    if not q > 0:
        raise ParameterError(f"{loop}.q", q, "must be > 0 (seed 001 (8))")
    if not d0e0 >= 0:
        raise ParameterError(f"{loop}.d0e0", d0e0, "must be >= 0 (keeps d0e >= 0 under (8), "
                             "needed for the sign of the remainder in (13))")
    if loop == "orbit":
        f1bar = float((A_H @ K1 @ A_H.T)[0, 0])
        if not f1bar > 0:
            raise ParameterError("orbit.K1", K1.tolist(), "must make F1 = a_h K1 a_h^T = K1_zz "
                                 f"> 0 (seed 001 (10)); it is {f1bar:.6g}")
    else:
        k1min = float(np.linalg.eigvalsh(0.5 * (K1 + K1.T)).min())
        if not k1min > 0:
            raise ParameterError("attitude.K1", K1.tolist(), "must have a positive definite "
                                 "symmetric part, else F1 = f1 K1 f1^T is singular or "
                                 f"indefinite (seed 001 (10)); its minimum eigenvalue is "
                                 f"{k1min:.6g}")
    return LoopGains(K1, F2, f3, d0e0, q)


def paper_gains() -> Gains:
    """Seed 001 Section 5's gains."""
    return Gains(make_loop("orbit", dict(ORBIT_GAINS)),
                 make_loop("attitude", dict(ATTITUDE_GAINS)))


def default_gains() -> Gains:
    """The built-in gain set: seed 001 Section 5's (``paper_gains``)."""
    return paper_gains()


def from_dict(d: dict[str, Any]) -> Gains:
    """Gains from a mapping {"orbit": {...}, "attitude": {...}}; a missing loop takes the
    paper's values, a given loop must be complete."""
    unknown = set(d) - set(LOOPS) - set(EXTRA_TABLES)
    if unknown:
        k = sorted(unknown)[0]
        raise ParameterError(k, d[k], "unknown table; valid tables: [orbit], [attitude] and "
                             "the optional " + ", ".join(f"[{t}]" for t in EXTRA_TABLES))
    defaults = {"orbit": ORBIT_GAINS, "attitude": ATTITUDE_GAINS}
    loops = {}
    for loop in LOOPS:
        t = d.get(loop, defaults[loop])
        if not isinstance(t, dict):
            raise ParameterError(loop, t, "must be a TOML table")
        loops[loop] = make_loop(loop, dict(t))
    extra = {}
    for name, keys in DESIGN_TABLES.items():
        if name in d:
            extra[name] = _design_table(name, d[name], keys)
    if "certificate" in d:
        if not isinstance(d["certificate"], dict):
            raise ParameterError("certificate", d["certificate"], "must be a TOML table")
        extra["certificate"] = d["certificate"]
    return Gains(**loops, extra=extra)


def _design_table(name: str, t: Any, keys: dict[str, tuple[float, float]]) -> dict[str, float]:
    if not isinstance(t, dict):
        raise ParameterError(name, t, "must be a TOML table")
    for k in t:
        if k not in keys:
            raise ParameterError(f"{name}.{k}", t[k], f"unknown key; valid keys: "
                                 f"{', '.join(keys)}")
    out = {}
    for k, (lo, hi) in keys.items():
        if k not in t:
            raise ParameterError(f"{name}.{k}", None, "missing")
        v = _num(f"{name}.{k}", t[k])
        if not lo < v <= hi:
            raise ParameterError(f"{name}.{k}", v, f"must lie in ({lo:g}, {hi:g}]")
        out[k] = v
    return out


def load(path: Path) -> Gains:
    """Gains from a TOML file with tables [orbit] and [attitude] (``lgw.theory.inputs``)."""
    return from_dict(load_toml(path, "--gains"))
