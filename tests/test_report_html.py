"""The report's HTML is one self-contained, navigable page whose mathematics is well-formed.

Checked structurally on the golden seed 000 report (every real claim) and on a small report
with a figure: no ``http:`` / ``https:`` reference, every ``<img>`` a PNG data URI, every claim
reachable from the verdict summary and linking back, every internal link resolving, every
MathML block well-formed XML.  The LaTeX compiles with ``pdflatex`` and the page renders in
headless Chromium (``benchmarks/render_report.py``) when those programs are on PATH.
"""

from __future__ import annotations

import base64
import importlib.util
import re
import shutil
import subprocess
import xml.dom.minidom
import xml.parsers.expat
from html.parser import HTMLParser
from pathlib import Path

import pytest
import sympy as sp
from lgw.theory.evidence import Claim
from lgw.theory.provers import prove_identity, prove_nonneg
from lgw.theory.report import (
    Figure,
    ReportSpec,
    Section,
    anchor,
    render_html,
    render_latex,
    render_markdown,
)
from lgw.theory.symbolic import sig

ROOT = Path(__file__).resolve().parents[1]
GOLDEN_HTML = ROOT / "tests" / "mars" / "golden" / "report_nocompare.html"


class _Page(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.ids: list[str] = []
        self.hrefs: list[str] = []
        self.imgs: list[str] = []
        self.details = 0

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = dict(attrs)
        if a.get("id"):
            self.ids.append(a["id"])
        if tag == "a" and a.get("href"):
            self.hrefs.append(a["href"])
        if tag == "img":
            self.imgs.append(a.get("src") or "")
        if tag == "details":
            self.details += 1


def check_html(text: str, claim_ids: list[str]) -> _Page:
    """Every structural property of a report page; returns the parsed page."""
    assert "http:" not in text and "https:" not in text
    page = _Page()
    page.feed(text)
    assert len(page.ids) == len(set(page.ids)), "duplicate ids"
    ids = set(page.ids)
    for h in page.hrefs:
        assert h.startswith("#"), f"non-internal link {h[:80]}"
        assert h[1:] in ids, f"dangling link {h}"
    for src in page.imgs:
        assert src.startswith("data:image/png;base64,"), src[:60]
        assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    for cid in claim_ids:
        a = anchor(cid)
        back = "sum-" + a[len("claim-"):]
        assert a in ids and back in ids, cid
        assert f"#{a}" in page.hrefs and f"#{back}" in page.hrefs, cid
        # the link back sits inside the claim's own section
        body = text[text.index(f"id='{a}'"):]
        assert f"href='#{back}'" in body[:body.index("</section>")], cid
    blocks = re.findall(r"<math\b.*?</math>", text, flags=re.S)
    for m in blocks:
        xml.dom.minidom.parseString(m)  # raises on malformed XML
    assert text.count("<math") == len(blocks)
    return page


def _tiny_png() -> bytes:
    from lgw.tuning.figures import png_bytes, styled

    with styled() as plt:
        fig, ax = plt.subplots(figsize=(2, 1.5))
        ax.plot([0, 1], [0, 1], label="a line")
        ax.legend()
        return png_bytes(fig, dpi=60)


def _small_report() -> tuple[list[Claim], ReportSpec, list[Section]]:
    x = sp.Symbol("x", real=True)
    q = sp.Symbol("q", positive=True)
    y = sp.Symbol("y", positive=True)
    steps = [prove_identity(sp.expand((x + 1) ** 2 - x**2 - 2 * x - 1), "(x+1)^2 = x^2+2x+1"),
             prove_nonneg(y**q, "y^q >= 0 for y > 0")]
    c1 = Claim("one@gains", "(1)", "A claim < with & specials", "x^2 <= |x| (printed)",
               "derived", steps, scope="gain-set",
               paper_expr=(sp.Le(x**2, sp.Abs(x), evaluate=False),),
               derived_expr=(sp.Eq(sig(x, q), sp.Abs(x) ** q * sp.sign(x), evaluate=False),))
    c2 = Claim("two", "(2)", "Another", "p", "d", steps[:1])
    spec = ReportSpec("Test", (("k", "1"),), ("w ^ _ %",), (("T", "T bound", "s"),), ("x",),
                      {"x": {"T": 1.5}}, ("ref 1",))
    sec = Section("Figures", ("a paragraph",), (), (),
                  figures=(Figure("tiny.png", "a tiny figure", _tiny_png()),))
    return [c1, c2], spec, [sec]


def test_golden_report_html_is_self_contained_and_navigable() -> None:
    text = GOLDEN_HTML.read_text()
    ids = re.findall(r"<section class='claim' id='claim-([^']+)'", text)
    assert len(ids) > 30
    page = check_html(text, [])  # anchors are checked below from the page itself
    for a in ids:
        assert f"#claim-{a}" in page.hrefs and f"#sum-{a}" in page.hrefs
    assert page.details > 100  # evidence folded
    assert text.count("<math") > 100  # formulas rendered, not ASCII


def test_small_report_with_figure() -> None:
    claims, spec, secs = _small_report()
    text = render_html(claims, spec, secs)
    page = check_html(text, [c.id for c in claims])
    assert len(page.imgs) == 1
    assert "&lt; with &amp; specials" in text
    assert "\u2308" in text  # the signed power as ceiling-floor brackets (&#8968; in MathML)
    md = render_markdown(claims, spec, secs)
    assert "$$" in md and "![a tiny figure](tiny.png)" in md


def test_a_broken_page_fails_the_check() -> None:
    """The checker itself can fail: a linked image, an external URL, a dangling link, bad
    MathML and a claim without its way back are each caught."""
    claims, spec, secs = _small_report()
    good = render_html(claims, spec, secs)
    a = anchor("two")
    bad = [good.replace("data:image/png;base64,", "tiny.png?", 1),
           good.replace("</body>", "<p>https://example.org</p></body>"),
           good.replace(f"href='#{a}'", "href='#nowhere'", 1),
           good.replace("</mrow></math>", "</math>", 1),
           good.replace("href='#sum-two'", "href='#claim-one-gains'")]
    for i, b in enumerate(bad):
        assert b != good
        error = xml.parsers.expat.ExpatError if i == 3 else AssertionError
        with pytest.raises(error):
            check_html(b, [c.id for c in claims])


def test_html_never_links_an_image_file(tmp_path: Path) -> None:
    claims, spec, _ = _small_report()
    sec = Section("S", (), ("a",), (("1",),), image="f.png")
    assert "<img" not in render_html(claims, spec, [sec])
    (tmp_path / "f.png").write_bytes(_tiny_png())
    text = render_html(claims, spec, [sec], asset_dir=tmp_path)
    check_html(text, [c.id for c in claims])
    assert text.count("<img") == 1


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex not on PATH")
def test_small_report_latex_compiles(tmp_path: Path) -> None:
    claims, spec, secs = _small_report()
    tex = render_latex(claims, spec, secs)
    assert r"\^{}" not in tex and "$<$" not in tex
    (tmp_path / "report.tex").write_text(tex)
    (tmp_path / "tiny.png").write_bytes(secs[0].figures[0].png)
    for _ in range(2):
        res = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error",
                              "report.tex"], cwd=tmp_path, capture_output=True, text=True,
                             timeout=120)
        assert res.returncode == 0, res.stdout[-3000:]
    assert (tmp_path / "report.pdf").stat().st_size > 10_000


def _render_module():
    spec = importlib.util.spec_from_file_location("render_report",
                                                  ROOT / "benchmarks" / "render_report.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.skipif(shutil.which("chromium") is None, reason="chromium not on PATH")
def test_chromium_renders_the_report(tmp_path: Path) -> None:
    """Headless Chromium, offline, renders the summary, a derivation with its MathML and the
    figure; each screenshot has real content (many colours, not a blank page)."""
    from PIL import Image

    claims, spec, secs = _small_report()
    (tmp_path / "report.html").write_text(render_html(claims, spec, secs))
    shots = _render_module().render(tmp_path, tmp_path / "shots", claim="one@gains")
    assert [p.name for p in shots] == ["screenshot_verdicts.png", "screenshot_derivation.png",
                                       "screenshot_figure.png"]
    for p in shots:
        with Image.open(p) as im:
            assert len(im.convert("RGB").getcolors(1 << 20) or ()) > 8, p.name


def test_mathml_names_and_long_lines() -> None:
    """Gamma prints as the capital letter, a user function keeps its case, a dotted symbol
    gets its dot, and a long sum becomes several well-formed lines holding every term."""
    from lgw.theory import report_math as RM

    x, y = sp.symbols("x y", positive=True)
    assert "&#x393;" in RM.mathml(sp.gamma(x))
    assert "<mi>V</mi>" in RM.mathml(sp.Function("V")(x))
    assert "<mover>" in RM.mathml(sp.Symbol("Vdot_2"))
    long = sp.Eq(sp.Symbol("a"), sum(sp.Symbol(f"beta_{i}") * x ** (i + y) for i in range(12)))
    lines = RM.split_lines(long)
    assert lines is not None and len(lines) >= 2
    block = RM.mathml_lines(long)
    xml.dom.minidom.parseString(block)
    assert block.count("<mtr>") == len(lines)
    assert sum(t.count(r"\beta") for t, _ in lines) == 12
    assert RM.split_lines(sp.Eq(x, y)) is None


def _report_with_findings():
    """A paper claim refuted by a re-checked witness, its workbench correction (proved), a
    proved paper claim and a refuted workbench claim (not a finding of the paper)."""
    from lgw.theory.provers import witness_step

    claims, spec, secs = _small_report()
    x = sp.Symbol("x", real=True)
    bad = witness_step("x^2 <= |x| for every x", {"x": 2}, -2.0, "value at x = 2", -2.0,
                       "exact arithmetic")
    paper = Claim("printed", "(7)", "Printed bound", "x^2 <= |x|", "false for |x| > 1", [bad])
    fix = Claim("printed-corrected", "(7)", "Corrected bound", "x^2 <= |x|",
                "x^2 <= |x| for |x| <= 1", [prove_identity(x - x, "trivial")],
                statement="workbench", corrects="printed")
    own = Claim("own-law", "(8)", "A workbench law", "(not in the paper)", "d", [bad],
                statement="workbench")
    spec = ReportSpec(spec.title, spec.gain_rows, spec.warnings, spec.bound_labels,
                      spec.columns, spec.bounds, spec.references, paper_title="A Paper Title")
    return [*claims, paper, fix, own], spec, secs


def test_findings_open_every_format_and_count_the_papers_statements(tmp_path: Path) -> None:
    from lgw.theory.report import claims_json, findings, verdict_counts

    claims, spec, secs = _report_with_findings()
    cmd = {"printed": "lgw report test --claim printed --json"}
    fs = findings(claims, cmd)
    assert [f.id for f in fs] == ["printed"]  # the refuted workbench claim is no finding
    assert fs[0].corrected_by == "printed-corrected" and fs[0].command == cmd["printed"]
    assert "x = 2" in fs[0].witness and "exact arithmetic" in fs[0].witness
    assert verdict_counts(claims)["refuted"] == 1 and verdict_counts(claims)["proved"] == 2
    assert verdict_counts(claims, "workbench") == {"proved": 1, "proved-given": 0,
                                                   "checked": 0, "unproven": 0, "refuted": 1}
    html = render_html(claims, spec, secs, reproduce=cmd)
    check_html(html, [c.id for c in claims])
    head = html[:html.index("id='gains'")]
    assert "id='findings'" in head and "A Paper Title" in head and cmd["printed"] in head
    assert "href='#claim-printed-corrected'" in head  # the correction is linked
    md = render_markdown(claims, spec, secs, reproduce=cmd)
    assert md.index("## Findings") < md.index("## Gain set") and cmd["printed"] in md
    assert "correcting printed" in md and "corrected by printed-corrected" in md
    tex = render_latex(claims, spec, secs, reproduce=cmd)
    assert tex.index("Findings") < tex.index(r"\section{Gain set}")
    import json
    doc = json.loads(claims_json(claims, cmd))
    assert doc["verdicts"]["refuted"] == 1 and doc["verdicts_workbench"]["refuted"] == 1
    assert doc["findings"][0]["id"] == "printed"
    if shutil.which("pdflatex"):
        (tmp_path / "report.tex").write_text(tex)
        (tmp_path / "tiny.png").write_bytes(secs[0].figures[0].png)
        res = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error",
                              "report.tex"], cwd=tmp_path, capture_output=True, text=True,
                             timeout=120)
        assert res.returncode == 0, res.stdout[-3000:]
