"""Render a report's HTML with headless Chromium and save screenshots; rasterise a PDF page.

    python benchmarks/render_report.py REPORT_DIR [--out DIR] [--pdf-page N]

Screenshots (PNG, 1280 px wide, a laptop screen): the verdict summary (``#verdicts``), one
derivation with rendered equations (``#claim-V2dot-printed``, or ``--claim ID``) and the first
figure (the first ``<figure>``).  Chromium runs offline: a fresh
``--user-data-dir`` and no background networking, component updates or sync, so a page that
needed the network would show it.  With ``report.pdf`` present (``pdflatex report.tex``), page
``--pdf-page`` is rasterised by ``pdftoppm``.  Prints the files it wrote.

Not a timing benchmark: it lives here because it drives an external program (Debian's
``chromium``) and is run by hand or by ``tests/test_report_html.py`` when Chromium is on PATH.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run",
         "--hide-scrollbars", "--force-device-scale-factor=1")


def chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


# Headless Chromium's --screenshot ignores a URL fragment (the capture stays blank or at the
# top), so a shot of one element loads a copy of the page whose body is that element alone:
# the same CSS and the same MathML, laid out at the same width.
_ISOLATE = ("<script>document.addEventListener('DOMContentLoaded',function(){{var e=document."
            "getElementById('{id}');if(e){{document.body.replaceChildren(e);}}}});</script>")


def screenshot(html: Path, element_id: str | None, out: Path,
               size: tuple[int, int] = (1280, 900), timeout: float = 120.0) -> Path:
    """A screenshot of ``html`` (or of its element ``element_id`` alone), a fresh profile."""
    exe = chromium()
    if exe is None:
        raise RuntimeError("chromium is not on PATH (apt-get install -y chromium)")
    with tempfile.TemporaryDirectory(prefix="lgw-chromium-") as tmp:
        page = html
        if element_id:
            text = html.read_text()
            if f"id='{element_id}'" not in text:
                raise ValueError(f"{html} has no element with id {element_id!r}")
            page = Path(tmp) / "page.html"
            page.write_text(text.replace("</head>", _ISOLATE.format(id=element_id) + "</head>",
                                         1))
        cmd = [exe, *FLAGS, f"--user-data-dir={Path(tmp) / 'profile'}",
               f"--window-size={size[0]},{size[1]}", f"--screenshot={out.resolve()}",
               page.resolve().as_uri()]
        res = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if not out.is_file():
        raise RuntimeError(f"chromium wrote no screenshot (exit {res.returncode}): "
                           f"{res.stderr[-2000:]}")
    return out


def first_figure_id(html_text: str) -> str | None:
    """The id of the first <figure> (None without figures)."""
    m = re.search(r"<figure id='([^']+)'", html_text)
    return m.group(1) if m else None


def pdf_page(pdf: Path, page: int, out_prefix: Path, dpi: int = 80) -> Path:
    exe = shutil.which("pdftoppm")
    if exe is None:
        raise RuntimeError("pdftoppm is not on PATH (apt-get install -y poppler-utils)")
    subprocess.run([exe, "-png", "-r", str(dpi), "-f", str(page), "-l", str(page),
                    "-singlefile", str(pdf), str(out_prefix)], check=True, timeout=120)
    return out_prefix.with_suffix(".png")


def render(report_dir: Path, out: Path, claim: str = "V2dot-printed",
           pdf_page_no: int | None = None) -> list[Path]:
    html = report_dir / "report.html"
    text = html.read_text()
    out.mkdir(parents=True, exist_ok=True)
    anchor = "claim-" + re.sub(r"[^A-Za-z0-9-]", "-", claim)
    shots = [("verdicts", "verdicts"), (anchor, "derivation")]
    fig = first_figure_id(text)
    if fig is not None:
        shots.append((fig, "figure"))
    written = [screenshot(html, frag, out / f"screenshot_{name}.png", size=(1280, 1400))
               for frag, name in shots]
    pdf = report_dir / "report.pdf"
    if pdf_page_no is not None and pdf.is_file():
        written.append(pdf_page(pdf, pdf_page_no, out / f"pdf_page_{pdf_page_no}"))
    return written


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("report_dir", type=Path)
    ap.add_argument("--out", type=Path, default=None, help="default: REPORT_DIR/screenshots")
    ap.add_argument("--claim", default="V2dot-printed", help="the derivation to screenshot")
    ap.add_argument("--pdf-page", type=int, default=None, help="rasterise this page of "
                    "report.pdf (needs pdftoppm)")
    args = ap.parse_args(argv)
    for p in render(args.report_dir, args.out or args.report_dir / "screenshots", args.claim,
                    args.pdf_page):
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main())
