#!/usr/bin/env bash
# redraw_check.sh J232 REPO OUT: `j232 redraw` draws every shipped page from its JSON alone
# (reports/*/result.json's report.html, hazard.json, compare.json, uq.json), and the page is
# the shipped one byte for byte (the writers draw them from the same JSON as saved); a field's
# page redrawn in US units is the page `j232 hazard --units us` wrote.
set -euo pipefail
j232=$1 repo=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
pages=0
for json in "$repo"/reports/*/result.json "$repo"/reports/*/hazard.json "$repo"/reports/*/compare.json "$repo"/reports/*/uq.json; do
  [ -e "$json" ] || continue
  folder=$(basename "$(dirname "$json")") page=$(basename "$json" .json).html
  [ "$page" != result.html ] || page=report.html
  "$j232" redraw "$json" --out "$out/$folder-$page" >/dev/null
  cmp "$out/$folder-$page" "$(dirname "$json")/$page"
  pages=$((pages + 1))
done
[ "$pages" -eq 17 ] || { echo "redraw_check: $pages shipped pages found, expected 17 (11 J232 tests, 3 fields, 2 comparisons, 1 study)" >&2; exit 1; }
# In US units: the lawn's field at a small sample, drawn by j232 hazard --units us and redrawn
# from the SI run's hazard.json (the same run: only the provenance's date and time differ).
field="$repo/scenarios/field/deck-72in-lawn-stones.toml"
"$j232" hazard "$field" --objects 2000 --out "$out/si" >/dev/null
"$j232" hazard "$field" --objects 2000 --units us --out "$out/us" >/dev/null
"$j232" redraw "$out/si/hazard.json" --units us --out "$out/redrawn-us.html" >/dev/null
strip() { sed 's/<section id="provenance">.*<\/section>//' "$1"; }
diff <(strip "$out/redrawn-us.html") <(strip "$out/us/hazard.html")
grep -q "ft-lb" "$out/redrawn-us.html"
# Without --out, a page in US units goes beside the file under a name of its own.
"$j232" redraw "$out/si/hazard.json" --units us >/dev/null
cmp "$out/si/hazard-us.html" "$out/redrawn-us.html"
# A saved file that lacks a key its page draws is refused, naming the key (exit 2), never a crash.
for lacking in highway-pivoted/result.json:pictures uq-raised-skirt/uq.json:outputs compare-raised-skirt-chains/compare.json:differences hazard-deck-72in-lawn-stones/hazard.json:plan_views; do
  json=reports/${lacking%%:*} key=${lacking##*:}
  python3 -c "import json, sys; j = json.load(open(sys.argv[1])); del j[sys.argv[3]]; json.dump(j, open(sys.argv[2], 'w'))" \
    "$repo/$json" "$out/lacking.json" "$key"
  code=0
  "$j232" redraw "$out/lacking.json" --out "$out/lacking.html" 2>"$out/lacking.txt" || code=$?
  [ "$code" = 2 ] || { echo "redraw_check: $json without a key: exit $code, expected 2" >&2; exit 1; }
  grep -q "lacking.json: lacks what .* draws.*key '$key' not found" "$out/lacking.txt"
  [ ! -e "$out/lacking.html" ]
done
# A result.json whose pictures are garbled (a list too long or of odd length, a count that is not
# a whole number, a mark of no kind, a huge outline) is refused naming what, never a crash.
for garble in "board_side:p['board_side']['distances_m'] = [1.0, 2.0, 3.0]:pictures.board_side.distances_m" \
              "count:r['exit_speed']['counts'][0] = 1e300:a histogram's counts" \
              "run:p['board_unrolled']['runs'][0][0] = -1.5:pictures.board_unrolled.runs" \
              "kind:p['marks']['kind'] = 'x' * len(p['marks']['kind']):pictures.marks.kind" \
              "odd:p['plan']['layers'][0]['segments_xy_m'].append(1.0):segments_xy_m" \
              "outline:p['deck_outline_xy_m'] = [0.0] * 20000:pictures.deck_outline_xy_m"; do
  name=${garble%%:*} rest=${garble#*:} what=${garble##*:}
  edit=${rest%:*}
  python3 -c "import json, sys; r = json.load(open(sys.argv[1])); p = r['pictures']; $edit; json.dump(r, open(sys.argv[2], 'w'))" \
    "$repo/reports/highway-pivoted/result.json" "$out/garbled.json"
  code=0
  "$j232" redraw "$out/garbled.json" --out "$out/garbled.html" 2>"$out/garbled.txt" || code=$?
  [ "$code" = 2 ] || { echo "redraw_check: a result.json garbled ($name): exit $code, expected 2" >&2; exit 1; }
  grep -qF "garbled.json: holds what report.html cannot draw" "$out/garbled.txt" && grep -qF "$what" "$out/garbled.txt" ||
    { echo "redraw_check: a result.json garbled ($name) was not refused naming $what:" >&2; cat "$out/garbled.txt" >&2; exit 1; }
  [ ! -e "$out/garbled.html" ]
done
echo "redraw_check: $pages shipped pages redrawn as shipped; a field's page redrawn in US units; files lacking a key or garbled refused"
