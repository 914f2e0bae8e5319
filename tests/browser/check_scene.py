#!/usr/bin/env python3
"""check_scene.py J232 SCENARIO WORKDIR ARTEFACT_STEM [--paths RESULT.json | --run] [--expect-part TEXT]...

Writes the 3D view of SCENARIO with `j232 scene --html` (or, with --run, the scene.html
that `j232 run --trajectories` writes beside report.html) and opens it in headless
Chromium (WebGL through SwiftShader), checking that
  - the page is self-contained: no external scripts, style sheets, fonts or images, and
    carries three.js's licence;
  - it renders without a console message;
  - WebGL started and the page drew every face `j232 scene` counted, per label, and as
    many triangles as the scene has with its blades (three.js's own count);
  - each --expect-part names a part in the legend (a guard by name and kind, say);
  - the nail paths are drawn when there are any, and a path's trail shows (#trail=0);
  - the screenshot is a picture, not a blank canvas (many colours in the view), and hiding
    the board (#hide=target,operator_zone) changes the pixels.
Saves ARTEFACT_STEM.png. Standard library only."""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from headless import chromium, fail  # noqa: E402

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
         "--disable-quic", "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", "--hide-scrollbars", "--virtual-time-budget=15000", "--window-size=1200,800"]


def png_pixels(path):
    """The RGB(A) rows of an 8-bit, non-interlaced PNG (what Chromium writes)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path} is not a PNG")
    pos, idat, width, height, kind = 8, b"", 0, 0, 0
    while pos < len(data):
        length, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if tag == b"IHDR":
            width, height, depth, kind, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or kind not in (2, 6) or interlace:
                fail(f"{path}: expected an 8-bit RGB or RGBA PNG")
        elif tag == b"IDAT":
            idat += body
        pos += 12 + length
    channels = 3 if kind == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        filt = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if filt == 1:
                line[i] = (line[i] + left) & 255
            elif filt == 2:
                line[i] = (line[i] + up) & 255
            elif filt == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif filt == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append(line)
        previous = line
    return width, height, channels, rows


def main():
    args = sys.argv[1:]
    paths, parts, run_mode = None, [], False
    if "--run" in args:
        args.remove("--run")
        run_mode = True
    while "--paths" in args:
        i = args.index("--paths")
        paths = args[i + 1]
        del args[i:i + 2]
    while "--expect-part" in args:
        i = args.index("--expect-part")
        parts.append(args[i + 1])
        del args[i:i + 2]
    if len(args) != 4:
        fail(__doc__)
    exe, scenario, work, stem = args
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    html = os.path.join(work, "scene.html")
    cmd = [exe, "scene", scenario, "--html", html] + (["--paths", paths] if paths else [])
    if run_mode:
        folder = os.path.join(work, "run")
        made = subprocess.run([exe, "run", scenario, "--replicates", "40", "--trajectories", "6", "--out", folder],
                              capture_output=True, text=True, timeout=600)
        if made.returncode not in (0, 1):
            fail(f"j232 run exited {made.returncode}: {made.stderr}")
        html = os.path.join(folder, "scene.html")
        if not os.path.exists(html):
            fail("j232 run wrote no scene.html beside report.html")
        cmd = [exe, "scene", scenario]
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if run.returncode != 0:
        fail(f"{' '.join(cmd)} exited {run.returncode}: {run.stderr}")
    printed = {m.group(1): int(m.group(2)) for m in re.finditer(r"^  (\w+)\s+(\d+) faces$", run.stdout, re.M)}
    if not printed:
        fail(f"no face counts in j232 scene's output:\n{run.stdout}")

    with open(html, encoding="utf-8") as f:
        page = f.read()
    for pattern in (r"<script[^>]*\ssrc=", r"<link\b", r"@import", r"url\(\s*['\"]?(https?:|//)", r"<img\b"):
        if re.search(pattern, page, re.I):
            fail(f"the page is not self-contained: it matches {pattern}")
    if "Permission is hereby granted, free of charge" not in page or "three.js authors" not in page:
        fail("three.js's licence is not kept in the page")

    url = "file://" + os.path.abspath(html)
    with tempfile.TemporaryDirectory() as profile:
        base = [chromium(), *FLAGS, f"--user-data-dir={profile}"]
        shown = subprocess.run(base + ["--enable-logging=stderr", "--v=0", "--dump-dom", url + "#trail=0"],
                               capture_output=True, text=True, timeout=180)
        dom = shown.stdout
        # (The software renderer's own notes, such as "GPU stall due to ReadPixels", are the
        # test machine's, not the page's.)
        console = [l for l in shown.stderr.splitlines() if ("CONSOLE" in l or "Uncaught" in l)
                   and "GL Driver Message" not in l and "fallback to software WebGL" not in l]
        if console:
            fail("console messages while rendering:\n  " + "\n  ".join(console[:10]))
        m = re.search(r'<pre id="status">([^<]*)</pre>', dom)
        if not m:
            fail("no #status in the rendered page")
        status = json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))
        if not status.get("webgl"):
            fail(f"WebGL did not start: {status}")
        if status.get("faces") != printed:
            fail(f"the page's faces {status.get('faces')} are not those j232 scene counted {printed}")
        drawn = sum(status["parts"].values())
        blade_triangles = 12 * status.get("blade_plates", 0) + status.get("mark_triangles", 0)  # a plate is a box: 12
        if drawn != sum(printed.values()) or status.get("triangles") != drawn + blade_triangles:
            fail(f"drawn {drawn} faces and {blade_triangles} of blades and marks, rendered {status.get('triangles')} triangles; "
                 f"the scene has {sum(printed.values())}")
        if not status["lines"].get("blades"):
            fail(f"no blades drawn: {status['lines']}")
        for want in parts:
            if not any(want in name for name in status["parts"]):
                fail(f"no part named like {want!r} among {list(status['parts'])}")
        for group in ("tip_circles", "feed_stations"):
            if not status["lines"].get(group):
                fail(f"no {group} drawn: {status['lines']}")
        kept = sum(n for k, n in status["lines"].items() if k.startswith("paths: "))
        if (paths or run_mode) and not kept:
            fail(f"no nail paths drawn: {status['lines']}")
        if kept:
            t = re.search(r'<pre id="trail"[^>]*>([^<]*)</pre>', dom)
            if not t or "fate: " not in t.group(1) or "j232 trace" not in t.group(1):
                fail(f"#trail=0 shows no trail: {t.group(1) if t else 'no #trail'}")
            if run_mode and "blade strikes: " not in t.group(1):
                fail(f"a run's path trail lacks its strikes: {t.group(1)}")

        png = stem + ".png"
        os.makedirs(os.path.dirname(os.path.abspath(png)), exist_ok=True)
        subprocess.run(base + [f"--screenshot={png}", url], capture_output=True, text=True, timeout=180)
        if not os.path.exists(png):
            fail("Chromium wrote no screenshot")
        width, height, channels, rows = png_pixels(png)
        # The right half, away from the legend: a drawn scene has shading, lines and parts.
        colours = set()
        for y in range(0, height, 7):
            row = rows[y]
            for x in range(width // 2, width, 7):
                colours.add(bytes(row[x * channels:x * channels + 3]))
        if len(colours) < 50:
            fail(f"the screenshot looks blank ({len(colours)} colours in the view)")
        # A layer toggled off changes the picture.
        bare = os.path.join(os.path.dirname(os.path.abspath(png)), os.path.basename(stem) + "-without-board.png")
        subprocess.run(base + [f"--screenshot={bare}", url + "#hide=target,operator_zone"], capture_output=True, text=True, timeout=180)
        _, _, channels2, rows2 = png_pixels(bare)
        changed = sum(1 for y in range(0, height, 4) for x in range(0, width, 4)
                      if rows[y][x * channels:x * channels + 3] != rows2[y][x * channels2:x * channels2 + 3])
        os.remove(bare)
        if changed < 500:
            fail(f"hiding the board changed only {changed} sampled pixels")
    print(f"check_scene: ok: {drawn} faces in {len(status['parts'])} parts, lines {status['lines']}, "
          f"{len(colours)} colours, {changed} sampled pixels change without the board, WebGL {status.get('renderer')}")


if __name__ == "__main__":
    main()
