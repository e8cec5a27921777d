"""Adversarial campaign for the eros loop: counts per outcome, and the cases that
break a rule (0 expected for each):

  unexplained  a case without exactly one outcome, an outcome time outside [t0, t_final], or
               flags that contradict the outcome;
  impossible   |u_i| above what the law can ask for with its gains at that sample:
               |f_i - xdd_i| + |D_k,i| + |e'_i| max ds/de + k (max ds/de = alpha + beta (p/q)
               e_floor^(p/q-1), lam for PD; fuzzy weights in [0, 1]), recomputed from the
               recorded errors;
  NaN/inf      a non-finite number in an unflagged case's histories or per-case measures
               (a never-happened time, t_reach / t_track = NaN, is documented and excluded).

Cases: offsets per component drawn from exact zeros (both signs), tiny (1e-300..1e-6), moderate
(|x| <= 10), huge (1e2..1e12 m, 1e8 m/s) with random signs; each batch of ``--batch`` cases
shares one variant and one gain set drawn with every gain scaled by 1, 1e-12..1e12 or the float
limits 1e-300 / 1e300.  Each batch is flown by ``simulate`` (the compiled kernel) and audited;
the whole batch is re-flown by the numpy stand-in (``simulate_numpy``) and the outcome class of
every case compared; a few states per batch are re-flown by the solve_ivp reference
(``--reference-per-batch``) and their outcome class compared.

    python benchmarks/adversarial_eros.py --cases 10000
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from lgw.sim.eros import laws as SL
from lgw.sim.eros import plant as PL
from lgw.sim.eros.batch import (
    OUTCOMES,
    SimOptions,
    metrics,
    reference_solve,
    simulate,
    simulate_numpy,
)
from lgw.theory.eros import reference as REF
from lgw.theory.eros.gains import default_gains

GAIN_NAMES = ("alpha", "beta", "k", "lam", "N", "M", "phi", "e_floor")
EXPONENTS = [(3, 5), (1, 3), (7, 9), (1, 1001)]


def components(rng: np.random.Generator, shape: tuple[int, ...], huge: float) -> np.ndarray:
    kind = rng.integers(0, 4, shape)
    sign = rng.choice([-1.0, 1.0], shape)
    out = np.select([kind == 0, kind == 1, kind == 2],
                    [sign * 0.0, sign * 10.0 ** rng.uniform(-300, -6, shape),
                     rng.uniform(-10, 10, shape)],
                    default=sign * 10.0 ** rng.uniform(2, np.log10(huge), shape))
    return out


def gain_set(rng: np.random.Generator):
    g = default_gains()
    kw = {}
    for name in GAIN_NAMES:
        c = rng.integers(0, 4)
        scale = (1.0 if c <= 1 else 10.0 ** rng.uniform(-12, 12) if c == 2
                 else float(rng.choice([1e-300, 1e300])))
        kw[name] = getattr(g, name) * scale
    kw["p"], kw["q"] = EXPONENTS[rng.integers(len(EXPONENTS))]
    return g.replace(**kw)


def u_bound(res) -> np.ndarray:
    """(K, n, 3) upper bound on |u| from the law's structure (module docstring)."""
    g, o = res.gains, res.options
    coef = REF.coefficients(printed=o.reference == "printed")
    slope = g.lam if o.law == "pdsmc" else g.alpha + g.beta * g.r * g.e_floor ** (g.r - 1)
    out = np.empty_like(res.u)
    for kk, t in enumerate(res.t[:-1]):
        rp, rv, ra = REF.evaluate(coef, t)
        pos, vel = rp + res.e[kk], rv + res.ed[kk]
        f = PL.rotating_terms(pos, vel) + PL.gravity(pos, "two-point")
        dk = o.dist.amp if o.disturbance == "known" else 0.0  # |D_k,i| <= amp, any phase
        # e' = 0 contributes nothing even where the bound on ds/de overflows (0 * inf)
        term = np.where(res.ed[kk] == 0, 0.0, np.abs(res.ed[kk]) * slope)
        out[kk] = np.abs(f - ra) + dk + term + g.k
    return out


def audit(res) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per case: (unexplained, impossible, unflagged non-finite) as booleans."""
    n = len(res.nonfinite)
    code, t = res.outcome, res.t_outcome
    unexpl = ~((code >= 0) & (code < len(OUTCOMES)) & np.isfinite(t) & (t >= res.t[0])
               & (t <= res.t[-1]))
    unexpl |= (code == 0) != res.contact
    unexpl |= (code == 1) != res.nonfinite
    unexpl |= res.contact & res.nonfinite
    flagged = res.contact | res.nonfinite
    with np.errstate(all="ignore"):
        ub = u_bound(res)
        u = np.abs(res.u)
        ok = (u <= ub * (1 + 1e-12)) | (u == 0)
    impossible = ~ok.all(axis=(0, 2)) & ~flagged
    with np.errstate(all="ignore"):  # an overflowed sum is counted below, not warned about
        m = metrics(res)
    fin = np.ones(n, bool)
    for h in (res.e, res.ed, res.s, res.u):
        fin &= np.isfinite(h).all(axis=(0, 2))
    fin &= np.isfinite(res.pos).all(axis=1) & np.isfinite(res.vel).all(axis=1)
    for key in ("u_peak", "effort", "chatter", "e_final", "ed_final"):
        fin &= np.isfinite(m[key]).reshape(n, -1).all(axis=1)
    for key in ("iae", "iae_int"):
        fin &= np.isfinite(m[key])
    return unexpl, impossible, ~fin & ~flagged


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--batch", type=int, default=50)
    ap.add_argument("--t-final", type=float, default=0.5)
    ap.add_argument("--seed", type=int, default=14)
    ap.add_argument("--reference-per-batch", type=int, default=2)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    counts = dict.fromkeys(OUTCOMES, 0)
    unexpl = imposs = nonfin = ref_n = ref_agree = np_agree = 0
    disagree, np_disagree, examples = [], [], []
    t0 = time.perf_counter()
    done = 0
    while done < a.cases:
        n = min(a.batch, a.cases - done)
        law, sw = SL.VARIANTS[rng.integers(len(SL.VARIANTS))]
        g = gain_set(rng)
        dist = ("known", "unknown", "none")[rng.integers(3)]
        opts = SimOptions(law=law, switch=sw, t_final=a.t_final, disturbance=dist)
        e0, ed0 = components(rng, (n, 3), 1e12), components(rng, (n, 3), 1e8)
        ph = rng.uniform(0, 2 * np.pi, n)
        res = simulate(e0, ed0, g, opts, ph)
        rn = simulate_numpy(e0, ed0, g, opts, ph)
        same = rn.outcome == res.outcome
        np_agree += int(same.sum())
        for i in np.flatnonzero(~same)[:2]:
            np_disagree.append((SL.variant_name(law, sw), dist, OUTCOMES[res.outcome[i]],
                                OUTCOMES[rn.outcome[i]], e0[i].tolist(), ed0[i].tolist()))
        for i, c in enumerate(OUTCOMES):
            counts[c] += int(np.sum(res.outcome == i))
        ue, im, nf = audit(res)
        for i in np.flatnonzero(im)[:1]:
            examples.append((SL.variant_name(law, sw), dist, g, e0[i].tolist(), ed0[i].tolist()))
        unexpl, imposs, nonfin = unexpl + int(ue.sum()), imposs + int(im.sum()), nonfin + int(
            nf.sum())
        for i in rng.choice(n, size=min(a.reference_per_batch, n), replace=False):
            b = reference_solve(e0[i:i + 1], ed0[i:i + 1], g, opts, float(ph[i]))
            ref_n += 1
            if b.outcome[0] == res.outcome[i]:
                ref_agree += 1
            else:
                disagree.append((SL.variant_name(law, sw), OUTCOMES[res.outcome[i]],
                                 OUTCOMES[b.outcome[0]], e0[i].tolist(), ed0[i].tolist()))
        done += n
    wall = time.perf_counter() - t0
    print(f"eros adversarial campaign: {a.cases} cases, t_final {a.t_final} s, dt 0.01 s, "
          f"batches of {a.batch}, seed {a.seed}, {wall:.0f} s")
    for c in OUTCOMES:
        print(f"  {c:16s} {counts[c]}")
    print(f"  unexplained      {unexpl}")
    print(f"  impossible       {imposs}")
    print(f"  NaN/inf          {nonfin}")
    print(f"  kernel vs numpy stand-in outcome class: {np_agree}/{a.cases} agree")
    for d in np_disagree[:10]:
        print("   disagree (kernel, stand-in):", d)
    print(f"  kernel vs solve_ivp outcome class: {ref_agree}/{ref_n} agree")
    for d in disagree[:10]:
        print("   disagree:", d)
    for x in examples[:5]:
        print("   impossible:", x)


if __name__ == "__main__":
    main()
