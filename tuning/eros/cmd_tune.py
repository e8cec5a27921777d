"""``lgw tune eros``: alpha, beta, p/q, k of the FTSMC (19) (sign switching) so that the proven
reaching + sliding time meets --ts over the envelope of initial offsets and the simulated peak
control stays under --u-max, with a certificate (lgw.tuning.eros.design).

Exit codes: 0 feasible (file written if --out); 2 invalid input; 3 infeasible (nothing written).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click
from lgw.tuning.options import SEED, Integer, Number

EXIT_INFEASIBLE = 3


@click.command("eros")
@click.option("--ts", type=Number(0, 1e5, lo_open=True, unit="s"), required=True,
              help="time target: reaching + sliding (s)")
@click.option("--u-max", type=Number(0, 1e3, lo_open=True, unit="m/s^2"), required=True,
              help="per-axis control limit (m/s^2)")
@click.option("--e-max", type=Number(0, 1e5, lo_open=True, unit="m"), default=10.0,
              show_default=True, help="envelope |e_i(0)| (m)")
@click.option("--v-max", type=Number(0, 1e3, unit="m/s"), default=0.5, show_default=True,
              help="envelope |e_i'(0)|, m/s")
@click.option("--dbar", type=Number(0, unit="m/s^2"), default=0.0, show_default=True,
              help="unknown disturbance bound (m/s^2); 0: D known in u_eq (14)")
@click.option("--fresh-cases", type=Integer(1, 10**6, "cases"), default=200, show_default=True,
              help="cases of the fresh acceptance campaign flown with the tuned gains")
@click.option("--seed", type=SEED, default=7, show_default=True,
              help="random seed (numpy SeedSequence); integer in [0, 2^64 - 1]")
@click.option("--out", "out_path", type=click.Path(dir_okay=False, path_type=Path),
              default=None, help="the gains TOML file to write (one file, with its "
                                 "[certificate]); checked before any work, written atomically")
def command(ts: float, u_max: float, e_max: float, v_max: float, dbar: float,
            fresh_cases: int, seed: int, out_path: Path | None) -> None:
    """Design FTSMC gains for a time target and a control limit, with a certificate."""
    from lgw.tuning.io import atomic_write_text, check_out_file

    check_out_file(out_path)
    from lgw.theory.eros.gains import gains_to_toml
    from lgw.tuning.eros.design import Request, tune

    req = Request(ts=ts, u_max=u_max, e_max=e_max, v_max=v_max, dbar=dbar,
                  fresh_cases=fresh_cases, seed=seed)
    res = tune(req)
    if "infeasible" in res:
        click.echo(f"infeasible: {res['infeasible']}", err=True)
        sys.exit(EXIT_INFEASIBLE)
    g, bd, d, fr, va = (res["gains"], res["bound"], res["design"], res["fresh"],
                        res["validation"])
    cert = {"law": "ftsmc-sign", "ts_target": ts, "u_max": u_max, "e_max": e_max,
            "v_max": v_max, "dbar": dbar, "bound_t_total": bd["t_total"],
            "bound_t_reach": bd["t_reach"], "bound_t_slide": bd["t_slide"],
            "bound_note": "proven for the continuous-time law (claims reaching-sign, "
                          "settling-ftsm); worst case at the envelope corner",
            "design_cases": d["cases"], "design_peak": d["peak"],
            "acceptance_cases": fr["cases"], "acceptance_seed": seed + 1000,
            "acceptance_peak": fr["peak"], "acceptance_t_track_max": fr["t_track_max"],
            "validation_cases": va["cases"], "validation_seed": seed + 2000,
            "validation_peak": va["peak"], "validation_t_track_max": va["t_track_max"],
            "validation_nonfinite": va["nonfinite"],
            "validation_meets": bool(va["peak"] <= u_max and va["t_track_max"] <= ts
                                     and va["nonfinite"] == 0),
            "candidates_tried": len(res["tried"])}
    click.echo(json.dumps({"gains": g.to_dict()["gains"], "certificate": cert}, indent=2))
    if out_path is not None:
        text = gains_to_toml(g, "lgw tune eros: seed 002 FTSMC gains") + "\n[certificate]\n"
        text += "\n".join(f"{k} = {json.dumps(v)}" for k, v in cert.items()) + "\n"
        atomic_write_text(out_path, text)
        click.echo(f"wrote {out_path}")
