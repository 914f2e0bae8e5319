#!/usr/bin/env bash
# run_check.sh J232 SCENARIO OUTDIR [REPLICATES]: runs `j232 run` (60 replicates unless
# told) and checks that it ran (exit 0 = passes or 1 = fails), printed a verdict, and wrote
# complete result.json and marks.csv.
set -u
exe=$1 scenario=$2 out=$3 replicates=${4:-60}
rm -rf "$out"
"$exe" run "$scenario" --replicates "$replicates" --out "$out"
code=$?
case $code in 0|1) ;; *) echo "run_check: exit code $code" >&2; exit 1 ;; esac
[ -s "$out/result.json" ] || { echo "run_check: no result.json" >&2; exit 1; }
[ -s "$out/marks.csv" ] || { echo "run_check: no marks.csv" >&2; exit 1; }
ls "$out"/*.partial 2>/dev/null && { echo "run_check: partial files left" >&2; exit 1; }
verdict=$(grep -o '"verdict": "[a-z]*"' "$out/result.json")
if [ $code -eq 0 ]; then want='"verdict": "passes"'; else want='"verdict": "fails"'; fi
[ "$verdict" = "$want" ] || { echo "run_check: exit $code but $verdict" >&2; exit 1; }
head -1 "$out/marks.csv" | grep -q '^replicate,nail,x_m' || { echo "run_check: marks.csv header" >&2; exit 1; }
grep -Eiq '(^|[^a-z])(nan|-?inf)([^a-z]|$)' "$out/result.json" && { echo "run_check: nan/inf in result.json" >&2; exit 1; }
echo "run_check: ok ($verdict, exit $code)"
