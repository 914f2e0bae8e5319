#!/usr/bin/env bash
# versions_check.sh J232 SOURCE_DIR WORK: an earlier result (20 replicates, seed 7) beside its
# scenario: `j232 compare` runs the scenario with the earlier run's replicates and seed, and the
# same model gives the same counts (nothing moved); with another seed it runs that seed.
set -euo pipefail
exe=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
"$exe" run "$src/scenarios/highway-straight.toml" --replicates 20 --seed 7 --out "$work/earlier" >/dev/null || [ $? -eq 1 ]
out=$("$exe" compare "$work/earlier/result.json" "$src/scenarios/highway-straight.toml" --out "$work/same")
printf '%s\n' "$out"
grep -q "Running .*highway-straight.toml (20 replicates, seed 7)" <<<"$out" || { echo "versions_check: not run with the earlier replicates and seed" >&2; exit 1; }
grep -q "nothing: the same model and seed give the same" <<<"$out" || { echo "versions_check: the rerun moved" >&2; exit 1; }
[ -s "$work/same/versions.json" ] && [ -s "$work/same/versions.html" ] && [ -s "$work/same/run/result.json" ]
out=$("$exe" compare "$work/earlier/result.json" "$src/scenarios/highway-straight.toml" --seed 8 --out "$work/other")
printf '%s\n' "$out"
grep -q "(20 replicates, seed 8)" <<<"$out" || { echo "versions_check: --seed not taken" >&2; exit 1; }
if grep -q "nothing: the same model and seed" <<<"$out"; then echo "versions_check: another seed cannot give the same counts" >&2; exit 1; fi
echo "versions_check: ok"
