"""Tables of seed 002's report computed outside ``theory``: the scenario and campaign (Table 2
analogue), the settling-time table, the cubic coefficients, the gravity fit, the coverage."""

from __future__ import annotations

from lgw.theory.eros import bounds as B
from lgw.theory.eros import parameters as P
from lgw.theory.eros import reference as REF
from lgw.theory.eros.claims import ode_settling_time
from lgw.theory.report import Section

SETTLING_TABLE = ((1, 3, 1.0, 1.0, 5.0), (3, 5, 1.0, 1.0, 5.0), (3, 5, 0.5, 2.0, 0.01),
                  (3, 5, 1.0, 1.0, 100.0), (5, 7, 2.0, 0.3, 1.0), (7, 9, 10.0, 0.05, 2.0))


def settling_section() -> Section:
    rows = []
    for p, q, a, b, e0 in SETTLING_TABLE:
        r = p / q
        rows.append(tuple(f"{x:.6g}" for x in (
            p / q, a, b, e0, B.ts_tsm(e0, b, r), B.ts_tsm_printed(e0, b, p, q),
            ode_settling_time(e0, 0.0, b, r), B.ts_ftsm(e0, a, b, r),
            B.ts_ftsm_printed(e0, a, b, p, q), ode_settling_time(e0, a, b, r))))
    return Section("Settling times: derived, printed, ODE", (
        "TSM = surface (5), FTSM = surface (6); ODE: solve_ivp (DOP853, rtol 1e-11) to "
        "|e| = 1e-9 |e0| plus the tail by quadrature.  The printed times are negative.",),
        ("p/q", "alpha", "beta", "e0 m", "TSM derived", "TSM printed", "TSM ODE",
         "FTSM derived", "FTSM printed (7)", "FTSM ODE"), tuple(rows))


def cubic_section() -> Section:
    ex, pr = REF.exact_coefficients(), REF.coefficients(printed=True)
    miss = REF.endpoint_miss()
    rows = []
    for i, ax in enumerate(REF.AXES):
        for j in (2, 3):
            rows.append((ax, f"c{j}", str(ex[i][j]), f"{float(ex[i][j]):.6e}", f"{pr[i, j]:.3e}"))
    return Section("Cubic reference (9)-(10): exact against printed", (
        "Endpoint miss of the printed coefficients at t = 8000 s: position "
        + ", ".join(f"{m:+.3f}" for m in miss["position_m"]) + " m, velocity "
        + ", ".join(f"{v:+.3e}" for v in miss["velocity_m_s"]) + " m/s (x, y, z).",),
        ("axis", "coefficient", "exact (rational)", "exact", "printed"), tuple(rows))


def gravity_section() -> Section:
    rows = (("mu = M1/M", f"{P.TWO_POINT_MU:.5f}"), ("r1 (m)", str(P.TWO_POINT_P1.tolist())),
            ("r2 (m)", str(P.TWO_POINT_P2.tolist())),
            ("residual rms / max (relative)", f"{P.TWO_POINT_FIT_RMS} / {P.TWO_POINT_FIT_MAX}"),
            ("landing point altitude above the shape (m)", f"{P.LANDING_ALTITUDE}"))
    return Section("Two-mass-point gravity fitted to the polyhedron", (
        "Fit: benchmarks/eros_fit_gravity.py (240 points on and within 500 m of the reference, "
        "total mass fixed at the measured 6.687e15 kg; polyhedron: the Eros shape model scaled "
        "to 2503 km^3, uniform density).",), ("quantity", "value"), rows)


def table2_sections(scen: dict, mc_table: list[dict], n: int) -> list[Section]:
    keys = ("t_reach_max", "t_track_all", "iae", "u_peak", "effort", "chatter")
    cols = ("variant", "reach s", "tracked s", "IAE m", "peak m/s^2", "effort m/s", "TV(u)")
    srows = tuple((k, *(f"{v[kk]:.4g}" for kk in keys)) for k, v in scen.items())
    def g4(x: float | None) -> str:  # None: no tracked or horizon case to summarise
        return "-" if x is None else f"{x:.4g}"

    mrows = tuple((r["variant"], *(f"{g4(r[kk + '_mean'])} / {g4(r[kk + '_max'])}"
                                   for kk in keys)) for r in mc_table)
    note = ("IAE (the Table 2 analogue): sum over the 0.01 s samples and the three axes of "
            "|e_i| (m); tracked: |e_i| <= 0.01 m for the rest of the run on every axis; TV(u): "
            "total variation of the held control, summed over axes.  Paper (Table 2, '/' read "
            "as the decimal point): fuzzy 113.4, FTSMC 139.6, PD 244.8 for an unpublished offset.")
    return [Section("Scenario (15 s, offset 5 m per axis, known D)", (note,), cols, srows),
            Section(f"Monte Carlo campaign ({n} cases): mean / max over the tracked and "
                    "horizon cases (crashed and non-finite ones counted apart)", (note,), cols,
                    mrows)]


FIGURES_NOTE = ("Made by lgw.tuning.eros.figures: the scenario re-flown with histories (the same "
                "options as the table above) and the campaign's per-case times; each caption "
                "states what was flown.  The same kinds come from "
                "`lgw simulate eros ... --plot DIR`.")


def figures_section(g, base, mc, n: int, seed: int) -> Section:
    """The six variants side by side (scenario) and the Monte Carlo times, as figures."""
    from lgw.tuning.eros.figures import report_figures

    return Section("Figures: the six controllers side by side", (FIGURES_NOTE,), (), (),
                   figures=tuple(report_figures(g, base, mc, n, seed)))
