"""Seed 002's claims as ``lgw verify eros`` checks them (the shared machinery:
``lgw.tuning.verifying``).

The law under check is the FTSMC (19) with sign switching, sampled at dt = 0.01 s with a
zero-order hold (``lgw.sim.eros.batch.simulate``: the paper's loop).  Per case and axis the
bounds are those of ``lgw.theory.eros.bounds.axis_time_bound`` at the case's own e0, e0':

  reaching-known    (15)-(18), D known (in u_eq (14), dbar = 0): s reaches 0 by
                    t_r = |s0| / k                        (seed 002 (18); claim reaching-sign)
  time-known        reaching + sliding on (6): |e_i| <= TRACK_TOL for good by
                    t_r + t_s(e_max),  t_s(e) = ln(1 + alpha e^(1-r)/beta) / (alpha (1-r))
                    (seed 002 (6)-(7) derived, claim settling-ftsm; e_max: e_max_reaching)
  reaching-unknown  the same with D not in u_eq, |D_i| <= dbar = DIST_AMP: t_r = |s0|/(k - dbar)
  time-unknown      reaching + sliding with that t_r

and a tuned file's [certificate] promises: ``certificate-time`` (t_track <= bound_t_total) and
``certificate-u`` (max |u_i| <= u_max), flown with the disturbance mode the certificate was
designed for (dbar = 0: D known).

Observed (``lgw.sim.eros.batch.metrics``): t_reach, the first sample with |s_i| <= S_TOL or a
sign change of s_i; t_track, the first sample after which |e_i| <= TRACK_TOL = 1 cm to the end
of the run (never: +inf, a violation); u_peak, max |u_i|.  Tolerance of the times: one sample
dt, from the sampling alone (an event between samples is seen at the next sample).  The bounds
are for the continuous-time law; the loop flown (and re-flown by the reference route) is the
sampled one, so a violation means the 0.01 s sampled loop is slower than the continuous-time
bound by more than one sample, not necessarily that the continuous-time proof is wrong.

A case the batched RK4 cannot carry (nonfinite) is re-flown alone by ``reference_solve``
(DOP853, rtol = atol = 1e-11 between samples); only a case neither carries is excluded, and a
case that touches the shape model (the plant (4) has no contact: the bounds say nothing about
it).  The re-check of a violation re-flies the case by the reference route.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from lgw.sim.eros.batch import OUTCOMES, S_TOL, SimOptions, metrics, reference_solve, simulate
from lgw.theory.eros import bounds as B
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains
from lgw.theory.errors import ParameterError
from lgw.tuning.eros.cmd_verify import CLAIMS, VARIABLES
from lgw.tuning.verifying import Context, Envelope, Judged, cert_number

__all__ = ["CLAIMS", "VARIABLES", "judge"]

AXES = ("x", "y", "z")
BATCH = (1, 16)  # states per Hypothesis example: one batched simulation costs ~1.4 s
EXTRAS = ()
RECHECK = "reference_solve (DOP853, rtol = atol = 1e-11 between samples)"
DBAR = {"known": 0.0, "unknown": P.DIST_AMP}  # m/s^2, the bound's disturbance level per mode
NO_INTEGRATOR = "neither the batched RK4 nor DOP853 (reference_solve) carried it (nonfinite)"
CONTACT = "surface contact: the plant (4) has no contact model, the bounds do not apply"
WHOLE_E = (1e-6, 1e3)  # m, magnitudes of --domain whole
WHOLE_V = (1e-6, 10.0)  # m/s
LAW = "ftsmc-sign"


# --- what the gains file gives -------------------------------------------------------------

def promises(g: Gains, cert: Mapping[str, Any] | None, shown: str
             ) -> dict[str, dict[str, Any]]:
    """The certificate's values verify reads, each checked by name (the promises themselves
    are claims of their own: certificate-time, certificate-u)."""
    if cert is None:
        return {}
    law = cert.get("law", LAW)
    if not isinstance(law, str):
        raise ParameterError(f"--gains {shown} certificate.law", law, "must be a string")
    for key in ("bound_t_total", "u_max", "e_max", "v_max"):
        cert_number(cert, key, shown, "a finite number > 0")
    cert_number(cert, "dbar", shown, "a finite number >= 0 (m/s^2)", lo_open=False)
    return {}


def _cert_mode(cert: Mapping[str, Any]) -> str:
    return "unknown" if float(cert.get("dbar", 0.0)) > 0 else "known"


def not_applicable(g: Gains, cert: Mapping[str, Any] | None, settings: Mapping[str, Any]
                   ) -> dict[str, str]:
    out = {}
    if not g.k > P.DIST_AMP:
        why = (f"k = {g.k:g} <= dbar = {P.DIST_AMP:g} m/s^2: seed 002 (18) needs k > dbar, so "
               "these gains have no bound under the unknown disturbance")
        out.update({"reaching-unknown": why, "time-unknown": why})
    if cert is None:
        why = "the gains file has no [certificate] table (nothing is promised)"
        out.update({"certificate-time": why, "certificate-u": why})
        return out
    if cert.get("law", LAW) != LAW:
        why = f"the certificate is for the law {cert.get('law')!r}, verify flies {LAW}"
        out.update({"certificate-time": why, "certificate-u": why})
    dbar = float(cert.get("dbar", 0.0))
    if 0 < dbar < P.DIST_AMP:
        why = (f"the certificate's dbar = {dbar:g} m/s^2 is below the simulated unknown "
               f"disturbance amplitude {P.DIST_AMP:g} m/s^2")
        out.update({"certificate-time": why, "certificate-u": why})
    if not g.k > dbar:
        out.setdefault("certificate-time", f"k = {g.k:g} <= the certificate's dbar = {dbar:g}")
    for key, claim in (("bound_t_total", "certificate-time"), ("u_max", "certificate-u")):
        if key not in cert:
            out.setdefault(claim, f"the certificate gives no {key}")
    return out


def default_envelope(g: Gains | None, cert: Mapping[str, Any] | None) -> Envelope:
    """A tuned file's certificate envelope (|e_i(0)| <= e_max, |e_i'(0)| <= v_max), else the
    Monte Carlo envelope of ``lgw simulate eros --cases`` (chosen: 10 m, 0.5 m/s)."""
    e, v = P.MC_POS, P.MC_VEL
    name, src = f"|e_i(0)| <= {e:g} m, |e_i'(0)| <= {v:g} m/s", "lgw.theory.eros.parameters"
    if cert is not None and "e_max" in cert and "v_max" in cert:
        e, v = float(cert["e_max"]), float(cert["v_max"])
        name = f"|e_i(0)| <= {e:g} m, |e_i'(0)| <= {v:g} m/s (the gains file's certificate)"
        src = "certificate.e_max, certificate.v_max"
    names = tuple(x.name for x in VARIABLES)
    return Envelope(name, names, (((-e,) * 3 + (-v,) * 3 + (0.0,),
                                   (e,) * 3 + (v,) * 3 + (2 * math.pi,)),), source=src)


def whole_domain() -> Envelope:
    names = tuple(x.name for x in VARIABLES)
    return Envelope("whole domain", names,
                    (((WHOLE_E[0],) * 3 + (WHOLE_V[0],) * 3 + (0.0,),
                      (WHOLE_E[1],) * 3 + (WHOLE_V[1],) * 3 + (2 * math.pi,)),),
                    scales=("signed-log",) * 6 + ("linear",),
                    source="magnitudes the sampled loop carries near Eros, either sign")


def gains_text(g: Gains, axis: str | None) -> str:
    return (f"alpha = {g.alpha:g}, beta = {g.beta:g}, p/q = {g.p}/{g.q}, k = {g.k:g}, "
            f"e_floor = {g.e_floor:g}")


# --- simulation --------------------------------------------------------------------------------

def case_bounds(e0: np.ndarray, ed0: np.ndarray, g: Gains, dbar: float
                ) -> tuple[np.ndarray, np.ndarray]:
    """(t_reach, t_total) bounds (s), each (N, 3), of ``axis_time_bound`` per case and axis;
    +inf where the bound does not exist (k <= dbar: seed 002 (18) needs k > dbar)."""
    tr = np.full(e0.shape, np.inf)
    tt = np.full(e0.shape, np.inf)
    if not g.k > dbar:
        return tr, tt
    for i in range(e0.shape[0]):
        for a in range(3):
            b = B.axis_time_bound(float(e0[i, a]), float(ed0[i, a]), g, dbar)
            tr[i, a], tt[i, a] = b["t_reach"], b["t_total"]
    return tr, tt


def horizon(bound_total: np.ndarray, dt: float = P.DT_SAMPLE) -> float:
    """Simulated time (s): 1.2 x the largest bound + 1 s, a whole number of samples, so a case
    slower than its bound is seen as such (and one never tracked is +inf)."""
    t = 1.2 * float(np.max(bound_total, initial=0.0)) + 1.0
    return float(math.ceil(t / dt) * dt)


def fly(e0: np.ndarray, ed0: np.ndarray, ph: np.ndarray, g: Gains, mode: str, t_final: float,
        reference: bool = False) -> dict[str, np.ndarray]:
    """Per case: t_reach, t_track (N, 3; +inf never), u_peak (N, 3), outcome index (N,), and
    whether the reference route carried it (N,): the batched RK4, and ``reference_solve`` for
    every case it could not carry (for all cases with ``reference``)."""
    opts = SimOptions(law="ftsmc", switch="sign", disturbance=mode, t_final=t_final)
    n = len(e0)
    if reference:
        m = {"t_reach": np.full((n, 3), np.nan), "t_track": np.full((n, 3), np.nan),
             "u_peak": np.full((n, 3), np.nan),
             "outcome": np.full(n, OUTCOMES.index("nonfinite"))}
        redo = np.arange(n)
    else:
        m = metrics(simulate(e0, ed0, g, opts, ph))
        redo = np.flatnonzero(np.asarray(m["outcome"]) == OUTCOMES.index("nonfinite"))
    out = {k: np.array(m[k], float) for k in ("t_reach", "t_track", "u_peak")}
    out["outcome"] = np.asarray(m["outcome"]).copy()
    out["by_ref"] = np.zeros(n, bool)
    for i in redo:
        r = metrics(reference_solve(e0[i:i + 1], ed0[i:i + 1], g, opts, float(ph[i])))
        out["outcome"][i] = int(r["outcome"][0])
        if out["outcome"][i] != OUTCOMES.index("nonfinite"):
            out["by_ref"][i] = True
            for k in ("t_reach", "t_track", "u_peak"):
                out[k][i] = r[k][0]
    for k in ("t_reach", "t_track"):
        out[k] = np.where(np.isnan(out[k]), np.inf, out[k])
    return out


def judge(ctx: Context, group: str, X: np.ndarray,
          extras: Sequence[Mapping[str, Any]] | None = None) -> dict[str, Judged]:
    """Fly the offsets ``X`` (N, 7: e0, e0', phase) in the disturbance mode of ``group``."""
    g: Gains = ctx.gains
    dt = P.DT_SAMPLE
    e0, ed0, ph = np.array(X[:, :3]), np.array(X[:, 3:6]), np.array(X[:, 6])
    n = len(X)
    cert = ctx.certificate or {}
    mode = _cert_mode(cert) if group == "certificate" else group
    claims = [c for c in CLAIMS if CLAIMS[c].group == group]
    tr, tt = case_bounds(e0, ed0, g, DBAR[mode] if group != "certificate"
                         else float(cert.get("dbar", 0.0)))
    if group == "certificate":
        tt = np.full((n, 3), float(cert.get("bound_t_total", np.inf)))
    grow = max(ctx.factors.get(c, 1.0) for c in claims)
    f = fly(e0, ed0, ph, g, mode, horizon(np.where(np.isfinite(tt), tt, 0.0) * max(grow, 1.0)),
            reference=ctx.fine)
    bad = {OUTCOMES.index("nonfinite"): NO_INTEGRATOR, OUTCOMES.index("crashed"): CONTACT}
    excl = [bad.get(int(o)) for o in f["outcome"]]
    s0 = np.abs(ed0 + g.alpha * e0 + g.beta * np.sign(e0) * np.abs(e0) ** g.r)
    off_surface = s0 > S_TOL
    untracked = (np.abs(e0) > P.TRACK_TOL) | off_surface
    reach = Judged(X, f["t_reach"] - dt, tr, off_surface, excl, dt, fallback=f["by_ref"])
    track = Judged(X, f["t_track"] - dt, tt, untracked, excl, dt, fallback=f["by_ref"])
    if group == "certificate":
        u = Judged(X, f["u_peak"], np.full((n, 3), float(cert.get("u_max", np.inf))),
                   np.ones((n, 3), bool), excl, 0.0, fallback=f["by_ref"])
        return {"certificate-time": track, "certificate-u": u}
    return dict(zip(claims, (reach, track), strict=True))
