#!/usr/bin/env python3
"""reports_check.py [--except NAME,...] SHIPPED REGENERATED: the shipped reports/ folder
equals a fresh regeneration (scripts/make-reports REGENERATED), provenance aside:
  - every result.json and summary.json equal, ignoring "provenance";
  - every report.html and summary.html equal outside the provenance section;
  - every sweep CSV and SVG byte-identical;
  - no file missing on either side (marks.csv and scene.html are not shipped: large raw
    data, and a page that is mostly a copy of three.js).
With --except (scripts/make-reports --check-quick), the shipped folders and top-level files
so named are left out, and must not have been regenerated; every other must be there."""
import json
import os
import re
import sys

args = sys.argv[1:]
skipped = set()
if len(args) >= 2 and args[0] == "--except":
    skipped = set(args[1].split(","))
    args = args[2:]
if len(args) != 2:
    sys.exit("usage: reports_check.py [--except NAME,...] SHIPPED REGENERATED")
shipped, fresh = args
problems = []


def files(root):
    out = set()
    for d, _, names in os.walk(root):
        for n in names:
            if n.endswith((".partial", ".log")) or n in ("marks.csv", "scene.html", "README.md", ".j232.lock"):
                continue
            out.add(os.path.relpath(os.path.join(d, n), root))
    return out


a, b = files(shipped), files(fresh)
if skipped:
    a = {f for f in a if f.split(os.sep)[0] not in skipped}
    if not a:
        problems.append("nothing left to compare: --except names every shipped file")
for f in sorted(a ^ b):
    problems.append(f"{f}: only in {'the shipped reports' if f in a else 'the regeneration'}")


def strip_provenance(text):
    return re.sub(r'<section id="provenance">.*?</section>', "", text, flags=re.S)


for f in sorted(a & b):
    x, y = os.path.join(shipped, f), os.path.join(fresh, f)
    if f.endswith(".json"):
        jx, jy = json.load(open(x)), json.load(open(y))
        for j in (jx, jy):
            j.pop("provenance", None)
        if jx != jy:
            problems.append(f"{f}: results differ")
    elif f.endswith(".html"):
        if strip_provenance(open(x).read()) != strip_provenance(open(y).read()):
            problems.append(f"{f}: page differs outside its provenance")
    elif open(x, "rb").read() != open(y, "rb").read():
        problems.append(f"{f}: differs")

if problems:
    print("reports_check: the shipped reports are not what the program now produces "
          "(run scripts/make-reports and commit):", file=sys.stderr)
    for p in problems:
        print("  " + p, file=sys.stderr)
    sys.exit(1)
left_out = f", {len(skipped)} folders and files left out" if skipped else ""
print(f"reports_check: ok: {len(a)} files equal (provenance aside){left_out}")
