"""Seed 002's figures: valid PNGs, the same bytes twice, the chattering bars equal to the
report's table, and ``lgw report eros`` embedding them in its HTML as data URIs (a small
campaign)."""

import json
from dataclasses import replace

import numpy as np
from click.testing import CliRunner
from lgw.sim.eros.batch import SimOptions
from lgw.sim.eros.campaign import monte_carlo, scenario
from lgw.tuning.commands import make_command
from lgw.tuning.eros import figures as F
from lgw.tuning.eros.options import resolve_gains
from lgw.tuning.system import get_system

from tests.figures import PNG_SIGNATURE, assert_deterministic_pngs, assert_report_embeds

FILES = ("eros_tracking.png", "eros_control.png", "eros_chatter.png", "eros_mc_times.png")
SHORT = SimOptions(t_final=3.0)  # s: the variants' first seconds (reaching, first chattering)

report_command = make_command(get_system("eros"), "report")


def test_figures_are_valid_deterministic_pngs():
    g = resolve_gains(None)
    mc = monte_carlo(g, 5, 3, SHORT)
    figs = F.report_figures(g, SHORT, mc, 5, 3)
    assert_deterministic_pngs(figs, F.report_figures(g, SHORT, mc, 5, 3), FILES, (300, 700))


def test_chatter_bars_are_the_tables_numbers():
    """The bars (re-flown with histories here) equal the summaries lgw.sim.eros.campaign flies
    for the report's scenario table, variant by variant."""
    g = resolve_gains(None)
    runs = F.scenario_runs(g, SHORT)
    bars = F._chatter(runs)
    table = scenario(g, SHORT)
    assert set(bars) == set(table) == set(F.NAMES)
    for name in F.NAMES:
        np.testing.assert_allclose(bars[name], table[name]["chatter"], rtol=1e-12)
    assert bars["pdsmc-sign"] > 10 * bars["pdsmc-tanh"]  # sgn chatters once on the surface


def test_report_embeds_the_figures(tmp_path, monkeypatch):
    """``lgw report eros`` end to end (a 3 s horizon, 3 cases): every figure is in report.html
    as a data URI holding exactly the PNG written beside the report."""
    import lgw.sim.eros.batch as B

    monkeypatch.setattr(B, "SimOptions", lambda **kw: replace(SHORT, **kw))
    r = CliRunner().invoke(report_command, ["--out", str(tmp_path), "--cases", "3",
                                            "--no-descent"])
    assert r.exit_code == 0, r.output
    assert_report_embeds(tmp_path, FILES, r.output)


def test_simulate_plot_writes_the_figures(tmp_path):
    """``lgw simulate eros --plot DIR``: the scenario's three figures for one variant, and the
    campaign's times figure too with --cases."""
    from tests.test_cli_conventions import run_lgw

    one, many = tmp_path / "one", tmp_path / "many"
    r = run_lgw(["simulate", "eros", "--law", "fuzzy-tanh", "--t-max", "2", "--plot", str(one)])
    assert r.code == 0, r.stderr
    assert sorted(p.name for p in one.iterdir() if p.suffix == ".png") == sorted(FILES[:3])
    r = run_lgw(["simulate", "eros", "--cases", "3", "--t-max", "2", "--json",
                 "--plot", str(many)])
    assert r.code == 0, r.stderr
    for name in FILES:
        assert (many / name).read_bytes().startswith(PNG_SIGNATURE), name
    assert len(json.loads(r.stdout)["rows"]) == 6  # --json stays one JSON object
