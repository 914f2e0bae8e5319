#!/usr/bin/env bash
# uq_resume_check.sh J232 SOURCE_DIR WORKDIR: an uncertainty study killed part-way resumes
# from its journal (`j232 uq --resume`) to the same uq.json as an uninterrupted study; a
# journal made from other inputs is not used; a finished study leaves no journal. A finished
# study's uq.csv reused (`--reuse`) rebuilds the same files; a changed number in it is found
# by running its assessments again, and another study's table is refused.
set -euo pipefail
exe=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
scenario=$work/uq-small.toml
sed 's/^base_draws = [0-9]*/base_draws = 8/; s/^replicates = 50 /replicates = 10/' "$src/scenarios/highway-pivoted-raised-skirt.toml" >"$scenario"
fail() { echo "uq_resume_check: $*" >&2; exit 1; }
# kill_part_way OUT: starts the study into OUT and kills it (SIGKILL: nothing can tidy up) as
# soon as its journal holds a few assessments - by progress, not by time, so a faster machine
# or program cannot finish it first.
kill_part_way() {
  "$exe" uq "$scenario" --threads 2 --out "$1" >/dev/null 2>&1 &
  local pid=$! journal=$1/uq-journal.csv
  for _ in $(seq 1 6000); do
    if [ -f "$journal" ] && [ "$(wc -l <"$journal")" -ge 4 ]; then kill -KILL "$pid"; wait "$pid" 2>/dev/null || true; return 0; fi
    kill -0 "$pid" 2>/dev/null || fail "the study finished before it was killed"
    sleep 0.01
  done
  kill -KILL "$pid"
  fail "no assessment was journalled in a minute"
}

"$exe" uq "$scenario" --threads 2 --out "$work/whole" >/dev/null
[ ! -e "$work/whole/uq-journal.csv" ] || fail "a finished study left its journal"

# A finished study reused (j232 uq --reuse): the same three files, some assessments run again.
"$exe" uq "$scenario" --threads 2 --out "$work/reused" --reuse "$work/whole/uq.csv" --recheck 6 | grep -q "Reusing .*: 6 assessments run again" ||
  fail "--reuse did not say what it reran"
for f in uq.csv uq.html; do cmp "$work/whole/$f" "$work/reused/$f" || fail "the reused study's $f differs"; done
python3 -c 'import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert b.pop("provenance") == {"reused_from": sys.argv[3], "assessments_run_again": 6}, "the reuse is not recorded"
assert a == b, "the reused uq.json differs"' "$work/whole/uq.json" "$work/reused/uq.json" "$work/whole/uq.csv" 2>/dev/null || fail "the reused uq.json differs or does not record the reuse"
# One output of one assessment changed in the last digit: found when every row is run again.
awk -F, 'BEGIN { OFS = "," } NR == 3 { $(NF - 6) = $(NF - 6) + 1e-9 } { print }' "$work/whole/uq.csv" >"$work/tampered.csv"
code=0
"$exe" uq "$scenario" --out "$work/tampered" --reuse "$work/tampered.csv" --recheck 1000 2>"$work/tampered.err" || code=$?
[ "$code" = 2 ] && grep -q "1 of them differ from the file.*assessment 2 (line 3)" "$work/tampered.err" ||
  fail "a changed assessment was not found (exit $code: $(cat "$work/tampered.err"))"
[ ! -e "$work/tampered/uq.json" ] || fail "a refused reuse wrote its study"
# Another study's table is refused before anything runs.
sed 's/^base_draws = [0-9]*/base_draws = 4/' "$scenario" >"$work/other-draws.toml"
code=0
"$exe" uq "$work/other-draws.toml" --out "$work/other-draws" --reuse "$work/whole/uq.csv" 2>"$work/other.err" || code=$?
[ "$code" = 2 ] && grep -q "assessments, as this study has" "$work/other.err" || fail "another study's uq.csv was not refused (exit $code)"

# Killed part-way, then resumed.
kill_part_way "$work/resumed"
lines=$(($(wc -l <"$work/resumed/uq-journal.csv") - 1))
out=$("$exe" uq "$scenario" --threads 1 --out "$work/resumed" --resume)
echo "$out" | head -1
echo "$out" | grep -q "Resuming: [0-9]* assessments kept" || fail "did not resume ($lines lines in the journal)"
cmp "$work/whole/uq.json" "$work/resumed/uq.json" || fail "the resumed study differs from the whole one"
cmp "$work/whole/uq.csv" "$work/resumed/uq.csv" || fail "the resumed uq.csv differs"

# A journal whose inputs differ is not used.
kill_part_way "$work/other"
sed -i '1s/.*/# j232 uq journal 0000000000000000/' "$work/other/uq-journal.csv"
"$exe" uq "$scenario" --out "$work/other" --resume | grep -q "made from other inputs or another program: starting afresh" ||
  fail "a journal of other inputs was not refused"
cmp "$work/whole/uq.json" "$work/other/uq.json" || fail "the restarted study differs"
echo "uq_resume_check: passed ($lines assessments were journalled before the kill)"
