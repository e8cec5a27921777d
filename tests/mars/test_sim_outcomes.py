"""Every case ends in exactly one outcome (lgw.sim.results), the same in RK4, dopri5 and the
reference mode for the same state."""

from __future__ import annotations

import numpy as np
from lgw.sim.mars.batch import simulate_batch
from lgw.sim.mars.reference import simulate_reference
from lgw.sim.results import OUTCOMES, classify, counts
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import M0, M_DRY, R0, V0

G = default_gains()


def _names(res) -> list[str]:
    code, t = res.outcomes()
    assert len(code) == len(res) and np.all(np.isfinite(t) | (code == 1))
    return [OUTCOMES[k] for k in code]


def test_same_outcome_in_every_integrator() -> None:
    r0 = np.array([R0, R0, [0.0, 1000.0, 1500.0]])
    v0 = np.array([V0, V0, [10.0, -15.0, -75.0]])
    m0 = np.array([M0, M_DRY + 60.0, M0])  # lands; runs dry first; r_x = 0 with v_x != 0
    want = ["landed", "propellant_exhausted", "nonfinite"]
    for kw in ({}, {"method": "dopri5"}):
        assert _names(simulate_batch(r0, v0, m0, G, **kw)) == want, kw
    assert _names(simulate_reference(r0, v0, m0, G)) == want
    # a horizon too short to land: "horizon" at t_max in all three
    for res in (simulate_batch(r0[:1], v0[:1], m0[:1], G, t_max=10.0),
                simulate_batch(r0[:1], v0[:1], m0[:1], G, t_max=10.0, method="dopri5"),
                simulate_reference(r0[:1], v0[:1], m0[:1], G, t_max=10.0)):
        code, t = res.outcomes()
        assert OUTCOMES[code[0]] == "horizon" and t[0] == 10.0
    lim = simulate_batch(r0[:1], v0[:1], m0[:1], G, method="dopri5", max_steps=5)
    assert _names(lim) == ["step_limit"]


def test_times_and_precedence() -> None:
    res = simulate_batch(np.array([R0, R0]), np.array([V0, V0]), np.array([M0, M_DRY + 60.0]),
                         G)
    code, t = res.outcomes()
    assert t[0] == res.landing_time[0] and t[1] == res.t_end[1] < res.info["t_max"]
    # a case that landed and later ran dry (stop="t_max") counts as landed, once
    code, t = classify(landed=[True, False], fuel_exhausted=[True, True],
                       nonfinite=[True, True], step_limit=[False, True],
                       landing_time=[3.0, np.nan], t_end=[9.0, 9.0], stop_at_outcome=False)
    assert code.tolist() == [0, 1] and t[0] == 3.0 and np.isnan(t[1])
    assert counts(code) == {"landed": 1, "propellant_exhausted": 1, "nonfinite": 0,
                            "step_limit": 0, "horizon": 0}
