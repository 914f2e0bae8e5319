#!/usr/bin/env bash
# redraw_check.sh J232 REPO OUT: `j232 redraw` draws every shipped page that has a JSON of its
# own (reports/*/hazard.json, compare.json, uq.json) from that JSON alone, and the page is the
# shipped one byte for byte (the writers draw them from the same JSON as saved); a field's
# page redrawn in US units is the page `j232 hazard --units us` wrote.
set -euo pipefail
j232=$1 repo=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
pages=0
for json in "$repo"/reports/*/hazard.json "$repo"/reports/*/compare.json "$repo"/reports/*/uq.json; do
  [ -e "$json" ] || continue
  folder=$(basename "$(dirname "$json")") page=$(basename "$json" .json).html
  "$j232" redraw "$json" --out "$out/$folder-$page" >/dev/null
  cmp "$out/$folder-$page" "$(dirname "$json")/$page"
  pages=$((pages + 1))
done
[ "$pages" -ge 4 ] || { echo "redraw_check: only $pages shipped pages found" >&2; exit 1; }
# In US units: the lawn's field at a small sample, drawn by j232 hazard --units us and redrawn
# from the SI run's hazard.json (the same run: only the provenance's date and time differ).
field="$repo/scenarios/field/deck-72in-lawn-stones.toml"
"$j232" hazard "$field" --objects 2000 --out "$out/si" >/dev/null
"$j232" hazard "$field" --objects 2000 --units us --out "$out/us" >/dev/null
"$j232" redraw "$out/si/hazard.json" --units us --out "$out/redrawn-us.html" >/dev/null
strip() { sed 's/<section id="provenance">.*<\/section>//' "$1"; }
diff <(strip "$out/redrawn-us.html") <(strip "$out/us/hazard.html")
grep -q "ft-lb" "$out/redrawn-us.html"
echo "redraw_check: $pages shipped pages redrawn as shipped; a field's page redrawn in US units"
