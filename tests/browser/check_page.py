#!/usr/bin/env python3
"""check_page.py PAGE.html RESULT.json ARTEFACT_STEM [--svgs N]

Opens a page j232 wrote in headless Chromium and checks that
  - it is self-contained: no scripts, no external style sheets, fonts or images;
  - every inline SVG is well-formed XML;
  - Chromium renders it without a console message (SVG attribute errors show there);
  - every number tagged data-key/data-value in the rendered page equals the value at
    that key in RESULT.json, and its shown text is that value rounded as displayed;
  - the key numbers (verdict, P(pass) and interval, the four shares) are present.
Saves ARTEFACT_STEM.png (full-page screenshot) and ARTEFACT_STEM.pdf (printed).
Standard library only."""
import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from headless import chromium, fail  # noqa: E402

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--hide-scrollbars"]


def run_chromium(args, profile):
    cmd = [chromium(), *FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0", *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    return p


def lookup(doc, key):
    node = doc
    for part in key.split("."):
        if isinstance(node, list):
            node = node[int(part)]
        elif isinstance(node, dict) and part in node:
            node = node[part]
        else:
            raise KeyError(key)
    return node


def main():
    args = sys.argv[1:]
    want_svgs = None
    if "--svgs" in args:
        i = args.index("--svgs")
        want_svgs = int(args[i + 1])
        del args[i:i + 2]
    page, result_path, stem = args
    html = open(page, encoding="utf-8").read()
    result = json.load(open(result_path, encoding="utf-8"))

    # Self-contained: nothing fetched, nothing run.
    if re.search(r"<script|<link\b|<img\b|<iframe|@import|@font-face", html, re.I):
        fail("page has a script, link, image, iframe, @import or @font-face")
    external = set(re.findall(r"""(?:src|href)\s*=\s*["']?((?:https?:)?//[^"' >]+)""", html, re.I))
    external |= set(re.findall(r"url\(\s*['\"]?(?!#)([^)'\"]+)", html))
    if external:
        fail(f"page refers to outside resources: {sorted(external)[:5]}")
    svgs = re.findall(r"<svg\b.*?</svg>", html, re.S)
    for n, svg in enumerate(svgs):
        try:
            ET.fromstring(svg)
        except ET.ParseError as e:
            fail(f"SVG {n + 1} is not well-formed: {e}")
    if want_svgs is not None and len(svgs) != want_svgs:
        fail(f"expected {want_svgs} charts, found {len(svgs)}")

    with tempfile.TemporaryDirectory() as profile:
        url = "file://" + os.path.abspath(page)
        dom = run_chromium(["--dump-dom", url], profile)
        if dom.returncode != 0:
            fail(f"chromium exit code {dom.returncode}: {dom.stderr[-2000:]}")
        console = [l for l in dom.stderr.splitlines() if "CONSOLE" in l or "Uncaught" in l]
        if console:
            fail("console messages while rendering:\n  " + "\n  ".join(console[:10]))
        rendered = dom.stdout
        if rendered.count("<svg") != len(svgs):
            fail(f"rendered page has {rendered.count('<svg')} SVGs, the file {len(svgs)}")

        # Tagged numbers against the result file.
        tags = re.findall(r'<span data-key="([^"]+)" data-value="([^"]*)" data-scale="([^"]+)">([^<]*)</span>', rendered)
        if not tags:
            fail("no tagged numbers in the rendered page")
        seen = set()
        for key, value, scale, shown in tags:
            value = value.replace("&quot;", '"').replace("&amp;", "&")
            try:
                expected = lookup(result, key)
            except (KeyError, IndexError, ValueError):
                fail(f"page shows {key} = {shown}, but {result_path} has no such key")
            if json.loads(value) != expected:
                fail(f"{key}: page's data-value {value} != {expected!r} in {os.path.basename(result_path)}")
            if isinstance(expected, (int, float)) and not isinstance(expected, bool):
                decimals = len(shown.split(".")[1]) if "." in shown else 0
                if abs(float(shown) - expected * float(scale)) > 0.5001 * 10 ** -decimals + 1e-12:
                    fail(f"{key}: shown {shown} is not {expected} x {scale} rounded to {decimals} decimals")
            elif str(expected) != shown:
                fail(f"{key}: shown {shown!r}, result has {expected!r}")
            seen.add(key)
        required = set()
        if "criteria" in result:  # a compliance report (not a batch summary)
            required = {"verdict", "pass_probability.estimate", "pass_probability.low", "pass_probability.high",
                        "required_pass_probability", "replicates"} | {f"criteria.{c}.mean_share" for c in range(4)}
        missing = required - seen
        if missing:
            fail(f"key numbers missing from the page: {sorted(missing)}")

        # Artefacts: a full-page screenshot and the printed PDF.
        os.makedirs(os.path.dirname(os.path.abspath(stem)), exist_ok=True)
        png, pdf = stem + ".png", stem + ".pdf"
        for f in (png, pdf):
            if os.path.exists(f):
                os.remove(f)
        shot = run_chromium([f"--screenshot={png}", "--window-size=1000,1400", url], profile)
        printed = run_chromium([f"--print-to-pdf={pdf}", "--no-pdf-header-footer", url], profile)
        for f, p in ((png, shot), (pdf, printed)):
            if p.returncode != 0 or not os.path.exists(f) or os.path.getsize(f) < 10000:
                fail(f"chromium did not write {f}: {p.stderr[-1000:]}")
        if open(pdf, "rb").read(5) != b"%PDF-":
            fail(f"{pdf} is not a PDF")
        pages = len(re.findall(rb"/Type\s*/Page\b", open(pdf, "rb").read()))
    print(f"check_page: ok: {page}: {len(svgs)} charts, {len(tags)} numbers match {os.path.basename(result_path)}; "
          f"wrote {png} and {pdf} ({pages} pages)")


if __name__ == "__main__":
    main()
