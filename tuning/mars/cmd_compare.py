"""Seed 000 Part 1's comparison on the Table I case: every registered law beside the
fuel-optimal baseline (open loop), without disturbance and with a_p,i = A sin t for each
--dist-amplitude: outcome, landing time, fuel, peak thrust per axis, time saturated, thrust
after arrival, minimum altitude.  The same function makes the comparison section of
``lgw report mars``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lgw.sim.mars.laws import LAWS
from lgw.sim.mars.optimal import N_RANGE
from lgw.theory.errors import ParameterError
from lgw.theory.mars.parameters import THRUST_MAX_AXIS
from lgw.tuning import vocabulary as V
from lgw.tuning.commands import DOCUMENT
from lgw.tuning.options import FILE, Integer, Number, choice
from lgw.tuning.spec import option
from lgw.tuning.system import Job, Outcome

AMPLITUDE = Number(0, 1e6, lo_open=True, unit="m/s^2")
DRAGS = ("none", "physical", "printed")


def probe_tuned_file(folder: Path) -> Path:
    """A tuned file other than the shipped one, for the options test: the default bounded
    cascade with a certificate naming its law (it adds a row)."""
    from lgw.theory.mars.bounded import default_bounded
    from lgw.tuning.mars.design_bounded import write_bounded_gains

    p = Path(folder) / "probe_tuned.toml"
    write_bounded_gains(p, default_bounded(), {"law": "bounded", "request": {"tf": 101.6}},
                        "# lgw options test: a bounded-law tuned file")
    return p


@dataclass(frozen=True)
class Options(V.Outputs, out="compare.json (the --json document) and compare.png"):
    tuned: tuple = option("--tuned", FILE, (), "tuned gains file from `lgw tune mars` "
                          "(repeatable; flown with the law its certificate names) [default: "
                          "the shipped tuning/mars/data/tuned_tf90_50kN.toml]", multiple=True,
                          probe=probe_tuned_file)
    dist_amplitude: tuple = option("--dist-amplitude", AMPLITUDE, (), "A in the disturbance "
                                   "a_p,i = A sin t, m/s^2 (repeatable: one disturbed run per "
                                   "A) [default: 1 (seed 000 Fig. 3) and 20 (seed 000 (47))]",
                                   multiple=True, probe=5.0)
    amplitude: float | None = option("--amplitude", AMPLITUDE, None, "deprecated name of "
                                     "--dist-amplitude", hidden=True, probe=5.0)
    thrust_max: float = V.thrust_max(THRUST_MAX_AXIS, "per axis |F_i| <= N, for the SOCP and "
                                     "every closed loop (seed 000 Part 3's 50 kN)")
    law: tuple = option("--law", choice(tuple(LAWS)), (), "registered law to fly "
                        "(repeatable) [default: every registered law]", multiple=True,
                        probe="bounded")
    drag: str = option("--drag", choice(DRAGS), "none", "plant drag model for every row "
                       "(none: the SOCP's)")
    n: int = option("--n", Integer(N_RANGE[0], N_RANGE[1], "SOCP time steps"), 80,
                    "SOCP zero-order-hold steps", probe=40)

    def check(self) -> None:
        super().check()
        self.refuse_unless(not self.dist_amplitude, "amplitude", "is the deprecated name of "
                           "--dist-amplitude; give only --dist-amplitude")

    @property
    def amplitudes(self) -> tuple[float, ...]:
        from lgw.tuning.mars.compare import AMPLITUDES

        given = self.dist_amplitude or ((self.amplitude,) if self.amplitude is not None else ())
        return tuple(dict.fromkeys(given)) or AMPLITUDES


def inputs(opts: Options) -> list[Path]:
    return list(opts.tuned)


@dataclass(frozen=True)
class CompareJob(Job):
    gains: Any
    gains_name: str
    tuned: tuple  # (label, Gains) of every tuned file flown
    tuned_files: tuple[str, ...]  # the files of the tuned rows, for the settings record
    amplitudes: tuple[float, ...]
    thrust_max: float
    laws: tuple[str, ...]
    drag: str
    n: int
    figure: bool  # compare.png (with --out)
    deprecated: bool  # --amplitude was used

    def run(self, progress: Any) -> Outcome:
        from lgw.tuning.mars.compare import figure_png, run_comparison

        progress.stage(f"fuel-optimal baseline and {len(self.laws)} law(s), "
                       f"{len(self.amplitudes) + 1} disturbance(s) each")
        try:
            report, trajs = run_comparison(self.gains, list(self.tuned),
                                           amplitudes=self.amplitudes, drag=self.drag,
                                           n=self.n, gains_name=self.gains_name,
                                           thrust_max=self.thrust_max, laws=list(self.laws))
        except RuntimeError as exc:  # the SOCP of the baseline: the limit is too low
            raise ParameterError("--thrust-max", self.thrust_max,
                                 _thrust_range(self.n)) from exc
        settings = {"dist_amplitudes": list(self.amplitudes),
                    "thrust_max_axis": self.thrust_max, "laws": list(self.laws),
                    "drag": self.drag, "n": self.n, "tuned": list(self.tuned_files)}
        doc = {"settings": settings,
               "tuned_gains": [{"label": lab, **tg.to_dict()} for lab, tg in self.tuned],
               **report}
        files: dict[str, Any] = {"compare.json": DOCUMENT}
        if self.figure:
            progress.stage("figure")
            files["compare.png"] = figure_png(trajs, self.thrust_max)
        stderr = ["warning: --amplitude is deprecated; use --dist-amplitude"] \
            if self.deprecated else []
        return Outcome(doc, render=lambda con: _render(con, report), files=files,
                       stderr=stderr, flags=list(report.get("convergence_flags", [])))


def _thrust_range(n: int) -> str:
    """The per-axis limit below which the baseline's SOCP has no solution at tf = 30 s
    (bisection on feasibility, which only grows with the limit)."""
    from lgw.sim.mars.optimal import solve_fuel_optimal
    from lgw.theory.mars.parameters import M0, R0, V0
    from lgw.tuning.mars.compare import OPTIMAL_TF

    lo, hi = 0.0, THRUST_MAX_AXIS
    while not solve_fuel_optimal(R0, V0, M0, OPTIMAL_TF, thrust_max=hi, n=n).feasible:
        lo, hi = hi, 2 * hi
    while hi - lo > 1e-3 * hi:
        mid = 0.5 * (lo + hi)
        if solve_fuel_optimal(R0, V0, M0, OPTIMAL_TF, thrust_max=mid, n=n).feasible:
            hi = mid
        else:
            lo = mid
    return (f"must be >= {hi:.6g} N: below it the fuel-optimal baseline has no solution at "
            f"the comparison's tf = {OPTIMAL_TF:g} s (seed 000 Part 1)")


def _render(con: Any, report: dict[str, Any]) -> None:
    from lgw.tuning.mars.compare import COLUMNS, table_cells
    from lgw.tuning.tables import result_table

    amps = ", ".join(f"{a:g} sin t" for a in report["amplitudes"])
    title = (f"Seed 000 Part 1 comparison, Table I case, tf = {report['optimal_tf']:g} s for the "
             f"optimum, per-axis thrust limit {report['thrust_max_axis']:g} N, drag "
             f"{report['drag']!r}, disturbance 0 or a_p,i = {amps}")
    result_table(con, title, [name for name, _ in COLUMNS],
                 [[c.strip() for c in row] for row in table_cells(report)])
    con.print(report["note"], markup=False, highlight=False)
    con.print(report["why"], markup=False, highlight=False)
    if "convergence" in report:  # the verdict; unconverged numbers follow as warnings
        con.print(report["convergence"].split("; UNCONVERGED")[0], markup=False,
                  highlight=False)


def plan(opts: Options, system: Any) -> CompareJob:
    from lgw.tuning.mars.compare import (
        TUNED_DEFAULT,
        cannot_fly,
        law_gain_sets,
        tuned_law,
        tuned_sets,
    )
    from lgw.tuning.mars.gains_file import load_tuned
    from lgw.tuning.mars.gainset import resolve

    gains = resolve(opts.gains)
    for p in opts.tuned:  # validated before anything runs or is written
        load_tuned(p)
    tuned = tuned_sets(list(opts.tuned))
    for p, (_, tg) in zip(opts.tuned, tuned, strict=False):  # a file no law would fly
        if tuned_law(tg) not in LAWS:
            raise ParameterError(f"--tuned {p} certificate.law", tuned_law(tg),
                                 f"must be a registered law: {', '.join(LAWS)}")
    laws = tuple(dict.fromkeys(opts.law)) or tuple(LAWS)
    for law in laws:  # each law's gains (e.g. a [bounded] table) checked before any run
        for _, g in law_gain_sets(law, gains, tuned, ""):
            cannot_fly(law, g)  # raises on bad input; other failures become a table row
    paths = list(opts.tuned) or [TUNED_DEFAULT]
    flown = [(str(p), (lab, tg)) for p, (lab, tg) in zip(paths, tuned, strict=True)
             if tuned_law(tg) in laws]
    name = "default gains" if opts.gains is None else f"gains {opts.gains.name}"
    return CompareJob(gains, name, tuple(t for _, t in flown), tuple(p for p, _ in flown),
                      opts.amplitudes, opts.thrust_max, laws, opts.drag, opts.n,
                      opts.out is not None,
                      opts.amplitude is not None)

