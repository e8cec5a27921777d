"""``lgw verify eros``: property campaign: every simulated case of the FTSMC (sign switching)
tracks each axis no later than its proven reaching + sliding bound
(lgw.theory.eros.bounds.axis_time_bound for that case's own e0, e0').

The bound is for the continuous-time law reaching e = 0; the simulation is the 0.01 s
sampled-data loop and "tracked" is |e_i| <= TRACK_TOL for the rest of the run, which the
continuous-time trajectory meets before e = 0: a violation therefore means the sampled loop is
slower than the continuous-time theory by more than its tolerance allows.
"""

from __future__ import annotations

from pathlib import Path

import click
from lgw.tuning.eros.options import resolve_gains
from lgw.tuning.io import json_document
from lgw.tuning.options import SEED, Integer, choice, gains_option


@click.command("eros")
@gains_option
@click.option("--cases", type=Integer(1, 10**6, "cases"), default=200, show_default=True,
              help="Monte Carlo initial offsets flown")
@click.option("--seed", type=SEED, default=11, show_default=True,
              help="random seed (numpy SeedSequence); integer in [0, 2^64 - 1]")
@click.option("--disturbance", type=choice(("known", "unknown")), default="known",
              show_default=True,
              help="known (bound with dbar = 0) or unknown (dbar = the chosen DIST_AMP)")
@click.option("--json", "as_json", is_flag=True,
              help="print one JSON object (strict, with lgw_version)")
def command(gains_path: Path | None, cases: int, seed: int, disturbance: str,
            as_json: bool) -> None:
    """Observed tracking times of a Monte Carlo campaign against the proven per-case bound."""
    import numpy as np
    from lgw.sim.eros.batch import SimOptions, metrics, simulate
    from lgw.sim.eros.campaign import offsets
    from lgw.theory.eros import bounds as B
    from lgw.theory.eros import parameters as P
    from lgw.theory.errors import ParameterError

    g = resolve_gains(gains_path)
    if cases < 1:
        raise ParameterError("--cases", cases, "must be >= 1")
    if disturbance not in ("known", "unknown"):
        raise ParameterError("--disturbance", disturbance, "known or unknown")
    dbar = 0.0 if disturbance == "known" else P.DIST_AMP
    e0, ed0, ph = offsets(cases, seed)
    bound = np.array([[B.axis_time_bound(e0[i, a], ed0[i, a], g, dbar)["t_total"]
                       for a in range(3)] for i in range(cases)])
    opts = SimOptions(law="ftsmc", switch="sign", disturbance=disturbance,
                      t_final=float(np.ceil(bound.max() + 2.0)))
    m = metrics(simulate(e0, ed0, g, opts, ph))
    t_obs = np.where(np.isnan(m["t_track"]), np.inf, m["t_track"])
    margin = bound - t_obs
    i, a = np.unravel_index(np.argmin(margin), margin.shape)
    out = {"cases": cases, "seed": seed, "disturbance": disturbance, "dbar": dbar,
           "violations": int(np.sum(margin < 0)), "worst_margin_s": float(margin[i, a]),
           "worst_case": {"e0": e0[i].tolist(), "ed0": ed0[i].tolist(), "axis": "xyz"[a],
                          "bound_s": float(bound[i, a]), "observed_s": float(t_obs[i, a])},
           "mean_bound_over_observed": float(np.mean(bound / t_obs)),
           "nonfinite": int(np.sum(m["nonfinite"]))}
    if as_json:
        click.echo(json_document({"command": "verify eros", **out}, indent=2))
        return
    click.echo(f"{cases} cases ({disturbance} D): {out['violations']} violations of the proven "
               f"per-case bound; worst margin {out['worst_margin_s']:.3f} s "
               f"(bound {out['worst_case']['bound_s']:.3f} s, observed "
               f"{out['worst_case']['observed_s']:.3f} s); mean bound/observed "
               f"{out['mean_bound_over_observed']:.2f}")
