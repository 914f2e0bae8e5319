#!/usr/bin/env python3
"""reports_check.py [--regenerated-only] SHIPPED REGENERATED: the shipped reports/ folder
equals a fresh regeneration (scripts/make-reports REGENERATED), provenance aside:
  - every result.json and summary.json equal, ignoring "provenance";
  - every report.html and summary.html equal outside the provenance section;
  - every sweep CSV and SVG byte-identical;
  - no file missing on either side (marks.csv and scene.html are not shipped: large raw
    data, and a page that is mostly a copy of three.js).
With --regenerated-only (scripts/make-reports --check-quick), only the shipped folders (and
top-level files) that the regeneration has are compared, each of them in full."""
import json
import os
import re
import sys

args = sys.argv[1:]
regenerated_only = bool(args) and args[0] == "--regenerated-only"
if regenerated_only:
    args = args[1:]
if len(args) != 2:
    sys.exit("usage: reports_check.py [--regenerated-only] SHIPPED REGENERATED")
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
if regenerated_only:
    top = {f.split(os.sep)[0] for f in b}
    a = {f for f in a if f.split(os.sep)[0] in top}
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
print(f"reports_check: ok: {len(a)} files equal (provenance aside)")
