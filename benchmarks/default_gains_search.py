"""How the default gain set (lgw.theory.mars.parameters.DEFAULT_GAINS) was chosen.

Random search: 12,000 gain sets (log-uniform gains, uniform exponents) fly the Table I case
together with the corrected law, no drag, semi-implicit Euler at dt = 0.01 s (a screening
integrator only; the chosen set is then verified with a tight solve_ivp).  Kept: landed
(|r| < 0.5 m, |v| < 0.5 m/s) within 30 s, peak thrust under 45 kN per axis, never below ground.
Printed: the 10 kept sets with the smallest sound landing-time bound (T1* + T2*).

    python benchmarks/default_gains_search.py
"""

from __future__ import annotations

import lgw.theory.mars.parameters as P
import numpy as np
from lgw.theory.mars.bounds import landing_time_bound
from lgw.theory.mars.gains import default_gains, gains_from_dict
from lgw.theory.mars.mss import law_numeric
from scipy.integrate import solve_ivp


def screen(n: int = 12_000, seed: int = 1) -> list[tuple]:
    rng = np.random.default_rng(seed)
    b1, b2 = 10 ** rng.uniform(-1.5, 0.5, n), 10 ** rng.uniform(-6, -1.5, n)
    a1, a2 = 10 ** rng.uniform(-1, 1, n), 10 ** rng.uniform(-5, -1, n)
    q1, q2 = rng.uniform(0.55, 0.95, n), rng.uniform(1.1, 2.0, n)
    g1, g2 = rng.uniform(0.55, 0.95, n), rng.uniform(1.05, 2.0, n)
    f = law_numeric("corrected")
    c = P.ISP * P.G_EARTH
    r, v, m = np.tile(P.R0, (n, 1)), np.tile(P.V0, (n, 1)), np.full(n, P.M0)
    dt, peak = 0.01, np.zeros(n)
    t_land, min_z = np.full(n, np.inf), np.full(n, np.inf)
    col = (lambda x: x[:, None])  # noqa: E731
    for k in range(int(45 / dt)):
        with np.errstate(all="ignore"):
            a = f(r, v, P.G_MARS, 0.0, col(b1), col(b2), col(a1), col(a2), col(q1), col(q2),
                  col(g1), col(g2))
        a = np.nan_to_num(a, nan=0.0, posinf=1e9, neginf=-1e9)
        peak = np.maximum(peak, np.max(np.abs(a), axis=1) * m)
        v = v + dt * (a + P.G_MARS)
        r = r + dt * v
        m = m - dt * np.linalg.norm(a, axis=1) * m / c
        min_z = np.minimum(min_z, r[:, 2])
        done = (np.linalg.norm(r, axis=1) < 0.5) & (np.linalg.norm(v, axis=1) < 0.5)
        t_land[done & np.isinf(t_land)] = (k + 1) * dt
    ok = np.where((peak < 45_000) & (t_land <= 30) & (min_z > -0.5))[0]
    rows = []
    for i in ok:
        g = gains_from_dict({"gains": dict(beta1=b1[i], beta2=b2[i], alpha1=a1[i], alpha2=a2[i],
                                           q1=q1[i], q2=q2[i], g1=g1[i], g2=g2[i])})
        rows.append((landing_time_bound(g), t_land[i], peak[i], g))
    return sorted(rows, key=lambda x: x[0])


def verify_default() -> None:
    g = default_gains()
    f = law_numeric("corrected")
    c = P.ISP * P.G_EARTH
    args = (g.beta1, g.beta2, g.alpha1, g.alpha2, g.q1, g.q2, g.g1, g.g2)

    def rhs(t, y):
        a = f(y[:3], y[3:6], P.G_MARS, 0.0, *args)
        return np.r_[y[3:6], a + P.G_MARS, -np.linalg.norm(a) * y[6] / c]

    def landed(t, y):
        return max(np.linalg.norm(y[:3]) - 0.1, np.linalg.norm(y[3:6]) - 0.1)

    landed.terminal = True
    sol = solve_ivp(rhs, (0, 80), np.r_[P.R0, P.V0, P.M0], rtol=1e-8, atol=1e-8, max_step=0.05,
                    events=landed)
    peak = max(np.max(np.abs(rhs(t, y)[3:6] - P.G_MARS) * y[6]) for t, y in zip(sol.t, sol.y.T,
                                                                                strict=True))
    print(f"default gains: landed at {sol.t_events[0]} s, peak {peak:.0f} N, fuel "
          f"{P.M0 - sol.y[6, -1]:.1f} kg, sound bound {landing_time_bound(g):.1f} s")


if __name__ == "__main__":
    for bound, t, pk, g in screen()[:10]:
        print(f"bound {bound:8.1f} s  landed {t:5.2f} s  peak {pk:7.0f} N  "
              f"{ {k: round(float(v[0]) if hasattr(v, '__len__') else v, 6) for k, v in g.to_dict()['gains'].items()} }")  # noqa: E501
    verify_default()
