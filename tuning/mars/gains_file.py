"""Write a tuned gain set with its [certificate] table (TOML).

The [gains] / [disturbance] tables come from ``lgw.theory.mars.gains.gains_to_toml``, so every
command
that reads gains (``lgw.theory.mars.gains.load_gains``) reads a tuned file unchanged; the
[certificate]
table is kept in ``Gains.extra`` by the loader and ignored by the bounds and the simulator.

The certificate records what was proven (every bound of ``lgw.theory.mars.bounds.axis_bounds``),
what was only simulated (worst-case peak thrust and the state attaining it, fuel, landing
error under a_max, ground clearance), how (solver, status, search counts) and with what
(versions of lgw, numpy, cvxpy, sympy, clarabel, numba).
"""

from __future__ import annotations

import json
import math
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np
from lgw.theory.errors import ParameterError
from lgw.theory.mars.bounds import axis_bounds
from lgw.theory.mars.gains import Gains, gains_to_toml, load_gains
from lgw.theory.mars.parameters import AXES, M_DRY
from lgw.tuning.io import atomic_write_text
from lgw.tuning.mars.design import (
    REFINE_FACTORS,
    REFINE_RTOL,
    SOLVER,
    Envelope,
    Request,
    TuneResult,
)

VERSION_PACKAGES = ("lgw", "numpy", "cvxpy", "sympy", "clarabel", "numba", "scipy")


def versions() -> dict[str, str]:
    out = {}
    for p in VERSION_PACKAGES:
        try:
            out[p] = metadata.version(p)
        except metadata.PackageNotFoundError:
            out[p] = "not installed"
    return out


def _value(x: Any) -> str:
    if isinstance(x, bool | np.bool_):
        return "true" if x else "false"
    if isinstance(x, int | np.integer):
        return str(int(x))
    if isinstance(x, float | np.floating):
        x = float(x)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(x, str):
        return json.dumps(x)  # a TOML basic string: JSON escapes are valid TOML escapes
    if isinstance(x, list | tuple | np.ndarray):
        return "[" + ", ".join(_value(y) for y in x) + "]"
    raise TypeError(f"cannot write {type(x).__name__} to TOML")


def toml_tables(name: str, table: dict[str, Any]) -> list[str]:
    """A nested dict as TOML: scalars first, then sub-tables [name.key]."""
    lines = [f"[{name}]"]
    subs = []
    for k, v in table.items():
        if v is None:  # TOML has no null: an absent key means "not given"
            continue
        if isinstance(v, dict):
            subs.append((k, v))
        else:
            lines.append(f"{k} = {_value(v)}")
    lines.append("")
    for k, v in subs:
        lines += toml_tables(f"{name}.{k}", v)
    return lines


def _state(x: np.ndarray) -> dict[str, Any]:
    return {"r0": [float(y) for y in x[:3]], "v0": [float(y) for y in x[3:6]],
            "m0": float(x[6])}


def certificate(res: TuneResult, req: Request, env: Envelope, command: str = "") -> dict:
    """The [certificate] table of a tuning result (feasible or not)."""
    cert: dict[str, Any] = {
        "tool": "lgw tune mars",
        "command": command,
        "created_utc": datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "feasible": res.feasible,
        "reason": res.reason,
        "law": "corrected",
        "solver": SOLVER,
        "solver_status": res.gp.status if res.gp is not None else "none",
        "gp_objective": float(res.gp.value) if res.gp is not None else float("nan"),
        "tune_seconds": round(res.elapsed, 2),
        "gp_time_budget": res.info.get("gp_time_budget"),
    }
    cert["request"] = {
        "tf": req.tf, "thrust_max": req.thrust_max, "limit": req.limit, "bound": req.bound,
        "objective": req.objective, "a_max": req.a_max, "neighborhood": req.neighborhood,
        "theta1": req.theta1, "theta2": req.theta2, "accept_peak_fraction": req.margin,
    }
    env_d = env.to_dict()
    whole = res.forced_fraction == 0.0 and env.singular_state() is None
    env_d.update(excluded_fraction=res.excluded_fraction, forced_overshoot_fraction=
                 res.forced_fraction, whole_box_certifiable=whole,
                 tf_min_remark1=res.tf_min_envelope,
                 tf_min_state=_state(res.tf_min_state), tf_min_a_max=req.thrust_max / M_DRY)
    cert["envelope"] = env_d
    if res.gains is not None:
        b = axis_bounds(res.gains)
        cert["bounds"] = {ax: b[ax] for ax in AXES}
        key = "landing_time_bound" if req.bound == "exact" else "landing_time_bound_polyakov"
        cert["landing_time_bound"] = max(b[ax][key] for ax in AXES)
        if req.disturbance is not None:
            cert["landing_time_bound_disturbed"] = max(
                b[ax]["landing_time_bound_disturbed"] for ax in AXES)
            cert["s1_bound"] = [b[ax]["s1_bound"] for ax in AXES]
    ev = res.evaluation
    if ev is not None:
        cert["worst_case"] = {
            "method": "lgw.sim.mars.batch.simulate_batch: extreme states, compass search, "
                      "Monte Carlo",
            "dt": ev.dt,
            "refinement": (f"cases over the limit at dt re-flown at dt/{REFINE_FACTORS[0]} and "
                           f"dt/{REFINE_FACTORS[1]}; replaced where both agree within "
                           f"{REFINE_RTOL:.0%} under the limit "
                           "(lgw.tuning.mars.design.refine_over_limit)"),
            "spikes_removed": ev.spikes_removed,
            "states": res.search_counts,
            "peak_thrust_axis": [float(x) for x in ev.peak_axis],
            "peak_thrust_norm": ev.peak_norm,
            "peak_thrust": ev.worst_value,
            "peak_fraction_of_limit": ev.worst_value / req.thrust_max,
            "worst_state": _state(ev.worst_state),
            "saturated_cases": ev.saturated,
            "nonfinite_cases": ev.nonfinite,
            "all_landed": ev.all_landed,
            "max_landing_time": ev.max_landing_time,
            "min_altitude": ev.min_altitude,
            "below_ground_cases": ev.ground_contact,
            "below_ground_cases_strict": ev.ground_contact_strict,
        }
        cert["fuel"] = {"max": ev.fuel_max, "mean": ev.fuel_mean,
                        "over": "Monte Carlo states of the envelope at their own masses"}
        if req.disturbance is not None:
            cert["disturbed"] = {
                "disturbance": "worst (a_p,i = -a_max sgn(s2_i))", "a_max": req.a_max,
                "landing_error_max_axis": [float(x) for x in ev.r_end_max],
                "landing_error_bound_s1": cert.get("s1_bound", []),
            }
    if res.suggestion is not None:
        cert["nearest_feasible_tf"] = res.suggestion
    cert["versions"] = versions()
    return cert


def check_certificate(g: Gains, shown: str, name: str = "--tuned") -> Gains:
    """Validate the [certificate] table of a tuned gains file as far as the commands read it
    (a table; its request.tf, if given, a finite number > 0 s); the [gains] tables were
    validated by ``load_gains``."""
    cert = g.extra.get("certificate")
    if cert is None:
        return g
    if not isinstance(cert, dict):
        raise ParameterError(name, shown, "its [certificate] must be a table")
    req = cert.get("request", {})
    if not isinstance(req, dict):
        raise ParameterError(name, shown, "its [certificate.request] must be a table")
    tf = req.get("tf")
    if tf is not None and (isinstance(tf, bool) or not isinstance(tf, int | float)
                           or not math.isfinite(float(tf)) or not float(tf) > 0):
        raise ParameterError(f"{name} {shown} certificate.request.tf", tf,
                             "must be a finite number > 0 (s)")
    return g


def load_tuned(path: str | Path, name: str = "--tuned") -> Gains:
    """A tuned gains file (``lgw tune`` output): its gains and its certificate, validated."""
    return check_certificate(load_gains(path), str(path), name)


def gains_file_text(gains: Gains, cert: dict[str, Any], header: str = "") -> str:
    """The tuned file: [gains], [disturbance] and [certificate]."""
    text = gains_to_toml(gains, header=header).rstrip("\n") + "\n\n"
    return text + "\n".join(toml_tables("certificate", cert)).rstrip("\n") + "\n"


def bounded_gains_file_text(bg: Any, cert: dict[str, Any], header: str) -> str:
    """A bounded-law tuned file: [gains] (seed 000's table, required by the loader, unused by
    the bounded laws), [bounded] (or [bounded-sat]) and [certificate]."""
    from lgw.theory.mars.gains import default_gains
    from lgw.tuning.mars.design_bounded import _plain, _table, law_of

    text = gains_to_toml(default_gains(), header=header).rstrip("\n") + "\n\n"
    text += "\n".join(toml_tables(_table(law_of(bg)), bg.to_dict())).rstrip("\n") + "\n\n"
    return text + "\n".join(toml_tables("certificate", _plain(cert))).rstrip("\n") + "\n"


def write_gains(path: str | Path, gains: Gains, cert: dict[str, Any], header: str = "") -> None:
    """Write [gains], [disturbance] and [certificate] (atomically: temp file, then rename)."""
    atomic_write_text(Path(path), gains_file_text(gains, cert, header))
