#!/usr/bin/env bash
# batch_check.sh J232 OUT SCENARIO... : `j232 batch` over good scenarios and one bad
# one: the bad one is refused without stopping the others (exit 2), summaries are
# written with one row each, and --resume keeps complete, current results untouched.
set -u
exe=$1 out=$2
shift 2
n=${J232_CHECK_REPLICATES:-40}  # fewer under the sanitizers (tests/cli/CMakeLists.txt)
rm -rf "$out"
fail() { echo "batch_check: $*" >&2; exit 1; }
"$exe" batch "$@" --replicates "$n" --out "$out" > "$out.log" 2>&1
code=$?
cat "$out.log"
[ $code -eq 2 ] || fail "expected exit 2 (one scenario refused), got $code"
for f in summary.html summary.json summary.csv; do [ -s "$out/$f" ] || fail "no $f"; done
rows=$(($(wc -l < "$out/summary.csv") - 1))
[ "$rows" -eq $# ] || fail "summary.csv has $rows rows for $# scenarios"
grep -q ',error,' "$out/summary.csv" || fail "the bad scenario is not reported as an error"
grep -q 'REFUSED' "$out.log" || fail "the bad scenario is not reported on the terminal"
good=$(grep -c ',passes,\|,fails,' "$out/summary.csv")
[ "$good" -eq $(($# - 1)) ] || fail "only $good good scenarios ran"
first=$(ls "$out" | grep -v summary | head -1)
before=$(stat -c %Y.%s "$out/$first/result.json")
sleep 1
"$exe" batch "$@" --replicates "$n" --out "$out" --resume > "$out.log2" 2>&1
grep -q 'current results kept' "$out.log2" || fail "--resume reran everything"
[ "$(stat -c %Y.%s "$out/$first/result.json")" = "$before" ] || fail "--resume rewrote $first/result.json"
"$exe" batch "$@" --replicates $((n + 1)) --out "$out" --resume > "$out.log3" 2>&1
grep -q 'current results kept' "$out.log3" && fail "--resume kept results made with other inputs"
echo "batch_check: ok"
