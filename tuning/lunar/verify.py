"""Seed 001's claims as ``lgw verify lunar`` checks them (the shared machinery:
``lgw.tuning.verifying``): the general system (5) (orbit-instance form, ||d|| = D constant,
saturation per axis) flown from initial errors, measured behaviour against (13), (18), (19),
(21a).

``observations`` is the one measurement, used by ``judge`` (the verify campaign) and by
``margins`` (tests/lunar/test_properties.py).  The chattering band of the sign-like term of (7)
(claim smooth-7) is excluded from the step-wise V2 check and stated.  The re-check of a
violation flies the case alone at dt/2.  The row "(19b) printed" is the paper's statement as
printed, (19b) with the printed (20) (``z_l2_bounds_printed``: no (d0e(0) - D)^2/(2q) term in
V2(0), f2bar where (13) gives f2bar - f3), beside the derived row.

A tuned file's [certificate] (``lgw tune lunar``) is checked by ``compute``: each record of
``lgw.tuning.lunar.design.check_certificate`` is a claim (``certificate-*``) with its evidence
word, "proven" (re-derived: exact arithmetic, the hypotheses, linfnorm) or "sampled" (a fresh
campaign over the certificate's envelope); a sampled violation is re-flown with the step
halved, the re-check that confirms it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from lgw.sim.lunar.batch import l2_norm
from lgw.sim.lunar.closed_loop import gain_arrays
from lgw.sim.lunar.general import GeneralCase, fly
from lgw.theory.lunar.bounds import (
    lambda_gain_bounds,
    transient_bounds,
    v2_initial,
    z_l2_bounds,
    z_l2_bounds_printed,
)
from lgw.theory.lunar.gains import Gains, LoopGains, make_loop
from lgw.tuning.lunar.cmd_verify import CERT_CLAIMS, CLAIMS, VARIABLES
from lgw.tuning.verifying import Computed, Context, Envelope, Judged
from lgw.tuning.verifying import margins as relative_margins

__all__ = ["CLAIMS", "VARIABLES", "judge", "margins", "observations"]

AXES = ("",)
BATCH = (1, 8)  # initial errors per Hypothesis example (one batched RK4 flight)
EXTRAS = ()
RECHECK = "the case flown alone at dt/2 (RK4)"
BAND = 3.0  # chattering band: ||z2|| <= BAND dt (d0e + D)
X1_MAX = 100.0  # m, |x1(0)| of the default envelope (chosen: seed 001 flies one case)
X2_MAX = 5.0  # m/s, |x2_i(0)|
WHOLE_X1 = (1e-6, 1e4)  # m, magnitudes of --domain whole
WHOLE_X2 = (1e-6, 1e2)  # m/s


def observations(t: np.ndarray, o: dict, g: LoopGains, case: GeneralCase, x1_0: float,
                 dt: float, i: int = 0) -> dict[str, tuple[float, float, bool]]:
    """Claim -> (bound, observed, informative) of case ``i``: the L2 norms (squared for (19))
    against their bounds; for (13) the largest V2 step outside the chattering band over V2(0),
    bound 0 (informative when such a step exists); plus "V2_max_rise_inside_band", the
    statistic of the band (not a claim)."""
    V2 = o["V2"][:, i]
    band = BAND * dt * (o["d0e"][:-1, i] + case.D)
    outside = o["nz"][:-1, i] > band
    dV = np.diff(V2)
    f1b, f2b = float(g.K1[2, 2]), g.f2bar
    w = float(l2_norm(t, o["B0du"][..., i:i + 1])[0])
    c1, c2 = lambda_gain_bounds(f1b, f2b)
    v20 = v2_initial(np.array([x1_0]), o["z2"][0, :, i], g.d0e0, case.D, g.q)
    b1, b2 = z_l2_bounds(v20, f1b, f2b, g.f3)
    b2p = z_l2_bounds_printed(np.array([x1_0]), o["z2"][0, :, i], f1b, f2b)[1]
    x1b, _ = transient_bounds(v20, w, f1b, f2b, g.f3, float(np.linalg.norm(g.K1[:, 2])))

    def n(k: str) -> float:
        return float(l2_norm(t, o[k][..., i:i + 1])[0])

    pos = V2[0] > 0
    step = float(np.max(dV[outside], initial=-np.inf) / V2[0]) if pos else -np.inf
    l1, l2 = n("l1"), n("l2")
    return {
        "V2_step_outside_band": (0.0, step, bool(pos and outside.any())),
        "(18a)": (c1 * w, l1, w > 0 or l1 > 0), "(18b)": (c2 * w, l2, w > 0 or l2 > 0),
        "(19a)": (b1, n("z1") ** 2, b1 > 0), "(19b) derived": (b2, n("z2") ** 2, b2 > 0),
        "(19b) printed": (b2p, n("z2") ** 2, b2p > 0), "(21a)": (x1b, n("x1"), x1b > 0),
        "V2_max_rise_inside_band": (0.0, float(np.max(dV[~outside], initial=0.0) / V2[0])
                                    if pos else 0.0, False),
    }


def margins(t: np.ndarray, o: dict, g: LoopGains, case: GeneralCase, x1_0: float,
            dt: float, i: int = 0) -> dict[str, float]:
    """Relative margins (bound - observed)/bound of case ``i`` (< 0 violates; the (13) check
    over V2(0)), and the statistic V2_max_rise_inside_band (the band's largest rise)."""
    out = {}
    for k, (b, ob, _) in observations(t, o, g, case, x1_0, dt, i).items():
        if k == "V2_max_rise_inside_band":
            out[k] = ob
        else:
            out[k] = float(relative_margins(np.array(ob), np.array(b), np.array(1.0)))
    return out


def random_loop_gains(rng: np.random.Generator) -> LoopGains:
    """An orbit-loop gain set inside the hypotheses (lgw.testing.lunar.orbit_gain_dicts)."""
    k = rng.uniform(0.05, 1.0)
    F2 = rng.uniform(0.6, 5.0, 3)
    return make_loop("orbit", {"K1": [k, k, k], "F2": F2.tolist(),
                               "f3": float(rng.uniform(0.05, 0.95) * F2.min()), "d0e0": 0.0,
                               "q": float(rng.uniform(0.005, 1.0))})


# --- what lgw verify lunar needs of the system -------------------------------------------------

PRINTED = "(19b) printed"


def claims_for(settings: Mapping[str, Any]) -> tuple[str, ...]:
    """The claims checked unless --claim names others: every claim but the paper's (19b) as
    printed, which is false for every gain set whose d0e(0) differs from D (the theory's claim
    L2-19-20 refutes it: from zero initial errors the printed V2(0) and its bound are 0 while
    the disturbance moves z2), so it would fail every run; ``--claim "(19b) printed"`` checks
    it and shows the counterexample."""
    return tuple(c for c in CLAIMS if c != PRINTED)


def not_applicable(g: Gains, cert: Mapping[str, Any] | None, settings: Mapping[str, Any]
                   ) -> dict[str, str]:
    """The derived bounds apply to every orbit loop (a gains file's, or the paper's); the
    certificate claims need a [certificate] table (a file of ``lgw tune lunar``)."""
    if cert is None:
        why = ("the gains file has no [certificate] table (nothing is promised; lgw tune lunar "
               "writes one)")
        return dict.fromkeys(CERT_CLAIMS, why)
    return {}


def promises(g: Gains, cert: Mapping[str, Any] | None, shown: str
             ) -> dict[str, dict[str, Any]]:
    """The certificate's values verify reads, checked by name before any work
    (``certificate_request``: a string, list, nan or missing key is a named error); the
    promises themselves are the computed claims ``certificate-*``."""
    if cert is not None:
        from lgw.tuning.lunar.design import certificate_request

        certificate_request(Gains(g.orbit, g.attitude, extra={**g.extra, "certificate": cert}))
    return {}


# which record of check_certificate is which claim (by the start of its promise text)
_RECORDS = (("thrust redundancy", "certificate-redundancy"),
            ("hypotheses", "certificate-hypotheses"),
            ("L2 gain B0 du -> lambda1", "certificate-l2-lambda1"),
            ("L2 gain B0 du -> lambda2", "certificate-l2-lambda2"),
            ("every case", "certificate-completes"), ("|e_h(t_f)|", "certificate-eh"),
            ("|e_v(t_f)|", "certificate-ev"), ("commanded thrust", "certificate-thrust"))


FLOWN = ("certificate-completes", "certificate-eh", "certificate-ev", "certificate-thrust")


def _by_claim(records: Sequence[Any]) -> dict[str, Any]:
    out = {}
    for rec in records:
        name = next((c for pre, c in _RECORDS if rec.promise.startswith(pre)), None)
        if name is None:
            raise RuntimeError(f"a certificate check verify does not know: {rec.promise!r}")
        out[name] = rec
    return out


def _halved(g: Gains) -> Gains:
    """The same file with the certificate's step halved (the re-check of a sampled
    violation)."""
    cert = dict(g.extra["certificate"])
    cert["dt_s"] = float(cert["dt_s"]) / 2
    return Gains(g.orbit, g.attitude, extra={**g.extra, "certificate": cert})


def compute(ctx: Context, names: Sequence[str], progress: Any = None) -> dict[str, Computed]:
    """The certificate claims (``check_certificate`` on ``--cert-cases`` cases, seed
    ``--cert-seed``); a sampled record over its bound is re-flown at half the step."""
    from lgw.tuning.lunar.design import check_certificate

    g: Gains = ctx.gains
    if ctx.certificate is not None and "certificate" not in g.extra:
        g = Gains(g.orbit, g.attitude, extra={**g.extra, "certificate": dict(ctx.certificate)})
    s = ctx.settings
    n, seed = int(s["cert_cases"]), int(s["cert_seed"])
    flying = any(c in FLOWN for c in names)
    recs = _by_claim(check_certificate(g, cases=n, seed=seed, progress=progress,
                                       sampled=flying))
    flags = ("--cert-cases", str(n), "--cert-seed", str(seed)) if flying else ()
    out: dict[str, Computed] = {}
    fine: dict[str, Any] | None = None
    for name in names:
        rec = recs[name]
        zero = rec.bound == 0
        obs = (0.0 if rec.holds else 1.0) if name == "certificate-hypotheses" else rec.observed
        comp = Computed(float(obs), float(rec.bound), rec.evidence, rec.detail,
                        cases=n + 1 if rec.evidence == "sampled" else 0, flags=flags,
                        reference=1.0 if zero else None)
        if rec.evidence == "sampled" and comp.margin() < 0:
            if fine is None:
                fine = _by_claim(check_certificate(_halved(g), cases=n, seed=seed))
            f = fine[name]
            fobs = float(f.observed)
            comp.confirmed = bool(not f.holds)
            comp.recheck = (f"the same campaign at half the step: observed {fobs:.6g}, "
                            f"{'over' if not f.holds else 'within'} the bound")
            comp.case = f"the campaign of {n} cases (seed {seed}) plus the nominal case"
        elif rec.evidence == "proven" and not rec.holds:
            comp.recheck = "the proof re-done on the file's numbers (deterministic)"
        out[name] = comp
    return out


def default_envelope(g: Gains | None, cert: Mapping[str, Any] | None) -> Envelope:
    names = tuple(v.name for v in VARIABLES)
    return Envelope("initial errors |x1| <= 100 m, |x2_i| <= 5 m/s", names,
                    ((( -X1_MAX,) + (-X2_MAX,) * 3, (X1_MAX,) + (X2_MAX,) * 3),),
                    source="chosen (seed 001 Section 5 flies a single case)")


def whole_domain() -> Envelope:
    names = tuple(v.name for v in VARIABLES)
    return Envelope("whole domain", names,
                    (((WHOLE_X1[0],) + (WHOLE_X2[0],) * 3, (WHOLE_X1[1],) + (WHOLE_X2[1],) * 3),),
                    scales=("signed-log",) * 4,
                    source="magnitudes the RK4 flight carries, either sign")


def gains_text(g: Gains, axis: str | None) -> str:
    o = g.orbit
    return (f"orbit loop: K1 = diag{tuple(float(x) for x in np.diag(o.K1))}, F2 = "
            f"diag{tuple(float(x) for x in np.diag(o.F2))}, f3 = {o.f3:g}, d0e0 = "
            f"{o.d0e0:g}, q = {o.q:g}")


def judge(ctx: Context, group: str, X: np.ndarray,
          extras: Sequence[Mapping[str, Any]] | None = None) -> dict[str, Judged]:
    """Fly the initial errors ``X`` (N, 4: x1, x2) of the orbit loop in one RK4 batch."""
    g: LoopGains = ctx.gains.orbit
    s = ctx.settings
    dt = float(s["dt"]) / (2.0 if ctx.fine else 1.0)
    n = len(X)
    X0 = np.zeros((9, n))
    X0[0], X0[1:4], X0[8] = X[:, 0], X[:, 1:4].T, g.d0e0
    case = GeneralCase(D=float(s["D"]), u_max=float(s["thrust_max"]))
    with np.errstate(all="ignore"):
        t, o = fly(X0, gain_arrays([g] * n), case, float(s["t_max"]), dt)
        rows = [observations(t, o, g, case, float(X[i, 0]), dt, i) for i in range(n)]
    out = {}
    for c in CLAIMS:
        if CLAIMS[c].kind != "campaign":
            continue
        b, ob, inf_ = (np.array([[r[c][k]] for r in rows]) for k in range(3))
        out[c] = Judged(np.asarray(X, float), ob.astype(float), b.astype(float),
                        inf_.astype(bool), [None] * n,
                        reference=np.ones((n, 1)) if c == "V2_step_outside_band" else None)
    return out
