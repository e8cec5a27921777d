"""The simulated parts of seed 001's report: the reference, the Section 5 runs, the bounds
table with measured L2 norms."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from lgw.sim.lunar.batch import l2_norm
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.sim.lunar.reference import open_loop_full_model, reference
from lgw.sim.lunar.scenario import scenario_claims, section5_case, section5_runs, summarize
from lgw.theory.lunar import parameters as P
from lgw.theory.lunar.bounds import attitude_bounds, lambda_gain_bounds, orbit_bounds
from lgw.theory.lunar.gains import Gains
from lgw.theory.report import Section, fmt


def reference_section() -> Section:
    ref = reference()
    d = ref.to_dict()
    ol = open_loop_full_model(ref)
    rows = tuple((k, fmt(v) if not isinstance(v, list) else str([fmt(x) for x in v]))
                 for k, v in {**d, **{f"open loop (1): {k}": v for k, v in ol.items()}}.items())
    return Section("Reference trajectory (3)-(4): linear-tangent BVP",
                   columns=("quantity", "value"), rows=rows, paragraphs=(
                       "Simplified model of seed 001 Section 2 with constant T_d = 24 kN, "
                          "solved by scipy solve_bvp (initial guess by single shooting, whose "
                          "a2, a3, t_f are listed beside). The open-loop rows fly the full "
                          "model (1) with the same steering and thrust.",))


REF_TOL = {"height_m": 1.0, "speed_m_s": 0.01}  # chosen: "meets the boundary conditions"


def reference_claim():
    """Seed 001 (3)-(4) judged: the linear-tangent steering with a_i and t_f solved from the
    boundary conditions lands the simplified model at (h_f, V_f).  The BVP solution is
    re-flown by solve_ivp (an independent route: single shooting with the solved constants);
    the full model (1) flown open loop with the same steering gives the simplified model's
    miss (numbers)."""
    from lgw.sim.lunar.reference import simplified_rhs
    from lgw.theory.evidence import Claim, Search, Step, Witness
    from scipy.integrate import solve_ivp

    ref = reference()
    y0 = np.array([P.R_MOON + P.H0, *P.V0, P.M0])
    end = ref.state(ref.tf)
    bvp_margin = min(REF_TOL["height_m"] - abs(end[0] - P.R_MOON - P.HF),
                     REF_TOL["speed_m_s"] - float(np.linalg.norm(end[1:4] - P.VF)))
    sol = solve_ivp(lambda t, y: simplified_rhs(t, y, ref.a1, ref.a2, ref.a3), (0.0, ref.tf),
                    y0, method="DOP853", rtol=1e-12, atol=1e-9)
    y = sol.y[:, -1]
    shoot = {"height_m": float(y[0] - P.R_MOON - P.HF),
             "speed_m_s": float(np.linalg.norm(y[1:4] - P.VF))}
    shoot_margin = min(REF_TOL["height_m"] - abs(shoot["height_m"]),
                       REF_TOL["speed_m_s"] - shoot["speed_m_s"])
    w = None
    if bvp_margin < 0:
        w = Witness({"a1": ref.a1, "a2": ref.a2, "a3": ref.a3, "tf": ref.tf}, bvp_margin,
                    "solve_bvp's dense solution at t_f", shoot_margin,
                    "single shooting (solve_ivp DOP853 rtol 1e-12) with the solved constants")
    step = Step(f"the steering (3) with a1, a2, a3, t_f solved from the boundary conditions "
                f"lands the simplified model within {REF_TOL['height_m']} m of h_f and "
                f"{REF_TOL['speed_m_s']} m/s of V_f (solve_bvp, re-flown by single shooting)",
                Search({"boundary conditions": f"h0 = {P.H0} m, V0 = {P.V0.tolist()} m/s -> "
                        f"h_f = {P.HF} m, V_f = 0", "tolerance": REF_TOL},
                       "scipy solve_bvp (tol 1e-6) and single shooting (DOP853)", 2,
                       min(bvp_margin, shoot_margin), {"shooting_miss": shoot}, None, w))
    ol = open_loop_full_model(ref)
    return Claim("reference-3-4", "(3), (4)", "The linear-tangent reference lands",
                 "the constants a_i of (3) can be solved from the boundary conditions of "
                 "height and velocity, giving the closed-form landing trajectory (4)",
                 f"solved as a BVP on the simplified model: a1 = {ref.a1:.6g}, a2 = "
                 f"{ref.a2:.6g} 1/s, a3 = {ref.a3:.6g}, t_f = {ref.tf:.6g} s; single shooting "
                 f"misses h_f by {shoot['height_m']:.3g} m and V_f by {shoot['speed_m_s']:.3g} "
                 f"m/s; the full model (1) flown open loop misses by "
                 f"{ol['height_miss_final_m']:.3g} m (the terms the simplification drops); the "
                 "coefficients of (4) are never printed, so (4) itself is not checkable",
                 (step,), scope="scenario",
                 numbers={**ref.to_dict(), "shooting_miss": shoot, "open_loop_full_model": ol})


def run_scenario(fig_path: Path | None = None):
    """The Section 5 claims, the scenario section (table and figures) and the measured run.
    ``fig_path``: where the older one-file overview goes (None: not made)."""
    from lgw.sim.lunar.batch import rk4_batch
    from lgw.tuning.lunar.figures import report_figures, section5_figure

    claims = scenario_claims()
    ctx, res, s = section5_runs()
    ctx_i, X0 = section5_case(opts=RunOptions(thrust_pointing="ideal"))
    res_i = rk4_batch(ctx_i, X0, record_every=2)
    si = summarize(res_i, ctx_i)
    if fig_path is not None:
        section5_figure(res, fig_path, ideal=res_i)
    figs = report_figures(res, ctx, (res_i, ctx_i))
    keys = ("eh_final_m", "max_abs_eh_m", "max_abs_eh_after_failure_m",
            "thrust_cmd_max_after_failure_N", "orbit_saturated_s",
            "orbit_saturated_after_failure_s", "torque_saturated_s", "d0e_orbit_final",
            "d0e_attitude_final", "min_abs_eq0", "B0du_orbit_L2", "B0du_attitude_L2")
    rows = [(k, fmt(s[k]), fmt(si[k])) for k in keys]
    rows.append(("|e_v(t_f)| m/s", fmt(float(np.linalg.norm(s["ev_final_m_s"]))),
                 fmt(float(np.linalg.norm(si["ev_final_m_s"])))))
    rows.append(("flagged", str(s["flagged"] or "no"), str(si["flagged"] or "no")))
    sec = Section(f"Section 5 scenario (RK4, dt = {P.DT:g} s)",
                  columns=("quantity", "coupled (thrust along the body axis)",
                           "ideal pointing (thrust along the command)"), rows=tuple(rows),
                  paragraphs=("Coupled: the thrust direction (2) comes from the simulated "
                              "attitude (27). "
                   "Ideal pointing: the thrust follows the orbit command, the attitude loop "
                   "flies decoupled (the paper treats (22) with u_o as the input).",
                   FIGURES_NOTE), figures=tuple(figs))
    return claims, sec, (res, ctx)


FIGURES_NOTE = ("Figures: lgw.tuning.lunar.figures from the two runs of this table (coupled "
                "solid, ideal pointing dashed); each caption states what was flown.  The same "
                "figures come from `lgw simulate lunar ... --plot DIR`.")


def bounds_table(g: Gains, measured=None, run_gains: Gains | None = None):
    """The bounds of the gain set ``g``; with ``measured`` (a run and its context, flown at
    ``run_gains``, default ``g``), the run's L2 norms beside the (18) bounds of the gains it
    was flown with."""
    ob, ab = orbit_bounds(g.orbit).to_dict(), attitude_bounds(g.attitude, 1.0).to_dict()
    note = ("Attitude f1bar and H-infinity gains at eq0 = 1 (the target); along a run the "
            "attitude f1bar is lambda_min(K1) min eq0^2 / 4.")
    if measured is not None:
        res, ctx = measured
        t, o = res.t, res.out
        rg = run_gains or g
        rb = {"orbit": orbit_bounds(rg.orbit).to_dict(),
              "attitude": attitude_bounds(rg.attitude, 1.0).to_dict()}
        for col, key, l1, l2, eq0 in (("orbit", "B0du_o", "lam1o", "lam2o", None),
                                      ("attitude", "B0du_a", "lam1a", "lam2a", True)):
            b = ob if col == "orbit" else ab
            w = float(l2_norm(t, o[key])[0])
            f1b = rb[col]["f1bar"]
            if eq0:
                f1b = float(np.min(np.abs(o["eq"][:, 0, 0]))) ** 2 / 4 * float(
                    np.linalg.eigvalsh(rg.attitude.K1).min())
            c1, c2 = lambda_gain_bounds(f1b, rb[col]["f2bar"])
            b.update({"B0du_L2": w, "lambda1_L2": float(l2_norm(t, o[l1])[0]),
                      "lambda1_L2_bound": c1 * w,
                      "lambda2_L2": float(l2_norm(t, o[l2])[0]), "lambda2_L2_bound": c2 * w})
        note += (" Measured rows: the coupled Section 5 run on [0, t_f]; the attitude bound "
                 "uses f1bar from the run's min |eq0|.")
        if run_gains is not None and run_gains.to_dict() != g.to_dict():
            note += (" The Section 5 run flies the paper's stated gains (its claims judge the "
                     "paper's scenario): the measured rows and their (18) bounds are for those "
                     "gains, the rows above for this gain set.")
    return {"orbit": ob, "attitude": ab}, note
