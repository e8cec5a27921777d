"""Seed 001's figures: valid PNGs, the same bytes twice, embedded in ``lgw report lunar``'s HTML
as data URIs and written beside the report.  Small runs: the Section 5 case cut to
``T_END`` seconds with the failure at ``T_FAIL`` (the report's own runs take minutes)."""

import dataclasses
from functools import cache

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.sim.lunar import scenario as S
from lgw.sim.lunar.batch import rk4_batch
from lgw.sim.lunar.closed_loop import RunOptions
from lgw.theory.lunar import parameters as P
from lgw.tuning.commands import make_command
from lgw.tuning.lunar import figures as F
from lgw.tuning.system import get_system

from tests.figures import PNG_SIGNATURE, assert_deterministic_pngs, assert_report_embeds

T_END, T_FAIL = 10.0, 4.0  # s (the failure mid-run; long enough to see the transient settle)
FILES = ("lunar_tracking.png", "lunar_thrust.png", "lunar_d0e.png", "lunar_lyapunov.png")
REPORT_FILES = (*FILES, "lunar_bandwidth.png")

report_command = make_command(get_system("lunar"), "report")


def _short(opts: RunOptions | None) -> RunOptions:
    return dataclasses.replace(opts or RunOptions(), t_end=T_END, t_fail=T_FAIL)


@cache
def short_run(pointing: str = "coupled", dt: float = P.DT):
    ctx, X0 = S.section5_case(opts=_short(RunOptions(dt=dt, thrust_pointing=pointing)))
    return rk4_batch(ctx, X0, record_every=2), ctx


def test_figures_are_valid_deterministic_pngs():
    res, ctx = short_run()
    figs = F.report_figures(res, ctx, short_run("ideal"))
    assert_deterministic_pngs(figs, F.report_figures(res, ctx, short_run("ideal")), FILES,
                              (300, 800))
    assert all("dt = 0.05 s" in f.caption for f in figs)


def test_v2_is_the_parts_plus_the_estimation_term():
    """V2 (12) as drawn: the generated law's (|z1|^2+|z2|^2)/2 plus (d0e - D)^2/(2q), and the
    attitude D recomputed independently from the disturbance torque of the plant."""
    from lgw.sim.lunar.plant import disturbance_torque

    res, ctx = short_run()
    v2 = F.lyapunov_v2(res, ctx)
    d_a = np.array([np.linalg.norm(disturbance_torque(t)[:, 0] / P.J_DIAG) for t in res.t])
    want = res.out["V2a_part"][:, 0] + (res.out["d0e_attitude"][:, 0] - d_a) ** 2 / (
        2 * ctx.ga["q"][0])
    np.testing.assert_allclose(v2["attitude"], want, rtol=1e-12)
    assert np.all(v2["orbit"] >= res.out["V2o_part"][:, 0])


def test_report_embeds_the_figures(tmp_path, monkeypatch):
    """``lgw report lunar`` end to end on the short runs: every figure is in report.html as a
    data URI holding exactly the PNG written beside the report."""

    def case(gains=None, opts=None, n=1):
        return original_case(gains, _short(opts), n)

    from lgw.tuning.lunar import design as D

    original_case = S.section5_case
    monkeypatch.setattr(S, "section5_case", case)  # every Section 5 flight of the report
    monkeypatch.setattr(S, "_FLIGHTS", {})  # no flight cached by another test
    monkeypatch.setattr(D, "WN_GRID", (25.0, 30.0))  # the sweep: two full runs per wn
    r = CliRunner().invoke(report_command, ["--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    assert len(assert_report_embeds(tmp_path, REPORT_FILES, r.output)) == len(REPORT_FILES)
    md = (tmp_path / "report.md").read_text()
    assert all(f"]({name})" in md for name in REPORT_FILES)


@pytest.mark.parametrize("bad", [0.0])
def test_failure_time_default_is_half_tf(bad):
    ctx, _ = S.section5_case()
    assert F.failure_time(ctx) == pytest.approx(ctx.tf / 2)
    ctx2, _ = S.section5_case(opts=RunOptions(t_fail=bad))
    assert F.failure_time(ctx2) == bad


def test_simulate_plot_writes_the_figures(tmp_path):
    """``lgw simulate lunar --plot DIR`` on a short run writes the four PNGs; a file given as
    DIR is refused before any work (exit 2, nothing written)."""
    from tests.test_cli_conventions import run_lgw

    d = tmp_path / "plots"
    r = run_lgw(["simulate", "lunar", "--t-max", "6", "--t-fail", "3", "--plot", str(d)])
    assert r.code == 0, r.stderr
    for name in FILES:
        assert (d / name).read_bytes().startswith(PNG_SIGNATURE), name
    f = tmp_path / "a_file"
    f.write_text("x")
    r = run_lgw(["simulate", "lunar", "--t-max", "6", "--plot", str(f)])
    assert r.code == 2 and f.read_text() == "x"
