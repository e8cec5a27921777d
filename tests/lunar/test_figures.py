"""Seed 001's figures: valid PNGs, the same bytes twice, embedded in ``lgw report lunar``'s HTML
as data URIs and written beside the report.  Small runs: the Section 5 case cut to
``T_END`` seconds with the failure at ``T_FAIL`` (the report's own runs take minutes)."""

import base64
import dataclasses
import io
import re
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

T_END, T_FAIL = 20.0, 8.0  # s
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
FILES = ("lunar_tracking.png", "lunar_thrust.png", "lunar_d0e.png", "lunar_lyapunov.png")
REPORT_FILES = (*FILES, "lunar_bandwidth.png")

report_command = make_command(get_system("lunar"), "report")


def _short(opts: RunOptions | None) -> RunOptions:
    return dataclasses.replace(opts or RunOptions(), t_end=T_END, t_fail=T_FAIL)


@cache
def short_run(pointing: str = "coupled", dt: float = P.DT):
    ctx, X0 = S.section5_case(opts=_short(RunOptions(dt=dt, thrust_pointing=pointing)))
    return rk4_batch(ctx, X0, record_every=2), ctx


def _decode(png: bytes) -> np.ndarray:
    import matplotlib.image as mpimg

    return mpimg.imread(io.BytesIO(png), format="png")


def test_figures_are_valid_deterministic_pngs():
    res, ctx = short_run()
    figs = F.report_figures(res, ctx, short_run("ideal"))
    again = F.report_figures(res, ctx, short_run("ideal"))
    assert tuple(f.file for f in figs) == FILES
    for f, g in zip(figs, again, strict=True):
        assert f.png.startswith(PNG_SIGNATURE), f.file
        img = _decode(f.png)
        assert img.ndim == 3 and img.shape[0] > 300 and img.shape[1] > 800, f.file
        assert img.std() > 0.01, f.file  # not a blank canvas
        assert f.png == g.png, f"{f.file}: not the same bytes twice"
        assert f.caption == g.caption and "dt = 0.05 s" in f.caption


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
    html = (tmp_path / "report.html").read_text()
    uris = re.findall(r"src='data:image/png;base64,([A-Za-z0-9+/=]+)'", html)
    embedded = {base64.b64decode(u) for u in uris}
    for name in REPORT_FILES:
        png = (tmp_path / name).read_bytes()
        assert png.startswith(PNG_SIGNATURE)
        assert png in embedded, name
        assert name in r.output
    assert len(uris) == len(REPORT_FILES)
    assert "http:" not in html and "https:" not in html
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
