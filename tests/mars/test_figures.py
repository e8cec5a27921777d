"""Seed 000's figures: deterministic PNGs, the limit drawn, legends shared, data cross-checked.

The figure functions return PNG bytes; to look inside, ``png_bytes`` is wrapped so that the
matplotlib figure is kept before it is saved."""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner
from lgw.theory.mars.gains import default_gains
from lgw.theory.mars.parameters import THRUST_MAX_AXIS
from lgw.tuning.cli import cli
from lgw.tuning.mars import figures as F

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def small_campaign():
    return F.campaign(default_gains(), F.FigureOptions(cases=6, seed=3))


@pytest.fixture
def kept(monkeypatch):
    """The matplotlib figures passed to png_bytes (by this module and by compare)."""
    import lgw.tuning.figures as TF

    figs = []
    real = TF.png_bytes

    def keep(fig, dpi=TF.DPI):
        figs.append(fig)
        return real(fig, dpi)
    monkeypatch.setattr(F, "png_bytes", keep)
    monkeypatch.setattr(TF, "png_bytes", keep)
    return figs


def _limit_lines(ax, y):
    return [ln for ln in ax.get_lines() if "limit" in ln.get_label()
            and np.allclose(ln.get_ydata(), y)]


def test_campaign_figures_are_deterministic_pngs(small_campaign) -> None:
    a = F.trajectories_figure(small_campaign, "t")
    b = F.trajectories_figure(small_campaign, "t")
    assert a[:8] == PNG and a == b
    d = F.dispersion_figure(small_campaign, "d", 10.0)
    assert d[:8] == PNG and d == F.dispersion_figure(small_campaign, "d", 10.0)


def test_thrust_figure_draws_the_limit_in_every_panel_and_one_legend(kept) -> None:
    g = default_gains()
    F.thrust_figure([("unlimited", F.single_case(g))], "t")
    fig = kept[-1]
    axes = fig.get_axes()
    assert len(axes) == 3
    for ax in axes:
        assert _limit_lines(ax, THRUST_MAX_AXIS / 1e3), ax.get_title()
    assert len(fig.legends) == 1
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "unlimited" in labels and any("limit" in s for s in labels)


def test_compare_figure_has_the_limit_and_a_shared_legend(kept) -> None:
    from lgw.tuning.mars.compare import figure_png

    t = np.linspace(0.0, 10.0, 11)
    trajs = [{"label": lab, "disturbance": dist, "dist_amplitude": amp, "ended": "landed",
              "t": t, "r": np.ones((11, 3)), "F": np.full((11, 3), 1e4)}
             for lab in ("A", "B") for dist, amp in (("none", 0.0), ("sin", 1.0))]
    assert figure_png(trajs, THRUST_MAX_AXIS)[:8] == PNG
    fig = kept[-1]
    thrust_panels = [ax for ax in fig.get_axes() if "F_i" in ax.get_ylabel()]
    assert len(thrust_panels) == 2
    for ax in thrust_panels:
        assert _limit_lines(ax, THRUST_MAX_AXIS / 1e3)
    assert len(fig.legends) == 1
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels[:2] == ["A", "B"] and any("limit" in s for s in labels)
    assert all(ax.get_legend() is None for ax in fig.get_axes())


def test_settling_sweep_stays_inside_the_sound_bounds() -> None:
    """Fig. 6 data: every simulated first entry happens before the exact bounds (T2* for s2,
    T2* + T1* for s1) -- the sound bounds of lgw.theory.mars.bounds hold in the simulator."""
    sw = F.settling_sweep(default_gains(), F.FigureOptions(sweep=(-8000.0, -4000.0, -1000.0)))
    b = sw["bounds_x"]
    assert sw["t_max"] >= b["landing_time_bound"]
    for row in sw["rows"]:
        assert 0.0 < row["t_s2x"] <= b["T2_exact"]
        assert 0.0 < row["t_s1x"] <= b["landing_time_bound"]
    assert F.settling_figure(sw, "fig6")[:8] == PNG


def test_surfaces_match_the_printed_definition(small_campaign) -> None:
    """s2 along a run, from the lambdified (21), against (21) written out in numpy."""
    g = default_gains()
    s1, s2 = F.surfaces(g, small_campaign, 2)
    tr = small_campaign.trajectory
    ok = np.isfinite(tr["r"][2, :, 0])
    r, v = tr["r"][2][ok], tr["v"][2][ok]
    for k in range(3):
        ax = g.axis(k)
        a1 = np.abs(r[:, k]) ** ax["q1"] * np.sign(r[:, k])
        a2 = np.abs(r[:, k]) ** ax["q2"] * np.sign(r[:, k])
        expect = v[:, k] + ax["beta1"] * a1 + ax["beta2"] * a2
        np.testing.assert_allclose(s2[:, k], expect, rtol=1e-12, atol=1e-9)
    np.testing.assert_array_equal(s1, r)


def test_final_states_are_where_each_case_stopped(small_campaign) -> None:
    """Landed cases end at the landing point, the others where the run stopped (inside the
    last step: the recorded trajectory's last node is within one step's travel of it)."""
    res = small_campaign
    r_end, v_end = F.final_states(res)
    tr = res.trajectory
    for i in range(len(res)):
        ok = np.isfinite(tr["r"][i, :, 0])
        want = res.r_land[i] if res.landed[i] else res.y_end[i, :3]
        np.testing.assert_array_equal(r_end[i], want)
        last_r, last_v = tr["r"][i][ok][-1], tr["v"][i][ok][-1]
        travel = res.dt * (np.linalg.norm(last_v) + np.linalg.norm(v_end[i]))
        assert np.linalg.norm(last_r - r_end[i]) <= travel + 1e-9


def test_simulate_plot_writes_the_figures(tmp_path) -> None:
    res = CliRunner().invoke(cli, ["simulate", "mars", "--plot", str(tmp_path / "p")],
                             catch_exceptions=False)
    assert res.exit_code == 0, res.output
    # the folder also holds lgw's output marker (it may replace the folder as a whole)
    names = sorted(p.name for p in (tmp_path / "p").iterdir() if not p.name.startswith("."))
    assert names == ["phase_s1_s2.png", "thrust.png"]
    assert (tmp_path / "p" / ".lgw-output.json").is_file()
    assert all((tmp_path / "p" / n).read_bytes()[:8] == PNG for n in names)


@pytest.mark.slow
def test_report_with_figures_is_self_contained(tmp_path) -> None:
    from tests.test_report_html import check_html

    res = CliRunner().invoke(cli, ["report", "mars", "--no-sim", "--figures", "--out",
                                   str(tmp_path)], catch_exceptions=False)
    assert res.exit_code == 0, res.output
    text = (tmp_path / "report.html").read_text()
    page = check_html(text, [])
    assert len(page.imgs) == 5
    for name in ("mc_trajectories", "mc_dispersion", "settling_fig6", "thrust", "phase_s1_s2"):
        assert (tmp_path / f"{name}.png").is_file() and f"id='fig-{name.replace('_', '-')}'" \
            in text
