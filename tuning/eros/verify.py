"""Seed 002's claims as ``lgw verify eros`` checks them (the shared machinery:
``lgw.tuning.verifying``).

The law under check is the FTSMC (19) with sign switching, sampled at dt = 0.01 s with a
zero-order hold (``lgw.sim.eros.batch.simulate``: the paper's loop), |e|^(p/q-1) evaluated at
max(|e|, e_floor) as flown.  Per case and axis the bounds are the flown law's, at the case's
own e0, e0' (``lgw.theory.eros.floored``; as e_floor -> 0 they are seed 002's,
``lgw.theory.eros.bounds.axis_time_bound``):

  reaching-known    (15)-(18), D known (in u_eq (14), dbar = 0): s reaches 0 by
                    t_r = (sgn(s0) sigma0 + delta)^+ / k  (``s_reach_time``; |s0|/k without
                    the floor: seed 002 (18), claim reaching-sign)
  time-known        reaching + tracking: |e_i| <= TRACK_TOL for good by t_r(sigma) + t_s
                    (``axis_bound``: reaching on the floored surface, then the tracking
                    time from the largest |e| during reaching; seed 002 (6)-(7) without the
                    floor, claim settling-ftsm)
  reaching-unknown  the same with D not in u_eq, |D_i| <= dbar = DIST_AMP: over k - dbar
  time-unknown      reaching + tracking with that rate

and a tuned file's [certificate] promises: ``certificate-time`` (t_track <= bound_t_total) and
``certificate-u`` (max |u_i| <= u_max), flown with the disturbance mode the certificate was
designed for (dbar = 0: D known); and, for each promise the certificate says is proven, its
proof done again (``certificate-time-proof``, ``certificate-u-proof``: the floored law's
bounds over the certificate's envelope, ``lgw.theory.eros.floored`` in Arb; the certificate's
number must be at least the proven bound).

``--scenario descent``: the claim ``descent-landing`` over a campaign of
``lgw.sim.eros.descent.dispersions`` (the law, thrust, landing speed and navigation of a tuned
descent file's certificate, else the descent's defaults): ``landing_margin`` >= 0 for every
case; the worst case over its bound is re-flown by ``reference_solve_descent`` (DOP853, the
exact polyhedron, the contact by event location), which must confirm it.

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
from lgw.theory.eros import parameters as P
from lgw.theory.eros.gains import Gains
from lgw.theory.errors import ParameterError
from lgw.tuning.eros.cmd_verify import CLAIMS, TRACKING_CLAIMS, VARIABLES
from lgw.tuning.verifying import Computed, Context, Envelope, Judged, cert_number

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
    for key in ("law", "scenario", "bound_evidence", "u_max_evidence", "landing_evidence"):
        if key in cert and not isinstance(cert[key], str):
            raise ParameterError(f"--gains {shown} certificate.{key}", cert[key],
                                 "must be a string")
    if cert.get("scenario", "tracking") not in ("tracking", "descent"):
        raise ParameterError(f"--gains {shown} certificate.scenario", cert["scenario"],
                             "tracking or descent")
    if cert.get("scenario") == "descent":
        from lgw.sim.eros import laws as SL

        try:
            SL.parse_variant(cert.get("law", "fuzzy-tanh"))
        except ParameterError:
            raise ParameterError(f"--gains {shown} certificate.law", cert.get("law"),
                                 "a law variant, e.g. fuzzy-tanh") from None
        for key in ("thrust_max", "land_speed"):
            cert_number(cert, key, shown, "a finite number > 0")
        if "nav" in cert and not isinstance(cert["nav"], bool):
            raise ParameterError(f"--gains {shown} certificate.nav", cert["nav"],
                                 "must be true or false")
        return {}
    for key in ("bound_t_total", "u_max", "e_max", "v_max"):
        cert_number(cert, key, shown, "a finite number > 0")
    cert_number(cert, "dbar", shown, "a finite number >= 0 (m/s^2)", lo_open=False)
    return {}


def claims_for(settings: Mapping[str, Any]) -> tuple[str, ...]:
    """The claims of the scenario flown (unless --claim names others)."""
    if settings.get("scenario") == "descent":
        return ("descent-landing",)
    return TRACKING_CLAIMS


def builtin_gains(settings: Mapping[str, Any]) -> Gains | None:
    """The descent flies its own gains when no file is given (DESCENT_GAINS)."""
    if settings.get("scenario") == "descent":
        from lgw.sim.eros.descent import descent_gains

        return descent_gains()
    return None


def _proven(cert: Mapping[str, Any], key: str) -> bool:
    return str(cert.get(key, "")).startswith("proven")


def _cert_mode(cert: Mapping[str, Any]) -> str:
    return "unknown" if float(cert.get("dbar", 0.0)) > 0 else "known"


def not_applicable(g: Gains, cert: Mapping[str, Any] | None, settings: Mapping[str, Any]
                   ) -> dict[str, str]:
    out = {}
    if settings.get("scenario") == "descent":
        why = "--scenario descent flies the whole descent, not the tracking scenario"
        out.update(dict.fromkeys(TRACKING_CLAIMS, why))
        if cert is not None and cert.get("scenario", "tracking") != "descent":
            out["descent-landing"] = ("the gains file's certificate is for the tracking "
                                      "scenario (lgw tune eros --scenario descent writes a "
                                      "descent one)")
        return out
    out["descent-landing"] = "it is the descent's claim (--scenario descent)"
    if cert is not None and cert.get("scenario") == "descent":
        why = ("the gains file's certificate is for the descent (verify it with --scenario "
               "descent)")
        for c in ("certificate-time", "certificate-u", "certificate-time-proof",
                  "certificate-u-proof"):
            out[c] = why
    if not g.k > P.DIST_AMP:
        why = (f"k = {g.k:g} <= dbar = {P.DIST_AMP:g} m/s^2: seed 002 (18) needs k > dbar, so "
               "these gains have no bound under the unknown disturbance")
        out.update({"reaching-unknown": why, "time-unknown": why})
    certs = ("certificate-time", "certificate-u", "certificate-time-proof",
             "certificate-u-proof")
    if cert is None:
        why = "the gains file has no [certificate] table (nothing is promised)"
        out.update(dict.fromkeys(certs, why))
        return out
    if cert.get("law", LAW) != LAW:
        why = f"the certificate is for the law {cert.get('law')!r}, verify flies {LAW}"
        for c in certs:
            out.setdefault(c, why)
    for key, claim in (("bound_evidence", "certificate-time-proof"),
                       ("u_max_evidence", "certificate-u-proof")):
        if not _proven(cert, key):
            out.setdefault(claim, f"the certificate does not say the promise is proven "
                           f"({key} = {str(cert.get(key, 'absent'))[:60]!r}): it is checked "
                           "by flights only")
    dbar = float(cert.get("dbar", 0.0))
    if 0 < dbar < P.DIST_AMP:
        why = (f"the certificate's dbar = {dbar:g} m/s^2 is below the simulated unknown "
               f"disturbance amplitude {P.DIST_AMP:g} m/s^2")
        out.update({"certificate-time": why, "certificate-u": why})
    if not g.k > dbar:
        out.setdefault("certificate-time", f"k = {g.k:g} <= the certificate's dbar = {dbar:g}")
    for key, claims in (("bound_t_total", ("certificate-time", "certificate-time-proof")),
                        ("u_max", ("certificate-u", "certificate-u-proof"))):
        if key not in cert:
            for claim in claims:
                out.setdefault(claim, f"the certificate gives no {key}")
    for key in ("e_max", "v_max"):
        if key not in cert:
            for claim in ("certificate-time-proof", "certificate-u-proof"):
                out.setdefault(claim, f"the certificate gives no {key} (its envelope)")
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
    """(t_reach, t_total) bounds (s), each (N, 3), per case and axis, of the law as flown,
    |e|^(p/q-1) floored at e_floor (``lgw.theory.eros.floored``: ``s_reach_time`` and the
    reaching + tracking time of ``axis_bound``; as e_floor -> 0 they are seed 002 (18) and
    ``lgw.theory.eros.bounds.axis_time_bound``); +inf where the bound does not exist (k <=
    dbar: seed 002 (18) needs k > dbar)."""
    from lgw.theory.eros import floored as FL

    tr = np.full(e0.shape, np.inf)
    tt = np.full(e0.shape, np.inf)
    if not g.k > dbar:
        return tr, tt
    for i in range(e0.shape[0]):
        for a in range(3):
            x, v = float(e0[i, a]), float(ed0[i, a])
            tr[i, a] = FL.s_reach_time(x, v, g, dbar)
            tt[i, a] = FL.axis_bound(x, v, g, dm=dbar, screen=True).t_total
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


# --- computed claims: the certificate's proofs done again, the descent's campaign ---------------

def compute(ctx: Context, names: Sequence[str], progress: Any = None) -> dict[str, Computed]:
    """``certificate-time-proof``, ``certificate-u-proof`` (``lgw.theory.eros.floored`` over
    the certificate's envelope, Arb) and ``descent-landing`` (``descent_campaign``)."""
    out: dict[str, Computed] = {}
    proofs = [n for n in names if n.endswith("-proof")]
    if proofs:
        out.update(_proofs(ctx, proofs))
    if "descent-landing" in names:
        out["descent-landing"] = descent_campaign(ctx, progress)
    return out


def _proofs(ctx: Context, names: Sequence[str]) -> dict[str, Computed]:
    from lgw.theory.eros import floored as FL

    cert = ctx.certificate or {}
    g: Gains = ctx.gains
    e_max, v_max = float(cert["e_max"]), float(cert["v_max"])
    dbar = float(cert.get("dbar", 0.0))
    amp = P.DIST_AMP if dbar == 0 else 0.0
    hyp = FL.hypotheses(g, dbar)
    bd = FL.envelope_bound(g, e_max, v_max, dm=dbar, known_amp=amp)
    env = (f"|e_i(0)| <= {e_max:g} m, |e_i'(0)| <= {v_max:g} m/s, "
           + ("D known (cancelled, |D_i| <= 0.05 m/s^2)" if dbar == 0 else
              f"|D_i| <= dbar = {dbar:g} m/s^2 unknown"))
    failed = [k for k, ok in hyp.items() if not ok]
    why = f"; hypotheses that fail: {', '.join(failed)}" if failed else ""
    out = {}
    if "certificate-time-proof" in names:
        out["certificate-time-proof"] = Computed(
            bd["t_total"], float(cert["bound_t_total"]), "proven",
            f"{bd['how']}: reaching {bd['t_reach']:.6g} s + sliding {bd['t_slide']:.6g} s to "
            f"|e_i| <= {P.TRACK_TOL:g} m, over {env}{why}",
            recheck="the proof re-done (Arb, deterministic)")
    if "certificate-u-proof" in names:
        out["certificate-u-proof"] = Computed(
            bd["u"], float(cert["u_max"]), "proven",
            f"{bd['how']}: |u_i| <= drift {bd['drift']:.4g} + k {bd['k']:.4g} + max |e' G(e)| "
            f"{bd['ed_g']:.6g} (G(e_floor) = {bd['g_max']:.6g}, |e| <= {bd['E']:.6g} m), over "
            f"{env}{why}", recheck="the proof re-done (Arb, deterministic)")
    return out


def descent_setup(g: Gains, cert: Mapping[str, Any] | None, seed: int) -> Any:
    """The DescentOptions of a descent check: a tuned descent file's law, thrust limit,
    landing speed and navigation (on unless the certificate says off), else the defaults."""
    from lgw.sim.eros import laws as SL
    from lgw.sim.eros.descent import DescentOptions, Navigation, Probe

    c = cert if cert is not None and cert.get("scenario") == "descent" else {}
    law, sw = SL.parse_variant(c.get("law", "-".join(P.DESCENT_LAW)))
    nav = bool(c.get("nav", True))
    return DescentOptions(law=law, switch=sw,
                          probe=Probe(thrust_max=float(c.get("thrust_max", P.THRUST_MAX))),
                          nav=Navigation.typical(seed) if nav else Navigation(),
                          land_speed=float(c.get("land_speed", P.LAND_SPEED_MAX)), stride=0)


def descent_campaign(ctx: Context, progress: Any = None) -> Computed:
    """Every case of ``dispersions(--cases, --descent-seed)`` (or only --case) must land:
    observed the largest touchdown speed (inf: a case that never touched down), bound the
    landing speed; the worst case over it re-flown by ``reference_solve_descent``."""
    from lgw.sim.eros import descent as D

    s = ctx.settings
    n, seed, only = int(s["cases"]), int(s["descent_seed"]), s.get("case")
    o = descent_setup(ctx.gains, ctx.certificate, seed)
    d = D.dispersions(n, seed)
    idx = np.arange(n) if only is None else np.array([int(only)])
    r = D.simulate_descent(d["e0"][idx], d["ed0"][idx], ctx.gains, o, srp=d["srp"][idx],
                           case_phase=d["case_phase"][idx], nav_ids=d["nav_ids"][idx])
    m = D.landing_margin(r)
    j = int(np.argmin(m))
    i = int(idx[j])
    speed = float(o.land_speed - m[j])
    counts = {k: v for k, v in D.counts(r.outcome).items() if v}
    law = f"{o.law}-{o.switch}"
    detail = (f"{len(idx)} case(s) of lgw.sim.eros.descent.dispersions({n}, seed {seed}) "
              f"({law}, thrust {o.probe.thrust_max:g} N per {o.probe.limit}, navigation "
              f"errors {'on' if o.nav.on else 'off'}, RK4 at {o.dt:g} s, polyhedral plant): "
              f"outcomes {counts}")
    case = (f"case {i}: e(0) = {np.round(d['e0'][i], 6).tolist()} m, e'(0) = "
            f"{np.round(d['ed0'][i], 6).tolist()} m/s, SRP {d['srp'][i]:.4g} m/s^2, phase "
            f"{d['case_phase'][i]:.4g} rad, nav id {int(d['nav_ids'][i])}: "
            f"{r.outcome_names()[j]} at t = {float(r.t_outcome[j]):.6g} s")
    comp = Computed(speed, o.land_speed, "sampled", detail, cases=len(idx), case=case,
                    flags=("--scenario", "descent", "--cases", str(n), "--descent-seed",
                           str(seed), "--case", str(i)))
    if m[j] < 0:
        if progress is not None:
            progress.stage(f"re-flying case {i} by reference_solve_descent (minutes)")
        ref = D.reference_solve_descent(d["e0"][i], d["ed0"][i], ctx.gains, o,
                                        case_phase=float(d["case_phase"][i]),
                                        srp=float(d["srp"][i]), nav_id=int(d["nav_ids"][i]))
        sp = ref["touchdown"]["speed"]
        comp.confirmed = ref["outcome"] != "landed"
        comp.recheck = (f"reference_solve_descent (DOP853, exact polyhedron, contact by event "
                        f"location): {ref['outcome']} at t = {ref['t_outcome']:.6g} s"
                        + (f", speed {sp:.6g} m/s" if np.isfinite(sp) else ""))
    return comp
