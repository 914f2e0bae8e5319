#!/usr/bin/env bash
# outputs_check.sh J232 SOURCE_DIR WORKDIR: nothing the user made is lost or turned against
# them. A second run into a folder that holds a result keeps the earlier one (in previous-1,
# said so); a name written to break out of the pages' embedded data (a guard named
# "<!--<script>]]></script>") stays inert text in scene.html and report.html; numbers in the
# JSON files carry no binary noise (no 29.999999999999996 for 30: at most 12 significant digits).
set -euo pipefail
exe=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "outputs_check: $*" >&2; exit 1; }

out=$work/run
"$exe" run "$src/scenarios/highway-pivoted.toml" --replicates 2 --seed 1 --out "$out" >/dev/null 2>&1 || [ $? -le 1 ] || fail "first run"
first=$(grep -o '"inputs_digest": "[^"]*"' "$out/result.json")
"$exe" run "$src/scenarios/highway-pivoted.toml" --replicates 3 --seed 2 --out "$out" >/dev/null 2>"$work/second.err" || [ $? -le 1 ] || fail "second run"
grep -q "held an earlier result: kept in .*previous-1" "$work/second.err" || fail "the second run did not say where the first was kept"
[ -s "$out/previous-1/result.json" ] || fail "the first result was not kept in previous-1"
grep -q '"replicates": 2,' "$out/previous-1/result.json" || fail "previous-1 does not hold the first run"
grep -q '"replicates": 3,' "$out/result.json" || fail "the folder does not hold the second run"
[ "$(grep -o '"inputs_digest": "[^"]*"' "$out/previous-1/result.json")" = "$first" ] || fail "previous-1 was altered"

hostile=$src/tests/cli/hostile-guard-name.toml
"$exe" scene "$hostile" --html "$work/scene.html" >/dev/null
"$exe" run "$hostile" --replicates 2 --out "$work/hostile" >/dev/null 2>&1 || [ $? -le 1 ] || fail "run of the hostile name"
for page in "$work/scene.html" "$work/hostile/report.html"; do
  [ -s "$page" ] || fail "no $page"
  if grep -q '<!--<script>' "$page"; then fail "$page carries the name unescaped"; fi
  if grep -q ']]></script>' "$page"; then fail "$page carries the name's script end unescaped"; fi
done
grep -q '\\u003c!--\\u003cscript' "$work/scene.html" || fail "scene.html lost the name (expected it \\u-escaped in its data)"
# Binary noise: a real number with 13 or more significant digits (leading zeros aside).
noisy() { grep -Eo '(^|[ :,[])-?[0-9]+\.[0-9]+([eE][-+]?[0-9]+)?' "$1" | sed -E 's/^[ :,[]//; s/[eE].*//; s/^-//; s/\.//; s/^0+//' | awk 'length($0) > 12' | head -3; }
for f in "$out/result.json" "$work/hostile/result.json"; do
  n=$(noisy "$f")
  [ -z "$n" ] || fail "$f has numbers with binary noise (digits: $n)"
done
# Which physics made the result, named in it.
grep -q '"model_version": [0-9]' "$out/result.json" || fail "result.json does not name its model_version"
grep -q '"physics_model": "' "$out/result.json" || fail "result.json does not describe its physics_model"
echo "outputs_check: ok"
